//! The rays a ray diagram draws: a sample of the image's rays spread over the straw's sections and
//! over the kinds of light path, each with its broken path (the eye, every event, the straw point)
//! and its image point, so that a diagram shows which path made which piece of the image.

use std::collections::BTreeMap;

use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::light_path_type::LightPathType;
use crate::world::{Event, World};
use crate::Vec3;

/// One ray from the eye to the straw, as a diagram draws it.
#[derive(Clone, Debug, PartialEq)]
pub struct DiagramRay {
    /// The image point it makes (course's convention).
    pub image: ImagePoint,
    /// Its events, in order.
    pub events: Vec<Event>,
    /// The kind of its light path.
    pub kind: LightPathType,
}

impl DiagramRay {
    /// The broken path's vertices: the eye, each event's point, the straw point.
    pub fn vertices(&self, observer: Vec3) -> Vec<Vec3> {
        std::iter::once(observer)
            .chain(self.events.iter().map(|e| e.point))
            .chain(std::iter::once(self.image.straw_point))
            .collect()
    }
}

/// The ray from `observer` along unit `u0` through `world`, with its events, if it reaches an
/// object.
pub fn diagram_ray(world: &World, observer: Vec3, u0: Vec3) -> Option<DiagramRay> {
    let mut events = Vec::new();
    let mut kind = LightPathType::DIRECT;
    let outcome = world.trace_with(
        Ray {
            origin: observer,
            direction: u0,
        },
        |e| {
            kind.record_entry(world.entry_of(e), e.totally_reflected);
            events.push(*e);
        },
    );
    Some(DiagramRay {
        image: outcome.image_point(observer, u0)?,
        events,
        kind,
    })
}

/// The ray of image point `p` seen from `observer`, traced again in the world it was traced in.
fn point_ray(world: &World, observer: Vec3, p: &ImagePoint) -> Option<DiagramRay> {
    let mut ray = diagram_ray(world.of_point(p), observer, p.direction)?;
    ray.image.band = p.band;
    Some(ray)
}

/// Image points per kind of light path, most common first (ties by kind).
pub fn path_type_counts(
    world: &World,
    observer: Vec3,
    points: &[ImagePoint],
) -> Vec<(LightPathType, usize)> {
    let mut counts: BTreeMap<LightPathType, usize> = BTreeMap::new();
    for p in points {
        if let Some(r) = point_ray(world, observer, p) {
            *counts.entry(r.kind).or_default() += 1;
        }
    }
    let mut v: Vec<_> = counts.into_iter().collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    v
}

/// About `count` rays of `points` for a diagram: every group (section colour × kind of light path)
/// gets its share, at least one ray, spread evenly through the group (the points come in the
/// sampler's order, which sweeps across the image), so rare paths — the pieces made by total
/// reflection — are drawn too.
pub fn diagram_rays(
    world: &World,
    observer: Vec3,
    points: &[ImagePoint],
    count: usize,
) -> Vec<DiagramRay> {
    let mut groups: BTreeMap<(u8, LightPathType), Vec<DiagramRay>> = BTreeMap::new();
    for p in points {
        if let Some(r) = point_ray(world, observer, p) {
            groups.entry((p.color, r.kind)).or_default().push(r);
        }
    }
    if groups.is_empty() || count == 0 {
        return Vec::new();
    }
    let total: usize = groups.values().map(Vec::len).sum();
    let mut chosen = Vec::new();
    for rays in groups.values() {
        let share = ((count * rays.len()) as f64 / total as f64).round() as usize;
        let n = share.clamp(1, rays.len());
        for k in 0..n {
            // Evenly spread, centred in each of n equal slices of the group.
            let i = ((k as f64 + 0.5) * rays.len() as f64 / n as f64) as usize;
            chosen.push(rays[i.min(rays.len() - 1)].clone());
        }
    }
    chosen
}
