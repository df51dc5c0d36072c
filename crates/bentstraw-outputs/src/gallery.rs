//! The gallery of classic demonstrations, built into the program: its scene files, by name.

/// The gallery's scene files beyond the assignment's own (`scenes/`): name and text.
pub const GALLERY: [(&str, &str); 6] = [
    (
        "leaning-straw",
        include_str!("../../../scenes/leaning-straw.toml"),
    ),
    (
        "real-glass",
        include_str!("../../../scenes/real-glass.toml"),
    ),
    (
        "oil-on-water",
        include_str!("../../../scenes/oil-on-water.toml"),
    ),
    (
        "tank-pencil",
        include_str!("../../../scenes/tank-pencil.toml"),
    ),
    (
        "coin-in-glass",
        include_str!("../../../scenes/coin-in-glass.toml"),
    ),
    (
        "reversing-arrow",
        include_str!("../../../scenes/reversing-arrow.toml"),
    ),
];

/// What a scene file says it shows: its opening comment, as one paragraph.
pub fn opening_comment(text: &str) -> String {
    text.lines()
        .take_while(|l| l.starts_with('#'))
        .map(|l| l.trim_start_matches('#').trim())
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_input::file_world;
    use bentstraw_optics::scene::DEFAULT_MAX_EVENTS;

    #[test]
    fn every_gallery_scene_is_valid_and_says_what_it_shows() {
        for (stem, text) in GALLERY {
            let world = file_world(stem, text, DEFAULT_MAX_EVENTS).unwrap();
            assert!(!world.world.objects().is_empty(), "{stem}");
            assert!(opening_comment(text).len() > 60, "{stem}");
        }
    }
}
