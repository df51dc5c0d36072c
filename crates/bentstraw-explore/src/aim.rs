//! Where the scene's target appears in the picture, for the page's "Predict, then look": the
//! target (a straw's bottom end, a coin's centre, an arrow's tip) and the directions from the eye
//! whose rays reach it, found over the picture's own field of view.

use bentstraw_optics::camera::Camera;
use bentstraw_optics::geometry::Ray;
use bentstraw_optics::world::{Object, Outcome, Part, World};
use bentstraw_optics::Vec3;
use serde_json::{json, Value};

/// Most columns (and rows) of the grid of directions searched over the picture: at most
/// 128 × 128 traced rays, then a Newton search from each of the best few.
pub const AIM_GRID: usize = 128;
/// Most separate images of the target looked for (a straw's bottom seen through the wall and
/// through the surface, or once more by total reflection).
pub const MOST_IMAGES: usize = 6;
/// How far above a straw's bottom, along its axis, the point aimed at on its side lies (m): its
/// lower end as the eye sees it, on the side facing the light that reaches the eye.
pub const STRAW_END_LIFT: f64 = 1e-3;
/// Two images closer than this angle (radians, about 0.5°: a few pixels) are one: two rays of
/// the grid near the same image aim at points of a straw's end a fraction of a millimetre apart.
const SAME_IMAGE: f64 = 8.7e-3;

/// What the page asks the student to predict.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TargetKind {
    /// The bottom end of a straw.
    StrawBottom,
    /// The centre of a coin's face (the top one when the eye is above it).
    CoinCentre,
    /// The tip of the arrow drawn on a card.
    ArrowTip,
    /// The centre of a card with no arrow.
    CardCentre,
}

impl TargetKind {
    /// The name the page and its link use.
    pub fn key(self) -> &'static str {
        match self {
            TargetKind::StrawBottom => "straw-bottom",
            TargetKind::CoinCentre => "coin-centre",
            TargetKind::ArrowTip => "arrow-tip",
            TargetKind::CardCentre => "card-centre",
        }
    }
}

/// The scene's target: its kind, the object (its index among the world's objects) and the point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// What it is.
    pub kind: TargetKind,
    /// Which object of the world.
    pub object: usize,
    /// The point itself: a straw's bottom centre, a coin's face centre, the arrow's tip.
    pub point: Vec3,
}

/// The target seen from `eye`: the first straw's bottom end, else the first coin's centre (its
/// top face from above, else its bottom), else the first arrow's tip, else the first card's
/// centre; `None` in a scene with none of them (transparent solids alone).
pub fn scene_target(world: &World, eye: Vec3) -> Option<Target> {
    let objects = world.objects();
    let first = |want: &dyn Fn(&Object) -> bool| objects.iter().position(want);
    if let Some(k) = first(&|o| matches!(o, Object::Straw { .. })) {
        let Object::Straw { solid, .. } = objects[k] else {
            unreachable!()
        };
        return Some(Target {
            kind: TargetKind::StrawBottom,
            object: k,
            point: solid.base,
        });
    }
    if let Some(k) = first(&|o| matches!(o, Object::Coin(_))) {
        let Object::Coin(solid) = objects[k] else {
            unreachable!()
        };
        let top = solid.base + solid.length * solid.axis;
        let above = eye.z > 0.5 * (solid.base.z + top.z);
        return Some(Target {
            kind: TargetKind::CoinCentre,
            object: k,
            point: if above { top } else { solid.base },
        });
    }
    let card = first(&|o| matches!(o, Object::Card { arrow: true, .. }))
        .or_else(|| first(&|o| matches!(o, Object::Card { .. })))?;
    let Object::Card {
        centre,
        right,
        width,
        arrow,
        ..
    } = objects[card]
    else {
        unreachable!()
    };
    Some(if arrow {
        // The head's point (see `in_arrow`): 0.4 of the width right of the centre.
        Target {
            kind: TargetKind::ArrowTip,
            object: card,
            point: centre + 0.4 * width * right,
        }
    } else {
        Target {
            kind: TargetKind::CardCentre,
            object: card,
            point: centre,
        }
    })
}

/// One image of the target: the unit direction from the eye whose ray reaches it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sighting {
    /// The ray's first direction (unit).
    pub direction: Vec3,
    /// The point of the object the ray reaches (the target, or on a straw's side its lower end).
    pub reached: Vec3,
}

/// The images of `target` in `camera`'s picture of `world`: the directions within the picture
/// (its grid of at most [`AIM_GRID`]² rays) whose rays reach the target's object nearest the
/// target point, each then aimed exactly at it by Newton's method along its light path (the
/// stereo model's re-aiming). At most [`MOST_IMAGES`], nearest the target first; none when the
/// eye does not see the target in this picture (hidden, or seen only outside it).
pub fn sightings(world: &World, camera: &Camera, target: &Target) -> Vec<Sighting> {
    sightings_with(world, camera, target, AIM_GRID)
}

/// [`sightings`] on a grid of at most `grid` columns and rows.
fn sightings_with(world: &World, camera: &Camera, target: &Target, grid: usize) -> Vec<Sighting> {
    let eye = camera.eye;
    let (w, h) = (camera.width as f64, camera.height as f64);
    let cols = grid.min(camera.width as usize).max(2);
    let rows = ((cols as f64 * h / w).round() as usize).clamp(2, grid);
    let cell = |i: usize, j: usize| {
        let (row, col) = (
            (i as f64 + 0.5) * h / rows as f64,
            (j as f64 + 0.5) * w / cols as f64,
        );
        camera.direction_at(row, col).normalize()
    };
    // How far from the target each grid ray meets its object (infinite: not its object).
    let miss: Vec<(f64, Part)> = (0..rows * cols)
        .map(|k| {
            let ray = Ray {
                origin: eye,
                direction: cell(k / cols, k % cols),
            };
            match world.trace(ray) {
                Outcome::Object {
                    object,
                    point,
                    part,
                    ..
                } if object == target.object => (point.distance(target.point), part),
                _ => (f64::INFINITY, Part::Side),
            }
        })
        .collect();
    // The grid's local minima: the rays nearest the target in each piece of its image.
    let mut minima: Vec<usize> = (0..rows * cols)
        .filter(|&k| {
            let (i, j, d) = (k / cols, k % cols, miss[k].0);
            d.is_finite()
                && (-1i64..=1).all(|di| {
                    (-1i64..=1).all(|dj| {
                        let (a, b) = (i as i64 + di, j as i64 + dj);
                        if (di, dj) == (0, 0) || a < 0 || b < 0 {
                            return true;
                        }
                        let (a, b) = (a as usize, b as usize);
                        if a >= rows || b >= cols {
                            return true;
                        }
                        let other = a * cols + b;
                        // Ties go to the first cell, so that a flat piece gives one minimum.
                        miss[other].0 > d || (miss[other].0 == d && other > k)
                    })
                })
        })
        .collect();
    minima.sort_by(|a, b| miss[*a].0.total_cmp(&miss[*b].0));
    let mut found: Vec<Sighting> = Vec::new();
    for k in minima.into_iter().take(2 * MOST_IMAGES) {
        if found.len() == MOST_IMAGES {
            break;
        }
        let guess = cell(k / cols, k % cols);
        let Some(mut path) = world.light_path(eye, guess) else {
            continue;
        };
        let Some(aim) = aim_point(world, target, miss[k].1, path.final_direction) else {
            continue;
        };
        path.straw_point = aim;
        let Some(direction) = world.reaim(eye, &path, guess) else {
            continue;
        };
        if found
            .iter()
            .any(|s| s.direction.angle_between(direction) < SAME_IMAGE)
        {
            continue;
        }
        found.push(Sighting {
            direction,
            reached: aim,
        });
    }
    found
}

/// The point of the target's object to aim at, for a ray that meets it on `part` going along
/// `last` (its last direction): the target itself, except on a straw's side, where it is the
/// lower end's point facing that ray ([`STRAW_END_LIFT`] above the bottom); `None` when the ray
/// sees an arrow's card from behind (the arrow is drawn on its front only).
fn aim_point(world: &World, target: &Target, part: Part, last: Vec3) -> Option<Vec3> {
    match (target.kind, world.objects()[target.object]) {
        (TargetKind::StrawBottom, Object::Straw { solid, .. }) if part != Part::Bottom => {
            let across = last - last.dot(solid.axis) * solid.axis;
            if across.length() < 1e-9 {
                return Some(target.point);
            }
            let lift = STRAW_END_LIFT.min(0.5 * solid.length);
            Some(solid.base + lift * solid.axis - solid.radius * across.normalize())
        }
        (TargetKind::ArrowTip, Object::Card { front, .. }) => {
            (last.dot(front) < 0.0).then_some(target.point)
        }
        _ => Some(target.point),
    }
}

/// The answer for the page: the target (kind, object, point) and each image: its place in the
/// picture (`row`, `col` in its pixels, and whether it lies inside it) and its ray's path with
/// the course's, eye model's and stereo model's points (`ray`, as `/api/ray` gives it).
pub fn aim_json(world: &World, camera: &Camera, target: Option<Target>) -> Value {
    let Some(target) = target else {
        return json!({"target": Value::Null, "images": []});
    };
    let images: Vec<Value> = sightings(world, camera, &target)
        .iter()
        .filter_map(|s| {
            let (row, col) = camera.project(camera.eye + s.direction)?;
            let inside = (0.0..=camera.height as f64).contains(&row)
                && (0.0..=camera.width as f64).contains(&col);
            Some(json!({
                "row": row,
                "col": col,
                "inside": inside,
                "reached": [s.reached.x, s.reached.y, s.reached.z],
                "ray": crate::ray_json(world, camera.eye, s.direction),
            }))
        })
        .collect();
    json!({
        "target": {
            "kind": target.kind.key(),
            "object": target.object,
            "point": [target.point.x, target.point.y, target.point.z],
        },
        "images": images,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{handle, parse_query, Memory, View};
    use bentstraw_io::gallery::GALLERY;
    use bentstraw_io::scene_input::gallery_setup;
    use bentstraw_optics::frame::Frame;
    use bentstraw_optics::scene::DEFAULT_MAX_EVENTS;
    use bentstraw_optics::view::{CLASSIC_OBSERVER, CLASSIC_STRAW, CLASSIC_WATER_HEIGHT};

    fn view(q: &str) -> View {
        View::from_query(&parse_query(q).unwrap()).unwrap()
    }

    /// The page's first view: the straw seen from the side, broken at the surface.
    fn classic(extra: &str) -> View {
        let [x, y, z] = CLASSIC_OBSERVER;
        let [sx, sy] = CLASSIC_STRAW;
        view(&format!(
            "observer={x},{y},{z}&straw={sx},{sy}&water-height={CLASSIC_WATER_HEIGHT}&size=320x240{extra}"
        ))
    }

    /// Each image's ray, traced again, lands on the target's object at the point aimed at, and
    /// that point is the straw's lower end; its pixel's direction is its own.
    #[test]
    fn the_straws_bottom_is_seen_where_its_ray_lands() {
        let v = classic("");
        let world = &v.scene.world;
        let target = scene_target(world, v.observer).unwrap();
        assert_eq!(target.kind, TargetKind::StrawBottom);
        assert_eq!(target.point.z, 0.0);
        let found = sightings(world, &v.camera, &target);
        assert!(!found.is_empty());
        for s in &found {
            let ray = Ray {
                origin: v.observer,
                direction: s.direction,
            };
            let Outcome::Object { object, point, .. } = world.trace(ray) else {
                panic!("{s:?} reaches nothing");
            };
            assert_eq!(object, target.object);
            assert!(point.distance(s.reached) < 1e-9, "{point} {s:?}");
            let lift = s.reached.z - target.point.z;
            assert!((lift - STRAW_END_LIFT).abs() < 1e-12, "{lift}");
            let (row, col) = v.camera.project(v.observer + s.direction).unwrap();
            let back = v.camera.direction_at(row, col).normalize();
            assert!(back.angle_between(s.direction) < 1e-9);
        }
    }

    /// With water of index 1 nothing bends light: the one image is along the straight line from
    /// the eye to the point reached.
    #[test]
    fn without_refraction_the_image_is_on_the_straight_line() {
        let v = classic("&n-water=1");
        let world = &v.scene.world;
        let target = scene_target(world, v.observer).unwrap();
        let found = sightings(world, &v.camera, &target);
        assert_eq!(found.len(), 1, "{found:?}");
        let straight = (found[0].reached - v.observer).normalize();
        assert!(found[0].direction.angle_between(straight) < 1e-9);
    }

    /// Every gallery scene with an object names a target (a straw's bottom, a coin's centre, an
    /// arrow's tip), and its eye sees it in its picture in all but the marble's scene, where the
    /// marble hides the straw's bottom; the search stays within its bound of rays. The rainbow's
    /// drop alone in the sky has none.
    #[test]
    fn the_gallery_s_targets_are_found_from_their_own_eyes() {
        let mut hidden = Vec::new();
        for (stem, text) in GALLERY {
            let o = gallery_setup(stem, text, DEFAULT_MAX_EVENTS)
                .unwrap()
                .observer;
            let v = view(&format!(
                "scene={stem}&observer={},{},{}&size=320x240",
                o.x, o.y, o.z
            ));
            let world = &v.scene.world;
            if stem == "rainbow" {
                assert!(scene_target(world, v.observer).is_none());
                continue;
            }
            let target = scene_target(world, v.observer).unwrap();
            let want = match stem {
                "coin-in-glass" | "appearing-coin" | "apparent-depth" => TargetKind::CoinCentre,
                "reversing-arrow" | "near-and-far-arrow" | "cocktail-glass" => TargetKind::ArrowTip,
                _ => TargetKind::StrawBottom,
            };
            assert_eq!(target.kind, want, "{stem}");
            let found = sightings(world, &v.camera, &target);
            assert!(found.len() <= MOST_IMAGES);
            if found.is_empty() {
                hidden.push(stem);
            }
        }
        assert_eq!(hidden, ["marble-in-water"]);
    }

    /// The route answers the target and its images (each with its ray reaching the straw) as
    /// JSON; a view that breaks a rule is refused.
    #[test]
    fn the_route_answers_the_target_and_its_images() {
        let [x, y, z] = CLASSIC_OBSERVER;
        let q = format!("observer={x},{y},{z}&straw=0,0.03&water-height=0.15&size=160x120");
        let r = handle("/api/aim", &q, &mut Frame::default(), &Memory::default());
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        let a: Value = serde_json::from_slice(&r.body).unwrap();
        assert_eq!(a["target"]["kind"], "straw-bottom");
        let images = a["images"].as_array().unwrap();
        assert!(!images.is_empty());
        for im in images {
            assert_eq!(im["ray"]["outcome"], "straw");
            assert_eq!(im["ray"]["color"], 1);
            assert!(im["inside"].as_bool().unwrap());
            let (row, col) = (im["row"].as_f64().unwrap(), im["col"].as_f64().unwrap());
            assert!((0.0..=120.0).contains(&row) && (0.0..=160.0).contains(&col));
        }
        let bad = handle(
            "/api/aim",
            "observer=0,0,0.1&straw=0,0.03&water-height=0.15",
            &mut Frame::default(),
            &Memory::default(),
        );
        assert_eq!(bad.status, 400);
    }

    /// A scene with only a transparent solid has nothing to predict: no target, no image.
    #[test]
    fn a_scene_without_straw_coin_or_card_has_no_target() {
        let file = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.1\n\n\
                    [[sphere]]\ncenter = [0.0, 0.0, 0.02]\nradius = 0.01\nindex = 1.5\n";
        let q = format!(
            "scene-file={}&observer=0.2,0,0.05&size=80x60",
            bentstraw_io::view_spec::query_value(file)
        );
        let r = handle("/api/aim", &q, &mut Frame::default(), &Memory::default());
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        let a: Value = serde_json::from_slice(&r.body).unwrap();
        assert!(a["target"].is_null());
        assert_eq!(a["images"], json!([]));
    }
}
