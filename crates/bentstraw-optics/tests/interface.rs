//! Snell–Descartes refraction, total internal reflection and mirror reflection at an interface.

use bentstraw_optics::interface::{
    critical_angle, reflect, refract, scatter, total_internal_reflection, Scattering,
};
use bentstraw_optics::Vec3;
use proptest::prelude::*;

/// Sine of the angle between unit `d` and the normal line.
fn sin_angle(d: Vec3, n: Vec3) -> f64 {
    d.cross(n).length()
}

#[test]
fn critical_angle_water_to_air_is_48_607_degrees() {
    let c = critical_angle(1.333, 1.0).unwrap().to_degrees();
    assert!((c - 48.607).abs() < 5e-4, "{c}");
    assert_eq!(critical_angle(1.0, 1.333), None);
}

#[test]
fn total_reflection_sets_in_exactly_past_the_critical_angle() {
    let n = Vec3::Z;
    let crit = (1.0f64 / 1.333).asin();
    for (angle, expect_tir) in [
        (crit - 1e-6, false),
        (crit + 1e-6, true),
        (0.3, false),
        (1.2, true),
    ] {
        // Inside water going up to the surface at `angle` from the normal.
        let d = Vec3::new(angle.sin(), 0.0, angle.cos());
        assert_eq!(
            total_internal_reflection(1.333, 1.0, angle.cos()),
            expect_tir,
            "{angle}"
        );
        assert_eq!(refract(d, n, 1.333, 1.0).is_none(), expect_tir, "{angle}");
        match scatter(d, n, 1.333, 1.0) {
            Scattering::TotallyReflected(r) => {
                assert!(expect_tir);
                assert!((r - Vec3::new(d.x, 0.0, -d.z)).length() < 1e-15);
            }
            Scattering::Refracted(_) => assert!(!expect_tir),
        }
    }
    // Entering the denser medium is never totally reflected, even at grazing incidence.
    assert!(!total_internal_reflection(1.0, 1.333, 1e-9));
}

#[test]
fn refraction_at_normal_incidence_goes_straight() {
    let t = refract(Vec3::NEG_Z, Vec3::Z, 1.0, 1.333).unwrap();
    assert!((t - Vec3::NEG_Z).length() < 1e-15);
}

#[test]
fn refraction_at_30_degrees_into_water_matches_snell_by_hand() {
    // sin θt = sin 30° / 1.333 = 0.375093...
    let d = Vec3::new(0.5, 0.0, -(0.75f64).sqrt());
    let t = refract(d, Vec3::Z, 1.0, 1.333).unwrap();
    assert!((t.x - 0.5 / 1.333).abs() < 1e-15);
    assert!((t.length() - 1.0).abs() < 1e-15);
    assert!(t.z < 0.0, "continues downward");
}

fn unit_vector() -> impl Strategy<Value = Vec3> {
    (-1.0f64..1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

proptest! {
    #[test]
    fn snell_holds_and_rays_stay_in_the_plane_of_incidence(
        d in unit_vector(), n in unit_vector(), n1 in 1.0f64..2.0, n2 in 1.0f64..2.0,
    ) {
        prop_assume!(d.dot(n).abs() > 1e-6);
        match refract(d, n, n1, n2) {
            Some(t) => {
                prop_assert!((t.length() - 1.0).abs() < 1e-12);
                prop_assert!((n1 * sin_angle(d, n) - n2 * sin_angle(t, n)).abs() < 1e-12);
                // Same side of the interface as the incoming ray continues to.
                prop_assert!(t.dot(n).signum() == d.dot(n).signum());
                // Coplanar with the incoming direction and the normal.
                prop_assert!(t.dot(d.cross(n)).abs() < 1e-12);
                // Reversibility: the reversed refracted ray refracts back into the reversed incoming one.
                let back = refract(-t, n, n2, n1).unwrap();
                prop_assert!((back + d).length() < 1e-10);
            }
            None => {
                prop_assert!(n1 > n2);
                prop_assert!(n1 / n2 * sin_angle(d, n) > 1.0 - 1e-12);
            }
        }
    }

    #[test]
    fn reflection_preserves_the_angle_and_reverses_the_normal_component(
        d in unit_vector(), n in unit_vector(),
    ) {
        let r = reflect(d, n);
        prop_assert!((r.length() - 1.0).abs() < 1e-12);
        prop_assert!((r.dot(n) + d.dot(n)).abs() < 1e-12);
        prop_assert!((sin_angle(r, n) - sin_angle(d, n)).abs() < 1e-12);
        prop_assert!(r.dot(d.cross(n)).abs() < 1e-12);
    }
}
