//! Parsers for the value forms of the command line and the explorer's queries (`X,Y,Z`, `WxH`):
//! each refusal one line that quotes the value, clipped.

use bentstraw_optics::text::clip_text;

use crate::camera::MAX_SIDE;

/// Parses `X,Y,Z` (three finite or non-finite numbers; finiteness is checked with the scene).
pub fn parse_vec3(s: &str) -> Result<[f64; 3], String> {
    let v = parse_list(s, 3, "X,Y,Z")?;
    Ok([v[0], v[1], v[2]])
}

/// Parses `X,Y`.
pub fn parse_vec2(s: &str) -> Result<[f64; 2], String> {
    let v = parse_list(s, 2, "XP,YP")?;
    Ok([v[0], v[1]])
}

/// Longest user text quoted whole in a parser's message, in characters.
pub const QUOTED_MAX: usize = 40;

/// User text for a message, clipped so that a hostile value cannot flood the terminal.
fn quoted(text: &str) -> String {
    clip_text(text, QUOTED_MAX)
}

fn parse_list(s: &str, n: usize, form: &str) -> Result<Vec<f64>, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != n {
        return Err(format!(
            "'{}' has {} number(s); expected {n}, as {form}",
            quoted(s),
            parts.len()
        ));
    }
    parts
        .iter()
        .map(|p| {
            p.parse::<f64>().map_err(|_| {
                format!(
                    "'{}' in '{}' is not a number (expected {form})",
                    quoted(p),
                    quoted(s)
                )
            })
        })
        .collect()
}

/// Parses `WxH` pixel sizes (both at least 1, at most [`MAX_SIDE`]).
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{}' is not a size: expected WxH, e.g. 800x600", quoted(s)))?;
    let parse = |t: &str| -> Result<u32, String> {
        let v: i64 = t.trim().parse().map_err(|_| {
            format!(
                "'{}' in '{}' is not a whole number of pixels",
                quoted(t),
                quoted(s)
            )
        })?;
        if !(1..=i64::from(MAX_SIDE)).contains(&v) {
            return Err(format!(
                "size '{}': each side must be between 1 and {MAX_SIDE} pixels, got {v}",
                quoted(s)
            ));
        }
        Ok(v as u32)
    };
    Ok((parse(w)?, parse(h)?))
}
