//! The view asked for beside the scene, its defaults named once: how many image points, how the
//! picture is drawn (its size, mode, backdrop and samples) and where the first view looks from.
//! The command line's flags, the explorer's queries, the page and the Python keywords take their
//! defaults from here.

use crate::shading::{Backdrop, ShadingMode, ShadingOptions};

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
pub const CLASSIC_OBSERVER: [f64; 3] = [0.3, 0.0, 0.22];

/// The straw's axis `(xp, yp)` in the classic view: behind the glass's axis and to one side, so
/// that the water's surface visibly breaks it (below, the glass's curve shifts it sideways and
/// doubles its width).
pub const CLASSIC_STRAW: [f64; 2] = [-0.02, 0.02];

/// The water's height in the classic view (m).
pub const CLASSIC_WATER_HEIGHT: f64 = 0.15;

/// The picture's modes by name: the course's one ray per sample, or Fresnel's weighted branches.
pub const MODES: [&str; 2] = ["course", "fresnel"];

/// The backdrops by name: none (a plain background) or a checkerboard wall and floor.
pub const BACKDROPS: [&str; 2] = ["none", "checker"];

/// The picture's light by name: one wavelength (the scene's, `--wavelength`), or white light.
pub const LIGHTS: [&str; 2] = ["mono", "white"];

/// The picture's sampling by name: every pixel's centre, then the samples only where pixels
/// differ (adaptive), or the samples at every pixel (full).
pub const SAMPLINGS: [&str; 2] = ["adaptive", "full"];

/// How the observer's picture is drawn, as asked for: its mode, backdrop, pruning weight and
/// samples (the command line's `--mode`, `--backdrop`, `--prune`, `--samples`, the page's query
/// and Python's keywords of the same names). Checked where it is turned into shading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PictureSpec {
    /// Fresnel's weighted branches (true) or the course's one ray per sample.
    pub fresnel: bool,
    /// A checkerboard backdrop (true) or a plain one.
    pub checker: bool,
    /// Fresnel branches lighter than this are abandoned.
    pub prune: f64,
    /// Samples per pixel side at edges.
    pub samples: u32,
    /// Samples only at edges (true), or at every pixel.
    pub adaptive: bool,
    /// White light (true), or light of the scene's one wavelength: the picture's, and the image
    /// points' beside it.
    pub white: bool,
}

impl Default for PictureSpec {
    fn default() -> Self {
        PictureSpec {
            fresnel: true,
            checker: true,
            prune: DEFAULT_PRUNE,
            samples: DEFAULT_SAMPLES,
            adaptive: true,
            white: false,
        }
    }
}

impl PictureSpec {
    /// This spec in the mode named `name` (one of [`MODES`]), or the refusal naming the option
    /// as `option` (`--mode` on the command line and in the page, `mode` in Python).
    pub fn with_mode(self, option: &str, name: &str) -> Result<PictureSpec, String> {
        match name {
            "course" => Ok(PictureSpec {
                fresnel: false,
                ..self
            }),
            "fresnel" => Ok(PictureSpec {
                fresnel: true,
                ..self
            }),
            other => Err(crate::text::refuse_choice(option, other, &MODES)),
        }
    }

    /// This spec with the backdrop named `name` (one of [`BACKDROPS`]), or the refusal naming
    /// the option as `option`.
    pub fn with_backdrop(self, option: &str, name: &str) -> Result<PictureSpec, String> {
        match name {
            "none" => Ok(PictureSpec {
                checker: false,
                ..self
            }),
            "checker" => Ok(PictureSpec {
                checker: true,
                ..self
            }),
            other => Err(crate::text::refuse_choice(option, other, &BACKDROPS)),
        }
    }

    /// This spec with the light named `name` (one of [`LIGHTS`]), or the refusal naming the
    /// option as `option`.
    pub fn with_light(self, option: &str, name: &str) -> Result<PictureSpec, String> {
        match LIGHTS.iter().position(|l| *l == name) {
            Some(k) => Ok(PictureSpec {
                white: k == 1,
                ..self
            }),
            None => Err(crate::text::refuse_choice(option, name, &LIGHTS)),
        }
    }

    /// This spec with the sampling named `name` (one of [`SAMPLINGS`]), or the refusal naming
    /// the option as `option`.
    pub fn with_sampling(self, option: &str, name: &str) -> Result<PictureSpec, String> {
        match SAMPLINGS.iter().position(|s| *s == name) {
            Some(k) => Ok(PictureSpec {
                adaptive: k == 0,
                ..self
            }),
            None => Err(crate::text::refuse_choice(option, name, &SAMPLINGS)),
        }
    }

    /// The sampling's name.
    pub fn sampling(&self) -> &'static str {
        SAMPLINGS[!self.adaptive as usize]
    }

    /// The light's name.
    pub fn light(&self) -> &'static str {
        LIGHTS[self.white as usize]
    }

    /// The mode's name.
    pub fn mode(&self) -> &'static str {
        MODES[self.fresnel as usize]
    }

    /// The backdrop's name.
    pub fn backdrop(&self) -> &'static str {
        BACKDROPS[self.checker as usize]
    }

    /// The shading that draws this picture (its values as given: `checked_shading` in the I/O
    /// library checks them first).
    pub fn shading(&self) -> ShadingOptions {
        ShadingOptions {
            mode: if self.fresnel {
                ShadingMode::Fresnel {
                    prune_below: self.prune,
                }
            } else {
                ShadingMode::Course
            },
            backdrop: if self.checker {
                Backdrop::Checker
            } else {
                Backdrop::Plain
            },
            samples: self.samples,
            adaptive: self.adaptive,
            outline: true,
            white: self.white,
        }
    }

    /// The command line's arguments that draw this picture: the mode and the backdrop always,
    /// the samples, the sampling, the pruning weight and the light when they are not the
    /// defaults.
    pub fn args(&self) -> Vec<String> {
        let mut args = vec![
            "--mode".to_string(),
            self.mode().to_string(),
            "--backdrop".to_string(),
            self.backdrop().to_string(),
        ];
        if self.samples != DEFAULT_SAMPLES {
            args.extend(["--samples".to_string(), self.samples.to_string()]);
        }
        if !self.adaptive {
            args.extend(["--sampling".to_string(), self.sampling().to_string()]);
        }
        if self.prune != DEFAULT_PRUNE {
            args.extend(["--prune".to_string(), self.prune.to_string()]);
        }
        if self.white {
            args.extend(["--light".to_string(), self.light().to_string()]);
        }
        args
    }
}
