//! How numbers and quoted words are written in messages: a number in its shortest exact digits,
//! user input clipped to a length. A module of its own so that the rules' messages
//! ([`crate::rule`]) need nothing from [`crate::scene`], which uses the rules.

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
