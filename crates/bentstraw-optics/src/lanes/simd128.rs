//! Eight `f32` lanes in two WebAssembly SIMD registers: the packet tracer's numbers in the page.
//!
//! WebAssembly's vectors are four lanes wide, so a packet is two of them, and each operation is
//! two instructions, written out, where [`F8`](super::F8)'s array form leaves the choice to the
//! compiler's vectoriser (with which the page traced a quarter to a third fewer rays per
//! second). The operations are the array form's, with the same IEEE results lane by lane (no
//! fused multiply-add; `min` and `max` are the "pseudo" minimum and maximum, which are exactly
//! the array form's `<` and `>` choices, NaN included), so both give the same pixels, which a
//! test checks.
//!
//! Only compiled for `wasm32` with the `simd128` feature on (the site's build), where every
//! instruction used here exists.

use std::arch::wasm32::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

use super::{Constant, Mask, Packet, PacketMask, Real, RegisterValues, SetLanes, LANES};

/// Eight `f32`s, one per ray: lanes 0–3 in the first register, 4–7 in the second.
#[derive(Clone, Copy, Debug)]
pub struct F8Simd(v128, v128);

/// Eight lane masks, as [`F8Simd`]'s lanes (all bits set = true).
#[derive(Clone, Copy, Debug)]
pub struct M8Simd(v128, v128);

macro_rules! lanewise {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for F8Simd {
            type Output = F8Simd;
            #[inline(always)]
            fn $method(self, o: F8Simd) -> F8Simd {
                F8Simd($intrinsic(self.0, o.0), $intrinsic(self.1, o.1))
            }
        }
    };
}
lanewise!(Add, add, f32x4_add);
lanewise!(Sub, sub, f32x4_sub);
lanewise!(Mul, mul, f32x4_mul);
lanewise!(Div, div, f32x4_div);

impl Neg for F8Simd {
    type Output = F8Simd;
    #[inline(always)]
    fn neg(self) -> F8Simd {
        // The sign bit flipped, as `-x` does.
        F8Simd(f32x4_neg(self.0), f32x4_neg(self.1))
    }
}

macro_rules! compare {
    ($name:ident, $intrinsic:ident) => {
        #[inline(always)]
        fn $name(self, o: F8Simd) -> M8Simd {
            // False where either lane is NaN, as Rust's comparisons.
            M8Simd($intrinsic(self.0, o.0), $intrinsic(self.1, o.1))
        }
    };
}

impl F8Simd {
    /// Every lane `x`.
    #[inline(always)]
    fn splat32(x: f32) -> F8Simd {
        let v = f32x4_splat(x);
        F8Simd(v, v)
    }
}

impl Real for F8Simd {
    type Mask = M8Simd;
    const LANES: usize = LANES;
    const EXACT: bool = false;
    #[inline(always)]
    fn splat(x: f64) -> F8Simd {
        F8Simd::splat32(x as f32)
    }
    #[inline(always)]
    fn constant(c: Constant) -> F8Simd {
        F8Simd::splat32(c.f32)
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        self.to_array()[k] as f64
    }
    #[inline(always)]
    fn sqrt(self) -> F8Simd {
        F8Simd(f32x4_sqrt(self.0), f32x4_sqrt(self.1))
    }
    #[inline(always)]
    fn abs(self) -> F8Simd {
        F8Simd(f32x4_abs(self.0), f32x4_abs(self.1))
    }
    /// `self < o ? self : o`, as the array form's (`pmin(a, b)` is `b < a ? b : a`).
    #[inline(always)]
    fn min(self, o: F8Simd) -> F8Simd {
        F8Simd(f32x4_pmin(o.0, self.0), f32x4_pmin(o.1, self.1))
    }
    /// `self > o ? self : o`, as the array form's (`pmax(a, b)` is `a < b ? b : a`).
    #[inline(always)]
    fn max(self, o: F8Simd) -> F8Simd {
        F8Simd(f32x4_pmax(o.0, self.0), f32x4_pmax(o.1, self.1))
    }
    compare!(lt, f32x4_lt);
    compare!(le, f32x4_le);
    compare!(gt, f32x4_gt);
    compare!(ge, f32x4_ge);
    compare!(eq, f32x4_eq);
    #[inline(always)]
    fn select(m: M8Simd, a: F8Simd, b: F8Simd) -> F8Simd {
        F8Simd(v128_bitselect(a.0, b.0, m.0), v128_bitselect(a.1, b.1, m.1))
    }
    #[inline(always)]
    fn values(self, live: M8Simd, n: usize) -> impl Iterator<Item = (usize, M8Simd)> {
        RegisterValues {
            lanes: self,
            rest: live,
            next: 0,
            n,
        }
    }
    #[inline(always)]
    fn quotient(num: F8Simd, _den: F8Simd, inv_den: F8Simd) -> F8Simd {
        num * inv_den
    }
}

impl Packet for F8Simd {
    #[inline(always)]
    fn from_array(a: [f32; LANES]) -> F8Simd {
        F8Simd(f32x4(a[0], a[1], a[2], a[3]), f32x4(a[4], a[5], a[6], a[7]))
    }
    #[inline(always)]
    fn to_array(self) -> [f32; LANES] {
        let (a, b) = (self.0, self.1);
        [
            f32x4_extract_lane::<0>(a),
            f32x4_extract_lane::<1>(a),
            f32x4_extract_lane::<2>(a),
            f32x4_extract_lane::<3>(a),
            f32x4_extract_lane::<0>(b),
            f32x4_extract_lane::<1>(b),
            f32x4_extract_lane::<2>(b),
            f32x4_extract_lane::<3>(b),
        ]
    }
}

impl Mask for M8Simd {
    #[inline(always)]
    fn splat(b: bool) -> M8Simd {
        let v = i32x4_splat(-(b as i32));
        M8Simd(v, v)
    }
    #[inline(always)]
    fn and(self, o: M8Simd) -> M8Simd {
        M8Simd(v128_and(self.0, o.0), v128_and(self.1, o.1))
    }
    #[inline(always)]
    fn or(self, o: M8Simd) -> M8Simd {
        M8Simd(v128_or(self.0, o.0), v128_or(self.1, o.1))
    }
    #[inline(always)]
    fn and_not(self, o: M8Simd) -> M8Simd {
        M8Simd(v128_andnot(self.0, o.0), v128_andnot(self.1, o.1))
    }
    #[inline(always)]
    fn any(self) -> bool {
        v128_any_true(v128_or(self.0, self.1))
    }
    #[inline(always)]
    fn lane(self, k: usize) -> bool {
        self.bits() >> k & 1 != 0
    }
    #[inline(always)]
    fn select_mask(m: M8Simd, a: M8Simd, b: M8Simd) -> M8Simd {
        M8Simd(v128_bitselect(a.0, b.0, m.0), v128_bitselect(a.1, b.1, m.1))
    }
}

impl PacketMask for M8Simd {
    #[inline(always)]
    fn first(n: usize) -> M8Simd {
        let index = F8Simd::from_array(std::array::from_fn(|k| k as f32));
        index.lt(F8Simd::splat32(n.min(LANES) as f32))
    }
    #[inline(always)]
    fn from_lanes(set: [bool; LANES]) -> M8Simd {
        let b = set.map(|b| -(b as i32));
        M8Simd(i32x4(b[0], b[1], b[2], b[3]), i32x4(b[4], b[5], b[6], b[7]))
    }
    #[inline(always)]
    fn lanes(self) -> impl Iterator<Item = usize> {
        SetLanes(self.bits())
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        u32::from(i32x4_bitmask(self.0)) | u32::from(i32x4_bitmask(self.1)) << 4
    }
}
