// The resolution of the quick frames drawn while the input moves: the finest of a few scales
// whose engine time fits a budget, judged by the quick frames before. A frame twice finer has four
// times the pixels and the same image points: it takes less than four times as long, and is tried
// where that bound is within twice the budget.

/** Scales of the quick frames: that many times coarser along each side than the picture's box. */
export const QUICK_SCALES = [1, 2, 4];
/** The engine's time a quick frame may take (ms): a drag's latency is about two frames, since an
 * input waits for the frame being computed. */
export const QUICK_BUDGET_MS = 25;
/** A scale found too slow is tried again after this many quick frames (the time it took may have
 * been a moment's delay). */
export const QUICK_RETRY_FRAMES = 30;

/** The scale of the next quick frame, from the times of those before. */
export class QuickScale {
  constructor(scales = QUICK_SCALES, budgetMs = QUICK_BUDGET_MS, retryFrames = QUICK_RETRY_FRAMES) {
    Object.assign(this, { scales, budgetMs, retryFrames });
    /** Scale → { ms, frame }: the last quick frame's time at it and that frame's number. */
    this.timings = new Map();
    this.frames = 0;
  }

  /** The last time at `scale`, unless it was over budget long ago (then unknown again). */
  known(scale) {
    const t = this.timings.get(scale);
    if (t === undefined || (t.ms > this.budgetMs && this.frames - t.frame > this.retryFrames)) return undefined;
    return t.ms;
  }

  /** The finest scale whose last time fits the budget, or, untried, whose next coarser scale's
   * time four times over fits twice the budget; the coarsest before any frame is timed. */
  next() {
    for (const s of this.scales) {
      const ms = this.known(s);
      if (ms !== undefined) { if (ms <= this.budgetMs) return s; continue; }
      const coarser = this.known(2 * s);
      if (coarser !== undefined && 4 * coarser <= 2 * this.budgetMs) return s;
    }
    return this.scales.at(-1);
  }

  /** A quick frame at `scale` took `ms` in the engine. */
  timed(scale, ms) {
    this.timings.set(scale, { ms, frame: this.frames });
    this.frames += 1;
  }
}
