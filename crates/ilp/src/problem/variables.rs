//! The free variables of `<conditions meshSize>` (thesis §4.4, appendix D): placements
//! on rectangles, a sun's direction, a hole's size, an object's turn, a lamp's aim and
//! dimming, a material's colour; `<sunTime>` is read in `sun_time.rs`.

use super::{
    Anchor, ArraySpec, LightGroup, Node, PlacementSpec, Problem, Reader, VariableKind, VariableSpec,
};
use invlight_scene::daylight::SunSchedule;
use invlight_scene::{Diagnostic, Scene};

const VARIABLES: &[&str] = &[
    "objectInSurface",
    "lightInSurface",
    "holeInSurface",
    "holeSize",
    "objectRotation",
    "directionalLight",
    "lightAim",
    "color",
    "lightPower",
    "sunTime",
    "lightArray",
];
const VERTEX_ATTRS: [&str; 4] = [
    "vertexAIndex",
    "vertexBIndex",
    "vertexCIndex",
    "vertexDIndex",
];

/// What `<conditions>` holds: the cells per dimension, the variables in file order
/// and the `<sunTime objective="mean">`, if any, with its line.
pub(super) struct Conditions {
    /// `meshSize` (default 20).
    pub cells_per_dimension: Vec<u32>,
    /// The free variables, in file order.
    pub variables: Vec<VariableSpec>,
    /// The sun's id, its instants and the element's line.
    pub sun_schedule: Option<(String, SunSchedule, u32)>,
    /// `<lightGroup>`s, in file order.
    pub groups: Vec<LightGroup>,
}

impl<'a, 'i> Reader<'a, 'i> {
    /// `<conditions>` under `root`, exactly once, with at least one variable.
    pub(super) fn conditions(&self, root: Node<'a, 'i>) -> Result<Conditions, Diagnostic> {
        let conditions = self.only(root, "conditions")?.ok_or_else(|| {
            self.error(
                root,
                "no <conditions>, expected one with the free variables",
            )
        })?;
        self.check_attributes(conditions, &["meshSize"]);
        let cells_per_dimension = match conditions.attribute("meshSize") {
            None => vec![20],
            Some(m) => parse_mesh(m).ok_or_else(|| {
                self.error(
                    conditions,
                    format!(
                        "meshSize is '{m}', expected cells per dimension: a positive integer or several joined by 'x' (\"20\", \"20x6\")"
                    ),
                )
            })?,
        };
        let mut variables = Vec::new();
        let mut sun_schedule = None;
        let mut groups = Vec::new();
        for v in self.elements(conditions) {
            if v.tag_name().name() == "lightGroup" {
                groups.push(self.light_group(v, &groups)?);
                continue;
            }
            if v.tag_name().name() == "sunTime" && v.attribute("objective").is_some() {
                if sun_schedule.is_some() {
                    return Err(
                        self.error(v, "a second <sunTime objective=\"mean\">, expected one")
                    );
                }
                let id = self.required(v, "id")?.to_string();
                sun_schedule = Some((id, self.sun_schedule(v)?, self.line(v)));
                continue;
            }
            if let Some(spec) = self.variable(v)? {
                self.check_repeat(v, &variables, &spec)?;
                variables.push(spec);
            }
        }

        Ok(Conditions {
            cells_per_dimension,
            variables,
            sun_schedule,
            groups,
        })
    }

    /// Refuses `spec` (of element `v`) if a variable of `variables` already has its id,
    /// unless the two are parts of one thing. A light may be placed, dimmed and aimed:
    /// one lightInSurface, one lightPower and one lightAim of the same id; a hole placed
    /// and sized: one holeInSurface and one holeSize; any of them, or an
    /// objectInSurface, turned by one objectRotation (a luminaire's turn and its aim are
    /// one frame, so not with lightAim). Any other repeat is a mistake.
    fn check_repeat(
        &self,
        v: Node,
        variables: &[VariableSpec],
        spec: &VariableSpec,
    ) -> Result<(), Diagnostic> {
        let turned = |w: &VariableSpec| matches!(w.kind, VariableKind::ObjectRotation { .. });
        let aimed = |w: &VariableSpec| matches!(w.kind, VariableKind::LightAim { .. });
        let light_part = |w: &VariableSpec| match w.kind {
            VariableKind::LightInSurface(_) | VariableKind::LightArray(_) => Some((0, 0)),
            VariableKind::LightPower { .. } => Some((0, 1)),
            VariableKind::LightAim { .. } => Some((0, 2)),
            VariableKind::HoleInSurface(_) => Some((1, 0)),
            VariableKind::HoleSize { .. } => Some((1, 1)),
            _ => None,
        };
        let group = |w: &VariableSpec| light_part(w).map(|(g, _)| g);
        let allowed = variables
            .iter()
            .filter(|w: &&VariableSpec| w.id == spec.id)
            .all(|w| {
                let (a, b) = (w, &spec);
                if turned(a) || turned(b) {
                    let other = if turned(a) { b } else { a };
                    !turned(other) && !aimed(other)
                } else {
                    light_part(a).is_some()
                        && group(a) == group(b)
                        && light_part(a) != light_part(b)
                }
            });
        if !allowed {
            return Err(self.error(
                v,
                format!(
                    "a second variable with id '{}', expected distinct ids",
                    spec.id
                ),
            ));
        }
        Ok(())
    }

    fn vertices(&self, v: Node) -> Result<[usize; 4], Diagnostic> {
        let mut out = [0, 1, 2, 3];
        for (k, attr) in VERTEX_ATTRS.iter().enumerate() {
            if let Some(i) = self.number(v, attr, "a vertex index (0, 1, 2, …)")? {
                out[k] = i;
            }
        }
        Ok(out)
    }

    fn variable(&self, v: Node) -> Result<Option<VariableSpec>, Diagnostic> {
        let name = v.tag_name().name();
        let kind = match name {
            "objectInSurface" | "lightInSurface" | "holeInSurface" => self.placement(v, name)?,
            "directionalLight" => {
                self.check_attributes(v, &["id"]);
                VariableKind::DirectionalLight
            }
            "holeSize" => self.hole_size(v)?,
            "sunTime" => self.sun_time(v)?,
            "objectRotation" => self.object_rotation(v)?,
            "lightAim" => self.light_aim(v)?,
            "color" => self.colour(v)?,
            "lightPower" => self.light_power(v)?,
            "lightArray" => self.light_array(v)?,
            _ => {
                self.push_warning(self.unknown_element(v, "variable", VARIABLES, ""));
                return Ok(None);
            }
        };
        Ok(Some(VariableSpec {
            id: self.required(v, "id")?,
            kind,
            line: self.line(v),
        }))
    }

    /// `<objectInSurface|lightInSurface|holeInSurface id surface anchor vertex…Index>`.
    fn placement(&self, v: Node, name: &str) -> Result<VariableKind, Diagnostic> {
        let mut known = vec!["id", "surface", "anchor"];
        known.extend(VERTEX_ATTRS);
        self.check_attributes(v, &known);
        let anchor = match v.attribute("anchor").map(str::trim) {
            None | Some("vertexA") => Anchor::VertexA,
            Some("centre" | "center") => Anchor::Centre,
            Some(other) => {
                return Err(self.error(
                    v,
                    format!("'anchor' of <{name}> is '{other}', expected vertexA (P is where vertex A goes, ILPSolver's rule) or centre (P is where the object's own centre or the light goes)"),
                ));
            }
        };
        let spec = PlacementSpec {
            surface: self.required(v, "surface")?,
            vertices: self.vertices(v)?,
            anchor,
        };
        Ok(match name {
            "objectInSurface" => VariableKind::ObjectInSurface(spec),
            "lightInSurface" => VariableKind::LightInSurface(spec),
            _ => VariableKind::HoleInSurface(spec),
        })
    }

    /// `<lightArray id lights surface columns rows orientation continuous
    /// vertex…Index>`: `lights` the lamps' names (white space between; "Lamp1 … Lamp6"
    /// names the numbered lamps between), `columns` and `rows` a count ("3") or a range
    /// ("2..4"), `orientation` 0, 90 or search, `continuous` true or false. The least
    /// array must fit
    /// the lamps named; a larger columns × rows than there are lamps is refused by the
    /// search, not here, so that "2..4" × "2..6" over six lamps means every array of
    /// six or fewer.
    fn light_array(&self, v: Node) -> Result<VariableKind, Diagnostic> {
        let mut known = vec![
            "id",
            "lights",
            "surface",
            "columns",
            "rows",
            "orientation",
            "continuous",
        ];
        known.extend(VERTEX_ATTRS);
        self.check_attributes(v, &known);
        let id = self.required(v, "id")?;
        let lights = self.lamp_names(v, "lights", &format!("<lightArray id=\"{id}\">"))?;
        let range = |attr: &str| -> Result<(u32, u32), Diagnostic> {
            let text = self.required(v, attr)?;
            parse_count_range(&text).ok_or_else(|| {
                self.error(
                    v,
                    format!("'{attr}' of <lightArray> is '{text}', expected a count of lamps (\"3\") or a range (\"2..4\"), each at least 1"),
                )
            })
        };
        let (columns, rows) = (range("columns")?, range("rows")?);
        let least = columns.0 * rows.0;
        if least as usize > lights.len() {
            return Err(self
                .error(
                    v,
                    format!(
                        "<lightArray id=\"{id}\"> needs at least {} × {} = {least} lamps and names {}",
                        columns.0,
                        rows.0,
                        lights.len()
                    ),
                )
                .with_hint("name more lamps in 'lights', or lower the least 'columns' or 'rows'"));
        }
        let orientation = match v.attribute("orientation").map(str::trim) {
            None | Some("0") => Some(0.0),
            Some("90") => Some(90.0),
            Some("search") => None,
            Some(o) => {
                return Err(self
                    .error(
                        v,
                        format!("'orientation' of <lightArray> is '{o}', expected 0, 90 (degrees every lamp is turned about its aim) or search"),
                    )
                    .with_hint("search lets the search choose between 0 and 90 with the layout"));
            }
        };
        let continuous = match v.attribute("continuous").map(str::trim) {
            None | Some("false") => false,
            Some("true") => true,
            Some(c) => {
                return Err(self
                    .error(
                        v,
                        format!("'continuous' of <lightArray> is '{c}', expected true (the fittings of each row end to end) or false"),
                    )
                    .with_hint("continuous=\"true\" lays linear fittings end to end in rows, as trunking; leave it out for spaced fittings"));
            }
        };
        Ok(VariableKind::LightArray(ArraySpec {
            lights,
            surface: self.required(v, "surface")?,
            vertices: self.vertices(v)?,
            columns,
            rows,
            orientation,
            continuous,
        }))
    }

    /// `<holeSize id minScale maxScale>`.
    fn hole_size(&self, v: Node) -> Result<VariableKind, Diagnostic> {
        self.check_attributes(v, &["id", "minScale", "maxScale"]);
        let what = "a positive scale of the hole (1 is its authored size)";
        let scale = |attr: &str, default: f64| -> Result<f64, Diagnostic> {
            match self.real(v, attr, what)? {
                Some(x) if x <= 0.0 => {
                    Err(self.error(v, format!("'{attr}' of <holeSize> is {x}, expected {what}")))
                }
                x => Ok(x.unwrap_or(default)),
            }
        };
        let (min, max) = (scale("minScale", 0.5)?, scale("maxScale", 2.0)?);
        if min >= max {
            return Err(self.error(
                v,
                format!(
                    "<holeSize> has minScale {min} ≥ maxScale {max}, expected minScale < maxScale"
                ),
            ));
        }
        Ok(VariableKind::HoleSize { min, max })
    }

    /// `<objectRotation id min max>`, degrees.
    fn object_rotation(&self, v: Node) -> Result<VariableKind, Diagnostic> {
        self.check_attributes(v, &["id", "min", "max"]);
        let what = "an angle in degrees";
        let min = self.real(v, "min", what)?.unwrap_or(0.0);
        let max = self.real(v, "max", what)?.unwrap_or(360.0);
        if !(min < max && max - min <= 360.0) {
            return Err(self.error(
                v,
                format!("<objectRotation> has min {min}° and max {max}°, expected min < max ≤ min + 360°"),
            ));
        }
        Ok(VariableKind::ObjectRotation { min, max })
    }

    /// `<lightAim id maxTilt>`, degrees.
    fn light_aim(&self, v: Node) -> Result<VariableKind, Diagnostic> {
        self.check_attributes(v, &["id", "maxTilt"]);
        let what = "the largest tilt from the authored aim, degrees in (0, 90]";
        match self.real(v, "maxTilt", what)? {
            Some(t) if t > 0.0 && t <= 90.0 => Ok(VariableKind::LightAim { max_tilt: t }),
            Some(t) => Err(self.error(
                v,
                format!("'maxTilt' of <lightAim> is {t}, expected {what}"),
            )),
            None => Err(self.error(v, format!("<lightAim> needs 'maxTilt', {what}"))),
        }
    }

    /// `<color id hue saturation min max>`.
    fn colour(&self, v: Node) -> Result<VariableKind, Diagnostic> {
        self.check_attributes(v, &["id", "hue", "saturation", "min", "max"]);
        let need = |attr: &str, lo: f64, hi: f64| -> Result<f64, Diagnostic> {
            self.unit(v, attr, lo, hi)?.ok_or_else(|| {
                self.error(
                    v,
                    format!("<color> needs '{attr}', a number in [{lo}, {hi}]"),
                )
            })
        };
        let hue = need("hue", 0.0, 360.0)?;
        let saturation = need("saturation", 0.0, 1.0)?;
        let min = self.unit(v, "min", 0.0, 1.0)?.unwrap_or(0.0);
        let max = self.unit(v, "max", 0.0, 1.0)?.unwrap_or(1.0);
        if min >= max {
            return Err(self.error(
                v,
                format!("<color> has min {min} ≥ max {max}, expected min < max"),
            ));
        }
        Ok(VariableKind::Color {
            hue,
            saturation,
            min,
            max,
        })
    }

    /// `<lightPower id min max>`.
    fn light_power(&self, v: Node) -> Result<VariableKind, Diagnostic> {
        self.check_attributes(v, &["id", "min", "max"]);
        let level = |attr: &str, default: f64| -> Result<f64, Diagnostic> {
            match self.real(v, attr, "a level (1 is the authored output)")? {
                Some(x) if x < 0.0 => Err(self.error(
                    v,
                    format!("'{attr}' of <lightPower> is {x}, expected a level ≥ 0 (1 is the authored output)"),
                )),
                x => Ok(x.unwrap_or(default)),
            }
        };
        let (min, max) = (level("min", 0.0)?, level("max", 1.0)?);
        if min > max {
            return Err(self
                .error(
                    v,
                    format!("<lightPower> has min {min} > max {max}, expected min ≤ max"),
                )
                .with_hint("equal min and max fix the level: min=\"0.8\" max=\"0.8\""));
        }
        Ok(VariableKind::LightPower { min, max })
    }
}

/// `"3"` → (3, 3); `"2..4"` → (2, 4); counts of at least 1, the first not above the
/// second.
pub(super) fn parse_count_range(s: &str) -> Option<(u32, u32)> {
    let count = |p: &str| p.trim().parse::<u32>().ok().filter(|&n| n >= 1);
    let (lo, hi) = match s.split_once("..") {
        Some((a, b)) => (count(a)?, count(b)?),
        None => (count(s)?, count(s)?),
    };
    (lo <= hi).then_some((lo, hi))
}

/// `"20"` → [20]; `"20x6"` → [20, 6].
pub(super) fn parse_mesh(s: &str) -> Option<Vec<u32>> {
    let v: Option<Vec<u32>> = s
        .trim()
        .split(['x', 'X'])
        .map(|p| p.trim().parse().ok().filter(|&n| n > 0))
        .collect();
    v.filter(|v| !v.is_empty())
}

impl Problem {
    /// Turns every lamp of each `<lightArray orientation="90">` a quarter turn about its
    /// aim on `scene` as loaded (a name the scene lacks is the binder's to refuse).
    pub(super) fn turn_arrays(&self, scene: &mut Scene) {
        for spec in &self.variables {
            let VariableKind::LightArray(a) = &spec.kind else {
                continue;
            };
            // A searched orientation is the binding's to set, configuration by
            // configuration, from the frames as loaded.
            let Some(turn) = a.orientation.filter(|&t| t != 0.0) else {
                continue;
            };
            for name in &a.lights {
                if let Some(l) = scene.light(name) {
                    scene.lights[l].kind.turn_about_aim(turn);
                }
            }
        }
    }

    /// Degrees the light `name` is turned about its aim as the scene is loaded: its
    /// `<luminaire rotation>` and its array's fixed `orientation`; `None` when not
    /// turned. A folder of rows traced one way is not resumed another
    /// (`RunFile::check_resume`).
    pub fn turn_as_installed(&self, name: &str) -> Option<f64> {
        let rotation = self
            .scene
            .luminaires
            .iter()
            .rev()
            .find(|u| u.light == name)
            .map_or(0.0, |u| u.rotation);
        let array = self
            .variables
            .iter()
            .find_map(|v| match &v.kind {
                VariableKind::LightArray(a) if a.lights.iter().any(|l| l == name) => a.orientation,
                _ => None,
            })
            .unwrap_or(0.0);
        let turn = f64::from(rotation + array);
        (turn != 0.0).then_some(turn)
    }

    /// The light `name`'s `<luminaire size>` as [length, width], m.
    pub fn size_as_installed(&self, name: &str) -> Option<[f64; 2]> {
        self.scene
            .sizes
            .iter()
            .rev()
            .find(|s| s.light == name)
            .map(|s| [s.length, s.width])
    }
}
