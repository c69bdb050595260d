// Storybook for tests/pages: html-vite, light and dark through @storybook/addon-themes.
export default {
  stories: ["../stories/*.stories.js"],
  addons: ["@storybook/addon-themes"],
  framework: { name: "@storybook/html-vite", options: {} },
  core: { disableTelemetry: true, disableWhatsNewNotifications: true },
};
