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
