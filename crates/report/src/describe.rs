//! A problem's variables and values in words, for captions, tables and the report:
//! positions in world metres, sun directions as elevation and compass azimuth, colour
//! values; and what moved between two configurations.

use glam::{DVec3, Vec3};
use invlight_ilp::{Binding, Domain, VariableKind, VariableSpec, VariableValue};
use invlight_scene::Scene;
use invlight_scene::daylight::{Compass, TimeOfDay};
use invlight_stats::significant;

/// A point as `(x, y, z)` with four significant digits.
pub fn point(p: DVec3) -> String {
    format!(
        "({}, {}, {})",
        significant(p.x),
        significant(p.y),
        significant(p.z)
    )
}

/// The compass of `scene` with its default north (−Z for Y-up, +Y for Z-up; see
/// `invlight_scene::daylight`), for sun directions of problems without a site.
pub fn compass(scene: &Scene) -> Option<Compass> {
    Compass::new(scene.up, 0.0).ok()
}

/// (elevation above the horizon, azimuth clockwise from north) in degrees of the sun
/// whose light travels along `travel`.
pub fn sun_angles(compass: &Compass, travel: DVec3) -> (f64, f64) {
    let from = -travel.as_vec3();
    let (zenith, azimuth) = compass.angles(Vec3::new(from.x, from.y, from.z));
    (90.0 - zenith, azimuth)
}

/// What a variable moves, as a noun: "Cone (its centre)", "light Lamp", "the sun".
pub fn subject(spec: &VariableSpec) -> String {
    match &spec.kind {
        VariableKind::ObjectInSurface(_) => format!("{} (its centre)", spec.id),
        VariableKind::LightInSurface(_) if spec.id.to_lowercase().contains("light") => {
            spec.id.clone()
        }
        VariableKind::LightInSurface(_) => format!("light {}", spec.id),
        VariableKind::HoleInSurface(_) => format!("hole {} (its centre)", spec.id),
        VariableKind::DirectionalLight if spec.id.eq_ignore_ascii_case("sun") => "the sun".into(),
        VariableKind::DirectionalLight => format!("the sun ({})", spec.id),
        VariableKind::Color { .. } => format!("the colour of {}", spec.id),
        VariableKind::LightPower { .. } => format!("the dimming of {}", spec.id),
        VariableKind::LightAim { .. } => format!("the aim of {}", spec.id),
        VariableKind::HoleSize { .. } => format!("the size of hole {}", spec.id),
        VariableKind::ObjectRotation { .. } => format!("the turn of {}", spec.id),
        VariableKind::LightArray(_) => format!("the array {}", spec.id),
        VariableKind::SunTime { date, .. } => {
            format!("the time of day of the sun {} on {date}", spec.id)
        }
    }
}

/// A variable's value in words.
pub fn value(value: &VariableValue, compass: Option<&Compass>) -> String {
    match *value {
        VariableValue::Position { anchor, .. } => format!("at {} m", point(anchor)),
        VariableValue::Direction(d) => match compass {
            Some(c) => {
                let (el, az) = sun_angles(c, d);
                format!("elevation {el:.1}°, azimuth {az:.1}° (from north, clockwise)")
            }
            None => format!("travelling along {}", point(d)),
        },
        VariableValue::Colour { value, .. } => format!("V = {}", significant(value)),
        VariableValue::Power(level) => format!("at {} %", significant(100.0 * level)),
        VariableValue::Scale(k) => format!("× {} of its authored size", significant(k)),
        VariableValue::Angle(a) => format!("turned {}°", significant(a)),
        VariableValue::Array(a) => format!(
            "{} rows of {}, the outer ones {} and {} of a spacing from the edges",
            a.rows,
            a.columns,
            significant(a.walls[0]),
            significant(a.walls[1])
        ),
        VariableValue::Time { minutes, direction } => {
            let at = TimeOfDay::from_minutes(minutes);
            match compass {
                Some(c) if direction != DVec3::ZERO => {
                    let (el, az) = sun_angles(c, direction);
                    format!("at {at} (sun elevation {el:.1}°, azimuth {az:.1}°)")
                }
                _ => format!("at {at}"),
            }
        }
    }
}

/// How far a variable moved from `from` to `to`, in words ("moved 9.2 m").
pub fn moved(from: &VariableValue, to: &VariableValue) -> String {
    match (*from, *to) {
        (VariableValue::Position { anchor: a, .. }, VariableValue::Position { anchor: b, .. }) => {
            let d = b - a;
            format!("moved {} m (Δ = {})", significant(d.length()), point(d))
        }
        (VariableValue::Direction(a), VariableValue::Direction(b)) => {
            let angle = a.dot(b).clamp(-1.0, 1.0).acos().to_degrees();
            format!("turned {angle:.1}°")
        }
        (VariableValue::Colour { value: a, .. }, VariableValue::Colour { value: b, .. }) => {
            format!("V changed by {}", significant(b - a))
        }
        (VariableValue::Power(a), VariableValue::Power(b)) => {
            let pct = |x: f64| format!("{} %", significant(100.0 * x));
            let how = if b <= a { "dimmed" } else { "brightened" };
            format!("{how} from {} to {}", pct(a), pct(b))
        }
        (VariableValue::Scale(a), VariableValue::Scale(b)) => {
            format!("scaled by {}", significant(b / a))
        }
        (VariableValue::Array(a), VariableValue::Array(b)) if a.lamps() != b.lamps() => {
            format!("{} lamps instead of {}", b.lamps(), a.lamps())
        }
        (VariableValue::Array(a), VariableValue::Array(b))
            if (a.rows, a.columns) != (b.rows, b.columns) =>
        {
            format!(
                "{} × {} instead of {} × {}",
                b.rows, b.columns, a.rows, a.columns
            )
        }
        (VariableValue::Array(a), VariableValue::Array(b)) => format!(
            "set out {} and {} of a spacing from the rectangle's edges instead of {} and {}",
            significant(b.walls[0]),
            significant(b.walls[1]),
            significant(a.walls[0]),
            significant(a.walls[1])
        ),
        (VariableValue::Angle(a), VariableValue::Angle(b)) => {
            format!("turned {}°", significant(b - a))
        }
        (VariableValue::Time { minutes: a, .. }, VariableValue::Time { minutes: b, .. }) => {
            let later = if b >= a { "later" } else { "earlier" };
            format!("{} min {later}", significant((b - a).abs()))
        }
        _ => String::new(),
    }
}

/// A variable's range in words: the placement rectangle's corners, the sun's
/// hemisphere, the colour's segment; and its cells.
pub fn range(binding: &Binding, i: usize) -> String {
    let v = &binding.space.variables()[i];
    let cells = binding.space.cells_per_dimension();
    let first: usize = (0..i)
        .map(|j| binding.space.variables()[j].domain.dimensions())
        .sum();
    match &v.domain {
        Domain::Parallelogram(r) => format!(
            "a {} m × {} m rectangle with corners {}, {}, {}, {} m, in {} × {} cells",
            significant(r.e1.length()),
            significant(r.e2.length()),
            point(r.a),
            point(r.a + r.e1),
            point(r.a + r.e1 + r.e2),
            point(r.a + r.e2),
            cells[first],
            cells[first + 1]
        ),
        Domain::Hemisphere(h) if matches!(binding.specs[i].kind, VariableKind::LightAim { .. }) => {
            format!(
                "any aim within {}° of the authored one, in {} × {} cells of azimuth and tilt",
                significant(h.max_zenith.to_degrees()),
                cells[first],
                cells[first + 1]
            )
        }
        Domain::Hemisphere(_) => format!(
            "any direction from above the horizon, in {} × {} cells of azimuth and zenith angle",
            cells[first],
            cells[first + 1]
        ),
        Domain::Array(a) => format!(
            "{} to {} columns and {} to {} rows of at most {} lamps on a {} m × {} m rectangle, the outer ones 0 to 1 spacing from its edges in tenths",
            a.columns.0,
            a.columns.1,
            a.rows.0,
            a.rows.1,
            a.lamps,
            significant(a.rect.e1.length()),
            significant(a.rect.e2.length())
        ),
        Domain::Segment { min, max } | Domain::Turn { min, max } => {
            let hs = match &binding.specs[i].kind {
                VariableKind::Color {
                    hue, saturation, ..
                } => format!(
                    " (hue {}°, saturation {})",
                    significant(*hue),
                    significant(*saturation)
                ),
                _ => String::new(),
            };
            match binding.specs[i].kind {
                VariableKind::LightPower { .. } => format!(
                    "levels from {} % to {} % of the authored output, in {} cells",
                    significant(100.0 * min),
                    significant(100.0 * max),
                    cells[first]
                ),
                VariableKind::ObjectRotation { .. } => format!(
                    "turns from {}° to {}° about its placement's normal, in {} cells",
                    significant(*min),
                    significant(*max),
                    cells[first]
                ),
                VariableKind::HoleSize { .. } => format!(
                    "scales from {} to {} of the authored size, in {} cells",
                    significant(*min),
                    significant(*max),
                    cells[first]
                ),
                VariableKind::SunTime {
                    date,
                    from,
                    to,
                    step,
                } => format!(
                    "the times of day from {} to {} on {date}, every {} min ({} cells)",
                    TimeOfDay::from_minutes(from),
                    TimeOfDay::from_minutes(to),
                    significant(step),
                    cells[first]
                ),
                _ => format!(
                    "V from {} to {}{hs}, in {} cells",
                    significant(*min),
                    significant(*max),
                    cells[first]
                ),
            }
        }
    }
}
