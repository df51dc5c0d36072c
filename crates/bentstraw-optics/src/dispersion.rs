//! Dispersion: a material's refractive index as a function of the wavelength of light. A scene
//! gives a medium either one index for every wavelength, or a law: Cauchy's, Sellmeier's, or a
//! named material from [`MATERIALS`] (each a measured formula with its source). A scene is
//! traced at one wavelength at a time: its description is evaluated there
//! ([`crate::scene_file::SceneDescription::at_wavelength`]), every law becoming the index it gives,
//! so that a scene at λ is, to the bit, the scene whose indices are those values.
//!
//! Wavelengths are in nanometres where people give them (380–780 nm, the visible), and in
//! micrometres inside the formulas, as the sources write them.

use crate::scene::is_physical_index;

/// The wavelength a scene is traced at when none is asked (nm): the helium d line, at which
/// glasses' catalogue indices `n_d` are given.
pub const D_LINE_NM: f64 = 587.56;
/// The shortest wavelength of visible light that may be asked (nm).
pub const VISIBLE_MIN_NM: f64 = 380.0;
/// The longest wavelength of visible light that may be asked (nm).
pub const VISIBLE_MAX_NM: f64 = 780.0;
/// The most terms a Sellmeier law takes (each a pair `B, C`).
pub const MAX_SELLMEIER_TERMS: usize = 4;

/// Whether `nm` is a wavelength that may be asked: finite, from [`VISIBLE_MIN_NM`] to
/// [`VISIBLE_MAX_NM`].
pub fn is_visible(nm: f64) -> bool {
    (VISIBLE_MIN_NM..=VISIBLE_MAX_NM).contains(&nm)
}

/// A law of dispersion over coefficients as its source writes them, λ in micrometres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Formula<'a> {
    /// Cauchy's `n = A + B/λ² + C/λ⁴`, from `[A, B]` or `[A, B, C]`.
    Cauchy(&'a [f64]),
    /// Sellmeier's `n² = 1 + Σ Bᵢλ²/(λ² − Cᵢ)`, from `[B1, C1, B2, C2, …]` (Cᵢ in µm²).
    Sellmeier(&'a [f64]),
}

impl Formula<'_> {
    /// The index at the wavelength `um` (micrometres). Only the four operations and a square
    /// root, each rounded exactly by IEEE arithmetic: every target gives the same bits.
    pub fn index(&self, um: f64) -> f64 {
        let l2 = um * um;
        match *self {
            Formula::Cauchy(c) => {
                let a = c.first().copied().unwrap_or(f64::NAN);
                let b = c.get(1).copied().unwrap_or(0.0);
                let c4 = c.get(2).copied().unwrap_or(0.0);
                a + b / l2 + c4 / (l2 * l2)
            }
            Formula::Sellmeier(terms) => {
                let mut n2 = 1.0;
                for bc in terms.chunks_exact(2) {
                    n2 += bc[0] * l2 / (l2 - bc[1]);
                }
                n2.sqrt()
            }
        }
    }

    /// Where, in the visible, the law gives no physical index (see [`is_physical_index`]): the
    /// first such wavelength (nm) and the value there, looking at every nanometre and at each
    /// Sellmeier pole (`λ² = Cᵢ`) that falls in the visible. `None` when it holds throughout.
    pub fn unphysical_in_visible(&self) -> Option<(f64, f64)> {
        if let Formula::Sellmeier(terms) = *self {
            for bc in terms.chunks_exact(2) {
                let pole_nm = bc[1].max(0.0).sqrt() * 1000.0;
                if bc[0] != 0.0 && is_visible(pole_nm) {
                    return Some((pole_nm, f64::INFINITY));
                }
            }
        }
        let (lo, hi) = (VISIBLE_MIN_NM as u32, VISIBLE_MAX_NM as u32);
        (lo..=hi).map(f64::from).find_map(|nm| {
            let n = self.index(nm / 1000.0);
            (!is_physical_index(n)).then_some((nm, n))
        })
    }
}

/// A named material: a measured law of dispersion and where it comes from.
#[derive(Debug, PartialEq)]
pub struct Material {
    /// Its name in scene files (`material = "bk7"`).
    pub name: &'static str,
    /// What it is, in words.
    pub words: &'static str,
    /// Its law, λ in micrometres.
    pub formula: Formula<'static>,
    /// The wavelengths its source measured (nm); the law is used from 380 to 780 nm.
    pub measured_nm: (f64, f64),
    /// Its source.
    pub source: &'static str,
}

/// A medium's law of dispersion as a scene file gives it.
#[derive(Clone, Debug, PartialEq)]
pub enum Dispersion {
    /// `cauchy = [A, B]` or `[A, B, C]`.
    Cauchy(Vec<f64>),
    /// `sellmeier = [B1, C1, …]`.
    Sellmeier(Vec<f64>),
    /// `material = "NAME"`.
    Material(&'static Material),
}

impl Dispersion {
    /// Its formula.
    pub fn formula(&self) -> Formula<'_> {
        match self {
            Dispersion::Cauchy(c) => Formula::Cauchy(c),
            Dispersion::Sellmeier(s) => Formula::Sellmeier(s),
            Dispersion::Material(m) => m.formula,
        }
    }

    /// The index at the wavelength `nm` (nanometres).
    pub fn index_at(&self, nm: f64) -> f64 {
        self.formula().index(nm / 1000.0)
    }
}

/// The material called `name` (letter case aside), if the table has it.
pub fn material(name: &str) -> Option<&'static Material> {
    MATERIALS.iter().find(|m| m.name.eq_ignore_ascii_case(name))
}

/// The named materials, each with its source's law and range (see `docs/physics.md`).
pub static MATERIALS: &[Material] = &[
    Material {
        name: "water",
        words: "water at 24 °C",
        formula: Formula::Sellmeier(&[
            5.666959820e-1,
            5.084151894e-3,
            1.731900098e-1,
            1.818488474e-2,
            2.095951857e-2,
            2.625439472e-2,
            1.125228406e-1,
            1.073842352e1,
        ]),
        measured_nm: (182.0, 1129.0),
        source: "M. Daimon and A. Masumura, Appl. Opt. 46, 3811 (2007)",
    },
    Material {
        name: "bk7",
        words: "crown glass (Schott N-BK7)",
        formula: Formula::Sellmeier(&[
            1.03961212,
            0.00600069867,
            0.231792344,
            0.0200179144,
            1.01046945,
            103.560653,
        ]),
        measured_nm: (300.0, 2500.0),
        source: "Schott optical glass data sheet, N-BK7",
    },
    Material {
        name: "f2",
        words: "flint glass (Schott F2)",
        formula: Formula::Sellmeier(&[
            1.34533359,
            0.00997743871,
            0.209073176,
            0.0470450767,
            0.937357162,
            111.886764,
        ]),
        measured_nm: (320.0, 2500.0),
        source: "Schott optical glass data sheet, F2",
    },
    Material {
        name: "sf10",
        words: "dense flint glass (Schott N-SF10)",
        formula: Formula::Sellmeier(&[
            1.62153902,
            0.0122241457,
            0.256287842,
            0.0595736775,
            1.64447552,
            147.468793,
        ]),
        measured_nm: (380.0, 2500.0),
        source: "Schott optical glass data sheet, N-SF10",
    },
    Material {
        name: "fused-silica",
        words: "fused silica (quartz glass)",
        formula: Formula::Sellmeier(&[
            0.6961663,
            0.0684043 * 0.0684043,
            0.4079426,
            0.1162414 * 0.1162414,
            0.8974794,
            9.896161 * 9.896161,
        ]),
        measured_nm: (210.0, 3710.0),
        source: "I. H. Malitson, J. Opt. Soc. Am. 55, 1205 (1965)",
    },
    Material {
        name: "acrylic",
        words: "acrylic glass (PMMA) at 23 °C",
        formula: Formula::Sellmeier(&[0.99654, 0.00787, 0.18964, 0.02191, 0.00411, 3.85727]),
        measured_nm: (404.7, 1083.0),
        source: "P. Szczurowski (2013), in the refractiveindex.info database",
    },
    Material {
        name: "polycarbonate",
        words: "polycarbonate at 20 °C",
        formula: Formula::Sellmeier(&[1.4182, 0.021304]),
        measured_nm: (436.8, 1052.0),
        source: "N. Sultanova, S. Kasarova and I. Nikolov, Acta Phys. Pol. A 116, 585 (2009)",
    },
    Material {
        name: "diamond",
        words: "diamond",
        formula: Formula::Sellmeier(&[0.3306, 0.1750 * 0.1750, 4.3356, 0.1060 * 0.1060]),
        measured_nm: (226.0, 760.0),
        source: "F. Peter, Z. Phys. 15, 358 (1923)",
    },
    Material {
        name: "glycerol",
        words: "glycerol at room temperature",
        formula: Formula::Cauchy(&[1.46004, 3.94934611e-3, -1.77343e-5]),
        measured_nm: (400.0, 710.0),
        source: "Gupta et al., Adv. Photonics Res. 2022, 2200152 (2022)",
    },
    Material {
        name: "ethanol",
        words: "ethanol at 22 °C",
        formula: Formula::Sellmeier(&[0.8312, 0.0964 * 0.0964, 0.0192, 2.97 * 2.97]),
        measured_nm: (400.0, 2000.0),
        source: "H.-J. Chang et al., Opt. Mater. Express 14, 1253 (2024)",
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    /// The catalogue's indices at the d line and its Abbe numbers `(n_d − 1)/(n_F − n_C)`
    /// (F: 486.13 nm, C: 656.27 nm), as the glass makers list them.
    #[test]
    fn glasses_give_their_catalogue_index_and_abbe_number() {
        for (name, n_d, abbe) in [
            ("bk7", 1.5168, 64.17),
            ("f2", 1.62004, 36.37),
            ("sf10", 1.72828, 28.53),
            ("fused-silica", 1.45846, 67.82),
        ] {
            let law = Dispersion::Material(material(name).unwrap());
            let (d, f, c) = (
                law.index_at(587.56),
                law.index_at(486.13),
                law.index_at(656.27),
            );
            assert!((d - n_d).abs() < 2e-5, "{name}: n_d {d} against {n_d}");
            let v = (d - 1.0) / (f - c);
            assert!(
                (v - abbe).abs() < 0.05 * 2.0,
                "{name}: V_d {v} against {abbe}"
            );
        }
    }

    /// The other materials against handbook indices at the d line, each source's own
    /// measurement a few parts in 10⁴ from them.
    #[test]
    fn materials_give_their_handbook_index() {
        for (name, n_d, within) in [
            ("water", 1.3330, 5e-4),
            ("acrylic", 1.4905, 1e-3),
            ("polycarbonate", 1.585, 1e-3),
            ("diamond", 2.4175, 5e-4),
            ("glycerol", 1.4730, 3e-3),
            ("ethanol", 1.3614, 5e-4),
        ] {
            let d = Dispersion::Material(material(name).unwrap()).index_at(D_LINE_NM);
            assert!((d - n_d).abs() < within, "{name}: n_d {d} against {n_d}");
        }
        assert!(material("BK7").is_some() && material("oil").is_none());
    }

    #[test]
    fn cauchy_and_sellmeier_are_their_formulas() {
        // n = 1.5 + 0.004/λ² + 0.0001/λ⁴ at 0.5 µm: 1.5 + 0.016 + 0.0016.
        let c = Formula::Cauchy(&[1.5, 0.004, 0.0001]);
        assert!((c.index(0.5) - 1.5176).abs() < 1e-15);
        assert_eq!(Formula::Cauchy(&[1.5, 0.004]).index(0.5), 1.5 + 0.016);
        // One term: n² = 1 + B λ²/(λ² − C) with B = 1, C = 0.01 at λ = 0.5: 1 + 0.25/0.24.
        let s = Formula::Sellmeier(&[1.0, 0.01]);
        assert!((s.index(0.5) - (1.0 + 0.25 / 0.24f64).sqrt()).abs() < 1e-15);
        // Normal dispersion: blue bends more than red.
        for m in MATERIALS {
            assert!(m.formula.index(0.40) > m.formula.index(0.70), "{}", m.name);
            assert_eq!(m.formula.unphysical_in_visible(), None, "{}", m.name);
        }
    }

    #[test]
    fn a_law_without_a_physical_index_in_the_visible_is_found() {
        // Below 1 from 0.38 µm: A = 0.9.
        assert_eq!(
            Formula::Cauchy(&[0.9, 0.001])
                .unphysical_in_visible()
                .map(|(nm, _)| nm),
            Some(380.0)
        );
        // A pole at 0.5 µm (C = 0.25 µm²).
        let pole = Formula::Sellmeier(&[0.5, 0.25]).unphysical_in_visible();
        assert_eq!(pole.map(|(nm, _)| nm), Some(500.0));
        // Above 5 in the violet only (5.17 at 380 nm, 4.90 at 395 nm).
        let (nm, n) = Formula::Cauchy(&[1.5, 0.53])
            .unphysical_in_visible()
            .unwrap();
        assert!(nm == 380.0 && n > 5.0, "{nm} {n}");
        assert!(Formula::Cauchy(&[1.5, 0.53]).index(0.395) < 5.0);
    }
}
