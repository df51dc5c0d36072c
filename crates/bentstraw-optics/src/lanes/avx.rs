//! Eight `f32` lanes in one AVX register: the packet tracer's numbers in the x86-64 kernels.
//!
//! Each operation is one AVX instruction, written out, where [`F8`](super::F8)'s array form
//! leaves the choice of instructions to the compiler's vectoriser (which, depending on the code
//! around it, sometimes splits a packet into two 4-wide halves or single lanes). The operations
//! are the array form's, with the same IEEE results lane by lane (no fused multiply-add; `min`,
//! `max` and comparisons treat NaN as the array form's `<` and `>` do), so both give the same
//! pixels, which a test checks.
//!
//! These types may only be used inside code compiled with AVX enabled and entered after the
//! processor was found to have AVX2 (the packet tracer's kernels): each operation executes an AVX
//! instruction.

use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

use super::{Constant, Mask, Packet, PacketMask, Real, RegisterValues, SetLanes, LANES};

/// Eight `f32`s, one per ray, in one AVX register.
#[derive(Clone, Copy, Debug)]
pub struct F8Avx(__m256);

/// Eight lane masks in one AVX register (all bits set = true).
#[derive(Clone, Copy, Debug)]
pub struct M8Avx(__m256);

// SAFETY (every `unsafe` block below): the intrinsics need AVX, which the kernels that use these
// types have (module doc); the loads and stores are of exactly eight `f32`s.

macro_rules! lanewise {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for F8Avx {
            type Output = F8Avx;
            #[inline(always)]
            fn $method(self, o: F8Avx) -> F8Avx {
                F8Avx(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}
lanewise!(Add, add, _mm256_add_ps);
lanewise!(Sub, sub, _mm256_sub_ps);
lanewise!(Mul, mul, _mm256_mul_ps);
lanewise!(Div, div, _mm256_div_ps);

impl Neg for F8Avx {
    type Output = F8Avx;
    #[inline(always)]
    fn neg(self) -> F8Avx {
        // The sign bit flipped, as `-x` does.
        F8Avx(unsafe { _mm256_xor_ps(self.0, _mm256_set1_ps(-0.0)) })
    }
}

macro_rules! compare {
    ($name:ident, $predicate:ident) => {
        #[inline(always)]
        fn $name(self, o: F8Avx) -> M8Avx {
            // Ordered and quiet: false where either lane is NaN, as Rust's comparisons.
            M8Avx(unsafe { _mm256_cmp_ps::<$predicate>(self.0, o.0) })
        }
    };
}

impl F8Avx {
    /// Every lane `x`.
    #[inline(always)]
    fn splat32(x: f32) -> F8Avx {
        F8Avx(unsafe { _mm256_set1_ps(x) })
    }
}

impl Real for F8Avx {
    type Mask = M8Avx;
    const LANES: usize = LANES;
    const EXACT: bool = false;
    #[inline(always)]
    fn splat(x: f64) -> F8Avx {
        F8Avx::splat32(x as f32)
    }
    #[inline(always)]
    fn constant(c: Constant) -> F8Avx {
        F8Avx::splat32(c.f32)
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        self.to_array()[k] as f64
    }
    #[inline(always)]
    fn sqrt(self) -> F8Avx {
        F8Avx(unsafe { _mm256_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn abs(self) -> F8Avx {
        F8Avx(unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0) })
    }
    /// `o` where `self < o` is false (NaN or equal included), as the array form's.
    #[inline(always)]
    fn min(self, o: F8Avx) -> F8Avx {
        F8Avx(unsafe { _mm256_min_ps(self.0, o.0) })
    }
    /// `o` where `self > o` is false, as the array form's.
    #[inline(always)]
    fn max(self, o: F8Avx) -> F8Avx {
        F8Avx(unsafe { _mm256_max_ps(self.0, o.0) })
    }
    compare!(lt, _CMP_LT_OQ);
    compare!(le, _CMP_LE_OQ);
    compare!(gt, _CMP_GT_OQ);
    compare!(ge, _CMP_GE_OQ);
    compare!(eq, _CMP_EQ_OQ);
    #[inline(always)]
    fn select(m: M8Avx, a: F8Avx, b: F8Avx) -> F8Avx {
        F8Avx(unsafe { _mm256_blendv_ps(b.0, a.0, m.0) })
    }
    #[inline(always)]
    fn values(self, live: M8Avx, n: usize) -> impl Iterator<Item = (usize, M8Avx)> {
        RegisterValues {
            lanes: self,
            rest: live,
            next: 0,
            n,
        }
    }
    #[inline(always)]
    fn quotient(num: F8Avx, _den: F8Avx, inv_den: F8Avx) -> F8Avx {
        num * inv_den
    }
}

impl Packet for F8Avx {
    #[inline(always)]
    fn from_array(a: [f32; LANES]) -> F8Avx {
        F8Avx(unsafe { _mm256_loadu_ps(a.as_ptr()) })
    }
    #[inline(always)]
    fn to_array(self) -> [f32; LANES] {
        let mut a = [0.0; LANES];
        unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
}

impl Mask for M8Avx {
    #[inline(always)]
    fn splat(b: bool) -> M8Avx {
        M8Avx(unsafe {
            if b {
                _mm256_castsi256_ps(_mm256_set1_epi32(-1))
            } else {
                _mm256_setzero_ps()
            }
        })
    }
    #[inline(always)]
    fn and(self, o: M8Avx) -> M8Avx {
        M8Avx(unsafe { _mm256_and_ps(self.0, o.0) })
    }
    #[inline(always)]
    fn or(self, o: M8Avx) -> M8Avx {
        M8Avx(unsafe { _mm256_or_ps(self.0, o.0) })
    }
    #[inline(always)]
    fn and_not(self, o: M8Avx) -> M8Avx {
        M8Avx(unsafe { _mm256_andnot_ps(o.0, self.0) })
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.bits() != 0
    }
    #[inline(always)]
    fn lane(self, k: usize) -> bool {
        self.bits() >> k & 1 != 0
    }
    #[inline(always)]
    fn select_mask(m: M8Avx, a: M8Avx, b: M8Avx) -> M8Avx {
        M8Avx(unsafe { _mm256_blendv_ps(b.0, a.0, m.0) })
    }
}

impl PacketMask for M8Avx {
    #[inline(always)]
    fn first(n: usize) -> M8Avx {
        let index = F8Avx::from_array(std::array::from_fn(|k| k as f32));
        index.lt(F8Avx::splat32(n.min(LANES) as f32))
    }
    #[inline(always)]
    fn from_lanes(set: [bool; LANES]) -> M8Avx {
        let bits: [i32; LANES] = set.map(|b| -(b as i32));
        M8Avx(unsafe { _mm256_castsi256_ps(_mm256_loadu_si256(bits.as_ptr().cast())) })
    }
    #[inline(always)]
    fn lanes(self) -> impl Iterator<Item = usize> {
        SetLanes(self.bits())
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        unsafe { _mm256_movemask_ps(self.0) as u32 }
    }
}
