// The resolution of the quick frames drawn while the input moves: the finest of a few scales
// whose engine time fits a budget, judged by the quick frames before. A frame twice finer has four
// times the pixels and the same image points, so it takes at most four times as long.

/** Scales of the quick frames: that many times coarser along each side than the picture's box. */
export const QUICK_SCALES = [1, 2, 4];
/** The engine's time a quick frame may take (ms): a drag's latency is about two frames, since an
 * input waits for the frame being computed. */
export const QUICK_BUDGET_MS = 25;

/** The scale of the next quick frame, from the times of those before. */
export class QuickScale {
  constructor(scales = QUICK_SCALES, budgetMs = QUICK_BUDGET_MS) {
    this.scales = scales;
    this.budgetMs = budgetMs;
    /** Scale → the last quick frame's time at it (ms), or a bound on it. */
    this.ms = new Map();
  }

  /** The finest scale whose time, measured or bounded, fits the budget; the coarsest before any
   * frame is timed. */
  next() {
    return this.scales.find((s) => (this.ms.get(s) ?? Infinity) <= this.budgetMs) ?? this.scales.at(-1);
  }

  /** A quick frame at `scale` took `ms` in the engine; the next finer scale takes at most four
   * times that (a slow frame there before is taken as a moment's delay). */
  timed(scale, ms) {
    this.ms.set(scale, ms);
    const finer = scale / 2;
    if (this.scales.includes(finer)) this.ms.set(finer, Math.min(this.ms.get(finer) ?? Infinity, 4 * ms));
  }
}
