//! How numbers and quoted words are written in messages: a number in its shortest exact digits,
//! user input clipped to a length. A module of its own so that the rules' messages
//! ([`crate::rule`]) need nothing from [`crate::scene`], which uses the rules.

/// An 8-bit colour as CSS and SVG write it: `#rrggbb`.
pub fn css_hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// A number as a message quotes it: the shortest digits that read back to the same value (so a
/// value just past a limit shows why it fails), in scientific notation when that is shorter
/// (`-1e-320`, not 320 zeros), and at most 24 characters (longer ones are clipped with `…`).
pub fn number_text(x: f64) -> String {
    // Rust's `{:?}` for f64 is the shortest round-trip form, scientific outside 1e-5..1e16; a
    // whole number reads as the user wrote it (`1`, not `1.0`).
    let t = format!("{x:?}");
    clip_text(t.strip_suffix(".0").unwrap_or(&t), 24)
}

/// `text` cut to at most `max` characters, with `…` where it was cut (for quoting user input).
pub fn clip_text(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        text.to_string()
    } else {
        let mut t: String = text.chars().take(max.saturating_sub(1)).collect();
        t.push('…');
        t
    }
}

/// The refusal of `value` for the option `option`, which takes one of `choices`: the command
/// line's words (`invalid value 'wave' for '--mode' [possible values: course, fresnel]`), the
/// value clipped.
pub fn refuse_choice(option: &str, value: &str, choices: &[&str]) -> String {
    format!(
        "invalid value '{}' for '{option}' [possible values: {}]",
        clip_text(value, 40),
        choices.join(", ")
    )
}

/// The names among `names` that `word` may be a slip for, nearest first, at most three: those
/// that at most a third of their letters' edits (at least one; a swap of two letters counts as
/// one) turn into `word`, letter case aside.
pub fn nearest_names<'a>(word: &str, names: impl IntoIterator<Item = &'a str>) -> Vec<&'a str> {
    let word = word.to_lowercase();
    let mut near: Vec<(usize, &str)> = names
        .into_iter()
        .map(|name| {
            (
                strsim::damerau_levenshtein(&word, &name.to_lowercase()),
                name,
            )
        })
        .filter(|(edits, name)| *edits <= (name.chars().count() / 3).max(1))
        .collect();
    near.sort_by_key(|(edits, _)| *edits);
    near.into_iter().take(3).map(|(_, name)| name).collect()
}

/// The hint for a slip among `names`: `did you mean 'prism'?` (or `'a' or 'b'?`), or None when
/// no name is near.
pub fn did_you_mean<'a>(word: &str, names: impl IntoIterator<Item = &'a str>) -> Option<String> {
    let near = nearest_names(word, names);
    (!near.is_empty()).then(|| format!("did you mean {}?", quoted_names(&near)))
}

/// Names as a hint lists them: `'f2'`, or `'a' or 'b'`.
pub fn quoted_names(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
    quoted.join(" or ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slip_finds_the_names_it_may_stand_for_nearest_first() {
        let names = [
            "prism",
            "prism-spectrum",
            "ball-lens",
            "leaning-straw",
            "coin",
        ];
        assert_eq!(nearest_names("prysm", names), ["prism"]);
        assert_eq!(nearest_names("Leaning_Straw", names), ["leaning-straw"]);
        assert_eq!(nearest_names("coins", names), ["coin"]);
        assert!(nearest_names("aquarium", names).is_empty());
        assert_eq!(nearest_names("f3", ["f2", "sf10", "bk7"]), ["f2"]);
        assert!(nearest_names("x", ["f2"]).is_empty());
        assert_eq!(
            did_you_mean("bal-lens", names).as_deref(),
            Some("did you mean 'ball-lens'?")
        );
        assert_eq!(did_you_mean("wine", names), None);
    }
}
