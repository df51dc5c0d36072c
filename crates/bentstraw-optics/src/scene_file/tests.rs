//! Every rule of a scene file refused with its key and value, the defaults, the straw's foot, and
//! the round trip through TOML.

use super::*;

/// The assignment's glass with water to 0.15 and `rest` appended.
fn glass_with(rest: &str) -> String {
    format!(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n\n[[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.15\n{rest}"
    )
}

/// The message refusing `text`, after checking that it names `key` and quotes `value`.
fn refused(text: &str, key: &str, value: &str) -> String {
    let e = SceneDescription::from_toml(text).expect_err("the file must be refused");
    assert!(
        e.message.contains(key),
        "the message should name {key}: {}",
        e.message
    );
    assert!(
        e.message.contains(value),
        "the message should quote {value}: {}",
        e.message
    );
    assert!(!e.message.contains('\n'), "one line: {}", e.message);
    e.message
}

fn parsed(text: &str) -> SceneDescription {
    SceneDescription::from_toml(text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

#[test]
fn defaults_are_applied_to_the_optional_keys() {
    let d = parsed(&glass_with(
        "[[straw]]\nx = 0.0\ny = 0.0\n[[coin]]\nx = 0.02\ny = 0.0\n[[card]]\ncenter = [-0.2, 0, 0.1]\nwidth = 0.1\nheight = 0.05\n",
    ));
    let Container::Glass(g) = d.container else {
        panic!("a glass")
    };
    assert_eq!((g.wall, g.bottom, g.index), (0.0, 0.0, 1.5));
    let s = d.straws[0];
    assert_eq!(
        (s.tilt_deg, s.azimuth_deg, s.radius, s.length),
        (0.0, 0.0, 0.005, 0.25)
    );
    assert_eq!((d.coins[0].radius, d.coins[0].thickness), (0.0115, 0.0019));
    assert_eq!(d.cards[0].facing_deg, 0.0);
    assert_eq!(d.cards[0].picture, Picture::Arrow);
    assert_eq!(d.observer, None);
}

#[test]
fn an_empty_glass_is_allowed_and_is_the_assignment_scene_without_water() {
    let d = parsed(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n[[straw]]\nx = 0.01\ny = 0.0\n",
    );
    assert!(d.liquids.is_empty());
    let scene = d
        .spec_scene()
        .expect("an empty glass of the assignment's size");
    assert_eq!(scene.water_height(), 0.0);
    assert_eq!((scene.straw_x(), scene.straw_y()), (0.01, 0.0));
}

#[test]
fn an_unknown_key_is_refused_with_its_table_and_line() {
    let m = refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\ncolour = 3\n",
        "container",
        "colour",
    );
    assert!(m.contains("line 5"), "{m}");
    refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\nlean = 3\n"),
        "straw[1]",
        "lean",
    );
    refused(&glass_with("[lid]\nheight = 1\n"), "", "lid");
}

#[test]
fn a_missing_required_value_is_named_by_its_path() {
    let m = refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\n[[straw]]\nx = 0.02\n"),
        "straw[2].y",
        "missing",
    );
    assert!(m.contains("required"), "{m}");
    refused("[[straw]]\nx = 0\ny = 0\n", "container", "missing");
    refused(
        "[container]\nshape = \"glass\"\nheight = 0.2\n",
        "container.radius",
        "missing",
    );
    refused(
        "[container]\nshape = \"tank\"\nhalf_x = 0.1\nheight = 0.2\n",
        "container.half_y",
        "missing",
    );
}

#[test]
fn a_wrong_type_is_refused_with_its_line_and_key() {
    let m = refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\ntilt = \"15\"\n"),
        "straw[1].tilt",
        "\"15\"",
    );
    assert!(m.contains("line 13"), "{m}");
    let e = SceneDescription::from_toml(&glass_with("[[straw]]\nx = 0\ny = 0\ntilt = \"15\"\n"))
        .unwrap_err();
    assert_eq!((e.key.as_str(), e.line), ("straw[1].tilt", Some(13)));
    refused(
        &glass_with("[observer]\nposition = [1, 0]\ntarget = [0, 0, 0]\n"),
        "observer.position",
        "2",
    );
}

#[test]
fn a_syntax_error_is_one_line_with_its_line_number() {
    let m = refused(
        "[container]\nshape = \"glass\"\nradius = \nheight = 0.2\n",
        "line 3",
        "",
    );
    assert!(!m.contains('\n'));
}

#[test]
fn non_finite_numbers_are_refused() {
    refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\ntilt = nan\n"),
        "straw[1].tilt",
        "NaN",
    );
    refused(
        &glass_with("[[straw]]\nx = inf\ny = 0\n"),
        "straw[1].x",
        "inf",
    );
    refused(
        &glass_with("[observer]\nposition = [1, 0, -inf]\ntarget = [0, 0, 0]\n"),
        "observer.position",
        "-inf",
    );
    refused(
        &glass_with("[[card]]\ncenter = [nan, 0, 0]\nwidth = 1\nheight = 1\n"),
        "card[1].center",
        "NaN",
    );
}

#[test]
fn sizes_must_be_positive() {
    refused(
        "[container]\nshape = \"glass\"\nradius = 0\nheight = 0.2\n",
        "container.radius",
        "= 0",
    );
    refused(
        "[container]\nshape = \"tank\"\nhalf_x = 0.1\nhalf_y = -0.05\nheight = 0.2\n",
        "container.half_y",
        "-0.05",
    );
    refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\nradius = -0.001\n"),
        "straw[1].radius",
        "-0.001",
    );
    refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\nlength = 0\n"),
        "straw[1].length",
        "0",
    );
    refused(
        &glass_with("[[coin]]\nx = 0\ny = 0\nthickness = 0\n"),
        "coin[1].thickness",
        "0",
    );
    refused(
        &glass_with("[[card]]\ncenter = [-0.2, 0, 0]\nwidth = 0\nheight = 1\n"),
        "card[1].width",
        "0",
    );
    refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\nwall = -0.001\n",
        "container.wall",
        "-0.001",
    );
}

#[test]
fn a_wall_as_thick_as_the_radius_or_a_bottom_as_high_as_the_walls_is_refused() {
    refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\nwall = 0.04\n",
        "container.wall",
        "0.04",
    );
    refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\nbottom = 0.2\n",
        "container.bottom",
        "0.2",
    );
}

#[test]
fn the_shape_must_be_glass_tank_or_revolution() {
    let m = refused(
        "[container]\nshape = \"cube\"\nradius = 0.04\nheight = 0.2\n",
        "container.shape",
        "\"cube\"",
    );
    assert!(m.contains("\"glass\", \"tank\" or \"revolution\""), "{m}");
}

#[test]
fn the_keys_of_the_other_shape_are_refused() {
    refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nhalf_x = 0.1\nheight = 0.2\n",
        "container.half_x",
        "0.1",
    );
    refused(
        "[container]\nshape = \"tank\"\nradius = 0.04\nhalf_x = 0.1\nhalf_y = 0.1\nheight = 0.2\n",
        "container.radius",
        "0.04",
    );
}

#[test]
fn a_tank_has_no_wall_bottom_or_index() {
    let tank = "[container]\nshape = \"tank\"\nhalf_x = 0.1\nhalf_y = 0.05\nheight = 0.2\n";
    refused(&format!("{tank}wall = 0.003\n"), "container.wall", "0.003");
    refused(
        &format!("{tank}bottom = 0.01\n"),
        "container.bottom",
        "0.01",
    );
    refused(&format!("{tank}index = 1.5\n"), "container.index", "1.5");
}

#[test]
fn indices_below_one_are_refused() {
    refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n[[liquid]]\nname = \"w\"\nindex = 0.9\ntop = 0.1\n",
        "liquid[1].index",
        "0.9",
    );
    refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\nindex = 0.5\n",
        "container.index",
        "0.5",
    );
}

#[test]
fn liquid_tops_must_rise_strictly_above_the_floor_and_not_above_the_walls() {
    let m = refused(
        &glass_with("[[liquid]]\nname = \"oil\"\nindex = 1.47\ntop = 0.15\n"),
        "liquid[2].top",
        "0.15",
    );
    assert!(m.contains("layer below"), "{m}");
    refused(
        &glass_with("[[liquid]]\nname = \"oil\"\nindex = 1.47\ntop = 0.12\n"),
        "liquid[2].top",
        "0.12",
    );
    refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n[[liquid]]\nname = \"w\"\nindex = 1.3\ntop = 0.25\n",
        "liquid[1].top",
        "0.25",
    );
    // The floor of a glass with a thick bottom is at z = bottom: a top there holds no liquid.
    let m = refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\nbottom = 0.01\n[[liquid]]\nname = \"w\"\nindex = 1.3\ntop = 0.01\n",
        "liquid[1].top",
        "0.01",
    );
    assert!(m.contains("floor"), "{m}");
}

#[test]
fn the_tilt_must_be_in_0_to_90_degrees() {
    refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\ntilt = 90\n"),
        "straw[1].tilt",
        "90",
    );
    refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\ntilt = -1\n"),
        "straw[1].tilt",
        "-1",
    );
}

#[test]
fn a_straw_whose_foot_is_off_the_floor_is_refused() {
    let m = refused(
        &glass_with("[[straw]]\nx = 0.05\ny = 0\n"),
        "straw[1]",
        "0.05",
    );
    assert!(m.contains("foot"), "{m}");
}

#[test]
fn an_upright_straw_touching_the_wall_fits_and_one_past_it_pierces_it() {
    // The assignment's own rule, sqrt(x² + y²) + radius <= glass radius, at its edge.
    parsed(&glass_with("[[straw]]\nx = 0.035\ny = 0\n"));
    let m = refused(
        &glass_with("[[straw]]\nx = 0.036\ny = 0\n"),
        "straw[1]",
        "0.036",
    );
    assert!(m.contains("pierces"), "{m}");
}

#[test]
fn a_straw_in_a_tank_must_not_pierce_its_walls() {
    let tank = "[container]\nshape = \"tank\"\nhalf_x = 0.1\nhalf_y = 0.05\nheight = 0.2\n";
    parsed(&format!("{tank}[[straw]]\nx = 0.095\ny = -0.045\n"));
    refused(
        &format!("{tank}[[straw]]\nx = 0.095\ny = 0.046\n"),
        "straw[1]",
        "pierces",
    );
    // Leaning 30° towards +x from x = 0.05, a 0.22 m pencil reaches x ≈ 0.16 at z ≈ 0.19,
    // below the rim: through the wall. Leaning towards +y it hits the near wall sooner.
    refused(
        &format!("{tank}[[straw]]\nx = 0.05\ny = 0\ntilt = 30\nlength = 0.22\nradius = 0.0035\n"),
        "straw[1]",
        "pierces",
    );
    refused(
        &format!("{tank}[[straw]]\nx = -0.06\ny = 0\ntilt = 30\nazimuth = 90\nlength = 0.22\nradius = 0.0035\n"),
        "straw[1]",
        "pierces",
    );
    parsed(&format!(
        "{tank}[[straw]]\nx = -0.06\ny = 0\ntilt = 30\nlength = 0.22\nradius = 0.0035\n"
    ));
}

/// Where a straw's side is farthest out at height `z` along its lean, when its whole
/// cross-section there is an ellipse: the axis's point plus the semi-axis `radius / cos(tilt)`.
fn outermost_at(x: f64, tilt_deg: f64, radius: f64, floor: f64, z: f64) -> f64 {
    let t = tilt_deg.to_radians();
    x + (z - floor - radius * t.sin()) * t.tan() + radius / t.cos()
}

#[test]
fn a_leaning_straw_fits_just_below_the_rim_and_pierces_just_past_it() {
    // Leaning towards +x, its side reaches the rim's height at x = outermost_at(...): place it
    // 1 µm inside the wall and 1 µm through it.
    for (tilt, azimuth) in [(15.0, 0.0), (10.0, 45.0), (15.0, 90.0), (15.0, 180.0)] {
        let reach = outermost_at(0.0, tilt, 0.005, 0.0, 0.2);
        let (c, s) = (
            f64::to_radians(azimuth).cos(),
            f64::to_radians(azimuth).sin(),
        );
        for (offset, fits) in [(-1e-6, true), (1e-6, false)] {
            let along = 0.04 - reach + offset;
            let text = glass_with(&format!(
                "[[straw]]\nx = {}\ny = {}\ntilt = {tilt}\nazimuth = {azimuth}\n",
                along * c,
                along * s
            ));
            let result = SceneDescription::from_toml(&text);
            assert_eq!(
                result.is_ok(),
                fits,
                "tilt {tilt} azimuth {azimuth} offset {offset}: {result:?}"
            );
        }
    }
}

#[test]
fn a_tilted_straw_rests_on_the_floor_at_its_lowest_rim_point() {
    for (tilt, azimuth, floor) in [(0.0, 0.0, 0.0), (15.0, 30.0, 0.008), (60.0, 200.0, 0.002)] {
        let s = Straw {
            x: 0.01,
            y: -0.02,
            tilt_deg: tilt,
            azimuth_deg: azimuth,
            radius: 0.005,
            length: 0.25,
        };
        let (t, a) = (f64::to_radians(tilt), f64::to_radians(azimuth));
        let c = s.bottom_centre(floor);
        assert!((c.z - (floor + 0.005 * t.sin())).abs() < 1e-15, "{c}");
        assert_eq!((c.x, c.y), (0.01, -0.02));
        // The foot is on the floor, displaced towards the lean by radius·cos(tilt).
        let foot = s.foot(floor);
        assert!((foot.z - floor).abs() < 1e-15, "{foot}");
        assert!((foot.x - (0.01 + 0.005 * t.cos() * a.cos())).abs() < 1e-15);
        assert!((foot.y - (-0.02 + 0.005 * t.cos() * a.sin())).abs() < 1e-15);
        // No point of the rim is below the floor: the rim is the circle about the axis.
        let axis = s.axis();
        assert!((axis.length() - 1.0).abs() < 1e-15);
        let helper = if axis.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
        let e1 = axis.cross(helper).normalize();
        let e2 = axis.cross(e1);
        for k in 0..360 {
            let phi = f64::to_radians(k as f64);
            let p = c + 0.005 * (phi.cos() * e1 + phi.sin() * e2);
            assert!(
                p.z >= floor - 1e-15,
                "rim point {p} below the floor {floor}"
            );
        }
    }
}

#[test]
fn straws_and_coins_must_not_overlap_on_the_floor() {
    let m = refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\n[[straw]]\nx = 0.009\ny = 0\n"),
        "straw[2]",
        "0.009",
    );
    assert!(m.contains("straw[1]"), "{m}");
    parsed(&glass_with(
        "[[straw]]\nx = 0\ny = 0\n[[straw]]\nx = 0.01\ny = 0\n",
    ));
    refused(
        &glass_with("[[straw]]\nx = 0.015\ny = 0\n[[coin]]\nx = 0\ny = 0\n"),
        "coin[1]",
        "0.015",
    );
    refused(
        &glass_with("[[coin]]\nx = -0.012\ny = 0\n[[coin]]\nx = 0.01\ny = 0\n"),
        "coin[2]",
        "0.022",
    );
}

#[test]
fn straws_leaning_into_each_other_cross_and_are_refused() {
    // Feet 24 mm apart (footprints clear), leaning 5° towards each other: their axes meet at
    // z ≈ 0.137, inside the straws' length.
    let m = refused(
        &glass_with(
            "[[straw]]\nx = -0.012\ny = 0\ntilt = 5\n[[straw]]\nx = 0.012\ny = 0\ntilt = 5\nazimuth = 180\n",
        ),
        "straw[2]",
        "crosses straw[1]",
    );
    assert!(m.contains("0.01"), "{m}");
    // Leaning away from each other they are clear.
    parsed(&glass_with(
        "[[straw]]\nx = -0.012\ny = 0\ntilt = 5\nazimuth = 180\n[[straw]]\nx = 0.012\ny = 0\ntilt = 5\n",
    ));
}

#[test]
fn the_distance_between_segments_is_exact_in_known_cases() {
    let v = Vec3::new;
    // Crossing at right angles 0.3 apart; parallel and overlapping 0.2 apart; end to end 0.5.
    let cases = [
        (
            v(-1.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.0, -1.0, 0.3),
            v(0.0, 1.0, 0.3),
            0.3,
        ),
        (
            v(0.0, 0.0, 0.0),
            v(0.0, 0.0, 1.0),
            v(0.2, 0.0, 0.5),
            v(0.2, 0.0, 2.0),
            0.2,
        ),
        (
            v(0.0, 0.0, 0.0),
            v(0.0, 0.0, 1.0),
            v(0.0, 0.0, 1.5),
            v(0.0, 0.0, 2.0),
            0.5,
        ),
        (
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(2.0, 1.0, 0.0),
            v(3.0, 5.0, 0.0),
            2f64.sqrt(),
        ),
    ];
    for (p1, q1, p2, q2, want) in cases {
        for (a, b, c, d) in [(p1, q1, p2, q2), (q2, p2, q1, p1)] {
            let got = segment_distance(a, b, c, d);
            assert!((got - want).abs() < 1e-15, "{got} != {want}");
        }
    }
}

#[test]
fn a_straw_leaning_low_over_a_coin_is_refused() {
    // Leaning 80° towards +x from x = -0.03 (in a wide tank), its underside rises from the foot
    // at x ≈ -0.0291 by 1 mm per 5.67 mm (tan 80°): it is below the coin's top (1.9 mm) until
    // x ≈ -0.0184. A coin whose edge is 3 mm before that is under it; 2 mm after, it is clear.
    // Their footprints (circles about the cap's centre and the coin's) are clear in both.
    let tank = "[container]\nshape = \"tank\"\nhalf_x = 0.5\nhalf_y = 0.5\nheight = 0.2\n";
    let straw = "[[straw]]\nx = -0.03\ny = 0\ntilt = 80\nlength = 0.1\n";
    let t = f64::to_radians(80.0);
    let foot = -0.03 + 0.005 * t.cos();
    let clear_of_coin_top = foot + 0.0019 * t.tan();
    for (edge, fits) in [
        (clear_of_coin_top - 3e-3, false),
        (clear_of_coin_top + 2e-3, true),
    ] {
        let text = format!("{tank}{straw}[[coin]]\nx = {}\ny = 0\n", edge + 0.0115);
        let result = SceneDescription::from_toml(&text);
        assert_eq!(result.is_ok(), fits, "coin edge at {edge}: {result:?}");
        if !fits {
            let m = result.unwrap_err().message;
            assert!(
                m.contains("coin[1]") && m.contains("straw[1] leans on it"),
                "{m}"
            );
        }
    }
}

#[test]
fn the_distance_to_a_convex_hull_is_exact_in_known_cases() {
    let square = [
        (0.0, 0.0),
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (0.5, 0.5),
        (0.2, 0.9),
    ];
    assert_eq!(distance_to_hull((0.5, 0.5), &square), 0.0);
    assert_eq!(distance_to_hull((0.5, 2.0), &square), 1.0);
    assert_eq!(distance_to_hull((-3.0, -4.0), &square), 5.0);
    assert_eq!(distance_to_hull((3.0, 0.5), &square[..2]), 2f64.hypot(0.5));
}

#[test]
fn a_coin_must_lie_inside_the_walls() {
    refused(
        &glass_with("[[coin]]\nx = 0.03\ny = 0\n"),
        "coin[1]",
        "0.03",
    );
}

#[test]
fn a_card_must_not_cut_through_the_container() {
    refused(
        &glass_with(
            "[[card]]\ncenter = [-0.03, 0, 0.1]\nfacing = 0\nwidth = 0.12\nheight = 0.06\n",
        ),
        "card[1]",
        "-0.03",
    );
    // Facing +y, it spans x from -0.11 to 0.01 at y = 0.035: within the glass's radius.
    refused(
        &glass_with(
            "[[card]]\ncenter = [-0.05, 0.035, 0.1]\nfacing = 90\nwidth = 0.12\nheight = 0.06\n",
        ),
        "card[1]",
        "0.035",
    );
    // The same card 1 cm farther out, or wholly above the rim, is clear.
    parsed(&glass_with(
        "[[card]]\ncenter = [-0.05, 0.045, 0.1]\nfacing = 90\nwidth = 0.12\nheight = 0.06\n",
    ));
    parsed(&glass_with(
        "[[card]]\ncenter = [0, 0, 0.3]\nwidth = 0.12\nheight = 0.06\n",
    ));
    let tank = "[container]\nshape = \"tank\"\nhalf_x = 0.1\nhalf_y = 0.05\nheight = 0.2\n";
    refused(
        &format!(
            "{tank}[[card]]\ncenter = [0, 0.06, 0.1]\nfacing = 45\nwidth = 0.1\nheight = 0.06\n"
        ),
        "card[1]",
        "0.06",
    );
    parsed(&format!(
        "{tank}[[card]]\ncenter = [0, 0.06, 0.1]\nfacing = 90\nwidth = 0.1\nheight = 0.06\n"
    ));
}

#[test]
fn the_picture_must_be_arrow_or_none() {
    refused(
        &glass_with(
            "[[card]]\ncenter = [-0.2, 0, 0.1]\nwidth = 0.1\nheight = 0.05\npicture = \"circle\"\n",
        ),
        "card[1].picture",
        "\"circle\"",
    );
}

#[test]
fn the_observer_must_be_outside_the_container_and_the_straws() {
    refused(
        &glass_with("[observer]\nposition = [0.01, 0, 0.1]\ntarget = [0, 0, 0]\n"),
        "observer.position",
        "0.01",
    );
    let tank = "[container]\nshape = \"tank\"\nhalf_x = 0.1\nhalf_y = 0.05\nheight = 0.2\n";
    refused(
        &format!("{tank}[observer]\nposition = [0.09, 0.04, 0.0]\ntarget = [0, 0, 0]\n"),
        "observer.position",
        "0.09",
    );
    // In the straw where it sticks out above the rim, leaning or not.
    let m = refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\n[observer]\nposition = [0.001, 0, 0.22]\ntarget = [0, 0, 0]\n"),
        "observer.position",
        "0.22",
    );
    assert!(m.contains("straw[1]"), "{m}");
    let reach = 0.21 * f64::to_radians(15.0).tan();
    refused(
        &glass_with(&format!(
            "[[straw]]\nx = -0.019\ny = 0\ntilt = 15\n[observer]\nposition = [{}, 0, 0.21]\ntarget = [0, 0, 0]\n",
            -0.019 + reach
        )),
        "observer.position",
        "straw[1]",
    );
    refused(
        &glass_with("[observer]\nposition = [0.1, 0, 0.1]\ntarget = [0.1, 0, 0.1]\n"),
        "observer.target",
        "0.1",
    );
}

#[test]
fn too_many_layers_or_objects_are_refused_at_once() {
    let coins: String = (0..=MAX_OBJECTS)
        .map(|_| "[[coin]]\nx = 0\ny = 0\n")
        .collect();
    refused(&glass_with(&coins), "straw, coin, card", "101 objects");
    let layers: String = (1..=MAX_LIQUIDS + 1)
        .map(|k| {
            format!(
                "[[liquid]]\nname = \"l{k}\"\nindex = 1.3\ntop = {}\n",
                0.001 * k as f64
            )
        })
        .collect();
    let text =
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n".to_string() + &layers;
    refused(&text, "liquid", "33 layers");
}

#[test]
fn many_leaning_straws_beside_coins_pass_and_a_coin_under_one_does_not() {
    // Well apart: no pair overlaps, so every pair is looked at (the far ones only by their
    // distance, which must never skip a pair that meets).
    let mut text =
        String::from("[container]\nshape = \"tank\"\nhalf_x = 2\nhalf_y = 2\nheight = 0.3\n");
    for k in 0..50 {
        let y = -1.8 + 0.072 * k as f64;
        text += &format!(
            "[[straw]]\nx = 0\ny = {y}\ntilt = 80\nlength = 0.1\n[[coin]]\nx = 1\ny = {y}\n"
        );
    }
    let scene = SceneDescription::from_toml(&text).unwrap();
    assert_eq!((scene.straws.len(), scene.coins.len()), (50, 50));
    // A coin 3 mm under the first straw's low end (see the test of a straw leaning low over a
    // coin): refused.
    let t = f64::to_radians(80.0);
    let under_x = 0.005 * t.cos() + 0.0019 * t.tan() - 3e-3 + 0.0115;
    let under = text.replacen(
        "[[coin]]\nx = 1\ny = -1.8\n",
        &format!("[[coin]]\nx = {under_x}\ny = -1.8\n"),
        1,
    );
    refused(&under, "coin[1]", "straw[1] leans on it");
}

#[test]
fn numbers_that_would_lose_the_objects_are_refused() {
    refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\ntilt = 1e-160\n"),
        "straw[1].tilt",
        "write tilt = 0",
    );
    refused(
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 1e155\n",
        "container.height",
        "between",
    );
    refused(
        &glass_with("[[straw]]\nx = 0\ny = 0\nradius = 1e-200\n"),
        "straw[1].radius",
        "between",
    );
    refused(
        &glass_with("[[straw]]\nx = 2e6\ny = 0\n"),
        "straw[1].x",
        "at most",
    );
    // An eye on a card sees from inside it.
    refused(
        &glass_with(
            "[[card]]\ncenter = [0, -0.1, 0.1]\nfacing = 90\nwidth = 0.1\nheight = 0.1\n\n[observer]\nposition = [0.01, -0.1, 0.12]\ntarget = [0, 0, 0.1]\n",
        ),
        "observer.position",
        "card[1]",
    );
}

#[test]
fn the_assignment_scene_is_recognised_and_anything_else_is_named() {
    let spec = glass_with("[[straw]]\nx = 0.02\ny = 0.01\n");
    assert_eq!(
        parsed(&spec).spec_scene(),
        Some(Scene::with_defaults(0.02, 0.01, 0.15).unwrap())
    );
    for (extra, words) in [
        ("[[straw]]\nx = -0.019\ny = 0\ntilt = 15\n", "a straw tilted 15°"),
        ("[[straw]]\nx = 0.02\ny = 0.01\nradius = 0.004\n", "a straw of radius 0.004 m"),
        ("[[straw]]\nx = 0.02\ny = 0.01\nlength = 0.2\n", "a straw 0.2 m long"),
        ("[[straw]]\nx = 0.02\ny = 0.01\n[[straw]]\nx = -0.02\ny = 0\n", "2 straws"),
        ("[[straw]]\nx = 0.02\ny = 0.01\n[[coin]]\nx = -0.02\ny = 0\n", "a coin"),
        (
            "[[straw]]\nx = 0.02\ny = 0.01\n[[card]]\ncenter = [-0.2, 0, 0.1]\nwidth = 0.1\nheight = 0.05\n",
            "a card",
        ),
        (
            "[[liquid]]\nname = \"oil\"\nindex = 1.47\ntop = 0.18\n[[straw]]\nx = 0.02\ny = 0.01\n",
            "2 liquid layers",
        ),
        ("", "no straw"),
    ] {
        let d = parsed(&glass_with(extra));
        assert_eq!(d.spec_scene(), None, "{extra}");
        assert!(d.unsupported().iter().any(|w| w == words), "{:?}", d.unsupported());
    }
    // Alike straws are one reason, said once.
    let twins = glass_with(
        "[[straw]]\nx = -0.02\ny = 0\nlength = 0.2\n[[straw]]\nx = 0.02\ny = 0\nlength = 0.2\n",
    );
    assert_eq!(
        parsed(&twins).unsupported(),
        vec!["2 straws", "a straw 0.2 m long"]
    );
    let thick = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\nwall = 0.002\n[[straw]]\nx = 0\ny = 0\n";
    assert_eq!(parsed(thick).unsupported(), vec!["walls 0.002 m thick"]);
    let tank = "[container]\nshape = \"tank\"\nhalf_x = 0.1\nhalf_y = 0.05\nheight = 0.2\n[[straw]]\nx = 0\ny = 0\n";
    assert_eq!(parsed(tank).unsupported(), vec!["a rectangular tank"]);
    let small =
        "[container]\nshape = \"glass\"\nradius = 0.05\nheight = 0.1\n[[straw]]\nx = 0\ny = 0\n";
    assert_eq!(
        parsed(small).unsupported(),
        vec!["a glass of radius 0.05 m", "a glass 0.1 m high"]
    );
}

#[test]
fn writing_a_description_and_reading_it_back_gives_it_again() {
    let text = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.12\nwall = 0.003\nbottom = 0.008\nindex = 1.52\n\
        [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.06\n[[liquid]]\nname = \"oil \\\"extra\\\"\"\nindex = 1.47\ntop = 0.0900000000000001\ntint = \"#E0b020\"\n\
        [[straw]]\nx = -0.012\ny = 0.003\ntilt = 12.5\nazimuth = -33\nradius = 0.004\nlength = 0.2\n\
        [[coin]]\nx = 0.02\ny = 0.0\n\
        [[card]]\ncenter = [-0.15, 0.01, 0.08]\nfacing = 10\nwidth = 0.12\nheight = 0.06\npicture = \"none\"\n\
        [observer]\nposition = [0.3, 1e-7, 0.25]\ntarget = [0.0, 0.0, 0.1]\n";
    let first = parsed(text);
    let written = first.to_toml();
    let again = parsed(&written);
    assert_eq!(first, again, "{written}");
    assert_eq!(first.liquids[1].tint, Some([0xe0, 0xb0, 0x20]));
    assert_eq!(first.liquids[0].tint, None);
    // A tank too, and an empty one; a glass of revolution.
    let tank = parsed("[container]\nshape = \"tank\"\nhalf_x = 0.1\nhalf_y = 0.05\nheight = 0.2\n");
    assert_eq!(parsed(&tank.to_toml()), tank);
    let turned = parsed(
        "[container]\nshape = \"revolution\"\nouter = [[0.03, 0], [0.045, 0.06], [0.04, 0.12]]\n\
         inner = [[0.0, 0.01], [0.04, 0.06], [0.037, 0.12]]\nindex = 1.52\n",
    );
    assert_eq!(parsed(&turned.to_toml()), turned);
}

proptest::proptest! {
    /// On the assignment's glass a file accepts exactly the straws and water heights the
    /// assignment's own rules accept, even at the wall's edge, and gives the same scene.
    #[test]
    fn the_file_and_the_assignment_rules_agree_on_the_assignment_glass(
        rho in 0.0345f64..0.0355,
        theta in 0.0f64..std::f64::consts::TAU,
        top in 1e-6f64..0.2002,
    ) {
        let (x, y) = (rho * theta.cos(), rho * theta.sin());
        let text = glass_with("")
            .replace("top = 0.15", &format!("top = {top:?}"))
            + &format!("[[straw]]\nx = {x:?}\ny = {y:?}\n");
        let by_file = SceneDescription::from_toml(&text).ok().and_then(|d| d.spec_scene());
        let by_rules = Scene::with_defaults(x, y, top).ok();
        proptest::prop_assert_eq!(by_file, by_rules);
    }
}

/// An `[observer]` with a position alone looks at the middle of the container.
#[test]
fn an_observer_without_a_target_looks_at_the_containers_middle() {
    let d = parsed(&glass_with("[observer]\nposition = [0.3, 0, 0.1]\n"));
    let o = d.observer.unwrap();
    assert_eq!(o.position, Vec3::new(0.3, 0.0, 0.1));
    assert_eq!(o.target, Vec3::new(0.0, 0.0, 0.1));
    // Written back, the target is written out and read again.
    assert_eq!(parsed(&d.to_toml()), d);
}

/// Rules that do not depend on one another are all reported at once, each on its own line with
/// its key, so that a file is mended in one go.
#[test]
fn every_independent_broken_rule_is_reported_at_once() {
    let text = glass_with(
        "\n[[liquid]]\nname = \"oil\"\nindex = 0.5\ntop = 0.18\n\n[[straw]]\nx = 0\ny = 0\ntilt = 95\n\n[[coin]]\nx = 0.02\ny = 0\nradius = -1\n\n[[card]]\ncenter = [0, 0.1, 0.05]\nwidth = 0\nheight = 0.05\n",
    );
    let e = SceneDescription::from_toml(&text).expect_err("four rules are broken");
    let keys: Vec<&str> = e.rules().map(|r| r.key.as_str()).collect();
    assert_eq!(
        keys,
        [
            "liquid[2].index",
            "straw[1].tilt",
            "coin[1].radius",
            "card[1].width"
        ]
    );
    let shown = e.to_string();
    assert!(shown.starts_with("4 rules are broken:"), "{shown}");
    for r in e.rules() {
        assert!(!r.message.contains('\n'), "{}", r.message);
        assert!(shown.contains(&r.message), "{shown}");
    }
    // One broken rule is one line, as before.
    let one = SceneDescription::from_toml(&glass_with("[[straw]]\nx = 0\ny = 0\ntilt = 95\n"))
        .unwrap_err();
    assert!(one.more.is_empty() && !one.to_string().contains('\n'));
}

/// Every missing key is named at once, and a missing key does not hide a misplaced one.
#[test]
fn every_missing_key_is_named_at_once() {
    let text = "[container]\nshape = \"glass\"\nradius = 0.04\nhalf_x = 0.1\n\n[[liquid]]\nindex = 1.333\n\n[[straw]]\nx = 0\n\n[observer]\ntarget = [0, 0, 0.1]\n";
    let e = SceneDescription::from_toml(text).expect_err("keys are missing");
    let keys: Vec<&str> = e.rules().map(|r| r.key.as_str()).collect();
    assert_eq!(
        keys,
        [
            "container.height",
            "container.half_x",
            "liquid[1].name",
            "liquid[1].top",
            "straw[1].y",
            "observer.position"
        ]
    );
    assert!(e.rules().all(|r| !r.message.is_empty()));
}

/// A layer that breaks a rule does not make the next layer's good top a second refusal: the
/// next is compared with the last good layer below it.
#[test]
fn a_bad_layer_is_reported_once() {
    let text = glass_with("\n[[liquid]]\nname = \"oil\"\nindex = 0.5\ntop = 0.18\n\n[[liquid]]\nname = \"air-ish\"\nindex = 1.1\ntop = 0.19\n");
    let e = SceneDescription::from_toml(&text).expect_err("one layer is broken");
    let keys: Vec<&str> = e.rules().map(|r| r.key.as_str()).collect();
    assert_eq!(keys, ["liquid[2].index"]);
}

/// Sizes that read like centimetres get a hint naming the key, the size in metres and what to
/// write instead; a tabletop scene gets none.
#[test]
fn centimetres_written_as_metres_get_a_hint() {
    let text = "[container]\nshape = \"glass\"\nradius = 4\nheight = 20\n\n[[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 15\n\n[[straw]]\nx = 0\ny = 0\n";
    let hints = parsed(text).hints();
    assert_eq!(hints.len(), 2, "{hints:?}");
    assert!(hints[0].starts_with("container.radius = 4:"), "{hints:?}");
    assert!(hints[0].contains("write 0.04"), "{hints:?}");
    assert!(hints[1].starts_with("container.height = 20:"), "{hints:?}");
    assert!(parsed(&glass_with("[[straw]]\nx = 0\ny = 0\n"))
        .hints()
        .is_empty());
}

/// Numbers a hostile or careless file may hold: zero, signs, the edges of the rules, the tiny
/// and the huge, and TOML's infinities and NaN.
const HOSTILE: [&str; 18] = [
    "0", "-0.0", "1e-300", "1e-7", "1e-6", "0.001", "0.005", "0.04", "0.15", "1", "4", "89.999",
    "1e6", "1e7", "1e155", "1.7e308", "inf", "nan",
];

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(400))]

    /// Any bytes are read or refused with a message, never a panic.
    #[test]
    fn any_text_is_read_or_refused_without_a_panic(
        bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..300),
    ) {
        let _ = SceneDescription::from_toml(&String::from_utf8_lossy(&bytes));
    }

    /// A file of the right layout holding hostile numbers is refused, or is a scene whose world
    /// is built and traced from its eye without a panic, every ray ending (it meets something,
    /// escapes, or runs out of events).
    #[test]
    fn hostile_numbers_are_refused_or_traced(
        picks in proptest::collection::vec(0..HOSTILE.len(), 24),
        shape in 0u8..3,
        (liquids, straws, coins, cards) in (0usize..3, 0usize..3, 0usize..2, 0usize..2),
        (spheres, prisms, lenses) in (0usize..2, 0usize..2, 0usize..2),
    ) {
        let mut k = 0;
        let mut n = || { k += 1; HOSTILE[picks[(k - 1) % picks.len()]] };
        let mut text = match shape {
            0 => format!("[container]\nshape = \"tank\"\nhalf_x = {}\nhalf_y = {}\nheight = {}\n", n(), n(), n()),
            1 => format!("[container]\nshape = \"glass\"\nradius = {}\nheight = {}\nwall = {}\n", n(), n(), n()),
            // Profiles of two and three points, the base at 0 so that some are valid.
            _ => format!(
                "[container]\nshape = \"revolution\"\nouter = [[{}, 0], [{}, {}], [{}, {}]]\n\
                 inner = [[{}, {}], [{}, {}]]\nindex = {}\n",
                n(), n(), n(), n(), n(), n(), n(), n(), n(), n()
            ),
        };
        for i in 0..liquids {
            text += &format!("[[liquid]]\nname = \"l{i}\"\nindex = {}\ntop = {}\n", n(), n());
        }
        for _ in 0..straws {
            text += &format!("[[straw]]\nx = {}\ny = {}\ntilt = {}\nradius = {}\n", n(), n(), n(), n());
        }
        for _ in 0..coins {
            text += &format!("[[coin]]\nx = {}\ny = {}\nthickness = {}\n", n(), n(), n());
        }
        for _ in 0..cards {
            text += &format!("[[card]]\ncenter = [{}, {}, {}]\nwidth = {}\nheight = {}\n", n(), n(), n(), n(), n());
        }
        for _ in 0..spheres {
            text += &format!("[[sphere]]\ncenter = [{}, {}, {}]\nradius = {}\nindex = {}\n", n(), n(), n(), n(), n());
        }
        for _ in 0..prisms {
            text += &format!(
                "[[prism]]\ncorners = [[{}, {}], [{}, {}], [{}, {}]]\nbottom = {}\ntop = {}\nindex = {}\n",
                n(), n(), n(), n(), n(), n(), n(), n(), n()
            );
        }
        for _ in 0..lenses {
            text += &format!(
                "[[lens]]\ncenter = [{}, {}, {}]\naxis = [{}, {}, {}]\nradius1 = {}\nradius2 = -{}\nthickness = {}\ndiameter = {}\nindex = {}\n",
                n(), n(), n(), n(), n(), n(), n(), n(), n(), n(), n()
            );
        }
        text += &format!("[observer]\nposition = [{}, {}, {}]\n", n(), n(), n());
        if let Ok(scene) = SceneDescription::from_toml(&text) {
            let world = crate::world::World::new(&scene, 10).expect("a valid scene");
            let eye = scene.observer.expect("an observer was given").position;
            for d in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Z, Vec3::new(-1.0, 0.3, -0.2).normalize()] {
                let _ = world.trace(crate::geometry::Ray::new(eye, d));
            }
        }
    }
}

/// A file breaking each rule of scene files, with the rule's code (every code has one).
pub(crate) fn broken_samples() -> Vec<(&'static str, String)> {
    let glass = |rest: &str| glass_with(rest);
    let container = |c: &str| format!("[container]\n{c}\n");
    let tank = |c: &str| {
        container(&format!(
            "shape = \"tank\"\nhalf_x = 0.2\nhalf_y = 0.2\nheight = 0.3\n{c}"
        ))
    };
    let glass_c = |c: &str| {
        container(&format!(
            "shape = \"glass\"\nradius = 0.04\nheight = 0.2\n{c}"
        ))
    };
    let revolution = |c: &str| {
        container(&format!(
            "shape = \"revolution\"\nouter = [[0.04, 0], [0.04, 0.12]]\n\
             inner = [[0.035, 0.01], [0.035, 0.12]]\n{c}"
        ))
    };
    let layers: String = (0..MAX_LIQUIDS + 1)
        .map(|k| {
            format!(
                "[[liquid]]\nname = \"l\"\nindex = 1.3\ntop = {}\n",
                0.001 * (k + 1) as f64
            )
        })
        .collect();
    let coins: String = (0..MAX_OBJECTS + 1)
        .map(|_| "[[coin]]\nx = 0\ny = 0\n")
        .collect();
    vec![
        ("finite", glass("[[straw]]\nx = nan\ny = 0\n")),
        ("length.max", glass("[[straw]]\nx = 2e6\ny = 0\n")),
        ("size.range", glass("[[straw]]\nx = 0\ny = 0\nradius = 2e6\n")),
        ("size.positive", glass("[[straw]]\nx = 0\ny = 0\nradius = -0.005\n")),
        ("thickness.positive", glass_c("wall = -0.001")),
        ("thickness.range", glass_c("wall = 1e-9")),
        ("wall.thinner", glass_c("wall = 0.05")),
        ("bottom.thinner", glass_c("bottom = 0.3")),
        ("index.range", glass("").replace("index = 1.333", "index = 0.8")),
        ("index.range", glass("").replace("index = 1.333", "index = 1e308")),
        ("index.range", glass("").replace("index = 1.333", "index = 5.01")),
        ("index.choice", glass("").replace("index = 1.333", "index = 1.333\nmaterial = \"water\"")),
        ("cauchy.count", glass("").replace("index = 1.333", "cauchy = [1.3]")),
        ("cauchy.count", glass("").replace("index = 1.333", "cauchy = [1.3, 0.003, 0.0, 0.0]")),
        ("sellmeier.count", glass("").replace("index = 1.333", "sellmeier = [1.0, 0.01, 0.5]")),
        ("sellmeier.count", glass("").replace("index = 1.333", "sellmeier = []")),
        ("dispersion.range", glass("").replace("index = 1.333", "cauchy = [0.9, 0.001]")),
        ("dispersion.range", glass("").replace("index = 1.333", "sellmeier = [0.5, 0.25]")),
        ("dispersion.range", glass("").replace("index = 1.333", "cauchy = [nan, 0.001]")),
        ("material.unknown", glass("").replace("index = 1.333", "material = \"unobtainium\"")),
        ("material.near", glass("").replace("index = 1.333", "material = \"watr\"")),
        ("container.tank-index", tank("material = \"bk7\"")),
        ("liquid.above-floor", glass("").replace("top = 0.15", "top = 0")),
        ("liquid.above-layer", glass("[[liquid]]\nname = \"oil\"\nindex = 1.47\ntop = 0.1\n")),
        ("liquid.below-rim", glass("").replace("top = 0.15", "top = 0.3")),
        ("liquid.too-many", glass_c("") + &layers),
        ("liquid.tint", glass("").replace("top = 0.15", "top = 0.15\ntint = \"red\"")),
        ("liquid.tint", glass("").replace("top = 0.15", "top = 0.15\ntint = \"#12345\"")),
        ("liquid.tint", glass("").replace("top = 0.15", "top = 0.15\ntint = \"#+12345\"")),
        ("objects.too-many", tank("") + &coins),
        ("tilt.range", glass("[[straw]]\nx = 0\ny = 0\ntilt = 95\n")),
        ("tilt.tiny", glass("[[straw]]\nx = 0\ny = 0\ntilt = 1e-9\n")),
        ("straw.foot", glass("[[straw]]\nx = 0.05\ny = 0\n")),
        ("straw.pierces", glass("[[straw]]\nx = 0.038\ny = 0\n")),
        ("coin.outside", glass("[[coin]]\nx = 0.038\ny = 0\n")),
        ("coin.below-rim", glass("[[coin]]\nx = 0\ny = 0\nthickness = 0.3\n")),
        ("card.cuts", glass("[[card]]\ncenter = [0, 0, 0.1]\nwidth = 0.05\nheight = 0.05\n")),
        ("floor.overlap", glass("[[straw]]\nx = 0\ny = 0\n[[straw]]\nx = 0.002\ny = 0\n")),
        ("coin.leaned-on", tank("") + "[[straw]]\nx = 0\ny = 0\ntilt = 80\nlength = 0.1\n[[coin]]\nx = 0.0201\ny = 0\n"),
        ("straws.cross", glass("[[straw]]\nx = -0.012\ny = 0\ntilt = 5\n[[straw]]\nx = 0.012\ny = 0\ntilt = 5\nazimuth = 180\n")),
        ("observer.in-container", glass("[observer]\nposition = [0, 0, 0.1]\n")),
        ("observer.in-straw", glass("[[straw]]\nx = 0\ny = 0\n[observer]\nposition = [0, 0, 0.22]\n")),
        ("observer.on-card", glass("[[card]]\ncenter = [0.2, 0, 0.1]\nwidth = 0.05\nheight = 0.05\n[observer]\nposition = [0.2, 0, 0.1]\n")),
        ("observer.target-at-eye", glass("[observer]\nposition = [0.3, 0, 0.1]\ntarget = [0.3, 0, 0.1]\n")),
        ("sphere.container", glass("[[sphere]]\ncenter = [0.035, 0, 0.05]\nradius = 0.01\nindex = 1.5\n")),
        ("solid.overlap", glass("[[sphere]]\ncenter = [0.3, 0, 0.1]\nradius = 0.02\nindex = 1.5\n[[sphere]]\ncenter = [0.31, 0, 0.1]\nradius = 0.02\nindex = 1.5\n")),
        ("solid.card", glass("[[sphere]]\ncenter = [0.3, 0, 0.1]\nradius = 0.012\nindex = 1.5\n[[card]]\ncenter = [0.3, 0, 0.1]\nwidth = 0.02\nheight = 0.02\n")),
        ("observer.in-solid", glass("[[sphere]]\ncenter = [0.3, 0, 0.1]\nradius = 0.02\nindex = 1.5\n[observer]\nposition = [0.3, 0, 0.1]\n")),
        ("prism.convex", glass("[[prism]]\ncorners = [[0.3, 0], [0.4, 0]]\nbottom = 0\ntop = 0.1\nindex = 1.5\n")),
        ("prism.top", glass("[[prism]]\ncorners = [[0.3, 0], [0.4, 0], [0.35, 0.08]]\nbottom = 0.1\ntop = 0.1\nindex = 1.5\n")),
        ("prism.container", glass("[[prism]]\ncorners = [[0.03, 0], [0.06, 0], [0.05, 0.02]]\nbottom = 0\ntop = 0.1\nindex = 1.5\n")),
        ("sun.direction", glass("[sun]\ndirection = [0, 0, 0]\n")),
        ("lens.axis", glass("[[lens]]\ncenter = [0.3, 0, 0.1]\naxis = [0, 0, 0]\nradius1 = 0.05\nradius2 = -0.05\nthickness = 0.01\ndiameter = 0.04\nindex = 1.5\n")),
        ("lens.radius", glass("[[lens]]\ncenter = [0.3, 0, 0.1]\naxis = [1, 0, 0]\nradius1 = 0.015\nradius2 = -0.05\nthickness = 0.01\ndiameter = 0.04\nindex = 1.5\n")),
        ("lens.faces", glass("[[lens]]\ncenter = [0.3, 0, 0.1]\naxis = [1, 0, 0]\nradius1 = 0.025\nradius2 = -0.025\nthickness = 0.004\ndiameter = 0.04\nindex = 1.5\n")),
        ("lens.place", glass("[[lens]]\ncenter = [0.05, 0, 0.1]\naxis = [1, 0, 0]\nradius1 = 0.05\nradius2 = -0.05\nthickness = 0.01\ndiameter = 0.04\nindex = 1.5\n")),
        ("lesson.length", glass("[lesson.en]\ntitle = \"\"\n")),
        ("lesson.length", glass(&format!("[lesson.fr]\ntitle = \"t\"\nquestions = [{}]\n", ["\"q ?\""; 4].join(", ")))),
        ("lesson.length", glass(&format!("[lesson.en]\ntitle = \"t\"\ntext = \"{}\"\n", "é".repeat(601)))),
        ("required", glass("[lesson.en]\ntext = \"no title\"\n")),
        ("required", glass("[[straw]]\nx = 0\n")),
        ("container.missing", "[[straw]]\nx = 0\ny = 0\n".to_string()),
        ("container.glass-needs", container("shape = \"glass\"\nheight = 0.2")),
        ("container.tank-needs", container("shape = \"tank\"\nhalf_y = 0.1\nheight = 0.2")),
        ("container.glass-half-widths", glass_c("half_x = 0.1")),
        ("container.tank-radius", tank("radius = 0.1")),
        ("container.tank-thin", tank("wall = 0.001")),
        ("container.tank-index", tank("index = 1.5")),
        ("container.revolution-needs", revolution("").replace("inner = [[0.035, 0.01], [0.035, 0.12]]\n", "")),
        ("container.revolution-keys", revolution("height = 0.12")),
        ("container.profiles", glass_c("outer = [[0.04, 0], [0.04, 0.2]]")),
        ("profile.points", revolution("").replace("[[0.04, 0], [0.04, 0.12]]", "[[0.04, 0]]")),
        ("profile.rise", revolution("").replace("[[0.04, 0], [0.04, 0.12]]", "[[0.04, 0], [0.045, 0.08], [0.04, 0.07], [0.04, 0.12]]")),
        ("profile.radius", revolution("").replace("[[0.035, 0.01]", "[[0.0, 0.01], [0.0, 0.02]")),
        ("profile.base", revolution("").replace("[[0.04, 0]", "[[0.04, 0.01]")),
        ("profile.floor", revolution("").replace("[[0.035, 0.01]", "[[0.035, -0.01]")),
        ("profile.rim", revolution("").replace("[0.035, 0.12]", "[0.035, 0.11]")),
        ("profile.inside", revolution("").replace("[0.035, 0.12]", "[0.041, 0.12]")),
        ("shape.unknown", container("shape = \"cone\"\nheight = 0.2")),
        ("shape.missing", container("height = 0.2")),
        ("picture.unknown", glass("[[card]]\ncenter = [0.2, 0, 0.1]\nwidth = 0.05\nheight = 0.05\npicture = \"cat\"\n")),
        ("toml.syntax", glass("[[straw]]\nx = 0\ny = 0\ntilt = \"steep\"\n")),
    ]
}

/// Each sample breaks the rule it is listed with, first, and its message is that rule's line;
/// every rule of scene files has a sample.
#[test]
fn every_rule_is_refused_with_its_code_and_its_own_words() {
    let samples = broken_samples();
    for (code, text) in &samples {
        let e = SceneDescription::from_toml(text).expect_err(code);
        assert_eq!(e.rule.code(), *code, "{}", e.message);
        let line = rule::line(e.rule, &e.key, e.value.as_deref(), &e.params);
        let place = e.line.map_or(String::new(), |l| format!("line {l}: "));
        assert_eq!(e.message, place + &line, "{code}");
        for (name, _) in &e.params {
            assert!(
                e.rule.template().contains(&format!("{{{name}}}")),
                "{code}: {name}"
            );
        }
    }
    // The values' own rules (the assignment's glass, the event limit, the wavelength) are not a
    // scene file's.
    for r in Rule::ALL
        .iter()
        .filter(|r| !r.code().starts_with("glass.") && **r != Rule::Wavelength)
    {
        assert!(
            samples.iter().any(|(c, _)| c == &r.code()),
            "no sample breaks {}",
            r.code()
        );
    }
}
