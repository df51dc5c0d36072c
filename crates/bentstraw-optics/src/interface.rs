//! What light does at the boundary between two media: reflection, refraction (Snell–Descartes),
//! total internal reflection and the Fresnel reflectance.

use crate::Vec3;

/// Mirror reflection of direction `d` about the unit `normal` (either orientation).
#[inline]
pub fn reflect(d: Vec3, normal: Vec3) -> Vec3 {
    d - 2.0 * d.dot(normal) * normal
}

/// Whether light going from index `n1` to index `n2` at incidence `cos_i` (cosine of the angle of
/// incidence) is totally reflected: `(n1/n2)·sin θi > 1`.
#[inline]
pub fn total_internal_reflection(n1: f64, n2: f64, cos_i: f64) -> bool {
    let eta = n1 / n2;
    eta * eta * (1.0 - cos_i * cos_i) > 1.0
}

/// The direction of light refracted from index `n1` into index `n2` at an interface of unit `normal`
/// (either orientation), by Snell–Descartes `n1 sin θi = n2 sin θt`; `None` under total internal
/// reflection.
#[inline]
pub fn refract(d: Vec3, normal: Vec3, n1: f64, n2: f64) -> Option<Vec3> {
    // Orient the normal against the incoming direction, so that cos_i >= 0.
    let (nn, cos_i) = {
        let c = -d.dot(normal);
        if c >= 0.0 {
            (normal, c)
        } else {
            (-normal, -c)
        }
    };
    let eta = n1 / n2;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(eta * d + (eta * cos_i - cos_t) * nn)
}

/// [`refract`] and, from the same `cos θi`, `sin² θt` and `cos θt`, the reflectance
/// [`fresnel_reflectance`]`(n1, n2, d·normal)`: the same operations, so the same bits, without
/// computing the angles twice (it defers to [`fresnel_reflectance`] where that one's clamps act).
/// `None` under total internal reflection.
#[inline]
pub fn refract_with_reflectance(d: Vec3, normal: Vec3, n1: f64, n2: f64) -> Option<(Vec3, f64)> {
    let dn = d.dot(normal);
    let c = -dn;
    let (nn, cos_i) = if c >= 0.0 { (normal, c) } else { (-normal, -c) };
    let eta = n1 / n2;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let refracted = eta * d + (eta * cos_i - cos_t) * nn;
    let r = if cos_i <= 1.0 && sin2_t < 1.0 {
        let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
        let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
        0.5 * (rs * rs + rp * rp)
    } else {
        fresnel_reflectance(n1, n2, dn)
    };
    Some((refracted, r))
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
    let (rs, rp) = fresnel_reflectance_sp(n1, n2, cos_i);
    0.5 * (rs + rp)
}

/// The s- and p-polarised Fresnel reflectances `(Rs, Rp)`; both 1 under total internal reflection.
#[inline]
pub fn fresnel_reflectance_sp(n1: f64, n2: f64, cos_i: f64) -> (f64, f64) {
    let cos_i = cos_i.abs().min(1.0);
    let eta = n1 / n2;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return (1.0, 1.0);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    (rs * rs, rp * rp)
}

/// Critical angle (radians) for light going from index `n1` into a lower index `n2`; `None` if
/// `n1 <= n2` (no total reflection possible).
pub fn critical_angle(n1: f64, n2: f64) -> Option<f64> {
    (n1 > n2).then(|| (n2 / n1).asin())
}
