//! The gallery of classic demonstrations, built into the program: its scene files, by name.

/// The gallery's scene files beyond the assignment's own (`scenes/`): name and text.
pub const GALLERY: [(&str, &str); 34] = [
    (
        "leaning-straw",
        include_str!("../scenes/leaning-straw.toml"),
    ),
    ("real-glass", include_str!("../scenes/real-glass.toml")),
    ("oil-on-water", include_str!("../scenes/oil-on-water.toml")),
    ("tank-pencil", include_str!("../scenes/tank-pencil.toml")),
    (
        "coin-in-glass",
        include_str!("../scenes/coin-in-glass.toml"),
    ),
    (
        "reversing-arrow",
        include_str!("../scenes/reversing-arrow.toml"),
    ),
    (
        "vanishing-glass",
        include_str!("../scenes/vanishing-glass.toml"),
    ),
    ("two-straws", include_str!("../scenes/two-straws.toml")),
    (
        "oil-on-water-above",
        include_str!("../scenes/oil-on-water-above.toml"),
    ),
    (
        "appearing-coin",
        include_str!("../scenes/appearing-coin.toml"),
    ),
    (
        "apparent-depth",
        include_str!("../scenes/apparent-depth.toml"),
    ),
    (
        "mirror-surface",
        include_str!("../scenes/mirror-surface.toml"),
    ),
    (
        "near-and-far-arrow",
        include_str!("../scenes/near-and-far-arrow.toml"),
    ),
    (
        "pencil-at-a-slant",
        include_str!("../scenes/pencil-at-a-slant.toml"),
    ),
    (
        "leaning-straw-above",
        include_str!("../scenes/leaning-straw-above.toml"),
    ),
    ("dense-liquid", include_str!("../scenes/dense-liquid.toml")),
    (
        "marble-in-water",
        include_str!("../scenes/marble-in-water.toml"),
    ),
    ("fish-bowl", include_str!("../scenes/fish-bowl.toml")),
    (
        "water-drop-magnifier",
        include_str!("../scenes/water-drop-magnifier.toml"),
    ),
    (
        "vanishing-ball",
        include_str!("../scenes/vanishing-ball.toml"),
    ),
    ("ball-lens", include_str!("../scenes/ball-lens.toml")),
    (
        "half-dipped-ball",
        include_str!("../scenes/half-dipped-ball.toml"),
    ),
    ("prism", include_str!("../scenes/prism.toml")),
    (
        "glass-block-pencil",
        include_str!("../scenes/glass-block-pencil.toml"),
    ),
    (
        "magnifying-glass",
        include_str!("../scenes/magnifying-glass.toml"),
    ),
    (
        "diverging-lens",
        include_str!("../scenes/diverging-lens.toml"),
    ),
    (
        "lens-in-water",
        include_str!("../scenes/lens-in-water.toml"),
    ),
    (
        "tapered-tumbler",
        include_str!("../scenes/tapered-tumbler.toml"),
    ),
    ("wine-glass", include_str!("../scenes/wine-glass.toml")),
    (
        "cocktail-glass",
        include_str!("../scenes/cocktail-glass.toml"),
    ),
    (
        "prism-spectrum",
        include_str!("../scenes/prism-spectrum.toml"),
    ),
    ("lens-colours", include_str!("../scenes/lens-colours.toml")),
    (
        "dispersive-liquid",
        include_str!("../scenes/dispersive-liquid.toml"),
    ),
    ("rainbow", include_str!("../scenes/rainbow.toml")),
];

/// The assignment's own scene as a scene file (`scenes/spec.toml`): name and text.
pub const SPEC: (&str, &str) = ("spec", include_str!("../scenes/spec.toml"));

/// Every scene known by name from any folder: the assignment's own and the gallery's.
pub fn named_scenes() -> impl Iterator<Item = (&'static str, &'static str)> {
    std::iter::once(SPEC).chain(GALLERY)
}

/// What a scene file teaches, in `lang` (else in the other language): its lesson's title, and
/// its text followed by each question, numbered, as a report's notes. None without a lesson.
pub fn lesson_notes(text: &str, lang: crate::words::Lang) -> Option<(String, Vec<String>)> {
    let d = bentstraw_optics::scene_file::SceneDescription::from_toml(text).ok()?;
    let lesson = d.lesson?;
    let l = lesson.in_language(lang.code())?;
    let mut notes = vec![l.text.clone()];
    for (k, q) in l.questions.iter().enumerate() {
        notes.push(lang.fill(crate::words::LESSON_QUESTION, &[&(k + 1), q]));
    }
    Some((l.title.clone(), notes))
}

/// What a scene file says it shows: its opening comment, as one paragraph.
pub fn opening_comment(text: &str) -> String {
    text.lines()
        .take_while(|l| l.starts_with('#'))
        .map(|l| l.trim_start_matches('#').trim())
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_input::gallery_setup;
    use bentstraw_optics::geometry::Ray;
    use bentstraw_optics::image::ImagePoint;
    use bentstraw_optics::light_path_type::{Entry, LightPathType};
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::DEFAULT_MAX_EVENTS;
    use bentstraw_optics::setup::Setup;
    use bentstraw_optics::world::{CARD_COLOR, COIN_COLOR, PICTURE_COLOR};
    use bentstraw_optics::Vec3;

    /// The text of gallery scene `stem`.
    fn text_of(stem: &str) -> &'static str {
        GALLERY
            .iter()
            .find(|(s, _)| *s == stem)
            .unwrap_or_else(|| panic!("{stem} is in the gallery"))
            .1
    }

    /// The world of a scene file's `text` (a gallery scene, or one edited from it).
    fn load(stem: &str, text: &str) -> Setup {
        gallery_setup(stem, text, DEFAULT_MAX_EVENTS).unwrap_or_else(|e| panic!("{stem}: {e}"))
    }

    /// `text` with `from` replaced by `to`, which must occur in it.
    fn edited(text: &str, from: &str, to: &str) -> String {
        assert!(text.contains(from), "{from:?} is not in the text");
        text.replace(from, to)
    }

    /// At least `n` image points of the loaded scene, from its own observer.
    fn points(world: &Setup, n: usize) -> Vec<ImagePoint> {
        sample_image(&world.world, world.observer, n, &|_| {}).points
    }

    /// The kind of light path that makes image point `p`.
    fn path_of(world: &Setup, p: &ImagePoint) -> LightPathType {
        world
            .world
            .trace_path_type(Ray::new(world.observer, p.direction))
            .1
    }

    #[test]
    fn every_gallery_scene_is_valid_and_says_what_it_shows() {
        for (stem, text) in GALLERY {
            let world = gallery_setup(stem, text, DEFAULT_MAX_EVENTS).unwrap();
            // Something to see: an object, or a drop in the sun.
            let in_sun = world.world.sun().is_some() && !world.description.spheres.is_empty();
            assert!(!world.world.objects().is_empty() || in_sun, "{stem}");
            assert!(opening_comment(text).len() > 60, "{stem}");
        }
    }

    /// Every named scene teaches in both languages: a title, a text and one or two questions in
    /// English and in French, the French written with French spacing and no English left; the
    /// lesson comes back whole from the file the page writes.
    #[test]
    fn every_named_scene_has_its_lesson_in_english_and_french() {
        use bentstraw_optics::scene_file::SceneDescription;
        for (stem, text) in named_scenes() {
            let d = SceneDescription::from_toml(text).unwrap();
            let lesson = d
                .lesson
                .clone()
                .unwrap_or_else(|| panic!("{stem} has no lesson"));
            for (lang, l) in [("en", &lesson.en), ("fr", &lesson.fr)] {
                let l = l
                    .as_ref()
                    .unwrap_or_else(|| panic!("{stem}: no lesson in {lang}"));
                assert!(l.text.len() > 40, "{stem} {lang}");
                assert!((1..=2).contains(&l.questions.len()), "{stem} {lang}");
                for q in &l.questions {
                    assert!(q.ends_with('?'), "{stem} {lang}: {q}");
                    // French puts a (no-break) space before ? : ; and !; English does not.
                    assert_eq!(q.ends_with("\u{a0}?"), lang == "fr", "{stem} {lang}: {q}");
                }
                if lang == "fr" {
                    let words = format!("{} {} {}", l.title, l.text, l.questions.join(" "));
                    for english in [" the ", " and ", " of ", " is ", " straw", " glass "] {
                        assert!(!words.contains(english), "{stem}: {english:?} in {words}");
                    }
                }
            }
            let again = SceneDescription::from_toml(&d.to_toml()).unwrap();
            assert_eq!(again.lesson, d.lesson, "{stem}");
        }
    }

    /// Oil of the glass's own index hides the glass: filled to the brim, the glass of index 1.47
    /// with walls 5 mm thick gives exactly the image points of the same glass with walls of no
    /// thickness (one medium, one outer surface); as the file fills it, the wall's inner face
    /// below the oil is no surface at all, which glass of index 1.5 would have.
    #[test]
    fn the_vanishing_glass_is_one_medium_with_its_oil() {
        let text = text_of("vanishing-glass");
        let full = edited(text, "top = 0.10", "top = 0.15");
        let thick = load("full", &full);
        let thin = load("thin", &edited(&full, "wall = 0.005", "wall = 0.0"));
        let (a, b) = (points(&thick, 3000), points(&thin, 3000));
        assert!(a.len() >= 3000);
        assert_eq!(a.len(), b.len());
        for (p, q) in a.iter().zip(&b) {
            assert_eq!((p.color, p.events), (q.color, q.events), "{p:?} {q:?}");
            assert!(p.position.distance(q.position) < 1e-12, "{p:?} {q:?}");
        }
        let as_given = load("vanishing-glass", text);
        let ordinary = load(
            "ordinary",
            &edited(
                text,
                "wall = 0.005\nbottom = 0.012\nindex = 1.47",
                "wall = 0.005\nbottom = 0.012\nindex = 1.5",
            ),
        );
        assert!(
            as_given.world.boundaries().len() < ordinary.world.boundaries().len(),
            "{} against {}",
            as_given.world.boundaries().len(),
            ordinary.world.boundaries().len()
        );
    }

    /// The appearing coin: from the file's eye the coin is seen through the water's surface,
    /// straight (no total reflection) as well as by its reflection; with the water poured out,
    /// not at all.
    #[test]
    fn the_coin_appears_only_with_the_water() {
        let text = text_of("appearing-coin");
        let wet = load("appearing-coin", text);
        let cloud = points(&wet, 4000);
        let coin: Vec<&ImagePoint> = cloud.iter().filter(|p| p.color == COIN_COLOR).collect();
        let straight = coin
            .iter()
            .filter(|p| {
                path_of(&wet, p)
                    == LightPathType {
                        entry: Entry::Top,
                        total_reflections: 0,
                    }
            })
            .count();
        assert!(straight >= 20, "{straight} of {} coin points", coin.len());
        let dry = load(
            "dry",
            &edited(
                text,
                "[[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.10\n",
                "",
            ),
        );
        let cloud = points(&dry, 4000);
        assert!(cloud.len() >= 4000, "the card is still seen");
        assert!(cloud.iter().any(|p| p.color == CARD_COLOR));
        let seen = cloud.iter().filter(|p| p.color == COIN_COLOR).count();
        assert_eq!(seen, 0, "the empty glass shows the coin");
    }

    /// Apparent depth from straight above, by the eye model: the coin's centre seems raised by
    /// a quarter of its depth under the surface (d − d/n, n = 1.333), and every point of its top
    /// face, seen at θ from the vertical (θ' in the water), lies between the depths of its two foci
    /// below the surface, d·cos θ/(n·cos θ') and d·cos³θ/(n·cos³θ'), at most d/n.
    #[test]
    fn the_coin_seen_from_straight_above_looks_raised_by_a_quarter_of_its_depth() {
        let text = text_of("apparent-depth");
        let world = load("apparent-depth", text);
        let (n, top, coin_top) = (1.333f64, 0.16, 0.0019);
        let d = top - coin_top;
        let eye = world.observer;
        let centre = world.world.image_point(eye, -Vec3::Z).expect("the coin");
        assert_eq!(centre.color, COIN_COLOR);
        let p = world
            .world
            .apparent_point(eye, &centre)
            .position
            .expect("both foci");
        let raised = p.z - coin_top;
        assert!((raised - d * (1.0 - 1.0 / n)).abs() < 1e-7, "{raised}");
        assert!((raised / d - 0.25).abs() < 0.001, "{}", raised / d);
        let cloud = points(&world, 2000);
        let mut checked = 0;
        for image in cloud.iter().filter(|p| p.color == COIN_COLOR) {
            assert!(
                (image.straw_point.z - coin_top).abs() < 1e-9,
                "only its top face is seen"
            );
            let Some(a) = world.world.apparent_point(eye, image).position else {
                continue;
            };
            let cos_t = -image.direction.z;
            let sin_w = (1.0 - cos_t * cos_t).sqrt() / n;
            let cos_w = (1.0 - sin_w * sin_w).sqrt();
            let depth = top - a.z;
            let low = d / n * (cos_t / cos_w).powi(3);
            assert!(
                depth <= d / n + 1e-9 && depth >= low - 1e-9,
                "{depth} not in [{low}, {}]",
                d / n
            );
            checked += 1;
        }
        assert!(checked >= 500, "{checked} coin points checked");
    }

    /// The surface as a mirror: part of the straw is seen through the side wall after one total
    /// reflection, at the water's surface (from below), and those images lie above the surface,
    /// as a reflection in a mirror does.
    #[test]
    fn the_surface_seen_from_below_mirrors_the_straw() {
        let world = load("mirror-surface", text_of("mirror-surface"));
        let top = 0.12;
        let cloud = points(&world, 4000);
        let mirrored: Vec<&ImagePoint> = cloud
            .iter()
            .filter(|p| {
                let mut at_surface = 0;
                let mut total = 0;
                world
                    .world
                    .trace_with(Ray::new(world.observer, p.direction), |e| {
                        if e.totally_reflected {
                            total += 1;
                            if (e.point.z - top).abs() < 1e-9 && e.incoming.z > 0.0 {
                                at_surface += 1;
                            }
                        }
                    });
                total == 1 && at_surface == 1
            })
            .collect();
        assert!(
            mirrored.len() * 20 >= cloud.len(),
            "{} of {}",
            mirrored.len(),
            cloud.len()
        );
        for p in &mirrored {
            assert_eq!(path_of(&world, p).entry, Entry::Wall);
            assert!(p.straw_point.z < top);
        }
        let above = mirrored.iter().filter(|p| p.position.z > top).count();
        assert!(
            above * 10 >= mirrored.len() * 9,
            "{above} of {}",
            mirrored.len()
        );
    }

    /// The card far behind the water is seen reversed (a ray from the eye to the right of the
    /// axis ends on the card's left), the near one is not.
    #[test]
    fn only_the_far_arrow_is_reversed() {
        let world = load("near-and-far-arrow", text_of("near-and-far-arrow"));
        let cloud = points(&world, 4000);
        let (mut near, mut far) = ([0usize; 2], [0usize; 2]);
        for p in cloud.iter().filter(|p| {
            (p.color == CARD_COLOR || p.color == PICTURE_COLOR)
                && p.events > 0
                && p.straw_point.y.abs() > 0.005
        }) {
            let same = (p.direction.y > 0.0) == (p.straw_point.y > 0.0);
            let tally = if p.straw_point.x > -0.1 {
                &mut near
            } else {
                &mut far
            };
            tally[usize::from(same)] += 1;
        }
        assert!(near[1] >= 200 && near[0] * 20 <= near[1], "near: {near:?}");
        assert!(far[0] >= 200 && far[1] * 20 <= far[0], "far: {far:?}");
    }

    /// The angles, seen from the eye, by which the points of `cloud` seen through the side wall
    /// below the surface (`top`) appear shifted to the eye's right of the straw points they come
    /// from, for the straw points that `pick` keeps.
    fn shifts(
        world: &Setup,
        cloud: &[ImagePoint],
        top: f64,
        pick: &dyn Fn(Vec3) -> bool,
    ) -> Vec<f64> {
        let o = world.observer;
        let forward = Vec3::new(-o.x, -o.y, 0.0).normalize();
        let right = forward.cross(Vec3::Z);
        let angle = |d: Vec3| d.dot(right).atan2(d.dot(forward));
        cloud
            .iter()
            .filter(|p| p.straw_point.z < top - 0.01 && pick(p.straw_point))
            .filter(|p| path_of(world, p).entry == Entry::Wall)
            .map(|p| angle(p.direction) - angle(p.straw_point - o))
            .collect()
    }

    /// The mean of `values` and how many there are.
    fn mean(values: impl IntoIterator<Item = f64>) -> (f64, usize) {
        let (sum, n) = values
            .into_iter()
            .fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
        (sum / n as f64, n)
    }

    /// Two straws: under water the one on the axis stays in place on average (it only looks
    /// wider), the one near the side is shifted outwards.
    #[test]
    fn the_straw_near_the_side_jumps_outwards_and_the_one_on_the_axis_does_not() {
        let world = load("two-straws", text_of("two-straws"));
        let cloud = points(&world, 6000);
        let (centre, n1) = mean(shifts(&world, &cloud, 0.13, &|s| s.y.abs() < 0.01));
        let (side, n2) = mean(shifts(&world, &cloud, 0.13, &|s| s.y > 0.01));
        assert!(n1 >= 300 && n2 >= 300, "{n1} {n2}");
        assert!(side.abs() > 0.01, "{side}");
        assert!(centre.abs() < 0.1 * side.abs(), "{centre} against {side}");
    }

    /// A liquid of index 1.63 breaks the straw more than water: the points seen through the
    /// side wall are shifted further from their straw points, on average and either way (the
    /// straw looks wider as well as moved), than with the same liquid at 1.333.
    #[test]
    fn the_dense_liquid_breaks_the_straw_more_than_water() {
        let text = text_of("dense-liquid");
        let dense = load("dense-liquid", text);
        let water = load("water", &edited(text, "index = 1.63", "index = 1.333"));
        let all = |_: Vec3| true;
        let size = |w: &Setup| {
            mean(
                shifts(w, &points(w, 4000), 0.15, &all)
                    .into_iter()
                    .map(f64::abs),
            )
        };
        let ((a, na), (b, nb)) = (size(&dense), size(&water));
        assert!(na >= 300 && nb >= 300);
        assert!(a > 1.2 * b, "{a} against {b}");
    }

    /// Seen from above at a slant, every point seen through the surface straight (no total
    /// reflection) appears above the straw point it comes from; with oil on water, parts are
    /// seen through one surface (in the oil) and through two (in the water below it).
    #[test]
    fn seen_from_above_the_parts_under_the_surface_look_raised() {
        for stem in [
            "leaning-straw-above",
            "oil-on-water-above",
            "pencil-at-a-slant",
        ] {
            let world = load(stem, text_of(stem));
            let cloud = points(&world, 3000);
            let through_top: Vec<&ImagePoint> = cloud
                .iter()
                .filter(|p| {
                    path_of(&world, p)
                        == LightPathType {
                            entry: Entry::Top,
                            total_reflections: 0,
                        }
                })
                .collect();
            assert!(through_top.len() >= 300, "{stem}: {}", through_top.len());
            for p in &through_top {
                assert!(p.position.z > p.straw_point.z, "{stem}: {p:?}");
            }
            if stem == "oil-on-water-above" {
                let once = through_top
                    .iter()
                    .filter(|p| p.straw_point.z > 0.05)
                    .count();
                let twice = through_top
                    .iter()
                    .filter(|p| p.straw_point.z < 0.05)
                    .count();
                assert!(once >= 100 && twice >= 100, "{once} {twice}");
            }
        }
    }
}
