//! Luminaires that would stand in one another: a candidate whose moved fittings'
//! outlines overlap is refused before it is traced. A `<luminaire size>` gives the
//! luminaire's outline as installed, else its photometric file (EULUMDAT's luminaire
//! length and width, or the luminous opening where the file gives no more); two 1.5 m linear fittings 1.37 m apart cannot be
//! installed, and a search that traced them would answer with a layout no one can
//! build.
//!
//! Each outline is a rectangle (or a disk) in its luminaire's C0–C90 plane, centred on
//! its photometric centre; two overlap unless an axis separates them (the separating
//! axis theorem for two convex outlines in one plane: the four edge directions, and for
//! a disk the line between the centres). A `<lightArray>` whose orientation is searched
//! turns its fittings' outlines with its lamps.

use super::{Binding, Target, VariableValue};
use crate::problem::FittingSize;
use crate::space::Configuration;
use glam::DVec3;
use invlight_scene::{LightKind, Opening, Photometry, Scene};

/// A luminaire a placement variable moves, with its outline.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Fitting {
    /// The index of the variable that moves it.
    variable: usize,
    /// Its light's name.
    name: String,
    /// Where it stands for its variable.
    anchor: Anchor,
    /// Its outline as loaded.
    outline: Outline,
}

/// A fitting's outline in its C0–C90 plane.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Outline {
    /// Its C0 and C90 directions.
    axes: [DVec3; 2],
    /// Half its outline along them, m (a disk's radius twice).
    half: [f64; 2],
    /// Whether the outline is a disk or an ellipse (taken as its bounding disk).
    round: bool,
}

/// How a fitting's photometric centre follows its variable.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Anchor {
    /// Moved with a placement: the variable's point plus this offset (the centre less
    /// the reference point, as authored).
    Moved(DVec3),
    /// Lamp `k` of a `<lightArray>`, where the array's shape puts it, plus its offset
    /// from the placement rectangle; off (not placed) past the shape's lamps.
    InArray { k: u32, offset: DVec3 },
}

impl Outline {
    /// Half its extent along the unit direction `a` in its plane.
    fn reach(&self, a: DVec3) -> f64 {
        if self.round {
            self.half[0].max(self.half[1])
        } else {
            self.half[0] * self.axes[0].dot(a).abs() + self.half[1] * self.axes[1].dot(a).abs()
        }
    }

    /// The outline turned by `degrees` about its plane's normal, C0 toward C90, as
    /// [`invlight_scene::LightKind::turn_about_aim`] turns the luminaire.
    fn turned(&self, degrees: f64) -> Outline {
        let (sin, cos) = degrees.to_radians().sin_cos();
        let [x, y] = self.axes;
        Outline {
            axes: [cos * x + sin * y, cos * y - sin * x],
            ..*self
        }
    }
}

/// The outlines of the luminaires `targets` move, from their `<luminaire size>` (the
/// last of `sizes` for the light) else their photometric files; lights without a file
/// or without dimensions are left out.
pub(super) fn fittings(scene: &Scene, targets: &[Target], sizes: &[FittingSize]) -> Vec<Fitting> {
    let mut out = Vec::new();
    for (variable, target) in targets.iter().enumerate() {
        let lights: Vec<(invlight_scene::LightId, Anchor)> = match target {
            Target::Move(m) => m
                .lights
                .iter()
                .map(|&(light, p)| (light, Anchor::Moved(p.as_dvec3() - m.reference)))
                .collect(),
            Target::Array(a) => (0..)
                .zip(&a.lamps)
                .map(|(k, &(light, offset, _))| (light, Anchor::InArray { k, offset }))
                .collect(),
            _ => continue,
        };
        for (light, anchor) in lights {
            let l = &scene.lights[light];
            let LightKind::Goniometric {
                frame, photometry, ..
            } = &l.kind
            else {
                continue;
            };
            let outline = installed(&l.name, photometry, sizes).unwrap_or(photometry.opening);
            let [a, b] = outline.extents();
            if outline == Opening::Point || a <= 0.0 || b <= 0.0 {
                continue;
            }
            out.push(Fitting {
                variable,
                name: l.name.clone(),
                anchor,
                outline: Outline {
                    axes: [frame.x_axis.as_dvec3(), frame.y_axis.as_dvec3()],
                    half: [0.5 * f64::from(a), 0.5 * f64::from(b)],
                    round: !matches!(outline, Opening::Rectangle { .. }),
                },
            });
        }
    }
    out
}

/// The outline of the luminaire `name` as installed: its `<luminaire size>` (the last
/// of `sizes` for it; a rectangle, its length along C90 as EULUMDAT's), else its
/// photometric file's luminaire dimensions; `None` when neither gives one.
fn installed(name: &str, photometry: &Photometry, sizes: &[FittingSize]) -> Option<Opening> {
    match sizes.iter().rev().find(|s| s.light == name) {
        Some(s) => Some(Opening::Rectangle {
            along_c0: s.width as f32,
            along_c90: s.length as f32,
        }),
        None => photometry.luminaire.map(|(o, _)| o),
    }
}

/// The length of the luminaire `name` as installed (its extent along C90, as
/// EULUMDAT's length and `<luminaire size>`'s are measured), m, and the unit C90
/// direction it lies along: what fittings laid end to end in a row are spaced by.
/// `None` for a light without a photometric file or with no dimensions in it and no
/// size: a luminous opening is not the housing, and rows spaced by it would leave gaps
/// or overlap.
pub(super) fn length(name: &str, kind: &LightKind, sizes: &[FittingSize]) -> Option<(f64, DVec3)> {
    let LightKind::Goniometric {
        frame, photometry, ..
    } = kind
    else {
        return None;
    };
    let along = installed(name, photometry, sizes)?.extents()[1];
    (along > 0.0).then(|| (f64::from(along), frame.y_axis.as_dvec3()))
}

/// Whether outlines `f` at `p` and `g` at `q` overlap (see the module doc).
fn overlap(f: &Outline, p: DVec3, g: &Outline, q: DVec3) -> bool {
    let d = q - p;
    let normal = f.axes[0].cross(f.axes[1]).normalize_or_zero();
    let across = d - normal * d.dot(normal);
    let mut axes = vec![f.axes[0], f.axes[1], g.axes[0], g.axes[1]];
    if f.round || g.round {
        axes.push(across.normalize_or_zero());
    }
    // Outlines a fitting's height apart or more, one above the other, do not touch.
    if d.dot(normal).abs() > 1e-3 {
        return false;
    }
    axes.into_iter()
        .filter(|a| a.length_squared() > 0.5)
        .all(|a| d.dot(a).abs() < f.reach(a) + g.reach(a) - 1e-9)
}

impl Binding {
    /// The clear gaps, m, between neighbouring fittings of `variable` (a placement of
    /// interchangeable lamps, or a `<lightArray>`) whose centres stand `spacing` apart
    /// along the unit directions `axes`, each fitting turned `turn` degrees from its
    /// frame as loaded: what an installer measures between two fittings, edge to edge.
    /// `None` when its luminaires have no outline.
    pub(super) fn gaps(
        &self,
        variable: usize,
        spacing: [f64; 2],
        axes: [DVec3; 2],
        turn: f64,
    ) -> Option<[f64; 2]> {
        let f = self.fittings.iter().find(|f| f.variable == variable)?;
        let outline = f.outline.turned(turn);
        Some([0, 1].map(|i| spacing[i] - 2.0 * outline.reach(axes[i])))
    }

    /// The one of the unit directions `axes` the outline of `variable`'s fittings is
    /// longer along, turned `turn` degrees from their frame as loaded; `None` without
    /// an outline or for one as long as it is wide.
    pub(super) fn lengthwise(&self, variable: usize, axes: [DVec3; 2], turn: f64) -> Option<usize> {
        let f = self.fittings.iter().find(|f| f.variable == variable)?;
        let o = f.outline.turned(turn);
        if o.round || (o.half[0] - o.half[1]).abs() < 1e-9 {
            return None;
        }
        let long = o.axes[usize::from(o.half[1] > o.half[0])];
        Some(usize::from(
            long.dot(axes[1]).abs() > long.dot(axes[0]).abs(),
        ))
    }

    /// The first two moved luminaires whose outlines overlap at `config`, as a reason
    /// to refuse it.
    pub(super) fn overlapping_fittings(&self, config: &Configuration) -> Option<String> {
        if self.fittings.len() < 2 {
            return None;
        }
        let values = self.values(config);
        // Where each fitting stands and its outline, turned as its array's orientation is.
        let at = |f: &Fitting| match (f.anchor, &values[f.variable]) {
            (Anchor::Moved(offset), VariableValue::Position { point, .. }) => {
                Some((*point + offset, f.outline))
            }
            (Anchor::InArray { k, offset }, VariableValue::Array(shape)) => {
                let Target::Array(lamps) = &self.targets[f.variable] else {
                    return None;
                };
                (k < shape.lamps()).then(|| {
                    let outline = f.outline.turned(shape.orientation.unwrap_or(0.0));
                    (lamps.place(shape, k) + offset, outline)
                })
            }
            _ => None,
        };
        // Lights moved by one placement keep their authored places among themselves.
        let rigid = |f: &Fitting, g: &Fitting| {
            f.variable == g.variable && matches!(f.anchor, Anchor::Moved(_))
        };
        let placed: Vec<Option<(DVec3, Outline)>> = self.fittings.iter().map(at).collect();
        for (k, f) in self.fittings.iter().enumerate() {
            let Some((p, a)) = placed[k] else { continue };
            for (g, &q) in self.fittings.iter().zip(&placed).skip(k + 1) {
                if let Some((q, b)) = q
                    && !rigid(f, g)
                    && overlap(&a, p, &b, q)
                {
                    return Some(format!(
                        "it puts the fittings of '{}' and '{}' over each other ({:.2} m apart)",
                        f.name,
                        g.name,
                        p.distance(q)
                    ));
                }
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn linear(x: f64, turned: bool) -> (Outline, DVec3) {
        let f = Outline {
            axes: [DVec3::X, DVec3::Y],
            // 1.5 m long along C90, 0.1 m wide.
            half: [0.05, 0.75],
            round: false,
        };
        let f = if turned { f.turned(90.0) } else { f };
        (f, DVec3::new(x, 0.0, 0.0))
    }

    /// Two 1.5 m fittings side by side overlap only when closer than their width; end
    /// to end, closer than their length.
    #[test]
    fn outlines_overlap_as_the_fittings_would() {
        let (a, p) = linear(0.0, false);
        let (b, q) = linear(0.2, false);
        assert!(!overlap(&a, p, &b, q), "side by side 0.2 m apart");
        let (b, q) = linear(0.08, false);
        assert!(overlap(&a, p, &b, q), "0.08 m apart, 0.1 m wide");
        // Turned a quarter turn their lengths lie along the line between them.
        let (a, p) = linear(0.0, true);
        let (b, q) = linear(1.37, true);
        assert!(overlap(&a, p, &b, q), "end to end 1.37 m apart, 1.5 m long");
        let (b, q) = linear(1.6, true);
        assert!(!overlap(&a, p, &b, q));
        // A disk of 0.17 m beside another.
        let disk = |x: f64| {
            (
                Outline {
                    axes: [DVec3::X, DVec3::Y],
                    half: [0.085, 0.085],
                    round: true,
                },
                DVec3::new(x, x, 0.0),
            )
        };
        let ((a, p), (b, q)) = (disk(0.0), disk(0.1));
        assert!(overlap(&a, p, &b, q), "0.14 m apart, 0.17 m across");
        let (b, q) = disk(0.13);
        assert!(!overlap(&a, p, &b, q), "0.18 m apart");
    }

    /// A quarter turn takes C0 where C90 was and C90 where −C0 was, as
    /// `turn_about_aim` turns a luminaire's frame; a whole turn of four is the start.
    #[test]
    fn an_outline_turns_as_its_luminaire() {
        let (a, _) = linear(0.0, false);
        let b = a.turned(90.0);
        assert!(b.axes[0].abs_diff_eq(DVec3::Y, 1e-12), "{:?}", b.axes);
        assert!(b.axes[1].abs_diff_eq(-DVec3::X, 1e-12), "{:?}", b.axes);
        let round = b.turned(90.0).turned(90.0).turned(90.0);
        assert!(round.axes[0].abs_diff_eq(a.axes[0], 1e-12));
        assert!(
            (b.reach(DVec3::X) - 0.75).abs() < 1e-12,
            "its length along X"
        );
    }
}
