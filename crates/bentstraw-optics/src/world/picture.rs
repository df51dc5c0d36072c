//! The observer's picture of a scene file's world: the same picture as the assignment's glass
//! gets, through the same packet tracer and shading ([`crate::shading`]); and the raw data of
//! one double-precision ray per pixel centre.

use crate::camera::Camera;
use crate::picture::{world_course_picture_exact, world_fresnel_picture_exact};
use crate::shading::{shaded_world_picture_into, RgbPicture, ShadingBuffers, ShadingOptions};

use super::{World, COLOR_COUNT};

/// The picture of `world` through `camera`, shaded as `options` says (the glass's outline is the
/// assignment's glass's only: the faces of other scenes show by what they refract and reflect).
pub fn world_picture(world: &World, camera: &Camera, options: &ShadingOptions) -> RgbPicture {
    let mut picture = RgbPicture::default();
    shaded_world_picture_into(
        world,
        camera,
        options,
        &mut ShadingBuffers::default(),
        &mut picture,
    );
    picture
}

/// One course ray per pixel centre, in double precision: the colour code it ends on (0 for none),
/// row-major.
pub fn world_codes(world: &World, camera: &Camera) -> Vec<u8> {
    world_course_picture_exact(world, camera)
}

/// One Fresnel ray per pixel centre, in double precision: the weight reaching each colour code,
/// row-major.
pub fn world_weights(world: &World, camera: &Camera, prune_below: f64) -> Vec<[f64; COLOR_COUNT]> {
    world_fresnel_picture_exact(world, camera, prune_below)
}
