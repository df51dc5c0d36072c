//! Transparent solids: a sphere of its own index, in air or in a liquid, checked against closed
//! forms (a ball lens's rays and focal length), its laws (Snell at its faces, a sphere of its
//! surroundings' index vanishing) and the eye model (a point at a ball's centre seen there).

use bentstraw_optics::apparent::eye_model_points;
use bentstraw_optics::geometry::Ray;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene_file::SceneDescription;
use bentstraw_optics::world::{Event, Outcome, World};
use bentstraw_optics::Vec3;

fn scene(toml: &str) -> SceneDescription {
    SceneDescription::from_toml(toml).unwrap_or_else(|e| panic!("{e}\n{toml}"))
}

/// A small empty glass at the origin and a ball of `index` and `radius` centred at `centre`,
/// wholly outside it, in air.
fn ball_in_air(centre: Vec3, radius: f64, index: f64) -> World {
    let d = scene(&format!(
        "[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n\
         [[sphere]]\ncenter = [{}, {}, {}]\nradius = {radius}\nindex = {index}\n",
        centre.x, centre.y, centre.z
    ));
    World::new(&d, 10).expect("a valid scene")
}

fn trace_events(world: &World, ray: Ray) -> (Outcome, Vec<Event>) {
    let mut events = Vec::new();
    let outcome = world.trace_with(ray, |e| events.push(*e));
    (outcome, events)
}

/// How far beyond `centre` (along `x`) the ray's line, which lies in the plane `z = centre.z`,
/// crosses the line `y = centre.y` of that plane.
fn axis_crossing(ray: Ray, centre: Vec3) -> f64 {
    let s = (centre.y - ray.origin.y) / ray.direction.y;
    ray.origin.x + s * ray.direction.x - centre.x
}

/// A ray parallel to a ball lens's axis at height `h` leaves it crossing the axis at distance
/// `R·sin i / sin δ` beyond the centre, where `sin i = h/R`, `sin r = h/(nR)` and the deviation
/// is `δ = 2(i − r)`: the ray leaves at the angle it entered (the ball's symmetry), so its line
/// passes the centre at `R·sin i`. As `h → 0` this is the paraxial focal length `nR/(2(n − 1))`.
#[test]
fn a_ball_lens_brings_parallel_rays_to_its_closed_form_focus() {
    let (centre, radius) = (Vec3::new(0.3, 0.0, 0.2), 0.02);
    for n in [1.333, 1.5, 1.9] {
        let world = ball_in_air(centre, radius, n);
        for h in [1e-5, 0.002, 0.008, 0.014] {
            let ray = Ray::new(centre + Vec3::new(-0.2, h, 0.0), Vec3::X);
            let (outcome, events) = trace_events(&world, ray);
            assert_eq!(events.len(), 2, "in and out of the ball: {events:?}");
            let Outcome::Escaped { ray: out, .. } = outcome else {
                panic!("it leaves the scene: {outcome:?}")
            };
            let (i, r) = ((h / radius).asin(), (h / (n * radius)).asin());
            let delta = 2.0 * (i - r);
            let expected = radius * i.sin() / delta.sin();
            let t = axis_crossing(out, centre);
            assert!(
                (out.origin.z - centre.z).abs() < 1e-15 && out.direction.z.abs() < 1e-15,
                "the ray stays in the plane of the axis: {out:?}"
            );
            assert!(
                (t - expected).abs() < 1e-11 * expected.max(1.0),
                "n {n}, h {h}: crosses at {t}, closed form {expected}"
            );
            // The ray's line after the ball passes the centre at R·sin i.
            let gap = (centre - out.origin).cross(out.direction).length();
            assert!((gap - h).abs() < 1e-13, "{gap} {h}");
        }
        // Paraxially: the focal length of a ball lens.
        let paraxial = n * radius / (2.0 * (n - 1.0));
        let ray = Ray::new(centre + Vec3::new(-0.2, 1e-6, 0.0), Vec3::X);
        let Outcome::Escaped { ray: out, .. } = world.trace(ray) else {
            panic!("it leaves the scene")
        };
        let t = axis_crossing(out, centre);
        assert!(
            (t - paraxial).abs() < 1e-8,
            "n {n}: focus {t}, paraxial {paraxial}"
        );
    }
}

/// Every event at a ball's faces obeys Snell's law, rays from every side; a ray through the
/// centre goes straight.
#[test]
fn snell_holds_at_a_balls_faces_and_its_diameters_go_straight() {
    let centre = Vec3::new(0.0, 0.25, 0.1);
    let world = ball_in_air(centre, 0.03, 1.5);
    let eye = Vec3::new(0.2, 0.45, 0.3);
    let mut events_seen = 0;
    for k in 0..400u32 {
        let f = |m: f64| (k as f64 * m).fract() - 0.5;
        let aim = centre + 0.07 * Vec3::new(f(0.618034), f(0.7548777), f(0.5698403));
        let (_, events) = trace_events(&world, Ray::new(eye, aim - eye));
        for e in events {
            let sine = |d: Vec3| d.cross(e.normal).length();
            if e.totally_reflected {
                assert!(e.n1 * sine(e.incoming) > e.n2 * (1.0 - 1e-12));
            } else {
                let (a, b) = (e.n1 * sine(e.incoming), e.n2 * sine(e.outgoing));
                assert!((a - b).abs() < 1e-12, "{e:?}");
            }
            // The normal is the radius's direction, outwards.
            let radial = (e.point - centre).normalize();
            assert!((e.normal - radial).length() < 1e-12);
            assert!(((e.point - centre).length() - 0.03).abs() < 1e-15);
            events_seen += 1;
        }
    }
    assert!(events_seen > 100);
    let (outcome, events) = trace_events(&world, Ray::new(eye, centre - eye));
    assert_eq!(events.len(), 2);
    let Outcome::Escaped { ray, .. } = outcome else {
        panic!("escapes")
    };
    assert!((ray.direction - (centre - eye).normalize()).length() < 1e-15);
}

/// A ball of its liquid's index is no ball: the world is the same without it, every image point
/// the same.
#[test]
fn a_ball_of_its_liquids_index_vanishes() {
    let with = |index: f64| {
        let mut text = String::from(
            "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
             [[liquid]]\nname = \"oil\"\nindex = 1.47\ntop = 0.1\n\n\
             [[straw]]\nx = 0.015\ny = 0.0\n\n",
        );
        if index > 0.0 {
            text += &format!(
                "[[sphere]]\ncenter = [-0.015, 0.0, 0.04]\nradius = 0.012\nindex = {index}\n"
            );
        }
        World::new(&scene(&text), 10).expect("a valid scene")
    };
    let (plain, vanished, seen) = (with(0.0), with(1.47), with(1.5));
    assert_eq!(plain.boundaries(), vanished.boundaries());
    assert_eq!(seen.boundaries().len(), plain.boundaries().len() + 1);
    for eye in [Vec3::new(0.2, 0.0, 0.1), Vec3::new(-0.1, 0.2, 0.25)] {
        let (a, b) = (
            sample_image(&plain, eye, 3000, &|_| {}),
            sample_image(&vanished, eye, 3000, &|_| {}),
        );
        assert_eq!(a.points, b.points);
    }
}

/// A point at a ball's centre sends its light out along radii, unbent: the eye model sees it at
/// the centre from anywhere, and a point near the centre near it (magnified at most `n` times).
#[test]
fn the_eye_model_sees_a_balls_centre_at_the_centre() {
    let centre = Vec3::new(0.0, 0.3, 0.1);
    // A small card at the ball's centre, facing +x, inside the ball.
    let d = scene(&format!(
        "[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n\
         [[sphere]]\ncenter = [{x}, {y}, {z}]\nradius = 0.03\nindex = 1.5\n\n\
         [[card]]\ncenter = [{x}, {y}, {z}]\nfacing = 0\nwidth = 0.004\nheight = 0.004\npicture = \"none\"\n",
        x = centre.x,
        y = centre.y,
        z = centre.z
    ));
    let world = World::new(&d, 10).expect("a valid scene");
    for eye in [
        Vec3::new(0.3, 0.3, 0.1),
        Vec3::new(0.25, 0.45, 0.25),
        Vec3::new(0.2, 0.2, -0.1),
    ] {
        let cloud = sample_image(&world, eye, 4000, &|_| {});
        let near: Vec<_> = cloud
            .points
            .iter()
            .filter(|p| (p.straw_point - centre).length() < 3e-4)
            .copied()
            .collect();
        assert!(!near.is_empty(), "the card's middle is seen from {eye}");
        for a in eye_model_points(&world, eye, &near) {
            let p = a
                .position
                .expect("a point of a card seen through a ball is placed");
            let e = (a.image.straw_point - centre).length();
            assert!(
                (p - centre).length() <= 1.5 * e * 1.01 + 1e-9,
                "from {eye}: {} from the centre for a point {e} from it",
                (p - centre).length()
            );
        }
    }
}

/// A sphere's place is checked: inside the container above the floor and in one layer, or
/// wholly outside it; clear of the other objects; a card wholly inside or outside; the eye
/// outside it.
#[test]
fn a_spheres_place_breaks_no_rule() {
    let base = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
                [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.1\n\n\
                [[straw]]\nx = 0.02\ny = 0.0\n\n";
    let refused = |sphere: &str, code: &str| {
        let text = format!("{base}{sphere}");
        let e = SceneDescription::from_toml(&text).expect_err(sphere);
        assert!(
            e.rules().any(|r| r.rule.code() == code),
            "{sphere}: {e} (wanted {code})"
        );
    };
    let ball = |c: [f64; 3], r: f64| {
        format!(
            "[[sphere]]\ncenter = [{}, {}, {}]\nradius = {r}\nindex = 1.5\n",
            c[0], c[1], c[2]
        )
    };
    // Through the wall, through the floor.
    refused(&ball([0.035, 0.0, 0.05], 0.01), "sphere.container");
    refused(&ball([-0.01, 0.0, 0.005], 0.01), "sphere.container");
    // Into the straw, into another ball.
    refused(&ball([0.01, 0.0, 0.05], 0.008), "solid.overlap");
    let two = format!(
        "{}{}",
        ball([-0.02, 0.0, 0.03], 0.01),
        ball([-0.02, 0.0, 0.045], 0.01)
    );
    refused(&two, "solid.overlap");
    // A card through its surface; the eye inside it.
    let card = "[[card]]\ncenter = [0.3, 0.0, 0.1]\nwidth = 0.02\nheight = 0.02\n";
    refused(
        &format!("{}{card}", ball([0.3, 0.0, 0.1], 0.012)),
        "solid.card",
    );
    let eye = "[observer]\nposition = [0.3, 0.0, 0.1]\n";
    refused(
        &format!("{}{eye}", ball([0.3, 0.0, 0.1], 0.02)),
        "observer.in-solid",
    );
    refused(
        "[[sphere]]\ncenter = [0.3, 0.0, 0.1]\nradius = 0.02\nindex = 0.9\n",
        "index.range",
    );
    // A ball resting on a thick bottom, its centre written as floor + radius (0.037 − 0.025 is
    // a hair below 0.012 in binary): it rests on the floor.
    scene(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\nbottom = 0.012\n\n\
         [[sphere]]\ncenter = [0.0, 0.0, 0.037]\nradius = 0.025\nindex = 1.5\n",
    );
    // In the water, in the air above it inside the glass, outside the glass, a card inside it:
    // each a valid scene, written back as it was read.
    for ok in [
        ball([-0.015, 0.0, 0.03], 0.012),
        ball([-0.015, 0.0, 0.12], 0.012),
        ball([-0.015, 0.0, 0.095], 0.01),
        ball([0.3, 0.0, 0.1], 0.05),
        format!(
            "{}{}",
            ball([0.3, 0.0, 0.1], 0.05),
            card.replace("0.02\n", "0.01\n")
        ),
    ] {
        let d = scene(&format!("{base}{ok}"));
        assert_eq!(scene(&d.to_toml()), d);
        World::new(&d, 10).expect("a world");
    }
}

/// A ball half in the water: its upper half meets air, its lower half water, and the water has
/// no surface inside it. Every event's indices are the geometry's on its two sides; a ray down
/// the ball's axis goes straight, with one event where it enters the ball and one where it
/// leaves it into the water; a ball of the water's own index keeps only its upper face.
#[test]
fn a_ball_half_in_the_water_has_no_water_surface_inside_it() {
    let (centre, radius, top) = (Vec3::new(-0.015, 0.0, 0.1), 0.012, 0.1);
    let world_of = |index: f64| {
        let d = scene(&format!(
            "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
             [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = {top}\n\n\
             [[straw]]\nx = 0.02\ny = 0.0\n\n\
             [[sphere]]\ncenter = [{}, {}, {}]\nradius = {radius}\nindex = {index}\n",
            centre.x, centre.y, centre.z
        ));
        World::new(&d, 10).expect("a valid scene")
    };
    let index_at = |p: Vec3, ball: f64| {
        if (p - centre).length() < radius {
            ball
        } else if p.x.hypot(p.y) < 0.04 && (0.0..top).contains(&p.z) {
            1.333
        } else {
            1.0
        }
    };
    let world = world_of(1.5);
    let eye = Vec3::new(0.15, 0.1, 0.2);
    let mut checked = 0;
    for k in 0..600u32 {
        let f = |m: f64| (k as f64 * m).fract() - 0.5;
        let aim = centre + 0.03 * Vec3::new(f(0.618034), f(0.7548777), f(0.5698403));
        let (_, events) = trace_events(&world, Ray::new(eye, aim - eye));
        for e in events {
            let before = index_at(e.point - 1e-9 * e.incoming, 1.5);
            let beyond = index_at(e.point + 1e-9 * e.incoming, 1.5);
            // Near the rim where the ball meets the water's surface the sides are not told by
            // one step: such events are left out.
            let rim = ((e.point - centre).length() - radius).abs() < 1e-6
                && (e.point.z - top).abs() < 1e-6;
            if rim || e.incoming.dot(e.normal).abs() < 1e-6 {
                continue;
            }
            assert_eq!((e.n1, e.n2), (before, beyond), "{e:?}");
            let sine = |d: Vec3| d.cross(e.normal).length();
            if !e.totally_reflected {
                assert!((e.n1 * sine(e.incoming) - e.n2 * sine(e.outgoing)).abs() < 1e-12);
            }
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked}");
    // Down the axis: into the ball from the air, out of it into the water, straight on.
    let down = Ray::new(centre + Vec3::new(0.0, 0.0, 0.1), Vec3::new(0.0, 0.0, -1.0));
    let (_, events) = trace_events(&world, down);
    let faces: Vec<(f64, f64)> = events.iter().map(|e| (e.n1, e.n2)).collect();
    assert_eq!(faces[..2], [(1.0, 1.5), (1.5, 1.333)], "{events:?}");
    assert!(events
        .iter()
        .all(|e| e.outgoing == Vec3::new(0.0, 0.0, -1.0)));
    // A ball of the water's index: only its upper half is a face.
    let (_, events) = trace_events(&world_of(1.333), down);
    assert_eq!(events[0].n1, 1.0);
    assert_eq!(events[0].n2, 1.333);
    assert!(events.iter().skip(1).all(|e| e.point.z < centre.z - radius));
}

/// A prism in air, its corners `corners` seen from above, from height 0.05 to 0.15, of `index`.
fn prism_in_air(corners: &[[f64; 2]], index: f64) -> World {
    let list: Vec<String> = corners
        .iter()
        .map(|c| format!("[{}, {}]", c[0], c[1]))
        .collect();
    let d = scene(&format!(
        "[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n\
         [[prism]]\ncorners = [{}]\nbottom = 0.05\ntop = 0.15\nindex = {index}\n",
        list.join(", ")
    ));
    World::new(&d, 10).expect("a valid scene")
}

/// The angle (radians) of a horizontal direction from `+x`.
fn heading(d: Vec3) -> f64 {
    d.y.atan2(d.x)
}

/// Through a 60° prism at the angle of minimum deviation the ray inside runs parallel to the
/// base, and the deviation is `2·asin(n·sin(A/2)) − A`; any other angle deviates it more.
#[test]
fn a_prism_deviates_least_by_its_closed_form() {
    let h = 0.1 * 3f64.sqrt() / 2.0;
    // Counterclockwise from above, then the other way: the file may list them either way.
    let corners = [[0.3, 0.0], [0.4, 0.0], [0.35, h]];
    let apex = std::f64::consts::PI / 3.0;
    for (n, order) in [(1.5, false), (1.7, true)] {
        let mut c = corners.to_vec();
        if order {
            c.reverse();
        }
        let world = prism_in_air(&c, n);
        let deviation = |i: f64| {
            // Aimed at the middle of the left face, `i` from its normal, from below the normal.
            let mid = Vec3::new(0.325, h / 2.0, 0.1);
            let theta = i - apex / 2.0;
            let d = Vec3::new(theta.cos(), theta.sin(), 0.0);
            let (outcome, events) = trace_events(&world, Ray::new(mid - 0.2 * d, d));
            assert_eq!(events.len(), 2, "in and out: {events:?}");
            let Outcome::Escaped { ray, .. } = outcome else {
                panic!("it leaves the scene")
            };
            (heading(d) - heading(ray.direction), events[0].outgoing)
        };
        let i_min = (n * (apex / 2.0).sin()).asin();
        let (least, inside) = deviation(i_min);
        let closed = 2.0 * i_min - apex;
        assert!((least - closed).abs() < 1e-12, "n {n}: {least} vs {closed}");
        assert!(
            inside.y.abs() < 1e-12 && inside.z == 0.0,
            "parallel to the base: {inside}"
        );
        for di in [-0.05, -0.01, 0.01, 0.05] {
            assert!(deviation(i_min + di).0 > least + 1e-6);
        }
    }
}

/// A glass block shifts a ray sideways by `t·sin(i − r)/cos r` and leaves it parallel to itself.
#[test]
fn a_glass_block_shifts_a_ray_by_its_closed_form() {
    let (t, n) = (0.04, 1.5);
    let world = prism_in_air(
        &[[0.3, -0.05], [0.3 + t, -0.05], [0.3 + t, 0.05], [0.3, 0.05]],
        n,
    );
    for i in [0.1f64, 0.5, 1.0] {
        let d = Vec3::new(i.cos(), i.sin(), 0.0);
        let start = Vec3::new(0.3, 0.0, 0.1) - 0.2 * d;
        let (outcome, events) = trace_events(&world, Ray::new(start, d));
        assert_eq!(events.len(), 2);
        let Outcome::Escaped { ray, .. } = outcome else {
            panic!("it leaves the scene")
        };
        assert!((ray.direction - d).length() < 1e-14);
        let shift = (ray.origin - start).cross(d).length();
        let r = (i.sin() / n).asin();
        let closed = t * (i - r).sin() / r.cos();
        assert!((shift - closed).abs() < 1e-13, "i {i}: {shift} vs {closed}");
    }
}

/// A block standing on the floor of a glass, through the water's surface: every event's indices
/// are the geometry's on its two sides (no water surface inside the block, its bottom on the
/// floor); a block of the water's index keeps only its part above the water.
#[test]
fn a_block_through_the_waters_surface_is_traced_as_its_geometry_says() {
    let (x0, x1, y0, y1, height, top) = (-0.02, 0.0, -0.015, 0.015, 0.13, 0.1);
    let world_of = |index: f64| {
        let d = scene(&format!(
            "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
             [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = {top}\n\n\
             [[straw]]\nx = 0.02\ny = 0.0\n\n\
             [[prism]]\ncorners = [[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}]]\n\
             bottom = 0.0\ntop = {height}\nindex = {index}\n"
        ));
        World::new(&d, 10).expect("a valid scene")
    };
    let index_at = |p: Vec3, block: f64| {
        let in_block =
            (x0..x1).contains(&p.x) && (y0..y1).contains(&p.y) && (0.0..height).contains(&p.z);
        if in_block {
            block
        } else if p.x.hypot(p.y) < 0.04 && (0.0..top).contains(&p.z) {
            1.333
        } else {
            1.0
        }
    };
    for (block, eye) in [
        (1.5, Vec3::new(0.15, 0.1, 0.2)),
        (1.5, Vec3::new(-0.1, 0.05, -0.1)),
        (1.333, Vec3::new(0.12, -0.1, 0.25)),
    ] {
        let world = world_of(block);
        let mut checked = 0;
        for k in 0..800u32 {
            let f = |m: f64| (k as f64 * m).fract() - 0.5;
            let aim = Vec3::new(-0.01, 0.0, 0.07)
                + 0.06 * Vec3::new(f(0.618034), f(0.7548777), f(0.5698403));
            let (_, events) = trace_events(&world, Ray::new(eye, aim - eye));
            for e in events {
                let (before, beyond) = (
                    index_at(e.point - 1e-9 * e.incoming, block),
                    index_at(e.point + 1e-9 * e.incoming, block),
                );
                // Near an edge of two regions the sides are not told by one step.
                let t1 = if e.normal.z.abs() < 0.9 {
                    Vec3::Z
                } else {
                    Vec3::X
                };
                let t1 = e.normal.cross(t1).normalize();
                let t2 = e.normal.cross(t1);
                let near_edge = [t1, -t1, t2, -t2].iter().any(|&t| {
                    index_at(e.point - 1e-9 * e.incoming + 1e-6 * t, block) != before
                        || index_at(e.point + 1e-9 * e.incoming + 1e-6 * t, block) != beyond
                });
                if near_edge || e.incoming.dot(e.normal).abs() < 1e-6 {
                    continue;
                }
                assert_eq!((e.n1, e.n2), (before, beyond), "{e:?}");
                checked += 1;
            }
        }
        assert!(checked > 100, "{checked}");
    }
}

/// A prism's rules: a convex polygon of 3 to 16 corners, its top above its bottom, inside the
/// container above the floor or wholly outside it, clear of the other objects, a card wholly
/// inside or outside, the eye outside.
#[test]
fn a_prisms_shape_and_place_break_no_rule() {
    let base = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
                [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.1\n\n\
                [[straw]]\nx = 0.02\ny = 0.0\n\n";
    let prism = |corners: &str, bottom: f64, top: f64| {
        format!("[[prism]]\ncorners = {corners}\nbottom = {bottom}\ntop = {top}\nindex = 1.5\n")
    };
    let refused = |extra: &str, code: &str| {
        let e = SceneDescription::from_toml(&format!("{base}{extra}")).expect_err(extra);
        assert!(
            e.rules().any(|r| r.rule.code() == code),
            "{extra}: {e} (wanted {code})"
        );
    };
    let outside = "[[0.3, 0.0], [0.4, 0.0], [0.35, 0.08]]";
    refused(&prism("[[0.3, 0.0], [0.4, 0.0]]", 0.0, 0.1), "prism.convex");
    refused(
        &prism(
            "[[0.3, 0.0], [0.4, 0.0], [0.32, 0.02], [0.3, 0.1]]",
            0.0,
            0.1,
        ),
        "prism.convex",
    );
    refused(&prism(outside, 0.1, 0.1), "prism.top");
    refused(
        &prism("[[0.03, 0.0], [0.06, 0.0], [0.05, 0.02]]", 0.0, 0.1),
        "prism.container",
    );
    refused(
        &prism("[[-0.03, -0.01], [0.03, -0.01], [0.0, 0.01]]", 0.0, 0.1),
        "solid.overlap",
    );
    refused(
        &format!(
            "{}[[sphere]]\ncenter = [0.35, 0.03, 0.05]\nradius = 0.01\nindex = 1.5\n",
            prism(outside, 0.0, 0.1)
        ),
        "solid.overlap",
    );
    refused(
        &format!(
            "{}[[card]]\ncenter = [0.35, 0.03, 0.05]\nwidth = 0.2\nheight = 0.02\n",
            prism(outside, 0.0, 0.1)
        ),
        "solid.card",
    );
    refused(
        &format!(
            "{}[observer]\nposition = [0.35, 0.03, 0.05]\n",
            prism(outside, 0.0, 0.1)
        ),
        "observer.in-solid",
    );
    for ok in [
        prism(outside, 0.0, 0.1),
        prism("[[-0.03, -0.01], [-0.01, -0.01], [-0.02, 0.01]]", 0.0, 0.12),
        format!(
            "{}[[card]]\ncenter = [0.35, 0.03, 0.05]\nwidth = 0.01\nheight = 0.01\n",
            prism(outside, 0.0, 0.1)
        ),
    ] {
        let d = scene(&format!("{base}{ok}"));
        assert_eq!(scene(&d.to_toml()), d);
        World::new(&d, 10).expect("a world");
    }
}

/// A lens in air centred at `centre` with optical axis `axis`.
fn lens_in_air(centre: Vec3, axis: Vec3, r1: f64, r2: f64, thickness: f64, index: f64) -> World {
    let d = scene(&format!(
        "[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n\
         [[lens]]\ncenter = [{}, {}, {}]\naxis = [{}, {}, {}]\nradius1 = {r1}\nradius2 = {r2}\n\
         thickness = {thickness}\ndiameter = 0.04\nindex = {index}\n",
        centre.x, centre.y, centre.z, axis.x, axis.y, axis.z
    ));
    World::new(&d, 10).expect("a valid scene")
}

/// The thick lens's back focal distance, from the back vertex: `1/f = (n − 1)[1/R1 − 1/R2 +
/// (n − 1)·d/(n·R1·R2)]` and `BFD = f·(1 − (n − 1)·d/(n·R1))` (a flat face has `1/R = 0`).
fn back_focal_distance(r1: f64, r2: f64, d: f64, n: f64) -> f64 {
    let inv = |r: f64| if r == 0.0 { 0.0 } else { 1.0 / r };
    let power = (n - 1.0) * (inv(r1) - inv(r2) + (n - 1.0) * d * inv(r1) * inv(r2) / n);
    let f = 1.0 / power;
    f * (1.0 - (n - 1.0) * d * inv(r1) / n)
}

/// A paraxial ray parallel to a lens's axis crosses it (or seems to come from it, for a
/// diverging lens) at the back focal distance the lensmaker's formula with thickness gives:
/// biconvex, plano-convex (face 1 flat, then turned round: face 2 flat), a positive meniscus and
/// a biconcave lens; along `+x` and along a slanted axis.
#[test]
fn a_lens_focuses_at_the_lensmakers_back_focal_distance() {
    let centre = Vec3::new(0.3, 0.0, 0.2);
    for (r1, r2, d, n) in [
        (0.05, -0.05, 0.01, 1.5),
        (0.0, -0.04, 0.008, 1.5),
        (0.04, 0.0, 0.008, 1.6),
        (0.03, 0.06, 0.008, 1.5),
        (-0.05, 0.05, 0.004, 1.5),
    ] {
        let world = lens_in_air(centre, Vec3::X, r1, r2, d, n);
        let h = 1e-6;
        let ray = Ray::new(centre + Vec3::new(-0.2, h, 0.0), Vec3::X);
        let (outcome, events) = trace_events(&world, ray);
        assert_eq!(events.len(), 2, "({r1}, {r2}): {events:?}");
        let Outcome::Escaped { ray: out, .. } = outcome else {
            panic!("it leaves the scene")
        };
        let bfd = axis_crossing(out, centre) - d / 2.0;
        let closed = back_focal_distance(r1, r2, d, n);
        assert!(
            (bfd - closed).abs() < 1e-9 * closed.abs().max(1.0),
            "({r1}, {r2}, {d}, {n}): {bfd} vs {closed}"
        );
    }
    // The same biconvex lens along a slanted axis.
    let axis = Vec3::new(1.0, -2.0, 0.5).normalize();
    let world = lens_in_air(centre, axis, 0.05, -0.05, 0.01, 1.5);
    let side = axis.any_orthonormal_vector();
    let h = 1e-4;
    let ray = Ray::new(centre - 0.2 * axis + h * side, axis);
    let Outcome::Escaped { ray: out, .. } = world.trace(ray) else {
        panic!("it leaves the scene")
    };
    // Where the ray's line comes closest to the axis, along the axis from the back vertex.
    let w = out.origin - centre;
    let (b, dd, e) = (out.direction.dot(axis), out.direction.dot(w), axis.dot(w));
    let s = (b * e - dd) / (1.0 - b * b);
    let along = (out.at(s) - centre).dot(axis) - 0.005;
    let closed = back_focal_distance(0.05, -0.05, 0.01, 1.5);
    assert!((along - closed).abs() < 1e-6, "{along} vs {closed}");
}

/// A lens's rules: its axis a direction, each curved face's radius at least half its diameter,
/// its faces apart across the whole diameter, its place inside the container (through any
/// liquid's surface) or outside it; the eye outside it.
#[test]
fn a_lenss_shape_and_place_break_no_rule() {
    let base = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
                [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.1\n\n";
    let lens = |c: [f64; 3], axis: [f64; 3], r1: f64, r2: f64, t: f64, d: f64| {
        format!(
            "[[lens]]\ncenter = [{}, {}, {}]\naxis = [{}, {}, {}]\nradius1 = {r1}\nradius2 = {r2}\n\
             thickness = {t}\ndiameter = {d}\nindex = 1.5\n",
            c[0], c[1], c[2], axis[0], axis[1], axis[2]
        )
    };
    let refused = |extra: &str, code: &str| {
        let e = SceneDescription::from_toml(&format!("{base}{extra}")).expect_err(extra);
        assert!(
            e.rules().any(|r| r.rule.code() == code),
            "{extra}: {e} (wanted {code})"
        );
    };
    let out = [0.3, 0.0, 0.1];
    refused(
        &lens(out, [0.0, 0.0, 0.0], 0.05, -0.05, 0.01, 0.04),
        "lens.axis",
    );
    refused(
        &lens(out, [1.0, 0.0, 0.0], 0.015, -0.05, 0.01, 0.04),
        "lens.radius",
    );
    refused(
        &lens(out, [1.0, 0.0, 0.0], 0.025, -0.025, 0.004, 0.04),
        "lens.faces",
    );
    refused(
        &lens([0.05, 0.0, 0.1], [1.0, 0.0, 0.0], 0.05, -0.05, 0.01, 0.04),
        "lens.place",
    );
    refused(
        &format!(
            "{}[observer]\nposition = [0.3, 0.0, 0.1]\n",
            lens(out, [1.0, 0.0, 0.0], 0.05, -0.05, 0.01, 0.04)
        ),
        "observer.in-solid",
    );
    for ok in [
        lens(out, [1.0, 0.0, 0.0], 0.05, -0.05, 0.01, 0.04),
        lens(out, [0.0, 0.0, 1.0], 0.0, 0.0, 0.01, 0.04),
        lens([0.0, 0.0, 0.05], [1.0, 1.0, 0.0], 0.05, -0.05, 0.006, 0.03),
        // Through the water's surface.
        lens([0.0, 0.0, 0.1], [1.0, 0.0, 0.0], 0.05, -0.05, 0.01, 0.03),
    ] {
        let d = scene(&format!("{base}{ok}"));
        assert_eq!(scene(&d.to_toml()), d);
        World::new(&d, 10).expect("a world");
    }
}

/// The eye model through a magnifying glass: a point on the axis inside the focal length of a
/// thick biconvex lens is seen where Gauss's lens equation puts its virtual image, measured from
/// the lens's principal planes (`1/s' − 1/s = 1/f`), magnified `s'/s` times; points near the
/// axis as far beside the axis's image as the magnification says (farther out the lens's field
/// curvature and astigmatism move them, as exact rays through it do: half a millimetre off the
/// axis the eye sees the point midway between its two focal lines, 0.12 mm nearer the lens).
#[test]
fn the_eye_model_sees_through_a_magnifying_glass_where_gauss_says() {
    let (r1, r2, d, n) = (0.05, -0.05, 0.01, 1.5);
    let centre = Vec3::new(0.3, 0.0, 0.2);
    let object = Vec3::new(0.27, 0.0, 0.2);
    let text = format!(
        "[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n\
         [[lens]]\ncenter = [{}, {}, {}]\naxis = [1, 0, 0]\nradius1 = {r1}\nradius2 = {r2}\n\
         thickness = {d}\ndiameter = 0.04\nindex = {n}\n\n\
         [[card]]\ncenter = [{}, {}, {}]\nfacing = 0\nwidth = 0.004\nheight = 0.004\npicture = \"none\"\n",
        centre.x, centre.y, centre.z, object.x, object.y, object.z
    );
    let world = World::new(&scene(&text), 10).expect("a valid scene");
    // Gauss: the focal length, the principal planes, the image.
    let f = 1.0 / ((n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * d / (n * r1 * r2)));
    let front = centre.x - d / 2.0 - f * (n - 1.0) * d / (n * r2);
    let back = centre.x + d / 2.0 - f * (n - 1.0) * d / (n * r1);
    let s = object.x - front;
    let s_image = 1.0 / (1.0 / f + 1.0 / s);
    let image = back + s_image;
    let magnification = s_image / s;
    assert!(
        s_image < 0.0 && magnification > 1.0,
        "a virtual, upright, magnified image"
    );
    let eye = Vec3::new(1.3, 0.0, 0.2);
    let cloud = sample_image(&world, eye, 20_000, &|_| {});
    let near: Vec<_> = cloud
        .points
        .iter()
        .filter(|p| (p.straw_point - object).length() < 6e-5)
        .copied()
        .collect();
    assert!(
        !near.is_empty(),
        "the card's middle is seen through the lens"
    );
    for a in eye_model_points(&world, eye, &near) {
        let p = a.position.expect("placed");
        let off = a.image.straw_point - object;
        // Where the lens puts this point: on the axis's image plane, `m` times as far off it.
        let expected = Vec3::new(
            image,
            magnification * off.y,
            centre.z + magnification * off.z,
        );
        assert!(
            (p - expected).length() < 2e-6,
            "seen at {p}, Gauss puts it at {expected}"
        );
    }
}

/// A lens standing through the water's surface, of the water's own index: below the surface it
/// vanishes (no event on its faces there), above it is a lens in air (a ray through it bends at
/// both faces, as the same lens in air bends it), and the water's surface has a hole of its
/// shape (a ray falling through the lens meets no water surface inside it).
#[test]
fn a_lens_through_the_waters_surface_is_a_lens_above_and_vanishes_below() {
    let (top, centre) = (0.1, Vec3::new(0.0, 0.0, 0.1));
    let lens = "[[lens]]\ncenter = [0.0, 0.0, 0.1]\naxis = [1.0, 0.0, 0.0]\nradius1 = 0.05\n\
                radius2 = -0.05\nthickness = 0.01\ndiameter = 0.03\nindex = 1.333\n";
    let half = World::new(
        &scene(&format!(
            "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
             [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = {top}\n\n{lens}"
        )),
        10,
    )
    .expect("a lens through the surface");
    let in_air = lens_in_air(centre, Vec3::X, 0.05, -0.05, 0.01, 1.333);
    let on_lens = |e: &Event| {
        let v = e.point - centre;
        v.x.abs() < 0.02 && v.y.hypot(v.z) <= 0.015 + 1e-12
    };
    // Below the surface, across the lens: only the glass's walls, never the lens.
    for z in [0.09, 0.095, 0.0995] {
        let (_, events) = trace_events(&half, Ray::new(Vec3::new(-0.3, 0.002, z), Vec3::X));
        assert_eq!(events.len(), 2, "at z = {z}: {events:?}");
        assert!(events.iter().all(|e| !on_lens(e)), "{events:?}");
    }
    // Above it, through the lens: its two faces, bent exactly as by the lens in air.
    for (y, z) in [(0.003, 0.104), (-0.006, 0.11), (0.0, 0.1005)] {
        let ray = Ray::new(Vec3::new(-0.3, y, z), Vec3::X);
        let (_, events) = trace_events(&half, ray);
        let (_, alone) = trace_events(&in_air, ray);
        let through: Vec<&Event> = events.iter().filter(|e| on_lens(e)).collect();
        assert_eq!(through.len(), 2, "at ({y}, {z}): {events:?}");
        for (e, f) in through.iter().zip(&alone) {
            assert!((e.point - f.point).length() < 1e-12, "{e:?} {f:?}");
            assert!((e.outgoing - f.outgoing).length() < 1e-12);
        }
    }
    // Falling through the lens: it enters the lens's rim from the air, then meets nothing until
    // the glass's floor (no water surface inside the lens, no face of the lens below it).
    let (_, events) = trace_events(&half, Ray::new(Vec3::new(0.001, 0.002, 0.3), -Vec3::Z));
    assert!(on_lens(&events[0]) && events[0].n1 == 1.0 && events[0].n2 == 1.333);
    assert!(events[1].point.z < 1e-12, "{events:?}");
    // Beside the lens, the same ray meets the water's surface.
    let (_, events) = trace_events(&half, Ray::new(Vec3::new(0.001, 0.025, 0.3), -Vec3::Z));
    assert!((events[0].point.z - top).abs() < 1e-15, "{events:?}");
}
