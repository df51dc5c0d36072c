//! Numbers one ray at a time or eight at a time.
//!
//! The tracer's rules (which surface a ray meets first, how it bends there) are written once,
//! over [`Real`], and compiled twice: for `f64`, one ray in double precision (image points, the
//! raw data, every test's reference), and for [`F8`], eight rays side by side in single precision
//! (pictures), where each step maps onto one 8-wide SIMD instruction. A [`Mask`] says which lanes
//! a step applies to: `bool` for one ray, [`M8`] for eight. Work that no lane needs is skipped
//! (`if !mask.any()`), which for one ray is an ordinary branch.
//!
//! The eight lanes have three forms ([`Packet`]): an array ([`F8`]), which any target compiles;
//! on x86-64, one AVX register ([`avx::F8Avx`]) whose every operation is one instruction, for the
//! kernels chosen when the processor has AVX2; and in WebAssembly with SIMD (the page), two
//! 4-lane registers (`simd128::F8Simd`, the [`BaselinePacket`] there). The register forms are
//! explicit, so that no change elsewhere can make the compiler split the packets into narrower
//! vectors or single lanes. With AVX-512, course pictures take thirty-two lanes in two registers
//! ([`avx512::F32Avx512`]), a [`Real`] of its own.
//!
//! All instances perform the same operations in the same order, with two exceptions, the places
//! where the two precisions are meant to differ: [`Real::quotient`] divides in double precision
//! and multiplies by a reciprocal computed once in the packets, and a vector that is unit to
//! rounding is made unit again only in double precision ([`V3::renormalize`]).

use std::ops::{Add, Div, Mul, Neg, Sub};

#[cfg(target_arch = "x86_64")]
pub mod avx;
#[cfg(target_arch = "x86_64")]
pub mod avx512;
#[cfg(any(
    target_arch = "x86_64",
    all(target_arch = "wasm32", target_feature = "simd128")
))]
mod registers;
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
pub mod simd128;
#[cfg(any(
    target_arch = "x86_64",
    all(target_arch = "wasm32", target_feature = "simd128")
))]
use registers::{RegisterValues, SetLanes};

/// The packets' form on the baseline instruction set: two WebAssembly SIMD registers where the
/// target has them (the page), else the array.
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
pub type BaselinePacket = simd128::F8Simd;
/// The packets' form on the baseline instruction set: two WebAssembly SIMD registers where the
/// target has them (the page), else the array.
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
pub type BaselinePacket = F8;

/// Which lanes of a [`Real`] a step applies to.
pub trait Mask: Copy {
    /// Every lane `b`.
    fn splat(b: bool) -> Self;
    /// Lanes set in both.
    fn and(self, o: Self) -> Self;
    /// Lanes set in either.
    fn or(self, o: Self) -> Self;
    /// Lanes set in `self` but not in `o`.
    fn and_not(self, o: Self) -> Self;
    /// Whether any lane is set.
    fn any(self) -> bool;
    /// Whether lane `k` is set.
    fn lane(self, k: usize) -> bool;
    /// `a`'s lanes where `m` is set, `b`'s elsewhere.
    #[inline(always)]
    fn select_mask(m: Self, a: Self, b: Self) -> Self {
        m.and(a).or(b.and_not(m))
    }
}

/// A number of the scene in both precisions, rounded to `f32` once (when the world is built)
/// rather than at every step of the packets.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Constant {
    /// The number.
    pub f64: f64,
    /// It rounded to single precision.
    pub f32: f32,
}

impl Constant {
    /// `x` in both precisions.
    pub fn new(x: f64) -> Constant {
        Constant {
            f64: x,
            f32: x as f32,
        }
    }
}

/// A number of the tracer: `f64` (one lane) or [`F8`] (eight `f32` lanes).
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Its lane mask.
    type Mask: Mask;
    /// How many rays it holds.
    const LANES: usize;
    /// Whether this is the precision of record (double: image points, raw data), which makes
    /// every unit vector unit again after it is computed; the single-precision packets keep the
    /// ones that are unit to rounding as they are (the drift over a few events, ~1e-7, is far
    /// below what changes a pixel).
    const EXACT: bool;
    /// Every lane `x` (rounded to the lanes' precision).
    fn splat(x: f64) -> Self;
    /// Every lane `c`, in the lanes' precision (the same as [`Real::splat`] of `c.f64`).
    fn constant(c: Constant) -> Self;
    /// Lane `k`, as an `f64`.
    fn lane(self, k: usize) -> f64;
    /// The square root of each lane.
    fn sqrt(self) -> Self;
    /// The absolute value of each lane.
    fn abs(self) -> Self;
    /// The smaller of each pair of lanes.
    fn min(self, o: Self) -> Self;
    /// The larger of each pair of lanes.
    fn max(self, o: Self) -> Self;
    /// `self < o`, lane by lane.
    fn lt(self, o: Self) -> Self::Mask;
    /// `self <= o`, lane by lane.
    fn le(self, o: Self) -> Self::Mask;
    /// `self > o`, lane by lane.
    fn gt(self, o: Self) -> Self::Mask;
    /// `self >= o`, lane by lane.
    fn ge(self, o: Self) -> Self::Mask;
    /// `self == o`, lane by lane.
    fn eq(self, o: Self) -> Self::Mask;
    /// `a` in the lanes of `m`, `b` in the others.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Each whole number `k < n` that a lane of `live` holds, with those lanes: for one ray, its
    /// own value (so the lanes are known to be set); for eight, each value some of them share.
    fn values(self, live: Self::Mask, n: usize) -> impl Iterator<Item = (usize, Self::Mask)>;
    /// `num / den`, where `inv_den = 1 / den` is at hand: divided in double precision (exactly
    /// rounded), multiplied by the reciprocal in the single-precision packets (a division per ray
    /// instead of one per surface).
    fn quotient(num: Self, den: Self, inv_den: Self) -> Self;
}

impl Mask for bool {
    #[inline(always)]
    fn splat(b: bool) -> bool {
        b
    }
    #[inline(always)]
    fn and(self, o: bool) -> bool {
        self & o
    }
    #[inline(always)]
    fn or(self, o: bool) -> bool {
        self | o
    }
    #[inline(always)]
    fn and_not(self, o: bool) -> bool {
        self & !o
    }
    #[inline(always)]
    fn any(self) -> bool {
        self
    }
    #[inline(always)]
    fn lane(self, _: usize) -> bool {
        self
    }
}

impl Real for f64 {
    type Mask = bool;
    const LANES: usize = 1;
    const EXACT: bool = true;
    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn constant(c: Constant) -> f64 {
        c.f64
    }
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn min(self, o: f64) -> f64 {
        f64::min(self, o)
    }
    #[inline(always)]
    fn max(self, o: f64) -> f64 {
        f64::max(self, o)
    }
    #[inline(always)]
    fn lt(self, o: f64) -> bool {
        self < o
    }
    #[inline(always)]
    fn le(self, o: f64) -> bool {
        self <= o
    }
    #[inline(always)]
    fn gt(self, o: f64) -> bool {
        self > o
    }
    #[inline(always)]
    fn ge(self, o: f64) -> bool {
        self >= o
    }
    #[inline(always)]
    fn eq(self, o: f64) -> bool {
        self == o
    }
    #[inline(always)]
    fn select(m: bool, a: f64, b: f64) -> f64 {
        if m {
            a
        } else {
            b
        }
    }
    #[inline(always)]
    fn values(self, live: bool, n: usize) -> impl Iterator<Item = (usize, bool)> {
        let k = self as usize;
        (live && k < n).then_some((k, true)).into_iter()
    }
    #[inline(always)]
    fn quotient(num: f64, den: f64, _inv_den: f64) -> f64 {
        num / den
    }
}

/// Rays per packet.
pub const LANES: usize = 8;

/// Eight `f32`s, one per ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct F8(pub [f32; LANES]);

/// Eight lane masks (all bits set = true).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct M8(pub [u32; LANES]);

macro_rules! lanewise {
    ($trait:ident, $method:ident, $op:tt) => {
        impl $trait for F8 {
            type Output = F8;
            #[inline(always)]
            fn $method(self, o: F8) -> F8 {
                F8(std::array::from_fn(|k| self.0[k] $op o.0[k]))
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);
lanewise!(Div, div, /);

impl Neg for F8 {
    type Output = F8;
    #[inline(always)]
    fn neg(self) -> F8 {
        F8(self.0.map(|x| -x))
    }
}

macro_rules! compare {
    ($name:ident, $op:tt) => {
        #[inline(always)]
        fn $name(self, o: F8) -> M8 {
            M8(std::array::from_fn(|k| if self.0[k] $op o.0[k] { u32::MAX } else { 0 }))
        }
    };
}

impl Real for F8 {
    type Mask = M8;
    const LANES: usize = LANES;
    const EXACT: bool = false;
    #[inline(always)]
    fn splat(x: f64) -> F8 {
        F8([x as f32; LANES])
    }
    #[inline(always)]
    fn constant(c: Constant) -> F8 {
        F8([c.f32; LANES])
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        self.0[k] as f64
    }
    #[inline(always)]
    fn sqrt(self) -> F8 {
        F8(self.0.map(f32::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> F8 {
        F8(self.0.map(f32::abs))
    }
    #[inline(always)]
    fn min(self, o: F8) -> F8 {
        F8(std::array::from_fn(|k| {
            if self.0[k] < o.0[k] {
                self.0[k]
            } else {
                o.0[k]
            }
        }))
    }
    #[inline(always)]
    fn max(self, o: F8) -> F8 {
        F8(std::array::from_fn(|k| {
            if self.0[k] > o.0[k] {
                self.0[k]
            } else {
                o.0[k]
            }
        }))
    }
    compare!(lt, <);
    compare!(le, <=);
    compare!(gt, >);
    compare!(ge, >=);
    compare!(eq, ==);
    #[inline(always)]
    fn select(m: M8, a: F8, b: F8) -> F8 {
        F8(std::array::from_fn(|k| {
            f32::from_bits((a.0[k].to_bits() & m.0[k]) | (b.0[k].to_bits() & !m.0[k]))
        }))
    }
    #[inline(always)]
    fn values(self, live: M8, n: usize) -> impl Iterator<Item = (usize, M8)> {
        // From the lanes themselves, not by trying every k below n: at most eight rounds (most
        // packets hold one value), however many surfaces or objects the scene has.
        let mut rest = live;
        std::iter::from_fn(move || loop {
            let lane = (0..LANES).find(|&k| rest.0[k] != 0)?;
            let v = self.0[lane];
            let m = rest.and(self.eq(F8(std::array::from_fn(|_| v))));
            rest = rest.and_not(m);
            rest.0[lane] = 0; // a NaN matches nothing, not even itself
            let k = v as usize;
            if k as f32 == v && k < n {
                return Some((k, m));
            }
        })
    }
    #[inline(always)]
    fn quotient(num: F8, _den: F8, inv_den: F8) -> F8 {
        num * inv_den
    }
}

impl Mask for M8 {
    #[inline(always)]
    fn splat(b: bool) -> M8 {
        M8([if b { u32::MAX } else { 0 }; LANES])
    }
    #[inline(always)]
    fn and(self, o: M8) -> M8 {
        M8(std::array::from_fn(|k| self.0[k] & o.0[k]))
    }
    #[inline(always)]
    fn or(self, o: M8) -> M8 {
        M8(std::array::from_fn(|k| self.0[k] | o.0[k]))
    }
    #[inline(always)]
    fn and_not(self, o: M8) -> M8 {
        M8(std::array::from_fn(|k| self.0[k] & !o.0[k]))
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.0.iter().fold(0, |a, &b| a | b) != 0
    }
    #[inline(always)]
    fn lane(self, k: usize) -> bool {
        self.0[k] != 0
    }
}

/// The packet tracer's lane masks: [`M8`] or, in registers, [`avx::M8Avx`] (x86-64 kernels) and
/// `simd128::M8Simd` (WebAssembly).
pub trait PacketMask: Mask {
    /// The first `n` lanes set.
    fn first(n: usize) -> Self;
    /// The lanes `set` says.
    fn from_lanes(set: [bool; LANES]) -> Self;
    /// The lanes set, in order.
    fn lanes(self) -> impl Iterator<Item = usize>;
    /// Bit `k` set where lane `k` is.
    fn bits(self) -> u32;
}

/// The packet tracer's numbers: eight single-precision lanes, held as an array ([`F8`], for any
/// target) or in one AVX register ([`avx::F8Avx`], for the x86-64 kernels). Both do the same
/// IEEE operations in the same order, so they give the same pixels.
pub trait Packet: Real<Mask: PacketMask> {
    /// The lanes `a`.
    fn from_array(a: [f32; LANES]) -> Self;
    /// The lanes, as an array.
    fn to_array(self) -> [f32; LANES];
}

impl PacketMask for M8 {
    #[inline(always)]
    fn first(n: usize) -> M8 {
        M8(std::array::from_fn(|k| if k < n { u32::MAX } else { 0 }))
    }
    #[inline(always)]
    fn from_lanes(set: [bool; LANES]) -> M8 {
        M8(set.map(|b| if b { u32::MAX } else { 0 }))
    }
    /// A test per lane (iterating the set bits of a movemask instead made the compiler split
    /// the array lanes' arithmetic into 4-wide halves).
    #[inline(always)]
    fn lanes(self) -> impl Iterator<Item = usize> {
        (0..LANES).filter(move |&k| self.0[k] != 0)
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        (0..LANES).fold(0, |b, k| b | u32::from(self.0[k] != 0) << k)
    }
}

impl Packet for F8 {
    #[inline(always)]
    fn from_array(a: [f32; LANES]) -> F8 {
        F8(a)
    }
    #[inline(always)]
    fn to_array(self) -> [f32; LANES] {
        self.0
    }
}

/// A vector of three [`Real`]s: one point or direction per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<R> {
    /// `x` of each lane.
    pub x: R,
    /// `y` of each lane.
    pub y: R,
    /// `z` of each lane.
    pub z: R,
}

impl<R: Real> V3<R> {
    /// The vector `(x, y, z)`.
    #[inline(always)]
    pub fn new(x: R, y: R, z: R) -> V3<R> {
        V3 { x, y, z }
    }

    /// Every lane `v`.
    #[inline(always)]
    pub fn splat(v: crate::Vec3) -> V3<R> {
        V3::new(R::splat(v.x), R::splat(v.y), R::splat(v.z))
    }

    /// Component `axis` (0 `x`, 1 `y`, 2 `z`).
    #[inline(always)]
    pub fn get(&self, axis: usize) -> R {
        match axis {
            0 => self.x,
            1 => self.y,
            _ => self.z,
        }
    }

    /// `self + t·d` (a point along a ray).
    #[inline(always)]
    pub fn along(self, t: R, d: V3<R>) -> V3<R> {
        V3::new(self.x + t * d.x, self.y + t * d.y, self.z + t * d.z)
    }

    /// Each component times `s`.
    #[inline(always)]
    pub fn scale(self, s: R) -> V3<R> {
        V3::new(s * self.x, s * self.y, s * self.z)
    }

    /// The dot product, summed `x`, `y`, then `z`.
    #[inline(always)]
    pub fn dot(self, o: V3<R>) -> R {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// The unit vector along `self` (times the reciprocal of its length, as glam does).
    #[inline(always)]
    pub fn normalize(self) -> V3<R> {
        let inv = R::splat(1.0) / self.dot(self).sqrt();
        V3::new(self.x * inv, self.y * inv, self.z * inv)
    }

    /// A vector that is unit to rounding, made unit again in the precision of record
    /// ([`Real::EXACT`]), kept as it is in the packets.
    #[inline(always)]
    pub fn renormalize(self) -> V3<R> {
        if R::EXACT {
            self.normalize()
        } else {
            self
        }
    }

    /// `a` in the lanes of `m`, `b` in the others.
    #[inline(always)]
    pub fn select(m: R::Mask, a: V3<R>, b: V3<R>) -> V3<R> {
        V3::new(
            R::select(m, a.x, b.x),
            R::select(m, a.y, b.y),
            R::select(m, a.z, b.z),
        )
    }
}

impl<R: Real> Add for V3<R> {
    type Output = V3<R>;
    #[inline(always)]
    fn add(self, o: V3<R>) -> V3<R> {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<R: Real> Sub for V3<R> {
    type Output = V3<R>;
    #[inline(always)]
    fn sub(self, o: V3<R>) -> V3<R> {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<R: Real> Neg for V3<R> {
    type Output = V3<R>;
    #[inline(always)]
    fn neg(self) -> V3<R> {
        V3::new(-self.x, -self.y, -self.z)
    }
}

impl From<crate::Vec3> for V3<f64> {
    #[inline(always)]
    fn from(v: crate::Vec3) -> V3<f64> {
        V3::new(v.x, v.y, v.z)
    }
}

impl From<V3<f64>> for crate::Vec3 {
    #[inline(always)]
    fn from(v: V3<f64>) -> crate::Vec3 {
        crate::Vec3::new(v.x, v.y, v.z)
    }
}

impl V3<F8> {
    /// Lane `k`, as an `f64` vector.
    #[inline(always)]
    pub fn lane(&self, k: usize) -> crate::Vec3 {
        crate::Vec3::new(self.x.lane(k), self.y.lane(k), self.z.lane(k))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec3;

    /// The packets' arithmetic is the scalar one in each lane, rounded to `f32`.
    #[test]
    fn eight_lanes_compute_as_eight_single_numbers() {
        let a = F8(std::array::from_fn(|k| k as f32 - 3.5));
        let b = F8(std::array::from_fn(|k| 1.0 + 0.25 * k as f32));
        let m = a.lt(b);
        let s = F8::select(m, a * b, a / b);
        for k in 0..LANES {
            let (x, y) = (a.0[k], b.0[k]);
            assert_eq!(m.lane(k), x < y);
            assert_eq!(s.0[k], if x < y { x * y } else { x / y });
            assert_eq!(a.max(b).0[k], x.max(y));
            assert_eq!(a.min(b).0[k], x.min(y));
            assert_eq!(a.abs().sqrt().0[k], x.abs().sqrt());
        }
        assert!(
            m.any() && !M8::splat(false).any() && M8::first(3).lane(2) && !M8::first(3).lane(3)
        );
    }

    /// `values` gives each whole number the live lanes hold once, with exactly its lanes, and
    /// skips the lanes that are not live, out of range, not whole, or NaN.
    #[test]
    fn values_are_each_number_with_its_lanes() {
        let codes = F8([2.0, 0.0, 2.0, 7.0, f32::NAN, 1.5, 0.0, 2.0]);
        let live = M8([
            u32::MAX,
            u32::MAX,
            u32::MAX,
            u32::MAX,
            u32::MAX,
            u32::MAX,
            u32::MAX,
            0,
        ]);
        let lanes = |m: M8| (0..LANES).filter(|&k| m.lane(k)).collect::<Vec<_>>();
        let got: Vec<_> = codes.values(live, 5).map(|(k, m)| (k, lanes(m))).collect();
        assert_eq!(got, vec![(2, vec![0, 2]), (0, vec![1, 6])]);
        assert_eq!(codes.values(M8::splat(false), 5).count(), 0);
    }

    /// Normalising is glam's (a reciprocal of the length, then products): the same bits.
    #[test]
    fn normalize_is_glams() {
        for v in [Vec3::new(0.3, -1.7, 2.9), Vec3::new(1e-3, 4e-4, -7e-5)] {
            let n: Vec3 = V3::<f64>::from(v).normalize().into();
            assert_eq!(n, v.normalize());
            assert_eq!(
                V3::<f64>::from(v).dot(V3::from(Vec3::Z + v)),
                v.dot(Vec3::Z + v)
            );
        }
    }
}
