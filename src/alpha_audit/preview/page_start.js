  // ---- hook for automated validation (tests/browser/), and start-up ---------
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
   * Icons are drawn in batches that fit the GPU's drawing-buffer limits.
   */
  function renderBatch(jobs) {
    const n = DATA.icons.length;
    let total = 0;
    for (const job of jobs) total += n * job.size * job.size * 3;
    const out = new Uint8Array(total);
    let offset = 0;
    for (const job of jobs) {
      const size = job.size;
      const cols = Math.max(1, Math.min(Math.ceil(Math.sqrt(n)), Math.floor(limits.w / size)));
      const perBatch = cols * Math.max(1, Math.floor(limits.h / size));
      const canvas = DATA.canvases[job.canvas];
      const code = BLENDS.find((b) => b.id === job.blend).code;
      for (let first = 0; first < n; first += perBatch) {
        const count = Math.min(perBatch, n - first);
        const w = cols * size, h = Math.ceil(count / cols) * size;
        renderer.resize(w, h);
        renderer.fill(0, 0, w, h, hexToCodes(canvas.hex));
        const items = [];
        for (let k = 0; k < count; k++) {
          items.push({ icon: first + k, x: (k % cols) * size, y: Math.floor(k / cols) * size,
            alpha: job.alpha });
        }
        renderer.draw(size, canvas.linear, code, items, CSS);
        const pixels = renderer.read(w, h);
        for (const item of items) {
          for (let r = 0; r < size; r++) {
            let src = ((item.y + r) * w + item.x) * 4;
            for (let c = 0; c < size; c++, src += 4) {
              out[offset++] = pixels[src];
              out[offset++] = pixels[src + 1];
              out[offset++] = pixels[src + 2];
            }
          }
        }
      }
    }
    return toBase64(out);
  }

  try {
    renderer = new Renderer(document.createElement("canvas")); // offscreen; tiles are 2D canvases
    limits = tileLimits();
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
