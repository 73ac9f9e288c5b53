//! Lighting intentions as designers state them: one goal ("the most light on the desk",
//! "500 lx on the desk", "as even as possible", "the least power") and any number of
//! constraints ("at least 500 lx", "at most 300 lx on the screen", "U0 ≥ 0.6",
//! "nowhere below 300 lx"), each on a named surface and a side of it.
//!
//! Uniformity and point values are read on a grid over the surface: EN 12464-1:2021's
//! grid by default (`grid="auto"`, [`en12464_spacing`]), or a spacing in metres; the
//! photon layer measures them ([`invlight_photon::measure_with`]).

pub use invlight_photon::{GridValues, Side, en12464_spacing};
use invlight_scene::AreaKind;
use std::fmt;

/// A surface an intention is about.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceRef {
    /// Its name in the scene.
    pub name: String,
    /// Which side counts.
    pub side: Side,
}

impl fmt::Display for SurfaceRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.side {
            Side::Both => write!(f, "'{}'", self.name),
            side => write!(f, "'{}' ({})", self.name, side.name()),
        }
    }
}

/// The grid uniformity and point values are read on: its spacing, and what its cells
/// read — the illuminance at their centres, as EN 12464-1 judges a grid (the default),
/// or their means (`values="cell-means"`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Grid {
    /// Its spacing.
    pub spacing: Spacing,
    /// What a cell reads.
    pub values: GridValues,
}

impl Grid {
    /// EN 12464-1's grid: its spacing, read at points.
    pub const AUTO: Grid = Grid {
        spacing: Spacing::Auto,
        values: GridValues::Points,
    };

    /// Cells at most `metres` wide, read at points.
    pub fn metres(metres: f64) -> Grid {
        Grid {
            spacing: Spacing::Metres(metres),
            values: GridValues::Points,
        }
    }
}

/// A grid's spacing.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Spacing {
    /// EN 12464-1:2021's spacing for the surface's size ([`en12464_spacing`]).
    #[default]
    Auto,
    /// Cells at most this wide, m.
    Metres(f64),
}

/// What a configuration should achieve above all.
#[derive(Debug, Clone, PartialEq)]
pub enum Goal {
    /// `<maximizeRadiance surface maxRadiosity?>`: the most mean illuminance, lx; a
    /// configuration whose whole interval lies above `cap` is invalid (the thesis'
    /// objective, §5.3.4).
    Maximize {
        /// The surface.
        surface: SurfaceRef,
        /// `maxRadiosity`, lx.
        cap: Option<f64>,
    },
    /// `<minimizeRadiance surface>`: the least mean illuminance, lx.
    Minimize {
        /// The surface.
        surface: SurfaceRef,
    },
    /// `<targetRadiance surface lux>`: the mean illuminance closest to `lux`.
    Target {
        /// The surface.
        surface: SurfaceRef,
        /// The target, lx.
        lux: f64,
    },
    /// `<maximizeUniformity surface grid>`: the largest U0 = Emin/Eavg over the grid.
    MaximizeUniformity {
        /// The surface.
        surface: SurfaceRef,
        /// Its grid.
        grid: Grid,
    },
    /// `<minimizePower/>`: the least power of the scene's lights as dimmed: watts when
    /// every light's file gives them, lumens otherwise ([`crate::PowerUnit`]).
    MinimizePower,
    /// `<maximizeDaylightFactor surface>`: the largest daylight factor, % — the mean
    /// illuminance under the CIE overcast sky alone over that sky's unobstructed
    /// horizontal illuminance (CIE S 017:2020, "daylight factor"; docs/daylight.md).
    MaximizeDaylightFactor {
        /// The surface.
        surface: SurfaceRef,
    },
    /// `<minimizeGlare observer view name?>`: the least Unified Glare Rating at one
    /// observer (CIE 117; [`invlight_photon::glare`]).
    MinimizeGlare {
        /// The observer's eye square, the calculation surface named after it that the
        /// problem adds to the scene (its front faces the view).
        observer: SurfaceRef,
    },
}

impl Goal {
    /// The problem-file element.
    pub fn element(&self) -> &'static str {
        match self {
            Goal::Maximize { .. } => "maximizeRadiance",
            Goal::Minimize { .. } => "minimizeRadiance",
            Goal::Target { .. } => "targetRadiance",
            Goal::MaximizeUniformity { .. } => "maximizeUniformity",
            Goal::MinimizePower => "minimizePower",
            Goal::MaximizeDaylightFactor { .. } => "maximizeDaylightFactor",
            Goal::MinimizeGlare { .. } => "minimizeGlare",
        }
    }

    /// What its value is, in words for an axis: `mean illuminance`, `uniformity U0`,
    /// `lamp power`.
    pub fn quantity(&self) -> &'static str {
        match self {
            Goal::Maximize { .. } | Goal::Minimize { .. } | Goal::Target { .. } => {
                "mean illuminance"
            }
            Goal::MaximizeUniformity { .. } => "uniformity U0",
            Goal::MaximizeDaylightFactor { .. } => "daylight factor",
            Goal::MinimizePower => "lamp power",
            Goal::MinimizeGlare { .. } => "UGR",
        }
    }

    /// The surface it is about, if any.
    pub fn surface(&self) -> Option<&SurfaceRef> {
        match self {
            Goal::Maximize { surface, .. }
            | Goal::Minimize { surface }
            | Goal::Target { surface, .. }
            | Goal::MaximizeUniformity { surface, .. }
            | Goal::MaximizeDaylightFactor { surface } => Some(surface),
            Goal::MinimizePower | Goal::MinimizeGlare { .. } => None,
        }
    }

    /// The unit of its value: `lx`, `` (a ratio, or UGR's index), `lm` (a bound
    /// problem's `minimizePower` may count watts instead: [`crate::Binding::goal_unit`])
    /// or `DF %`.
    pub fn unit(&self) -> &'static str {
        match self {
            Goal::MaximizeUniformity { .. } | Goal::MinimizeGlare { .. } => "",
            Goal::MinimizePower => "lm",
            Goal::MaximizeDaylightFactor { .. } => DF_UNIT,
            _ => "lx",
        }
    }

    /// How `result.json` names its sense.
    pub fn sense(&self) -> &'static str {
        match self {
            Goal::Maximize { .. } => "maximize",
            Goal::Minimize { .. } => "minimize",
            Goal::Target { .. } => "target",
            Goal::MaximizeUniformity { .. } => "maximizeUniformity",
            Goal::MinimizePower => "minimizePower",
            Goal::MaximizeDaylightFactor { .. } => "maximize",
            Goal::MinimizeGlare { .. } => "minimize",
        }
    }
}

/// The unit of a daylight factor in columns and labels: per cent of the unobstructed
/// horizontal illuminance.
pub const DF_UNIT: &str = "DF %";

/// What a constraint bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// `minLux`: the mean illuminance at least this, lx.
    MinLux(f64),
    /// `maxLux`: the mean illuminance at most this, lx.
    MaxLux(f64),
    /// `minUniformity`: U0 over the grid at least this.
    MinUniformity(f64, Grid),
    /// `minPointLux`: Emin over the grid at least this, lx.
    MinPointLux(f64, Grid),
    /// `minDaylightFactor`: the daylight factor of the mean illuminance at least this, %
    /// ([`Goal::MaximizeDaylightFactor`]).
    MinDaylightFactor(f64),
    /// `maxUGR`: the Unified Glare Rating at an observer at most this (CIE 117;
    /// EN 12464-1's UGR_L), on the observer's eye square.
    MaxUgr(f64),
}

impl Bound {
    /// The problem-file attribute.
    pub fn attribute(&self) -> &'static str {
        match self {
            Bound::MinLux(_) => "minLux",
            Bound::MaxLux(_) => "maxLux",
            Bound::MinUniformity(..) => "minUniformity",
            Bound::MinPointLux(..) => "minPointLux",
            Bound::MinDaylightFactor(_) => "minDaylightFactor",
            Bound::MaxUgr(_) => "maxUGR",
        }
    }

    /// The limit.
    pub fn limit(&self) -> f64 {
        match *self {
            Bound::MinLux(x) | Bound::MaxLux(x) | Bound::MinUniformity(x, _) => x,
            Bound::MinPointLux(x, _) | Bound::MinDaylightFactor(x) | Bound::MaxUgr(x) => x,
        }
    }

    /// The bound with an illuminance limit divided by `factor` (a uniformity, a
    /// daylight factor or a UGR unchanged): a maintained requirement E·MF ≥ L read as
    /// the new installation's E ≥ L/MF. A UGR is rated for the new installation, as
    /// CIE 117's tables are: a maintenance factor scales the luminances by MF and the
    /// background by MF, which only lowers it by 8·log10(1/MF).
    pub fn for_new(&self, factor: f64) -> Bound {
        match *self {
            Bound::MinLux(x) => Bound::MinLux(x / factor),
            Bound::MaxLux(x) => Bound::MaxLux(x / factor),
            Bound::MinPointLux(x, g) => Bound::MinPointLux(x / factor, g),
            other => other,
        }
    }

    /// Whether it bounds from below.
    pub fn is_lower(&self) -> bool {
        !matches!(self, Bound::MaxLux(_) | Bound::MaxUgr(_))
    }

    /// How far `value` lies inside the bound, in its unit: value − limit for a lower
    /// bound, limit − value for an upper one; negative when it is outside.
    pub fn inside(&self, value: f64) -> f64 {
        if self.is_lower() {
            value - self.limit()
        } else {
            self.limit() - value
        }
    }

    /// The grid it is read on, when it is read on one.
    pub fn grid(&self) -> Option<Grid> {
        match *self {
            Bound::MinUniformity(_, g) | Bound::MinPointLux(_, g) => Some(g),
            _ => None,
        }
    }
}

/// `<constraint surface side? minLux|maxLux|minUniformity|minPointLux|minDaylightFactor
/// grid?>`, or `<constraint maxUGR observer view name?>` (its surface the observer's eye
/// square).
#[derive(Debug, Clone, PartialEq)]
pub struct Constraint {
    /// The surface.
    pub surface: SurfaceRef,
    /// What is bounded, and how, in the new installation's values: an illuminance
    /// limit is the file's divided by the maintenance factor.
    pub bound: Bound,
    /// Line of its element.
    pub line: u32,
    /// The maintenance factor the file's illuminance limit was divided by
    /// (`<objectives maintenanceFactor>`); 1 for a ratio, or without one.
    pub maintenance_factor: f64,
    /// The `<task>` that asked it, when one did rather than a `<constraint>`.
    pub from_task: Option<FromTask>,
    /// For a mean bound (`minLux`, `maxLux`) given a `grid`: the grid whose values'
    /// mean is bounded, EN 12464-1's Ēm (the mean of its points); `None`: the surface's
    /// mean illuminance.
    pub average_over: Option<Grid>,
}

/// Which requirement of a `<task>` a constraint states: the task area's own, or one of
/// the EN 12464-1 areas built around it.
#[derive(Debug, Clone, PartialEq)]
pub struct FromTask {
    /// The task's name in EN 12464-1's table (`office`), or `task` for one given by its
    /// figures alone.
    pub task: String,
    /// The area around the task area, or `None` for the task area itself.
    pub area: Option<AreaKind>,
}

impl FromTask {
    /// In words, for tables and reports: `EN 12464-1 office: immediate surrounding`.
    pub fn words(&self) -> String {
        format!(
            "EN 12464-1 {}: {}",
            self.task,
            self.area.map_or("task area", AreaKind::name)
        )
    }
}

impl Constraint {
    /// A short label for columns and tables: `Desk.minLux`, `Desk.front.minLux` when a
    /// side is named (a problem holds at most one constraint per label).
    pub fn label(&self) -> String {
        match self.surface.side {
            // An observer's eye square is read on its front alone, which goes unsaid.
            _ if matches!(self.bound, Bound::MaxUgr(_)) => {
                format!("{}.{}", self.surface.name, self.bound.attribute())
            }
            Side::Both => format!("{}.{}", self.surface.name, self.bound.attribute()),
            side => format!(
                "{}.{}.{}",
                self.surface.name,
                side.name(),
                self.bound.attribute()
            ),
        }
    }

    /// The standard's name for it when a `<task>` asked it:
    /// `EN 12464-1 office: immediate surrounding Ēm`.
    pub fn standard_name(&self) -> Option<String> {
        let task = self.from_task.as_ref()?;
        let quantity = match self.bound {
            Bound::MinUniformity(..) => "U0",
            Bound::MaxUgr(_) => return Some(format!("EN 12464-1 {}: UGR_L", task.task)),
            _ if task.area == Some(AreaKind::Cylindrical) => "Ēz",
            _ => "Ēm",
        };
        Some(format!("{} {quantity}", task.words()))
    }

    /// The constraint on a new installation under the maintenance factor `factor`: an
    /// illuminance limit, stated maintained, divided by it ([`Bound::for_new`], which
    /// leaves ratios and ratings alone), and the factor kept where it applied.
    pub fn maintained(mut self, factor: f64) -> Constraint {
        let new = self.bound.for_new(factor);
        if new != self.bound {
            self.bound = new;
            self.maintenance_factor = factor;
        }
        self
    }

    /// The limit as the file states it: maintained illuminance (EN 12464-1's Em is
    /// maintained, the value the installation must keep at the end of its
    /// maintenance cycle), the bound's new-installation limit × the maintenance factor.
    pub fn maintained_limit(&self) -> f64 {
        self.bound.limit() * self.maintenance_factor
    }

    /// The unit of the bounded quantity: `lx`, `` for a uniformity or a UGR, `DF %`.
    pub fn unit(&self) -> &'static str {
        match self.bound {
            Bound::MinUniformity(..) | Bound::MaxUgr(_) => "",
            Bound::MinDaylightFactor(_) => DF_UNIT,
            _ => "lx",
        }
    }

    /// The one-sided bound of an estimate that decides it at the one-sided `z`:
    /// mean − z·σ against a lower limit, mean + z·σ against an upper one
    /// ([`Feasibility::of`]).
    pub fn one_sided_bound(&self, e: &invlight_stats::Estimate, z: f64) -> f64 {
        let i = e.interval(z);
        if self.bound.is_lower() { i.low } else { i.high }
    }

    /// Its verdict for an estimate of its quantity, at the one-sided `z`.
    pub fn verdict(&self, e: &invlight_stats::Estimate, z: f64) -> Feasibility {
        Feasibility::of(e.mean, e.std_error, z, &self.bound)
    }
}

/// What a configuration's constraint evaluation decided (at the run's confidence,
/// one-sided: the lower end of the interval for a lower bound, the upper for an upper
/// bound).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feasibility {
    /// Holds at the confidence.
    Feasible,
    /// Is violated at the confidence.
    Infeasible,
    /// The interval straddles the limit: more photons may tell.
    Undecided,
}

impl Feasibility {
    /// The output spelling.
    pub fn name(self) -> &'static str {
        match self {
            Feasibility::Feasible => "feasible",
            Feasibility::Infeasible => "infeasible",
            Feasibility::Undecided => "undecided",
        }
    }

    /// Parses the output spelling.
    pub fn parse(s: &str) -> Option<Feasibility> {
        [
            Feasibility::Feasible,
            Feasibility::Infeasible,
            Feasibility::Undecided,
        ]
        .into_iter()
        .find(|f| f.name() == s)
    }

    /// The verdict of an estimate `mean ± z·σ` (z one-sided) against `bound`.
    pub fn of(mean: f64, std_error: f64, z: f64, bound: &Bound) -> Feasibility {
        let estimate = invlight_stats::Estimate {
            mean,
            std_error,
            samples: 0,
        };
        let invlight_stats::Interval { low, high } = estimate.interval(z);
        let limit = bound.limit();
        let (holds, fails) = if bound.is_lower() {
            (low >= limit, high < limit)
        } else {
            (high <= limit, low > limit)
        };
        if holds {
            Feasibility::Feasible
        } else if fails {
            Feasibility::Infeasible
        } else {
            Feasibility::Undecided
        }
    }

    /// The verdict of several constraints together: infeasible if one is, feasible if
    /// all are, undecided otherwise.
    pub fn all(verdicts: impl IntoIterator<Item = Feasibility>) -> Feasibility {
        let mut out = Feasibility::Feasible;
        for v in verdicts {
            match v {
                Feasibility::Infeasible => return Feasibility::Infeasible,
                Feasibility::Undecided => out = Feasibility::Undecided,
                Feasibility::Feasible => {}
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdicts_are_one_sided() {
        let min = Bound::MinLux(500.0);
        assert_eq!(
            Feasibility::of(520.0, 5.0, 1.645, &min),
            Feasibility::Feasible
        );
        assert_eq!(
            Feasibility::of(480.0, 5.0, 1.645, &min),
            Feasibility::Infeasible
        );
        assert_eq!(
            Feasibility::of(505.0, 5.0, 1.645, &min),
            Feasibility::Undecided
        );
        let max = Bound::MaxLux(300.0);
        assert_eq!(
            Feasibility::of(290.0, 5.0, 1.645, &max),
            Feasibility::Feasible
        );
        assert_eq!(
            Feasibility::of(310.0, 5.0, 1.645, &max),
            Feasibility::Infeasible
        );
        assert_eq!(
            Feasibility::all([Feasibility::Feasible, Feasibility::Undecided]),
            Feasibility::Undecided
        );
        assert_eq!(
            Feasibility::all([Feasibility::Undecided, Feasibility::Infeasible]),
            Feasibility::Infeasible
        );
    }
}
