//! The kind of light path that makes an image point, in a teacher's words: the kind of face by
//! which the ray from the eye enters the liquid or the container (or none: the object seen
//! directly through air) and how many total reflections it undergoes on its way. The same names
//! serve every scene: a glass or a tank, water or any liquid.
//!
//! The first event of a ray coming from air is always a refraction into a denser medium (light
//! going into a denser medium is never totally reflected), so the entry face is the first
//! event's face.

use std::fmt;

/// The face by which a ray from the eye enters the liquid (or the container's material), or none.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Entry {
    /// The ray reaches the straw through air only (no event).
    Direct,
    /// Through a horizontal face met from above: a liquid's free surface (or a glass's rim).
    Top,
    /// Through a side wall (a glass's or a tank's).
    Wall,
    /// Through a horizontal face met from below: the container's bottom.
    Bottom,
    /// Through a transparent solid's face first (a sphere: a marble, a drop, a bowl of water).
    Solid,
}

/// The kind of a ray's light path: its entry face and its count of total reflections.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct LightPathType {
    /// How the ray enters.
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

    /// A short stable key, e.g. `direct`, `top`, `wall+1` (for data files and the page).
    pub fn key(&self) -> String {
        let base = match self.entry {
            Entry::Direct => "direct",
            Entry::Top => "top",
            Entry::Wall => "wall",
            Entry::Bottom => "bottom",
            Entry::Solid => "solid",
        };
        match self.total_reflections {
            0 => base.to_string(),
            k => format!("{base}+{k}"),
        }
    }

    /// The colour every figure and the page draw this kind of path in, whatever else the
    /// picture shows: one hue per entry face (direct grey, surface blue, wall orange, bottom
    /// green, solid teal), another once the light has been totally reflected (purple, red,
    /// brown, dark teal), darker with each further reflection.
    pub fn rgb(&self) -> [u8; 3] {
        let base: [u8; 3] = match (self.entry, self.total_reflections) {
            (Entry::Direct, _) => [70, 70, 70],
            (Entry::Top, 0) => [31, 119, 180],
            (Entry::Top, _) => [148, 103, 189],
            (Entry::Wall, 0) => [255, 127, 14],
            (Entry::Wall, _) => [214, 39, 40],
            (Entry::Bottom, 0) => [44, 160, 44],
            (Entry::Bottom, _) => [140, 86, 75],
            (Entry::Solid, 0) => [23, 190, 207],
            (Entry::Solid, _) => [0, 110, 120],
        };
        // Each reflection past the first darkens by a quarter, down to a third of the hue.
        let darker = 0.75f64.powi(self.total_reflections.saturating_sub(1).min(4) as i32);
        base.map(|c| (c as f64 * darker).round() as u8)
    }

    /// [`LightPathType::rgb`] as CSS and SVG write it: `#rrggbb`.
    pub fn hex(&self) -> String {
        crate::text::css_hex(self.rgb())
    }
}

impl LightPathType {
    /// In French, the explorer's words: "direct (dans l'air)", "par la paroi latérale, 1 réflexion
    /// totale", …
    pub fn french(&self) -> String {
        let entry = match self.entry {
            Entry::Direct => "direct (dans l'air)",
            Entry::Top => "par la surface libre",
            Entry::Wall => "par la paroi latérale",
            Entry::Bottom => "par le fond",
            Entry::Solid => "par un solide transparent",
        };
        match self.total_reflections {
            0 => entry.to_string(),
            1 => format!("{entry}, 1 réflexion totale"),
            k => format!("{entry}, {k} réflexions totales"),
        }
    }
}

impl fmt::Display for LightPathType {
    /// In words: "direct (through air)", "through the wall, 1 total reflection", …
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self.entry {
            Entry::Direct => "direct (through air)",
            Entry::Top => "through the surface",
            Entry::Wall => "through the side wall",
            Entry::Bottom => "through the bottom",
            Entry::Solid => "through a transparent solid",
        })?;
        match self.total_reflections {
            0 => Ok(()),
            1 => f.write_str(", 1 total reflection"),
            k => write!(f, ", {k} total reflections"),
        }
    }
}
