//! The image points as dots: squares sorted from far to near and clipped to the panel, those
//! that later dots hide left out, and the rest drawn as a few rectangles per colour.

use bentstraw_optics::image::ImagePoint;
use plotters::prelude::*;
use rayon::slice::ParallelSliceMut;

use super::colours::point_rgb8;
use super::figure::{AreaOn, DrawResultOn};
use super::panel::Panel;

/// Side of the square dot of one image point, in pixels.
pub(crate) const DOT: i32 = 3;

/// One image point's dot: its top-left pixel and colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Dot {
    /// Left column (px).
    pub x: i32,
    /// Top row (px).
    pub y: i32,
    /// Width and height (px): [`DOT`], less what is clipped off at the panel's edge.
    pub size: (i32, i32),
    /// Colour.
    pub rgb: [u8; 3],
}

/// The dots of a panel that the picture shows, in drawing order: first `ghost` (pale, in the
/// given order), then `points` in their colours from far to near, each a [`DOT`]-pixel square
/// clipped to the panel. A dot whose every pixel a later dot covers is left out: the picture is
/// the same, and an SVG of a million points stays a few megabytes.
pub(crate) fn visible_dots(
    panel: &Panel,
    ghost: &[(ImagePoint, [u8; 3])],
    points: &[ImagePoint],
) -> Vec<Dot> {
    let proj = &panel.proj;
    let mut order: Vec<(f64, usize)> = points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.position.is_finite())
        .map(|(i, p)| (proj.nearness(p.position), i))
        .collect();
    // Stable, so that equal depths keep the input order and the picture is reproducible.
    order.par_sort_by(|a, b| a.0.total_cmp(&b.0));
    let place = |p: &ImagePoint, rgb: [u8; 3]| {
        let (px, py) = proj.pixel(p.position);
        let half = DOT as f64 / 2.0;
        Dot {
            x: (px - half).round() as i32,
            y: (py - half).round() as i32,
            size: (DOT, DOT),
            rgb,
        }
    };
    let drawn: Vec<Dot> = ghost
        .iter()
        .filter(|(p, _)| p.position.is_finite())
        .map(|(p, c)| place(p, *c))
        .chain(
            order
                .iter()
                .map(|&(_, i)| place(&points[i], point_rgb8(&points[i]))),
        )
        .collect();
    // From the last drawn back: a dot shows if one of its pixels is not yet covered.
    let (w, h) = (panel.width.max(0) as usize, panel.height.max(0) as usize);
    let mut covered = vec![false; w * h];
    let mut kept: Vec<Dot> = Vec::new();
    for d in drawn.iter().rev() {
        let x0 = (d.x - panel.left).max(0);
        let y0 = (d.y - panel.top).max(0);
        let x1 = (d.x + DOT - panel.left).min(w as i32);
        let y1 = (d.y + DOT - panel.top).min(h as i32);
        let mut shows = false;
        for y in y0..y1 {
            for x in x0..x1 {
                let k = y as usize * w + x as usize;
                shows |= !covered[k];
                covered[k] = true;
            }
        }
        if shows && x1 > x0 && y1 > y0 {
            kept.push(Dot {
                x: x0 + panel.left,
                y: y0 + panel.top,
                size: (x1 - x0, y1 - y0),
                rgb: d.rgb,
            });
        }
    }
    kept.reverse();
    kept
}

/// The pixels `dots` cover, each in the colour of the last dot over it, as rectangles that do
/// not overlap, one colour after the other: pixel rows of one colour, rows of the same extent one
/// under the other joined. Drawn in any order they make the picture the dots make in theirs, and
/// an SVG writes each colour as one path.
pub(crate) fn covered_pixels(dots: &[Dot]) -> Vec<Dot> {
    let (Some(x0), Some(y0)) = (
        dots.iter().map(|d| d.x).min(),
        dots.iter().map(|d| d.y).min(),
    ) else {
        return Vec::new();
    };
    let x1 = dots.iter().map(|d| d.x + d.size.0).max().unwrap_or(x0);
    let y1 = dots.iter().map(|d| d.y + d.size.1).max().unwrap_or(y0);
    let (w, h) = ((x1 - x0) as usize, (y1 - y0) as usize);
    let mut colours: Vec<[u8; 3]> = dots.iter().map(|d| d.rgb).collect();
    colours.sort_unstable();
    colours.dedup();
    // Each pixel's colour (its index in `colours`, plus one; 0: uncovered).
    let mut grid = vec![0u16; w * h];
    for d in dots {
        let c = colours.binary_search(&d.rgb).expect("listed") as u16 + 1;
        for y in d.y..d.y + d.size.1 {
            let row = (y - y0) as usize * w;
            for x in d.x..d.x + d.size.0 {
                grid[row + (x - x0) as usize] = c;
            }
        }
    }
    let mut out = Vec::new();
    for (k, rgb) in colours.iter().enumerate() {
        let c = k as u16 + 1;
        // Rectangles still growing downwards, by their left column and width.
        let mut open: Vec<Dot> = Vec::new();
        for y in 0..=h {
            let mut runs: Vec<(i32, i32)> = Vec::new();
            if y < h {
                let row = &grid[y * w..(y + 1) * w];
                let mut x = 0;
                while x < w {
                    if row[x] == c {
                        let start = x;
                        while x < w && row[x] == c {
                            x += 1;
                        }
                        runs.push((x0 + start as i32, (x - start) as i32));
                    } else {
                        x += 1;
                    }
                }
            }
            let mut next = Vec::with_capacity(runs.len());
            for (x, len) in runs {
                match open.iter().position(|d| d.x == x && d.size.0 == len) {
                    Some(i) => {
                        let mut d = open.swap_remove(i);
                        d.size.1 += 1;
                        next.push(d);
                    }
                    None => next.push(Dot {
                        x,
                        y: y0 + y as i32,
                        size: (len, 1),
                        rgb: *rgb,
                    }),
                }
            }
            out.append(&mut open);
            open = next;
        }
    }
    out
}

/// Draws the pixels dots cover (see [`covered_pixels`]) as filled rectangles.
pub(crate) fn draw_dots<DB: DrawingBackend>(root: &AreaOn<DB>, dots: &[Dot]) -> DrawResultOn<DB> {
    for d in &covered_pixels(dots) {
        root.draw(&Rectangle::new(
            [(d.x, d.y), (d.x + d.size.0, d.y + d.size.1)],
            RGBColor(d.rgb[0], d.rgb[1], d.rgb[2]).filled(),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::figure::FIGURE_WIDTH;
    use crate::plot::section_rgb8;
    use crate::plot::tests::{panels_of, point};
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::REFERENCES;
    use bentstraw_optics::setup::Setup;
    use bentstraw_optics::Vec3;

    /// Leaving out the dots that later dots cover changes no pixel, and leaves out most of a
    /// dense cloud's dots.
    #[test]
    fn hidden_dots_left_out_change_no_pixel() {
        let r = REFERENCES[2];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 20_000, &|_| {});
        let panels = panels_of(&scene, r.observer, &cloud.points);
        let size = (FIGURE_WIDTH, 1400);
        for p in &panels {
            let ghost: Vec<(ImagePoint, [u8; 3])> = cloud.points[..500]
                .iter()
                .map(|q| (point(q.position + Vec3::new(0.003, 0.0, 0.0), 1), [9, 9, 9]))
                .collect();
            let kept = visible_dots(p, &ghost, &cloud.points);
            // Every dot drawn, far to near, straight into pixels, clipped to the panel.
            let mut all = vec![255u8; (size.0 * size.1 * 3) as usize];
            let mut order: Vec<(f64, usize)> = cloud
                .points
                .iter()
                .enumerate()
                .map(|(i, q)| (p.proj.nearness(q.position), i))
                .collect();
            order.sort_by(|a, b| a.0.total_cmp(&b.0));
            let squares = ghost
                .iter()
                .map(|(q, c)| (q.position, *c))
                .chain(order.iter().map(|&(_, i)| {
                    (
                        cloud.points[i].position,
                        section_rgb8(cloud.points[i].color),
                    )
                }));
            for (q, c) in squares {
                let (x, y) = p.proj.pixel(q);
                let (x, y) = ((x - 1.5).round() as i32, (y - 1.5).round() as i32);
                for yy in y.max(p.top)..(y + DOT).min(p.top + p.height) {
                    for xx in x.max(p.left)..(x + DOT).min(p.left + p.width) {
                        let k = ((yy as u32 * size.0 + xx as u32) * 3) as usize;
                        all[k..k + 3].copy_from_slice(&c);
                    }
                }
            }
            let mut some = vec![255u8; all.len()];
            for d in &kept {
                for yy in d.y..d.y + d.size.1 {
                    for xx in d.x..d.x + d.size.0 {
                        let k = ((yy as u32 * size.0 + xx as u32) * 3) as usize;
                        some[k..k + 3].copy_from_slice(&d.rgb);
                    }
                }
            }
            assert!(all == some, "the kept dots draw a different picture");
            assert!(
                kept.len() < (cloud.points.len() + ghost.len()) / 2,
                "{} of {} dots kept",
                kept.len(),
                cloud.points.len()
            );
        }
    }
}
