// alpha-audit runtime page: the preview's own shader, timed (paper, Section 4.4, Appendix A.3).
// Each frame clears a 1280 x 960 canvas to the warm light or the cool dark background in
// turn, draws every icon at 48 px with one coefficient, and reads back one pixel
// synchronously; performance.now() times blocks of consecutive frames.
"use strict";
(() => {
  const DATA = JSON.parse(document.getElementById("alpha-audit-runtime").textContent);
  try {
    const canvas = document.getElementById("gl");
    canvas.width = DATA.width;
    canvas.height = DATA.height;
    const gl = canvas.getContext("webgl2", {
      alpha: false, antialias: false, depth: false, stencil: false,
      premultipliedAlpha: false, preserveDrawingBuffer: true,
    });
    if (!gl) throw new Error("no WebGL2");
    const program = gl.createProgram();
    for (const [type, source] of [[gl.VERTEX_SHADER, DATA.vertex],
      [gl.FRAGMENT_SHADER, DATA.fragment]]) {
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
    const u = {};
    for (const name of ["u_viewport", "u_origin", "u_size", "u_mask", "u_atlas", "u_source",
      "u_background", "u_alpha", "u_blend"]) {
      u[name] = gl.getUniformLocation(program, name);
    }
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1, 1]),
      gl.STATIC_DRAW);
    const loc = gl.getAttribLocation(program, "a_corner");
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, 2, gl.FLOAT, false, 0, 0);
    gl.disable(gl.BLEND);
    gl.disable(gl.DITHER);
    const atlas = DATA.atlas;
    const bytes = Uint8Array.from(atob(atlas.data), (ch) => ch.charCodeAt(0));
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, gl.createTexture());
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.R8, atlas.width, atlas.height, 0, gl.RED,
      gl.UNSIGNED_BYTE, bytes);
    for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) {
      gl.texParameteri(gl.TEXTURE_2D, p, gl.NEAREST);
    }
    gl.uniform1i(u.u_mask, 0);
    gl.uniform1i(u.u_size, DATA.size);
    gl.uniform1i(u.u_blend, 0);
    gl.viewport(0, 0, DATA.width, DATA.height);
    gl.uniform2f(u.u_viewport, DATA.width, DATA.height);
    const size = DATA.size;
    const perRow = Math.floor(DATA.width / size);
    const pixel = new Uint8Array(4);
    let frameCount = 0;

    function frame(alpha) {
      const bg = DATA.backgrounds[frameCount++ % DATA.backgrounds.length];
      gl.clearColor(bg.codes[0] / 255, bg.codes[1] / 255, bg.codes[2] / 255, 1);
      gl.clear(gl.COLOR_BUFFER_BIT);
      gl.uniform3f(u.u_background, bg.linear[0], bg.linear[1], bg.linear[2]);
      gl.uniform1f(u.u_alpha, alpha);
      for (let k = 0; k < DATA.draws.length; k++) {
        const icon = DATA.draws[k];
        const s = DATA.sources[icon];
        gl.uniform3f(u.u_source, s[0], s[1], s[2]);
        gl.uniform2i(u.u_origin, (k % perRow) * size,
          DATA.height - (Math.floor(k / perRow) + 1) * size);
        gl.uniform2i(u.u_atlas, (icon % atlas.columns) * size,
          Math.floor(icon / atlas.columns) * size);
        gl.drawArrays(gl.TRIANGLES, 0, 6);
      }
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel); // synchronous: waits for GL
    }

    /** Mean milliseconds per frame of one block of `frames` frames at each alpha, in order. */
    function sweep(alphas, frames) {
      const means = [];
      for (const alpha of alphas) {
        const start = performance.now();
        for (let f = 0; f < frames; f++) frame(alpha);
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
})();
