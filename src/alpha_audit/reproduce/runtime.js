  // ---- the timing loop (paper, Section 4.4, Appendix A.3) ----------------------------------
  // Runs after the preview's own page_shader.js in one function scope (runtime.py): the frames
  // are drawn by its Renderer, the very WebGL2 set-up and shader the preview page uses.
  // Each frame clears a 1280 x 960 canvas to the warm light or the cool dark background in
  // turn, draws every icon at 48 px with one coefficient, and reads back one pixel
  // synchronously; performance.now() times blocks of consecutive frames.
  const DATA = JSON.parse(document.getElementById("alpha-audit-runtime").textContent);
  try {
    const renderer = new Renderer(document.getElementById("gl"));
    if (!renderer.resize(DATA.width, DATA.height)) {
      throw new Error(`the browser gave no ${DATA.width} x ${DATA.height} drawing buffer`);
    }
    const gl = renderer.gl;
    const size = DATA.size;
    const perRow = Math.floor(DATA.width / size);
    const pixel = new Uint8Array(4);
    let frameCount = 0;

    /** The frame's draws at one coefficient, laid out row by row from the top left. */
    function items(alpha) {
      return DATA.draws.map((icon, k) => ({
        icon, x: (k % perRow) * size, y: Math.floor(k / perRow) * size, alpha,
      }));
    }

    function frame(draws) {
      const bg = DATA.backgrounds[frameCount++ % DATA.backgrounds.length];
      renderer.fill(0, 0, DATA.width, DATA.height, bg.codes);
      renderer.draw(size, bg.linear, 0, draws);
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel); // synchronous: waits for GL
    }

    /** Mean milliseconds per frame of one block of `frames` frames at each alpha, in order. */
    function sweep(alphas, frames) {
      const means = [];
      for (const alpha of alphas) {
        const draws = items(alpha);
        const start = performance.now();
        for (let f = 0; f < frames; f++) frame(draws);
        means.push((performance.now() - start) / frames);
      }
      return means;
    }

    const debug = gl.getExtension("WEBGL_debug_renderer_info");
    window.alphaAuditRuntime = {
      ready: true,
      renderer: gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER),
      sweep,
    };
  } catch (error) {
    window.alphaAuditRuntime = { ready: false, error: String(error.message || error) };
  }
