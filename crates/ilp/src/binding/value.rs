//! A variable's value in world terms (a point, a direction, a level, a time…): what
//! the outputs write, and the one way back from them to a configuration.

use super::{Binding, Target, hsv_to_rgb};
use crate::space::{ArrayShape, Configuration, Domain};
use glam::DVec3;
use std::fmt;

/// A variable's value in world terms, for the outputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VariableValue {
    /// A placement: the placement point P (where the rule of the variable's anchor puts
    /// it) and the anchor, the object's or light's own place.
    Position {
        /// P, m.
        point: DVec3,
        /// The light's position or the object's bounding-box centre on the placement
        /// plane, m.
        anchor: DVec3,
    },
    /// The unit vector the light travels along.
    Direction(DVec3),
    /// HSV value V and the resulting linear K_d.
    Colour {
        /// V.
        value: f64,
        /// K_d, linear RGB.
        rgb: [f64; 3],
    },
    /// A dimming level: the light's output is its authored output times it.
    Power(f64),
    /// A hole's scale: its size over its authored size.
    Scale(f64),
    /// A turn about the placement's normal, degrees.
    Angle(f64),
    /// A `sunTime`: minutes after local midnight, and the unit vector the sunlight
    /// travels along then (zero when it is not known, as in a row read back).
    Time {
        /// Minutes after local midnight.
        minutes: f64,
        /// The sunlight's travel direction.
        direction: DVec3,
    },
    /// A `<lightArray>`: its columns, rows and wall fractions.
    Array(ArrayShape),
}

/// Why world values make no configuration of a binding ([`Binding::configuration`]).
#[derive(Debug, Clone, PartialEq)]
pub enum ConfigurationError {
    /// There are not as many values as variables.
    Count {
        /// Values given.
        values: usize,
        /// Variables bound.
        variables: usize,
    },
    /// The value of the variable of this id lies more than 10⁻⁶ outside its domain.
    Outside(String),
    /// The value of the variable of this id is of another kind (a direction for a
    /// placement, …).
    Kind(String),
}

impl fmt::Display for ConfigurationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConfigurationError::Count { values, variables } => {
                write!(f, "{values} values for {variables} variables")
            }
            ConfigurationError::Outside(id) => {
                write!(f, "the value of '{id}' lies outside its domain")
            }
            ConfigurationError::Kind(id) => {
                write!(f, "the value of '{id}' is not of its variable's kind")
            }
        }
    }
}

impl std::error::Error for ConfigurationError {}

impl Binding {
    /// The world value of every variable at `config`.
    pub fn values(&self, config: &Configuration) -> Vec<VariableValue> {
        self.space
            .variables()
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let x = self.space.slice(config, i);
                match (&v.domain, &self.targets[i]) {
                    (Domain::Parallelogram(r), Target::Move(m)) => {
                        let point = r.point(x[0], x[1]);
                        VariableValue::Position {
                            point,
                            anchor: m.anchor + (point - m.reference),
                        }
                    }
                    (Domain::Hemisphere(h), _) => VariableValue::Direction(h.direction(x[0], x[1])),
                    (Domain::Array(a), _) => VariableValue::Array(a.shape(x)),
                    (Domain::Segment { min, max }, Target::Power { .. }) => {
                        VariableValue::Power(min + x[0] * (max - min))
                    }
                    (Domain::Segment { min, max }, Target::Scale { .. }) => {
                        VariableValue::Scale(min + x[0] * (max - min))
                    }
                    (
                        Domain::Segment { min, max } | Domain::Turn { min, max },
                        Target::Rotate { .. },
                    ) => VariableValue::Angle(min + x[0] * (max - min)),
                    (Domain::Segment { min, max }, Target::SunTime(clock)) => {
                        let minutes = min + x[0] * (max - min);
                        let direction = clock.at(minutes).map_or(DVec3::ZERO, |(d, _)| d);
                        VariableValue::Time { minutes, direction }
                    }
                    (Domain::Segment { min, max } | Domain::Turn { min, max }, target) => {
                        let value = min + x[0] * (max - min);
                        let rgb = match target {
                            Target::Colour {
                                hue, saturation, ..
                            } => hsv_to_rgb(*hue, *saturation, value),
                            _ => [value; 3],
                        };
                        VariableValue::Colour { value, rgb }
                    }
                    (Domain::Parallelogram(r), _) => {
                        let point = r.point(x[0], x[1]);
                        VariableValue::Position {
                            point,
                            anchor: point,
                        }
                    }
                }
            })
            .collect()
    }

    /// The configuration whose variables have the world values `values` (as
    /// [`Binding::values`] gives them and the outputs write them: the placement point,
    /// the travel direction, the colour value) — the one way back from a result to the
    /// scene, for `--resume` and `--config`. The configuration is that of the values'
    /// cell (its reference point, where every evaluated configuration lies), so the
    /// rounding of world values written as decimals is undone. Values may stray from
    /// their domain by rounding (they are clamped); a value farther than 10⁻⁶ of the
    /// domain outside it is an error naming the variable.
    pub fn configuration(
        &self,
        values: &[VariableValue],
    ) -> Result<Configuration, ConfigurationError> {
        const SLACK: f64 = 1e-6;
        if values.len() != self.space.variables().len() {
            return Err(ConfigurationError::Count {
                values: values.len(),
                variables: self.space.variables().len(),
            });
        }
        let mut coords = Vec::with_capacity(self.space.dimensions());
        for (var, value) in self.space.variables().iter().zip(values) {
            let inside = |x: f64| (-SLACK..=1.0 + SLACK).contains(&x);
            let outside = || ConfigurationError::Outside(var.id.clone());
            match (&var.domain, value) {
                (Domain::Parallelogram(r), VariableValue::Position { point, .. }) => {
                    let (s, t) = r.coords(*point);
                    if !(inside(s) && inside(t)) {
                        return Err(outside());
                    }
                    coords.extend([s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)]);
                }
                (Domain::Array(a), VariableValue::Array(shape)) => {
                    coords.extend(a.coords(shape).ok_or_else(outside)?);
                }
                (Domain::Hemisphere(h), VariableValue::Direction(d)) => {
                    let (phi, theta) = h.coords(*d);
                    coords.extend([phi, theta]);
                }
                (
                    Domain::Segment { min, max } | Domain::Turn { min, max },
                    VariableValue::Colour { value, .. }
                    | VariableValue::Power(value)
                    | VariableValue::Scale(value)
                    | VariableValue::Angle(value)
                    | VariableValue::Time { minutes: value, .. },
                ) => {
                    let x = if max > min {
                        (value - min) / (max - min)
                    } else {
                        0.0
                    };
                    let x = match var.domain {
                        Domain::Turn { .. } => x.rem_euclid(1.0),
                        _ => x,
                    };
                    if !inside(x) {
                        return Err(outside());
                    }
                    coords.push(x.clamp(0.0, 1.0));
                }
                _ => return Err(ConfigurationError::Kind(var.id.clone())),
            }
        }
        Ok(self.space.snap(&Configuration { coords }))
    }
}
