//! Every file of the gallery (`scenes/*.toml`) is a valid scene that opens with a comment saying
//! what it shows; `spec.toml` is the assignment's scene.

use std::path::PathBuf;

use bentstraw_optics::scene::Scene;
use bentstraw_optics::scene_file::SceneDescription;

fn gallery() -> Vec<(PathBuf, String)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("the gallery folder")
        .map(|e| e.expect("a gallery entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("a gallery file");
            (p, text)
        })
        .collect();
    files.sort();
    files
}

#[test]
fn every_gallery_file_parses_validates_and_says_what_it_shows() {
    let files = gallery();
    assert_eq!(
        files.len(),
        35,
        "the gallery's thirty-four scenes and the assignment's"
    );
    for (path, text) in &files {
        let d =
            SceneDescription::from_toml(text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            text.starts_with("# "),
            "{} opens with a comment",
            path.display()
        );
        assert!(d.observer.is_some(), "{} has its view", path.display());
        // What it writes reads back the same.
        assert_eq!(SceneDescription::from_toml(&d.to_toml()).unwrap(), d);
    }
}

#[test]
fn the_spec_file_is_the_assignment_scene_and_the_others_are_not() {
    for (path, text) in gallery() {
        let d = SceneDescription::from_toml(&text).unwrap();
        if path.ends_with("spec.toml") {
            assert_eq!(
                d.spec_scene(),
                Some(Scene::with_defaults(0.02, 0.01, 0.15).unwrap())
            );
        } else {
            assert_eq!(d.spec_scene(), None, "{}", path.display());
        }
    }
}

/// The packet tracer's kernels for the processor's wider instruction sets (eight lanes in one AVX
/// register, or thirty-two in two AVX-512 registers for course rows) give the portable kernel's
/// pixels (eight lanes as an array), bit for bit, on every gallery scene, in course and in Fresnel
/// mode, seen from the file's observer and from far away. Without AVX2 there is no second kernel
/// to compare and the test fails (the portable kernel compared with itself would prove nothing).
#[test]
#[ignore = "needs a processor with AVX2 (a packet kernel besides the portable one)"]
fn every_packet_kernel_gives_the_portable_pixels_on_every_gallery_scene() {
    use bentstraw_optics::camera::Camera;
    use bentstraw_optics::packet::{FresnelWave, Instructions, PacketTracer};
    use bentstraw_optics::world::World;

    let any = World::assignment(&Scene::with_defaults(0.02, 0.01, 0.15).unwrap());
    let kernels: Vec<Instructions> = [Instructions::Avx512, Instructions::Avx2]
        .into_iter()
        .filter(|&i| PacketTracer::new(&any).with_instructions(i).is_some())
        .collect();
    assert!(
        !kernels.is_empty(),
        "no AVX2 here: the packet kernels cannot be compared (run on an x86-64 processor with AVX2)"
    );
    for (path, text) in gallery() {
        let d = SceneDescription::from_toml(&text).unwrap();
        let world = World::new(&d, 10).unwrap();
        let observer = d.observer.as_ref().unwrap();
        let far = observer.target + 40.0 * (observer.position - observer.target);
        for eye in [observer.position, far] {
            let fov = if eye == far { 0.02 } else { 0.9 };
            let cam = Camera::new(eye, observer.target, 160, 48, fov);
            let portable = PacketTracer::new(&world);
            for &isa in &kernels {
                let fast = PacketTracer::new(&world).with_instructions(isa).unwrap();
                let mut wave = FresnelWave::default();
                for i in 0..cam.height {
                    let mut a = vec![0u8; cam.width as usize];
                    let mut b = a.clone();
                    fast.course_row(&cam, i, &mut a);
                    portable.course_row_portable(&cam, i, &mut b);
                    assert_eq!(a, b, "{} {isa:?} course row {i}", path.display());
                    let mut fa = vec![[0.0; 8]; cam.width as usize];
                    let mut fb = fa.clone();
                    fast.fresnel_row(&cam, i, 1e-4, &mut wave, &mut fa);
                    portable.fresnel_row_portable(&cam, i, 1e-4, &mut wave, &mut fb);
                    assert_eq!(fa, fb, "{} {isa:?} Fresnel row {i}", path.display());
                }
            }
        }
    }
}
