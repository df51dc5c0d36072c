//! The single-precision packet picture agrees with the double-precision one on every pixel but a
//! few on colour boundaries.

use bentstraw_optics::camera::Camera;
use bentstraw_optics::picture::{
    course_picture, course_picture_exact, fresnel_picture, fresnel_picture_exact,
};
use bentstraw_optics::scene::{Scene, REFERENCES, SCENE_CENTRE};
use bentstraw_optics::world::{World, COLOR_COUNT};
use bentstraw_optics::Vec3;

/// Pixels that differ, and how many of them lie off every colour boundary of the exact picture.
fn compare(scene: &Scene, camera: &Camera) -> (usize, usize) {
    let world = World::assignment(scene);
    let fast = course_picture(&world, camera);
    let exact = course_picture_exact(&world, camera);
    differing(&fast, &exact, camera.width as usize)
}

fn check(scene: &Scene, camera: &Camera, what: &str) {
    let (differ, off) = compare(scene, camera);
    eprintln!("{what}: {differ} pixels differ, {off} off boundaries");
    let total = (camera.width * camera.height) as usize;
    assert_eq!(
        off, 0,
        "{what}: {off} differing pixels off any colour boundary"
    );
    assert!(
        differ * 1000 < 5 * total,
        "{what}: {differ} of {total} pixels differ (bound 0.5%)"
    );
}

#[test]
fn packet_picture_matches_exact_on_benchmark_views() {
    for r in REFERENCES {
        let scene = r.scene(1.333);
        let target = r.zoom_target();
        let camera = Camera::new(r.observer, target, 1024, 768, 50f64.to_radians());
        check(&scene, &camera, &format!("simulation {}", r.number));
        // Wide view of the whole glass, odd size (partial packets at the row ends).
        let camera = Camera::new(r.observer, SCENE_CENTRE, 301, 203, 90f64.to_radians());
        check(&scene, &camera, &format!("simulation {} wide", r.number));
    }
}

#[test]
fn packet_picture_matches_exact_on_other_scenes() {
    for (xp, yp, he, n, observer) in [
        (0.0, 0.0, 0.1, 1.333, Vec3::new(0.15, 0.0, 0.05)),
        (0.025, -0.015, 0.2, 1.5, Vec3::new(-0.1, 0.1, 0.25)),
        (0.01, 0.0, 0.0, 1.333, Vec3::new(0.1, 0.05, 0.1)),
        (0.02, 0.01, 0.12, 1.0, Vec3::new(0.0, -0.2, 0.3)),
        (-0.02, 0.0, 0.18, 2.4, Vec3::new(0.0, 0.0, -0.15)),
    ] {
        let scene = Scene::new(xp, yp, he, n, 10).unwrap();
        let camera = Camera::new(observer, SCENE_CENTRE, 320, 240, 60f64.to_radians());
        check(&scene, &camera, &format!("scene {scene:?} from {observer}"));
    }
}

/// Fresnel: pixels whose weights differ from the double-precision picture's by more than 1e-3
/// (largest over the sections); how many differ by more than 0.01 off any boundary of the exact
/// picture (no 8-neighbour whose weights differ from the pixel's by more than 0.01); the largest
/// difference off boundaries.
///
/// A light secondary branch (weight ~1e-3) that grazes a rim can go either way in single
/// precision without the pixel being on a visible boundary; a heavy one cannot.
fn compare_fresnel(scene: &Scene, camera: &Camera) -> (usize, usize, f64) {
    let world = World::assignment(scene);
    let fast = fresnel_picture(&world, camera, 1e-4);
    let exact = fresnel_picture_exact(&world, camera, 1e-4);
    let (w, h) = (camera.width as i64, camera.height as i64);
    let at = |i: i64, j: i64| exact[(i * w + j) as usize];
    let gap = |a: [f64; COLOR_COUNT], b: [f64; COLOR_COUNT]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    let (mut differ, mut off, mut largest_inside) = (0, 0, 0.0f64);
    for i in 0..h {
        for j in 0..w {
            let d = gap(fast[(i * w + j) as usize], at(i, j));
            let mut boundary = false;
            for di in -1..=1 {
                for dj in -1..=1 {
                    let (ii, jj) = (i + di, j + dj);
                    if ii >= 0 && jj >= 0 && ii < h && jj < w && gap(at(ii, jj), at(i, j)) > 0.01 {
                        boundary = true;
                    }
                }
            }
            if !boundary {
                largest_inside = largest_inside.max(d);
            }
            differ += usize::from(d > 1e-3);
            off += usize::from(d > 0.01 && !boundary);
        }
    }
    (differ, off, largest_inside)
}

#[test]
fn packet_fresnel_picture_matches_exact() {
    for r in REFERENCES {
        let scene = r.scene(1.333);
        let target = r.zoom_target();
        for camera in [
            Camera::new(r.observer, target, 512, 384, 50f64.to_radians()),
            Camera::new(r.observer, SCENE_CENTRE, 301, 203, 90f64.to_radians()),
        ] {
            let (differ, off, largest) = compare_fresnel(&scene, &camera);
            let total = (camera.width * camera.height) as usize;
            eprintln!(
                "fresnel simulation {}: {differ} of {total} pixels differ by > 1e-3, {off} by > 0.01 off boundaries, largest difference off boundaries {largest:.2e}",
                r.number
            );
            assert_eq!(
                off, 0,
                "simulation {}: {off} pixels off boundaries",
                r.number
            );
            assert!(
                differ * 1000 < 5 * total,
                "simulation {}: {differ} pixels",
                r.number
            );
        }
    }
}

/// Far observers (1 km to 100 km) with a field of view that frames the glass: the packet
/// pictures agree with the double-precision ones as closely as near views do (the rays are made
/// in double precision and started on the scene's bounding sphere before they are rounded).
#[test]
fn packet_pictures_of_far_observers_match_exact() {
    let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
    for d in [1e3, 1e4, 1e5] {
        let observer = Vec3::new(d * 0.8, d * 0.6, 0.1 + d * 0.1);
        // The glass and straw, 0.3 m tall, fill about 80 % of the picture's height.
        let fov = 2.0 * (0.19 / d).atan();
        let camera = Camera::new(observer, SCENE_CENTRE, 320, 240, fov);
        check(&scene, &camera, &format!("course from {d} m"));
        let straw_pixels = course_picture_exact(&World::assignment(&scene), &camera)
            .iter()
            .filter(|&&c| c > 0)
            .count();
        assert!(
            straw_pixels > 800,
            "from {d} m only {straw_pixels} straw pixels"
        );
        let (differ, off, _) = compare_fresnel(&scene, &camera);
        assert_eq!(off, 0, "fresnel from {d} m: {off} pixels off boundaries");
        assert!(
            differ * 1000 < 5 * 320 * 240,
            "fresnel from {d} m: {differ} pixels"
        );
    }
}

/// Pixels of `fast` that differ from `exact` (row-major, `w` wide), and how many of them lie off
/// every colour boundary of `exact` (no 8-neighbour of another colour).
fn differing(fast: &[u8], exact: &[u8], w: usize) -> (usize, usize) {
    let h = exact.len() / w;
    let at = |i: usize, j: usize| exact[i * w + j];
    let (mut differ, mut off) = (0, 0);
    for i in 0..h {
        for j in 0..w {
            if fast[i * w + j] == at(i, j) {
                continue;
            }
            differ += 1;
            let boundary = (i.saturating_sub(1)..=(i + 1).min(h - 1))
                .any(|a| (j.saturating_sub(1)..=(j + 1).min(w - 1)).any(|b| at(a, b) != at(i, j)));
            off += usize::from(!boundary);
        }
    }
    (differ, off)
}

/// The packet pictures of `world` seen by `camera` (course and Fresnel, all eight codes) agree
/// with the double-precision ones on every pixel but a few on colour boundaries; `name` in the
/// messages.
fn check_world(name: &str, world: &World, camera: &Camera) {
    use bentstraw_optics::picture::{course_picture_into, fresnel_picture_into};
    let total = (camera.width * camera.height) as usize;
    let mut fast = vec![0u8; total];
    course_picture_into(world, camera, &mut fast);
    let exact = course_picture_exact(world, camera);
    if world.objects().is_empty() {
        // A drop alone in the sky: no colour code anywhere, in both.
        assert!(fast.iter().chain(&exact).all(|&c| c == 0), "{name}");
        return;
    }
    let seen = exact.iter().filter(|&&c| c > 0).count();
    assert!(seen > total / 200, "{name}: objects on {seen} pixels");
    let (differ, off) = differing(&fast, &exact, camera.width as usize);
    eprintln!(
        "{name}: course {differ} of {total} pixels differ ({seen} show objects), {off} off boundaries"
    );
    assert_eq!(off, 0, "{name}: {off} pixels off any colour boundary");
    assert!(differ * 1000 < 5 * total, "{name}: {differ} pixels differ");
    // Fresnel: the weights on every code agree to 1e-3 on all but a few pixels.
    let mut weights = vec![[0.0; 8]; total];
    fresnel_picture_into(world, camera, 1e-4, &mut weights);
    let exact_w = fresnel_picture_exact(world, camera, 1e-4);
    let close = weights
        .iter()
        .zip(&exact_w)
        .filter(|(a, b)| a.iter().zip(b.iter()).all(|(x, y)| (x - y).abs() < 1e-3))
        .count();
    eprintln!("{name}: fresnel {close} of {total} pixels within 1e-3");
    assert!(
        (total - close) * 100 < 2 * total,
        "{name}: {} pixels differ by more than 1e-3",
        total - close
    );
}

/// Every gallery scene (the assignment's, thick walls, layers, a tank, leaning straws, a coin, a
/// card): the packet
/// tracer, the same rule in single precision, agrees with the double-precision tracer on every
/// pixel but a few on colour boundaries, in course and in Fresnel mode (all eight codes).
#[test]
fn packet_pictures_of_every_gallery_scene_match_exact() {
    use bentstraw_optics::scene_file::SceneDescription;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 7, "the gallery: {files:?}");
    for path in files {
        let name = path.file_stem().unwrap().to_string_lossy();
        let text = std::fs::read_to_string(&path).unwrap();
        let d = SceneDescription::from_toml(&text).unwrap();
        let world = World::new(&d, 10).expect("a valid scene");
        let o = d.observer.unwrap();
        let camera = Camera::new(o.position, o.target, 240, 180, 40f64.to_radians());
        check_world(&name, &world, &camera);
    }
}

/// Scenes with transparent solids, each with its view: a marble in water beside a straw, a ball
/// in air in front of the glass, a fish-bowl (a ball of water in air with a small card inside),
/// a 60° prism in air beside the glass, a glass block standing in the water through its surface,
/// a biconvex lens in air between the eye and the glass, one standing through the water's
/// surface, a biconcave lens in the water in front of the straw.
fn solid_scenes() -> Vec<(&'static str, String)> {
    let glass = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
                 [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.1\n\n\
                 [[straw]]\nx = 0.015\ny = 0.0\n\n";
    vec![
        (
            "marble in water",
            format!(
                "{glass}[[sphere]]\ncenter = [-0.012, 0.012, 0.035]\nradius = 0.012\nindex = 1.5\n\n\
                 [observer]\nposition = [-0.2, 0.12, 0.09]\ntarget = [-0.004, 0.006, 0.05]\n"
            ),
        ),
        (
            "ball in front of the glass",
            format!(
                "{glass}[[sphere]]\ncenter = [0.1, 0.02, 0.09]\nradius = 0.035\nindex = 1.6\n\n\
                 [observer]\nposition = [0.35, 0.05, 0.12]\ntarget = [0.0, 0.0, 0.08]\n"
            ),
        ),
        (
            "fish-bowl",
            "[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n\
             [[sphere]]\ncenter = [0.0, 0.3, 0.1]\nradius = 0.05\nindex = 1.333\n\n\
             [[card]]\ncenter = [0.0, 0.3, 0.1]\nfacing = 20\nwidth = 0.04\nheight = 0.025\n\n\
             [observer]\nposition = [0.25, 0.38, 0.13]\ntarget = [0.0, 0.3, 0.1]\n"
                .to_string(),
        ),
        (
            "60° prism beside the glass",
            format!(
                "{glass}[[prism]]\ncorners = [[0.07, -0.02], [0.11, -0.02], [0.09, 0.014641]]\n\
                 bottom = 0.0\ntop = 0.06\nindex = 1.5\n\n\
                 [observer]\nposition = [0.4, -0.1, 0.06]\ntarget = [0.09, -0.008, 0.035]\n"
            ),
        ),
        (
            "glass block through the water's surface",
            format!(
                "{glass}[[prism]]\n\
                 corners = [[-0.025, -0.01], [-0.005, -0.01], [-0.005, 0.02], [-0.025, 0.02]]\n\
                 bottom = 0.0\ntop = 0.13\nindex = 1.5\n\n\
                 [observer]\nposition = [-0.2, 0.1, 0.12]\ntarget = [-0.015, 0.005, 0.09]\n"
            ),
        ),
        (
            "biconvex lens before the glass",
            format!(
                "{glass}[[lens]]\ncenter = [0.1, 0.0, 0.08]\naxis = [-1.0, 0.0, 0.0]\n\
                 radius1 = 0.06\nradius2 = -0.06\nthickness = 0.008\ndiameter = 0.04\n\
                 index = 1.5\n\n\
                 [observer]\nposition = [0.35, 0.02, 0.1]\ntarget = [0.0, 0.0, 0.07]\n"
            ),
        ),
        (
            "biconvex lens through the water's surface",
            format!(
                "{glass}[[lens]]\ncenter = [-0.015, 0.0, 0.1]\naxis = [1.0, 0.0, 0.0]\n\
                 radius1 = 0.04\nradius2 = -0.04\nthickness = 0.008\ndiameter = 0.03\n\
                 index = 1.5\n\n\
                 [observer]\nposition = [-0.2, 0.02, 0.11]\ntarget = [-0.015, 0.0, 0.1]\n"
            ),
        ),
        (
            "biconcave lens in the water",
            format!(
                "{glass}[[lens]]\ncenter = [-0.018, 0.0, 0.05]\naxis = [1.0, 0.0, 0.0]\n\
                 radius1 = -0.03\nradius2 = 0.03\nthickness = 0.002\ndiameter = 0.03\n\
                 index = 1.6\n\n\
                 [observer]\nposition = [-0.18, 0.0, 0.06]\ntarget = [-0.018, 0.0, 0.05]\n"
            ),
        ),
    ]
}

/// The packet tracer agrees with the double-precision tracer on solid scenes (spheres, prisms,
/// lenses) as on the gallery's, seen from each scene's observer, with a wide view (whole solids,
/// partial packets at the row ends) and a narrow one (a solid's rim and what is seen through it).
#[test]
fn packet_pictures_of_solid_scenes_match_exact() {
    use bentstraw_optics::scene_file::SceneDescription;
    for (name, text) in solid_scenes() {
        let d = SceneDescription::from_toml(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
        let world = World::new(&d, 10).expect("a valid scene");
        let o = d.observer.unwrap();
        for (fov, w, h) in [(40.0f64, 240, 180), (15.0, 161, 121)] {
            let camera = Camera::new(o.position, o.target, w, h, fov.to_radians());
            check_world(&format!("{name}, {fov}°"), &world, &camera);
            // The solids are in view: some pixels' rays refract at a solid's face.
            let through = (0..h)
                .flat_map(|i| (0..w).map(move |j| (i, j)))
                .filter(|&(i, j)| {
                    let mut on_solid = false;
                    world.trace_with(camera.pixel_ray(i, j), |e| {
                        on_solid |= world.boundaries()[e.boundary].solid
                    });
                    on_solid
                })
                .count();
            eprintln!("{name}, {fov}°: {through} pixels see through a solid");
            assert!(
                through * 100 > (w * h) as usize,
                "{name}, {fov}°: {through} pixels see through a solid"
            );
        }
    }
}

/// The packet kernels for the processor's wider instruction sets (AVX2, AVX-512) give the
/// portable kernel's pixels, bit for bit, on the solid scenes, course and Fresnel, from each
/// scene's observer and from far away. Without AVX2 there is no second kernel to compare and
/// the test fails.
#[test]
#[ignore = "needs a processor with AVX2 (a packet kernel besides the portable one)"]
fn every_packet_kernel_gives_the_portable_pixels_on_solid_scenes() {
    use bentstraw_optics::packet::{FresnelWave, Instructions, PacketTracer};
    use bentstraw_optics::scene_file::SceneDescription;
    let any = World::assignment(&Scene::with_defaults(0.02, 0.01, 0.15).unwrap());
    let kernels: Vec<Instructions> = [Instructions::Avx512, Instructions::Avx2]
        .into_iter()
        .filter(|&i| PacketTracer::new(&any).with_instructions(i).is_some())
        .collect();
    assert!(
        !kernels.is_empty(),
        "no AVX2 here: the packet kernels cannot be compared (run on an x86-64 processor with AVX2)"
    );
    for (name, text) in solid_scenes() {
        let d = SceneDescription::from_toml(&text).unwrap();
        let world = World::new(&d, 10).unwrap();
        let o = d.observer.unwrap();
        let far = o.target + 40.0 * (o.position - o.target);
        for (eye, fov) in [(o.position, 0.9), (far, 0.02)] {
            let cam = Camera::new(eye, o.target, 213, 48, fov);
            let portable = PacketTracer::new(&world);
            for &isa in &kernels {
                let fast = PacketTracer::new(&world).with_instructions(isa).unwrap();
                let mut wave = FresnelWave::default();
                for i in 0..cam.height {
                    let mut a = vec![0u8; cam.width as usize];
                    let mut b = a.clone();
                    fast.course_row(&cam, i, &mut a);
                    portable.course_row_portable(&cam, i, &mut b);
                    assert_eq!(a, b, "{name} {isa:?} course row {i}");
                    let mut fa = vec![[0.0; 8]; cam.width as usize];
                    let mut fb = fa.clone();
                    fast.fresnel_row(&cam, i, 1e-4, &mut wave, &mut fa);
                    portable.fresnel_row_portable(&cam, i, 1e-4, &mut wave, &mut fb);
                    assert_eq!(fa, fb, "{name} {isa:?} Fresnel row {i}");
                }
            }
        }
    }
}
