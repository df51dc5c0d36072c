//! `bentstraw-io`: everything bentstraw reads or writes besides arguments: scene files and
//! solutions read and checked, image points written (CSV, JSON, PLY), figures (PNG, SVG, PDF),
//! pictures, ray diagrams, the rotatable HTML view and the report (figures, behind the default feature `figures`,
//! which needs a native target). No argument parsing: the command line and the
//! explorer give plain values.

#![warn(missing_docs)]

pub mod camera;
#[cfg(feature = "figures")]
pub mod check_plot;
#[cfg(feature = "grade")]
pub mod class;
pub mod error;
pub mod escape;
pub mod files;
pub mod gallery;
#[cfg(feature = "figures")]
pub mod gallery_report;
#[cfg(feature = "grade")]
pub mod grade;
#[cfg(feature = "figures")]
pub mod html;
#[cfg(feature = "figures")]
pub mod model_plots;
pub mod parse;
pub mod pictures;
#[cfg(feature = "figures")]
pub mod plot;
#[cfg(feature = "figures")]
pub mod rainbow_plot;
#[cfg(feature = "figures")]
pub mod ray_diagram;
#[cfg(feature = "figures")]
pub mod report;
#[cfg(feature = "figures")]
pub mod report_pdf;
#[cfg(feature = "figures")]
pub mod report_plan;
pub mod scene_input;
pub mod solution;
pub mod summary;
#[cfg(feature = "figures")]
mod svg_marks;
pub mod sweep;
#[cfg(test)]
mod test_support;
#[cfg(feature = "figures")]
pub mod validation;
pub mod view_spec;
pub mod words;
pub mod writers;

pub use error::{Error, Result};
pub use view_spec::ViewSpec;
