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
    assert_eq!(files.len(), 17, "the gallery's seventeen scenes");
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
