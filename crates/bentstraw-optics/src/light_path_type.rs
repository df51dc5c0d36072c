//! The kind of light path that makes an image point, in a teacher's words: which water face the
//! ray from the eye enters by (or none: the straw seen directly through air) and how many total
//! reflections it undergoes on its way to the straw.
//!
//! The first event of a ray coming from air is always a refraction into the water (light going
//! into a denser medium is never totally reflected), so the entry face is the first event's face.

use std::fmt;

use crate::geometry::Ray;
use crate::scene::Scene;
use crate::trace::{Event, Face, NearestFace, Outcome};

/// The water face by which a ray from the eye enters the water, or none.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Entry {
    /// The ray reaches the straw through air only (no event).
    Direct,
    /// Into the water through its free surface.
    Top,
    /// Into the water through the glass's side wall.
    Wall,
    /// Into the water through the glass's bottom.
    Bottom,
}

/// The kind of a ray's light path: its entry face and its count of total reflections.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct LightPathType {
    /// How the ray enters the water.
    pub entry: Entry,
    /// Total internal reflections on the way.
    pub total_reflections: u32,
}

impl LightPathType {
    /// The path of a ray that has met no water face yet.
    pub const DIRECT: LightPathType = LightPathType {
        entry: Entry::Direct,
        total_reflections: 0,
    };

    /// Takes one more event of the ray into account (events in the order they happen).
    #[inline]
    pub fn record(&mut self, event: &Event) {
        let entry = match event.face {
            Face::WaterTop => Entry::Top,
            Face::WaterBottom => Entry::Bottom,
            _ => Entry::Wall,
        };
        self.record_entry(entry, event.totally_reflected);
    }

    /// Takes one more event into account by the kind of face it happens on: the first one's is
    /// how the ray enters.
    #[inline]
    pub fn record_entry(&mut self, entry: Entry, totally_reflected: bool) {
        if self.entry == Entry::Direct {
            self.entry = entry;
        }
        if totally_reflected {
            self.total_reflections += 1;
        }
    }

    /// The path type of a sequence of events.
    pub fn of_events<'a>(events: impl IntoIterator<Item = &'a Event>) -> LightPathType {
        let mut t = LightPathType::DIRECT;
        for e in events {
            t.record(e);
        }
        t
    }

    /// A short stable key, e.g. `direct`, `top`, `wall+1` (for data files and the page).
    pub fn key(&self) -> String {
        let base = match self.entry {
            Entry::Direct => "direct",
            Entry::Top => "top",
            Entry::Wall => "wall",
            Entry::Bottom => "bottom",
        };
        match self.total_reflections {
            0 => base.to_string(),
            k => format!("{base}+{k}"),
        }
    }
}

impl fmt::Display for LightPathType {
    /// In words: "direct (through air)", "through the wall, 1 total reflection", …
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self.entry {
            Entry::Direct => "direct (through air)",
            Entry::Top => "through the water's surface",
            Entry::Wall => "through the glass's wall",
            Entry::Bottom => "through the glass's bottom",
        })?;
        match self.total_reflections {
            0 => Ok(()),
            1 => f.write_str(", 1 total reflection"),
            k => write!(f, ", {k} total reflections"),
        }
    }
}

/// Traces `ray` (from air) through `faces` by the course's law, with the event limit of `scene`
/// (the same scene, or the same with another limit), and tells the kind of its light path.
pub fn trace_path_type(
    faces: &impl NearestFace,
    scene: &Scene,
    ray: Ray,
) -> (Outcome, LightPathType) {
    let mut kind = LightPathType::DIRECT;
    let outcome = faces
        .prepared()
        .trace_limited(ray, scene.max_events, |e| kind.record(e));
    (outcome, kind)
}
