//! The virtual image of the straw in the course's convention: a ray that reaches the straw gives
//! the image point `P = O + L·u0` (eye, first direction, length of the whole broken path).

use crate::Vec3;

/// A point of the straw's virtual image: where the observer believes a straw point is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImagePoint {
    /// The image point `P = O + L·u0` (m).
    pub position: Vec3,
    /// Colour code of the straw section the light came from, 1..=5.
    pub color: u8,
    /// Unit initial direction `u0` of the ray from the observer.
    pub direction: Vec3,
    /// Length `L` of the broken path from the observer to the straw (m).
    pub path_length: f64,
    /// The straw point the ray really reached.
    pub straw_point: Vec3,
    /// Events (refractions and total reflections) on the way.
    pub events: u32,
    /// The band of white light the ray carried (an index into
    /// [`crate::spectrum::white_bands`], violet first), or `None` for light of the scene's one
    /// wavelength.
    pub band: Option<u8>,
}

impl ImagePoint {
    /// The image point `P = O + L·u0` of the ray from `observer` along unit `u0` that reached
    /// `point`, of colour code `color`, after a broken path of length `path_length` and `events`
    /// events.
    #[inline]
    pub fn reached(
        observer: Vec3,
        u0: Vec3,
        color: u8,
        point: Vec3,
        path_length: f64,
        events: u32,
    ) -> ImagePoint {
        ImagePoint {
            position: observer + path_length * u0,
            color,
            direction: u0,
            path_length,
            straw_point: point,
            events,
            band: None,
        }
    }
}
