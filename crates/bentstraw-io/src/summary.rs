//! The one-screen summaries `simulate` prints when it is done: what was traced, how many image
//! points of each colour, the time taken, the files written; and what the eye and stereo models
//! placed.

use std::fmt::Write as _;
use std::time::Duration;

use bentstraw_optics::spectrum::{white_bands, WHITE_BANDS};
use bentstraw_optics::world::COLOR_NAMES;

use crate::writers::{ModelPoints, PointSet};

/// The one-screen summary printed on stderr; `written` names the files written, one a line.
pub fn summary(set: &PointSet, traced: Duration, total: Duration, written: &[String]) -> String {
    let (o, cloud) = (set.scene.observer, set.cloud);
    let mut t = String::new();
    // What was traced: the straw by its values, a scene file by its name.
    let scene = set.scene;
    let _ = writeln!(
        t,
        "bentstraw simulate: the virtual image of {} ({} model)",
        scene.subject().unwrap_or(scene.name()),
        set.image_model()
    );
    let _ = writeln!(t, "  observer        ({}, {}, {}) m", o.x, o.y, o.z);
    let values: Vec<String> = scene
        .inputs()
        .iter()
        .filter_map(|i| i.heading_phrase())
        .collect();
    if !values.is_empty() {
        let _ = writeln!(t, "  scene           {}", values.join(", "));
    }
    let _ = writeln!(t, "  event limit     {}", scene.world.max_events());
    if cloud.white {
        // Where nothing disperses every band's rays bend alike: say so, as the points show no
        // colour apart.
        let parted = if scene.world.white_light().is_empty() {
            "nothing in the scene disperses: every band is bent alike"
        } else {
            "each ray traced at its band's wavelength"
        };
        let bands = white_bands();
        let _ = writeln!(
            t,
            "  light           white: {WHITE_BANDS} bands in turn, {} to {} nm; {parted}",
            bands[0].nm,
            bands[WHITE_BANDS - 1].nm
        );
    }
    // The colours the scene's objects can show; a scene file's only where seen (a card has no red).
    let counts: Vec<(usize, usize)> = cloud.counts_per_code()[..scene.colour_names().len()]
        .iter()
        .copied()
        .enumerate()
        .filter(|&(_, n)| n > 0 || scene.lists_unseen_colours())
        .collect();
    let _ = writeln!(t, "  rays traced     {}", cloud.rays_traced);
    let _ = writeln!(
        t,
        "  image points    {} (asked for at least {})",
        cloud.points.len(),
        set.min_points
    );
    for (k, n) in counts {
        let _ = writeln!(t, "    {} {:<8} {:>8}", k + 1, COLOR_NAMES[k], n);
    }
    let _ = writeln!(
        t,
        "  hit ratio       {:.1} % of the rays reached {}",
        100.0 * cloud.hit_ratio(),
        scene.subject().unwrap_or("an object")
    );
    let _ = writeln!(
        t,
        "  time            {:.3} s tracing, {:.3} s in all",
        traced.as_secs_f64(),
        total.as_secs_f64()
    );
    if let Some((first, rest)) = written.split_first() {
        let _ = writeln!(t, "  wrote           {first}");
        for w in rest {
            let _ = writeln!(t, "                  {w}");
        }
    }
    if cloud.points.len() < set.min_points {
        let invisible = match set.scene.subject() {
            Some(subject) => format!("{subject} is"),
            None => "the objects are".to_string(),
        };
        let _ = writeln!(
            t,
            "  note            fewer points than asked: {invisible} all but invisible from here"
        );
    }
    t
}

/// The lines of the summary about the eye or stereo model: points placed, and why others are not.
pub fn model_summary(set: &PointSet, time: Duration) -> String {
    let mut t = String::new();
    match set.model {
        ModelPoints::Course => {}
        ModelPoints::Eye(points) => {
            let placed = points.iter().filter(|p| p.position.is_some()).count();
            let _ = writeln!(
                t,
                "  eye model       {placed} of {} points placed at (s_h + s_v)/2",
                points.len()
            );
            let mut kinds: Vec<(&str, usize)> = Vec::new();
            for p in points.iter().filter(|p| p.position.is_none()) {
                let k = if p.s_h.kind() != "in_front" {
                    p.s_h.kind()
                } else {
                    p.s_v.kind()
                };
                match kinds.iter_mut().find(|(name, _)| *name == k) {
                    Some((_, n)) => *n += 1,
                    None => kinds.push((k, 1)),
                }
            }
            for (k, n) in kinds {
                let _ = writeln!(
                    t,
                    "    no position   {n} with a focus {}",
                    k.replace('_', " ")
                );
            }
            let gaps: Vec<f64> = points.iter().filter_map(|p| p.gap_to_course()).collect();
            if let Some(max) = gaps.iter().copied().reduce(f64::max) {
                let _ = writeln!(t, "  gap to course   up to {:.2} mm", 1e3 * max);
            }
        }
        ModelPoints::Stereo(s) => {
            let placed = s.points.iter().filter(|p| p.position.is_some()).count();
            let _ = writeln!(
                t,
                "  stereo model    {placed} points seen by both eyes and triangulated, {} seen by one eye only",
                s.skipped
            );
            let gaps: Vec<f64> = s.points.iter().filter_map(|p| p.gap_to_course()).collect();
            if let Some(max) = gaps.iter().copied().reduce(f64::max) {
                let _ = writeln!(t, "  gap to course   up to {:.2} mm", 1e3 * max);
            }
        }
    }
    let _ = writeln!(t, "  model time      {:.3} s", time.as_secs_f64());
    t
}
