//! The observer's picture of a scene file's world: one ray per pixel centre (course) or the
//! Fresnel split at every interface, the surroundings behind, and `samples × samples` rays in the
//! pixels where the centres of neighbours disagree (the edges).

use rayon::prelude::*;

use crate::camera::Camera;
use crate::geometry::Ray;
use crate::shading::{
    linear_to_srgb, srgb_to_linear, RgbPicture, ShadingMode, ShadingOptions, Surroundings,
};
use crate::Vec3;

use super::{World, WorldOutcome, COLOR_COUNT, COLOR_RGB};

/// What one ray from the eye shows: linear RGB, and a code telling edges apart (what it ended
/// on: a colour code, or 0 for the surroundings).
#[inline]
fn ray_colour(
    world: &World,
    around: &Surroundings,
    light: Vec3,
    mode: ShadingMode,
    ray: Ray,
) -> ([f64; 3], u8) {
    let object = |code: u8| COLOR_RGB[code as usize - 1].map(srgb_to_linear);
    match mode {
        ShadingMode::Course => match world.trace(ray) {
            WorldOutcome::Object { color, normal, .. } => {
                // Light from the observer's side and above, so the objects keep their relief.
                let shade = 0.62 + 0.38 * normal.dot(light).max(0.0);
                (object(color).map(|c| c * shade), color)
            }
            WorldOutcome::Escaped { ray, .. } => (around.radiance(&ray), 0),
            WorldOutcome::Dropped => ([0.0; 3], 0),
        },
        ShadingMode::Fresnel { prune_below } => {
            let mut rgb = [0.0; 3];
            let weights = world.trace_fresnel(ray, prune_below, |leaving, w| {
                if let Some(r) = leaving {
                    let c = around.radiance(&r);
                    for k in 0..3 {
                        rgb[k] += w * c[k];
                    }
                }
            });
            let mut strongest = (0.0, 0u8);
            for (k, &w) in weights.iter().enumerate() {
                if w > 0.0 {
                    let c = object(k as u8 + 1);
                    for i in 0..3 {
                        rgb[i] += 0.8 * w * c[i];
                    }
                    if w > strongest.0 {
                        strongest = (w, k as u8 + 1);
                    }
                }
            }
            // Half the light or more from one colour marks the pixel as showing it.
            let code = if strongest.0 >= 0.5 { strongest.1 } else { 0 };
            (rgb, code)
        }
    }
}

/// The picture of `world` through `camera`, shaded as `options` says (its outline flag is not
/// used: the faces show by what they refract and reflect).
pub fn world_picture(world: &World, camera: &Camera, options: &ShadingOptions) -> RgbPicture {
    let (w, h) = (camera.width as usize, camera.height as usize);
    let around = Surroundings::new(options.backdrop, camera.eye);
    let light = (-camera.forward + 0.8 * Vec3::Z + 0.5 * camera.right).normalize();
    let shade = |row: f64, col: f64| {
        let ray = Ray::new(camera.eye, camera.direction_at(row, col));
        ray_colour(world, &around, light, options.mode, ray)
    };
    // Pass 1: the pixel centres.
    let centres: Vec<([f64; 3], u8)> = (0..w * h)
        .into_par_iter()
        .with_min_len(256)
        .map(|k| shade((k / w) as f64 + 0.5, (k % w) as f64 + 0.5))
        .collect();
    // Pass 2: pixels whose centre ends elsewhere than a neighbour's get n × n rays.
    let n = options.samples.max(1) as usize;
    let pixels: Vec<u8> = (0..w * h)
        .into_par_iter()
        .with_min_len(256)
        .flat_map_iter(|k| {
            let (i, j) = (k / w, k % w);
            let code = centres[k].1;
            let edge = n > 1
                && [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)]
                    .iter()
                    .any(|(di, dj)| {
                        let (ii, jj) = (i as i64 + di, j as i64 + dj);
                        (0..h as i64).contains(&ii)
                            && (0..w as i64).contains(&jj)
                            && centres[ii as usize * w + jj as usize].1 != code
                    });
            let rgb = if edge {
                let mut sum = [0.0; 3];
                for a in 0..n {
                    for b in 0..n {
                        let row = i as f64 + (a as f64 + 0.5) / n as f64;
                        let col = j as f64 + (b as f64 + 0.5) / n as f64;
                        let (c, _) = shade(row, col);
                        for q in 0..3 {
                            sum[q] += c[q];
                        }
                    }
                }
                sum.map(|s| s / (n * n) as f64)
            } else {
                centres[k].0
            };
            rgb.map(|c| (linear_to_srgb(c) * 255.0).round() as u8)
        })
        .collect();
    RgbPicture {
        width: camera.width,
        height: camera.height,
        pixels,
    }
}

/// One course ray per pixel centre: the colour code it ends on (0 for none), row-major.
pub fn world_codes(world: &World, camera: &Camera) -> Vec<u8> {
    let mut codes = vec![0; camera.width as usize * camera.height as usize];
    world_codes_into(world, camera, &mut codes);
    codes
}

/// [`world_codes`] into a buffer of `width × height` codes (reused from picture to picture).
pub fn world_codes_into(world: &World, camera: &Camera, codes: &mut [u8]) {
    let w = camera.width as usize;
    codes
        .par_iter_mut()
        .with_min_len(256)
        .enumerate()
        .for_each(|(k, code)| {
            let (i, j) = ((k / w) as u32, (k % w) as u32);
            *code = world.trace(camera.pixel_ray(i, j)).color();
        });
}

/// One Fresnel ray per pixel centre: the weight reaching each colour code, row-major.
pub fn world_weights(world: &World, camera: &Camera, prune_below: f64) -> Vec<[f64; COLOR_COUNT]> {
    let mut weights = vec![[0.0; COLOR_COUNT]; camera.width as usize * camera.height as usize];
    world_weights_into(world, camera, prune_below, &mut weights);
    weights
}

/// [`world_weights`] into a buffer of `width × height` pixels (reused from picture to picture).
pub fn world_weights_into(
    world: &World,
    camera: &Camera,
    prune_below: f64,
    weights: &mut [[f64; COLOR_COUNT]],
) {
    let w = camera.width as usize;
    weights
        .par_iter_mut()
        .with_min_len(256)
        .enumerate()
        .for_each(|(k, px)| {
            let (i, j) = ((k / w) as u32, (k % w) as u32);
            *px = world.trace_fresnel(camera.pixel_ray(i, j), prune_below, |_, _| {});
        });
}
