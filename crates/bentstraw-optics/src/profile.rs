//! A profile turned about the `z` axis: the wall of a container of revolution (a tapered
//! tumbler, a wine glass), given as points `(r, z)` with `z` rising.
//!
//! The surface passes through the points and is smooth between them (its tangent is
//! continuous). It is made of pieces on which the squared radius is a quadratic in the height,
//! `r² = c0 + c1·(z − zc) + c2·(z − zc)²`: each piece is a quadric of revolution (a cylinder, a
//! cone, a sphere, an ellipsoid, a paraboloid or a hyperboloid), which a ray's line meets where a
//! quadratic vanishes, so that every crossing is exact. A two-point profile is a straight wall,
//! the cylinder or cone itself. With more points the squared radius is a monotone quadratic
//! Hermite spline: two quadratics between each pair of points, joined at the midpoint, matching
//! the values and slopes at both points. The slope at a point is that of the parabola through it
//! and its neighbours, but flat where the radius turns (its neighbours both wider, or both
//! narrower) and never more than twice the steeper-side chord's least slope: then the radius
//! between two points stays between theirs, so a wall never swings past its points (nor onto the
//! axis), whatever points a hand drags.

/// One piece of a surface of revolution: `r² = c[0] + c[1]·(z − zc) + c[2]·(z − zc)²` for `z`
/// from `z0` to `z1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// The height the quadratic is written about (m).
    pub zc: f64,
    /// The quadratic's coefficients: `r²` (m²), its slope (m) and its half second derivative.
    pub c: [f64; 3],
    /// Lowest height (m).
    pub z0: f64,
    /// Highest height (m).
    pub z1: f64,
}

impl Piece {
    /// The squared radius at height `z` (m²).
    pub fn r2(&self, z: f64) -> f64 {
        let u = z - self.zc;
        self.c[0] + u * (self.c[1] + u * self.c[2])
    }

    /// The slope `d(r²)/dz` at height `z` (m).
    pub fn slope(&self, z: f64) -> f64 {
        self.c[1] + 2.0 * self.c[2] * (z - self.zc)
    }

    /// The least and the greatest squared radius between heights `lo` and `hi` (within the
    /// piece): at an end, or where the quadratic turns.
    pub fn r2_range(&self, lo: f64, hi: f64) -> (f64, f64) {
        let mut least = self.r2(lo).min(self.r2(hi));
        let mut most = self.r2(lo).max(self.r2(hi));
        if self.c[2] != 0.0 {
            let turn = self.zc - self.c[1] / (2.0 * self.c[2]);
            if turn > lo && turn < hi {
                least = least.min(self.r2(turn));
                most = most.max(self.r2(turn));
            }
        }
        (least, most)
    }
}

/// The pieces of the smooth surface through `points` (`[r, z]`, at least two, `z` strictly
/// rising), lowest first.
pub fn pieces(points: &[[f64; 2]]) -> Vec<Piece> {
    let n = points.len();
    if n < 2 {
        return Vec::new();
    }
    if n == 2 {
        // A straight wall: the cone (or cylinder) r = r0 + k·(z − z0), squared exactly.
        let ([r0, z0], [r1, z1]) = (points[0], points[1]);
        let k = (r1 - r0) / (z1 - z0);
        return vec![Piece {
            zc: z0,
            c: [r0 * r0, 2.0 * r0 * k, k * k],
            z0,
            z1,
        }];
    }
    let f: Vec<f64> = points.iter().map(|p| p[0] * p[0]).collect();
    let z: Vec<f64> = points.iter().map(|p| p[1]).collect();
    let h: Vec<f64> = z.windows(2).map(|w| w[1] - w[0]).collect();
    let s: Vec<f64> = (0..n - 1).map(|i| (f[i + 1] - f[i]) / h[i]).collect();
    // The slope of the parabola through each point and its two neighbours (one-sided at the
    // ends), limited so that each span stays monotone: 0 where the chords' slopes change sign,
    // at most twice the smaller chord slope (the two quadratics of a span are then monotone,
    // their slopes at the midpoint `2s − (d0 + d1)/2` keeping the chord's sign).
    let limited = |d: f64, chords: &[f64]| -> f64 {
        let same = chords.iter().all(|c| c * d > 0.0);
        if !same {
            return 0.0;
        }
        let cap = 2.0 * chords.iter().fold(f64::INFINITY, |m, c| m.min(c.abs()));
        d.clamp(-cap, cap)
    };
    let slope = |i: usize| -> f64 {
        if i == 0 {
            let d = ((2.0 * h[0] + h[1]) * s[0] - h[0] * s[1]) / (h[0] + h[1]);
            limited(d, &s[..1])
        } else if i == n - 1 {
            let (a, b) = (h[n - 2], h[n - 3]);
            let d = ((2.0 * a + b) * s[n - 2] - a * s[n - 3]) / (a + b);
            limited(d, &s[n - 2..])
        } else {
            let d = (h[i] * s[i - 1] + h[i - 1] * s[i]) / (h[i - 1] + h[i]);
            limited(d, &s[i - 1..=i])
        }
    };
    let mut out = Vec::with_capacity(2 * (n - 1));
    for i in 0..n - 1 {
        let (d0, d1, hi) = (slope(i), slope(i + 1), h[i]);
        // p(z) = f0 + d0·u + α·u² on the lower half, f1 + d1·v + β·v² on the upper (u = z − z0,
        // v = z − z1), equal in value and slope at the midpoint.
        let alpha = 2.0 * (f[i + 1] - f[i]) / (hi * hi) - (3.0 * d0 + d1) / (2.0 * hi);
        let beta = (d1 - d0) / hi - alpha;
        let lower = Piece {
            zc: z[i],
            c: [f[i], d0, alpha],
            z0: z[i],
            z1: z[i + 1],
        };
        if (alpha - beta).abs() <= 1e-9 * (alpha.abs() + beta.abs()) {
            // One quadratic through both points with both slopes: one piece.
            out.push(lower);
            continue;
        }
        let mid = 0.5 * (z[i] + z[i + 1]);
        out.push(Piece { z1: mid, ..lower });
        out.push(Piece {
            zc: z[i + 1],
            c: [f[i + 1], d1, beta],
            z0: mid,
            z1: z[i + 1],
        });
    }
    out
}

/// The radius at height `z` of the surface made of `pieces` (`None` outside its heights).
pub fn radius_at(pieces: &[Piece], z: f64) -> Option<f64> {
    pieces
        .iter()
        .find(|p| p.z0 <= z && z <= p.z1)
        .map(|p| p.r2(z).max(0.0).sqrt())
}

/// The least and the greatest radius of the surface between heights `lo` and `hi` (the part of
/// them it spans; `None` if it spans none).
pub fn radius_range(pieces: &[Piece], lo: f64, hi: f64) -> Option<(f64, f64)> {
    pieces
        .iter()
        .filter(|p| p.z1 >= lo && p.z0 <= hi)
        .map(|p| p.r2_range(p.z0.max(lo), p.z1.min(hi)))
        .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
        .map(|(least, most)| (least.max(0.0).sqrt(), most.max(0.0).sqrt()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every piece's squared radius and slope at `z`, from the piece holding it.
    fn at(pieces: &[Piece], z: f64) -> (f64, f64) {
        let p = pieces.iter().find(|p| p.z0 <= z && z <= p.z1).unwrap();
        (p.r2(z), p.slope(z))
    }

    #[test]
    fn two_points_make_a_cylinder_or_a_cone_exactly() {
        let cylinder = pieces(&[[0.04, 0.0], [0.04, 0.12]]);
        assert_eq!(cylinder.len(), 1);
        assert_eq!(cylinder[0].c, [0.04 * 0.04, 0.0, 0.0]);
        let cone = pieces(&[[0.03, 0.005], [0.045, 0.155]]);
        assert_eq!(cone.len(), 1);
        for z in [0.005, 0.05, 0.1, 0.155] {
            let r = 0.03 + 0.1 * (z - 0.005);
            assert!((cone[0].r2(z) - r * r).abs() < 1e-17, "{z}");
        }
    }

    #[test]
    fn points_on_a_cone_give_that_cone() {
        // Three points on one cone: the parabola's slope is the cone's, within the limits.
        let pts = [[0.03, 0.0], [0.036, 0.06], [0.042, 0.12]];
        let ps = pieces(&pts);
        for k in 0..=100 {
            let z = 0.12 * k as f64 / 100.0;
            let (f, _) = at(&ps, z);
            let r = 0.03 + 0.1 * z;
            assert!((f - r * r).abs() < 1e-16, "{z}");
        }
    }

    #[test]
    fn between_two_points_the_radius_stays_between_theirs() {
        // A foot, a thin stem and a bowl: steep and flat spans side by side, where an
        // unlimited spline would swing past its points and onto the axis.
        let pts = [
            [0.035, 0.0],
            [0.016, 0.006],
            [0.006, 0.01],
            [0.0045, 0.02],
            [0.004, 0.045],
            [0.012, 0.078],
            [0.041, 0.13],
            [0.035, 0.19],
        ];
        let ps = pieces(&pts);
        for w in pts.windows(2) {
            let (lo, hi) = (w[0][0].min(w[1][0]), w[0][0].max(w[1][0]));
            for k in 0..=200 {
                let z = w[0][1] + (w[1][1] - w[0][1]) * k as f64 / 200.0;
                let r = radius_at(&ps, z).unwrap();
                assert!(
                    r >= lo * (1.0 - 1e-12) && r <= hi * (1.0 + 1e-12),
                    "{z}: {r}"
                );
            }
        }
    }

    #[test]
    fn a_bent_profile_passes_through_its_points_with_a_continuous_tangent() {
        let pts = [
            [0.035, 0.0],
            [0.004, 0.02],
            [0.004, 0.08],
            [0.04, 0.13],
            [0.036, 0.2],
        ];
        let ps = pieces(&pts);
        for p in &pts {
            let r = radius_at(&ps, p[1]).unwrap();
            assert!((r - p[0]).abs() < 1e-15, "{p:?}: {r}");
        }
        // Where two pieces meet, their values and slopes agree.
        for w in ps.windows(2) {
            let z = w[0].z1;
            assert_eq!(z, w[1].z0);
            assert!((w[0].r2(z) - w[1].r2(z)).abs() < 1e-15);
            assert!((w[0].slope(z) - w[1].slope(z)).abs() < 1e-12);
        }
        let (least, most) = radius_range(&ps, 0.0, 0.2).unwrap();
        assert!(least <= 0.004 && most >= 0.04);
    }
}
