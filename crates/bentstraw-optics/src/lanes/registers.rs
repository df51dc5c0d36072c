//! What the packets held in registers share ([`super::avx::F8Avx`] and, in WebAssembly,
//! `super::simd128::F8Simd`): their values and their set lanes, read from a mask's bits.

use super::{Mask, Packet, PacketMask, LANES};

/// [`Real::values`](super::Real::values) of the packets held in registers: each whole number below `n` that the lanes
/// of `rest` hold, with its lanes. Few possible values (a scene's handful of surfaces): one
/// comparison each, until no lane is left. Many: from the lanes themselves, at most eight rounds.
///
/// A type with `#[inline(always)]` methods rather than a closure in `std::iter::from_fn`: a
/// closure's call may be compiled apart from the kernel, without its instruction set.
pub(super) struct RegisterValues<P: Packet> {
    pub(super) lanes: P,
    pub(super) rest: P::Mask,
    /// The next number to try, when `n` is small.
    pub(super) next: usize,
    pub(super) n: usize,
}

impl<P: Packet> Iterator for RegisterValues<P> {
    type Item = (usize, P::Mask);

    #[inline(always)]
    fn next(&mut self) -> Option<(usize, P::Mask)> {
        loop {
            let bits = self.rest.bits();
            if bits == 0 {
                return None;
            }
            if self.n <= LANES {
                if self.next >= self.n {
                    return None;
                }
                let k = self.next;
                self.next += 1;
                let m = self.rest.and(self.lanes.eq(P::splat(k as f64)));
                if m.any() {
                    self.rest = self.rest.and_not(m);
                    return Some((k, m));
                }
                continue;
            }
            let lane = bits.trailing_zeros() as usize;
            let v = self.lanes.to_array()[lane];
            let m = self.rest.and(self.lanes.eq(P::splat(f64::from(v))));
            // That lane is done even where it holds a NaN, which matches nothing.
            let mut only = [false; LANES];
            only[lane] = true;
            self.rest = self.rest.and_not(m).and_not(P::Mask::from_lanes(only));
            let k = v as usize;
            if k as f32 == v && k < self.n {
                return Some((k, m));
            }
        }
    }
}

/// [`PacketMask::lanes`] of the masks held in registers: the set bits of a bitmask, lowest
/// first.
pub(super) struct SetLanes(pub(super) u32);

impl Iterator for SetLanes {
    type Item = usize;

    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        let k = self.0.trailing_zeros();
        self.0 &= self.0.wrapping_sub(1);
        (k < 32).then_some(k as usize)
    }
}
