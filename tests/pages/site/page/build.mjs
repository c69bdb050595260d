// Assembles the static page: Lucide icons inlined from lucide-static (never committed)
// and Tailwind v4's colours (tailwindcss/theme.css) next to it. Usage: node page/build.mjs OUT_DIR
import { mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { createRequire } from "node:module";
import { fileURLToPath } from "node:url";

const require = createRequire(import.meta.url);
const here = dirname(fileURLToPath(import.meta.url));
const out = process.argv[2];
mkdirSync(out, { recursive: true });
const icons = dirname(require.resolve("lucide-static/icons/bell.svg"));
const html = readFileSync(join(here, "index.html"), "utf8").replace(/\{\{([a-z-]+)\}\}/g, (_, name) =>
  readFileSync(join(icons, `${name}.svg`), "utf8")
    .replace(/<!--[\s\S]*?-->/g, "")
    .replace("<svg", `<svg data-icon="${name}"`)
    .trim(),
);
writeFileSync(join(out, "index.html"), html);
// theme.css is an @theme block for Tailwind's compiler; browsers need its colours on :root.
const theme = readFileSync(require.resolve("tailwindcss/theme.css"), "utf8");
const colours = theme.match(/^\s*--color-[a-z0-9-]+:[^;]+;/gm);
writeFileSync(join(out, "theme.css"), `:root {\n${colours.join("\n")}\n}\n`);
