//! Options every command shares, so that a flag means the same thing everywhere:
//! [`LoadArgs`] (how to read a scene), [`SceneArgs`] (a scene file, or a problem file
//! and one of its solve's results) and [`TraceArgs`] (photons, seed, bounces,
//! confidence, threads).

use crate::InputError;
use anyhow::Context;
use clap::Args;
use invlight_ilp::{Problem, configured_scene};
use invlight_photon::{DEFAULT_MAX_BOUNCES, TraceSettings, photon_count};
use invlight_render::Requirement;
use invlight_report::GridOptions as Grid;
use invlight_scene::daylight::{Daylight, DaylightFlags, Site, SkySpec, SunAt};
use invlight_scene::{
    Calculation, CalculationSurface, LoadOptions, Luminaire, Scene, UpAxis, load_with,
};
pub use invlight_scene::{finite, positive};
use invlight_stats::Confidence;
use invlight_trace::Accel;
use std::path::{Path, PathBuf};

/// How to read a scene file.
#[derive(Args, Debug, Clone, Default)]
pub struct LoadArgs {
    /// Metres per file unit, for files authored in other units (e.g. 0.001 for mm)
    /// [default: 1, or a problem file's <scene scale>]. Applied after the file's own unit
    /// declaration (COLLADA <unit meter>).
    #[arg(long, value_name = "M", value_parser = positive::<f32>)]
    pub scale: Option<f32>,
    /// The file's up axis when it does not say (OBJ) or says wrongly [default: the
    /// file's, or a problem file's <scene up>]. Positions are never swapped; the axis
    /// orients sun directions and default views.
    #[arg(long, value_name = "y|z")]
    pub up: Option<UpAxis>,
    /// Memory the scene may take, loading and tracing: 8G, 512M, 64K or bytes (powers of
    /// 1024). A file whose declared sizes (buffers, vertex counts, texture pixels), or
    /// whose ray-tracing structure, would need more is refused with the figure before
    /// anything is allocated. Default: half of this machine's memory.
    #[arg(long, value_name = "SIZE", value_parser = invlight_scene::parse_memory_size)]
    pub max_memory: Option<u64>,
    /// Let the scene file read files anywhere: absolute paths, `..` out of its folder,
    /// links that lead out. Without it only files in the scene's folder tree are read,
    /// as a scene file may come from anyone; use it for files you trust. Devices and
    /// pipes are never read.
    #[arg(long)]
    pub allow_outside_paths: bool,
    /// NAME=FILE or NAME=FILE*M: light NAME emits an IES or EULUMDAT file's table, times M
    /// (> 0, default 1, as <luminaire multiplier>) (repeatable; wins over <luminaire>)
    #[arg(long)]
    pub luminaire: Vec<Luminaire>,
    /// NAME: surface NAME receives light without touching it: photons pass it unchanged,
    /// it casts no shadow and is not drawn, and it is measured on both sides as asked
    /// (repeatable; as a problem file's <calculationSurface>).
    #[arg(long, value_name = "NAME")]
    pub calculation_surface: Vec<String>,
    /// LAT,LON,TZ: the site of --sun (degrees, longitude east positive; the clock's hours
    /// east of UTC, e.g. -34.9,-56.2,-3 for Montevideo), else the problem file's site.
    #[arg(long, value_name = "LAT,LON,TZ", allow_hyphen_values = true)]
    pub site: Option<Site>,
    /// True north, degrees clockwise seen from above from the scene's −Z (Y-up) or +Y
    /// (Z-up), of --site or the problem file's site.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub north: Option<f64>,
    /// DATE,TIME or DATE,TIME,LUX: the sun at that local time at the site (NREL SPA), with LUX
    /// or the IES RP-21 clear-sky beam, as the scene's directional light (docs/daylight.md).
    #[arg(long, value_name = "DATE,TIME[,LUX]")]
    pub sun: Option<SunAt>,
    /// KIND:LUX: a CIE sky (cie-overcast, cie-clear) giving LUX on an open horizontal plane.
    #[arg(long, value_name = "KIND:LUX")]
    pub sky: Option<SkySpec>,
}

impl LoadArgs {
    /// The loader's options.
    pub fn options(&self) -> LoadOptions {
        let defaults = LoadOptions::default();
        LoadOptions {
            scale: self.scale.unwrap_or(1.0),
            up: self.up,
            max_memory: self.max_memory.unwrap_or(defaults.max_memory),
            allow_outside_paths: self.allow_outside_paths,
        }
    }

    /// Whether any option changes how the scene is read, so that a command rebuilding
    /// from the same files must be given them too.
    pub fn given(&self) -> bool {
        self.scale.is_some()
            || self.up.is_some()
            || self.allow_outside_paths
            || !self.luminaire.is_empty()
            || !self.calculation_surface.is_empty()
            || self.site.is_some()
            || self.north.is_some()
            || self.sun.is_some()
            || self.sky.is_some()
    }

    /// --site, --north, --sun and --sky.
    fn daylight(&self) -> DaylightFlags {
        Daylight::flags(self.site, self.north, self.sun, self.sky)
    }

    /// Puts the flags' daylight on a scene file's scene (a problem's goes over its own)
    /// and makes the --calculation-surface surfaces calculation surfaces; refuses a scene whose ray-tracing structure would not fit the memory limit.
    fn fits(&self, mut scene: Scene, path: &Path, file: bool) -> anyhow::Result<Scene> {
        if file {
            crate::warn(self.daylight().light(&mut scene)?);
        }
        let calculation = Calculation {
            surfaces: self
                .calculation_surface
                .iter()
                .map(|name| CalculationSurface::named(name))
                .collect(),
            workplanes: Vec::new(),
        };
        scene.set_calculation(path, &calculation)?;
        Accel::check_memory(&scene, path, self.options().max_memory)?;
        Ok(scene)
    }

    /// Loads a problem file's scene, these options over its `<scene>`'s and its daylight.
    pub fn load_problem(&self, problem: &mut Problem) -> anyhow::Result<Scene> {
        crate::warn(problem.lit_by(&self.daylight())?);
        let scene = problem.load_scene(&self.options(), self.scale, self.up, &self.luminaire)?;
        self.fits(scene, &problem.scene.path, false)
    }
}

/// A scene to work on: a scene file, or a problem file (its scene) with optionally one
/// of its solve's configurations applied.
#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// Scene file: glTF 2.0 (.gltf, .glb), COLLADA (.dae) or Wavefront OBJ (.obj); or a
    /// problem file (.xml), whose scene is read as its <scene> says.
    pub scene: PathBuf,
    /// With a problem file: apply configuration K of a solve's result (RESULT#K, a
    /// result.json written by `invlight solve`; K counts from 1 in result.json's order,
    /// as isoc-01.png, isoc-02.png, … do; RESULT alone is member 1, the best; a result
    /// with no feasible configuration numbers its closest instead).
    #[arg(long, value_name = "RESULT#K")]
    pub config: Option<String>,
    #[command(flatten)]
    pub load: LoadArgs,
}

impl SceneArgs {
    /// Loads the scene, configured as `--config` says.
    pub fn load(&self) -> anyhow::Result<Scene> {
        Ok(self.load_with_problem()?.0)
    }

    /// Loads the scene as [`SceneArgs::load`] does, with the problem file it came from
    /// (read once for both), if it came from one.
    pub fn load_with_problem(&self) -> anyhow::Result<(Scene, Option<Problem>)> {
        let (path, options, lum) = (&self.scene, self.load.options(), &self.load.luminaire);
        let file = || self.load.fits(load_with(path, &options, lum)?, path, true);
        let mut read = None;
        let scene = configured_scene(path, self.config.as_deref(), file, |p| {
            let scene = self.load.load_problem(p);
            read = Some(p.clone());
            scene
        })?;
        Ok((scene, read))
    }
}

/// Options of every command that traces photons.
#[derive(Args, Debug, Clone, Default)]
pub struct TraceArgs {
    /// Photons to trace [default: measure and render 1 000 000, map 4 000 000, solve the
    /// problem's `photons`]. The standard error falls as 1/√N. Measurements trace
    /// whole groups of 64 photons, at least 2048; the output says how many.
    #[arg(long, short = 'n', value_name = "N")]
    pub photons: Option<u64>,
    /// Seed of the random streams: the same seed gives the same numbers on any number
    /// of threads [default: 1, solve the problem's `seed`].
    #[arg(long, value_name = "S")]
    pub seed: Option<u64>,
    /// Surface interactions followed after the first hit [default: 1000, solve the
    /// problem's `maxBounces`]. Russian roulette ends paths without bias; this is a
    /// safety cap. 4 reproduces the thesis, which under-counts light in bright rooms.
    #[arg(long, value_name = "K")]
    pub max_bounces: Option<u32>,
    /// Confidence level of the intervals and comparisons, in (0, 1) [default: 0.95,
    /// solve the problem's `confidence`].
    #[arg(long, value_name = "C")]
    pub confidence: Option<Confidence>,
    /// Worker threads [default: one per core].
    #[arg(long, short = 'j', value_name = "T")]
    pub threads: Option<usize>,
}

impl TraceArgs {
    /// The photons to trace, `default` unless given, refused when 0 or when rounding up
    /// to whole groups would overflow.
    pub fn photons(&self, default: u64) -> anyhow::Result<u64> {
        let n = photon_count(self.photons.unwrap_or(default));
        Ok(n.map_err(|e| InputError(format!("--photons {e}")))?)
    }

    /// The tracing settings with `default` photons.
    pub fn settings(&self, default: u64) -> anyhow::Result<TraceSettings> {
        Ok(TraceSettings {
            photons: self.photons(default)?,
            seed: self.seed.unwrap_or(1),
            max_bounces: self.max_bounces.unwrap_or(DEFAULT_MAX_BOUNCES),
            ..TraceSettings::default()
        })
    }

    /// The thread pool to work in.
    pub fn pool(&self) -> anyhow::Result<rayon::ThreadPool> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads.unwrap_or(0))
            .build()
            .context("starting the worker threads")
    }
}

/// What the report checks a grid against (EN 12464-1), and how it measures the grid.
#[derive(Args, Debug, Clone)]
pub struct ReportArgs {
    /// An EN 12464-1:2021 task whose Em and U0 the grid must meet: office, filing,
    /// meeting, drawing, corridor, classroom or board.
    #[arg(long, value_name = "NAME")]
    pub task: Option<String>,
    /// Required maintained mean illuminance, lx (replaces the task's).
    #[arg(long, value_name = "LX", value_parser = positive::<f64>)]
    pub em: Option<f64>,
    /// Required uniformity Emin/Eavg (replaces the task's).
    #[arg(long, value_name = "U0", value_parser = positive::<f64>)]
    pub u0: Option<f64>,
    /// Maintenance factor in (0, 1]: maintained values are MF × the computed ones
    /// [default: the problem's maintenanceFactor, else 1].
    #[arg(long, value_name = "MF")]
    pub maintenance_factor: Option<f64>,
}

/// How report.html measures the objective surface's grid.
#[derive(Args, Debug, Clone, Default)]
pub struct GridArgs {
    /// Photons of the objective surface's grid in report.html [default: 1 000 000].
    #[arg(long, value_name = "N")]
    pub report_photons: Option<u64>,
}

impl ReportArgs {
    /// These options as flags, to pass on to `invlight report`.
    pub fn flags(&self) -> Vec<String> {
        let mut flags = Vec::new();
        if let Some(task) = &self.task {
            flags.extend(["--task".to_string(), task.clone()]);
        }
        if let Some(em) = self.em {
            flags.extend(["--em".to_string(), em.to_string()]);
        }
        if let Some(u0) = self.u0 {
            flags.extend(["--u0".to_string(), u0.to_string()]);
        }
        if let Some(mf) = self.maintenance_factor {
            flags.extend(["--maintenance-factor".to_string(), mf.to_string()]);
        }
        flags
    }

    /// The requirement asked for, if any; `--maintenance-factor`, else `mf` (a
    /// problem's own, or 1).
    pub fn requirement(&self, mf: f64) -> anyhow::Result<Option<Requirement>> {
        let (t, mf) = (self.task.as_deref(), self.maintenance_factor.unwrap_or(mf));
        Ok(Requirement::from_flags(t, self.em, self.u0, mf)
            .map_err(|e| InputError(e.to_string()))?)
    }
}

impl GridArgs {
    /// These options as flags, to pass on to `invlight report`.
    pub fn flags(&self) -> Vec<String> {
        self.report_photons
            .map(|n| vec!["--report-photons".to_string(), n.to_string()])
            .unwrap_or_default()
    }

    /// The grid at EN 12464-1's spacing, traced with `seed` and the bounce cap `bounces`.
    pub fn grid(&self, seed: u64, bounces: u32) -> Grid {
        Grid::en(self.report_photons.unwrap_or(1_000_000), seed, bounces)
    }
}
