//! The one scene value: what someone asked to look at. A scene as described (the assignment's
//! glass of water and its straw, or any scene file), the observer's eye and the point it looks
//! at, and the world built from them for tracing. Every front end (the command line, the
//! explorer, the page, Python) makes one here, from its values or from a scene file's text, and
//! every figure, picture, writer and check takes it.
//!
//! The assignment's glass is a description like any other; what sets it apart (its documented
//! output columns, its five colours, the way its figures frame and draw it) is chosen here from
//! the description, once, and asked of the setup by what it is for.

use std::fmt;

use crate::camera::{framing_fov, framing_fov_box};
use crate::dispersion::{is_visible, D_LINE_NM};
use crate::scene::{
    Scene, SceneError, GLASS_HEIGHT, GLASS_RADIUS, MAX_EVENTS_LIMIT, SCENE_CENTRE, SECTION_NAMES,
    STRAW_HEIGHT, STRAW_RADIUS, WATER_INDEX,
};
use crate::scene_file::{Observer, SceneDescription, SceneFileError};
use crate::sketch::{
    object_outlines, straw_outline, straw_schematic, straw_schematic_extent, water_segments,
    world_schematic, world_schematic_extent, world_wireframe, Mark, Panel, SceneLines,
};
use crate::world::{World, COLOR_NAMES};
use crate::Vec3;

/// Largest scene file read (1 MB): a scene is a few dozen lines.
pub const MAX_SCENE_FILE_BYTES: u64 = 1 << 20;

/// The scene's values as someone gives them (the command line's flags, the page's query,
/// Python's keywords): each optional but the event limit. With a scene file they override its
/// own values; without one, the observer, the straw and the water height are required.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneValues {
    /// The observer's eye (m).
    pub observer: Option<[f64; 3]>,
    /// The straw's axis `(xp, yp)` (m).
    pub straw: Option<[f64; 2]>,
    /// The water's height (m).
    pub water_height: Option<f64>,
    /// The water's refractive index.
    pub n_water: Option<f64>,
    /// Most events (refractions and total reflections) a ray may undergo.
    pub max_events: u32,
    /// The wavelength of the light traced (nm), where a medium's index depends on it; the d
    /// line ([`D_LINE_NM`]) when none is given.
    pub wavelength: Option<f64>,
}

impl Default for SceneValues {
    fn default() -> Self {
        SceneValues {
            observer: None,
            straw: None,
            water_height: None,
            n_water: None,
            max_events: crate::scene::DEFAULT_MAX_EVENTS,
            wavelength: None,
        }
    }
}

impl SceneValues {
    /// The wavelength to trace at (nm): the one given, checked to be visible light, or the d
    /// line.
    pub fn wavelength_nm(&self) -> Result<f64, SceneError> {
        match self.wavelength {
            None => Ok(D_LINE_NM),
            Some(nm) if is_visible(nm) => Ok(nm),
            Some(nm) => Err(SceneError::Wavelength(nm)),
        }
    }
}

/// Why a setup cannot be made, as one message for the user (every broken rule of a scene file as
/// data too).
#[derive(Clone, Debug, PartialEq)]
pub enum SetupError {
    /// The assignment's values break its rules.
    Scene(SceneError),
    /// The scene file `name` breaks the rules of scene files (`flagged`: once the values that
    /// override it were applied): `{name}: {error}`, every broken rule as data in `error`.
    SceneFile {
        /// The file's name as messages show it.
        name: String,
        /// Whether the rules were broken by the values given rather than the file's own.
        flagged: bool,
        /// Every broken rule.
        error: Box<SceneFileError>,
    },
    /// Anything else (a missing value, overrides a file cannot take): its message.
    Refused(String),
}

impl fmt::Display for SetupError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SetupError::Scene(e) => write!(f, "{e}"),
            SetupError::SceneFile {
                name,
                flagged: false,
                error,
            } => write!(f, "{name}: {error}"),
            SetupError::SceneFile {
                name,
                flagged: true,
                error,
            } => write!(f, "{name} with the flags given: {error}"),
            SetupError::Refused(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for SetupError {}

impl From<SceneError> for SetupError {
    fn from(e: SceneError) -> Self {
        SetupError::Scene(e)
    }
}

/// A scene ready to trace and draw, with its observer.
#[derive(Clone, Debug)]
pub struct Setup {
    /// The scene file's name as messages show it, when the scene is a file's of its own kind
    /// (not one of the assignment's glass, which is named by its values).
    pub name: Option<String>,
    /// The scene as described (the values given applied).
    pub description: SceneDescription,
    /// The scene ready for tracing.
    pub world: World,
    /// The validated observer.
    pub observer: Vec3,
    /// The point the scene file says to look at, if any.
    pub target: Option<Vec3>,
    /// The assignment's numbers, when the description is of its kind.
    assignment: Option<Scene>,
}

impl Setup {
    /// The assignment's scene seen from `observer` (both already validated).
    pub fn assignment(scene: Scene, observer: Vec3) -> Setup {
        Setup {
            name: None,
            description: SceneDescription::assignment(&scene),
            world: World::assignment(&scene),
            observer,
            target: None,
            assignment: Some(scene),
        }
    }

    /// The assignment's scene from `values` alone: the observer, the straw and the water height
    /// are required, the index defaults to water's; every value checked by the assignment's rules.
    pub fn from_values(values: &SceneValues) -> Result<Setup, SetupError> {
        let (Some(observer), Some(straw), Some(water_height)) =
            (values.observer, values.straw, values.water_height)
        else {
            return Err(SetupError::Refused(
                "the scene needs --observer, --straw and --water-height, or a --scene file"
                    .to_string(),
            ));
        };
        // The assignment's water has one index at every wavelength; the wavelength is still
        // checked, as everywhere.
        values.wavelength_nm()?;
        let scene = Scene::new(
            straw[0],
            straw[1],
            water_height,
            values.n_water.unwrap_or(WATER_INDEX),
            values.max_events,
        )?;
        let observer = Vec3::from_array(observer);
        scene.validate_observer(observer)?;
        Ok(Setup::assignment(scene, observer))
    }

    /// The scene file `name` whose text is `text`, read and checked by the scene file's rules,
    /// then `values` applied.
    #[cfg(feature = "scene-file")]
    pub fn from_text(name: &str, text: &str, values: &SceneValues) -> Result<Setup, SetupError> {
        Setup::from_description(name, parse_scene_text(name, text)?, values)
    }

    /// The scene file `name` read as `description`, `values` applied and checked: a description
    /// of the assignment's kind becomes the assignment's scene (checked by its rules, exactly as
    /// the same values alone give it); any other is checked again, observer included, by every
    /// rule of a scene file. Values may change a file's straw and liquid only when it has one of
    /// each.
    pub fn from_description(
        name: &str,
        description: SceneDescription,
        values: &SceneValues,
    ) -> Result<Setup, SetupError> {
        let mut description = description.at_wavelength(values.wavelength_nm()?);
        let overrides: Vec<&str> = [
            (values.straw.is_some(), "--straw"),
            (values.water_height.is_some(), "--water-height"),
            (values.n_water.is_some(), "--n-water"),
        ]
        .iter()
        .filter(|(given, _)| *given)
        .map(|(_, flag)| *flag)
        .collect();
        let (straws, liquids) = (description.straws.len(), description.liquids.len());
        if !overrides.is_empty() && (straws != 1 || liquids != 1) {
            return Err(SetupError::Refused(format!(
                "{} can change a scene file's values only when it has one straw and one liquid: {name} has {straws} straw(s) and {liquids} liquid(s)",
                overrides.join(", ")
            )));
        }
        let observer = match (values.observer, description.observer) {
            (Some(o), _) => o,
            (None, Some(o)) => o.position.to_array(),
            (None, None) => {
                return Err(SetupError::Refused(format!(
                    "{name} has no [observer]: give --observer X,Y,Z"
                )))
            }
        };
        if let Some(spec) = description.spec_scene() {
            let setup = Setup::from_values(&SceneValues {
                observer: Some(observer),
                straw: Some(values.straw.unwrap_or([spec.straw_x(), spec.straw_y()])),
                water_height: Some(values.water_height.unwrap_or(spec.water_height())),
                n_water: Some(values.n_water.unwrap_or(spec.n_water())),
                max_events: values.max_events,
                wavelength: values.wavelength,
            })?;
            return Ok(Setup {
                target: description.observer.map(|o| o.target),
                ..setup
            });
        }
        // Any other scene: the values change the file's one straw and liquid, and the whole
        // scene, observer included, is checked again by the file's rules.
        if let Some([x, y]) = values.straw {
            description.straws[0].x = x;
            description.straws[0].y = y;
        }
        if let Some(h) = values.water_height {
            description.liquids[0].top = h;
        }
        if let Some(n) = values.n_water {
            // One index at every wavelength, in place of the liquid's law.
            description.liquids[0].index = n;
            description
                .dispersion
                .retain(|d| d.medium != crate::scene_file::Medium::Liquid(0));
        }
        if values.max_events == 0 || values.max_events > MAX_EVENTS_LIMIT {
            return Err(SceneError::MaxEvents(values.max_events).into());
        }
        let target = description.observer.map(|o| o.target);
        let position = Vec3::from_array(observer);
        let mut checked = description.clone();
        checked.observer = Some(Observer {
            position,
            // Any point away from the eye: the target is the camera's business.
            target: target
                .filter(|t| *t != position)
                .unwrap_or(position + Vec3::Z),
        });
        // The world of the scene with the values applied, checked by every rule of a file.
        let world =
            World::new(&checked, values.max_events).map_err(|error| SetupError::SceneFile {
                name: name.to_string(),
                flagged: true,
                error,
            })?;
        Ok(Setup {
            name: Some(name.to_string()),
            description,
            world,
            observer: position,
            target,
            assignment: None,
        })
    }

    /// The scene file's name, or empty when the scene is the assignment's glass.
    pub fn name(&self) -> &str {
        self.name.as_deref().unwrap_or("")
    }

    /// The assignment's numbers, when the description is of its kind: what the scene's record
    /// ([`Setup::inputs`]) and sketches are chosen from, here and nowhere else.
    pub(crate) fn assignment_numbers(&self) -> Option<&Scene> {
        self.assignment.as_ref()
    }

    /// The names of the colour codes the scene can show, code 1 first: the straw's five
    /// sections for the assignment's glass, every object's code for a scene file.
    pub fn colour_names(&self) -> &'static [&'static str] {
        match self.assignment {
            Some(_) => &SECTION_NAMES,
            None => &COLOR_NAMES,
        }
    }

    /// The box that figures and cameras frame when told nothing else, and the point they centre
    /// on: the glass and the straw around the middle of their cylinder for the assignment's
    /// glass (the course's convention), the box holding every boundary and object around its
    /// middle for a scene file.
    pub fn frame(&self) -> (Vec3, Vec3, Vec3) {
        match &self.assignment {
            Some(scene) => {
                let lo = Vec3::new(-GLASS_RADIUS, -GLASS_RADIUS, 0.0);
                let hi = Vec3::new(GLASS_RADIUS, GLASS_RADIUS, GLASS_HEIGHT);
                let straw = Vec3::new(scene.straw_x(), scene.straw_y(), 0.0);
                (
                    lo.min(straw - Vec3::new(STRAW_RADIUS, STRAW_RADIUS, 0.0)),
                    hi.max(straw + Vec3::new(STRAW_RADIUS, STRAW_RADIUS, STRAW_HEIGHT)),
                    SCENE_CENTRE,
                )
            }
            None => {
                let (lo, hi) = self.world.bounds();
                (lo, hi, 0.5 * (lo + hi))
            }
        }
    }

    /// The scene's size (m): the glass's height for the assignment's glass, the largest side of
    /// the box holding everything for a scene file. Figures leave out image points farther than
    /// a few times this from the scene's centre.
    pub fn size(&self) -> f64 {
        match self.assignment {
            Some(_) => GLASS_HEIGHT,
            None => {
                let (lo, hi) = self.world.bounds();
                (hi - lo).max_element()
            }
        }
    }

    /// The point a camera looks at when told none: the scene file's target, else the centre of
    /// [`Setup::frame`].
    pub fn default_target(&self) -> Vec3 {
        self.target.unwrap_or_else(|| self.frame().2)
    }

    /// The vertical field of view (radians) that frames the scene for a camera at `eye` aimed at
    /// `target` with `aspect = width / height`: the cylinder holding the assignment's glass and
    /// its straw wherever it stands, or the box holding a scene file's everything.
    pub fn framing_fov(&self, eye: Vec3, target: Vec3, aspect: f64) -> f64 {
        match self.assignment {
            Some(_) => framing_fov(eye, target, aspect),
            None => framing_fov_box(eye, target, self.world.bounds(), aspect),
        }
    }

    /// The wireframe figures draw of the container and its liquids, and the point whose depth
    /// sorts its segments into the near and the far ones: the assignment's water (its top and
    /// bottom circles and vertical lines), or every boundary of a scene file's world.
    pub fn wireframe(&self) -> (Vec3, Vec<[Vec3; 2]>) {
        match &self.assignment {
            Some(scene) => (
                Vec3::new(0.0, 0.0, scene.water_height() / 2.0),
                water_segments(scene),
            ),
            None => {
                let (lo, hi) = self.world.bounds();
                (0.5 * (lo + hi), world_wireframe(&self.world))
            }
        }
    }

    /// The lines a 3D page draws of the scene besides its points, when it cannot draw the scene
    /// from its documented values: a scene file's boundaries' edges and objects' outlines. The
    /// assignment's glass has none here: a page draws its water and its straw from the values
    /// its data gives (the glass's radius, the water's height, the straw's axis).
    pub fn page_lines(&self) -> Option<SceneLines> {
        match self.assignment {
            Some(_) => None,
            None => Some(SceneLines {
                edges: world_wireframe(&self.world),
                outlines: object_outlines(&self.world),
            }),
        }
    }

    /// The schematic drawing of the scene in `panel`, back to front: the assignment's glass as
    /// its water, wall and banded straw; a scene file's world as its boundaries' edges and its
    /// objects' outlines.
    pub fn schematic(&self, panel: Panel) -> Vec<Mark> {
        match &self.assignment {
            Some(scene) => straw_schematic(scene, panel),
            None => world_schematic(&self.world, panel),
        }
    }

    /// The points a schematic's panels must hold, besides the rays.
    pub fn schematic_extent(&self) -> Vec<Vec3> {
        match &self.assignment {
            Some(scene) => straw_schematic_extent(scene),
            None => world_schematic_extent(&self.world),
        }
    }

    /// The objects' true outlines as polylines, for a view whose rightward direction is `right`
    /// (the assignment's straw shows its silhouette; a scene file's objects their edges).
    pub fn outlines(&self, right: Vec3) -> Vec<Vec<Vec3>> {
        match &self.assignment {
            Some(scene) => straw_outline(scene, right),
            None => object_outlines(&self.world),
        }
    }
}

/// The scene file named `name` whose text is `text`, read and checked by the scene file's rules
/// (at most [`MAX_SCENE_FILE_BYTES`]); every refusal names the file.
#[cfg(feature = "scene-file")]
pub fn parse_scene_text(name: &str, text: &str) -> Result<SceneDescription, SetupError> {
    if text.len() as u64 > MAX_SCENE_FILE_BYTES {
        return Err(SetupError::Refused(format!(
            "the scene file {name} is {} bytes: a scene file is at most {MAX_SCENE_FILE_BYTES} bytes (1 MB), not read",
            text.len()
        )));
    }
    SceneDescription::from_toml(text).map_err(|error| SetupError::SceneFile {
        name: name.to_string(),
        flagged: false,
        error,
    })
}
