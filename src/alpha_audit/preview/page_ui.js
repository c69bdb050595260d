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

