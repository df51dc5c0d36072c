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
    let mut codes = vec![0u8; camera.width as usize * camera.height as usize];
    course_picture_into(scene, camera, &mut codes);
    codes
}

/// [`course_picture`] into a caller's buffer of `width × height` codes (an interactive view keeps
/// one and redraws into it, with no allocation per picture).
pub fn course_picture_into(scene: &Scene, camera: &Camera, codes: &mut [u8]) {
    let w = camera.width as usize;
    assert_eq!(
        codes.len(),
        w * camera.height as usize,
        "one code per pixel"
    );
    let tracer = PacketTracer::new(scene);
    codes.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        tracer.course_row(camera, i as u32, row);
    });
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
    let w = camera.width as usize;
    assert_eq!(
        weights.len(),
        w * camera.height as usize,
        "one pixel per pixel"
    );
    let tracer = PacketTracer::new(scene);
    weights
        .par_chunks_mut(w)
        .enumerate()
        .for_each_init(FresnelWave::default, |wave, (i, row)| {
            tracer.fresnel_row(camera, i as u32, prune_below, wave, row);
        });
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
