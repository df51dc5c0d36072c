//! Transparent balls against an independent tracer (`support/spheres.rs`: textbook sphere
//! intersection, Snell–Descartes, total reflection and Fresnel's reflectance in double-double,
//! sharing nothing with the library but the scene's numbers): a ball lens, two balls one behind
//! the other, a fish-bowl with a card inside and one outside, each in air beside a tiny empty glass
//! that has no face (so nothing but the balls and cards is in the rays' way). Over many random
//! rays, from near and from afar (up to 10 km), the library's one-ray tracer gives the reference's
//! outcome, its events' points, its final ray or the point reached and the path's length, to
//! 1e-12 m; and in Fresnel mode each card's weight and the escaped, dropped and pruned weights
//! (which add up to 1) to 1e-12. A ray that passes within rounding of a decision (grazing a ball,
//! a card's edge, a tie, a weight at the pruning threshold) is not compared, as in the other
//! reference tests. Where the answer is finer than the ray's own numbers can say (an eye
//! kilometres away, light entering within a micrometre of grazing) the library may differ by
//! twice what one unit in the last place of the ray's numbers changes in the reference's answer:
//! a few rays in a hundred.

#[path = "support/spheres.rs"]
mod spheres;

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::scene_file::SceneDescription;
use bentstraw_optics::world::{FresnelStep, Outcome, World, FRESNEL_SEGMENTS_PER_RAY};
use bentstraw_optics::Vec3;
use spheres::{Ball, BallOutcome, Balls, Card, Prism, Shares, CARD_CODE};

/// Margin (m) above which a ray's answer is not a matter of rounding.
const WELL_POSED: f64 = 1e-9;

/// Agreement asked (m for points and lengths, and for unit directions).
const CLOSE: f64 = 1e-12;

/// The pruning threshold of the Fresnel comparisons.
const PRUNE: f64 = 1e-4;

/// Small deterministic generator (xorshift64*), so the test needs no extra crate.
struct Rng(u64);

impl Rng {
    fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
    /// A random unit vector.
    fn unit(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
    /// A random point of the cube of half-side `half` about `c`.
    fn around(&mut self, c: Vec3, half: f64) -> Vec3 {
        c + half
            * Vec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            )
    }
}

/// The scene file of `balls` and `cards` in air, beside a tiny empty glass at the origin (with
/// no wall and no liquid it has no face), every number written so that it reads back exactly.
fn scene_text(balls: &[Ball], prisms: &[Prism], cards: &[Card]) -> String {
    let mut text = String::from("[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n");
    for p in prisms {
        let corners: Vec<String> = p
            .corners
            .iter()
            .map(|c| format!("[{}, {}]", c[0], c[1]))
            .collect();
        text += &format!(
            "[[prism]]\ncorners = [{}]\nbottom = {}\ntop = {}\nindex = {}\n\n",
            corners.join(", "),
            p.bottom,
            p.top,
            p.index
        );
    }
    for b in balls {
        let c = b.centre;
        text += &format!(
            "[[sphere]]\ncenter = [{}, {}, {}]\nradius = {}\nindex = {}\n\n",
            c.x, c.y, c.z, b.radius, b.index
        );
    }
    for k in cards {
        let c = k.centre;
        text += &format!(
            "[[card]]\ncenter = [{}, {}, {}]\nfacing = {}\nwidth = {}\nheight = {}\npicture = \"none\"\n\n",
            c.x, c.y, c.z, k.facing_deg, k.width, k.height
        );
    }
    text
}

/// The library's world and the reference for the same numbers.
fn both(balls: &[Ball], cards: &[Card], max_events: u32) -> (World, Balls) {
    both_with_prisms(balls, &[], cards, max_events)
}

/// The same with `prisms` besides.
fn both_with_prisms(
    balls: &[Ball],
    prisms: &[Prism],
    cards: &[Card],
    max_events: u32,
) -> (World, Balls) {
    let text = scene_text(balls, prisms, cards);
    let d = SceneDescription::from_toml(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let world = World::new(&d, max_events).unwrap_or_else(|e| panic!("{e}\n{text}"));
    (
        world,
        Balls::new(balls, cards, max_events).with_prisms(prisms),
    )
}

/// What was compared over the rays: rays shot, compared in course and in Fresnel mode, with
/// events, ending on cards, dropped, from eyes 10 m away or more, compared to the wider
/// tolerance.
#[derive(Default, Debug)]
struct Tally {
    rays: usize,
    compared: usize,
    with_events: usize,
    on_cards: usize,
    dropped: usize,
    far: usize,
    fresnel: usize,
    widened: usize,
}

/// How far an answer moves: its points (m), its final direction, its length (m), its weights.
#[derive(Clone, Copy, Debug, Default)]
struct Spread {
    point: f64,
    direction: f64,
    length: f64,
    weight: f64,
}

impl Spread {
    /// Widens to cover `other` against `want`; `None` if it is another kind of answer.
    fn widen(&mut self, other: &BallOutcome, want: &BallOutcome) -> Option<()> {
        let points = |a: &[Vec3], b: &[Vec3]| {
            (a.len() == b.len()).then(|| {
                a.iter()
                    .zip(b)
                    .map(|(p, q)| (*p - *q).length())
                    .fold(0.0, f64::max)
            })
        };
        match (other, want) {
            (
                BallOutcome::Card {
                    card: c1,
                    point: p1,
                    length: l1,
                    events: e1,
                },
                BallOutcome::Card {
                    card: c2,
                    point: p2,
                    length: l2,
                    events: e2,
                },
            ) if c1 == c2 => {
                self.point = self.point.max(points(e1, e2)?).max((*p1 - *p2).length());
                self.length = self.length.max((l1 - l2).abs());
            }
            (
                BallOutcome::Escaped {
                    events: e1,
                    direction: d1,
                },
                BallOutcome::Escaped {
                    events: e2,
                    direction: d2,
                },
            ) => {
                self.point = self.point.max(points(e1, e2)?);
                self.direction = self.direction.max((*d1 - *d2).length());
            }
            (BallOutcome::Dropped, BallOutcome::Dropped) => {}
            _ => return None,
        }
        Some(())
    }

    /// Widens to cover the Fresnel shares `other` against `want`.
    fn widen_shares(&mut self, other: &Shares, want: &Shares) {
        let gaps = other
            .cards
            .iter()
            .zip(want.cards)
            .map(|(a, b)| (a - b).abs())
            .chain([
                (other.escaped - want.escaped).abs(),
                (other.dropped - want.dropped).abs(),
                (other.pruned - want.pruned).abs(),
            ]);
        self.weight = gaps.fold(self.weight, f64::max);
    }
}

/// How far the reference's answers (course and Fresnel) move when one of the ray's six numbers
/// moves by one unit in its last place, either way. Where it is more than `CLOSE` the answer is
/// finer than the ray's own numbers can say (light entering a ball within a micrometre of
/// grazing, where the exit direction turns a million times faster than the ray moves; an eye
/// kilometres away, whose last digit moves the ray a nanometre at the ball): an answer exact for
/// a ray a rounding away is as right. `None` when a nudge changes the kind of answer.
fn sensitivity(reference: &Balls, ray: Ray, want: &BallOutcome, shares: &Shares) -> Option<Spread> {
    let mut spread = Spread::default();
    for which in 0..6 {
        for step in [-1i64, 1] {
            let mut numbers = [ray.origin.to_array(), ray.direction.to_array()];
            let x = &mut numbers[which / 3][which % 3];
            *x = f64::from_bits((x.to_bits() as i64 + step) as u64);
            let nudged = Ray {
                origin: Vec3::from_array(numbers[0]),
                direction: Vec3::from_array(numbers[1]),
            };
            spread.widen(&reference.trace(nudged).0, want)?;
            spread.widen_shares(&reference.fresnel(nudged, PRUNE).0, shares);
        }
    }
    Some(spread)
}

/// Compares `ray` by the library and the reference, course and Fresnel, where well posed: to
/// `CLOSE`, or where that fails, to `CLOSE` plus twice the answer's [`sensitivity`] to the ray's
/// own rounding (counted in `tally.widened`).
fn check(world: &World, reference: &Balls, ray: Ray, tally: &mut Tally) {
    tally.rays += 1;
    let (want, margin) = reference.trace(ray);
    let (shares, fresnel_margin) = reference.fresnel(ray, PRUNE);
    let (course, fresnel) = (margin >= WELL_POSED, fresnel_margin >= WELL_POSED);
    if compare(
        world,
        ray,
        (course, &want),
        (fresnel, &shares),
        Spread::default(),
    )
    .is_err()
    {
        tally.widened += 1;
        let Some(spread) = sensitivity(reference, ray, &want, &shares) else {
            return; // a rounding of the ray changes the answer: either is right
        };
        if let Err(e) = compare(world, ray, (course, &want), (fresnel, &shares), spread) {
            panic!("{e} ({spread:?})");
        }
    }
    tally.compared += usize::from(course);
    tally.fresnel += usize::from(fresnel);
    tally.far += usize::from(ray.origin.length() >= 10.0);
    if !course {
        return;
    }
    let mut events = Vec::new();
    world.trace_with(ray, |e| events.push(*e));
    tally.with_events += usize::from(!events.is_empty());
    match want {
        BallOutcome::Card { .. } => tally.on_cards += 1,
        BallOutcome::Dropped => tally.dropped += 1,
        BallOutcome::Escaped { .. } => {}
    }
    // Every event is Snell's, and a ball in air never reflects totally light that came in from
    // the air (a prism may: between two of its faces light meets the next past the critical
    // angle).
    for e in &events {
        if e.totally_reflected && reference.has_prisms() {
            continue;
        }
        assert!(!e.totally_reflected, "{e:?}");
        let sine = |d: Vec3| d.cross(e.normal).length();
        assert!((e.n1 * sine(e.incoming) - e.n2 * sine(e.outgoing)).abs() < 1e-12);
    }
}

/// The library's answers for `ray` against the reference's `want` (if `course`) and `shares` (if
/// `fresnel`), each number to `CLOSE` plus twice its `spread`: what differs, if anything.
fn compare(
    world: &World,
    ray: Ray,
    (course, want): (bool, &BallOutcome),
    (fresnel, shares): (bool, &Shares),
    spread: Spread,
) -> Result<(), String> {
    let close = |a: Vec3, b: Vec3, spread: f64| (a - b).length() <= CLOSE + 2.0 * spread;
    let fail = |what: &str, got: &dyn std::fmt::Debug| {
        Err(format!(
            "{ray:?}: {what}: library {got:?}, reference {want:?}"
        ))
    };
    if course {
        let mut events = Vec::new();
        let got = world.trace_with(ray, |e| events.push(*e));
        let points: Vec<Vec3> = events.iter().map(|e| e.point).collect();
        let same_events = |want: &[Vec3]| {
            points.len() == want.len()
                && points
                    .iter()
                    .zip(want)
                    .all(|(a, b)| close(*a, *b, spread.point))
        };
        match (&got, want) {
            (
                Outcome::Object {
                    color,
                    point,
                    path_length,
                    events: n,
                    object,
                    ..
                },
                BallOutcome::Card {
                    card,
                    point: p,
                    length,
                    events: e,
                },
            ) => {
                if (*color, *object, *n as usize) != (CARD_CODE, *card, e.len()) {
                    return fail("what it meets", &got);
                }
                if !same_events(e) {
                    return fail("events", &points);
                }
                if !close(*point, *p, spread.point)
                    || (path_length - length).abs() > CLOSE + 2.0 * spread.length
                {
                    return fail("point or length", &got);
                }
            }
            (
                Outcome::Escaped {
                    events: n,
                    ray: out,
                },
                BallOutcome::Escaped {
                    events: e,
                    direction,
                },
            ) => {
                if *n as usize != e.len() || !same_events(e) {
                    return fail("events", &points);
                }
                if !close(out.direction, *direction, spread.direction)
                    || e.last()
                        .is_some_and(|last| !close(out.origin, *last, spread.point))
                {
                    return fail("final ray", &got);
                }
            }
            (Outcome::Dropped, BallOutcome::Dropped) => {}
            _ => return fail("outcome", &got),
        }
    }
    if fresnel {
        let (mut cards, mut escaped, mut dropped, mut pruned) = ([0.0; 4], 0.0, 0.0, 0.0);
        let weights =
            world.fresnel_steps::<false>(ray, PRUNE, FRESNEL_SEGMENTS_PER_RAY, |s| match s {
                FresnelStep::Object { object, weight, .. } => cards[object] += weight,
                FresnelStep::Escaped { weight, .. } => escaped += weight,
                FresnelStep::Dropped { weight } => dropped += weight,
                FresnelStep::Pruned { weight } => pruned += weight,
                _ => {}
            });
        let near = |a: f64, b: f64| (a - b).abs() <= CLOSE + 2.0 * spread.weight;
        let got = (cards, escaped, dropped, pruned);
        if !(cards.iter().zip(shares.cards).all(|(a, b)| near(*a, b))
            && near(escaped, shares.escaped)
            && near(dropped, shares.dropped)
            && near(pruned, shares.pruned))
        {
            return Err(format!(
                "{ray:?}: Fresnel: library {got:?}, reference {shares:?}"
            ));
        }
        // All the light is told, and the returned weights are the cards'.
        let total = cards.iter().sum::<f64>() + escaped + dropped + pruned;
        assert!((total - 1.0).abs() < 1e-12, "{ray:?}: {got:?}");
        let on_cards: f64 = cards.iter().sum();
        let card = CARD_CODE as usize - 1;
        assert!((weights[card] - on_cards).abs() <= 1e-15, "{weights:?}");
        assert!(weights
            .iter()
            .enumerate()
            .all(|(i, &w)| i == card || w == 0.0));
    }
    Ok(())
}

/// An eye at a random distance from `c` (outside the ball of radius `r` there): mostly within a
/// metre, sometimes 100 m to 10 km away.
fn eye(rng: &mut Rng, c: Vec3, r: f64) -> Vec3 {
    let dist = if rng.next_f64() < 0.1 {
        10f64.powf(rng.range(2.0, 4.0))
    } else {
        rng.range(1.2 * r + 0.01, 1.0)
    };
    c + dist * rng.unit()
}

/// A ball's centre in air, clear of the tiny glass at the origin.
fn somewhere(rng: &mut Rng) -> Vec3 {
    let (rho, bearing) = (rng.range(0.2, 0.5), rng.range(0.0, std::f64::consts::TAU));
    Vec3::new(
        rho * bearing.cos(),
        rho * bearing.sin(),
        rng.range(-0.2, 0.3),
    )
}

/// An index in 1..2, sometimes exactly 1 (no ball at all then).
fn index(rng: &mut Rng) -> f64 {
    if rng.next_f64() < 0.05 {
        1.0
    } else {
        rng.range(1.0, 2.0)
    }
}

/// An event limit: mostly 10, sometimes 1 (a ray through a ball is dropped) or 3.
fn limit(rng: &mut Rng) -> u32 {
    match rng.next_f64() {
        x if x < 0.1 => 1,
        x if x < 0.2 => 3,
        _ => 10,
    }
}

/// The tally's shares are what a comparison over `what` needs to mean something.
fn assert_meaningful(what: &str, t: &Tally, cards: bool) {
    eprintln!("{what}: {t:?}");
    assert!(t.compared * 100 >= t.rays * 99, "{what}: {t:?}");
    assert!(t.fresnel * 100 >= t.rays * 98, "{what}: {t:?}");
    assert!(t.with_events * 3 >= t.compared, "{what}: {t:?}");
    assert!(t.dropped > 0, "{what}: {t:?}");
    // Only rays from afar, or grazing a ball within a micrometre, need the wider tolerance.
    assert!(t.widened * 20 <= t.rays, "{what}: {t:?}");
    if cards {
        assert!(t.on_cards * 10 >= t.compared, "{what}: {t:?}");
    }
}

#[test]
fn a_ball_lens_traces_as_the_independent_tracer_says() {
    let mut rng = Rng(0x5EED_BA11_0001);
    let mut tally = Tally::default();
    for _ in 0..40 {
        let ball = Ball {
            centre: somewhere(&mut rng),
            radius: rng.range(0.003, 0.06),
            index: index(&mut rng),
        };
        let (world, reference) = both(&[ball], &[], limit(&mut rng));
        let (c, r) = (ball.centre, ball.radius);
        for k in 0..400 {
            let from = eye(&mut rng, c, r);
            // Mostly at the ball; some through its centre, some along its axis's parallels.
            let aim = match k % 8 {
                0 => c,
                _ => rng.around(c, 1.1 * r),
            };
            check(&world, &reference, Ray::new(from, aim - from), &mut tally);
        }
        for h in [0.0, 0.3, 0.7, 0.99, 0.999_999] {
            let from = c + Vec3::new(-0.5, h * r, 0.0);
            check(&world, &reference, Ray::new(from, Vec3::X), &mut tally);
        }
    }
    assert_meaningful("ball lens", &tally, false);
}

#[test]
fn two_balls_one_behind_the_other_trace_as_the_independent_tracer_says() {
    let mut rng = Rng(0x5EED_BA11_0002);
    let mut tally = Tally::default();
    for _ in 0..40 {
        let (r1, r2) = (rng.range(0.005, 0.05), rng.range(0.005, 0.05));
        let first = somewhere(&mut rng);
        let along = rng.unit();
        let second = first + (r1 + r2 + rng.range(0.001, 0.1)) * along;
        let balls = [
            Ball {
                centre: first,
                radius: r1,
                index: index(&mut rng),
            },
            Ball {
                centre: second,
                radius: r2,
                index: index(&mut rng),
            },
        ];
        let (world, reference) = both(&balls, &[], limit(&mut rng));
        for _ in 0..400 {
            // From before the first ball, along the line of centres, at a point of either ball.
            let from = first - rng.range(1.5 * r1 + 0.01, 0.8) * along + rng.around(Vec3::ZERO, r1);
            let (c, r) = if rng.next_f64() < 0.5 {
                (first, r1)
            } else {
                (second, r2)
            };
            let aim = rng.around(c, 1.1 * r);
            if (from - first).length() <= r1 || (from - second).length() <= r2 {
                continue;
            }
            check(&world, &reference, Ray::new(from, aim - from), &mut tally);
        }
    }
    assert_meaningful("two balls", &tally, false);
}

#[test]
fn a_fish_bowl_and_a_card_behind_it_trace_as_the_independent_tracer_says() {
    let mut rng = Rng(0x5EED_BA11_0003);
    let mut tally = Tally::default();
    for _ in 0..40 {
        let r = rng.range(0.02, 0.06);
        let bowl = Ball {
            centre: somewhere(&mut rng),
            radius: r,
            index: index(&mut rng),
        };
        let c = bowl.centre;
        // A card inside (its corners within 0.9 r of the centre), facing anywhere, and one
        // outside beyond it, facing it.
        let (w, h) = (rng.range(0.2, 1.2) * r, rng.range(0.2, 1.2) * r);
        let shrink = (0.9 * r / (0.5 * w.hypot(h))).min(1.0);
        let beyond = rng.range(0.0, 360.0f64);
        let cards = [
            Card {
                centre: c + rng.around(Vec3::ZERO, 0.05 * r),
                facing_deg: rng.range(0.0, 360.0),
                width: w * shrink * 0.9,
                height: h * shrink * 0.9,
            },
            Card {
                centre: c
                    + (r + 0.03)
                        * Vec3::new(beyond.to_radians().cos(), beyond.to_radians().sin(), 0.0),
                facing_deg: beyond + 180.0,
                width: 0.03,
                height: 0.02,
            },
        ];
        let (world, reference) = both(&[bowl], &cards, limit(&mut rng));
        for _ in 0..400 {
            let from = eye(&mut rng, c, r);
            let aim = if rng.next_f64() < 0.7 {
                rng.around(cards[0].centre, 0.6 * r)
            } else {
                rng.around(cards[1].centre, 0.02)
            };
            check(&world, &reference, Ray::new(from, aim - from), &mut tally);
        }
    }
    assert_meaningful("fish-bowl", &tally, true);
}

/// A prism in air (a triangle, at times a 60° one, seen from above; planes for faces, sharp
/// edges and corners) beside a card: rays from near and far at it, some level (through its sides
/// only), compared as for the balls.
#[test]
fn a_prism_in_air_traces_as_the_independent_tracer_says() {
    let mut rng = Rng(0x5EED_9815_0004);
    let mut tally = Tally::default();
    for _ in 0..40 {
        let c = somewhere(&mut rng);
        let side = rng.range(0.01, 0.06);
        let height = rng.range(0.01, 0.08);
        let turn = rng.range(0.0, std::f64::consts::TAU);
        let regular = rng.next_f64() < 0.5;
        let corners: Vec<[f64; 2]> = (0..3)
            .map(|j| {
                // A 60° prism, or a triangle with its corners nudged.
                let a = turn
                    + std::f64::consts::TAU * j as f64 / 3.0
                    + if regular { 0.0 } else { rng.range(-0.4, 0.4) };
                let r = side / 3f64.sqrt() * if regular { 1.0 } else { rng.range(0.7, 1.3) };
                [c.x + r * a.cos(), c.y + r * a.sin()]
            })
            .collect();
        let prism = Prism {
            corners,
            bottom: c.z - height / 2.0,
            top: c.z + height / 2.0,
            index: index(&mut rng),
        };
        let r = (side / 3f64.sqrt() * 1.3).hypot(height / 2.0);
        let beyond = rng.range(0.0, 360.0f64);
        let card = Card {
            centre: c
                + (r + 0.03) * Vec3::new(beyond.to_radians().cos(), beyond.to_radians().sin(), 0.0),
            facing_deg: beyond + 180.0,
            width: 0.04,
            height: 0.03,
        };
        let (world, reference) = both_with_prisms(&[], &[prism], &[card], limit(&mut rng));
        for k in 0..400 {
            let from = eye(&mut rng, c, r);
            let aim = match k % 4 {
                0 => rng.around(card.centre, 0.02),
                1 => rng.around(c, 1.1 * r),
                _ => rng.around(c, 0.4 * r),
            };
            check(&world, &reference, Ray::new(from, aim - from), &mut tally);
        }
        // Level rays through the sides only (the bottom and top never met).
        for _ in 0..40 {
            let from = c
                + Vec3::new(0.0, 0.0, rng.range(-0.4, 0.4) * height)
                + (r + 0.05) * {
                    let a = rng.range(0.0, std::f64::consts::TAU);
                    Vec3::new(a.cos(), a.sin(), 0.0)
                };
            let aim = rng.around(c, 0.5 * r);
            let aim = Vec3::new(aim.x, aim.y, from.z);
            check(&world, &reference, Ray::new(from, aim - from), &mut tally);
        }
    }
    assert_meaningful("prism", &tally, true);
}
