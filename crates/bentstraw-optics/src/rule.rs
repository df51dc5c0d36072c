//! The rules a scene may break, each with a stable code and its English text, listed once here:
//! a refusal is data (the rule, the key, the value, the rule's numbers), and its English message
//! is the rule's text with those filled in. A page shows the same refusal in its own language
//! from the code and the parameters; the command line prints the English.

use crate::text::number_text;

/// One parameter of a broken rule: a number as the message writes it, or words quoted as they
/// are (another object's key, a name from the file, a parser's own message).
#[derive(Clone, Debug, PartialEq)]
pub enum Param {
    /// A number, written as the English message writes it (`0.04`, `1e-7`).
    Number(String),
    /// Words quoted as they are, never translated.
    Text(String),
}

impl Param {
    /// The parameter's text as the English message shows it.
    pub fn text(&self) -> &str {
        match self {
            Param::Number(t) | Param::Text(t) => t,
        }
    }
}

/// The named parameters of a broken rule, in the order its text names them.
pub type Params = Vec<(&'static str, Param)>;

/// `template` with each `{name}` replaced by the parameter of that name (`{name}` left as it is
/// when there is none), as the page's `t(key, params)` does.
pub fn fill(template: &str, params: &[(&str, &str)]) -> String {
    let mut out = String::with_capacity(template.len() + 16);
    let mut rest = template;
    while let Some(open) = rest.find('{') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let name_end = after
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(after.len());
        let name = &after[..name_end];
        match (
            after[name_end..].starts_with('}'),
            params.iter().find(|p| p.0 == name),
        ) {
            (true, Some((_, value))) if !name.is_empty() => {
                out.push_str(value);
                rest = &after[name_end + 1..];
            }
            _ => {
                out.push('{');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

macro_rules! rules {
    ($($(#[doc = $doc:literal])+ $name:ident = $code:literal, $text:literal;)+) => {
        /// A rule of scenes and scene files, by its stable code ([`Rule::code`]).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Rule {
            $($(#[doc = $doc])+ $name,)+
        }

        impl Rule {
            /// Every rule, each once.
            pub const ALL: &'static [Rule] = &[$(Rule::$name),+];

            /// Its stable code, which a page looks its text up by (`size.range`).
            pub fn code(self) -> &'static str {
                match self {
                    $(Rule::$name => $code,)+
                }
            }

            /// Its English text, `{name}` where a parameter goes.
            pub fn template(self) -> &'static str {
                match self {
                    $(Rule::$name => $text,)+
                }
            }
        }
    };
}

rules! {
    /// A number is NaN or infinite.
    Finite = "finite", "it must be a finite number";
    /// A length or coordinate is too large.
    LengthMax = "length.max", "a length or position must be at most {max} in size (metres)";
    /// A size is outside its range.
    SizeRange = "size.range", "a size must be between {min} and {max} (metres)";
    /// A size is 0 or negative.
    SizePositive = "size.positive", "a size must be > 0 (metres)";
    /// A thickness is negative.
    ThicknessPositive = "thickness.positive", "a thickness must be >= 0 (metres)";
    /// A thickness is neither 0 nor in the range of sizes.
    ThicknessRange = "thickness.range", "a thickness must be 0, or between {min} and {max} (metres)";
    /// A glass's wall leaves no room inside.
    WallThinner = "wall.thinner", "the wall must be thinner than the glass's radius {radius} (something must fit inside)";
    /// A glass's bottom is as thick as the glass is high.
    BottomThinner = "bottom.thinner", "the bottom must be thinner than the glass's height {height}";
    /// A refractive index is outside the physical range.
    IndexRange = "index.range", "a refractive index must be between 1 and 5 (vacuum is 1; the most refractive materials known are about 4)";
    /// More than one of `index`, `cauchy`, `sellmeier` and `material` for one medium.
    IndexChoice = "index.choice", "give one of index, cauchy, sellmeier or material, not {keys}";
    /// Cauchy's law with the wrong count of coefficients.
    CauchyCount = "cauchy.count", "Cauchy's law takes [A, B] or [A, B, C] (n = A + B/λ² + C/λ⁴, λ in µm), not {count} numbers";
    /// Sellmeier's law with the wrong count of coefficients.
    SellmeierCount = "sellmeier.count", "Sellmeier's law takes pairs [B1, C1, B2, C2, …] (n² = 1 + Σ B·λ²/(λ² − C), λ in µm, C in µm²), 1 to {max} of them, not {count} numbers";
    /// A law of dispersion gives no physical index somewhere in the visible.
    DispersionRange = "dispersion.range", "the law gives n = {index} at {wavelength} nm: from 380 to 780 nm a refractive index must be between 1 and 5";
    /// A material's name is not in the table.
    MaterialUnknown = "material.unknown", "\"{material}\" is not a named material: they are {materials}";
    /// A material's name is a slip for one in the table.
    MaterialNear = "material.near", "\"{material}\" is not a named material: did you mean {nearest}? They are {materials}";
    /// The first liquid's top is not above the floor.
    LiquidAboveFloor = "liquid.above-floor", "the liquid's top must be above the floor at z = {floor}";
    /// A liquid's top is not above the layer below it.
    LiquidAboveLayer = "liquid.above-layer", "each liquid's top must be above the top of the layer below it ({below})";
    /// A liquid's top is above the walls.
    LiquidBelowRim = "liquid.below-rim", "the liquid's top must not be above the walls' height {height}";
    /// Too many liquid layers.
    TooManyLiquids = "liquid.too-many", "the file lists {count} layers: at most {max} are allowed, as every ray is tested against each";
    /// Too many objects.
    TooManyObjects = "objects.too-many", "the file lists {count} objects: at most {max} straws, coins and cards together are allowed, as every ray is tested against each";
    /// A straw's tilt is outside `[0, 90)`.
    TiltRange = "tilt.range", "the tilt from the vertical must satisfy 0 <= tilt < 90 (degrees)";
    /// A straw's tilt is too small to lean it.
    TiltTiny = "tilt.tiny", "a tilt below {min}° leans the straw by less than a nanometre: write tilt = 0 for an upright straw";
    /// A straw's foot is not on the floor inside the walls.
    StrawFoot = "straw.foot", "its foot, where its bottom rim rests, at ({x}, {y}) is not on the floor inside the walls";
    /// A straw goes through the container's wall.
    StrawPierces = "straw.pierces", "standing at ({x}, {y}) with radius {radius} and tilt {tilt}°, it pierces the container's wall below the rim";
    /// A coin is not on the floor inside the walls.
    CoinOutside = "coin.outside", "at ({x}, {y}) with radius {radius} it does not lie on the floor inside the walls";
    /// A coin is thicker than the walls are high.
    CoinBelowRim = "coin.below-rim", "the coin must not stand higher than the walls";
    /// A card goes through the container.
    CardCuts = "card.cuts", "centred at ({x}, {y}, {z}), {width} wide and {height} high, it cuts through the container";
    /// Two objects share floor.
    FloorOverlap = "floor.overlap", "it overlaps {other} on the floor: their centres are {gap} apart, less than their radii's sum {sum}";
    /// A leaning straw lies on a coin.
    CoinLeanedOn = "coin.leaned-on", "{other} leans on it: within the coin's thickness the straw comes {gap} from the coin's centre, less than its radius {radius}";
    /// Two straws cross.
    StrawsCross = "straws.cross", "it crosses {other}: their axes pass {gap} apart, less than their radii's sum {sum}";
    /// The eye is inside or on the container.
    EyeInContainer = "observer.in-container", "({x}, {y}, {z}) is inside or on the container: the eye must be outside it";
    /// The eye is inside a straw.
    EyeInStraw = "observer.in-straw", "({x}, {y}, {z}) is inside {other}";
    /// The eye is on a card.
    EyeOnCard = "observer.on-card", "({x}, {y}, {z}) is on {other}: the eye must be off it";
    /// A sphere cuts the container's walls or floor.
    SphereContainer = "sphere.container", "centred at ({x}, {y}, {z}) with radius {radius}, it cuts the container: a sphere stands inside it, above the floor (through any liquid's surface), or wholly outside it";
    /// A prism's corners make no convex polygon.
    PrismConvex = "prism.convex", "the corners must make a convex polygon of 3 to {max} corners seen from above, in either order round it (it has {count})";
    /// A prism's top is not above its bottom.
    PrismTop = "prism.top", "the top must be above the bottom ({bottom})";
    /// A prism cuts the container's walls or floor.
    PrismContainer = "prism.container", "it cuts the container: a prism stands inside it, above the floor (through any liquid's surface), or wholly outside it";
    /// The direction towards the sun is zero.
    SunDirection = "sun.direction", "the direction towards the sun must be a direction: not (0, 0, 0)";
    /// A lens's axis is zero.
    LensAxis = "lens.axis", "the axis must be a direction: not (0, 0, 0)";
    /// A lens's face is more curved than its diameter allows.
    LensRadius = "lens.radius", "a curved face's radius must be at least half the diameter ({half}) in size, or 0 for a flat face";
    /// A lens's faces cross inside its diameter.
    LensFaces = "lens.faces", "its faces cross inside its diameter: {rho} from the axis they are {gap} apart (make it thicker or its faces less curved)";
    /// A lens cuts the container or a liquid's surface.
    LensPlace = "lens.place", "centred at ({x}, {y}, {z}), within {radius} of its centre, it cuts the container: a lens stands inside the container above the floor (through any liquid's surface), or wholly outside it";
    /// A transparent solid overlaps another object.
    SolidOverlap = "solid.overlap", "it overlaps {other}: they come {gap} close, less than {sum}; a transparent solid must stand clear of every other object";
    /// A card cuts a solid's surface.
    SolidCard = "solid.card", "{other} cuts its surface: a card stands wholly inside a transparent solid or wholly outside it";
    /// The eye is inside or on a transparent solid.
    EyeInSolid = "observer.in-solid", "({x}, {y}, {z}) is inside or on {other}: the eye must be outside every transparent solid";
    /// The eye looks at itself.
    TargetAtEye = "observer.target-at-eye", "({x}, {y}, {z}) is the observer's own position: it must look somewhere else";
    /// A lesson's texts are empty or too long for the page.
    LessonLength = "lesson.length", "a lesson's title must have 1 to {title} characters, its text at most {text}, and it asks at most {questions} questions of at most {question} characters each";
    /// A liquid's tint is not a colour.
    TintFormat = "liquid.tint", "{tint} is no colour: a tint is written \"#RRGGBB\" (three hexadecimal pairs), the colour white light takes through 10 cm of the liquid";
    /// A required key is missing.
    Required = "required", "is missing: it is required";
    /// The file has no `[container]`.
    ContainerMissing = "container.missing", "is missing: a scene needs its [container]";
    /// A glass lacks its radius.
    GlassNeeds = "container.glass-needs", "is missing: a glass needs it";
    /// A tank lacks a half width.
    TankNeeds = "container.tank-needs", "is missing: a tank needs it";
    /// A glass is given a tank's half widths.
    GlassNoHalfWidths = "container.glass-half-widths", "a glass has no half widths (they are a tank's): give its radius";
    /// A tank is given a radius.
    TankNoRadius = "container.tank-radius", "a tank has no radius (a glass has): give its half widths half_x and half_y";
    /// A tank is given a wall or bottom thickness.
    TankThin = "container.tank-thin", "a tank's walls and bottom have zero thickness (only a glass's may be thick)";
    /// A tank is given an index.
    TankIndex = "container.tank-index", "a tank's walls have zero thickness, so it has no index of its own";
    /// A container of revolution lacks a profile.
    RevolutionNeeds = "container.revolution-needs", "is missing: a container of revolution needs it (its outer and inner profiles, [[r, z], …])";
    /// A container of revolution is given a glass's or a tank's sizes.
    RevolutionKeys = "container.revolution-keys", "a container of revolution is given by its profiles outer and inner, not by a radius, half widths, a height, a wall or a bottom";
    /// A glass or a tank is given profiles.
    ProfilesOnly = "container.profiles", "only a container of revolution (shape = \"revolution\") has profiles";
    /// A profile has too few or too many points.
    ProfilePoints = "profile.points", "a profile needs 2 to {max} points [r, z] (it has {count})";
    /// A profile's heights do not rise.
    ProfileRise = "profile.rise", "z must rise from point to point: point {k} is at z = {z}, not above the point before ({below})";
    /// A profile's point lies on or across the axis.
    ProfileRadius = "profile.radius", "point {k}'s radius {r} must be positive (only the inner profile's first point may lie on the axis: a round bottom)";
    /// The outer profile does not start at the base.
    ProfileBase = "profile.base", "the outer profile starts at the base: its first point's z must be 0 (it is {z})";
    /// The inner profile starts below the base.
    ProfileFloor = "profile.floor", "the inner profile starts at the floor, on or above the base: its first point's z must be at least 0 (it is {z})";
    /// The profiles end at different heights.
    ProfileRim = "profile.rim", "the inner profile ends at the rim: its last point's z must be the outer profile's last, {height} (it is {z})";
    /// The inner profile leaves the outer one.
    ProfileInside = "profile.inside", "the inner profile leaves the outer one near z = {z} (radii {inner} and {outer}): the wall must have a thickness below the rim";
    /// The container's shape is not a known one.
    ShapeUnknown = "shape.unknown", "\"{shape}\" is not a shape: it must be \"glass\", \"tank\" or \"revolution\"";
    /// The container's shape is missing.
    ShapeMissing = "shape.missing", "is missing: it must be \"glass\", \"tank\" or \"revolution\"";
    /// A card's picture is not a known one.
    PictureUnknown = "picture.unknown", "\"{picture}\" is not a picture: it must be \"arrow\" or \"none\"";
    /// The text is not TOML of the format (the parser's own words).
    Syntax = "toml.syntax", "{what}";
    /// One of the assignment's numbers is NaN or infinite.
    GlassNotFinite = "glass.finite", "{name} = {value} is not a finite number";
    /// The assignment's water is higher than its glass.
    GlassWaterHeight = "glass.water-height", "water height {value} m is outside the glass: it must satisfy 0 <= he <= {max}";
    /// The assignment's straw does not fit in its glass.
    GlassStrawOutside = "glass.straw-outside", "straw axis ({x}, {y}) does not fit in the glass: need sqrt(xp² + yp²) + {radius} <= {glass} (it is {reach})";
    /// The eye is inside or on the assignment's glass.
    GlassEyeInside = "glass.eye-inside", "observer ({x}, {y}, {z}) is inside or on the glass: it must not satisfy 0 <= z <= {height} and x² + y² <= {radius}²";
    /// The eye is inside the assignment's straw above the glass.
    GlassEyeInStraw = "glass.eye-in-straw", "observer ({x}, {y}, {z}) is inside the straw where it sticks out of the glass";
    /// The eye is farther than any scene reaches.
    GlassEyeFar = "glass.eye-far", "{name} = {value} m is too far: a position must be at most {max} m in size";
    /// The assignment's water index is outside the physical range.
    GlassWaterIndex = "glass.water-index", "water index {value} is not allowed: it must be a number between 1 and 5";
    /// The wavelength asked is not visible light.
    Wavelength = "wavelength.range", "wavelength {value} nm is not allowed: visible light is from {min} to {max} nm";
    /// The event limit is out of range.
    MaxEvents = "glass.max-events", "event limit {value} is not allowed: it must be between 1 and {max}";
}

impl Rule {
    /// Its text with `params` filled in.
    pub fn text(self, params: &[(&'static str, Param)]) -> String {
        let named: Vec<(&str, &str)> = params.iter().map(|(k, v)| (*k, v.text())).collect();
        fill(self.template(), &named)
    }
}

/// The English line of the rule `rule` broken by `key` (empty: a rule of no one key) of value
/// `value`: `key = value: text`, `key: text`, or the text alone for a rule of no one key.
pub fn line(
    rule: Rule,
    key: &str,
    value: Option<&str>,
    params: &[(&'static str, Param)],
) -> String {
    let text = rule.text(params);
    match value {
        _ if key.is_empty() => text,
        Some(v) => format!("{key} = {v}: {text}"),
        None => format!("{key}: {text}"),
    }
}

/// A number parameter as messages write it ([`number_text`]).
pub fn number(x: f64) -> Param {
    Param::Number(number_text(x))
}

/// A point's coordinates as the parameters `x`, `y`, `z` of a message.
pub fn point(p: crate::Vec3) -> Params {
    vec![("x", number(p.x)), ("y", number(p.y)), ("z", number(p.z))]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_templates_fill() {
        let mut codes: Vec<&str> = Rule::ALL.iter().map(|r| r.code()).collect();
        codes.sort_unstable();
        let n = codes.len();
        codes.dedup();
        assert_eq!(codes.len(), n, "two rules share a code");
        assert_eq!(fill("a {x} b {y}", &[("x", "1"), ("y", "2")]), "a 1 b 2");
        assert_eq!(fill("{missing} {x", &[("x", "1")]), "{missing} {x");
        assert_eq!(
            fill("x² + y² <= {r}²", &[("r", "0.04")]),
            "x² + y² <= 0.04²"
        );
    }
}
