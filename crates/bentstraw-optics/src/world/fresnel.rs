//! How a Fresnel trace shares its light out: the one policy of the double-precision tracer (one
//! ray, depth first) and the packet tracer (eight branches at a time, breadth first).
//!
//! At each interface a branch of weight `w` splits into a reflected branch `w·R` (all of it under
//! total reflection) and a refracted one `w·(1 − R)`; a branch lighter than the pruning threshold
//! (or of no weight) is abandoned and reported as pruned, so that the weights told always add up
//! to the ray's; and each ray from the eye may follow at most so many straight segments, all its
//! branches together, after which what still travels is reported as dropped.

use crate::lanes::{Mask, Real};

/// The weights `(reflected, refracted)` of a branch of weight `w` meeting an interface of
/// reflectance `r` (all reflected where `total`).
#[inline(always)]
pub(crate) fn split<R: Real>(w: R, r: R, total: R::Mask) -> (R, R) {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    (
        R::select(total, w, w * r),
        R::select(total, zero, w * (one - r)),
    )
}

/// Whether a branch of weight `w` is followed: it has some weight, and at least `prune_below`.
#[inline(always)]
pub(crate) fn followed(w: f64, prune_below: f64) -> bool {
    w > 0.0 && w >= prune_below
}

/// [`followed`] for the lanes of single-precision weights `w`, given
/// `threshold = prune_threshold(prune_below)`: the same answer for each lane.
#[inline(always)]
pub(crate) fn followed_lanes<R: Real>(w: R, threshold: R) -> R::Mask {
    w.gt(R::splat(0.0)).and(w.ge(threshold))
}

/// The smallest `f32` at least `prune_below`: an `f32` weight is at least this exactly where, as
/// an `f64`, it is at least `prune_below` (which `f32` may not hold exactly, as 1e-4).
pub(crate) fn prune_threshold(prune_below: f64) -> f32 {
    let t = prune_below as f32;
    if (t as f64) < prune_below {
        t.next_up()
    } else {
        t
    }
}

/// The straight segments one ray from the eye may still follow, all its branches together.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegmentBudget {
    /// Segments followed so far (the first, from the eye, counts).
    used: u32,
    /// Most segments.
    max: u32,
}

impl SegmentBudget {
    /// A ray's budget of `max` segments, its first (from the eye) spent.
    #[inline(always)]
    pub fn new(max: u32) -> SegmentBudget {
        SegmentBudget { used: 1, max }
    }

    /// Takes one more segment, if any is left.
    #[inline(always)]
    pub fn spend(&mut self) -> bool {
        if self.used >= self.max {
            return false;
        }
        self.used += 1;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::{F8, LANES, M8};

    #[test]
    fn a_split_keeps_the_weight_and_total_reflection_keeps_it_all() {
        let (wr, wt) = split(0.8f64, 0.25, false);
        assert_eq!((wr, wt), (0.2, 0.6000000000000001));
        assert_eq!(split(0.8f64, 0.25, true), (0.8, 0.0));
        // Eight lanes: the same numbers in single precision, lane by lane.
        let mut total = M8::splat(false);
        total.0[3] = u32::MAX;
        let (r8, t8) = split(F8::splat(0.8), F8::splat(0.25), total);
        assert_eq!(r8.0[0], 0.8f32 * 0.25);
        assert_eq!(t8.0[0], 0.8f32 * (1.0 - 0.25));
        assert_eq!((r8.0[3], t8.0[3]), (0.8, 0.0));
    }

    #[test]
    fn weightless_and_light_branches_are_not_followed() {
        assert!(!followed(0.0, 0.0));
        assert!(!followed(0.5e-4, 1e-4));
        assert!(followed(1e-4, 1e-4));
    }

    /// The lanes' rule in single precision is the double-precision rule for every weight near
    /// the threshold, whether the threshold is an `f32` or not.
    #[test]
    fn the_lanes_follow_exactly_the_branches_one_ray_follows() {
        for prune in [0.0, 1e-4, 1e-3, 0.1, 0.25, 1e-7 / 3.0] {
            let threshold = F8::splat(0.0) + F8([prune_threshold(prune); LANES]);
            let mut w = (prune as f32).next_down().next_down();
            for _ in 0..4 {
                let lanes = F8(std::array::from_fn(|k| {
                    let mut x = w;
                    for _ in 0..k {
                        x = x.next_up();
                    }
                    x
                }));
                let kept = followed_lanes(lanes, threshold);
                for k in 0..LANES {
                    assert_eq!(
                        kept.lane(k),
                        followed(lanes.0[k] as f64, prune),
                        "weight {:e}, prune {prune:e}",
                        lanes.0[k]
                    );
                }
                w = lanes.0[LANES - 1].next_up();
            }
        }
    }

    #[test]
    fn a_budget_of_n_segments_follows_n() {
        let mut b = SegmentBudget::new(3);
        assert!(b.spend() && b.spend());
        assert!(!b.spend());
    }
}
