//! The observer's picture as data, one ray per pixel centre: colour codes (course mode)
//! or weights per colour (fresnel mode), row-major, for the assignment's scene or any world.
//!
//! Traced two ways: in single precision, eight rays at a time ([`crate::packet`], what pictures
//! use), and in double precision, one ray at a time (the `_exact` functions, what raw files hold
//! and the tests compare the packets with).

use rayon::prelude::*;

use crate::camera::Camera;
use crate::packet::{FresnelWave, PacketTracer};
use crate::scene::{Scene, SECTION_COUNT};
use crate::world::{World, COLOR_COUNT};

/// Colour code (0 = no straw) of the ray through each pixel centre, row-major, by the course's
/// law (refraction or total reflection at each water face).
///
/// Traced in single precision, eight rays at a time ([`crate::packet`]): the same pixels as
/// [`course_picture_exact`] except, rarely, on a colour boundary.
pub fn course_picture(scene: &Scene, camera: &Camera) -> Vec<u8> {
    let mut codes = vec![0u8; camera.width as usize * camera.height as usize];
    course_picture_into(scene, camera, &mut codes);
    codes
}

/// [`course_picture`] into a caller's buffer of `width × height` codes (an interactive view keeps
/// one and redraws into it, with no allocation per picture).
pub fn course_picture_into(scene: &Scene, camera: &Camera, codes: &mut [u8]) {
    course_codes_into(&PacketTracer::new(scene), camera, codes);
}

/// [`course_picture_into`] of any world (colour codes 1..=8).
pub fn world_course_picture_into(world: &World, camera: &Camera, codes: &mut [u8]) {
    course_codes_into(&PacketTracer::for_world(world), camera, codes);
}

/// The course codes of `tracer`'s world through `camera`, into `codes`.
fn course_codes_into(tracer: &PacketTracer, camera: &Camera, codes: &mut [u8]) {
    let w = camera.width as usize;
    assert_eq!(
        codes.len(),
        w * camera.height as usize,
        "one code per pixel"
    );
    codes.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        tracer.course_row(camera, i as u32, row);
    });
}

/// Colour code (0 = no straw) of the ray through each pixel centre, row-major, by the course's
/// law, traced in double precision: exactly [`Scene::trace`]'s colours.
pub fn course_picture_exact(scene: &Scene, camera: &Camera) -> Vec<u8> {
    world_course_picture_exact(&World::assignment(scene), camera)
}

/// [`course_picture_exact`] of any world: exactly [`World::trace`]'s colours.
pub fn world_course_picture_exact(world: &World, camera: &Camera) -> Vec<u8> {
    let w = camera.width as usize;
    let mut codes = vec![0u8; w * camera.height as usize];
    codes.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        for (j, code) in row.iter_mut().enumerate() {
            *code = world.trace(camera.pixel_ray(i as u32, j as u32)).color();
        }
    });
    codes
}

/// Weights per section (fresnel mode: each branch weighted by the Fresnel reflectance) of the ray
/// through each pixel centre, row-major.
///
/// Traced in single precision, breadth first, eight branches at a time ([`crate::packet`]): the
/// weights of [`fresnel_picture_exact`] to about 1e-4, except, rarely, on a boundary.
pub fn fresnel_picture(
    scene: &Scene,
    camera: &Camera,
    prune_below: f64,
) -> Vec<[f64; SECTION_COUNT]> {
    let mut weights = vec![[0.0; SECTION_COUNT]; camera.width as usize * camera.height as usize];
    fresnel_picture_into(scene, camera, prune_below, &mut weights);
    weights
}

/// [`fresnel_picture`] into a caller's buffer of `width × height` pixels (every pixel is written).
pub fn fresnel_picture_into(
    scene: &Scene,
    camera: &Camera,
    prune_below: f64,
    weights: &mut [[f64; SECTION_COUNT]],
) {
    fresnel_weights_into(&PacketTracer::new(scene), camera, prune_below, weights);
}

/// [`fresnel_picture_into`] of any world: the weight reaching each colour code 1..=8.
pub fn world_fresnel_picture_into(
    world: &World,
    camera: &Camera,
    prune_below: f64,
    weights: &mut [[f64; COLOR_COUNT]],
) {
    fresnel_weights_into(
        &PacketTracer::for_world(world),
        camera,
        prune_below,
        weights,
    );
}

/// The Fresnel weights of `tracer`'s world through `camera`, into `weights` (codes past `N` are
/// not kept).
fn fresnel_weights_into<const N: usize>(
    tracer: &PacketTracer,
    camera: &Camera,
    prune_below: f64,
    weights: &mut [[f64; N]],
) {
    let w = camera.width as usize;
    assert_eq!(
        weights.len(),
        w * camera.height as usize,
        "one pixel per pixel"
    );
    weights
        .par_chunks_mut(w)
        .enumerate()
        .for_each_init(FresnelWave::default, |wave, (i, row)| {
            tracer.fresnel_row(camera, i as u32, prune_below, wave, row);
        });
}

/// Weights per section (fresnel mode: each branch weighted by the Fresnel reflectance) of the ray
/// through each pixel centre, row-major,
/// traced in double precision (branches that provably escape are not followed).
pub fn fresnel_picture_exact(
    scene: &Scene,
    camera: &Camera,
    prune_below: f64,
) -> Vec<[f64; SECTION_COUNT]> {
    weights_exact(&World::assignment(scene), camera, prune_below)
}

/// [`fresnel_picture_exact`] of any world: the weight reaching each colour code 1..=8.
pub fn world_fresnel_picture_exact(
    world: &World,
    camera: &Camera,
    prune_below: f64,
) -> Vec<[f64; COLOR_COUNT]> {
    weights_exact(world, camera, prune_below)
}

/// The Fresnel weights of the first `N` colour codes, each pixel centre traced in double
/// precision.
fn weights_exact<const N: usize>(
    world: &World,
    camera: &Camera,
    prune_below: f64,
) -> Vec<[f64; N]> {
    let w = camera.width as usize;
    let mut weights = vec![[0.0; N]; w * camera.height as usize];
    weights.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        for (j, px) in row.iter_mut().enumerate() {
            let ray = camera.pixel_ray(i as u32, j as u32);
            let all = world.fresnel_steps::<true>(
                ray,
                prune_below,
                crate::trace::FRESNEL_SEGMENTS_PER_RAY,
                |_| {},
            );
            *px = std::array::from_fn(|k| all[k]);
        }
    });
    weights
}
