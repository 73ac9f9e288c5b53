//! What a problem's intentions ask the photon tracer to measure, and how an evaluation
//! is read from one measurement: the distinct surfaces named by the goal and the
//! constraints (each measured once, front and back apart), the grids uniformity and
//! point values need, and for each intention the quantity it reads (a side's mean, a
//! grid's U0 or Emin, the lamps' power).

use crate::intention::{Bound, Goal, Grid, GridValues, Side, Spacing, SurfaceRef};
use crate::problem::Problem;
use crate::vns::Evaluation;
use invlight_photon::glare::{GlareError, Observer, light_without_luminous_area, ugr_estimate};
use invlight_photon::{GridError, GridRequest, Measurement, SurfaceGrid};
use invlight_scene::daylight::SkyKind;
use invlight_scene::{Diagnostic, Scene, SurfaceId, known_names};
use invlight_stats::Estimate;

/// A grid to lay on one of the measured surfaces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridSpec {
    /// Index of the surface in [`Reading::surfaces`].
    pub target: usize,
    /// The side counted.
    pub side: Side,
    /// Its spacing.
    pub grid: Grid,
}

/// The quantity one intention reads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Quantity {
    /// The mean illuminance of a surface's side, lx.
    Mean {
        /// Index in [`Reading::surfaces`].
        target: usize,
        /// The side.
        side: Side,
    },
    /// The mean of a grid's values, lx: EN 12464-1's Ēm, the mean of its points (of
    /// its cells' means when it reads means: the surface's mean).
    Average {
        /// Index in [`Reading::grids`].
        grid: usize,
    },
    /// U0 over a grid.
    Uniformity {
        /// Index in [`Reading::grids`].
        grid: usize,
    },
    /// Emin over a grid, lx.
    MinPoint {
        /// Index in [`Reading::grids`].
        grid: usize,
    },
    /// The electric lights' luminous flux as dimmed, lm (exact).
    Power,
    /// The Unified Glare Rating at an observer: its luminaires' glare sum (exact, per
    /// component) over the indirect illuminance its eye square's grid reads
    /// ([`ugr_estimate`]).
    Ugr {
        /// Index in [`Reading::observers`].
        observer: usize,
        /// Index in [`Reading::grids`] of its eye square's indirect grid.
        grid: usize,
    },
    /// The daylight factor of a surface side's mean illuminance, %: the mean times
    /// `per_lux` = 100 / E_h, E_h the overcast sky's unobstructed horizontal
    /// illuminance, which is exact, so the standard error scales the same way.
    DaylightFactor {
        /// Index in [`Reading::surfaces`].
        target: usize,
        /// The side.
        side: Side,
        /// 100 / E_h, % per lx.
        per_lux: f64,
    },
}

/// What a problem measures and reads.
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// The distinct surfaces measured.
    pub surfaces: Vec<SurfaceId>,
    /// Their names.
    pub names: Vec<String>,
    /// Whether some intention counts a surface's both sides (then its back's share is
    /// worth a warning).
    pub both_sides: Vec<bool>,
    /// The distinct grids.
    pub grids: Vec<GridSpec>,
    /// The goal's quantity.
    pub goal: Quantity,
    /// Each constraint's quantity, in the problem's order.
    pub constraints: Vec<Quantity>,
    /// The observers whose glare is rated, with their eye squares' names.
    pub observers: Vec<(String, Observer)>,
}

impl Reading {
    /// The measurement plan of `problem`'s goal and constraints on `scene`: every named
    /// surface must exist and have area, and every grid must lie on a planar surface.
    pub fn new(problem: &Problem, scene: &Scene) -> Result<Reading, Diagnostic> {
        let mut reading = Reading {
            surfaces: Vec::new(),
            names: Vec::new(),
            both_sides: Vec::new(),
            grids: Vec::new(),
            goal: Quantity::Power,
            constraints: Vec::new(),
            observers: Vec::new(),
        };
        let line = problem.goal_line;
        reading.goal = match &problem.goal {
            Goal::Maximize { surface, .. }
            | Goal::Minimize { surface }
            | Goal::Target { surface, .. } => reading.mean(problem, scene, surface, line)?,
            Goal::MaximizeUniformity { surface, grid } => {
                let grid = reading.grid(problem, scene, surface, *grid, line)?;
                Quantity::Uniformity { grid }
            }
            Goal::MinimizePower => Quantity::Power,
            Goal::MaximizeDaylightFactor { surface } => {
                reading.daylight_factor(problem, scene, surface, line)?
            }
            Goal::MinimizeGlare { observer } => reading.ugr(problem, scene, observer, line)?,
        };
        for c in &problem.constraints {
            let q = match c.bound {
                Bound::MinLux(_) | Bound::MaxLux(_) => match c.average_over {
                    Some(grid) => Quantity::Average {
                        grid: reading.grid(problem, scene, &c.surface, grid, c.line)?,
                    },
                    None => reading.mean(problem, scene, &c.surface, c.line)?,
                },
                Bound::MinUniformity(_, grid) => Quantity::Uniformity {
                    grid: reading.grid(problem, scene, &c.surface, grid, c.line)?,
                },
                Bound::MinPointLux(_, grid) => Quantity::MinPoint {
                    grid: reading.grid(problem, scene, &c.surface, grid, c.line)?,
                },
                Bound::MinDaylightFactor(_) => {
                    reading.daylight_factor(problem, scene, &c.surface, c.line)?
                }
                Bound::MaxUgr(_) => reading.ugr(problem, scene, &c.surface, c.line)?,
            };
            reading.constraints.push(q);
        }
        if let Some(first) = problem
            .observers
            .first()
            .filter(|_| !reading.observers.is_empty())
            && let Some(GlareError::NoLuminousArea { light, kind }) =
                light_without_luminous_area(scene)
        {
            return Err(Diagnostic::at_line(
                &problem.path,
                first.line,
                format!("glare is rated at '{}', and the light '{light}' is {kind} without a luminous area: UGR needs each luminaire's luminance, its intensity over its luminous area", first.name),
            )
            .with_hint("give it a photometric file with luminous dimensions (IES width and length, EULUMDAT luminous area) with <luminaire light=… file=…>: a glare search rates every light of the scene, since a moved or turned one may come into view"));
        }
        Ok(reading)
    }

    /// The index of surface `r`, added when new.
    fn target(
        &mut self,
        problem: &Problem,
        scene: &Scene,
        r: &SurfaceRef,
        line: u32,
    ) -> Result<usize, Diagnostic> {
        let err = |msg: String| Diagnostic::at_line(&problem.path, line, msg);
        let id = scene.surface(&r.name).ok_or_else(|| {
            err(format!(
                "no surface named '{}' in the scene, expected the surface to light",
                r.name
            ))
            .with_hint(known_names(
                scene.surfaces.iter().map(|s| s.name.as_str()),
                "surfaces",
            ))
        })?;
        // Illuminance is flux over area: a surface without area has none.
        if scene.surface_area(id) <= 0.0 {
            return Err(err(format!(
                "the surface '{}' has no area, expected a surface to light",
                r.name
            )));
        }
        let t = match self.surfaces.iter().position(|&s| s == id) {
            Some(t) => t,
            None => {
                self.surfaces.push(id);
                self.names.push(r.name.clone());
                self.both_sides.push(false);
                self.surfaces.len() - 1
            }
        };
        self.both_sides[t] |= r.side == Side::Both;
        Ok(t)
    }

    fn mean(
        &mut self,
        problem: &Problem,
        scene: &Scene,
        r: &SurfaceRef,
        line: u32,
    ) -> Result<Quantity, Diagnostic> {
        Ok(Quantity::Mean {
            target: self.target(problem, scene, r, line)?,
            side: r.side,
        })
    }

    /// The daylight factor of `r`'s mean, under `scene`'s overcast sky (which
    /// [`crate::Binding::new`] made the scene's only light).
    fn daylight_factor(
        &mut self,
        problem: &Problem,
        scene: &Scene,
        r: &SurfaceRef,
        line: u32,
    ) -> Result<Quantity, Diagnostic> {
        let lux = match &scene.sky {
            Some(sky) if sky.kind() == SkyKind::CieOvercast => sky.horizontal_illuminance(),
            _ => {
                return Err(Diagnostic::at_line(
                    &problem.path,
                    line,
                    "a daylight factor is measured under the CIE overcast sky, and the scene has none",
                )
                .with_hint("give <sky type=\"cie-overcast\" horizontalLux=\"10000\"/>, or leave the sky out for that one"));
            }
        };
        Ok(Quantity::DaylightFactor {
            target: self.target(problem, scene, r, line)?,
            side: r.side,
            per_lux: 100.0 / lux,
        })
    }

    /// The UGR at the observer whose eye square is `eye` ([`Problem::observers`]).
    fn ugr(
        &mut self,
        problem: &Problem,
        scene: &Scene,
        eye: &SurfaceRef,
        line: u32,
    ) -> Result<Quantity, Diagnostic> {
        let spec = problem
            .observers
            .iter()
            .find(|o| o.name == eye.name)
            .expect("every glare intention names an observer of the problem");
        let observer = match self.observers.iter().position(|(n, _)| *n == spec.name) {
            Some(o) => o,
            None => {
                self.observers.push((spec.name.clone(), spec.observer));
                self.observers.len() - 1
            }
        };
        let background = Grid {
            spacing: Spacing::Metres(EYE_CELL),
            values: GridValues::Indirect,
        };
        let grid = self.grid(problem, scene, eye, background, line)?;
        Ok(Quantity::Ugr { observer, grid })
    }

    /// The index of the grid of `r` spaced by `grid`, added (and checked on `scene`)
    /// when new.
    fn grid(
        &mut self,
        problem: &Problem,
        scene: &Scene,
        r: &SurfaceRef,
        grid: Grid,
        line: u32,
    ) -> Result<usize, Diagnostic> {
        let target = self.target(problem, scene, r, line)?;
        let spec = GridSpec {
            target,
            side: r.side,
            grid,
        };
        if let Some(g) = self.grids.iter().position(|g| *g == spec) {
            return Ok(g);
        }
        lay(scene, self.surfaces[target], grid).map_err(|e| {
            Diagnostic::at_line(
                &problem.path,
                line,
                format!("cannot lay a grid on '{}': {e}", r.name),
            )
            .with_hint(match e {
                GridError::NotPlanar { .. } => {
                    "uniformity and point values are read on a planar surface: name a flat part (a desk's top, a floor)"
                }
                _ => "choose a larger grid spacing",
            })
        })?;
        self.grids.push(spec);
        Ok(self.grids.len() - 1)
    }

    /// The surface the goal is about, if it is about one.
    pub fn goal_surface(&self) -> Option<SurfaceId> {
        self.surface_of(&self.goal).map(|(s, _)| s)
    }

    /// The surface a quantity is read on, if any, with the side it counts.
    pub fn surface_of(&self, q: &Quantity) -> Option<(SurfaceId, Side)> {
        match *q {
            Quantity::Mean { target, side } | Quantity::DaylightFactor { target, side, .. } => {
                Some((self.surfaces[target], side))
            }
            Quantity::Average { grid }
            | Quantity::Uniformity { grid }
            | Quantity::MinPoint { grid } => {
                let g = &self.grids[grid];
                Some((self.surfaces[g.target], g.side))
            }
            Quantity::Power | Quantity::Ugr { .. } => None,
        }
    }

    /// The surface a report draws the light on, with the side it counts: the goal's,
    /// else the first constraint's (a least-power problem's desk).
    pub fn plan_surface(&self) -> Option<(SurfaceId, Side)> {
        self.surface_of(&self.goal)
            .or_else(|| self.constraints.iter().find_map(|q| self.surface_of(q)))
    }

    /// The grids on `scene` as it is now (a measured surface may have moved); an error
    /// names the surface whose grid cannot be laid.
    pub fn grid_requests(&self, scene: &Scene) -> Result<Vec<GridRequest>, (String, GridError)> {
        self.grids
            .iter()
            .map(|g| {
                Ok(GridRequest {
                    target: g.target,
                    side: g.side,
                    grid: lay(scene, self.surfaces[g.target], g.grid)
                        .map_err(|e| (self.names[g.target].clone(), e))?,
                    values: g.grid.values,
                })
            })
            .collect()
    }

    /// The evaluation of a measurement at component weights `w` (the dimming levels),
    /// with the electric lights' flux `power`, lm.
    pub fn read(&self, m: &Measurement, w: &[f64], power: f64) -> Evaluation {
        let quantity = |q: &Quantity| match *q {
            Quantity::Mean { target, side } => m.estimate_of(target, side, w),
            Quantity::Average { grid } => m.grids[grid].average(w),
            Quantity::Uniformity { grid } => m.grids[grid].uniformity(w).u0,
            Quantity::MinPoint { grid } => m.grids[grid].uniformity(w).min,
            Quantity::Power => Estimate {
                mean: power,
                std_error: 0.0,
                samples: m.photons,
            },
            Quantity::DaylightFactor {
                target,
                side,
                per_lux,
            } => {
                let e = m.estimate_of(target, side, w);
                Estimate {
                    mean: e.mean * per_lux,
                    std_error: e.std_error * per_lux,
                    samples: e.samples,
                }
            }
            Quantity::Ugr { observer, grid } => {
                ugr_estimate(m.glare_sum(observer, w), &m.grids[grid].average(w))
            }
        };
        let groups = match self.goal {
            Quantity::Mean { target, side } => m.group_means(target, side, w),
            Quantity::DaylightFactor {
                target,
                side,
                per_lux,
            } => m
                .group_means(target, side, w)
                .into_iter()
                .map(|g| g * per_lux)
                .collect(),
            _ => Vec::new(),
        };
        Evaluation {
            goal: quantity(&self.goal),
            constraints: self.constraints.iter().map(quantity).collect(),
            groups,
            solved: None,
        }
    }
}

/// The spacing of an eye square's grid, m: wider than the square, so one cell.
const EYE_CELL: f64 = 1.0;

/// The grid `grid` on `surface`.
fn lay(scene: &Scene, surface: SurfaceId, grid: Grid) -> Result<SurfaceGrid, GridError> {
    match grid.spacing {
        Spacing::Auto => SurfaceGrid::en12464(scene, surface),
        Spacing::Metres(p) => SurfaceGrid::new(scene, surface, p as f32),
    }
}
