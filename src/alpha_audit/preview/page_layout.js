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

