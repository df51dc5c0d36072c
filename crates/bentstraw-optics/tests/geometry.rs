//! Intersections of rays with the cylinder sides and disks the scene is made of.

use bentstraw_optics::geometry::{CylinderSide, Disk, Ray};
use bentstraw_optics::Vec3;

fn unit_cylinder() -> CylinderSide {
    CylinderSide {
        cx: 0.0,
        cy: 0.0,
        radius: 1.0,
        z_min: -1.0,
        z_max: 1.0,
    }
}

#[test]
fn cylinder_hit_from_outside_is_the_near_side() {
    let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
    assert_eq!(unit_cylinder().intersect(&ray), Some(4.0));
}

#[test]
fn cylinder_hit_off_centre_matches_pythagoras() {
    // Impact parameter b = 0.6: the near side is at x = -sqrt(1 - 0.36) = -0.8.
    let ray = Ray::new(Vec3::new(-5.0, 0.6, 0.0), Vec3::X);
    let t = unit_cylinder().intersect(&ray).unwrap();
    assert!((t - 4.2).abs() < 1e-14, "{t}");
}

#[test]
fn cylinder_from_inside_finds_the_far_side() {
    let ray = Ray::new(Vec3::new(0.5, 0.0, 0.0), Vec3::X);
    assert!((unit_cylinder().intersect(&ray).unwrap() - 0.5).abs() < 1e-15);
    // Leaving from a point on the surface, the surface itself (t = 0) does not count.
    let ray = Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::X);
    assert!((unit_cylinder().intersect(&ray).unwrap() - 2.0).abs() < 1e-15);
}

#[test]
fn cylinder_misses() {
    let c = unit_cylinder();
    // Passing beside it.
    assert_eq!(
        c.intersect(&Ray::new(Vec3::new(-5.0, 1.0 + 1e-9, 0.0), Vec3::X)),
        None
    );
    // Pointing away.
    assert_eq!(
        c.intersect(&Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::NEG_X)),
        None
    );
    // Vertical: parallel to the side.
    assert_eq!(
        c.intersect(&Ray::new(Vec3::new(0.5, 0.0, -5.0), Vec3::Z)),
        None
    );
    // Above the side's height range, and below it.
    assert_eq!(
        c.intersect(&Ray::new(Vec3::new(-5.0, 0.0, 1.0 + 1e-9), Vec3::X)),
        None
    );
    assert_eq!(
        c.intersect(&Ray::new(Vec3::new(-5.0, 0.0, -1.0 - 1e-9), Vec3::X)),
        None
    );
}

#[test]
fn cylinder_tangent_ray_touches_once() {
    // Exactly tangent at (0, 1, 0): discriminant zero, one point of contact at t = 5.
    let ray = Ray::new(Vec3::new(-5.0, 1.0, 0.0), Vec3::X);
    assert_eq!(unit_cylinder().intersect(&ray), Some(5.0));
}

#[test]
fn cylinder_slanted_ray_enters_through_the_side_within_its_height() {
    // A ray climbing at 45° meets the side at x = -1, i.e. after 4 units of x, so z = -4.5 + 4 = -0.5.
    let ray = Ray::new(Vec3::new(-5.0, 0.0, -4.5), Vec3::new(1.0, 0.0, 1.0));
    let t = unit_cylinder().intersect(&ray).unwrap();
    let p = ray.at(t);
    assert!(
        (p.x + 1.0).abs() < 1e-12 && (p.z + 0.5).abs() < 1e-12,
        "{p}"
    );
    // Climbing faster, it passes over the near side's top and the far side is too high as well.
    let ray = Ray::new(Vec3::new(-5.0, 0.0, -4.5), Vec3::new(1.0, 0.0, 2.0));
    assert_eq!(unit_cylinder().intersect(&ray), None);
}

#[test]
fn cylinder_normal_points_outward() {
    let c = CylinderSide {
        cx: 1.0,
        cy: 2.0,
        radius: 0.5,
        z_min: 0.0,
        z_max: 1.0,
    };
    let n = c.normal(Vec3::new(1.0, 2.5, 0.3));
    assert!((n - Vec3::Y).length() < 1e-15);
}

#[test]
fn disk_hits_inside_and_on_its_rim_and_misses_outside() {
    let d = Disk {
        cx: 1.0,
        cy: 0.0,
        z: 2.0,
        radius: 0.5,
    };
    let down = Vec3::NEG_Z;
    assert_eq!(
        d.intersect(&Ray::new(Vec3::new(1.2, 0.1, 5.0), down)),
        Some(3.0)
    );
    assert_eq!(
        d.intersect(&Ray::new(Vec3::new(1.5, 0.0, 5.0), down)),
        Some(3.0),
        "rim counts"
    );
    assert_eq!(
        d.intersect(&Ray::new(Vec3::new(1.5 + 1e-9, 0.0, 5.0), down)),
        None
    );
    assert_eq!(
        d.intersect(&Ray::new(Vec3::new(1.0, 0.0, 5.0), Vec3::Z)),
        None,
        "behind"
    );
    assert_eq!(
        d.intersect(&Ray::new(Vec3::new(1.0, 0.0, 5.0), Vec3::X)),
        None,
        "parallel"
    );
    // A ray starting on the disk does not meet it again.
    assert_eq!(d.intersect(&Ray::new(Vec3::new(1.0, 0.0, 2.0), down)), None);
    // Just above the plane: met a hair away (no minimum distance hides it).
    let t = d
        .intersect(&Ray::new(Vec3::new(1.0, 0.0, 2.0 + 1e-12), down))
        .unwrap();
    assert!(t > 0.0 && t < 2e-12, "{t}");
}

#[test]
fn a_distant_ray_meets_the_cylinder_exactly() {
    // From 100 km, impact parameter 0.6: the near side at x = -0.8, so t = 1e5 - 0.8. The
    // discriminant's textbook form half_b² - a·c subtracts two numbers of 1e10 and loses ~1e-6 of
    // it; the cancellation-free form keeps every digit.
    for dist in [1e3, 1e5, 1e7] {
        let ray = Ray::new(Vec3::new(-dist, 0.6, 0.0), Vec3::X);
        let t = unit_cylinder().intersect(&ray).unwrap();
        let want = dist - 0.8;
        assert!(
            (t - want).abs() <= 4.0 * f64::EPSILON * dist,
            "{dist}: {t} vs {want}"
        );
        assert!((ray.at(t).x + 0.8).abs() <= 4.0 * f64::EPSILON * dist);
    }
}

#[test]
fn a_ray_leaving_the_side_meets_it_again_only_across_the_chord() {
    // Start on the surface (rounded: cos and sin are not exact), heading inwards at an angle: the
    // other side is a chord 2·|d·n| away; the start itself never counts, however it rounded.
    let c = unit_cylinder();
    for k in 0..200 {
        let th = 0.0314 * k as f64;
        let p = Vec3::new(th.cos(), th.sin(), 0.0);
        let inward = Vec3::new(-th.cos() + 0.3 * th.sin(), -th.sin() - 0.3 * th.cos(), 0.1);
        let ray = Ray::new(p, inward);
        let n = Vec3::new(p.x, p.y, 0.0);
        let horizontal = Vec3::new(ray.direction.x, ray.direction.y, 0.0);
        let want = 2.0 * horizontal.dot(-n) / horizontal.length_squared();
        let t = c.intersect_leaving(&ray).unwrap();
        assert!((t - want).abs() < 1e-14, "{t} vs {want}");
        // Heading outwards from the surface: no second meeting.
        assert_eq!(c.intersect_leaving(&Ray::new(p, -inward)), None);
    }
}

#[test]
fn a_side_a_hair_away_is_met_a_hair_away() {
    // No minimum distance: 1e-12 m outside the side, moving in, the side is 1e-12 m ahead.
    let ray = Ray::new(Vec3::new(-1.0 - 1e-12, 0.0, 0.0), Vec3::X);
    let t = unit_cylinder().intersect(&ray).unwrap();
    assert!(t > 0.0 && t < 2e-12, "{t}");
    assert!((unit_cylinder().entry(&ray).unwrap() - t).abs() < 1e-20);
}

#[test]
fn an_opaque_solid_is_entered_only_through_its_near_side() {
    let c = unit_cylinder();
    // From outside: the entering root, never the exit one.
    let ray = Ray::new(Vec3::new(-5.0, 0.6, 0.0), Vec3::X);
    assert!((c.entry(&ray).unwrap() - 4.2).abs() < 1e-14);
    // From inside the solid (only rounding puts a ray there): met at once.
    assert_eq!(
        c.entry(&Ray::new(Vec3::new(0.5, 0.0, 0.0), Vec3::X)),
        Some(0.0)
    );
    // From outside, moving away: nothing, even though the line crosses the cylinder behind.
    assert_eq!(
        c.entry(&Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::NEG_X)),
        None
    );
    // Entering above the side's top (through where a cap would be): not through the side.
    let ray = Ray::new(Vec3::new(-5.0, 0.0, 1.5), Vec3::new(1.0, 0.0, -0.1));
    assert_eq!(c.entry(&ray), None);
}
