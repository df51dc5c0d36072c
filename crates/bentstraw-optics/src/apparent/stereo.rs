//! The stereo model: two eyes on a horizontal baseline, each ray re-aimed at the straw point along
//! the observer's light path (from the eye model's first-order prediction), the two lines of sight
//! triangulated (the physics in [`super`], "Stereo model").

use std::sync::atomic::{AtomicBool, Ordering};

use super::pupil_axes;
use super::reaim::Aim;
use crate::image::ImagePoint;
use crate::parallel::*;
use crate::scene::SCENE_CENTRE;
use crate::world::World;
use crate::Vec3;

/// Distance between the two eyes of the stereo model (m).
pub const EYE_SEPARATION: f64 = 0.065;

/// The two eyes of the stereo model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StereoEyes {
    /// The left eye.
    pub left: Vec3,
    /// The right eye.
    pub right: Vec3,
}

impl StereoEyes {
    /// Eyes [`EYE_SEPARATION`] apart around `observer`, facing [`SCENE_CENTRE`] (see [`super`]).
    pub fn around(observer: Vec3) -> StereoEyes {
        StereoEyes::with_separation(observer, EYE_SEPARATION)
    }

    /// Eyes `separation` apart (m) around `observer` on the horizontal baseline of [`Self::around`].
    pub fn with_separation(observer: Vec3, separation: f64) -> StereoEyes {
        let to_centre = SCENE_CENTRE - observer;
        let level = Vec3::new(to_centre.x, to_centre.y, 0.0);
        // "Right" as for the observer's camera: forward × ẑ.
        let right = if level.length() < 1e-9 {
            Vec3::X
        } else {
            level.cross(Vec3::Z).normalize()
        };
        StereoEyes {
            left: observer - 0.5 * separation * right,
            right: observer + 0.5 * separation * right,
        }
    }
}

/// A straw point as two eyes see it (the stereo model).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StereoPoint {
    /// The course's image point (`O + L·u0`) of the observer's ray to the same straw point.
    pub image: ImagePoint,
    /// Midpoint of the closest approach of the two lines of sight, if they converge in front of
    /// both eyes.
    pub position: Option<Vec3>,
    /// Unit direction in which the left eye sees the point.
    pub left_direction: Vec3,
    /// Unit direction in which the right eye sees the point.
    pub right_direction: Vec3,
    /// Closest-approach distance of the two lines of sight (m): zero for a point image; not zero
    /// through astigmatic (curved) surfaces.
    pub miss_distance: f64,
    /// Vertical disparity (rad): angle of the right line of sight out of the plane of the baseline
    /// and the left line of sight, positive when the right eye looks higher.
    pub vertical_disparity: f64,
    /// Binocular disparity relative to the straw point itself (rad): the angle between the two
    /// lines of sight minus the angle the baseline subtends at the straw point; positive when the
    /// image looks nearer than the straw point.
    pub disparity: f64,
}

impl StereoPoint {
    /// Distance between the course's image point and the stereo point (m), if defined.
    pub fn gap_to_course(&self) -> Option<f64> {
        Some(self.position?.distance(self.image.position))
    }
}

/// The stereo image of a list of image points.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StereoImage {
    /// Points seen by both eyes, in the order of the input.
    pub points: Vec<StereoPoint>,
    /// Input points skipped because an eye does not see them along the same light path.
    pub skipped: usize,
}

/// The stereo model, for any world.
impl World {
    /// The stereo model's point for `image` (seen from `observer`), seen by `eyes`; `None` if an
    /// eye does not see the same straw point along the same light path.
    pub fn stereo_point(
        &self,
        eyes: &StereoEyes,
        observer: Vec3,
        image: &ImagePoint,
    ) -> Option<StereoPoint> {
        self.stereo_point_with(None, eyes, observer, image)
    }

    /// [`World::stereo_point`], with the world's faces alone ([`World::faces_only`]) if already
    /// made (else made for this point if an object is in the way of an eye's ray).
    fn stereo_point_with(
        &self,
        faces: Option<&World>,
        eyes: &StereoEyes,
        observer: Vec3,
        image: &ImagePoint,
    ) -> Option<StereoPoint> {
        let u0 = image.direction;
        let (e_h, e_v) = pupil_axes(u0);
        let (path, w) = self.vergence_matrix(observer, u0, e_h, e_v)?;
        let mut aim = Aim::new(self, path, u0, e_h, e_v);
        if let Some(faces) = faces {
            aim = aim.with_faces(faces);
        }
        // The first-order prediction from the vergence matrix, then Newton's method with the
        // exact Jacobian (a move along u0 keeps the ray: only the part across it turns it).
        let slope = |eye: Vec3| {
            let moved = eye - observer;
            let (h, v) = (moved.dot(e_h), moved.dot(e_v));
            [-(w[0][0] * h + w[0][1] * v), -(w[1][0] * h + w[1][1] * v)]
        };
        let (sl, sr) = (slope(eyes.left), slope(eyes.right));
        let xl = aim.predict_and_follow(observer, eyes.left, sl, sl)?;
        // The eyes straddle the observer: the solution's even part (second order in the eye's
        // offset) is the same for both, so the left eye's gives the right eye's to third order.
        let first = [sr[0] + (xl[0] - sl[0]), sr[1] + (xl[1] - sl[1])];
        let xr = aim.predict_and_follow(observer, eyes.right, sr, first)?;
        let (ul, ur) = (aim.direction(xl), aim.direction(xr));
        Some(triangulate(eyes, image, path.straw_point, ul, ur))
    }

    /// The stereo model's point by following the solution from the observer to each eye in
    /// small steps (continuation): the oracle of the predicted Newton's method.
    #[cfg(test)]
    fn stereo_point_by_continuation(
        &self,
        eyes: &StereoEyes,
        observer: Vec3,
        image: &ImagePoint,
    ) -> Option<StereoPoint> {
        let u0 = image.direction;
        let path = self.light_path(observer, u0)?;
        let (e_h, e_v) = pupil_axes(u0);
        let aim = Aim::new(self, path, u0, e_h, e_v);
        let ul = aim.continue_to(observer, eyes.left)?;
        let ur = aim.continue_to(observer, eyes.right)?;
        Some(triangulate(eyes, image, path.straw_point, ul, ur))
    }
}

/// The stereo point of `image` (straw point `q`) where `eyes` look along `ul` and `ur`.
fn triangulate(eyes: &StereoEyes, image: &ImagePoint, q: Vec3, ul: Vec3, ur: Vec3) -> StereoPoint {
    // Closest approach of left + s·ul and right + t·ur.
    let w0 = eyes.left - eyes.right;
    let (b, d, e) = (ul.dot(ur), ul.dot(w0), ur.dot(w0));
    let denom = 1.0 - b * b;
    let (position, miss_distance) = if denom > 1e-24 {
        let s = (b * e - d) / denom;
        let t = (e - b * d) / denom;
        let (pl, pr) = (eyes.left + s * ul, eyes.right + t * ur);
        (
            (s > 0.0 && t > 0.0).then(|| 0.5 * (pl + pr)),
            pl.distance(pr),
        )
    } else {
        (None, w0.cross(ul).length()) // parallel lines of sight
    };
    let baseline = (eyes.right - eyes.left).normalize();
    let vertical_disparity = libm::asin(ur.dot(baseline.cross(ul).normalize()).clamp(-1.0, 1.0));
    let straw_angle = libm::acos(
        (q - eyes.left)
            .normalize()
            .dot((q - eyes.right).normalize())
            .clamp(-1.0, 1.0),
    );
    let disparity = libm::acos(b.clamp(-1.0, 1.0)) - straw_angle;
    StereoPoint {
        image: *image,
        position,
        left_direction: ul,
        right_direction: ur,
        miss_distance,
        vertical_disparity,
        disparity,
    }
}

/// The stereo model's points for `points` (image points seen from `observer`), seen by the eyes
/// [`StereoEyes::around`] the observer, in the input's order; in parallel.
pub fn stereo_points(world: &World, observer: Vec3, points: &[ImagePoint]) -> StereoImage {
    stereo_points_until(world, observer, points, &AtomicBool::new(false)).expect("never stopped")
}

/// [`stereo_points`], abandoned as soon as another thread sets `stop` (`None` then). The points
/// are the same when it is not set.
pub fn stereo_points_until(
    world: &World,
    observer: Vec3,
    points: &[ImagePoint],
    stop: &AtomicBool,
) -> Option<StereoImage> {
    let all = stereo_point_each_until(world, observer, points, stop)?;
    let skipped = all.iter().filter(|p| p.is_none()).count();
    Some(StereoImage {
        points: all.into_iter().flatten().collect(),
        skipped,
    })
}

/// The stereo model's point for each of `points` (image points seen from `observer`), seen by the
/// eyes [`StereoEyes::around`] the observer: one per input point, `None` where an eye does not see
/// it along the same light path; in parallel.
pub fn stereo_point_each(
    world: &World,
    observer: Vec3,
    points: &[ImagePoint],
) -> Vec<Option<StereoPoint>> {
    stereo_point_each_until(world, observer, points, &AtomicBool::new(false))
        .expect("never stopped")
}

/// [`stereo_point_each`], abandoned as soon as another thread sets `stop` (`None` then). The
/// points are the same when it is not set.
pub fn stereo_point_each_until(
    world: &World,
    observer: Vec3,
    points: &[ImagePoint],
    stop: &AtomicBool,
) -> Option<Vec<Option<StereoPoint>>> {
    let eyes = StereoEyes::around(observer);
    let faces = world.faces_only();
    let all = points
        .par_iter()
        .map(|p| {
            if stop.load(Ordering::Relaxed) {
                None
            } else {
                world
                    .of_point(p)
                    .stereo_point_with(Some(faces.of_point(p)), &eyes, observer, p)
            }
        })
        .collect();
    (!stop.load(Ordering::Relaxed)).then_some(all)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::apparent::tests::{comparison_worlds, image, N};
    use crate::sampling::sample_image;
    use crate::scene::{Scene, REFERENCES, STRAW_RADIUS};

    /// Fermat's principle, independently of the tracer: the point S of the plane z = `he` where
    /// light from `q` (in the water, index n) to `e` (in the air) crosses the surface minimises
    /// |S − E| + n|S − Q|, a convex function of (S.x, S.y): Newton's method on its gradient.
    fn fermat_crossing(e: Vec3, q: Vec3, he: f64) -> Vec3 {
        let mut s = Vec3::new(0.5 * (e.x + q.x), 0.5 * (e.y + q.y), he);
        for _ in 0..50 {
            let (mut g, mut h) = ([0.0; 2], [[0.0; 2]; 2]);
            for (p, w) in [(e, 1.0), (q, N)] {
                let v = s - p;
                let l = v.length();
                let a = [v.x / l, v.y / l];
                for i in 0..2 {
                    g[i] += w * a[i];
                    for j in 0..2 {
                        h[i][j] += w * ((i == j) as u8 as f64 - a[i] * a[j]) / l;
                    }
                }
            }
            let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
            s.x -= (h[1][1] * g[0] - h[0][1] * g[1]) / det;
            s.y -= (h[0][0] * g[1] - h[1][0] * g[0]) / det;
        }
        s
    }

    /// Two eyes 65 mm apart looking down through the flat surface at a straw point under it:
    /// the stereo point is where the two lines of sight through the crossings given by Fermat's
    /// principle meet; by the mirror symmetry about the plane of incidence they do meet.
    #[test]
    fn stereo_through_flat_surface_matches_fermat() {
        let scene = Scene::with_defaults(0.0, 0.0, 0.15).unwrap();
        let he = scene.water_height();
        for (theta_w, d) in [(0.2, 0.05), (0.45, 0.04)] {
            let theta = (N * f64::sin(theta_w)).asin();
            let q = Vec3::new(STRAW_RADIUS, 0.0, he - d);
            let s = Vec3::new(STRAW_RADIUS + d * f64::tan(theta_w), 0.0, he);
            let observer = s + 0.2 * Vec3::new(theta.sin(), 0.0, theta.cos());
            let im = image(&scene, observer, s - observer);
            let eyes = StereoEyes::around(observer);
            let st = World::assignment(&scene)
                .stereo_point(&eyes, observer, &im)
                .unwrap();
            let line = |e: Vec3| (e, (fermat_crossing(e, q, he) - e).normalize());
            let ((el, ul), (er, ur)) = (line(eyes.left), line(eyes.right));
            assert!(
                ul.distance(st.left_direction) < 1e-12 && ur.distance(st.right_direction) < 1e-12
            );
            // Mirror images in y = 0: they meet there, where the left line crosses y = 0.
            let meet = el + (-el.y / ul.y) * ul;
            assert!((meet - er).cross(ur).length() < 1e-12);
            let p = st.position.unwrap();
            assert!(p.distance(meet) < 1e-9, "{p:?} vs {meet:?}");
            assert!(st.miss_distance < 1e-12 && st.vertical_disparity.abs() < 1e-12);
            // The image is lifted towards the eyes: nearer than the straw point.
            assert!(st.disparity > 0.0 && p.z > q.z);
        }
    }

    /// The eyes: 65 mm apart, centred on the observer, level, across the horizontal direction to
    /// the scene's centre, the left one on the left; `x̂` straight above the centre.
    #[test]
    fn stereo_eyes_straddle_the_observer_across_the_view() {
        for r in REFERENCES {
            let o = r.observer;
            let eyes = StereoEyes::around(o);
            let baseline = eyes.right - eyes.left;
            assert!((baseline.length() - EYE_SEPARATION).abs() < 1e-15);
            assert!((0.5 * (eyes.left + eyes.right)).distance(o) < 1e-15);
            assert!(baseline.z.abs() < 1e-15);
            let view = SCENE_CENTRE - o;
            assert!(baseline.dot(Vec3::new(view.x, view.y, 0.0)).abs() < 1e-15);
            // Facing the centre with z up, the right eye is on the side of view × ẑ.
            assert!(baseline.dot(view.cross(Vec3::Z)) > 0.0);
        }
        let above = StereoEyes::around(Vec3::new(0.0, 0.0, 0.5));
        assert!((above.right - above.left).normalize().distance(Vec3::X) < 1e-15);
    }

    /// The stereo model by predicted Newton's method gives the continuation oracle's points
    /// (within 1 nm) and sees the same points, in every world.
    #[test]
    fn stereo_model_matches_the_continuation_oracle_in_every_world() {
        for (name, world, observer) in comparison_worlds() {
            let eyes = StereoEyes::around(observer);
            let cloud = sample_image(&world, observer, 2000, &|_| {});
            let (mut compared, mut disagree, mut worst, mut lost) = (0, 0, 0.0_f64, 0);
            for im in &cloud.points {
                let fast = world.stereo_point(&eyes, observer, im);
                let oracle = world.stereo_point_by_continuation(&eyes, observer, im);
                match (fast, oracle) {
                    (Some(a), Some(b)) => {
                        let gap = a.left_direction.distance(b.left_direction)
                            + a.right_direction.distance(b.right_direction);
                        assert!(gap < 1e-12, "{name}: {a:?} vs {b:?}");
                        match (a.position, b.position) {
                            (Some(p), Some(q)) => {
                                assert!(p.distance(q) <= 1e-9, "{name}: {p} vs {q}");
                                worst = worst.max(p.distance(q));
                            }
                            (None, None) => {}
                            _ => panic!("{name}: {a:?} vs {b:?}"),
                        }
                        compared += 1;
                    }
                    (None, None) => {}
                    (Some(_), None) => disagree += 1,
                    (None, Some(_)) => lost += 1,
                }
            }
            eprintln!("{name}: {compared} stereo points compared, worst {worst:.2e} m, {disagree} seen only by Newton, {lost} only by the continuation");
            assert!(compared >= 1000, "{name}: {compared}");
            assert!(
                disagree * 200 <= compared,
                "{name}: {disagree} of {compared}"
            );
            assert!(lost * 200 <= compared, "{name}: {lost} of {compared}");
        }
    }

    /// On the reference views, the points the continuation oracle sees both eyes see (but for a
    /// handful at the edges of what an eye sees: deciding early that an eye does not see a point
    /// must not lose more), at the same place within 1 nm.
    #[test]
    fn stereo_model_loses_no_point_of_the_oracle_on_the_reference_views() {
        use crate::scene::{REFERENCES, WATER_INDEX};
        for r in REFERENCES {
            let world = World::assignment(&r.scene(WATER_INDEX));
            let eyes = StereoEyes::around(r.observer);
            let cloud = sample_image(&world, r.observer, 1500, &|_| {});
            let (mut compared, mut extra, mut lost) = (0, 0, 0);
            let fast = stereo_point_each(&world, r.observer, &cloud.points);
            for (im, fast) in cloud.points.iter().zip(fast) {
                let oracle = world.stereo_point_by_continuation(&eyes, r.observer, im);
                match (fast, oracle) {
                    (Some(a), Some(b)) => {
                        match (a.position, b.position) {
                            (Some(p), Some(q)) => assert!(p.distance(q) <= 1e-9, "{p} vs {q}"),
                            (None, None) => {}
                            _ => panic!("sim {}: {a:?} vs {b:?}", r.number),
                        }
                        compared += 1;
                    }
                    (None, Some(_)) => lost += 1,
                    (Some(_), None) => extra += 1,
                    (None, None) => {}
                }
            }
            eprintln!(
                "sim {}: {compared} compared, {extra} seen only by Newton, {lost} only by the oracle",
                r.number
            );
            // Most points are seen by both eyes (sim 3, looking down, the fewest: 84 %).
            assert!(
                compared * 5 >= cloud.points.len() * 4,
                "sim {}: {compared}",
                r.number
            );
            assert!(
                lost * 400 <= compared,
                "sim {}: {lost} of {compared}",
                r.number
            );
            assert!(
                extra * 200 <= compared,
                "sim {}: {extra} of {compared}",
                r.number
            );
        }
    }
}
