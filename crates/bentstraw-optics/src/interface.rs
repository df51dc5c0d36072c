//! What light does at the boundary between two media: reflection, refraction (Snell–Descartes),
//! total internal reflection and the Fresnel reflectance.

use crate::lanes::{Real, V3};
use crate::Vec3;

/// Mirror reflection of direction `d` about the unit `normal` (either orientation).
#[inline]
pub fn reflect(d: Vec3, normal: Vec3) -> Vec3 {
    let (d, n) = (V3::<f64>::from(d), V3::from(normal));
    (d - n.scale(2.0 * d.dot(n))).into()
}

/// Whether light going from index `n1` to index `n2` at incidence `cos_i` (cosine of the angle of
/// incidence) is totally reflected: `(n1/n2)·sin θi > 1`.
#[inline]
pub fn total_internal_reflection(n1: f64, n2: f64, cos_i: f64) -> bool {
    snell(n1 / n2, cos_i).1
}

/// Snell–Descartes for `eta = n1/n2` at incidence `cos_i`: `sin² θt = eta²·(1 − cos² θi)`, and
/// whether it exceeds 1, i.e. whether the light is totally reflected. The one test of total
/// internal reflection every tracer and the Fresnel reflectance use.
#[inline(always)]
fn snell<R: Real>(eta: R, cos_i: R) -> (R, R::Mask) {
    let one = R::splat(1.0);
    let sin2_t = eta * eta * (one - cos_i * cos_i);
    (sin2_t, sin2_t.gt(one))
}

/// What light does at an interface, for one ray or eight ([`Real`]): the refracted direction (not
/// normalised; meaningless where `total`), the mirrored one, whether Snell's law forbids
/// refraction, and the cosine of incidence.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Scattered<R: Real> {
    /// `eta·d + (eta·cos θi − cos θt)·n`, with `n` facing the incoming light.
    pub refracted: V3<R>,
    /// `d − 2(d·n)n`.
    pub reflected: V3<R>,
    /// Total internal reflection: `(n1/n2)²·sin² θi > 1`.
    pub total: R::Mask,
    /// `|d·n|`.
    pub cos_i: R,
}

/// Refraction (Snell–Descartes, `n1 sin θi = n2 sin θt`) and mirror reflection of direction `d` at
/// an interface of unit `normal` (either orientation) from index `n1` into `n2`, `eta = n1/n2`:
/// the one rule every tracer uses, for one ray or eight.
#[inline(always)]
pub(crate) fn scatter_lanes<R: Real>(d: V3<R>, normal: V3<R>, eta: R) -> Scattered<R> {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let dn = d.dot(normal);
    // Orient the normal against the incoming direction, so that cos_i >= 0.
    let c = -dn;
    let facing = c.ge(zero);
    let nn = V3::select(facing, normal, -normal);
    let cos_i = R::select(facing, c, -c);
    let (sin2_t, total) = snell(eta, cos_i);
    let cos_t = (one - sin2_t).sqrt();
    Scattered {
        refracted: d.scale(eta) + nn.scale(eta * cos_i - cos_t),
        reflected: d - normal.scale(R::splat(2.0) * dn),
        total,
        cos_i,
    }
}

/// The unpolarised Fresnel reflectance `R = (Rs + Rp)/2` from index `n1` into `n2` (`eta =
/// n1/n2`) at incidence `cos_i >= 0` (clamped to 1), lane by lane; 1 under total internal
/// reflection.
#[inline(always)]
pub(crate) fn reflectance_lanes<R: Real>(n1: R, n2: R, eta: R, cos_i: R) -> R {
    let one = R::splat(1.0);
    let (rs, rp) = reflectances_lanes(n1, n2, eta, cos_i);
    R::select(rs.ge(R::splat(2.0)), one, R::splat(0.5) * (rs + rp))
}

/// `(Rs, Rp)` lane by lane, `(3, 3)` marking total internal reflection (see [`reflectance_lanes`]).
#[inline(always)]
fn reflectances_lanes<R: Real>(n1: R, n2: R, eta: R, cos_i: R) -> (R, R) {
    let one = R::splat(1.0);
    let cos_i = cos_i.min(one);
    let (sin2_t, total) = snell(eta, cos_i);
    let cos_t = (one - sin2_t).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    let three = R::splat(3.0);
    (
        R::select(total, three, rs * rs),
        R::select(total, three, rp * rp),
    )
}

/// The direction of light refracted from index `n1` into index `n2` at an interface of unit `normal`
/// (either orientation), by Snell–Descartes `n1 sin θi = n2 sin θt`; `None` under total internal
/// reflection.
#[inline]
pub fn refract(d: Vec3, normal: Vec3, n1: f64, n2: f64) -> Option<Vec3> {
    let s = scatter_lanes(V3::from(d), V3::from(normal), n1 / n2);
    (!s.total).then(|| s.refracted.into())
}

/// [`refract`] and, from the same `cos θi`, the reflectance
/// [`fresnel_reflectance`]`(n1, n2, d·normal)`, without computing the angles twice. `None` under
/// total internal reflection.
#[inline]
pub fn refract_with_reflectance(d: Vec3, normal: Vec3, n1: f64, n2: f64) -> Option<(Vec3, f64)> {
    let eta = n1 / n2;
    let s = scatter_lanes(V3::from(d), V3::from(normal), eta);
    (!s.total).then(|| (s.refracted.into(), reflectance_lanes(n1, n2, eta, s.cos_i)))
}

/// What happens to a ray at an interface: the outgoing direction and whether it was refracted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scattering {
    /// The ray crossed the interface, with this new direction.
    Refracted(Vec3),
    /// The ray was totally reflected, with this new direction.
    TotallyReflected(Vec3),
}

/// The course's law at an interface: refract when Snell allows it, otherwise reflect totally.
#[inline]
pub fn scatter(d: Vec3, normal: Vec3, n1: f64, n2: f64) -> Scattering {
    match refract(d, normal, n1, n2) {
        Some(t) => Scattering::Refracted(t),
        None => Scattering::TotallyReflected(reflect(d, normal)),
    }
}

/// Unpolarised Fresnel reflectance `R = (Rs + Rp)/2` for light from `n1` into `n2` at incidence
/// `cos_i` (`|cos θi|` is used); 1 under total internal reflection.
#[inline]
pub fn fresnel_reflectance(n1: f64, n2: f64, cos_i: f64) -> f64 {
    reflectance_lanes(n1, n2, n1 / n2, cos_i.abs())
}

/// The s- and p-polarised Fresnel reflectances `(Rs, Rp)`; both 1 under total internal reflection.
#[inline]
pub fn fresnel_reflectance_sp(n1: f64, n2: f64, cos_i: f64) -> (f64, f64) {
    let (rs, rp) = reflectances_lanes(n1, n2, n1 / n2, cos_i.abs());
    if rs >= 2.0 {
        (1.0, 1.0)
    } else {
        (rs, rp)
    }
}

/// Critical angle (radians) for light going from index `n1` into a lower index `n2`; `None` if
/// `n1 <= n2` (no total reflection possible).
pub fn critical_angle(n1: f64, n2: f64) -> Option<f64> {
    (n1 > n2).then(|| libm::asin(n2 / n1))
}
