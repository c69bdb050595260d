  // ---- labels, band titles, tooltip and controls ---------------------------------------------
  // Names come from input files: they only ever reach the page as textContent, never as markup.

  /** The icon's rows on a canvas: size contrast at the drawn size, at alpha and at 1. */
  function metrics(icon, canvas) {
    const a = alphaFor(icon), b = canvas.linear, size = state.size;
    return {
      a,
      cr: sizeContrast(icon, b, a, size, state.blend),
      ref: sizeContrast(icon, b, 1, size, 0),
    };
  }

  const fmt = (v) => (Number.isNaN(v) ? "-" : v < 10 ? v.toFixed(2) : v.toFixed(1));

  function buildBands(layout) {
    const overlay = $("overlay");
    overlay.replaceChildren();
    const z = layout.z;
    for (const band of layout.bands) {
      const el = document.createElement("div");
      el.className = "band";
      el.dataset.canvas = band.canvas.name;
      el.dataset.hex = band.canvas.hex;
      Object.assign(el.style, { top: `${band.y * z}px`, height: `${band.h * z}px` });
      const title = document.createElement("div");
      title.className = "band-title";
      title.style.left = `${layout.pad * z}px`;
      title.style.color = inkFor(band.canvas.linear);
      el.append(title);
      band.titleEl = title;
      overlay.append(el);
    }
  }

  /** Labels and hover targets for the cells whose icon starts in this tile. */
  function buildCells(layout, tile) {
    const z = layout.z;
    tile.cells = cellsIn(layout, tile.y, tile.y + tile.h, true);
    tile.labelled = -1;
    const parts = [];
    for (const cell of tile.cells) {
      const icon = DATA.icons[cell.icon];
      const hit = document.createElement("div");
      hit.className = "hit";
      hit.dataset.icon = String(cell.icon);
      hit.dataset.band = String(cell.band.index);
      Object.assign(hit.style, { left: `${cell.x * z}px`, top: `${cell.y * z}px`,
        width: `${layout.size * z}px`, height: `${layout.size * z}px` });
      if (icon.fixed) hit.classList.add("fixed");
      hit.addEventListener("mouseenter", () => showTip(cell, hit));
      hit.addEventListener("mouseleave", hideTip);
      parts.push(hit);
      if (state.labels) {
        const label = document.createElement("div");
        label.className = "cr";
        label.dataset.icon = String(cell.icon);
        label.dataset.band = String(cell.band.index);
        Object.assign(label.style, { left: `${cell.cellX * z}px`, width: `${cell.cellW * z}px`,
          top: `${(cell.y + layout.size) * z + 2}px`, color: inkFor(cell.band.canvas.linear) });
        const name = document.createElement("span");
        name.className = "name";
        name.textContent = icon.name;
        label.title = icon.name;
        const value = document.createElement("span");
        value.className = "value";
        label.append(name, value);
        cell.valueEl = value;
        cell.labelEl = label;
        parts.push(label);
      }
    }
    tile.overlay.replaceChildren(...parts);
  }

  function updateCells(tile) {
    if (tile.labelled === generation) return;
    const t = DATA.threshold;
    for (const cell of tile.cells) {
      if (!cell.labelEl) continue;
      const m = metrics(DATA.icons[cell.icon], cell.band.canvas);
      cell.valueEl.textContent = fmt(m.cr);
      cell.labelEl.classList.toggle("fail", m.cr < t);
    }
    tile.labelled = generation;
  }

  function updateTitles(layout) {
    const t = DATA.threshold;
    const n = DATA.icons.length;
    let pass = 0, ref = 0;
    for (const band of layout.bands) {
      let bandPass = 0, bandRef = 0;
      for (const icon of DATA.icons) {
        const m = metrics(icon, band.canvas);
        bandPass += m.cr >= t ? 1 : 0;
        bandRef += m.ref >= t ? 1 : 0;
      }
      pass += bandPass; ref += bandRef;
      band.titleEl.replaceChildren(band.canvas.name);
      const span = document.createElement("span");
      span.textContent = `${band.canvas.hex} · ${bandPass} of ${n} ≥ ${t}:1 (α = 1: ${bandRef})`;
      band.titleEl.append(span);
    }
    const total = n * layout.bands.length;
    const mode = state.blend ? BLENDS[state.blend].label : state.own ? "each icon's own α" : `α = ${state.alpha}`;
    $("stats").textContent = `${mode}: ${pass} of ${total} icon-canvas pairs at or above ${t}:1 (at α = 1: ${ref})`;
  }

  // ---- tooltip -----------------------------------------------------------------------------
  function showTip(cell, el) {
    const icon = DATA.icons[cell.icon];
    const m = metrics(icon, cell.band.canvas);
    const tip = $("tip");
    const line = (...items) => {
      const div = document.createElement("div");
      for (const item of items) {
        if (typeof item === "string") div.append(item);
        else {
          const sw = document.createElement("span");
          sw.className = "sw";
          sw.style.background = item.hex; // our own #rrggbb, never input text
          div.append(sw, item.hex);
        }
      }
      return div;
    };
    const name = document.createElement("b");
    name.textContent = icon.name;
    tip.replaceChildren(
      name,
      line(`α ${fmt(m.a)} on `, { hex: cell.band.canvas.hex }, ` · ${DATA.pipeline} pipeline`),
      ...icon.layers.map((layer) => line(layer.paint === "currentColor" ? "currentColor " : "fixed ",
        { hex: layer.hex }, layer.opacity < 1 ? ` · opacity ${fmt(layer.opacity)}` : "")),
      line(`size contrast at ${state.size} px ${fmt(m.ref)} → ${fmt(m.cr)}:1`),
    );
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

  function setAlpha(value) {
    if (!Number.isFinite(value)) return;
    const [low, high] = CSS ? [0, 1] : [-2, 2]; // css opacity is limited to [0, 1]
    state.alpha = Math.min(high, Math.max(low, Math.round(value * 1000) / 1000));
    state.own = false;
    syncControls();
    schedule(false, true);
  }

  /** The colour the free picker shows: the custom canvas when set, else the canvas on screen. */
  const pickerColour = () => state.custom || DATA.canvases[state.canvas].hex;

  function syncControls() {
    $("alpha-range").value = String(state.alpha);
    if (document.activeElement !== $("alpha-number")) $("alpha-number").value = String(state.alpha);
    $("own").checked = state.own;
    const alphaOff = state.own || state.blend !== 0;
    $("alpha-range").disabled = alphaOff;
    $("alpha-number").disabled = alphaOff;
    $("canvas").value = state.custom ? "custom" : String(state.canvas);
    $("custom-option").textContent = state.custom ? `custom colour  ${state.custom}` : "custom colour";
    $("custom").value = pickerColour();
    $("custom").title = `any canvas colour (now ${pickerColour()})`;
    $("all").checked = state.all;
    $("labels").checked = state.labels;
    for (const id of ["alpha-chips", "blend", "sizes", "zooms"]) $(id).refresh();
  }

  function setup() {
    const range = $("alpha-range"), number = $("alpha-number");
    range.addEventListener("input", () => setAlpha(parseFloat(range.value)));
    number.addEventListener("input", () => setAlpha(parseFloat(number.value)));
    chips($("alpha-chips"), CSS ? ALPHA_CHIPS.filter((v) => v >= 0 && v <= 1) : ALPHA_CHIPS, (v) => String(v),
      (v) => !state.own && state.blend === 0 && Number(v) === state.alpha,
      (v) => { state.blend = 0; setAlpha(v); });
    if (ownAlphas.length === 1 && ownAlphas[0] === 1) $("own-label").hidden = true;
    $("own").addEventListener("change", (e) => {
      state.own = e.target.checked; syncControls(); schedule(false, true);
    });
    chips($("blend"), BLENDS.map((b) => b.code), (c) => BLENDS[c].label,
      (c) => Number(c) === state.blend, (c) => { state.blend = c; schedule(false, true); });
    const select = $("canvas");
    DATA.canvases.forEach((c, k) => select.add(new Option(`${c.name}  ${c.hex}`, String(k))));
    const custom = new Option("custom colour", "custom");
    custom.id = "custom-option";
    select.add(custom);
    select.addEventListener("change", () => {
      if (select.value === "custom") state.custom = $("custom").value;
      else { state.custom = null; state.canvas = Number(select.value); }
      state.all = false;
      syncControls();
      schedule(true);
    });
    $("custom").addEventListener("input", (e) => {
      state.custom = e.target.value.toLowerCase();
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
