// alpha-audit preview page: the paper's compositing expression in a WebGL2 fragment shader.
// Pixel = encode(q * clip(Cb + a (Cs - Cb), 0, 1) + (1 - q) * Cb) in linear sRGB
// ("Opacity Is Not Just Opacity", Appendix A.2). No network, no external files.
"use strict";
(() => {
  const DATA = JSON.parse(document.getElementById("alpha-audit-data").textContent);
  const BLENDS = [
    { id: "alpha", label: "α (extended)", code: 0 },
    { id: "difference", label: "Difference", code: 1 },
    { id: "exclusion", label: "Exclusion", code: 2 },
  ];
  const ALPHA_CHIPS = [-1, 0, 0.6, 1, 1.1, 1.2, 1.4, 2];
  const ZOOMS = [1, 2, 3, 4];
  // WCAG 2.2 relative luminance weights.
  const WEIGHTS = [0.2126, 0.7152, 0.0722];

  // ---- colour maths in float64 (CSS Color 4 sRGB), for labels and contrast ----------------
  const decode = (v) => (v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4));
  const encode = (v) => (v > 0.0031308 ? 1.055 * Math.pow(v, 1 / 2.4) - 0.055 : 12.92 * v);
  const clip = (v) => Math.min(1, Math.max(0, v));
  const hexToCodes = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
  const hexToLinear = (hex) => hexToCodes(hex).map((c) => decode(c / 255));
  const roundHalfEven = (x) => {
    const r = Math.round(x);
    return Math.abs(x - Math.trunc(x)) === 0.5 && r % 2 !== 0 ? r - 1 : r;
  };
  const to8bit = (c) => c.map((v) => roundHalfEven(encode(clip(v)) * 255));
  const toHex = (c) => "#" + to8bit(c).map((v) => v.toString(16).padStart(2, "0")).join("");
  const luminance = (c) => WEIGHTS[0] * c[0] + WEIGHTS[1] * c[1] + WEIGHTS[2] * c[2];
  const contrast = (c1, c2) => {
    const y1 = luminance(c1), y2 = luminance(c2);
    return (Math.max(y1, y2) + 0.05) / (Math.min(y1, y2) + 0.05);
  };
  function blend(s, b, a, mode) {
    if (mode === 1) return s.map((v, k) => clip(Math.abs(v - b[k])));
    if (mode === 2) return s.map((v, k) => clip(v + b[k] - 2 * v * b[k]));
    return s.map((v, k) => clip(b[k] + a * (v - b[k])));
  }

  // ---- WebGL2 ------------------------------------------------------------------------------
  const VERTEX = `#version 300 es
in vec2 a_corner;
uniform vec2 u_viewport;
uniform ivec2 u_origin;
uniform int u_size;
void main() {
  vec2 px = vec2(u_origin) + a_corner * float(u_size);
  gl_Position = vec4(px / u_viewport * 2.0 - 1.0, 0.0, 1.0);
}`;
  const FRAGMENT = `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform sampler2D u_mask;    // R8 coverage atlas, q = k / 255
uniform ivec2 u_origin;      // icon's lower-left pixel in the framebuffer
uniform ivec2 u_atlas;       // icon's top-left texel in the atlas
uniform int u_size;
uniform vec3 u_source;       // Cs, linear sRGB, from the object
uniform vec3 u_background;   // Cb, linear sRGB, from the application
uniform float u_alpha;       // the real-valued coefficient
uniform int u_blend;         // 0 extended alpha, 1 Difference, 2 Exclusion
out vec4 o_color;
vec3 encodeSrgb(vec3 c) {    // CSS Color 4 gam_sRGB
  vec3 lo = c * 12.92;
  vec3 hi = 1.055 * pow(max(c, vec3(0.0)), vec3(1.0 / 2.4)) - 0.055;
  return mix(lo, hi, greaterThan(c, vec3(0.0031308)));
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  float q = texelFetch(u_mask, u_atlas + ivec2(p.x, u_size - 1 - p.y), 0).r;
  vec3 s = u_source;
  vec3 b = u_background;
  vec3 outColor;
  if (u_blend == 1) {
    outColor = clamp(abs(s - b), 0.0, 1.0);
  } else if (u_blend == 2) {
    outColor = clamp(s + b - 2.0 * s * b, 0.0, 1.0);
  } else {
    outColor = clamp(b + u_alpha * (s - b), 0.0, 1.0);
  }
  o_color = vec4(encodeSrgb(q * outColor + (1.0 - q) * b), 1.0);
}`;

  class Renderer {
    constructor(canvas) {
      this.canvas = canvas;
      const gl = canvas.getContext("webgl2", {
        alpha: false, antialias: false, depth: false, stencil: false,
        premultipliedAlpha: false, preserveDrawingBuffer: true,
      });
      if (!gl) throw new Error("This page needs WebGL2, which this browser does not provide.");
      this.gl = gl;
      const program = gl.createProgram();
      for (const [type, source] of [[gl.VERTEX_SHADER, VERTEX], [gl.FRAGMENT_SHADER, FRAGMENT]]) {
        const shader = gl.createShader(type);
        gl.shaderSource(shader, source);
        gl.compileShader(shader);
        if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
          throw new Error("shader: " + gl.getShaderInfoLog(shader));
        }
        gl.attachShader(program, shader);
      }
      gl.linkProgram(program);
      if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
        throw new Error("program: " + gl.getProgramInfoLog(program));
      }
      gl.useProgram(program);
      this.u = {};
      for (const name of ["u_viewport", "u_origin", "u_size", "u_mask", "u_atlas", "u_source",
        "u_background", "u_alpha", "u_blend"]) {
        this.u[name] = gl.getUniformLocation(program, name);
      }
      const vao = gl.createVertexArray();
      gl.bindVertexArray(vao);
      const buffer = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1, 1]),
        gl.STATIC_DRAW);
      const loc = gl.getAttribLocation(program, "a_corner");
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, 2, gl.FLOAT, false, 0, 0);
      gl.uniform1i(this.u.u_mask, 0);
      gl.disable(gl.BLEND);
      gl.disable(gl.DITHER);  // dithering would perturb the 8-bit output
      this.textures = new Map();
    }

    texture(size) {
      const gl = this.gl;
      if (!this.textures.has(size)) {
        const atlas = DATA.atlases[String(size)];
        const bytes = Uint8Array.from(atob(atlas.data), (ch) => ch.charCodeAt(0));
        const tex = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D, tex);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        gl.texImage2D(gl.TEXTURE_2D, 0, gl.R8, atlas.width, atlas.height, 0, gl.RED,
          gl.UNSIGNED_BYTE, bytes);
        for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) {
          gl.texParameteri(gl.TEXTURE_2D, p, gl.NEAREST);
        }
        for (const p of [gl.TEXTURE_WRAP_S, gl.TEXTURE_WRAP_T]) {
          gl.texParameteri(gl.TEXTURE_2D, p, gl.CLAMP_TO_EDGE);
        }
        this.textures.set(size, { tex, columns: atlas.columns });
      }
      return this.textures.get(size);
    }

    resize(width, height) {
      if (this.canvas.width !== width) this.canvas.width = width;
      if (this.canvas.height !== height) this.canvas.height = height;
      this.gl.viewport(0, 0, width, height);
      this.gl.uniform2f(this.u.u_viewport, width, height);
    }

    /** Fill a rectangle (top-down coordinates) with an 8-bit sRGB colour. */
    fill(x, y, w, h, codes) {
      const gl = this.gl;
      gl.enable(gl.SCISSOR_TEST);
      gl.scissor(x, this.canvas.height - y - h, w, h);
      gl.clearColor(codes[0] / 255, codes[1] / 255, codes[2] / 255, 1);
      gl.clear(gl.COLOR_BUFFER_BIT);
      gl.disable(gl.SCISSOR_TEST);
    }

    /** Draw icons of one size on one canvas colour; items are {icon, x, y, alpha}, top-down. */
    draw(size, background, blendCode, items) {
      const gl = this.gl;
      const { tex, columns } = this.texture(size);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, tex);
      gl.uniform1i(this.u.u_size, size);
      gl.uniform3f(this.u.u_background, background[0], background[1], background[2]);
      gl.uniform1i(this.u.u_blend, blendCode);
      for (const item of items) {
        const icon = DATA.icons[item.icon];
        const s = icon.linear;
        gl.uniform3f(this.u.u_source, s[0], s[1], s[2]);
        gl.uniform1f(this.u.u_alpha, item.alpha);
        gl.uniform2i(this.u.u_origin, item.x, this.canvas.height - item.y - size);
        gl.uniform2i(this.u.u_atlas, (item.icon % columns) * size,
          Math.floor(item.icon / columns) * size);
        gl.drawArrays(gl.TRIANGLES, 0, 6);
      }
    }
  }

  // ---- state and layout --------------------------------------------------------------------
  const $ = (id) => document.getElementById(id);
  const sizes = DATA.sizes;
  const ownAlphas = [...new Set(DATA.icons.map((i) => i.alpha))];
  const state = {
    alpha: DATA.alpha,
    own: false,
    blend: 0,
    canvas: 0,
    custom: null,
    all: false,
    size: sizes.includes(48) ? 48 : sizes[sizes.length - 1],
    zoom: 1,
    labels: true,
  };

  function canvasList() {
    const list = DATA.canvases.map((c) => ({ name: c.name, hex: c.hex, linear: c.linear }));
    if (state.custom) list.push({ name: "custom", hex: state.custom, linear: hexToLinear(state.custom) });
    if (state.all) return list;
    return [state.custom ? list[list.length - 1] : list[state.canvas]];
  }

  const alphaFor = (icon) => (state.own ? icon.alpha : state.alpha);

  function inkFor(linear) {
    const dark = hexToLinear("#161616"), light = hexToLinear("#f2f2f2");
    return contrast(dark, linear) >= contrast(light, linear) ? "#161616" : "#f2f2f2";
  }

  let renderer = null;
  let current = null; // the layout on screen

  function computeLayout() {
    const z = state.zoom, size = state.size, n = DATA.icons.length;
    const gap = Math.max(8, Math.floor(size / 3));
    const cellW = Math.max(size + gap, Math.ceil(50 / z));
    const labelH = state.labels ? Math.ceil(17 / z) : 0;
    const cellH = size + gap + labelH;
    const pad = Math.ceil(14 / z);
    const titleH = Math.ceil(26 / z);
    const avail = Math.max(200, document.querySelector("main").clientWidth - 40);
    const cols = Math.max(1, Math.min(n, Math.floor((avail / z - 2 * pad + gap) / cellW)));
    const rows = Math.max(1, Math.ceil(n / cols));
    const width = 2 * pad + cols * cellW - gap;
    const bandH = titleH + rows * cellH + pad - gap;
    const bands = canvasList().map((canvas, b) => ({ canvas, y: b * bandH, h: bandH }));
    const cells = [];
    for (const band of bands) {
      DATA.icons.forEach((icon, k) => {
        const r = Math.floor(k / cols), c = k % cols;
        const x0 = pad + c * cellW;
        const x = x0 + Math.floor((cellW - gap - size) / 2);
        cells.push({ band, icon: k, x, y: band.y + titleH + r * cellH, cellX: x0, cellW: cellW - gap });
      });
    }
    return { z, size, width, height: bands.length * bandH, bands, cells, labelH };
  }

  function buildOverlay(layout) {
    const overlay = $("overlay");
    overlay.replaceChildren();
    const z = layout.z;
    for (const band of layout.bands) {
      const title = document.createElement("div");
      title.className = "band-title";
      title.style.left = `${Math.ceil(14 / z) * z}px`;
      title.style.top = `${band.y * z + 6}px`;
      title.style.color = inkFor(band.canvas.linear);
      band.titleEl = title;
      overlay.append(title);
    }
    for (const cell of layout.cells) {
      const hit = document.createElement("div");
      hit.className = "hit";
      Object.assign(hit.style, { left: `${cell.x * z}px`, top: `${cell.y * z}px`,
        width: `${layout.size * z}px`, height: `${layout.size * z}px` });
      hit.addEventListener("mouseenter", () => showTip(cell, hit));
      hit.addEventListener("mouseleave", hideTip);
      overlay.append(hit);
      if (state.labels) {
        const label = document.createElement("div");
        label.className = "cr";
        Object.assign(label.style, { left: `${cell.cellX * z}px`, width: `${cell.cellW * z}px`,
          top: `${(cell.y + layout.size) * z + 2}px`, color: inkFor(cell.band.canvas.linear) });
        cell.labelEl = label;
        overlay.append(label);
      }
    }
  }

  function metrics(icon, canvas) {
    const a = alphaFor(icon);
    const out = blend(icon.linear, canvas.linear, a, state.blend);
    return { a, out, cr: contrast(out, canvas.linear), ref: contrast(icon.linear, canvas.linear) };
  }

  const fmt = (v) => (v < 10 ? v.toFixed(2) : v.toFixed(1));

  function updateLabels(layout) {
    const t = DATA.threshold;
    const tally = new Map();
    for (const cell of layout.cells) {
      const m = metrics(DATA.icons[cell.icon], cell.band.canvas);
      const entry = tally.get(cell.band) || { pass: 0, ref: 0 };
      entry.pass += m.cr >= t ? 1 : 0;
      entry.ref += m.ref >= t ? 1 : 0;
      tally.set(cell.band, entry);
      if (cell.labelEl) {
        cell.labelEl.textContent = fmt(m.cr);
        cell.labelEl.classList.toggle("fail", m.cr < t);
      }
    }
    const n = DATA.icons.length;
    let pass = 0, ref = 0;
    for (const band of layout.bands) {
      const e = tally.get(band) || { pass: 0, ref: 0 };
      pass += e.pass; ref += e.ref;
      band.titleEl.innerHTML = "";
      band.titleEl.append(band.canvas.name);
      const span = document.createElement("span");
      span.textContent = `${band.canvas.hex} · ${e.pass} of ${n} ≥ ${t}:1 (α = 1: ${e.ref})`;
      band.titleEl.append(span);
    }
    const total = n * layout.bands.length;
    const mode = state.blend ? BLENDS[state.blend].label : state.own ? "each icon's own α" : `α = ${state.alpha}`;
    $("stats").textContent = `${mode}: ${pass} of ${total} icon-canvas pairs at or above ${t}:1 (at α = 1: ${ref})`;
  }

  function draw(layout) {
    renderer.resize(layout.width, layout.height);
    for (const band of layout.bands) {
      renderer.fill(0, band.y, layout.width, band.h, hexToCodes(band.canvas.hex));
      const items = layout.cells.filter((c) => c.band === band)
        .map((c) => ({ icon: c.icon, x: c.x, y: c.y, alpha: alphaFor(DATA.icons[c.icon]) }));
      renderer.draw(layout.size, band.canvas.linear, state.blend, items);
    }
    const canvas = $("gl");
    canvas.style.width = `${layout.width * layout.z}px`;
    canvas.style.height = `${layout.height * layout.z}px`;
  }

  function render(relayout) {
    if (relayout || !current) {
      current = computeLayout();
      buildOverlay(current);
    }
    draw(current);
    updateLabels(current);
  }

  let pending = false;
  function schedule(relayout) {
    if (relayout) current = null;
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; render(false); });
  }

  // ---- tooltip -----------------------------------------------------------------------------
  function showTip(cell, el) {
    const icon = DATA.icons[cell.icon];
    const m = metrics(icon, cell.band.canvas);
    const tip = $("tip");
    const sw = (hex) => `<span class="sw" style="background:${hex}"></span>${hex}`;
    tip.innerHTML = `<b></b><br>source ${sw(icon.hex)} · α ${fmt(m.a)}<br>` +
      `output ${sw(toHex(m.out))} on ${sw(cell.band.canvas.hex)}<br>` +
      `contrast ${fmt(m.ref)} → <b>${fmt(m.cr)}</b>:1`;
    tip.querySelector("b").textContent = icon.name;
    const r = el.getBoundingClientRect();
    tip.style.display = "block";
    tip.style.left = `${Math.min(r.right + 8, window.innerWidth - tip.offsetWidth - 8)}px`;
    tip.style.top = `${Math.max(8, r.top - 4)}px`;
  }
  const hideTip = () => { $("tip").style.display = "none"; };

  // ---- controls ----------------------------------------------------------------------------
  function chips(container, values, label, isOn, onPick) {
    container.replaceChildren();
    for (const value of values) {
      const b = document.createElement("button");
      b.type = "button";
      b.textContent = label(value);
      b.addEventListener("click", () => { onPick(value); syncControls(); });
      b.dataset.value = String(value);
      container.append(b);
    }
    container.refresh = () => {
      for (const b of container.children) b.setAttribute("aria-pressed", String(isOn(b.dataset.value)));
    };
  }

  function setAlpha(value, relayout = false) {
    if (!Number.isFinite(value)) return;
    state.alpha = Math.min(2, Math.max(-2, Math.round(value * 1000) / 1000));
    state.own = false;
    syncControls();
    schedule(relayout);
  }

  function syncControls() {
    $("alpha-range").value = String(state.alpha);
    if (document.activeElement !== $("alpha-number")) $("alpha-number").value = String(state.alpha);
    $("own").checked = state.own;
    const alphaOff = state.own || state.blend !== 0;
    $("alpha-range").disabled = alphaOff;
    $("alpha-number").disabled = alphaOff;
    $("canvas").value = state.custom ? "custom" : String(state.canvas);
    $("all").checked = state.all;
    $("labels").checked = state.labels;
    for (const id of ["alpha-chips", "blend", "sizes", "zooms"]) $(id).refresh();
  }

  function setup() {
    const range = $("alpha-range"), number = $("alpha-number");
    range.addEventListener("input", () => setAlpha(parseFloat(range.value)));
    number.addEventListener("input", () => setAlpha(parseFloat(number.value)));
    chips($("alpha-chips"), ALPHA_CHIPS, (v) => String(v),
      (v) => !state.own && state.blend === 0 && Number(v) === state.alpha,
      (v) => { state.blend = 0; setAlpha(v); });
    if (ownAlphas.length === 1 && ownAlphas[0] === 1) $("own-label").hidden = true;
    $("own").addEventListener("change", (e) => { state.own = e.target.checked; syncControls(); schedule(false); });
    chips($("blend"), BLENDS.map((b) => b.code), (c) => BLENDS[c].label,
      (c) => Number(c) === state.blend, (c) => { state.blend = c; schedule(false); });
    const select = $("canvas");
    DATA.canvases.forEach((c, k) => select.add(new Option(`${c.name}  ${c.hex}`, String(k))));
    select.add(new Option("custom colour", "custom"));
    select.addEventListener("change", () => {
      if (select.value === "custom") state.custom = $("custom").value;
      else { state.custom = null; state.canvas = Number(select.value); }
      state.all = false;
      syncControls();
      schedule(true);
    });
    $("custom").addEventListener("input", (e) => {
      state.custom = e.target.value;
      syncControls();
      schedule(true);
    });
    $("all").addEventListener("change", (e) => { state.all = e.target.checked; schedule(true); });
    chips($("sizes"), sizes, (s) => `${s} px`, (s) => Number(s) === state.size,
      (s) => { state.size = s; schedule(true); });
    chips($("zooms"), ZOOMS, (z) => `${z}×`, (z) => Number(z) === state.zoom,
      (z) => { state.zoom = z; schedule(true); });
    $("labels").addEventListener("change", (e) => { state.labels = e.target.checked; schedule(true); });
    document.addEventListener("keydown", (e) => {
      if (e.target instanceof HTMLInputElement && e.target.type !== "checkbox") return;
      if (e.key === "[") setAlpha(state.alpha - 0.05);
      else if (e.key === "]") setAlpha(state.alpha + 0.05);
      else if (e.key === "1") setAlpha(1);
      else if (e.key === "a") { state.all = !state.all; syncControls(); schedule(true); }
    });
    let width = 0;
    new ResizeObserver(() => {
      const w = document.querySelector("main").clientWidth;
      if (w !== width) { width = w; schedule(true); }
    }).observe(document.querySelector("main"));
    syncControls();
  }

  // ---- hook for automated validation (tests/preview/test_browser.py) -----------------------
  function toBase64(bytes) {
    let text = "";
    for (let i = 0; i < bytes.length; i += 0x8000) {
      text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    }
    return btoa(text);
  }

  /**
   * Render every icon for each job {canvas, size, blend, alpha} through the page's shader and
   * return base64 RGB bytes, job by job, icon by icon, rows top-down: the 8-bit canvas output.
   */
  function renderBatch(jobs) {
    const n = DATA.icons.length;
    let total = 0;
    for (const job of jobs) total += n * job.size * job.size * 3;
    const out = new Uint8Array(total);
    let offset = 0;
    for (const job of jobs) {
      const size = job.size, cols = Math.ceil(Math.sqrt(n)), rows = Math.ceil(n / cols);
      const canvas = DATA.canvases[job.canvas];
      const code = BLENDS.find((b) => b.id === job.blend).code;
      renderer.resize(cols * size, rows * size);
      renderer.fill(0, 0, cols * size, rows * size, hexToCodes(canvas.hex));
      const items = DATA.icons.map((icon, k) => ({ icon: k, x: (k % cols) * size,
        y: Math.floor(k / cols) * size, alpha: job.alpha }));
      renderer.draw(size, canvas.linear, code, items);
      const w = cols * size, h = rows * size;
      const pixels = new Uint8Array(w * h * 4);
      const gl = renderer.gl;
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      for (const item of items) {
        for (let r = 0; r < size; r++) {
          const glRow = h - 1 - (item.y + r); // readPixels rows are bottom-up
          let src = (glRow * w + item.x) * 4;
          for (let c = 0; c < size; c++, src += 4) {
            out[offset++] = pixels[src];
            out[offset++] = pixels[src + 1];
            out[offset++] = pixels[src + 2];
          }
        }
      }
    }
    current = null;
    schedule(true); // put the interactive view back
    return toBase64(out);
  }

  try {
    renderer = new Renderer($("gl"));
    setup();
    render(true);
    const gl = renderer.gl;
    window.alphaAuditPreview = {
      ready: true,
      icons: DATA.icons.length,
      canvases: DATA.canvases.length,
      sizes,
      renderer: (() => {
        const debug = gl.getExtension("WEBGL_debug_renderer_info");
        return gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
      })(),
      version: gl.getParameter(gl.VERSION),
      renderBatch,
    };
  } catch (error) {
    $("error").style.display = "block";
    $("error").textContent = String(error.message || error);
    window.alphaAuditPreview = { ready: false, error: String(error.message || error) };
  }
})();
