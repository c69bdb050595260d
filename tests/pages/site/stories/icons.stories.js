// Icons the way components draw them: inline SVG, a sprite <use>, <img> and CSS mask-image.
import { Bell, Check, Info, Search, Settings, TriangleAlert } from "lucide-static";
import starUrl from "lucide-static/icons/star.svg?url";
import heartUrl from "lucide-static/icons/heart.svg?no-inline";

const inline = (svg, name) => svg.replace("<svg", `<svg data-icon="${name}"`);
const symbol = (svg, id) =>
  svg
    .replace(/<svg[^>]*>/, `<symbol id="${id}" viewBox="0 0 24 24" fill="none" stroke="currentColor" stroke-width="2" stroke-linecap="round" stroke-linejoin="round">`)
    .replace("</svg>", "</symbol>");

export default { title: "Icons" };

export const Toolbar = {
  render: () => `<div class="toolbar">
    ${inline(Search, "search")}${inline(Bell, "bell")}${inline(Settings, "settings")}
  </div>`,
};

export const Chip = {
  render: () => `<span class="chip">${inline(Check, "check")} Saved</span>
    <span class="chip">${inline(Info, "info")} Details</span>`,
};

export const Alert = {
  render: () => `<div class="alert">${inline(TriangleAlert, "triangle-alert")}</div>`,
};

export const Sprite = {
  render: () => `<svg style="display:none">${symbol(Bell, "bell")}${symbol(Check, "check")}</svg>
    <div class="toolbar">
      <svg width="24" height="24"><use href="#bell"/></svg>
      <svg width="24" height="24"><use href="#check"/></svg>
    </div>`,
};

export const Images = {
  render: () => `<div class="toolbar">
    <img src="${starUrl}" width="24" height="24" alt="star">
    <span class="mask-icon" style="--mask: url('${heartUrl}')"></span>
  </div>`,
};
