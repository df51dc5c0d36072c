//! The Fresnel reflectance against known values, and the conservation of weight in Fresnel tracing
//! (each split passes on the whole weight: `R` reflected, `1 − R` refracted).

mod support;

use support::reference::Reference;

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::interface::{critical_angle, fresnel_reflectance, fresnel_reflectance_sp};
use bentstraw_optics::scene::{Scene, GLASS_HEIGHT, GLASS_RADIUS, WATER_INDEX};
use bentstraw_optics::world::{FresnelStep, World, COLOR_COUNT, FRESNEL_SEGMENTS_PER_RAY};
use bentstraw_optics::Vec3;
use proptest::prelude::*;

const N: f64 = WATER_INDEX;

#[test]
fn normal_incidence_reflects_the_square_of_the_index_contrast() {
    for n in [1.333f64, 1.5, 2.4] {
        let want = ((n - 1.0) / (n + 1.0)).powi(2);
        assert!((fresnel_reflectance(1.0, n, 1.0) - want).abs() < 1e-15);
        assert!((fresnel_reflectance(n, 1.0, 1.0) - want).abs() < 1e-15);
        assert!((fresnel_reflectance(1.0, n, -1.0) - want).abs() < 1e-15);
    }
    // Water: 2.04 %, (0.333/2.333)².
    assert!((fresnel_reflectance(1.0, N, 1.0) - 0.020_373).abs() < 1e-6);
}

#[test]
fn textbook_values_at_45_degrees_for_glass() {
    // n = 1.5 at 45°: Rs = 9.20 %, Rp = 0.85 % (e.g. Hecht, Optics, Fig. 4.32).
    let (rs, rp) = fresnel_reflectance_sp(1.0, 1.5, 45f64.to_radians().cos());
    assert!((rs - 0.0920).abs() < 5e-4, "Rs = {rs}");
    assert!((rp - 0.0085).abs() < 5e-4, "Rp = {rp}");
}

#[test]
fn p_polarisation_is_not_reflected_at_brewsters_angle() {
    for (n1, n2) in [(1.0, N), (N, 1.0), (1.0, 1.5)] {
        let brewster: f64 = (n2 / n1).atan();
        let (rs, rp) = fresnel_reflectance_sp(n1, n2, brewster.cos());
        assert!(rp < 1e-20, "Rp = {rp} at Brewster ({n1} → {n2})");
        assert!(rs > 0.01, "Rs = {rs}");
        // Not zero a degree away.
        let (_, rp_off) = fresnel_reflectance_sp(n1, n2, (brewster + 0.02).cos());
        assert!(rp_off > 1e-6);
    }
}

#[test]
fn total_reflection_beyond_the_critical_angle_and_continuity_up_to_it() {
    let c = critical_angle(N, 1.0).unwrap();
    assert!((c.to_degrees() - 48.607).abs() < 1e-3);
    for extra in [1e-9, 1e-4, 0.1, 0.5] {
        let th: f64 = c + extra;
        assert_eq!(fresnel_reflectance_sp(N, 1.0, th.cos()), (1.0, 1.0));
    }
    // Just below: R climbs continuously to 1.
    let mut previous = 0.0;
    for eps in [1e-1, 1e-2, 1e-3, 1e-5, 1e-8, 1e-12] {
        let r = fresnel_reflectance(N, 1.0, (c - eps).cos());
        assert!(r > previous && r <= 1.0, "R({eps}) = {r}");
        previous = r;
    }
    assert!(
        previous > 0.999,
        "R just below the critical angle = {previous}"
    );
    // Grazing incidence from air reflects everything.
    assert!(fresnel_reflectance(1.0, N, 1e-9) > 0.999_99);
}

/// Transmittances from the amplitude coefficients (Fresnel's t_s, t_p times the flux factor).
fn transmittance_sp(n1: f64, n2: f64, th: f64) -> (f64, f64) {
    let ci = th.cos();
    let st = n1 / n2 * th.sin();
    let ct = (1.0 - st * st).sqrt();
    let ts = 2.0 * n1 * ci / (n1 * ci + n2 * ct);
    let tp = 2.0 * n1 * ci / (n2 * ci + n1 * ct);
    let flux = n2 * ct / (n1 * ci);
    (flux * ts * ts, flux * tp * tp)
}

proptest! {
    #[test]
    fn reflectance_and_transmittance_add_to_one(th in 0.0f64..1.5, n in 1.0f64..2.5, into in any::<bool>()) {
        let (n1, n2) = if into { (1.0, n) } else { (n, 1.0) };
        prop_assume!(n1 / n2 * th.sin() < 1.0);
        let (rs, rp) = fresnel_reflectance_sp(n1, n2, th.cos());
        let (ts, tp) = transmittance_sp(n1, n2, th);
        prop_assert!((rs + ts - 1.0).abs() < 1e-12);
        prop_assert!((rp + tp - 1.0).abs() < 1e-12);
    }
}

/// Every step of a Fresnel trace, with the returned weights.
fn steps(scene: &Scene, ray: Ray, prune: f64) -> (Vec<FresnelStep>, [f64; COLOR_COUNT]) {
    let mut all = Vec::new();
    let w = World::assignment(scene).fresnel_steps::<false>(
        ray,
        prune,
        FRESNEL_SEGMENTS_PER_RAY,
        |s| all.push(s),
    );
    (all, w)
}

/// Weight ending on the straw, escaping, dropped at the event limit, and pruned.
fn budget(all: &[FresnelStep]) -> (f64, f64, f64, f64) {
    let (mut straw, mut escaped, mut dropped, mut pruned) = (0.0, 0.0, 0.0, 0.0);
    for s in all {
        match *s {
            FresnelStep::Object { weight, .. } => straw += weight,
            FresnelStep::Escaped { weight, .. } => escaped += weight,
            FresnelStep::Dropped { weight } => dropped += weight,
            FresnelStep::Pruned { weight } => pruned += weight,
            _ => {}
        }
    }
    (straw, escaped, dropped, pruned)
}

fn arb_scene() -> impl Strategy<Value = Scene> {
    (
        0.0f64..0.035,
        0.0f64..std::f64::consts::TAU,
        0.0f64..=GLASS_HEIGHT,
        1.0f64..1.8,
        1u32..30,
    )
        .prop_map(|(r, a, he, n, m)| Scene::new(r * a.cos(), r * a.sin(), he, n, m).unwrap())
}

/// A ray from outside the glass, aimed at a point inside the glass's box (or near it).
fn arb_ray() -> impl Strategy<Value = Ray> {
    (
        0.06f64..0.5,
        0.0f64..std::f64::consts::TAU,
        -0.3f64..0.6,
        -0.05f64..0.05,
        -0.05f64..0.05,
        -0.02f64..0.27,
    )
        .prop_map(|(d, a, z, tx, ty, tz)| {
            let eye = Vec3::new(d * a.cos(), d * a.sin(), z);
            Ray::new(eye, Vec3::new(tx, ty, tz) - eye)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Pruning changes a ray's weights by at most the weight it abandons, never adding any: each
    /// section keeps at least what it had, and loses at most, all sections together, the total
    /// of the abandoned branches (each lighter than the threshold, but a ray may abandon
    /// several). Compared where following every branch drops nothing.
    #[test]
    fn pruning_changes_the_weights_by_at_most_what_it_abandons(scene in arb_scene(), ray in arb_ray(), prune in 1e-5f64..0.05) {
        let (all, pruned_weights) = steps(&scene, ray, prune);
        let (full_steps, full) = steps(&scene, ray, 0.0);
        let (.., dropped, lost) = budget(&full_steps);
        prop_assume!(dropped == 0.0 && lost == 0.0);
        let (.., pruned) = budget(&all);
        let mut change = 0.0;
        for (p, f) in pruned_weights.iter().zip(full) {
            prop_assert!(*p <= f + 1e-15, "{pruned_weights:?} vs {full:?}");
            change += f - p;
        }
        prop_assert!(change <= pruned + 1e-12, "changed by {change:e}, abandoned {pruned:e}");
    }

    /// R + T = 1 at every split, with R the Fresnel reflectance of the split's geometry; the
    /// branches' ends account for the whole weight; the weights returned are the straw's share.
    #[test]
    fn weight_is_conserved(scene in arb_scene(), ray in arb_ray(), prune in prop_oneof![Just(0.0), 1e-6f64..0.1]) {
        let (all, weights) = steps(&scene, ray, prune);
        for s in &all {
            if let FresnelStep::Split { normal, incoming, n1, n2, weight, reflected, refracted, .. } = *s {
                prop_assert!((reflected + refracted - weight).abs() <= 1e-15 * weight.max(1.0) * 4.0);
                let r = fresnel_reflectance(n1, n2, incoming.dot(normal));
                prop_assert!((reflected - r * weight).abs() <= 1e-15);
                prop_assert!(n1 == 1.0 || n2 == 1.0);
            }
        }
        let (straw, escaped, dropped, pruned) = budget(&all);
        prop_assert!((straw + escaped + dropped + pruned - 1.0).abs() < 1e-12,
            "{straw} + {escaped} + {dropped} + {pruned}");
        let total: f64 = weights.iter().sum();
        prop_assert!((total - straw).abs() < 1e-12);
        prop_assert!(total <= 1.0 + 1e-12);
        prop_assert!(weights.iter().all(|&w| w >= 0.0));
        // Every abandoned branch was lighter than the threshold.
        for s in &all {
            if let FresnelStep::Pruned { weight } = *s {
                prop_assert!(weight < prune || weight == 0.0);
            }
        }
        // An independent tracer (double-double, its own code) gives the same weights, wherever no
        // branch passes within rounding of an edge, a tie or the critical angle.
        let (want, margin) = Reference::new(&scene).fresnel(ray, prune);
        if margin >= 1e-9 {
            for (g, w) in weights.iter().zip(want) {
                prop_assert!((g - w).abs() <= 1e-12, "{weights:?} vs {want:?}");
            }
        }
    }
}

#[test]
fn straight_down_onto_the_top_cap_everything_is_blue() {
    let scene = Scene::with_defaults(0.01, -0.01, 0.15).unwrap();
    let ray = Ray::new(Vec3::new(0.011, -0.009, 0.4), Vec3::NEG_Z);
    let w = World::assignment(&scene).fresnel_steps::<false>(
        ray,
        1e-4,
        FRESNEL_SEGMENTS_PER_RAY,
        |_| {},
    );
    assert_eq!(w, [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
}

#[test]
fn reflected_and_refracted_parts_both_reach_the_straw_and_add_to_one() {
    // A ray onto the water surface beside the straw: the reflected part hits the straw above the
    // water (section 3), the refracted part the straw below it (section 2). Nothing escapes or is
    // dropped, so w2 + w3 = 1 exactly, and w3 is the Fresnel reflectance at the incidence angle.
    let scene = Scene::new(0.0, 0.0, 0.10, N, 10).unwrap();
    let hit = Vec3::new(0.012, 0.0, 0.10);
    let along = Vec3::new(-0.018, 0.0, -0.03);
    let eye = hit - 4.0 * along; // (0.084, 0, 0.22): above the glass, outside it
    let (all, w) = steps(&scene, Ray::new(eye, along), 0.0);
    let theta = (0.018f64 / 0.03).atan();
    let r = fresnel_reflectance(1.0, N, theta.cos());
    assert!((w[2] - r).abs() < 1e-12, "{w:?} vs R = {r}");
    assert!((w[1] - (1.0 - r)).abs() < 1e-12);
    assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    let (_, escaped, dropped, pruned) = budget(&all);
    assert_eq!((escaped, dropped, pruned), (0.0, 0.0, 0.0));
}

#[test]
fn horizontal_ray_at_the_axis_loses_only_the_normal_reflection() {
    // Straw on the axis, ray along −x at z = 0.07 (section 2): normal incidence on the water's
    // side, then straight to the straw. The reflected 2 % escapes back towards the observer.
    let scene = Scene::new(0.0, 0.0, 0.2, N, 10).unwrap();
    let (all, w) = steps(
        &scene,
        Ray::new(Vec3::new(0.2, 0.0, 0.07), Vec3::NEG_X),
        1e-4,
    );
    let r0 = ((N - 1.0) / (N + 1.0)).powi(2);
    assert!((w[1] - (1.0 - r0)).abs() < 1e-12, "{w:?}");
    assert_eq!(w.iter().filter(|&&x| x != 0.0).count(), 1);
    let (_, escaped, dropped, pruned) = budget(&all);
    assert!((escaped - r0).abs() < 1e-12 && dropped == 0.0 && pruned == 0.0);
    // The escaping branch goes straight back.
    assert!(all.iter().any(|s| matches!(s, FresnelStep::Escaped { ray, .. } if (ray.direction - Vec3::X).length() < 1e-12)));
}

#[test]
fn a_long_chain_of_near_critical_reflections_loses_no_weight() {
    // A horizontal ray entering the side almost grazing: inside, every chord meets the wall just
    // below the critical angle (R close to 1), so hundreds of splits follow, each sending a little
    // out. With no pruning and a large event limit, all the weight is still accounted for.
    let scene = Scene::new(0.0, 0.0, 0.2, N, 1000).unwrap();
    let b = 0.9999 * GLASS_RADIUS;
    let ray = Ray::new(Vec3::new(0.3, b, 0.1), Vec3::NEG_X);
    let (all, w) = steps(&scene, ray, 0.0);
    let splits = all
        .iter()
        .filter(|s| matches!(s, FresnelStep::Split { .. }))
        .count();
    assert!(splits > 100, "{splits} splits");
    let (straw, escaped, dropped, pruned) = budget(&all);
    assert_eq!(pruned, 0.0);
    assert!((straw + escaped + dropped - 1.0).abs() < 1e-12);
    assert_eq!(w, [0.0; COLOR_COUNT]);
}

/// Light trapped by total reflection (index 5, the largest allowed, and a thousand events) would be followed a
/// thousand times per branch: the work per ray is bounded, and what is cut is accounted as
/// dropped, so the weights still add up.
#[test]
fn fresnel_work_per_ray_is_bounded_and_accounted() {
    let scene = Scene::new(0.035, 0.0, 0.05, 5.0, 1000).unwrap();
    let observer = Vec3::new(0.0, 0.0, -1e-320);
    let mut trapped = 0;
    for k in 0..64 {
        let aim = Vec3::new(-0.039 + 0.078 * k as f64 / 63.0, 0.013, 0.03);
        let ray = Ray::new(observer, aim - observer);
        for bound in [100, 1000] {
            let mut all = Vec::new();
            let weights =
                World::assignment(&scene).fresnel_steps::<false>(ray, 0.0, bound, |s| all.push(s));
            // Every event (a split or a total reflection) ends one of the segments followed.
            let events = all
                .iter()
                .filter(|s| {
                    matches!(
                        s,
                        FresnelStep::Split { .. } | FresnelStep::TotalReflection { .. }
                    )
                })
                .count();
            assert!(
                events <= bound as usize,
                "{events} events past a bound of {bound}"
            );
            let (straw, escaped, dropped, pruned) = budget(&all);
            assert!((straw + escaped + dropped + pruned - 1.0).abs() < 1e-9);
            assert!((weights.iter().sum::<f64>() - straw).abs() < 1e-12);
            // Here each split costs two segments (the branch leaving the water ends at once).
            if bound == 100 && events + 1 >= 50 {
                trapped += 1;
                assert!(dropped > 0.0, "light cut by the bound is dropped");
            }
        }
    }
    assert!(trapped > 0, "some rays are trapped until the bound");
}
