//! How written files, summaries and figures name a scene: its inputs under their documented names
//! and in their documented order, what its image is of, and which colours its tables list. The
//! assignment's glass keeps the names its documentation gives (`straw`, `water_height`,
//! `n_water`); a scene file is named by its file and written out whole. Every writer formats the
//! one list below the same way whatever the scene, so the choice between the two is made here,
//! once.

use std::fmt;

use crate::setup::Setup;
use crate::Vec3;

/// One input of a scene, under the name files and messages give it.
#[derive(Clone, Debug, PartialEq)]
pub struct Input {
    /// The documented name: `observer`, `straw`, `water_height`, `n_water`, `max_events`,
    /// `scene_file` or `scene`.
    pub key: &'static str,
    /// Its value.
    pub value: InputValue,
}

/// The value of an [`Input`], typed by how text writes it.
#[derive(Clone, Debug, PartialEq)]
pub enum InputValue {
    /// A point (m).
    Point(Vec3),
    /// A point on the floor (m).
    Pair([f64; 2]),
    /// A length (m).
    Length(f64),
    /// A number without unit.
    Number(f64),
    /// A count.
    Count(u32),
    /// A name on one line.
    Name(String),
    /// A text of several lines: the scene file as TOML, written out in full by the points' JSON
    /// and left out of one-line texts.
    Text(String),
}

impl fmt::Display for InputValue {
    /// The value as tables show it: `(x, y, z) m`, `(x, y) m`, `h m`, `n`, the name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InputValue::Point(p) => write!(f, "({}, {}, {}) m", p.x, p.y, p.z),
            InputValue::Pair([x, y]) => write!(f, "({x}, {y}) m"),
            InputValue::Length(h) => write!(f, "{h} m"),
            InputValue::Number(n) => write!(f, "{n}"),
            InputValue::Count(n) => write!(f, "{n}"),
            InputValue::Name(s) | InputValue::Text(s) => f.write_str(s),
        }
    }
}

impl InputValue {
    /// The value as a file's header line writes it: numbers separated by spaces, no unit, a name
    /// as one word of printable ASCII (anything else replaced by `_`); `None` for a text of
    /// several lines.
    pub fn bare(&self) -> Option<String> {
        Some(match self {
            InputValue::Point(p) => format!("{} {} {}", p.x, p.y, p.z),
            InputValue::Pair([x, y]) => format!("{x} {y}"),
            InputValue::Length(v) | InputValue::Number(v) => v.to_string(),
            InputValue::Count(n) => n.to_string(),
            InputValue::Name(s) => s
                .chars()
                .map(|c| if c.is_ascii_graphic() { c } else { '_' })
                .collect(),
            InputValue::Text(_) => return None,
        })
    }

    /// The value as a command line's argument: `x,y,z`, `x,y`, the number, the name (`None` for
    /// a text of several lines).
    pub fn argument(&self) -> Option<String> {
        Some(match self {
            InputValue::Point(p) => format!("{},{},{}", p.x, p.y, p.z),
            InputValue::Pair([x, y]) => format!("{x},{y}"),
            InputValue::Name(s) => s.clone(),
            other => return other.bare(),
        })
    }
}

impl Input {
    /// The input in a line of text (`straw (0.01, 0) m`, `water 0.1 m`, `n = 1.333`, `at most 10
    /// events`, a scene file by its name); `None` for the scene's whole text.
    pub fn phrase(&self) -> Option<String> {
        let v = &self.value;
        Some(match self.key {
            "water_height" => format!("water {v}"),
            "n_water" => format!("n = {v}"),
            "max_events" => format!("at most {v} events"),
            "scene_file" => v.to_string(),
            "scene" => return None,
            key => format!("{key} {v}"),
        })
    }

    /// The input in a figure's heading, beside the observer (`straw axis (0.01, 0) m`, `water
    /// height 0.1 m`, `n_water = 1.333`); `None` for what headings leave to the title (the
    /// observer, the event limit, the scene file).
    pub fn heading_phrase(&self) -> Option<String> {
        let v = &self.value;
        match self.key {
            "straw" => Some(format!("straw axis {v}")),
            "water_height" => Some(format!("water height {v}")),
            "n_water" => Some(format!("n_water = {v}")),
            _ => None,
        }
    }

    /// The command line's flag that gives this input (`--straw 0.01,0`), if one does; the event
    /// limit only when it is not the default.
    pub fn flag(&self) -> Option<[String; 2]> {
        let flag = match self.key {
            "observer" => "--observer",
            "straw" => "--straw",
            "water_height" => "--water-height",
            "n_water" => "--n-water",
            "scene_file" => "--scene",
            "max_events" if self.value != InputValue::Count(crate::scene::DEFAULT_MAX_EVENTS) => {
                "--max-events"
            }
            _ => return None,
        };
        Some([flag.to_string(), self.value.argument()?])
    }
}

/// The words for what figures and pages draw of a scene besides its points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SketchWords {
    /// The legend's entry of the wireframe.
    pub wireframe: &'static str,
    /// The legend's entry of the objects' outlines.
    pub outlines: &'static str,
    /// The wireframe's switch on a page.
    pub wireframe_switch: &'static str,
    /// The outlines' switch on a page.
    pub outlines_switch: &'static str,
}

impl Setup {
    /// The scene's inputs as files record them, in their documented order: the assignment's
    /// glass by its values (`observer`, `straw`, `water_height`, `n_water`, `max_events`), a
    /// scene file by its name and its whole text (`scene_file`, `scene`, `observer`,
    /// `max_events`).
    pub fn inputs(&self) -> Vec<Input> {
        let input = |key, value| Input { key, value };
        let observer = input("observer", InputValue::Point(self.observer));
        let events = input("max_events", InputValue::Count(self.world.max_events()));
        match self.assignment_numbers() {
            Some(s) => vec![
                observer,
                input("straw", InputValue::Pair([s.straw_x(), s.straw_y()])),
                input("water_height", InputValue::Length(s.water_height())),
                input("n_water", InputValue::Number(s.n_water())),
                events,
            ],
            None => {
                let mut inputs = vec![input(
                    "scene_file",
                    InputValue::Name(self.name().to_string()),
                )];
                // The scene's whole text, where the format's writer is built in.
                #[cfg(feature = "scene-file")]
                inputs.push(input("scene", InputValue::Text(self.description.to_toml())));
                inputs.extend([observer, events]);
                inputs
            }
        }
    }

    /// The input named `key`, if the scene records one.
    pub fn input(&self, key: &str) -> Option<InputValue> {
        self.inputs()
            .into_iter()
            .find(|i| i.key == key)
            .map(|i| i.value)
    }

    /// The inputs as one line of text, observer first: `observer (…) m, straw (…) m, water … m,
    /// n = …` for the assignment's glass, `name, observer (…) m` for a scene file; with the event
    /// limit when `events` is set.
    pub fn inputs_line(&self, events: bool) -> String {
        self.inputs()
            .iter()
            .filter(|i| events || i.key != "max_events")
            .filter_map(Input::phrase)
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The command line's flags that give this scene seen from its observer: `--observer …
    /// --straw … --water-height … --n-water …`, or `--scene NAME --observer …`; `--max-events`
    /// when it is not the default.
    pub fn flags(&self) -> Vec<String> {
        self.inputs()
            .iter()
            .filter_map(Input::flag)
            .flatten()
            .collect()
    }

    /// What the scene's image is of, when files name it: "the straw" for the assignment's glass;
    /// a scene file's objects go unnamed (texts say "the objects").
    pub fn subject(&self) -> Option<&'static str> {
        self.assignment_numbers().map(|_| "the straw")
    }

    /// What one colour code names, in a figure's legend: a "section" of the assignment's straw,
    /// a "colour" of a scene file's objects.
    pub fn code_word(&self) -> &'static str {
        match self.assignment_numbers() {
            Some(_) => "section",
            None => "colour",
        }
    }

    /// How a points file's legend calls a colour code: "section code" for the straw's
    /// sections, "code" for a scene file's colours.
    pub fn code_legend(&self) -> &'static str {
        match self.assignment_numbers() {
            Some(_) => "section code",
            None => "code",
        }
    }

    /// What figures and pages call [`Setup::wireframe`] and [`Setup::outlines`]: the water and
    /// the straw's outline, or a scene file's container and liquids and its objects' outlines.
    pub fn sketch_words(&self) -> SketchWords {
        match self.assignment_numbers() {
            Some(_) => SketchWords {
                wireframe: "water (wireframe)",
                outlines: "straw, true outline",
                wireframe_switch: "water",
                outlines_switch: "straw outline",
            },
            None => SketchWords {
                wireframe: "container and liquids (wireframe)",
                outlines: "objects, true outlines",
                wireframe_switch: "wireframe",
                outlines_switch: "outlines",
            },
        }
    }

    /// The heights (m) a colour code spans on the scene's straw, where the straw's sections are
    /// bands of fixed height (the assignment's upright straw standing on the floor).
    pub fn code_heights(&self, code: u8) -> Option<(f64, f64)> {
        self.assignment_numbers()?;
        let k = f64::from(code.checked_sub(1)?);
        (k < crate::scene::SECTION_COUNT as f64).then(|| {
            let h = crate::scene::SECTION_HEIGHT;
            (k * h, (k + 1.0) * h)
        })
    }

    /// Whether tables list a colour that no point shows: the straw's five sections always (a
    /// section out of sight is a finding), a scene file's colours only when seen (a card has no
    /// red).
    pub fn lists_unseen_colours(&self) -> bool {
        self.assignment_numbers().is_some()
    }

    /// The colour codes (from 1) in the order a points file counts them: by code for the straw's
    /// five sections; by name for a scene file's (a map of names, written in its keys' order).
    pub fn counted_codes(&self) -> Vec<u8> {
        let names = self.colour_names();
        let mut codes: Vec<u8> = (1..=names.len() as u8).collect();
        if !self.lists_unseen_colours() {
            codes.sort_by_key(|&c| names[c as usize - 1]);
        }
        codes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn the_assignment_is_recorded_by_its_values_and_flags_give_it_back() {
        let scene = Scene::new(0.01, -0.02, 0.12, 1.4, 7).unwrap();
        let setup = Setup::assignment(scene, Vec3::new(0.2, 0.0, 0.3));
        let keys: Vec<_> = setup.inputs().iter().map(|i| i.key).collect();
        assert_eq!(
            keys,
            ["observer", "straw", "water_height", "n_water", "max_events"]
        );
        assert_eq!(
            setup.inputs_line(true),
            "observer (0.2, 0, 0.3) m, straw (0.01, -0.02) m, water 0.12 m, n = 1.4, at most 7 events"
        );
        assert_eq!(
            setup.flags().join(" "),
            "--observer 0.2,0,0.3 --straw 0.01,-0.02 --water-height 0.12 --n-water 1.4 --max-events 7"
        );
        // The flags make the same scene again.
        let again = Setup::from_values(&crate::setup::SceneValues {
            observer: Some([0.2, 0.0, 0.3]),
            straw: Some([0.01, -0.02]),
            water_height: Some(0.12),
            n_water: Some(1.4),
            max_events: 7,
            wavelength: None,
        })
        .unwrap();
        assert_eq!(again.inputs(), setup.inputs());
        assert_eq!(setup.counted_codes(), [1, 2, 3, 4, 5]);
    }

    #[cfg(feature = "scene-file")]
    #[test]
    fn a_scene_file_is_recorded_by_its_name_and_text() {
        let text = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n\n[[liquid]]\nname = \"oil\"\nindex = 1.47\ntop = 0.08\n\n[[coin]]\nx = 0.0\ny = 0.0\n";
        let setup = Setup::from_text(
            "oily",
            text,
            &crate::setup::SceneValues {
                observer: Some([0.15, 0.0, 0.3]),
                ..Default::default()
            },
        )
        .unwrap();
        let keys: Vec<_> = setup.inputs().iter().map(|i| i.key).collect();
        assert_eq!(keys, ["scene_file", "scene", "observer", "max_events"]);
        assert_eq!(setup.inputs_line(false), "oily, observer (0.15, 0, 0.3) m");
        assert_eq!(
            setup.flags().join(" "),
            "--scene oily --observer 0.15,0,0.3"
        );
        let names = setup.colour_names();
        let counted: Vec<_> = setup
            .counted_codes()
            .iter()
            .map(|&c| names[c as usize - 1])
            .collect();
        let mut sorted = counted.clone();
        sorted.sort();
        assert_eq!(counted, sorted);
        assert!(matches!(setup.input("scene"), Some(InputValue::Text(t)) if t.contains("oil")));
    }
}
