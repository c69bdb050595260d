// alpha-audit's stillness: what pages/stillness.py runs before a page is captured.
// Evaluated as one expression; pages/stillness.py calls hold() where the engine has an
// isolated world (the page cannot hide its animations from it) and quiet() in the
// page's own world (timers and frame callbacks belong to the world that made them).
(() => {
  const MARK = "data-alpha-audit-still";
  // The first cascade layer's !important declarations win over every later layer and
  // every unlayered style (CSS Cascade 5, section 6.4): a page's own !important
  // transition cannot delay the hidden capture.
  const CSS =
    "@layer alpha-audit-still { *, *::before, *::after {" +
    " transition: none !important; animation-play-state: paused !important;" +
    " caret-color: transparent !important; } }";

  function roots() {
    const found = [document];
    for (let k = 0; k < found.length; k++) {
      for (const el of found[k].querySelectorAll("*")) if (el.shadowRoot) found.push(el.shadowRoot);
    }
    return found;
  }

  // Animations that end are finished (the page as it rests: a fade-in ends shown);
  // endless ones are paused at the start of their first iteration, whatever phase
  // they had reached.  SVG animations (SMIL) go to time 0, media are paused, and a
  // style sheet first in each root stops transitions and pauses new animations.
  function hold() {
    const all = roots();
    const animations = new Set();
    for (const root of all) {
      for (const a of root.getAnimations ? root.getAnimations() : []) animations.add(a);
    }
    for (const a of animations) {
      try {
        const effect = a.effect;
        const end = effect ? effect.getComputedTiming().endTime : Infinity;
        if (Number.isFinite(end)) a.finish();
        else {
          a.pause();
          a.currentTime = effect ? Number(effect.getTiming().delay) || 0 : 0;
        }
      } catch (e) {
        try {
          a.pause();
        } catch (e2) {
          // a page's own object, not an animation: nothing to hold
        }
      }
    }
    for (const root of all) {
      for (const svg of root.querySelectorAll("svg")) {
        if (svg.pauseAnimations) {
          svg.pauseAnimations();
          svg.setCurrentTime(0);
        }
      }
      for (const media of root.querySelectorAll("video, audio")) {
        try {
          media.pause();
        } catch (e) {
          // not playable: nothing moves
        }
      }
      if (!root.querySelector(`style[${MARK}]`)) {
        const style = document.createElement("style");
        style.setAttribute(MARK, "");
        style.textContent = CSS;
        (root === document ? document.head || document.documentElement : root).prepend(style);
      }
    }
    return animations.size;
  }

  // Every pending timer, interval, animation frame and idle callback of this world,
  // cancelled: ids count up from 1, so the newest id bounds them (at most MAX of them).
  function quiet(max) {
    const newest = (make) => {
      try {
        return Number(make()) || 0;
      } catch (e) {
        return 0;
      }
    };
    const sweep = (top, cancel) => {
      for (let id = Math.max(1, top - max); id <= top; id++) {
        try {
          cancel(id);
        } catch (e) {
          // a page that replaced the function: what it left running shows as unstable
        }
      }
    };
    sweep(newest(() => setTimeout(() => {}, 0)), (id) => {
      clearTimeout(id);
      clearInterval(id);
    });
    if (typeof requestAnimationFrame === "function") {
      sweep(newest(() => requestAnimationFrame(() => {})), cancelAnimationFrame);
    }
    if (typeof requestIdleCallback === "function") {
      sweep(newest(() => requestIdleCallback(() => {})), cancelIdleCallback);
    }
    return true;
  }

  return { hold, quiet };
})()
