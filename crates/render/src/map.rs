//! Illuminance grids over a planar surface, as lighting standards ask for them
//! (EN 12464-1 §5.4: a regular grid of cells, Emin, Eavg, Emax and uniformity
//! U0 = Emin/Eavg). The grid and its measurement are the photon layer's
//! ([`SurfaceGrid`], [`invlight_photon::measure_with`]), the same the search's uniformity intentions
//! read: each cell's value is the luminous power the photons bring to it over its
//! covered area and N, with the standard error of the stratified photon groups, so
//! every value carries its interval, and U0's interval comes from the groups'
//! covariance of the least cell and the whole grid (the delta method).
//!
//! With [`Estimator::Connected`] every photon departure is also connected to one point
//! drawn on the whole surface, which counts for the cell it falls in: a departure costs
//! one ray whatever the number of cells. The grid is the same on any number of threads.

use glam::Vec3;
use invlight_photon::{
    Cluster, Components, Estimator, GridError, GridRequest, GridValues, Request, Side, SurfaceGrid,
    TraceSettings, behind_warning, cluster, en12464_rule, en12464_spacing, measure_across,
    photons_traced,
};
use invlight_scene::{Scene, SurfaceId};
use invlight_stats::{Confidence, Estimate};
use invlight_trace::Accel;
use serde::{Deserialize, Serialize};
use std::fmt;

/// A grid's cell size as asked: metres, or EN 12464-1's spacing for the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GridSpacing {
    /// `auto`: [`en12464_spacing`] of the surface's sides.
    Auto,
    /// The largest cell side, m: a side of length L gets ⌈L/m⌉ equal cells.
    Metres(f32),
}

/// A `--grid` that is no spacing: the text given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GridSpacingError(pub String);

impl fmt::Display for GridSpacingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "'{}' is neither 'auto' nor a positive length in metres",
            self.0
        )
    }
}

impl std::error::Error for GridSpacingError {}

impl std::str::FromStr for GridSpacing {
    type Err = GridSpacingError;
    fn from_str(s: &str) -> Result<GridSpacing, GridSpacingError> {
        if s == "auto" {
            return Ok(GridSpacing::Auto);
        }
        match s.parse::<f32>() {
            Ok(m) if m > 0.0 && m.is_finite() => Ok(GridSpacing::Metres(m)),
            _ => Err(GridSpacingError(s.to_string())),
        }
    }
}

impl GridSpacing {
    /// The grid this spacing lays on `surface`.
    pub fn grid(self, scene: &Scene, surface: SurfaceId) -> Result<SurfaceGrid, MapError> {
        match self {
            GridSpacing::Metres(m) => SurfaceGrid::new(scene, surface, m),
            GridSpacing::Auto => SurfaceGrid::en12464(scene, surface),
        }
        .map_err(MapError::Grid)
    }

    /// The largest cell side this spacing asks of `grid`, m.
    pub fn metres(self, grid: &SurfaceGrid) -> f32 {
        match self {
            GridSpacing::Metres(m) => m,
            GridSpacing::Auto => en12464_spacing(grid.size.x as f64, grid.size.y as f64) as f32,
        }
    }

    /// How this spacing chose the cells of `grid`, for a reader checking a grid as
    /// DIALux prints it: EN 12464-1's rule with its d, or the spacing asked for beside
    /// the one the rule would take (a coarser grid can hide an Emin).
    pub fn rule(self, grid: &SurfaceGrid) -> String {
        let (a, b) = (grid.size.x as f64, grid.size.y as f64);
        match self {
            GridSpacing::Auto => en12464_rule(a, b),
            GridSpacing::Metres(m) => format!(
                "{m} m as asked (EN 12464-1's grid rule would take {:.2} m)",
                en12464_spacing(a, b)
            ),
        }
    }
}

/// How to measure a grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapSettings {
    /// The cells' size.
    pub spacing: GridSpacing,
    /// The side of the surface whose light counts, against the grid's normal (the
    /// surface's area-weighted normal).
    pub side: Side,
    /// Photons, seed and bounce cap; the photons are rounded up to whole groups.
    pub trace: TraceSettings,
    /// Whether departures are connected to the surface (see the module doc).
    pub estimator: Estimator,
    /// What a cell reads: the illuminance at its centre (EN 12464-1's points, the
    /// default) or its mean.
    pub values: GridValues,
}

/// Why a grid cannot be measured.
#[derive(Debug, Clone, PartialEq)]
pub enum MapError {
    /// No grid can be laid on the surface.
    Grid(GridError),
    /// The photon count overflows when rounded up to whole groups.
    TooManyPhotons(u64),
}

impl fmt::Display for MapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MapError::Grid(e) => e.fmt(f),
            MapError::TooManyPhotons(n) => write!(f, "{n} photons cannot be traced"),
        }
    }
}

impl std::error::Error for MapError {}

/// One cell of a grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapCell {
    /// Column (along `u`) and row (along `v`).
    pub index: (u32, u32),
    /// The cell's centre in the world, m.
    pub centre: Vec3,
    /// The part of the cell the surface covers, m².
    pub area: f64,
    /// Mean illuminance over the covered part, lx, with its standard error.
    pub estimate: Estimate,
    /// Photon arrivals counted.
    pub hits: u64,
}

/// Illuminance over a grid of cells on a planar surface.
#[derive(Debug, Clone, PartialEq)]
pub struct IlluminanceMap {
    /// World position of the grid corner (u = v = 0).
    pub origin: Vec3,
    /// Unit in-plane axis of the columns.
    pub u: Vec3,
    /// Unit in-plane axis of the rows (u × v = normal).
    pub v: Vec3,
    /// Number of cells along `u`.
    pub columns: u32,
    /// Number of cells along `v`.
    pub rows: u32,
    /// Cell side along `u`, m.
    pub cell_u: f32,
    /// Cell side along `v`, m.
    pub cell_v: f32,
    /// The largest cell side asked for, m (EN 12464-1's spacing for `auto`).
    pub spacing: f32,
    /// How the spacing was chosen ([`GridSpacing::rule`]).
    pub spacing_rule: String,
    /// The side whose light was counted.
    pub side: Side,
    /// What a cell holds: the illuminance at its centre, or its mean.
    pub values: GridValues,
    /// Cells row by row (row 0 at v = 0); `None` where the surface covers no area.
    pub cells: Vec<Option<MapCell>>,
    /// Photons emitted: the settings' count rounded up to whole stratified groups.
    pub photons: u64,
    /// The mean illuminance over the covered area with its standard error: tallied
    /// from the same photons as one more cell covering all the others. Its mean is the
    /// cells' area-weighted mean; its standard error is that mean's, which the cells'
    /// own errors cannot give, as they come from the same photons and are correlated.
    pub mean: Estimate,
    /// U0 = Emin/Eavg with its standard error (the delta method over the groups).
    pub u0: Estimate,
    /// The whole surface's mean illuminance on its front and on its back, lx, whatever
    /// `side` counts: for [`IlluminanceMap::warning`].
    pub front_back: (f64, f64),
}

/// The figures of EN 12464-1 for a grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapSummary {
    /// Smallest cell mean, lx.
    pub emin: f64,
    /// Area-weighted mean of the cells: the surface's mean illuminance, lx.
    pub eavg: f64,
    /// Largest cell mean, lx.
    pub emax: f64,
    /// Uniformity Emin / Eavg (0 when Eavg is 0).
    pub u0: f64,
}

impl MapSummary {
    /// The largest ratio of two cells, Emax/Emin, as DIALux prints it beside U0 (its
    /// inverse is the diversity g2 = Emin/Emax); none when Emin is 0.
    pub fn max_ratio(&self) -> Option<f64> {
        (self.emin > 0.0).then(|| self.emax / self.emin)
    }
}

/// Measures the illuminance over the grid `settings.spacing` lays on the planar
/// surface `surface`: every photon arrival on the side `settings.side` counts (every
/// bounce, as in `invlight_photon::measure`). `progress` receives photons traced.
pub fn illuminance_map(
    scene: &Scene,
    accel: &Accel,
    surface: SurfaceId,
    settings: &MapSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<IlluminanceMap, MapError> {
    illuminance_map_across(scene, accel, surface, settings, progress, cluster())
}

/// [`illuminance_map`] traced by the processes of `cluster`, which must all ask for it
/// (`invlight map` on K ranks); what one process does alone, as rank 0 writing a
/// solve's report after the others ended, is traced with [`invlight_photon::Alone`].
pub fn illuminance_map_across(
    scene: &Scene,
    accel: &Accel,
    surface: SurfaceId,
    settings: &MapSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    cluster: &dyn Cluster,
) -> Result<IlluminanceMap, MapError> {
    let target = MapTarget {
        surface,
        spacing: settings.spacing,
        side: settings.side,
    };
    let mut maps = illuminance_maps_across(scene, accel, &[target], settings, progress, cluster)?;
    Ok(maps.remove(0))
}

/// A surface to map with its grid and side, one of several measured by one trace.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapTarget {
    /// The planar surface.
    pub surface: SurfaceId,
    /// Its cells' size.
    pub spacing: GridSpacing,
    /// The side whose light counts.
    pub side: Side,
}

/// The maps of `targets` from one trace with `settings`' photons and estimator (its
/// spacing and side are the targets' own), in their order: a task area and the areas
/// around it are measured by the same photons, as one map is.
pub fn illuminance_maps_across(
    scene: &Scene,
    accel: &Accel,
    targets: &[MapTarget],
    settings: &MapSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    cluster: &dyn Cluster,
) -> Result<Vec<IlluminanceMap>, MapError> {
    let both = MapsAndMeans {
        targets,
        means: &[],
    };
    Ok(illuminance_maps_and_means(scene, accel, &both, settings, progress, cluster)?.0)
}

/// Surfaces one trace measures: some mapped on grids, some read as a whole.
#[derive(Debug, Clone, Copy)]
pub struct MapsAndMeans<'a> {
    /// The surfaces mapped, each on its grid.
    pub targets: &'a [MapTarget],
    /// The surfaces whose mean illuminance on their front is read, not mapped (the
    /// cylindrical illuminance's prisms, which no plane holds).
    pub means: &'a [SurfaceId],
}

/// [`illuminance_maps_across`] of `what.targets`, and the mean illuminance on the
/// front of each of `what.means`, from the same photons.
pub fn illuminance_maps_and_means(
    scene: &Scene,
    accel: &Accel,
    what: &MapsAndMeans,
    settings: &MapSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    cluster: &dyn Cluster,
) -> Result<(Vec<IlluminanceMap>, Vec<Estimate>), MapError> {
    let targets = what.targets;
    let grids = targets
        .iter()
        .map(|t| t.spacing.grid(scene, t.surface))
        .collect::<Result<Vec<_>, _>>()?;
    photons_traced(settings.trace.photons)
        .ok_or(MapError::TooManyPhotons(settings.trace.photons))?;
    let surfaces: Vec<SurfaceId> = targets
        .iter()
        .map(|t| t.surface)
        .chain(what.means.iter().copied())
        .collect();
    let components = Components::one(scene);
    let request = Request {
        surfaces: &surfaces,
        grids: grids
            .iter()
            .zip(targets)
            .enumerate()
            .map(|(i, (grid, t))| GridRequest {
                target: i,
                side: t.side,
                grid: grid.clone(),
                values: settings.values,
            })
            .collect(),
        components: &components,
        estimator: settings.estimator,
        keep_groups: false,
        observers: Vec::new(),
    };
    let measured = measure_across(scene, accel, &request, &settings.trace, progress, cluster);
    let w = [1.0];
    let maps = targets
        .iter()
        .enumerate()
        .map(|(t, target)| {
            let g = &measured.grids[t];
            let grid = &g.grid;
            let cells = (0..grid.cells())
                .map(|i| {
                    g.cell(i, &w).map(|estimate| MapCell {
                        index: grid.index(i),
                        centre: grid.centre(i),
                        area: grid.areas[i],
                        estimate,
                        hits: g.hits(i),
                    })
                })
                .collect();
            let uniformity = g.uniformity(&w);
            let side = |s| measured.estimate_of(t, s, &w).mean;
            IlluminanceMap {
                origin: grid.origin,
                u: grid.u,
                v: grid.v,
                columns: grid.columns,
                rows: grid.rows,
                cell_u: grid.cell_u,
                cell_v: grid.cell_v,
                spacing: target.spacing.metres(grid),
                spacing_rule: target.spacing.rule(grid),
                side: target.side,
                values: settings.values,
                cells,
                photons: measured.photons,
                mean: uniformity.average,
                u0: uniformity.u0,
                front_back: (side(Side::Front), side(Side::Back)),
            }
        })
        .collect();
    let means = (0..what.means.len())
        .map(|i| measured.estimate_of(targets.len() + i, Side::Front, &w))
        .collect();
    Ok((maps, means))
}

/// A cell of `invlight map --json`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MapPoint {
    /// The cell's centre, m.
    pub position: [f32; 3],
    /// Mean illuminance over the part the surface covers, lx.
    pub mean: f64,
    /// Lower end of its interval, lx.
    pub low: f64,
    /// Upper end, lx.
    pub high: f64,
}

/// `invlight map --json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MapReport {
    /// The surface mapped.
    pub surface: String,
    /// The largest cell side asked for, m (EN 12464-1's spacing for `--grid auto`).
    pub cell: f32,
    /// How that cell side was chosen: EN 12464-1's rule with its d, or the spacing
    /// asked for beside the rule's.
    #[serde(default)]
    pub spacing_rule: String,
    /// The side whose light counts: `front`, `back` or `both`.
    pub side: String,
    /// The cells' sides along u and v, m.
    pub cell_size: [f32; 2],
    /// Columns and rows.
    pub cells: [u32; 2],
    /// Photons traced.
    pub photons: u64,
    /// How departures were counted: `connected` or `arrivals`.
    pub estimator: String,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// Seconds of the trace.
    pub seconds: f64,
    /// The cells the surface covers, row by row.
    pub points: Vec<MapPoint>,
    /// EN 12464-1's figures over the cells, lx (U0 a ratio).
    pub emin: f64,
    /// Area-weighted mean.
    pub eavg: f64,
    /// Standard error of Eavg: that of the whole surface's estimate
    /// ([`IlluminanceMap::mean`]).
    pub eavg_std_error: f64,
    /// Largest cell mean.
    pub emax: f64,
    /// Emax / Emin; absent when Emin is 0.
    #[serde(default)]
    pub emax_over_emin: Option<f64>,
    /// Emin / Eavg.
    pub u0: f64,
    /// Standard error of U0 (the delta method over the photon groups).
    pub u0_std_error: f64,
    /// EN 12464-1's areas around the surface (`--task`), each with its verdict: the
    /// immediate surrounding, the background, the walls and the ceiling.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub areas: Vec<crate::AreaReport>,
    /// EN 12464-1's cylindrical illuminance over the task area and its surrounding
    /// (`--task` of a task with an Ēz), with its verdict.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cylindrical: Option<crate::CylindricalReport>,
    /// With areas, the verdict on the task area and every area around it together:
    /// the worst of theirs (`fails` if one fails, else `cannot tell` if one cannot be
    /// told, else `meets`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overall: Option<String>,
}

/// A row of the map's CSV: one cell.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MapCsvRow {
    /// Column (along u).
    pub column: u32,
    /// Row (along v).
    pub row: u32,
    /// The cell's centre, m.
    pub x: f32,
    /// ″
    pub y: f32,
    /// ″
    pub z: f32,
    /// The part the surface covers, m².
    pub area: f64,
    /// Mean illuminance, lx.
    pub mean: f64,
    /// Lower end of its interval, lx.
    pub low: f64,
    /// Upper end, lx.
    pub high: f64,
    /// Standard error of the mean, lx.
    pub std_error: f64,
    /// Photon arrivals counted.
    pub hits: u64,
}

impl MapReport {
    /// The report's figures for people: the grid, Emin, Eavg, Emax and U0.
    pub fn summary(&self) -> String {
        use invlight_stats::significant;
        let z = Confidence::new(self.confidence).unwrap_or_default().z();
        let u0 = Estimate {
            mean: self.u0,
            std_error: self.u0_std_error,
            samples: self.photons,
        }
        .interval(z);
        let ratio = match self.emax_over_emin {
            Some(r) => format!("{r:.2}"),
            None => "∞ (Emin 0)".into(),
        };
        let rule = if self.spacing_rule.is_empty() {
            String::new()
        } else {
            format!("grid: {}\n", self.spacing_rule)
        };
        format!(
            "{}: {}×{} cells of {:.3}×{:.3} m, {} photons, {:.2} s\n{rule}Emin {} lx  Eavg {} lx  Emax {} lx  U0 = Emin/Eavg {:.3} [{:.3}, {:.3}]  Emax/Emin {ratio}\n",
            self.surface,
            self.cells[0],
            self.cells[1],
            self.cell_size[0],
            self.cell_size[1],
            self.photons,
            self.seconds,
            significant(self.emin),
            significant(self.eavg),
            significant(self.emax),
            self.u0,
            u0.low.max(0.0),
            u0.high
        )
    }
}

impl IlluminanceMap {
    /// A warning when both sides are counted and much of the light arrives on the back
    /// ([`behind_warning`]).
    pub fn warning(&self, surface: &str) -> Option<String> {
        let (front, back) = self.front_back;
        behind_warning(surface, self.side.name(), front, back)
    }

    /// The CSV rows of the cells the surface covers, intervals at `confidence`.
    pub fn csv_rows(&self, confidence: Confidence) -> Vec<MapCsvRow> {
        let z = confidence.z();
        self.cells
            .iter()
            .flatten()
            .map(|cell| {
                let e = cell.estimate;
                let i = e.interval(z);
                MapCsvRow {
                    column: cell.index.0,
                    row: cell.index.1,
                    x: cell.centre.x,
                    y: cell.centre.y,
                    z: cell.centre.z,
                    area: cell.area,
                    mean: e.mean,
                    low: i.low,
                    high: i.high,
                    std_error: e.std_error,
                    hits: cell.hits,
                }
            })
            .collect()
    }

    /// Writes the CSV rows to `path`.
    pub fn write_csv(&self, path: &std::path::Path, confidence: Confidence) -> csv::Result<()> {
        let mut w = csv::Writer::from_path(path)?;
        for row in self.csv_rows(confidence) {
            w.serialize(row)?;
        }
        w.flush()?;
        Ok(())
    }

    /// The `--json` report of this map of `surface` (asked for with `settings`), traced
    /// in `seconds`.
    pub fn report(
        &self,
        surface: &str,
        settings: &MapSettings,
        confidence: Confidence,
        seconds: f64,
    ) -> MapReport {
        let summary = self.summary();
        let points = self
            .csv_rows(confidence)
            .into_iter()
            .map(|r| MapPoint {
                position: [r.x, r.y, r.z],
                mean: r.mean,
                low: r.low,
                high: r.high,
            })
            .collect();
        MapReport {
            surface: surface.to_string(),
            cell: self.spacing,
            spacing_rule: self.spacing_rule.clone(),
            side: self.side.name().into(),
            cell_size: [self.cell_u, self.cell_v],
            cells: [self.columns, self.rows],
            photons: self.photons,
            estimator: settings.estimator.name().into(),
            confidence: confidence.level(),
            seconds,
            points,
            emin: summary.emin,
            eavg: summary.eavg,
            eavg_std_error: self.mean.std_error,
            emax: summary.emax,
            emax_over_emin: summary.max_ratio(),
            u0: summary.u0,
            u0_std_error: self.u0.std_error,
            areas: Vec::new(),
            cylindrical: None,
            overall: None,
        }
    }

    /// Emin, Eavg, Emax and U0 over the cells. Emin and Emax are taken over the cells the
    /// surface covers at least half of: a sliver's estimate rests on few photons and
    /// would decide the extremes by noise.
    pub fn summary(&self) -> MapSummary {
        let full = (self.cell_u * self.cell_v) as f64;
        let (mut emin, mut emax) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut sum, mut area) = (0.0, 0.0);
        for c in self.cells.iter().flatten() {
            sum += c.estimate.mean * c.area;
            area += c.area;
            if c.area >= 0.5 * full {
                emin = emin.min(c.estimate.mean);
                emax = emax.max(c.estimate.mean);
            }
        }
        // Read at points, Eavg is the points' mean as the measurement made it; of cell
        // means, their area-weighted mean.
        let eavg = match self.values {
            GridValues::Points => self.mean.mean,
            GridValues::CellMeans | GridValues::Indirect if area > 0.0 => sum / area,
            GridValues::CellMeans | GridValues::Indirect => 0.0,
        };
        if emin > emax {
            (emin, emax) = (eavg, eavg);
        }
        MapSummary {
            emin,
            eavg,
            emax,
            u0: if eavg > 0.0 { emin / eavg } else { 0.0 },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_spacings_parse() {
        assert_eq!("auto".parse::<GridSpacing>(), Ok(GridSpacing::Auto));
        assert_eq!("0.5".parse::<GridSpacing>(), Ok(GridSpacing::Metres(0.5)));
        assert!("-1".parse::<GridSpacing>().is_err());
        assert!("NaN".parse::<GridSpacing>().is_err());
    }
}
