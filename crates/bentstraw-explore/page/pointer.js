// Pointer input on a canvas: drags, clicks and taps, and two fingers' pinches, the same for a
// mouse, a pen and fingers.

/** Pointer input on `el` (mouse, pen, fingers): `move(dx, dy, event)` while dragging,
 * `click(event)` for a click or a tap, `pinch(ratio, event)` while two fingers spread (ratio > 1)
 * or close. A finger's drag is the page's only once it goes sideways: the canvases let the
 * browser scroll the page with a vertical swipe (touch-action: pan-y). With two fingers,
 * `twoFingers` says whether their middle's movement drags too. */
export function onDrag(el, { start, move, click, pinch, twoFingers }) {
  const pointers = new Map(); // pointerId → [x, y]
  let last = null, moved = 0, engaged = false, spread = null, multi = false;
  const middle = () => {
    const [a, b] = [...pointers.values()];
    return { at: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2], spread: Math.hypot(a[0] - b[0], a[1] - b[1]) };
  };
  el.addEventListener("pointerdown", (e) => {
    if (e.pointerType === "mouse" && e.button !== 0) return;
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    try { el.setPointerCapture(e.pointerId); } catch (_) { /* already gone */ }
    if (pointers.size === 1) {
      last = [e.clientX, e.clientY]; moved = 0; multi = false;
      // A mouse or a pen drags at once; a finger once it has gone sideways.
      engaged = e.pointerType !== "touch";
      if (start) start(e);
    } else if (pointers.size === 2) {
      const m = middle();
      multi = true; engaged = true; last = m.at; spread = m.spread;
    }
  });
  el.addEventListener("pointermove", (e) => {
    if (!pointers.has(e.pointerId)) return;
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    if (pointers.size >= 2) {
      const m = middle();
      if (pinch && spread > 0 && m.spread > 0) pinch(m.spread / spread, e);
      if (twoFingers && move) move(m.at[0] - last[0], m.at[1] - last[1], e);
      last = m.at; spread = m.spread;
      return;
    }
    if (!last) return;
    const dx = e.clientX - last[0], dy = e.clientY - last[1];
    if (!engaged) {
      // A finger: wait until its way is clear (its move so far is dx, dy); a vertical swipe is
      // the browser's, which scrolls the page.
      moved = Math.hypot(dx, dy);
      if (moved < 8) return;
      if (Math.abs(dy) > Math.abs(dx)) { pointers.delete(e.pointerId); last = null; return; }
      engaged = true;
    }
    last = [e.clientX, e.clientY]; moved += Math.abs(dx) + Math.abs(dy);
    if (moved > 3) move(dx, dy, e);
  });
  const end = (e) => {
    if (!pointers.has(e.pointerId)) return;
    pointers.delete(e.pointerId);
    if (pointers.size === 0) {
      if (e.type === "pointerup" && last && !multi && (!engaged || moved <= 3) && click) click(e);
      last = null;
    } else if (pointers.size === 1) {
      // From two fingers back to one: it drags on from where it is, never clicks.
      last = [...pointers.values()][0];
    }
  };
  el.addEventListener("pointerup", end);
  el.addEventListener("pointercancel", end);
}
