//! Numbers as the figures write them: angles in (−180°, 180°], wholes never "-0", and the
//! shortest exact form.

use bentstraw_optics::Vec3;

/// A number rounded to a whole, never written "-0".
pub(crate) fn whole(v: f64) -> String {
    let r = v.round();
    if r == 0.0 {
        "0".to_string()
    } else {
        format!("{r:.0}")
    }
}

/// An angle in degrees in (−180, 180].
pub(crate) fn degrees(angle: f64) -> f64 {
    let mut d = angle.to_degrees() % 360.0;
    if d > 180.0 {
        d -= 360.0;
    } else if d <= -180.0 {
        d += 360.0;
    }
    d
}

/// A number in its shortest exact form, for captions.
pub(crate) fn num(v: f64) -> String {
    format!("{v}")
}

/// A point as `(x, y, z)` in the shortest exact form.
pub(crate) fn triple(p: Vec3) -> String {
    format!("({}, {}, {})", num(p.x), num(p.y), num(p.z))
}
