  // ---- state, layout and tiled drawing -------------------------------------------------------
  // The view is a stack of bands (one per canvas shown), each a grid of cells: an icon with its
  // name and contrast ratio under it. It is drawn in horizontal tiles, each a 2D canvas no larger
  // than the GPU allows, painted only while near the viewport (3,000 icons x 40 canvases would be
  // gigabytes as one image) and released when far from it.
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
    size: sizes.includes(DATA.size) ? DATA.size : sizes[sizes.length - 1],
    zoom: 1,
    labels: true,
  };
  // Tiles this tall keep one readback near 10 MB and scrolling smooth; the GPU may allow less.
  const TILE_CAP = 2048;

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
  let limits = null; // the largest tile the GPU draws: {w, h}, from its queried limits
  let current = null; // the layout on screen
  let generation = 0; // bumped by every change of what the pixels show
  let observer = null;
  const visible = new Set();

  function tileLimits() {
    const l = renderer.limits();
    return {
      w: Math.min(l.viewportW, l.renderbuffer, l.texture),
      h: Math.min(l.viewportH, l.renderbuffer, l.texture, TILE_CAP),
    };
  }

  function computeLayout() {
    const z = state.zoom, size = state.size, n = DATA.icons.length;
    const gap = Math.max(8, Math.floor(size / 3));
    const cellW = Math.max(size + gap, Math.ceil(56 / z));
    const labelH = state.labels ? Math.ceil(30 / z) : 0; // two lines: name, contrast
    const cellH = size + gap + labelH;
    const pad = Math.ceil(14 / z);
    const titleH = Math.ceil(26 / z);
    const avail = Math.max(200, document.querySelector("main").clientWidth - 40);
    const fitCols = Math.floor((avail / z - 2 * pad + gap) / cellW);
    const maxCols = Math.floor((limits.w - 2 * pad + gap) / cellW); // a tile's width
    const cols = Math.max(1, Math.min(n, fitCols, maxCols));
    const rows = Math.max(1, Math.ceil(n / cols));
    const width = 2 * pad + cols * cellW - gap;
    const bandH = titleH + rows * cellH + pad - gap;
    const bands = canvasList().map((canvas, b) => ({ canvas, index: b, y: b * bandH, h: bandH }));
    const height = bands.length * bandH;
    const tiles = [];
    for (let y = 0; y < height; y += limits.h) tiles.push({ y, h: Math.min(limits.h, height - y) });
    return { z, size, gap, cellW, cellH, pad, titleH, labelH, cols, rows, width, height, bands, tiles };
  }

  /** The cell of icon k in a band: icon box at (x, y), label column from cellX, cellW wide. */
  function cellOf(layout, band, k) {
    const r = Math.floor(k / layout.cols), c = k % layout.cols;
    const cellX = layout.pad + c * layout.cellW;
    return {
      band, icon: k, cellX, cellW: layout.cellW - layout.gap,
      x: cellX + Math.floor((layout.cellW - layout.gap - layout.size) / 2),
      y: band.y + layout.titleH + r * layout.cellH,
    };
  }

  /** Cells whose icon box starts at or below y0 and above y1 (whole = false: any overlap). */
  function cellsIn(layout, y0, y1, whole) {
    const out = [];
    const n = DATA.icons.length;
    for (const band of layout.bands) {
      if (band.y >= y1 || band.y + band.h <= y0) continue;
      const top = band.y + layout.titleH;
      const reach = whole ? 0 : layout.size - 1;
      const r0 = Math.max(0, Math.ceil((y0 - reach - top) / layout.cellH));
      const r1 = Math.min(layout.rows - 1, Math.floor((y1 - 1 - top) / layout.cellH));
      for (let r = r0; r <= r1; r++) {
        for (let k = r * layout.cols; k < Math.min(n, (r + 1) * layout.cols); k++) {
          out.push(cellOf(layout, band, k));
        }
      }
    }
    return out;
  }

  /** Draw one tile through the shader and copy its pixels into the tile's 2D canvas. */
  function paintTile(layout, tile) {
    if (!renderer.resize(layout.width, tile.h)) {
      // The browser gave a smaller drawing buffer than the GPU's limits promise: use what it
      // gave from now on, and lay the view out again.
      const gl = renderer.gl;
      if (gl.drawingBufferWidth < 1 || gl.drawingBufferHeight < 1) {
        throw new Error("the browser gave no WebGL2 drawing buffer");
      }
      limits = { w: Math.min(limits.w, gl.drawingBufferWidth), h: Math.min(limits.h, gl.drawingBufferHeight) };
      schedule(true);
      return false;
    }
    for (const band of layout.bands) {
      const y0 = Math.max(band.y, tile.y), y1 = Math.min(band.y + band.h, tile.y + tile.h);
      if (y0 < y1) renderer.fill(0, y0 - tile.y, layout.width, y1 - y0, hexToCodes(band.canvas.hex));
    }
    const cells = cellsIn(layout, tile.y, tile.y + tile.h, false);
    for (const band of layout.bands) {
      const items = cells.filter((c) => c.band === band)
        .map((c) => ({ icon: c.icon, x: c.x, y: c.y - tile.y, alpha: alphaFor(DATA.icons[c.icon]) }));
      if (items.length) renderer.draw(layout.size, band.canvas.linear, state.blend, items, CSS);
    }
    const pixels = renderer.read(layout.width, tile.h);
    const canvas = tile.canvas;
    if (canvas.width !== layout.width) canvas.width = layout.width;
    if (canvas.height !== tile.h) canvas.height = tile.h;
    canvas.getContext("2d").putImageData(new ImageData(pixels, layout.width, tile.h), 0, 0);
    tile.painted = generation;
    canvas.dataset.generation = String(generation);
    return true;
  }

  function releaseTile(tile) {
    tile.canvas.width = 0; // frees the pixels; the element keeps its place and CSS size
    tile.canvas.height = 0;
    tile.painted = -1;
    delete tile.canvas.dataset.generation;
    tile.overlay.replaceChildren();
    tile.cells = null;
  }

  function buildStage(layout) {
    if (observer) observer.disconnect();
    visible.clear();
    const z = layout.z;
    const stage = $("stage"), tiles = $("tiles"), cells = $("cells");
    stage.style.width = `${layout.width * z}px`;
    stage.style.height = `${layout.height * z}px`;
    tiles.replaceChildren();
    cells.replaceChildren(); // above every tile: a label may hang over the next tile down
    observer = new IntersectionObserver((entries) => {
      for (const entry of entries) {
        const tile = entry.target.tile;
        if (entry.isIntersecting) visible.add(tile);
        else if (visible.delete(tile)) releaseTile(tile);
      }
      schedule(false);
    }, { rootMargin: "50% 0px" });
    layout.tiles.forEach((tile, t) => {
      const canvas = document.createElement("canvas");
      canvas.className = "tile";
      canvas.width = 0;
      canvas.height = 0;
      canvas.dataset.tile = String(t);
      Object.assign(canvas.style, { top: `${tile.y * z}px`, width: `${layout.width * z}px`,
        height: `${tile.h * z}px` });
      const overlay = document.createElement("div");
      overlay.className = "tile-overlay";
      Object.assign(tile, { canvas, overlay, painted: -1, cells: null });
      canvas.tile = tile;
      tiles.append(canvas);
      cells.append(overlay);
      observer.observe(canvas);
    });
    buildBands(layout);
  }

  function render(relayout) {
    if (relayout || !current) {
      current = computeLayout();
      generation++;
      buildStage(current);
    }
    for (const tile of visible) {
      if (tile.painted !== generation && !paintTile(current, tile)) return; // laid out again
      if (!tile.cells) buildCells(current, tile);
      updateCells(tile);
    }
    if (current.counted !== generation) {
      updateTitles(current);
      current.counted = generation;
    }
    $("stage").dataset.generation = String(generation);
  }

  let pending = false;
  function schedule(relayout, changed = false) {
    if (relayout) current = null;
    else if (changed) generation++;
    $("stage").dataset.pending = "1";
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => {
      pending = false;
      try {
        render(false);
      } catch (error) {
        $("error").style.display = "block";
        $("error").textContent = String(error.message || error);
      }
      if (!pending) $("stage").dataset.pending = "0";
    });
  }
