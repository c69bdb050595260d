// The themes addon's decorator puts data-theme on <html>; globals=theme:dark selects it.
import { withThemeByDataAttribute } from "@storybook/addon-themes";
import "./theme.css";

export const decorators = [
  withThemeByDataAttribute({
    themes: { light: "light", dark: "dark" },
    defaultTheme: "light",
    attributeName: "data-theme",
  }),
];

export const parameters = { layout: "padded" };
