//! The observer's picture, one ray per pixel centre (SPEC §6): colour codes (course mode) or
//! weights per section (fresnel mode), row-major.

use rayon::prelude::*;

use crate::camera::Camera;
use crate::packet::{FresnelWave, PacketTracer};
use crate::scene::{Scene, SECTION_COUNT};
use crate::tracer::Tracer;

/// Colour code (0 = no straw) of the ray through each pixel centre, row-major, by SPEC §3.
///
/// Traced in single precision, eight rays at a time ([`crate::packet`]): the same pixels as
/// [`course_picture_exact`] except, rarely, on a colour boundary.
pub fn course_picture(scene: &Scene, camera: &Camera) -> Vec<u8> {
    let w = camera.width as usize;
    let tracer = PacketTracer::new(scene);
    let mut codes = vec![0u8; w * camera.height as usize];
    codes.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        tracer.course_row(camera, i as u32, row);
    });
    codes
}

/// Colour code (0 = no straw) of the ray through each pixel centre, row-major, by SPEC §3, traced in
/// double precision: exactly [`Scene::trace`]'s colours.
pub fn course_picture_exact(scene: &Scene, camera: &Camera) -> Vec<u8> {
    let w = camera.width as usize;
    let tracer = Tracer::new(scene);
    let mut codes = vec![0u8; w * camera.height as usize];
    codes.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        for (j, code) in row.iter_mut().enumerate() {
            *code = tracer.color(camera.pixel_ray(i as u32, j as u32));
        }
    });
    codes
}

/// Weights per section (SPEC §6, fresnel mode) of the ray through each pixel centre, row-major.
///
/// Traced in single precision, breadth first, eight branches at a time ([`crate::packet`]): the
/// weights of [`fresnel_picture_exact`] to about 1e-4, except, rarely, on a boundary.
pub fn fresnel_picture(
    scene: &Scene,
    camera: &Camera,
    prune_below: f64,
) -> Vec<[f64; SECTION_COUNT]> {
    let w = camera.width as usize;
    let tracer = PacketTracer::new(scene);
    let mut weights = vec![[0.0; SECTION_COUNT]; w * camera.height as usize];
    weights
        .par_chunks_mut(w)
        .enumerate()
        .for_each_init(FresnelWave::default, |wave, (i, row)| {
            tracer.fresnel_row(camera, i as u32, prune_below, wave, row);
        });
    weights
}

/// Weights per section (SPEC §6, fresnel mode) of the ray through each pixel centre, row-major,
/// traced in double precision (branches that provably escape are not followed).
pub fn fresnel_picture_exact(
    scene: &Scene,
    camera: &Camera,
    prune_below: f64,
) -> Vec<[f64; SECTION_COUNT]> {
    let w = camera.width as usize;
    let tracer = Tracer::new(scene);
    let mut weights = vec![[0.0; SECTION_COUNT]; w * camera.height as usize];
    weights.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        for (j, px) in row.iter_mut().enumerate() {
            *px = tracer.trace_fresnel_escaping(camera.pixel_ray(i as u32, j as u32), prune_below);
        }
    });
    weights
}
