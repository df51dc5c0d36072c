//! The glass, the water and the straw, and the rules a valid simulation obeys.

use std::fmt;

use crate::rule::{self, Param, Params, Rule};
use crate::Vec3;

/// Radius of the glass `Rv` (m).
pub const GLASS_RADIUS: f64 = 0.04;
/// Height of the glass `Hv` (m).
pub const GLASS_HEIGHT: f64 = 0.20;
/// Radius of the straw `Rp` (m).
pub const STRAW_RADIUS: f64 = 0.005;
/// Height of the straw `Hp` (m).
pub const STRAW_HEIGHT: f64 = 0.25;
/// Number of coloured sections of the straw.
pub const SECTION_COUNT: usize = 5;
/// Height of one coloured section (m).
pub const SECTION_HEIGHT: f64 = STRAW_HEIGHT / SECTION_COUNT as f64;
/// Default refractive index of water.
pub const WATER_INDEX: f64 = 1.333;
/// Default limit on events (refractions and reflections) per ray.
pub const DEFAULT_MAX_EVENTS: u32 = 10;
/// Largest event limit accepted.
pub const MAX_EVENTS_LIMIT: u32 = 1000;
/// Display colours of the sections, codes 1..=5 (index 0 is code 1), RGB in 0..1.
pub const SECTION_RGB: [[f64; 3]; SECTION_COUNT] = [
    [1.0, 0.0, 0.0],
    [0.929, 0.694, 0.125],
    [1.0, 0.0, 1.0],
    [0.0, 0.8, 0.0],
    [0.0, 0.0, 1.0],
];
/// Names of the sections' colours, codes 1..=5.
pub const SECTION_NAMES: [&str; SECTION_COUNT] = ["red", "orange", "magenta", "green", "blue"];
/// The sections' colour names in French, as the explorer names them.
pub const SECTION_NAMES_FR: [&str; SECTION_COUNT] = ["rouge", "orange", "magenta", "vert", "bleu"];

/// Lower edges of sections 2..=5 (m), written out so that `z = 0.15` is exactly an edge.
pub const SECTION_EDGES: [f64; SECTION_COUNT - 1] = [0.05, 0.10, 0.15, 0.20];

/// The colour code (1 = red at the bottom … 5 = blue at the top) of the straw at height `z`.
///
/// Compared with the edges, not computed as `floor(z / 0.05)`: `0.15 / 0.05` rounds to
/// 2.9999999999999996 in binary floating point, which would paint the edge in the wrong colour.
#[inline]
pub fn section_at(z: f64) -> u8 {
    1 + SECTION_EDGES.iter().filter(|&&edge| z >= edge).count() as u8
}

/// Why the inputs of a simulation are not valid.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneError {
    /// A number is NaN or infinite.
    NotFinite {
        /// Which input.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The water height is outside `[0, Hv]`.
    WaterHeight(f64),
    /// The straw does not fit in the glass.
    StrawOutsideGlass {
        /// Axis `x`.
        xp: f64,
        /// Axis `y`.
        yp: f64,
    },
    /// The observer is inside or on the glass.
    ObserverInGlass(Vec3),
    /// The observer is inside the part of the straw above the glass.
    ObserverInStraw(Vec3),
    /// One of the observer's coordinates is larger than [`MAX_LENGTH`] in size.
    ObserverTooFar {
        /// Which coordinate.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The refractive index of water is below 1.
    WaterIndex(f64),
    /// The event limit is 0 or larger than [`MAX_EVENTS_LIMIT`].
    MaxEvents(u32),
    /// The wavelength asked is not visible light (nm).
    Wavelength(f64),
}

impl SceneError {
    /// The rule broken and its parameters (a page says it in its own language from them).
    pub fn rule(&self) -> (Rule, Params) {
        let n = rule::number;
        let bound = |x: f64| Param::Number(x.to_string());
        let at = |o: &Vec3, height: bool| {
            let mut p = rule::point(*o);
            if height {
                p.extend([
                    ("height", bound(GLASS_HEIGHT)),
                    ("radius", bound(GLASS_RADIUS)),
                ]);
            }
            p
        };
        match self {
            SceneError::NotFinite { name, value } => (
                Rule::GlassNotFinite,
                vec![
                    ("name", Param::Text(name.to_string())),
                    ("value", n(*value)),
                ],
            ),
            SceneError::WaterHeight(h) => (
                Rule::GlassWaterHeight,
                vec![("value", n(*h)), ("max", bound(GLASS_HEIGHT))],
            ),
            SceneError::StrawOutsideGlass { xp, yp } => (
                Rule::GlassStrawOutside,
                vec![
                    ("x", n(*xp)),
                    ("y", n(*yp)),
                    ("radius", bound(STRAW_RADIUS)),
                    ("glass", bound(GLASS_RADIUS)),
                    ("reach", n((xp * xp + yp * yp).sqrt() + STRAW_RADIUS)),
                ],
            ),
            SceneError::ObserverInGlass(o) => (Rule::GlassEyeInside, at(o, true)),
            SceneError::ObserverInStraw(o) => (Rule::GlassEyeInStraw, at(o, false)),
            SceneError::ObserverTooFar { name, value } => (
                Rule::GlassEyeFar,
                vec![
                    ("name", Param::Text(name.to_string())),
                    ("value", n(*value)),
                    ("max", bound(MAX_LENGTH)),
                ],
            ),
            SceneError::WaterIndex(v) => (Rule::GlassWaterIndex, vec![("value", n(*v))]),
            SceneError::MaxEvents(m) => (
                Rule::MaxEvents,
                vec![
                    ("value", Param::Number(m.to_string())),
                    ("max", Param::Number(MAX_EVENTS_LIMIT.to_string())),
                ],
            ),
            SceneError::Wavelength(nm) => (
                Rule::Wavelength,
                vec![
                    ("value", n(*nm)),
                    ("min", bound(crate::dispersion::VISIBLE_MIN_NM)),
                    ("max", bound(crate::dispersion::VISIBLE_MAX_NM)),
                ],
            ),
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (rule, params) = self.rule();
        f.write_str(&rule.text(&params))
    }
}

impl std::error::Error for SceneError {}

/// Checks that `value` is finite.
pub fn require_finite(name: &'static str, value: f64) -> Result<f64, SceneError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(SceneError::NotFinite { name, value })
    }
}

/// The glass of water with the straw in it: everything a ray can meet. Made only by
/// [`Scene::new`], so every scene obeys the rules of valid inputs (its numbers are read, not set).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scene {
    straw_x: f64,
    straw_y: f64,
    water_height: f64,
    n_water: f64,
    max_events: u32,
}

impl Scene {
    /// Axis of the straw, `x` (m).
    pub fn straw_x(&self) -> f64 {
        self.straw_x
    }

    /// Axis of the straw, `y` (m).
    pub fn straw_y(&self) -> f64 {
        self.straw_y
    }

    /// Height of the water surface `he` (m).
    pub fn water_height(&self) -> f64 {
        self.water_height
    }

    /// Refractive index of the water.
    pub fn n_water(&self) -> f64 {
        self.n_water
    }

    /// Most events (refractions and total reflections) a ray may undergo.
    pub fn max_events(&self) -> u32 {
        self.max_events
    }

    /// A validated scene: straw axis `(xp, yp)`, water height `he`, index `n_water`,
    /// event limit `max_events`.
    pub fn new(
        xp: f64,
        yp: f64,
        he: f64,
        n_water: f64,
        max_events: u32,
    ) -> Result<Self, SceneError> {
        require_finite("straw x", xp)?;
        require_finite("straw y", yp)?;
        require_finite("water height", he)?;
        if !is_physical_index(n_water) {
            return Err(SceneError::WaterIndex(n_water));
        }
        if !(0.0..=GLASS_HEIGHT).contains(&he) {
            return Err(SceneError::WaterHeight(he));
        }
        if (xp * xp + yp * yp).sqrt() + STRAW_RADIUS > GLASS_RADIUS {
            return Err(SceneError::StrawOutsideGlass { xp, yp });
        }
        if max_events == 0 || max_events > MAX_EVENTS_LIMIT {
            return Err(SceneError::MaxEvents(max_events));
        }
        Ok(Scene {
            straw_x: xp,
            straw_y: yp,
            water_height: he,
            n_water,
            max_events,
        })
    }

    /// A scene with the default index (1.333) and event limit (10).
    pub fn with_defaults(xp: f64, yp: f64, he: f64) -> Result<Self, SceneError> {
        Scene::new(xp, yp, he, WATER_INDEX, DEFAULT_MAX_EVENTS)
    }

    /// The same scene with another water index (validated).
    pub fn with_n_water(&self, n_water: f64) -> Result<Self, SceneError> {
        Scene::new(
            self.straw_x,
            self.straw_y,
            self.water_height,
            n_water,
            self.max_events,
        )
    }

    /// Checks that `observer` is a place an observer may stand: finite, not inside or on the
    /// glass, not inside the part of the straw above the glass.
    pub fn validate_observer(&self, observer: Vec3) -> Result<(), SceneError> {
        require_finite("observer x", observer.x)?;
        require_finite("observer y", observer.y)?;
        require_finite("observer z", observer.z)?;
        // The scene files' rule: positions within a thousand kilometres.
        for (name, value) in [
            ("observer x", observer.x),
            ("observer y", observer.y),
            ("observer z", observer.z),
        ] {
            if value.abs() > MAX_LENGTH {
                return Err(SceneError::ObserverTooFar { name, value });
            }
        }
        let r2 = observer.x * observer.x + observer.y * observer.y;
        if (0.0..=GLASS_HEIGHT).contains(&observer.z) && r2 <= GLASS_RADIUS * GLASS_RADIUS {
            return Err(SceneError::ObserverInGlass(observer));
        }
        let (sx, sy) = (observer.x - self.straw_x, observer.y - self.straw_y);
        if observer.z > GLASS_HEIGHT
            && observer.z <= STRAW_HEIGHT
            && sx * sx + sy * sy <= STRAW_RADIUS * STRAW_RADIUS
        {
            return Err(SceneError::ObserverInStraw(observer));
        }
        Ok(())
    }

    /// Whether there is any water (a zero height leaves none).
    #[inline]
    pub fn has_water(&self) -> bool {
        self.water_height > 0.0
    }
}

/// Largest length or coordinate (m) in a scene, the observer's included, a thousand kilometres:
/// beyond it, squared distances lose the precision of the sizes beside them.
pub const MAX_LENGTH: f64 = 1e6;

/// Largest refractive index a scene may give: vacuum is 1, and the most refractive materials
/// known (germanium in the infrared, some semiconductors) are about 4; beyond 5 a number is a
/// typing error, not a material.
pub const MAX_INDEX: f64 = 5.0;

/// Whether `n` is a refractive index a scene may give: a number from 1 to [`MAX_INDEX`].
pub fn is_physical_index(n: f64) -> bool {
    (1.0..=MAX_INDEX).contains(&n)
}

/// The centre of the box enclosing the glass and the straw, `(0, 0, 0.125)`: the default target.
pub const SCENE_CENTRE: Vec3 = Vec3::new(0.0, 0.0, STRAW_HEIGHT / 2.0);

/// One of the four reference simulations: an observer, a straw position and a water height.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reference {
    /// Number, 1..=4.
    pub number: u32,
    /// Observer position.
    pub observer: Vec3,
    /// Straw axis `(xp, yp)`.
    pub straw: (f64, f64),
    /// Water height.
    pub water_height: f64,
}

/// The four reference simulations (see the table of them in docs/usage.md).
pub const REFERENCES: [Reference; 4] = [
    Reference {
        number: 1,
        observer: Vec3::new(0.0, 0.1, 0.1),
        straw: (0.02, 0.01),
        water_height: 0.15,
    },
    Reference {
        number: 2,
        observer: Vec3::new(0.1, 0.0, 0.1),
        straw: (0.02, 0.01),
        water_height: 0.15,
    },
    Reference {
        number: 3,
        observer: Vec3::new(0.1, 0.0, 0.3),
        straw: (0.02, 0.01),
        water_height: 0.20,
    },
    Reference {
        number: 4,
        observer: Vec3::new(0.1, 0.0, -0.1),
        straw: (0.0, 0.0),
        water_height: 0.20,
    },
];

impl Reference {
    /// The scene of this reference with index `n_water` and the default event limit.
    pub fn scene(&self, n_water: f64) -> Scene {
        Scene::new(
            self.straw.0,
            self.straw.1,
            self.water_height,
            n_water,
            DEFAULT_MAX_EVENTS,
        )
        .expect("reference scenes are valid")
    }

    /// Where the benchmark's zoomed view of this reference looks: where the straw enters the
    /// water, or, for the observer below the glass, the straw's bottom.
    pub fn zoom_target(&self) -> Vec3 {
        if self.observer.z < 0.0 {
            Vec3::new(0.0, 0.0, 0.05)
        } else {
            Vec3::new(self.straw.0, self.straw.1, self.water_height)
        }
    }
}
