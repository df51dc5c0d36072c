//! The classic figure: the image points in their section colours, the water as a
//! wireframe, the observer, equal axes, three views (front, side, from above) in a 2 × 2 grid with
//! the legend in the fourth cell; and what every figure shares: one pipeline writing PNG, SVG or
//! PDF by the file's extension (`figure_bytes`), text sizes legible at 8.5 cm, headings, legends.
//!
//! The views are orthographic projections computed here (not plotters' 3D charts), so that one metre
//! has the same length on screen along both axes of a panel, and so that the drawing order (back of
//! the glass, points from far to near, front of the glass) is under our control. Each view looks
//! along one axis of the scene, so that each panel has exactly one horizontal and one vertical
//! scale, each a coordinate of the scene.
//!
//! One concept a file: the axis box, the views and their projection, the panels and their
//! scales, the dots, the scene's lines, the observer, legends, text, headings, and the figure's
//! formats and encoders; the classic figure puts them together.

mod axis_box;
mod cloud;
mod colours;
mod dots;
mod encode;
mod figure;
mod heading;
mod legend;
mod numbers;
mod observer;
mod panel;
mod projection;
mod scales;
#[cfg(test)]
pub(crate) mod tests;
mod text;
mod views;
mod wireframe;

pub use cloud::write_cloud_figure;
pub use encode::PDF_WIDTH_CM;
pub use figure::{FigureFormat, FIGURE_EXTENSIONS, FIGURE_WIDTH};
pub use text::{CAPTION, TEXT, TITLE};

pub(crate) use axis_box::{axis_box, AxisBox};
pub(crate) use cloud::{layout, legend_cell, three_view_size};
pub(crate) use colours::{rgb, section_rgb8};
pub(crate) use dots::{draw_dots, visible_dots};
pub(crate) use encode::svg_options;
pub(crate) use figure::{figure_bytes, AreaOn, DrawResultOn};
pub(crate) use heading::Heading;
#[cfg(test)]
pub(crate) use legend::counts;
pub(crate) use legend::{
    common_legend, draw_legend_cell, legend_entries, legend_key, section_words, LegendEntry,
    LegendMark, LEGEND_LINE,
};
pub(crate) use numbers::{degrees, triple, whole};
pub(crate) use observer::draw_observer;
pub(crate) use panel::{grid, Panel, CAPTION_LINE};
pub(crate) use scales::{draw_axis_labels, draw_panes};
pub(crate) use text::{font, wrap, FONT};
pub(crate) use views::{figure_views, observer_direction, ViewDirection};
pub(crate) use wireframe::{dashed, draw_straw_outline, draw_water};

#[cfg(test)]
pub(crate) use cloud::CELL_HEIGHT;
