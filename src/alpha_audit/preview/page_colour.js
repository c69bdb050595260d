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

  /** What an 8-bit screen shows for a linear colour. */
  const shipped = (c) => to8bit(c).map((v) => decode(v / 255));
  /**
   * A paint of colour s at weight w = opacity x coverage on canvas b, as its row draws it:
   * linear: w X + (1 - w) b with X the blend; css: b' + a w (s' - b') on encoded values, 8-bit.
   */
  function paintShown(s, b, a, w, mode) {
    if (CSS && mode === 0) {
      return s.map((v, k) => {
        const be = encode(b[k]);
        return decode(roundHalfEven(clip(be + a * w * (encode(v) - be)) * 255) / 255);
      });
    }
    const x = blend(s, b, a, mode);
    return x.map((v, k) => w * v + (1 - w) * b[k]);
  }
  /**
   * An icon's size contrast at `size` on canvas b: the lowest over its paint groups of the
   * contrast of the group shown at opacity x q50 (8-bit) against the 8-bit canvas. NaN when
   * no group draws at that size.
   */
  function sizeContrast(icon, b, a, size, mode) {
    const screen = shipped(b);
    let low = NaN;
    for (const layer of icon.layers) {
      const q50 = layer.q50[String(size)];
      if (q50 === null || q50 === undefined) continue;
      const c = contrast(shipped(paintShown(layer.linear, b, a, q50 * layer.opacity, mode)), screen);
      if (!(c >= low)) low = c;
    }
    return low;
  }
