//! The view asked for beside the scene, its defaults named once: how many image points, how the
//! picture is drawn (its size, mode, backdrop and samples) and where the first view looks from.
//! The command line's flags, the explorer's queries, the page and the Python keywords take their
//! defaults from here.

/// Image points asked for when no number is given: enough for a smooth 3D cloud (the course asks
/// for at least 1000).
pub const DEFAULT_POINTS: usize = 20_000;

/// Fresnel branches lighter than this are abandoned by default: a pixel loses at most a few such
/// weights (see `docs/physics.md`).
pub const DEFAULT_PRUNE: f64 = 1e-4;

/// Samples per pixel side at the edges of a picture by default (3×3 rays where a pixel straddles
/// an edge).
pub const DEFAULT_SAMPLES: u32 = 3;

/// Most samples per pixel side.
pub const MAX_SAMPLES: u32 = 16;

/// A picture's size in pixels by default.
pub const DEFAULT_SIZE: (u32, u32) = (800, 600);

/// The first view of the explorer and the page: the classic broken straw seen from 30 cm, the
/// eye a little above the water.
pub const CLASSIC_OBSERVER: [f64; 3] = [0.3, 0.0, 0.25];

/// The straw's axis `(xp, yp)` in the classic view.
pub const CLASSIC_STRAW: [f64; 2] = [0.0, 0.03];

/// The water's height in the classic view (m).
pub const CLASSIC_WATER_HEIGHT: f64 = 0.15;
