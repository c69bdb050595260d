// alpha-audit's page probe: finds the icons of a page, says how to map them to the
// manifest, what paints they declare, and hides them all at once (and back).
// Evaluated as one expression in an isolated world where the engine has one
// (alpha_audit.browser: Chromium, Firefox), so the page's scripts never see it.
// pages/capture.py installs the returned object as a global of that world and calls
// its methods; its state stays there.
(() => {
  const SHAPES = new Set(["path", "circle", "ellipse", "line", "polyline", "polygon", "rect"]);
  // Geometry attributes in a fixed order: the same list as pages/mapping.py (GEOMETRY).
  const GEOMETRY = ["d", "cx", "cy", "r", "rx", "ry", "x", "y", "x1", "y1", "x2", "y2",
    "width", "height", "points"];
  const MARK = "data-alpha-audit-hide";
  const HIDE_CSS =
    `[${MARK}~="self"], [${MARK}~="self"] * { visibility: hidden !important; }\n` +
    `[${MARK}~="before"]::before { visibility: hidden !important; }\n` +
    `[${MARK}~="after"]::after { visibility: hidden !important; }\n`;
  const state = { icons: [], sheets: [] };

  const norm = (v) => String(v).replace(/[\s,]+/g, " ").trim();

  // The geometry travels as text and is hashed by pages/mapping.py: hashing here
  // (crypto.subtle) would read a TypedArray across Firefox's Xray wrappers, which the
  // isolated world forbids ("Accessing TypedArray data over Xrays is ... forbidden").
  const MAX_GEOMETRY = 262144; // characters; a larger drawing is no icon to map by shape
  const geometryKey = (text) => (text.length <= MAX_GEOMETRY ? text : null);

  function shapesOf(root) {
    const out = [];
    const walk = (el) => {
      for (const child of el.children) {
        const tag = child.localName;
        if (SHAPES.has(tag)) out.push(child);
        if (tag !== "defs" && tag !== "mask" && tag !== "clipPath") walk(child);
      }
    };
    walk(root);
    return out;
  }

  function geometryText(shapes) {
    return shapes.map((el) => {
      const parts = [el.localName];
      for (const name of GEOMETRY) {
        const value = el.getAttribute(name);
        if (value !== null) parts.push(`${name}=${norm(value)}`);
      }
      return parts.join(" ");
    }).join("\n");
  }

  function domPath(el) {
    const parts = [];
    let node = el;
    while (node && node.nodeType === 1) {
      let part = node.localName;
      if (node.id) {
        parts.unshift(`${part}#${node.id}`);
        break;
      }
      const parent = node.parentElement;
      if (parent) {
        const same = Array.from(parent.children).filter((c) => c.localName === node.localName);
        if (same.length > 1) part += `:nth-of-type(${same.indexOf(node) + 1})`;
      }
      parts.unshift(part);
      const root = node.getRootNode();
      node = parent || (root instanceof ShadowRoot ? root.host : null);
    }
    return parts.join(" > ");
  }

  function opacityChain(el, stop) {
    let product = 1;
    for (let node = el; node && node.nodeType === 1; ) {
      product *= parseFloat(getComputedStyle(node).opacity);
      if (node === stop) break;
      const root = node.getRootNode();
      node = node.parentElement || (root instanceof ShadowRoot ? root.host : null);
    }
    return product;
  }

  // A paint as the engine computed it: the colour text (parsed by coloraide in Python)
  // and whether it is the element's currentColor.
  function declaredPaints(shapes, host, viaUse) {
    const groups = new Map();
    for (const el of shapes) {
      const style = getComputedStyle(viaUse ? host : el);
      const own = getComputedStyle(el);
      if (own.display === "none" || style.visibility !== "visible") continue;
      const opacity = (viaUse ? opacityChain(host) * opacityChain(el, el.closest("symbol, svg"))
        : opacityChain(el));
      for (const kind of ["fill", "stroke"]) {
        let value = own[kind];
        let current = value === own.color;
        const attr = el.getAttribute(kind) || el.closest(`[${kind}]`)?.getAttribute(kind);
        if (viaUse) {
          // The clone of a <symbol>'s shape inherits from the <use> (SVG 2): its own
          // attribute wins, currentColor is the use's colour, nothing is the use's paint.
          if (attr === "currentColor") [value, current] = [style.color, true];
          else if (attr) [value, current] = [attr, false];
          else [value, current] = [style[kind], style[kind] === style.color];
        }
        if (!value || value === "none" || value.startsWith("url(")) continue;
        if (kind === "stroke" && parseFloat(own.strokeWidth) === 0) continue;
        const o = opacity * parseFloat(own[kind === "fill" ? "fillOpacity" : "strokeOpacity"]);
        if (o <= 0) continue;
        const key = `${value}|${o}`;
        const entry = groups.get(key) || { color: value, opacity: o, kinds: [], current };
        if (!entry.kinds.includes(kind)) entry.kinds.push(kind);
        groups.set(key, entry);
      }
    }
    return Array.from(groups.values());
  }

  function box(el) {
    const r = el.getBoundingClientRect();
    return [r.left, r.top, r.width, r.height];
  }

  function visible(el, maxSize) {
    const style = getComputedStyle(el);
    if (style.display === "none" || style.visibility !== "visible") return false;
    const [, , w, h] = box(el);
    return w > 0 && h > 0 && w <= maxSize && h <= maxSize;
  }

  function fileName(url) {
    try {
      const path = new URL(url, document.baseURI).pathname;
      return decodeURIComponent(path.split("/").pop() || "");
    } catch (e) {
      return "";
    }
  }

  function maskUrl(style) {
    const value = style.maskImage || style.webkitMaskImage || "";
    const match = /url\(["']?([^"')]+)["']?\)/.exec(value);
    return match ? match[1] : null;
  }

  async function imageGeometry(url) {
    try {
      let text;
      if (url.startsWith("data:")) {
        const comma = url.indexOf(",");
        const head = url.slice(0, comma);
        const body = url.slice(comma + 1);
        text = head.endsWith(";base64") ? atob(body) : decodeURIComponent(body);
      } else {
        const response = await fetch(url);
        if (!response.ok) return null;
        text = await response.text();
      }
      const doc = new DOMParser().parseFromString(text, "image/svg+xml");
      if (doc.documentElement.localName !== "svg") return null;
      return geometryKey(geometryText(shapesOf(doc.documentElement)));
    } catch (e) {
      return null;
    }
  }

  function* allElements(root) {
    for (const el of root.querySelectorAll("*")) {
      yield el;
      if (el.shadowRoot) yield* allElements(el.shadowRoot);
    }
  }

  async function find(options) {
    const maxSize = options.maxSize;
    const attribute = options.attribute;
    const chosen = new Set();
    const found = [];
    const add = (el, kind, pseudo) => {
      if (chosen.has(el) && !pseudo) return;
      chosen.add(el);
      found.push({ el, kind, pseudo });
    };
    const picked = options.selector ? new Set(document.querySelectorAll(options.selector)) : null;
    for (const el of allElements(document)) {
      const tag = el.localName;
      if (tag === "svg" && el.parentElement?.closest("svg") == null) {
        if (visible(el, maxSize)) add(el, el.querySelector("use") ? "use" : "svg", null);
      } else if (tag === "img" && visible(el, maxSize)) {
        const src = el.currentSrc || el.src || "";
        if (/\.svg(\?|#|$)/i.test(fileName(src) + "|") || /\.svg$/i.test(fileName(src)) ||
            src.startsWith("data:image/svg+xml")) add(el, "img", null);
      } else if (!el.closest("svg")) {
        if (maskUrl(getComputedStyle(el)) && visible(el, maxSize)) add(el, "mask", null);
        for (const pseudo of ["before", "after"]) {
          const style = getComputedStyle(el, `::${pseudo}`);
          if (style.content !== "none" && maskUrl(style) && visible(el, maxSize)) {
            add(el, "mask", pseudo);
          }
        }
      }
      if (picked && picked.has(el) && !chosen.has(el) && visible(el, maxSize)) {
        add(el, "selector", null);
      }
    }
    state.icons = [];
    const out = [];
    for (const { el, kind, pseudo } of found) {
      const keys = { data: null, sprite: null, file: null, geometry: null, label: null,
        title: null, alt: null, id: null };
      let paints = [];
      const dataOwner = el.closest(`[${attribute}]`);
      if (dataOwner) keys.data = dataOwner.getAttribute(attribute);
      // What the page calls the icon (reports name an unmapped icon by it).
      // Its own aria-label, or that of a parent holding nothing else (an icon button).
      const parent = el.parentElement;
      keys.label = el.getAttribute("aria-label") ||
        (parent && parent.children.length === 1 ? parent.getAttribute("aria-label") : null);
      const title = el.querySelector(":scope > title");
      keys.title = (title && title.textContent) || el.getAttribute("title");
      if (kind === "img") keys.alt = el.getAttribute("alt");
      keys.id = el.id || null;
      if (kind === "svg") {
        const shapes = shapesOf(el);
        keys.geometry = geometryKey(geometryText(shapes));
        paints = declaredPaints(shapes, el, false);
      } else if (kind === "use") {
        const use = el.querySelector("use");
        const href = use.getAttribute("href") || use.getAttribute("xlink:href") || "";
        keys.sprite = href.includes("#") ? href.slice(href.indexOf("#") + 1) : null;
        keys.file = href.split("#")[0] ? fileName(href.split("#")[0]) : null;
        const target = href.startsWith("#") ? el.getRootNode().getElementById?.(keys.sprite)
          || document.getElementById(keys.sprite) : null;
        if (target) {
          const shapes = SHAPES.has(target.localName) ? [target] : shapesOf(target);
          keys.geometry = geometryKey(geometryText(shapes));
          paints = declaredPaints(shapes, use, true);
        }
      } else if (kind === "img") {
        const src = el.currentSrc || el.src;
        keys.file = src.startsWith("data:") ? null : fileName(src);
        keys.geometry = await imageGeometry(src);
      } else if (kind === "mask") {
        const style = getComputedStyle(el, pseudo ? `::${pseudo}` : null);
        const url = maskUrl(style);
        keys.file = url && !url.startsWith("data:") ? fileName(url) : null;
        keys.geometry = url ? await imageGeometry(url) : null;
        if (style.backgroundImage === "none") {
          paints = [{ color: style.backgroundColor, opacity: opacityChain(el),
            kinds: ["fill"], current: style.backgroundColor === style.color }];
        }
      }
      el.setAttribute(MARK, [el.getAttribute(MARK), pseudo || "self"].filter(Boolean).join(" "));
      const root = el.getRootNode();
      if (!state.sheets.some((s) => s.root === root)) {
        const sheet = document.createElement("style");
        sheet.textContent = HIDE_CSS;
        sheet.disabled = true;
        (root === document ? document.head || document.documentElement : root).appendChild(sheet);
        sheet.sheet.disabled = true;
        state.sheets.push({ root, sheet });
      }
      state.icons.push(el);
      out.push({ kind, pseudo, path: domPath(el) + (pseudo ? `::${pseudo}` : ""), box: box(el),
        keys, paints });
    }
    const doc = document.documentElement;
    return {
      icons: out,
      width: Math.ceil(Math.max(doc.scrollWidth, document.body?.scrollWidth || 0)),
      height: Math.ceil(Math.max(doc.scrollHeight, document.body?.scrollHeight || 0)),
    };
  }

  function hide(hidden) {
    for (const { sheet } of state.sheets) sheet.sheet.disabled = !hidden;
    return state.sheets.length;
  }

  return { find, hide };
})()
