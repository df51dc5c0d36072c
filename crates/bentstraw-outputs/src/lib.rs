//! `bentstraw-outputs`: everything bentstraw writes or reads besides arguments: scene files read
//! and checked, image points written (CSV, JSON, PLY), figures (PNG, SVG, PDF), pictures, ray
//! diagrams, the rotatable HTML view and the report. No argument parsing: the command line and the
//! explorer give plain values.

#![warn(missing_docs)]

pub mod camera;
pub mod check_plot;
pub mod error;
pub mod files;
pub mod gallery;
pub mod html;
pub mod model_plots;
pub mod parse;
pub mod pictures;
pub mod plot;
pub mod ray_diagram;
pub mod report;
pub mod scene_input;
pub mod sketch;
#[cfg(test)]
mod test_support;
pub mod validation;
pub mod writers;

pub use error::{Error, Result};
