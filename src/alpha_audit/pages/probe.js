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
  const state = { icons: [], sheets: [], found: [], nodes: [] };

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

  // Whether a shape's fill can paint anything.  A <line> has no interior (SVG 2, 10.5: lines
  // are never filled); an open path along one axis ("M4 12h16") has a box of zero height
  // or width.  Only a box with exactly one zero side says so: an element the engine does
  // not lay out (a <symbol>'s shape reached through <use>) reports 0 x 0 and keeps its fill.
  function fillHasArea(el, viaUse) {
    if (el.localName === "line") return false;
    if (viaUse || typeof el.getBBox !== "function") return true;
    try {
      const b = el.getBBox();
      return (b.width === 0) === (b.height === 0);
    } catch (e) {
      return true;
    }
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
        if (kind === "fill" && !fillHasArea(el, viaUse)) continue;
        const o = opacity * parseFloat(own[kind === "fill" ? "fillOpacity" : "strokeOpacity"]);
        if (o <= 0) continue;
        const key = `${value}|${o}`;
        const entry = groups.get(key) || { color: value, opacity: o, kinds: [], current };
        if (!entry.kinds.includes(kind)) entry.kinds.push(kind);
        paintSource(entry, kind, el, viaUse ? host : null, null);
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
    state.found = [];
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
          paintSource(paints[0], "background-color", el, null, pseudo);
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
      state.found.push({ el, kind, pseudo, paints });
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

  // ---------------------------------------------------------------------------------
  // Where the colours come from (pages/cascade.py): for each paint and each backdrop
  // the elements whose cascade sets it, in inheritance order; and, for engines without
  // a devtools protocol, the author declarations matching those elements, ranked as the
  // cascade ranks them (CSS Cascade 5, 6: origin and importance, attachment to the
  // element, layers, specificity, order of appearance).
  const AT = Symbol("alphaAuditSource"); // a paint's elements; symbols never reach JSON
  const TRACED = ["color", "fill", "stroke"];
  const BACKGROUND = ["background-color", "background-image"];
  const SVG_NS = "http://www.w3.org/2000/svg";
  // Elements whose colour the user-agent style sheet sets (HTML, 15.3): the colour an
  // icon inside inherits is the engine's, not an author's, unless an author rule wins.
  const UA_COLOR = "a:any-link, button, input, select, textarea, mark";
  const LEGACY_PSEUDO = new Set(["before", "after", "first-line", "first-letter"]);
  const MAX_VALUE = 2000; // characters of a declared value kept (a data: URL can be huge)
  const MAX_SHEET_TEXT = 1 << 20; // a <style> element's text, to find it in the page
  const LAST = 1 << 30; // a layer's own rules sort after its sublayers; unlayered last
  // Bounds on the walk, so that a page of huge style sheets costs seconds, not its time
  // limit: elements traced, style rules read, and selector matches over all the elements
  // (a microsecond or two each).
  const MAX_NODES = 4000;
  const MAX_RULES = 200000;
  const MAX_MATCHES = 500000;

  function paintSource(entry, property, el, use, pseudo) {
    const at = entry[AT] || (entry[AT] = {});
    if (!at[property]) at[property] = { el, use, pseudo };
  }

  function flatParent(node) {
    if (node.assignedSlot) return node.assignedSlot;
    if (node.parentElement) return node.parentElement;
    const root = node.getRootNode();
    return root instanceof ShadowRoot ? root.host : null;
  }

  // The elements a value inherits through, from the one that uses it to the root; a
  // <symbol>'s shape inherits from its <use> once past the referenced element.
  function chainOf(el, pseudo, use) {
    const out = pseudo ? [[el, pseudo]] : [];
    const ref = use ? (use.getAttribute("href") || use.getAttribute("xlink:href") || "")
      .split("#")[1] : null;
    for (let node = el; node && node.nodeType === 1; ) {
      out.push([node, null]);
      if (use && (node.id === ref || node.localName === "svg")) {
        node = use;
        use = null;
      } else {
        node = flatParent(node);
      }
    }
    return out;
  }

  function transparent(color) {
    return !color || color === "transparent" || /(?:,|\/)\s*0(?:\.0*)?%?\s*\)$/.test(color);
  }

  // The nearest element at or above the icon (above a mask icon: its own background is
  // the paint) that paints a background: what the icon is drawn on, as far as the
  // tree says (a positioned sibling behind it is not in the tree).
  function backdropOf(el, kind, pseudo) {
    let node = kind === "mask" && !pseudo ? flatParent(el) : el;
    for (; node && node.nodeType === 1; node = flatParent(node)) {
      const style = getComputedStyle(node);
      if (!transparent(style.backgroundColor)) {
        return { node, property: "background-color", color: style.backgroundColor };
      }
      if (style.backgroundImage && style.backgroundImage !== "none") {
        return { node, property: "background-image", color: style.backgroundColor };
      }
    }
    return null;
  }

  function targets() {
    const nodes = [];
    const seen = new Map();
    const ref = ([el, pseudo]) => {
      let per = seen.get(el);
      if (!per) seen.set(el, (per = new Map()));
      if (!per.has(pseudo)) {
        per.set(pseudo, nodes.length);
        nodes.push({ el, pseudo });
      }
      return per.get(pseudo);
    };
    const icons = state.found.map(({ el, kind, pseudo, paints }) => {
      const out = paints.map((paint) => {
        const at = paint[AT] || {};
        const chains = {};
        for (const property of Object.keys(at)) {
          const { el: owner, use, pseudo: own } = at[property];
          chains[property] = chainOf(owner, own, use).map(ref);
        }
        return chains;
      });
      const found = backdropOf(el, kind, pseudo);
      const backdrop = found && { property: found.property, color: found.color,
        chain: chainOf(found.node, null, null).map(ref) };
      return { paints: out, backdrop };
    });
    if (nodes.length > MAX_NODES) {
      state.nodes = [];
      return { pseudos: [], icons: null, error: `more than ${MAX_NODES} elements to trace` };
    }
    state.nodes = nodes;
    return { pseudos: nodes.map((n) => n.pseudo), icons };
  }

  function nodes() {
    return state.nodes.map((n) => n.el);
  }

  // ------------------------------------------------------------ selectors
  function splitTop(text) {
    const out = [];
    let depth = 0;
    let quote = null;
    let start = 0;
    for (let i = 0; i < text.length; i++) {
      const ch = text[i];
      if (ch === "\\") {
        i++;
      } else if (quote) {
        if (ch === quote) quote = null;
      } else if (ch === '"' || ch === "'") {
        quote = ch;
      } else if (ch === "(" || ch === "[") {
        depth++;
      } else if (ch === ")" || ch === "]") {
        depth--;
      } else if (ch === "," && depth === 0) {
        out.push(text.slice(start, i));
        start = i + 1;
      }
    }
    out.push(text.slice(start));
    return out.map((s) => s.trim()).filter(Boolean);
  }

  const compare = (x, y) => x[0] - y[0] || x[1] - y[1] || x[2] - y[2];

  function maxSpecificity(list) {
    let best = [0, 0, 0];
    for (const s of splitTop(list)) {
      const t = specificity(s);
      if (compare(t, best) > 0) best = t;
    }
    return best;
  }

  // Selectors 4, 17: ids, then classes, attributes and pseudo-classes, then types and
  // pseudo-elements; :is(), :not(), :has() and :nth-child(... of S) count their most
  // specific argument, :where() nothing.
  function specificity(sel) {
    let a = 0;
    let b = 0;
    let c = 0;
    let i = 0;
    const n = sel.length;
    const add = (t) => {
      a += t[0];
      b += t[1];
      c += t[2];
    };
    const ident = () => {
      const start = i;
      while (i < n) {
        if (sel[i] === "\\") i += 2;
        else if (/[\w\-\u00a0-\uffff]/.test(sel[i])) i++;
        else break;
      }
      return sel.slice(start, i);
    };
    const skipTo = (close) => {
      let depth = 0;
      let quote = null;
      const start = i + 1;
      for (; i < n; i++) {
        const ch = sel[i];
        if (ch === "\\") i++;
        else if (quote) {
          if (ch === quote) quote = null;
        } else if (ch === '"' || ch === "'") quote = ch;
        else if (ch === "(" || ch === "[") depth++;
        else if (ch === ")" || ch === "]") {
          depth--;
          if (depth === 0) {
            i++;
            return sel.slice(start, i - 1);
          }
        }
      }
      return sel.slice(start);
    };
    const typeOrNamespace = () => {
      if (sel[i] === "|") {
        i++;
        if (sel[i] === "*") i++;
        else if (ident()) c++;
        return true;
      }
      return false;
    };
    while (i < n) {
      const ch = sel[i];
      if (ch === "#") {
        i++;
        ident();
        a++;
      } else if (ch === ".") {
        i++;
        ident();
        b++;
      } else if (ch === "[") {
        skipTo("]");
        b++;
      } else if (ch === ":") {
        let element = sel[i + 1] === ":";
        i += element ? 2 : 1;
        const name = ident().toLowerCase();
        if (!element && LEGACY_PSEUDO.has(name)) element = true;
        const arg = sel[i] === "(" ? skipTo(")") : null;
        if (element) {
          c++;
          if (name === "slotted" && arg) add(maxSpecificity(arg));
        } else if (name === "where") {
          // zero
        } else if (["is", "not", "has", "matches", "-webkit-any", "-moz-any"].includes(name)) {
          add(maxSpecificity(arg || ""));
        } else if (/^nth-(last-)?child$/.test(name) && arg && /\sof\s/i.test(arg)) {
          b++;
          add(maxSpecificity(arg.slice(arg.search(/\sof\s/i) + 4)));
        } else if ((name === "host" || name === "host-context") && arg) {
          b++;
          add(maxSpecificity(arg));
        } else {
          b++;
        }
      } else if (ch === "*") {
        i++;
        typeOrNamespace();
      } else if (ch === "\\" || /[\w\-\u00a0-\uffff]/.test(ch)) {
        ident();
        if (!typeOrNamespace()) c++;
      } else {
        i++; // combinators, whitespace
      }
    }
    return [a, b, c];
  }

  // A nested rule's selector as a top-level one (CSS Nesting 1, 4: & is :is(parent);
  // a relative selector starts with an implied "& ").
  function nest(selector, parent) {
    if (!parent) return selector;
    return splitTop(selector).map((s) => (s.includes("&")
      ? s.split("&").join(`:is(${parent})`) : `:is(${parent}) ${s}`)).join(", ");
  }

  // Each complex selector of a list, its specificity and the pseudo-element it ends in.
  function complexes(selector) {
    return splitTop(selector).map((s) => {
      const m = /::?(before|after)\s*$/i.exec(s);
      const pseudo = m ? m[1].toLowerCase() : (/::[\w-]+(\([^)]*\))?\s*$/.test(s) ? "other" : null);
      const base = m ? s.slice(0, m.index).trim() || "*" : s;
      return { base, pseudo, spec: specificity(s), key: keyOf(base) };
    });
  }

  // What an element must have for a complex selector to match it, read off its last
  // compound (as engines bucket rules): an id, a class or a type; null for none (only
  // element.matches can tell).  Arguments of pseudo-classes and attribute brackets are
  // left out, and an escaped name is not guessed at.
  function keyOf(selector) {
    let depth = 0;
    let quote = null;
    let start = 0;
    for (let i = 0; i < selector.length; i++) {
      const ch = selector[i];
      if (ch === "\\") i++;
      else if (quote) {
        if (ch === quote) quote = null;
      } else if (ch === '"' || ch === "'") quote = ch;
      else if (ch === "(" || ch === "[") depth++;
      else if (ch === ")" || ch === "]") depth--;
      else if (depth === 0 && /[\s>+~]/.test(ch)) start = i + 1;
    }
    let last = selector.slice(start);
    if (last.includes("\\") || last.includes("|")) return null; // escapes, namespaces
    for (let before = ""; before !== last; ) {
      before = last;
      last = last.replace(/\([^()]*\)/g, "").replace(/\[[^\]]*\]/g, "");
    }
    const id = /#([\w-]+)/.exec(last);
    if (id) return { id: id[1] };
    const cls = /\.([\w-]+)/.exec(last);
    if (cls) return { cls: cls[1] };
    const tag = /^([a-zA-Z][\w-]*)/.exec(last);
    return tag ? { tag: tag[1].toLowerCase() } : null;
  }

  // The rules' complex selectors bucketed by key, for one tree scope.
  function bucket(rules) {
    const ids = new Map();
    const classes = new Map();
    const tags = new Map();
    const any = [];
    const put = (map, name, item) => {
      if (!map.has(name)) map.set(name, []);
      map.get(name).push(item);
    };
    rules.forEach((entry, index) => {
      for (const complex of entry.complexes) {
        const item = { index, complex };
        const key = complex.key;
        if (!key) any.push(item);
        else if (key.id) put(ids, key.id, item);
        else if (key.cls) put(classes, key.cls, item);
        else put(tags, key.tag, item);
      }
    });
    return { rules, ids, classes, tags, any };
  }

  function candidates(buckets, el) {
    const out = [...buckets.any];
    if (el.id && buckets.ids.has(el.id)) out.push(...buckets.ids.get(el.id));
    for (const c of el.classList || []) {
      if (buckets.classes.has(c)) out.push(...buckets.classes.get(c));
    }
    const tag = el.localName.toLowerCase();
    if (buckets.tags.has(tag)) out.push(...buckets.tags.get(tag));
    return out;
  }

  // ---------------------------------------------------------------- rules
  function declared(style) {
    const out = [];
    const one = (property, name) => {
      const value = style.getPropertyValue(name);
      if (value) {
        out.push({ property, name, value: value.trim().slice(0, MAX_VALUE),
          important: style.getPropertyPriority(name) === "important" });
      }
    };
    for (const p of TRACED) one(p, p);
    const shorthand = style.getPropertyValue("background");
    for (const p of BACKGROUND) one(p, shorthand ? "background" : p);
    for (let k = 0; k < style.length; k++) {
      const name = style.item(k);
      if (name.startsWith("--")) one(name, name);
    }
    return out;
  }

  function conditionHolds(rule) {
    try {
      if (rule instanceof CSSMediaRule) return matchMedia(rule.media.mediaText || "all").matches;
      if (rule instanceof CSSSupportsRule) return CSS.supports(rule.conditionText);
    } catch (e) {
      return false;
    }
    return true;
  }

  const has = (name) => typeof globalThis[name] === "function";

  function collectRules(root, sheets) {
    const rules = [];
    const layerRank = new Map();
    const layerCount = new Map();
    let anonymous = 0;
    let order = 0;
    let read = 0;
    const layerKey = (path) => {
      const ranks = [];
      for (let k = 0; k < path.length; k++) {
        const id = path.slice(0, k + 1).join("\u0000");
        if (!layerRank.has(id)) {
          const parent = path.slice(0, k).join("\u0000");
          const count = layerCount.get(parent) || 0;
          layerCount.set(parent, count + 1);
          layerRank.set(id, count);
        }
        ranks.push(layerRank.get(id));
      }
      return [...ranks, LAST];
    };
    const layerPath = (layer, name) => [...layer,
      ...(name ? name.split(".") : [`\u0000anonymous ${++anonymous}`])];
    const walk = (list, ctx) => {
      for (const rule of list) {
        if (rule instanceof CSSStyleRule) {
          if (++read > MAX_RULES) throw new Error(`more than ${MAX_RULES} style rules`);
          const index = ctx.counter.rules++;
          const selector = nest(rule.selectorText, ctx.parent);
          const decls = declared(rule.style);
          if (ctx.active && decls.length) {
            rules.push({ decls, complexes: complexes(selector), layer: layerKey(ctx.layer),
              order: order++, sheet: ctx.sheet, rule: index, selector: rule.selectorText });
          }
          if (rule.cssRules && rule.cssRules.length) {
            walk(rule.cssRules, { ...ctx, parent: selector, index, raw: rule.selectorText });
          }
        } else if (has("CSSNestedDeclarations") && rule instanceof CSSNestedDeclarations) {
          const decls = declared(rule.style);
          if (ctx.active && ctx.parent && decls.length) {
            rules.push({ decls, complexes: complexes(ctx.parent), layer: layerKey(ctx.layer),
              order: order++, sheet: ctx.sheet, rule: ctx.index, selector: ctx.raw });
          }
        } else if (rule instanceof CSSMediaRule || rule instanceof CSSSupportsRule) {
          walk(rule.cssRules, { ...ctx, active: ctx.active && conditionHolds(rule) });
        } else if (has("CSSLayerBlockRule") && rule instanceof CSSLayerBlockRule) {
          walk(rule.cssRules, { ...ctx, layer: layerPath(ctx.layer, rule.name) });
        } else if (has("CSSLayerStatementRule") && rule instanceof CSSLayerStatementRule) {
          for (const name of rule.nameList) layerKey([...ctx.layer, ...name.split(".")]);
        } else if (rule instanceof CSSImportRule) {
          const media = rule.media && rule.media.mediaText;
          const applies = !media || matchMedia(media).matches;
          const named = rule.layerName;
          const layer = named === null || named === undefined ? ctx.layer
            : layerPath(ctx.layer, named);
          if (rule.styleSheet && applies) sheet(rule.styleSheet, layer, ctx.active);
        } else if (has("CSSContainerRule") && rule instanceof CSSContainerRule) {
          walk(rule.cssRules, ctx); // container conditions are assumed to hold
        } else if (rule.cssRules && !(has("CSSKeyframesRule") && rule instanceof CSSKeyframesRule)) {
          walk(rule.cssRules, { ...ctx, active: false }); // @scope, @starting-style: counted only
        }
      }
    };
    const sheet = (styleSheet, layer, active) => {
      let list;
      try {
        list = styleSheet.cssRules;
      } catch (e) {
        return; // another origin's sheet: no rules to read
      }
      const owner = styleSheet.ownerNode;
      const inline = !styleSheet.href;
      sheets.push({
        url: styleSheet.href || (owner ? owner.ownerDocument.URL : null),
        inline,
        text: inline && owner && owner.localName === "style"
          ? owner.textContent.slice(0, MAX_SHEET_TEXT) : null,
      });
      const ctx = { sheet: sheets.length - 1, layer, active, parent: null, index: null,
        raw: null, counter: { rules: 0 } };
      walk(list, ctx);
    };
    const all = [...root.styleSheets, ...(root.adoptedStyleSheets || [])];
    for (const s of all) {
      if (s.disabled) continue;
      const media = s.media && s.media.mediaText;
      sheet(s, [], !media || matchMedia(media).matches);
    }
    return rules;
  }

  // The matching rules of an element (or its pseudo-element) and each one's specificity:
  // that of its most specific complex selector that matches.
  function matching(buckets, el, pseudo, budget) {
    const best = new Map();
    for (const { index, complex } of candidates(buckets, el)) {
      if (complex.pseudo !== pseudo) continue;
      if (--budget.left < 0) throw new Error(`more than ${MAX_MATCHES} selector matches`);
      let ok = false;
      try {
        ok = el.matches(complex.base);
      } catch (e) {
        ok = false;
      }
      const known = best.get(index);
      if (ok && (!known || compare(complex.spec, known) > 0)) best.set(index, complex.spec);
    }
    return Array.from(best, ([index, spec]) => ({ entry: buckets.rules[index], spec }));
  }

  function cascade() {
    try {
      const sheets = [];
      const byRoot = new Map();
      const budget = { left: MAX_MATCHES };
      const out = state.nodes.map(({ el, pseudo }) => {
        const root = el.getRootNode();
        if (!byRoot.has(root)) byRoot.set(root, bucket(collectRules(root, sheets)));
        const matched = matching(byRoot.get(root), el, pseudo, budget);
        matched.sort((x, y) => {
          const lx = x.entry.layer;
          const ly = y.entry.layer;
          for (let k = 0; k < Math.min(lx.length, ly.length); k++) {
            if (lx[k] !== ly[k]) return lx[k] - ly[k];
          }
          return compare(x.spec, y.spec) || x.entry.order - y.entry.order;
        });
        const decls = [];
        matched.forEach(({ entry }, position) => {
          for (const d of entry.decls) {
            decls.push({ ...d, kind: "rule", layer: entry.layer, position, sheet: entry.sheet,
              rule: entry.rule, selector: entry.selector });
          }
        });
        if (!pseudo) {
          const attribute = el.getAttribute("style");
          if (attribute && el.style) {
            for (const d of declared(el.style)) {
              decls.push({ ...d, kind: "attribute", layer: [LAST], position: matched.length,
                text: attribute.slice(0, MAX_VALUE) });
            }
          }
          if (el.namespaceURI === SVG_NS) {
            for (const name of ["fill", "stroke", "color"]) {
              const value = el.getAttribute(name);
              if (value) {
                decls.push({ property: name, name, value: value.slice(0, MAX_VALUE),
                  important: false, kind: "hint", layer: [LAST], position: -1 });
              }
            }
          }
          let ua = false;
          try {
            ua = el.matches(UA_COLOR);
          } catch (e) {
            ua = false;
          }
          if (ua) {
            decls.push({ property: "color", name: "color", value: "", important: false,
              kind: "ua", layer: [LAST], position: -2 });
          }
        }
        return decls;
      });
      const used = new Set(out.flatMap((decls) => decls.map((d) => d.sheet)));
      return { sheets: sheets.map((s, k) => (used.has(k) ? s : { url: s.url, inline: s.inline,
        text: null })), nodes: out, page: document.URL };
    } catch (e) {
      return { error: String(e && e.message || e) };
    }
  }

  return { find, hide, targets, nodes, cascade, specificity };
})()
