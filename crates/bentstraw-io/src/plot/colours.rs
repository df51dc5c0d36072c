//! The figures' colours: each colour code's, the water's wireframe and the straw's outline.

use bentstraw_optics::world::{COLOR_COUNT, COLOR_RGB};
use plotters::prelude::*;

/// Colour of the water's wireframe.
pub(crate) const WATER_RGB: (u8, u8, u8) = (40, 120, 200);
/// Colour of the straw's true outline.
pub(crate) const STRAW_OUTLINE_RGB: (u8, u8, u8) = (120, 120, 120);

/// A plotters colour from 8-bit RGB.
pub(crate) fn rgb(c: (u8, u8, u8)) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// The colour image point `p` is drawn in: its colour code's, or in white light its
/// wavelength's.
pub(crate) fn point_rgb8(p: &bentstraw_optics::image::ImagePoint) -> [u8; 3] {
    p.band.map_or(section_rgb8(p.color), |k| {
        bentstraw_optics::spectrum::wavelength_rgb8(
            bentstraw_optics::spectrum::white_bands()[k as usize].nm,
        )
    })
}

/// The display colour of colour code `code` (1..=5 a straw's sections, 6..=8 a coin, a card and
/// its picture), as 8-bit RGB.
pub(crate) fn section_rgb8(code: u8) -> [u8; 3] {
    let c = COLOR_RGB[(code.clamp(1, COLOR_COUNT as u8) - 1) as usize];
    [
        (c[0] * 255.0).round() as u8,
        (c[1] * 255.0).round() as u8,
        (c[2] * 255.0).round() as u8,
    ]
}
