//! White light: the visible spectrum cut into bands, each traced at its middle wavelength and
//! seen in the colour the eye gives it. The eye's response is the CIE 1931 standard observer
//! (its colour-matching functions x̄, ȳ, z̄), here in the analytic form of Wyman, Sloan and Shirley
//! (Journal of Computer Graphics Techniques 2, 2013), within a few per cent of the tabulated
//! functions; a band's colour is its integral of them, turned into linear sRGB. The bands'
//! colours are scaled so that together they make white: light that every band sees alike (a
//! scene where nothing disperses) keeps exactly its colour, and only where the bands part does
//! colour appear.

use crate::dispersion::{VISIBLE_MAX_NM, VISIBLE_MIN_NM};

/// How many bands white light is cut into: 50 nm each from 380 to 780 nm.
pub const WHITE_BANDS: usize = 8;

/// One band of white light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Band {
    /// The wavelength it is traced at (nm): its middle.
    pub nm: f64,
    /// Its colour in linear sRGB: what it adds to a pixel for each unit of light of each channel
    /// the band's ray brings back. The bands' colours add up to `[1, 1, 1]`.
    pub rgb: [f64; 3],
}

/// One lobe of the fit: a Gaussian of different widths below and above its peak.
fn lobe(nm: f64, peak: f64, below: f64, above: f64) -> f64 {
    let t = (nm - peak) / if nm < peak { below } else { above };
    (-0.5 * t * t).exp()
}

/// The CIE 1931 2° colour-matching functions `[x̄, ȳ, z̄]` at `nm` (the multi-lobe fit).
pub fn cie_1931(nm: f64) -> [f64; 3] {
    let x = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7)
        - 0.065 * lobe(nm, 501.1, 20.4, 26.2);
    let y = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
    let z = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
    [x, y, z]
}

/// CIE XYZ to linear sRGB (IEC 61966-2-1, D65 white).
pub fn xyz_to_linear_srgb([x, y, z]: [f64; 3]) -> [f64; 3] {
    [
        3.2406 * x - 1.5372 * y - 0.4986 * z,
        -0.9689 * x + 1.8758 * y + 0.0415 * z,
        0.0557 * x - 0.2040 * y + 1.0570 * z,
    ]
}

/// The bands of white light, violet first: each band's colour the integral of the eye's
/// response over it (1 nm steps), in linear sRGB, scaled channel by channel so that the bands add
/// up to white.
pub fn white_bands() -> [Band; WHITE_BANDS] {
    let width = (VISIBLE_MAX_NM - VISIBLE_MIN_NM) / WHITE_BANDS as f64;
    let mut bands = [Band {
        nm: 0.0,
        rgb: [0.0; 3],
    }; WHITE_BANDS];
    for (k, band) in bands.iter_mut().enumerate() {
        let lo = VISIBLE_MIN_NM + k as f64 * width;
        let mut xyz = [0.0; 3];
        // The middle of each nanometre of the band.
        for step in 0..width as usize {
            let c = cie_1931(lo + step as f64 + 0.5);
            for i in 0..3 {
                xyz[i] += c[i];
            }
        }
        *band = Band {
            nm: lo + width / 2.0,
            rgb: xyz_to_linear_srgb(xyz),
        };
    }
    let total = bands.iter().fold([0.0; 3], |t, b| add3(t, b.rgb));
    for b in &mut bands {
        for (c, t) in b.rgb.iter_mut().zip(total) {
            *c /= t;
        }
    }
    bands
}

/// The colour a figure shows light of wavelength `nm` in, as sRGB display values (0..1): the
/// eye's response to it made as bright as a screen allows, each channel a screen cannot give
/// (pure spectral colours lie outside its gamut) left out. The hue of a spectral colour hardly
/// changes beyond 410 and 650 nm, where the fit of the eye's response is least faithful: there
/// the hue of those ends is shown.
pub fn wavelength_rgb(nm: f64) -> [f64; 3] {
    let rgb = xyz_to_linear_srgb(cie_1931(nm.clamp(HUE_MIN_NM, HUE_MAX_NM))).map(|c| c.max(0.0));
    let most = rgb.iter().copied().fold(0.0, f64::max);
    rgb.map(|c| crate::shading::linear_to_srgb(c / most))
}

/// Below this wavelength (nm) a figure shows light in the hue of this one.
const HUE_MIN_NM: f64 = 410.0;
/// Above this wavelength (nm) a figure shows light in the hue of this one.
const HUE_MAX_NM: f64 = 650.0;

/// [`wavelength_rgb`] in 8 bits a channel.
pub fn wavelength_rgb8(nm: f64) -> [u8; 3] {
    wavelength_rgb(nm).map(|c| (c * 255.0).round() as u8)
}

/// The sum of two colours, channel by channel.
fn add3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit against the CIE's own table (1931 2° observer, 5 nm steps) at its landmarks.
    #[test]
    fn the_eyes_response_is_the_cie_tables() {
        for (nm, table) in [
            (450.0, [0.3362, 0.0380, 1.7721]),
            (500.0, [0.0049, 0.3230, 0.2720]),
            (555.0, [0.5121, 1.0000, 0.0057]),
            (600.0, [1.0622, 0.6310, 0.0008]),
            (650.0, [0.2835, 0.1070, 0.0000]),
        ] {
            let fit = cie_1931(nm);
            for i in 0..3 {
                assert!(
                    (fit[i] - table[i]).abs() < 0.04,
                    "{nm} nm, function {i}: {} vs {}",
                    fit[i],
                    table[i]
                );
            }
        }
        // Each function's area over the visible: the table's 106.86 for each (1 nm steps).
        let mut area = [0.0; 3];
        for nm in 380..780 {
            let c = cie_1931(nm as f64 + 0.5);
            for i in 0..3 {
                area[i] += c[i];
            }
        }
        for a in area {
            assert!((a - 106.86).abs() < 2.0, "{a}");
        }
    }

    /// A figure's colour of a wavelength: the hue the eye sees there (blue, green, yellow, red
    /// as the CIE's observer has them), as bright as a screen allows.
    #[test]
    fn each_wavelength_is_shown_in_its_hue() {
        let hue = |nm: f64| {
            let [r, g, b] = wavelength_rgb(nm);
            assert!([r, g, b].iter().all(|c| (0.0..=1.0).contains(c)), "{nm}");
            assert!((r.max(g).max(b) - 1.0).abs() < 1e-12, "{nm}: {r} {g} {b}");
            (r, g, b)
        };
        let (r, g, b) = hue(450.0);
        assert!(b > 0.99 && r < b && g < b, "450 nm: {r} {g} {b}");
        let (r, g, b) = hue(530.0);
        assert!(g > 0.99 && r < g && b < g, "530 nm: {r} {g} {b}");
        // Yellow: red and green alike, little blue.
        let (r, g, b) = hue(578.0);
        assert!(r > 0.7 && g > 0.7 && b < 0.5, "578 nm: {r} {g} {b}");
        let (r, g, b) = hue(650.0);
        assert!(r > 0.99 && g < 0.5 && b < 0.5, "650 nm: {r} {g} {b}");
        // Violet: blue with some red; the far red, red.
        let (r, g, b) = hue(405.0);
        assert!(b > 0.99 && r > 0.3 && r > g, "405 nm: {r} {g} {b}");
        for nm in [700.0, 755.0] {
            let (r, g, b) = hue(nm);
            assert!(r > 0.99 && g < 0.1 && b < 0.1, "{nm} nm: {r} {g} {b}");
        }
    }

    #[test]
    fn the_bands_run_from_violet_to_red_and_make_white() {
        let bands = white_bands();
        let sum = bands.iter().fold([0.0; 3], |t, b| add3(t, b.rgb));
        for s in sum {
            assert!((s - 1.0).abs() < 1e-12);
        }
        assert_eq!(bands[0].nm, 405.0);
        assert_eq!(bands[WHITE_BANDS - 1].nm, 755.0);
        let dominant = |b: &Band| {
            (0..3)
                .max_by(|&i, &j| b.rgb[i].total_cmp(&b.rgb[j]))
                .unwrap()
        };
        // 455 nm is blue, 555 nm green, 605 and 655 nm red.
        assert_eq!(dominant(&bands[1]), 2);
        assert_eq!(dominant(&bands[3]), 1);
        assert_eq!(dominant(&bands[4]), 0);
        assert_eq!(dominant(&bands[5]), 0);
    }
}
