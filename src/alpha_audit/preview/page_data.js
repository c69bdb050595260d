  // ---- the data embedded by html.py, and the page's fixed choices --------------------------
  const DATA = JSON.parse(document.getElementById("alpha-audit-data").textContent);
  // The rows' pipeline: css draws source-over on encoded values (alpha in [0, 1]).
  const CSS = DATA.pipeline === "css";
  const BLENDS = [
    { id: "alpha", label: "α (extended)", code: 0 },
    { id: "difference", label: "Difference", code: 1 },
    { id: "exclusion", label: "Exclusion", code: 2 },
  ];
  const ALPHA_CHIPS = [-1, 0, 0.6, 1, 1.1, 1.2, 1.4, 2];
  const ZOOMS = [1, 2, 3, 4];
  // WCAG 2.2 relative luminance weights.
  const WEIGHTS = [0.2126, 0.7152, 0.0722];

