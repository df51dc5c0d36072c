//! Sixteen `f32` lanes in one AVX-512 register ([`F16Avx512`]), twice the rays of
//! [`F8Avx`](super::avx::F8Avx) per instruction, with the lane masks in a mask register, and
//! thirty-two in two ([`F32Avx512`]): the course pictures' numbers in the AVX-512 kernel.
//!
//! The operations are [`F8`](super::F8)'s, lane by lane, with the same IEEE results (no fused
//! multiply-add; `min`, `max` and comparisons treat NaN as the array form's `<` and `>` do), so
//! a ray's colour does not depend on how many rays are traced beside it, which a test checks.
//!
//! These types may only be used inside code compiled with AVX-512F enabled and entered after the
//! processor was found to have it: each operation executes an AVX-512 instruction.

use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

use super::{Constant, Mask, Real};

/// Rays per AVX-512 packet.
pub const WIDE_LANES: usize = 16;

/// Sixteen `f32`s, one per ray, in one AVX-512 register.
#[derive(Clone, Copy, Debug)]
pub struct F16Avx512(__m512);

/// Sixteen lane masks, one bit each (a mask register).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct M16Avx512(pub u16);

// SAFETY (every `unsafe` block below): the intrinsics need AVX-512F, which the kernel that uses
// these types has (module doc); the loads and stores are of exactly sixteen `f32`s.

macro_rules! lanewise {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for F16Avx512 {
            type Output = F16Avx512;
            #[inline(always)]
            fn $method(self, o: F16Avx512) -> F16Avx512 {
                F16Avx512(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}
lanewise!(Add, add, _mm512_add_ps);
lanewise!(Sub, sub, _mm512_sub_ps);
lanewise!(Mul, mul, _mm512_mul_ps);
lanewise!(Div, div, _mm512_div_ps);

impl Neg for F16Avx512 {
    type Output = F16Avx512;
    #[inline(always)]
    fn neg(self) -> F16Avx512 {
        // The sign bit flipped, as `-x` does (an integer xor: the float one needs AVX-512DQ).
        F16Avx512(unsafe {
            _mm512_castsi512_ps(_mm512_xor_si512(
                _mm512_castps_si512(self.0),
                _mm512_set1_epi32(i32::MIN),
            ))
        })
    }
}

macro_rules! compare {
    ($name:ident, $predicate:ident) => {
        #[inline(always)]
        fn $name(self, o: F16Avx512) -> M16Avx512 {
            // Ordered and quiet: false where either lane is NaN, as Rust's comparisons.
            M16Avx512(unsafe { _mm512_cmp_ps_mask::<$predicate>(self.0, o.0) })
        }
    };
}

impl F16Avx512 {
    /// Every lane `x`.
    #[inline(always)]
    pub fn splat32(x: f32) -> F16Avx512 {
        F16Avx512(unsafe { _mm512_set1_ps(x) })
    }

    /// The lanes `a`.
    #[inline(always)]
    pub fn from_array(a: [f32; WIDE_LANES]) -> F16Avx512 {
        F16Avx512(unsafe { _mm512_loadu_ps(a.as_ptr()) })
    }

    /// The lanes, as an array.
    #[inline(always)]
    pub fn to_array(self) -> [f32; WIDE_LANES] {
        let mut a = [0.0; WIDE_LANES];
        unsafe { _mm512_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }

    /// Each lane, a whole number in `0..=255`, as a byte (truncated, as `x as u8` is there).
    #[inline(always)]
    pub fn to_bytes(self) -> [u8; WIDE_LANES] {
        let mut b = [0u8; WIDE_LANES];
        unsafe {
            let bytes = _mm512_cvtepi32_epi8(_mm512_cvttps_epi32(self.0));
            _mm_storeu_si128(b.as_mut_ptr().cast(), bytes);
        }
        b
    }
}

impl Real for F16Avx512 {
    type Mask = M16Avx512;
    const LANES: usize = WIDE_LANES;
    const EXACT: bool = false;
    #[inline(always)]
    fn splat(x: f64) -> F16Avx512 {
        F16Avx512::splat32(x as f32)
    }
    #[inline(always)]
    fn constant(c: Constant) -> F16Avx512 {
        F16Avx512::splat32(c.f32)
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        self.to_array()[k] as f64
    }
    #[inline(always)]
    fn sqrt(self) -> F16Avx512 {
        F16Avx512(unsafe { _mm512_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn abs(self) -> F16Avx512 {
        F16Avx512(unsafe { _mm512_abs_ps(self.0) })
    }
    /// `o` where `self < o` is false (NaN or equal included), as the array form's.
    #[inline(always)]
    fn min(self, o: F16Avx512) -> F16Avx512 {
        F16Avx512(unsafe { _mm512_min_ps(self.0, o.0) })
    }
    /// `o` where `self > o` is false, as the array form's.
    #[inline(always)]
    fn max(self, o: F16Avx512) -> F16Avx512 {
        F16Avx512(unsafe { _mm512_max_ps(self.0, o.0) })
    }
    compare!(lt, _CMP_LT_OQ);
    compare!(le, _CMP_LE_OQ);
    compare!(gt, _CMP_GT_OQ);
    compare!(ge, _CMP_GE_OQ);
    compare!(eq, _CMP_EQ_OQ);
    #[inline(always)]
    fn select(m: M16Avx512, a: F16Avx512, b: F16Avx512) -> F16Avx512 {
        F16Avx512(unsafe { _mm512_mask_blend_ps(m.0, b.0, a.0) })
    }
    #[inline(always)]
    fn values(self, live: M16Avx512, n: usize) -> impl Iterator<Item = (usize, M16Avx512)> {
        Values {
            lanes: self,
            rest: live,
            next: 0,
            n,
        }
    }
    #[inline(always)]
    fn quotient(num: F16Avx512, _den: F16Avx512, inv_den: F16Avx512) -> F16Avx512 {
        num * inv_den
    }
}

impl Mask for M16Avx512 {
    #[inline(always)]
    fn splat(b: bool) -> M16Avx512 {
        M16Avx512(if b { u16::MAX } else { 0 })
    }
    #[inline(always)]
    fn and(self, o: M16Avx512) -> M16Avx512 {
        M16Avx512(self.0 & o.0)
    }
    #[inline(always)]
    fn or(self, o: M16Avx512) -> M16Avx512 {
        M16Avx512(self.0 | o.0)
    }
    #[inline(always)]
    fn and_not(self, o: M16Avx512) -> M16Avx512 {
        M16Avx512(self.0 & !o.0)
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.0 != 0
    }
    #[inline(always)]
    fn lane(self, k: usize) -> bool {
        self.0 >> k & 1 != 0
    }
}

// An iterator type with an `#[inline(always)]` method rather than a closure in
// `std::iter::from_fn`: a closure's call may be compiled apart from the kernel, without AVX-512.

/// [`F16Avx512::values`]: each whole number below `n` that the lanes of `rest` hold, with its
/// lanes.
struct Values {
    lanes: F16Avx512,
    rest: M16Avx512,
    /// The next number to try, when `n` is small.
    next: usize,
    n: usize,
}

impl Iterator for Values {
    type Item = (usize, M16Avx512);

    #[inline(always)]
    fn next(&mut self) -> Option<(usize, M16Avx512)> {
        // Few possible values (a scene's handful of surfaces): one comparison each, until no
        // lane is left. Many: from the lanes themselves, at most sixteen rounds.
        loop {
            if !self.rest.any() {
                return None;
            }
            if self.n <= WIDE_LANES {
                if self.next >= self.n {
                    return None;
                }
                let k = self.next;
                self.next += 1;
                let m = self.rest.and(self.lanes.eq(F16Avx512::splat32(k as f32)));
                if m.any() {
                    self.rest = self.rest.and_not(m);
                    return Some((k, m));
                }
                continue;
            }
            let lane = self.rest.0.trailing_zeros() as usize;
            let v = self.lanes.to_array()[lane];
            let m = self.rest.and(self.lanes.eq(F16Avx512::splat32(v)));
            // That lane is done even where it holds a NaN, which matches nothing.
            self.rest = self.rest.and_not(m).and_not(M16Avx512(1 << lane));
            let k = v as usize;
            if k as f32 == v && k < self.n {
                return Some((k, m));
            }
        }
    }
}

/// Thirty-two `f32`s, one per ray, in two AVX-512 registers: two packets of sixteen whose
/// instructions interleave, so that one's work fills the other's waits.
#[derive(Clone, Copy, Debug)]
pub struct F32Avx512(F16Avx512, F16Avx512);

/// Thirty-two lane masks, one bit each, as the two halves' masks (two mask registers: a mask
/// joined into one word would cost moves between mask and general registers at every step).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct M32Avx512(M16Avx512, M16Avx512);

impl M32Avx512 {
    /// The masks of the two halves.
    #[inline(always)]
    fn halves(self) -> (M16Avx512, M16Avx512) {
        (self.0, self.1)
    }

    /// The mask of the two halves `a`, `b`.
    #[inline(always)]
    fn join(a: M16Avx512, b: M16Avx512) -> M32Avx512 {
        M32Avx512(a, b)
    }

    /// Bit `k` set where lane `k` is.
    #[inline(always)]
    fn bits(self) -> u32 {
        self.0 .0 as u32 | (self.1 .0 as u32) << 16
    }

    /// The lanes of the bits `b`.
    #[inline(always)]
    fn from_bits(b: u32) -> M32Avx512 {
        M32Avx512(M16Avx512(b as u16), M16Avx512((b >> 16) as u16))
    }
}

macro_rules! pairwise {
    ($trait:ident, $method:ident) => {
        impl $trait for F32Avx512 {
            type Output = F32Avx512;
            #[inline(always)]
            fn $method(self, o: F32Avx512) -> F32Avx512 {
                F32Avx512(self.0.$method(o.0), self.1.$method(o.1))
            }
        }
    };
}
pairwise!(Add, add);
pairwise!(Sub, sub);
pairwise!(Mul, mul);
pairwise!(Div, div);

impl Neg for F32Avx512 {
    type Output = F32Avx512;
    #[inline(always)]
    fn neg(self) -> F32Avx512 {
        F32Avx512(-self.0, -self.1)
    }
}

macro_rules! compare_pair {
    ($name:ident) => {
        #[inline(always)]
        fn $name(self, o: F32Avx512) -> M32Avx512 {
            M32Avx512::join(self.0.$name(o.0), self.1.$name(o.1))
        }
    };
}

impl Real for F32Avx512 {
    type Mask = M32Avx512;
    const LANES: usize = 2 * WIDE_LANES;
    const EXACT: bool = false;
    #[inline(always)]
    fn splat(x: f64) -> F32Avx512 {
        let h = F16Avx512::splat(x);
        F32Avx512(h, h)
    }
    #[inline(always)]
    fn constant(c: Constant) -> F32Avx512 {
        let h = F16Avx512::constant(c);
        F32Avx512(h, h)
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        if k < WIDE_LANES {
            self.0.lane(k)
        } else {
            self.1.lane(k - WIDE_LANES)
        }
    }
    #[inline(always)]
    fn sqrt(self) -> F32Avx512 {
        F32Avx512(self.0.sqrt(), self.1.sqrt())
    }
    #[inline(always)]
    fn abs(self) -> F32Avx512 {
        F32Avx512(self.0.abs(), self.1.abs())
    }
    #[inline(always)]
    fn min(self, o: F32Avx512) -> F32Avx512 {
        F32Avx512(self.0.min(o.0), self.1.min(o.1))
    }
    #[inline(always)]
    fn max(self, o: F32Avx512) -> F32Avx512 {
        F32Avx512(self.0.max(o.0), self.1.max(o.1))
    }
    compare_pair!(lt);
    compare_pair!(le);
    compare_pair!(gt);
    compare_pair!(ge);
    compare_pair!(eq);
    #[inline(always)]
    fn select(m: M32Avx512, a: F32Avx512, b: F32Avx512) -> F32Avx512 {
        let (m0, m1) = m.halves();
        F32Avx512(
            F16Avx512::select(m0, a.0, b.0),
            F16Avx512::select(m1, a.1, b.1),
        )
    }
    #[inline(always)]
    fn values(self, live: M32Avx512, n: usize) -> impl Iterator<Item = (usize, M32Avx512)> {
        PairValues {
            lanes: self,
            rest: live,
            next: 0,
            n,
        }
    }
    #[inline(always)]
    fn quotient(num: F32Avx512, _den: F32Avx512, inv_den: F32Avx512) -> F32Avx512 {
        num * inv_den
    }
}

impl Mask for M32Avx512 {
    #[inline(always)]
    fn splat(b: bool) -> M32Avx512 {
        M32Avx512(M16Avx512::splat(b), M16Avx512::splat(b))
    }
    #[inline(always)]
    fn and(self, o: M32Avx512) -> M32Avx512 {
        M32Avx512(self.0.and(o.0), self.1.and(o.1))
    }
    #[inline(always)]
    fn or(self, o: M32Avx512) -> M32Avx512 {
        M32Avx512(self.0.or(o.0), self.1.or(o.1))
    }
    #[inline(always)]
    fn and_not(self, o: M32Avx512) -> M32Avx512 {
        M32Avx512(self.0.and_not(o.0), self.1.and_not(o.1))
    }
    #[inline(always)]
    fn any(self) -> bool {
        (self.0 .0 | self.1 .0) != 0
    }
    #[inline(always)]
    fn lane(self, k: usize) -> bool {
        self.bits() >> k & 1 != 0
    }
}

/// [`F32Avx512::values`], as [`Values`] for thirty-two lanes.
struct PairValues {
    lanes: F32Avx512,
    rest: M32Avx512,
    next: usize,
    n: usize,
}

impl Iterator for PairValues {
    type Item = (usize, M32Avx512);

    #[inline(always)]
    fn next(&mut self) -> Option<(usize, M32Avx512)> {
        loop {
            if !self.rest.any() {
                return None;
            }
            if self.n <= 2 * WIDE_LANES {
                if self.next >= self.n {
                    return None;
                }
                let k = self.next;
                self.next += 1;
                let m = self.rest.and(self.lanes.eq(F32Avx512::splat(k as f64)));
                if m.any() {
                    self.rest = self.rest.and_not(m);
                    return Some((k, m));
                }
                continue;
            }
            let lane = self.rest.bits().trailing_zeros() as usize;
            let v = self.lanes.lane(lane) as f32;
            let m = self.rest.and(self.lanes.eq(F32Avx512::splat(v as f64)));
            // That lane is done even where it holds a NaN, which matches nothing.
            self.rest = self
                .rest
                .and_not(m)
                .and_not(M32Avx512::from_bits(1 << lane));
            let k = v as usize;
            if k as f32 == v && k < self.n {
                return Some((k, m));
            }
        }
    }
}

/// The course rows' wide numbers ([`F16Avx512`], [`F32Avx512`]): how a row's rays are made
/// and their codes stored.
pub trait Wide: Real {
    /// Every lane `x`.
    fn splat32(x: f32) -> Self;
    /// Each lane its own index, `0, 1, 2, …`.
    fn index() -> Self;
    /// The first `out.len()` lanes, whole numbers in `0..=255`, as bytes (truncated, as
    /// `x as u8` is there).
    fn store_bytes(self, out: &mut [u8]);
}

impl Wide for F16Avx512 {
    #[inline(always)]
    fn splat32(x: f32) -> F16Avx512 {
        F16Avx512::splat32(x)
    }
    #[inline(always)]
    fn index() -> F16Avx512 {
        F16Avx512::from_array(std::array::from_fn(|k| k as f32))
    }
    #[inline(always)]
    fn store_bytes(self, out: &mut [u8]) {
        out.copy_from_slice(&self.to_bytes()[..out.len()]);
    }
}

impl Wide for F32Avx512 {
    #[inline(always)]
    fn splat32(x: f32) -> F32Avx512 {
        let h = F16Avx512::splat32(x);
        F32Avx512(h, h)
    }
    #[inline(always)]
    fn index() -> F32Avx512 {
        F32Avx512(
            F16Avx512::from_array(std::array::from_fn(|k| k as f32)),
            F16Avx512::from_array(std::array::from_fn(|k| (k + WIDE_LANES) as f32)),
        )
    }
    #[inline(always)]
    fn store_bytes(self, out: &mut [u8]) {
        let (a, b) = out.split_at_mut(out.len().min(WIDE_LANES));
        a.copy_from_slice(&self.0.to_bytes()[..a.len()]);
        b.copy_from_slice(&self.1.to_bytes()[..b.len()]);
    }
}
