  // ---- the WebGL2 shader and its renderer: one offscreen drawing buffer, drawn in tiles -----
  // The renderer draws into an offscreen canvas no larger than the GPU's limits and hands the
  // pixels back; the page copies them into 2D tile canvases (page_layout.js).
  const VERTEX = `#version 300 es
in vec2 a_corner;
uniform vec2 u_viewport;
uniform ivec2 u_origin;
uniform int u_size;
void main() {
  vec2 px = vec2(u_origin) + a_corner * float(u_size);
  gl_Position = vec4(px / u_viewport * 2.0 - 1.0, 0.0, 1.0);
}`;
  // Up to MAX_PAINT_GROUPS (load/paint_masks.py) groups per icon, painted in order.
  const MAX_GROUPS = 32;
  const FRAGMENT = `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2DArray;
uniform sampler2DArray u_mask; // R8 coverage slots, q = k / 255, pages of columns x rows slots
uniform ivec2 u_origin;        // icon's lower-left pixel in the framebuffer
uniform int u_columns;         // slots across a page
uniform int u_perPage;         // slots on a page
uniform int u_first;           // the icon's first group's slot
uniform int u_count;           // the icon's groups
uniform int u_size;
uniform vec3 u_sources[${MAX_GROUPS}];  // Cs per group, linear sRGB
uniform float u_opacity[${MAX_GROUPS}]; // o per group
uniform vec3 u_background;     // Cb, linear sRGB, from the application
uniform float u_alpha;         // the real-valued coefficient
uniform int u_blend;           // 0 extended alpha, 1 Difference, 2 Exclusion
uniform int u_css;             // 1: source-over on encoded values (the css pipeline)
out vec4 o_color;
vec3 encodeSrgb(vec3 c) {      // CSS Color 4 gam_sRGB
  vec3 lo = c * 12.92;
  vec3 hi = 1.055 * pow(max(c, vec3(0.0)), vec3(1.0 / 2.4)) - 0.055;
  return mix(lo, hi, greaterThan(c, vec3(0.0031308)));
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  vec3 b = u_background;
  bool css = u_css == 1 && u_blend == 0;
  vec3 colour = css ? encodeSrgb(b) : b;
  for (int g = 0; g < ${MAX_GROUPS}; g++) {
    if (g >= u_count) break;
    int slot = u_first + g;
    int page = slot / u_perPage;
    int rest = slot - page * u_perPage;
    int row = rest / u_columns;
    int col = rest - row * u_columns;
    float q = texelFetch(u_mask, ivec3(col * u_size + p.x, row * u_size + u_size - 1 - p.y, page), 0).r;
    vec3 s = u_sources[g];
    if (css) {
      float w = u_alpha * (u_opacity[g] * q);
      colour = clamp(colour + w * (encodeSrgb(s) - colour), 0.0, 1.0);
      continue;
    }
    vec3 x;
    if (u_blend == 1) {
      x = clamp(abs(s - b), 0.0, 1.0);
    } else if (u_blend == 2) {
      x = clamp(s + b - 2.0 * s * b, 0.0, 1.0);
    } else {
      x = clamp(b + u_alpha * (s - b), 0.0, 1.0);
    }
    float w = u_opacity[g] * q;
    colour = w * x + (1.0 - w) * colour;
  }
  o_color = vec4(css ? colour : encodeSrgb(colour), 1.0);
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
      for (const name of ["u_viewport", "u_origin", "u_size", "u_mask", "u_columns",
        "u_perPage", "u_first", "u_count", "u_sources", "u_opacity", "u_background", "u_alpha",
        "u_blend", "u_css"]) {
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

    /** The GPU's own limits, queried (WebGL2 guarantees only minimums; never assume more). */
    limits() {
      const gl = this.gl;
      const viewport = gl.getParameter(gl.MAX_VIEWPORT_DIMS);
      return {
        viewportW: viewport[0], viewportH: viewport[1],
        texture: gl.getParameter(gl.MAX_TEXTURE_SIZE),
        renderbuffer: gl.getParameter(gl.MAX_RENDERBUFFER_SIZE),
      };
    }

    /** The mask slots of one size as one texture array (pages of at most 2048 x 2048). */
    texture(size) {
      const gl = this.gl;
      if (!this.textures.has(size)) {
        const atlas = DATA.atlases[String(size)];
        const limit = gl.getParameter(gl.MAX_TEXTURE_SIZE);
        const layers = gl.getParameter(gl.MAX_ARRAY_TEXTURE_LAYERS);
        if (atlas.width > limit || atlas.height > limit) {
          throw new Error(`mask atlas larger than this GPU's ${limit} px`);
        }
        if (atlas.pages > layers) throw new Error(`mask atlas beyond this GPU's ${layers} layers`);
        const bytes = Uint8Array.from(atob(atlas.data), (ch) => ch.charCodeAt(0));
        const tex = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D_ARRAY, tex);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        gl.texImage3D(gl.TEXTURE_2D_ARRAY, 0, gl.R8, atlas.width, atlas.height, atlas.pages, 0,
          gl.RED, gl.UNSIGNED_BYTE, bytes);
        for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) {
          gl.texParameteri(gl.TEXTURE_2D_ARRAY, p, gl.NEAREST);
        }
        for (const p of [gl.TEXTURE_WRAP_S, gl.TEXTURE_WRAP_T]) {
          gl.texParameteri(gl.TEXTURE_2D_ARRAY, p, gl.CLAMP_TO_EDGE);
        }
        this.textures.set(size, { tex, columns: atlas.columns, perPage: atlas.columns * atlas.rows });
      }
      return this.textures.get(size);
    }

    /** Size the drawing buffer; false if the browser gave less than asked (its own limit). */
    resize(width, height) {
      if (this.canvas.width !== width) this.canvas.width = width;
      if (this.canvas.height !== height) this.canvas.height = height;
      const gl = this.gl;
      gl.viewport(0, 0, width, height);
      gl.uniform2f(this.u.u_viewport, width, height);
      return gl.drawingBufferWidth === width && gl.drawingBufferHeight === height;
    }

    /** The drawing buffer's RGBA bytes, rows top-down (readPixels gives them bottom-up). */
    read(width, height) {
      const gl = this.gl;
      const raw = new Uint8Array(width * height * 4);
      gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, raw);
      const out = new Uint8ClampedArray(raw.length);
      const stride = width * 4;
      for (let r = 0; r < height; r++) {
        out.set(raw.subarray((height - 1 - r) * stride, (height - r) * stride), r * stride);
      }
      return out;
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

    /**
     * Draw icons of one size on one canvas colour; items are {icon, x, y, alpha}, top-down.
     * An icon's groups are its `layers` (colour, opacity) from slot `first`; an icon without
     * layers is one group of its own colour at opacity 1 in the slot of its index.
     */
    draw(size, background, blendCode, items, css = false) {
      const gl = this.gl;
      const { tex, columns, perPage } = this.texture(size);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D_ARRAY, tex);
      gl.uniform1i(this.u.u_size, size);
      gl.uniform1i(this.u.u_columns, columns);
      gl.uniform1i(this.u.u_perPage, perPage);
      gl.uniform3f(this.u.u_background, background[0], background[1], background[2]);
      gl.uniform1i(this.u.u_blend, blendCode);
      gl.uniform1i(this.u.u_css, css ? 1 : 0);
      const sources = new Float32Array(3 * MAX_GROUPS), opacity = new Float32Array(MAX_GROUPS);
      for (const item of items) {
        const icon = DATA.icons[item.icon];
        const layers = icon.layers || [{ linear: icon.linear, opacity: 1 }];
        const count = Math.min(layers.length, MAX_GROUPS);
        for (let g = 0; g < count; g++) {
          sources.set(layers[g].linear, 3 * g);
          opacity[g] = layers[g].opacity;
        }
        gl.uniform3fv(this.u.u_sources, sources);
        gl.uniform1fv(this.u.u_opacity, opacity);
        gl.uniform1i(this.u.u_count, count);
        gl.uniform1i(this.u.u_first, icon.layers ? icon.first : item.icon);
        gl.uniform1f(this.u.u_alpha, item.alpha);
        gl.uniform2i(this.u.u_origin, item.x, this.canvas.height - item.y - size);
        gl.drawArrays(gl.TRIANGLES, 0, 6);
      }
    }
  }
