//! `GET /api/sweep`: apparent depth against the viewing angle. One object point, picked in the
//! picture (`row`, `col`, as `/api/ray` takes them) or given (`point=x,y,z`, on an object's
//! surface, with `direction=dx,dy,dz` the direction the observer sees it along, if known: the
//! readout's ray), followed as the eye moves round the glass (`sweep=around`) or up and down
//! (`sweep=updown`) at the same distance from where the camera looks; `rows=N` seats (2 to 361,
//! 61 when not given); `format=json` (the page's plot) or `format=csv` (the file, see
//! `bentstraw_io::sweep`).

use std::collections::HashMap;
use std::sync::atomic::AtomicBool;

use bentstraw_io::parse::parse_vec3;
use bentstraw_io::sweep::{model_points, shown_heights, write_sweep_csv};
use bentstraw_io::view_spec::number;
use bentstraw_optics::apparent::{
    sweep_apparent_until, Sight, Sweep, SweepKind, DEFAULT_SWEEP_ROWS, MAX_SWEEP_ROWS,
    MIN_SWEEP_ROWS, SWEEP_POINT_TOLERANCE,
};
use bentstraw_optics::text::{clip_text, refuse_choice};
use bentstraw_optics::Vec3;

use crate::pixel_direction;
use serde_json::{json, Value};

use super::{get, stopped, vec_json, Reply, View};

/// The point to follow and the direction the observer sees it along, if picked in the picture.
fn object_point(view: &View, q: &HashMap<String, String>) -> Result<(Vec3, Option<Vec3>), String> {
    let world = &view.scene.world;
    if let Some(text) = get(q, "point") {
        let p = parse_vec3(text)
            .map(Vec3::from_array)
            .map_err(|e| format!("invalid value '{}' for 'point': {e}", clip_text(text, 40)))?;
        if !p.is_finite() {
            return Err(format!(
                "invalid value '{}' for 'point': not a finite number",
                clip_text(text, 40)
            ));
        }
        let seen_along = match get(q, "direction") {
            Some(d) => {
                let u = parse_vec3(d).map(Vec3::from_array).map_err(|e| {
                    format!("invalid value '{}' for 'direction': {e}", clip_text(d, 40))
                })?;
                if !u.is_finite() || u.length() < 1e-12 {
                    return Err(format!(
                        "invalid value '{}' for 'direction': not a direction (finite, not zero)",
                        clip_text(d, 40)
                    ));
                }
                Some(u)
            }
            None => None,
        };
        let off = world.distance_to_objects(p);
        if off > SWEEP_POINT_TOLERANCE {
            return Err(format!(
                "point ({}, {}, {}) m is {} mm from the nearest object's surface: a sweep follows \
                 a point on an object (at most {} mm from one); pick one in the picture",
                p.x,
                p.y,
                p.z,
                (off * 1e3 * 1e3).round() / 1e3,
                SWEEP_POINT_TOLERANCE * 1e3
            ));
        }
        return Ok((p, seen_along));
    }
    let (row, col, u0) = pixel_direction(view, q)?;
    match world.image_point(view.observer, u0) {
        Some(image) => Ok((image.straw_point, Some(u0))),
        None => Err(format!(
            "the ray through pixel ({row}, {col}) reaches no object: a sweep follows a point on \
             an object; pick one in the picture"
        )),
    }
}

/// The sweep asked for by the query: its kind and its number of seats, about the point the
/// camera looks at.
fn asked_sweep(view: &View, q: &HashMap<String, String>) -> Result<Sweep, String> {
    let name = get(q, "sweep").unwrap_or("around");
    let kind = SweepKind::from_name(name)
        .ok_or_else(|| refuse_choice("sweep", name, &SweepKind::NAMES))?;
    let rows = match get(q, "rows") {
        Some(t) => number::<usize>(t, "rows")?,
        None => DEFAULT_SWEEP_ROWS,
    };
    if !(MIN_SWEEP_ROWS..=MAX_SWEEP_ROWS).contains(&rows) {
        return Err(format!(
            "rows={rows} is not allowed: a sweep has {MIN_SWEEP_ROWS} <= rows <= \
             {MAX_SWEEP_ROWS} seats"
        ));
    }
    Ok(Sweep {
        kind,
        centre: sweep_centre(view),
        rows,
    })
}

/// Where the camera looks (the page's target, else the scene's): the eye keeps its distance
/// from it, and turns about the vertical through it.
pub fn sweep_centre(view: &View) -> Vec3 {
    view.spec
        .camera
        .target
        .map(Vec3::from_array)
        .unwrap_or_else(|| view.scene.default_target())
}

/// `GET /api/sweep` (see the module's documentation). Setting `stop` abandons it (a 409 answer).
pub fn sweep_reply(
    view: &View,
    q: &HashMap<String, String>,
    stop: &AtomicBool,
) -> Result<Reply, String> {
    let format = get(q, "format").unwrap_or("json");
    if !["json", "csv"].contains(&format) {
        return Err(refuse_choice("format", format, &["json", "csv"]));
    }
    let sweep = asked_sweep(view, q)?;
    let (point, seen_along) = object_point(view, q)?;
    let Some(rows) =
        sweep_apparent_until(&view.scene, view.observer, point, seen_along, &sweep, stop)
    else {
        return Ok(stopped());
    };
    if format == "csv" {
        let mut body = Vec::new();
        write_sweep_csv(&mut body, &rows).map_err(|e| format!("cannot write the sweep: {e}"))?;
        let mut r = Reply::bytes("text/csv", body);
        r.file_name = Some(format!("sweep-{}.csv", sweep.kind.name()));
        return Ok(r);
    }
    let point_or_null = |p: Option<Vec3>| p.map_or(Value::Null, vec_json);
    let rows: Vec<Value> = rows
        .iter()
        .map(|r| {
            let [course, focus_h, focus_v, stereo] = model_points(r);
            let seen = r.seen();
            json!({
                "angle": r.angle,
                "eye": vec_json(r.eye),
                "current": r.current,
                "sight": match r.sight {
                    Sight::Seen(_) => "seen",
                    Sight::NotSeen => "not_seen",
                    Sight::EyeInside => "eye_inside",
                },
                "path": seen.map(|s| s.path.key()),
                "course": point_or_null(course),
                "focus_h": point_or_null(focus_h),
                "focus_v": point_or_null(focus_v),
                "stereo": point_or_null(stereo),
                "s_h": seen.and_then(|s| s.apparent.s_h.distance()),
                "s_v": seen.and_then(|s| s.apparent.s_v.distance()),
            })
        })
        .collect();
    Ok(Reply::json(&json!({
        "sweep": sweep.kind.name(),
        "range": sweep.kind.range(),
        "centre": vec_json(sweep.centre),
        "point": vec_json(point),
        "shown": shown_heights(point),
        "observer": vec_json(view.observer),
        "rows": rows,
    })))
}

#[cfg(test)]
mod tests {
    use crate::{handle, Frame, Memory};

    const REF2: &str = "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15";

    fn get(path_query: &str) -> crate::Reply {
        let (path, query) = path_query.split_once('?').unwrap();
        handle(path, query, &mut Frame::default(), &Memory::default())
    }

    /// The picked pixel's ray and the sweep's own seat give the same numbers as `/api/ray`; the
    /// CSV has a row per seat, the same numbers as the JSON; both kinds answer.
    #[test]
    fn the_observers_seat_gives_the_rays_numbers_and_the_csv_the_jsons() {
        let size = "&size=160x120";
        // The first pixel of the middle row whose ray reaches the straw.
        let (col, ray) = (0..160)
            .step_by(2)
            .find_map(|col| {
                let q = format!("/api/ray?{REF2}{size}&row=80&col={col}");
                let ray: serde_json::Value = serde_json::from_slice(&get(&q).body).unwrap();
                (ray["outcome"] == "straw").then_some((col, ray))
            })
            .expect("the straw is in the picture");
        for kind in ["around", "updown"] {
            let q = format!("/api/sweep?{REF2}{size}&row=80&col={col}&sweep={kind}&rows=21");
            let r = get(&q);
            assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
            let v: serde_json::Value = serde_json::from_slice(&r.body).unwrap();
            let rows = v["rows"].as_array().unwrap();
            assert!(rows.len() == 21 || rows.len() == 22);
            let own: Vec<&serde_json::Value> =
                rows.iter().filter(|r| r["current"] == true).collect();
            assert_eq!(own.len(), 1);
            assert_eq!(own[0]["course"], ray["image_point"]);
            assert_eq!(own[0]["stereo"], ray["stereo_point"]);
            assert_eq!(own[0]["s_h"], ray["s_h"]["distance"]);
            assert_eq!(v["point"], ray["straw_point"]);
            let csv = get(&format!("{q}&format=csv"));
            assert_eq!(csv.status, 200);
            assert_eq!(
                csv.file_name.as_deref(),
                Some(&*format!("sweep-{kind}.csv"))
            );
            let text = String::from_utf8(csv.body).unwrap();
            let lines: Vec<&str> = text.lines().collect();
            assert_eq!(lines.len(), rows.len() + 1);
            // serde_json reads numbers to within an ulp (the page's JSON.parse reads them exactly).
            let same = |a: f64, b: f64| (a - b).abs() <= 1e-14 * a.abs().max(1.0);
            for (line, row) in lines[1..].iter().zip(rows) {
                let f: Vec<&str> = line.split(',').collect();
                assert!(same(f[0].parse().unwrap(), row["angle"].as_f64().unwrap()));
                assert_eq!(f[5], row["sight"]);
                if let Some(z) = row["course"][2].as_f64() {
                    assert!(same(f[9].parse().unwrap(), z));
                }
            }
            // The same point given by its coordinates: the same rows but the observer's seat,
            // where the search may find the same ray to within rounding.
            let p = &ray["straw_point"];
            let by_point = get(&format!(
                "/api/sweep?{REF2}{size}&point={},{},{}&sweep={kind}&rows=21",
                p[0], p[1], p[2]
            ));
            assert_eq!(by_point.status, 200);
            // With the readout's direction too: exactly the readout's numbers at the seat.
            let u = &ray["direction"];
            let along: serde_json::Value = serde_json::from_slice(
                &get(&format!(
                    "/api/sweep?{REF2}{size}&point={},{},{}&direction={},{},{}&sweep={kind}&rows=21",
                    p[0], p[1], p[2], u[0], u[1], u[2]
                ))
                .body,
            )
            .unwrap();
            assert_eq!(along["rows"], v["rows"]);
        }
    }

    /// Refusals name the value and the rule.
    #[test]
    fn bad_sweeps_are_refused_with_the_rule() {
        let refused = |extra: &str| {
            let r = get(&format!("/api/sweep?{REF2}&size=160x120&{extra}"));
            assert_eq!(r.status, 400, "{extra}");
            String::from_utf8(r.body).unwrap()
        };
        assert!(refused("row=60&col=80&sweep=sideways").contains("sideways"));
        let rows = refused("row=60&col=80&rows=100000");
        assert!(
            rows.contains("rows=100000") && rows.contains("361"),
            "{rows}"
        );
        assert!(refused("row=60&col=80&rows=1").contains("2 <= rows"));
        assert!(refused("row=60&col=80&format=xml").contains("xml"));
        let off = refused("point=0.5,0.5,0.5");
        assert!(off.contains("from the nearest object's surface"), "{off}");
        assert!(refused("point=nan,0,0").contains("point"));
        assert!(refused("point=0.02,0.015,0.05&direction=0,0,0").contains("'direction'"));
        assert!(refused("row=0&col=0").contains("reaches no object"));
        assert!(refused("row=500&col=0").contains("outside"));
        assert!(refused("sweep=around").contains("'row'"));
    }
}
