//! Illuminance grids over a planar surface, as lighting standards ask for them
//! (EN 12464-1 §4.4: a regular grid of cells, Emin, Eavg, Emax and uniformity
//! U0 = Emin/Eavg). Each cell's value is the mean illuminance over the cell, measured
//! as `invlight_photon::measure` measures a surface: the luminous power the photons
//! bring to it over its area and N, with the standard error of the contributions of the
//! stratified photon groups, so every value carries its interval.
//!
//! With [`Estimator::Connected`] every photon departure is connected to one point drawn
//! uniformly on the whole surface ([`Targets::connect`]), which counts for the cell the
//! point falls in; arrivals are weighted against it by the same balance heuristic. The
//! weights sum to one at every point of the surface, so each cell's estimate stays
//! unbiased, and a departure costs one ray whatever the number of cells (a ray per cell
//! would make a 20 × 20 grid cost 400).
//!
//! Photons are traced by `invlight_photon::trace_chunks`, each chunk tallied on its own
//! and the tallies added in chunk order: the grid is the same on any number of threads.

use glam::{Vec2, Vec3};
use invlight_photon::{
    Departure, Emitters, Estimator, GroupTallies, PathVisitor, Sampler, Tally, Targets,
    TraceSettings, photons_traced, trace_chunks,
};
use invlight_scene::{Rgb, Scene, SurfaceId, luminance};
use invlight_stats::{Confidence, Estimate};
use invlight_trace::{Accel, Interaction};
use serde::{Deserialize, Serialize};
use std::fmt;

/// How to measure a grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapSettings {
    /// Largest cell side, m: a side of length L gets ⌈L/cell⌉ equal cells (EN 12464-1
    /// spaces its points so).
    pub cell: f32,
    /// Photons, seed and bounce cap; the photons are rounded up to whole groups.
    pub trace: TraceSettings,
    /// Whether departures are connected to the surface (see the module doc).
    pub estimator: Estimator,
}

/// Why a grid cannot be measured.
#[derive(Debug, Clone, PartialEq)]
pub enum MapError {
    /// The surface has no area.
    Empty,
    /// A vertex lies this far (m) from the surface's plane.
    NotPlanar {
        /// Largest distance of a vertex from the plane, m.
        deviation: f32,
    },
    /// The cell size is not a positive length.
    BadCell(f32),
    /// The grid would have this many cells (more than [`MAX_CELLS`]).
    TooManyCells(u64),
    /// The photon count overflows when rounded up to whole groups.
    TooManyPhotons(u64),
}

/// The most cells a grid may have: a million cells of a few photons each measure
/// nothing.
pub const MAX_CELLS: u64 = 1 << 20;

impl fmt::Display for MapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MapError::Empty => write!(f, "the surface has no area"),
            MapError::NotPlanar { deviation } => write!(
                f,
                "the surface is not planar: a vertex lies {deviation} m from its plane"
            ),
            MapError::BadCell(c) => write!(f, "the cell size {c} is not a positive length"),
            MapError::TooManyCells(n) => write!(
                f,
                "the grid would have {n} cells (at most {MAX_CELLS}): choose larger cells"
            ),
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
    /// Cells row by row (row 0 at v = 0); `None` where the surface covers no area.
    pub cells: Vec<Option<MapCell>>,
    /// Photons emitted: the settings' count rounded up to whole stratified groups.
    pub photons: u64,
    /// The mean illuminance over the whole surface with its standard error: tallied
    /// from the same photons as one more cell covering all the others, exactly as
    /// `invlight_photon::measure` measures the surface. Its mean is the cells'
    /// area-weighted mean; its standard error is that mean's, which the cells' own
    /// errors cannot give, as they come from the same photons and are correlated.
    pub mean: Estimate,
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

/// The surface's plane: a point, unit normal and in-plane axes, with its triangles in
/// plane coordinates.
struct Plane {
    origin: Vec3,
    u: Vec3,
    v: Vec3,
    size: Vec2,
    triangles: Vec<[Vec2; 3]>,
}

fn plane_of(scene: &Scene, surface: SurfaceId) -> Result<Plane, MapError> {
    let mut tris: Vec<[Vec3; 3]> = Vec::new();
    for &i in &scene.surfaces[surface].instances {
        let inst = &scene.instances[i];
        let mesh = &scene.meshes[inst.mesh];
        for t in 0..mesh.triangles.len() {
            tris.push(mesh.triangle(t).map(|p| inst.transform.transform_point3(p)));
        }
    }
    let cross = |t: &[Vec3; 3]| (t[1] - t[0]).cross(t[2] - t[0]);
    let largest = tris
        .iter()
        .map(cross)
        .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
        .filter(|c| c.length_squared() > 0.0)
        .ok_or(MapError::Empty)?;
    // Area-weighted normal, every triangle turned to agree with the largest.
    let sum: Vec3 = tris
        .iter()
        .map(|t| {
            let c = cross(t);
            if c.dot(largest) < 0.0 { -c } else { c }
        })
        .sum();
    let n = sum.normalize();
    let p0 = tris[0][0];
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let mut deviation = 0.0f32;
    for t in &tris {
        for &p in t {
            deviation = deviation.max((p - p0).dot(n).abs());
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    let extent = (hi - lo).length();
    if deviation > 1e-4 * extent + 1e-6 {
        return Err(MapError::NotPlanar { deviation });
    }
    // Columns along the world axis closest to the plane, so floors and walls get
    // axis-aligned grids.
    let axis = [Vec3::X, Vec3::Y, Vec3::Z]
        .into_iter()
        .min_by(|a, b| a.dot(n).abs().total_cmp(&b.dot(n).abs()))
        .unwrap_or(Vec3::X);
    let u = (axis - n * axis.dot(n)).normalize();
    let v = n.cross(u);
    let (mut lo2, mut hi2) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for t in &tris {
        for &p in t {
            let q = Vec2::new((p - p0).dot(u), (p - p0).dot(v));
            lo2 = lo2.min(q);
            hi2 = hi2.max(q);
        }
    }
    let origin = p0 + u * lo2.x + v * lo2.y;
    let triangles = tris
        .iter()
        .map(|t| t.map(|p| Vec2::new((p - origin).dot(u), (p - origin).dot(v))))
        .collect();
    Ok(Plane {
        origin,
        u,
        v,
        size: hi2 - lo2,
        triangles,
    })
}

/// The sides (along the grid's u and v) of the rectangle a planar surface's grid
/// covers, m: what EN 12464-1's grid rule is applied to.
pub fn surface_extent(scene: &Scene, surface: SurfaceId) -> Result<(f32, f32), MapError> {
    let plane = plane_of(scene, surface)?;
    Ok((plane.size.x, plane.size.y))
}

/// Area of the part of triangle `t` inside the rectangle [lo, hi] (Sutherland–Hodgman
/// clipping, then the shoelace formula).
fn clipped_area(t: &[Vec2; 3], lo: Vec2, hi: Vec2) -> f64 {
    let mut poly: Vec<Vec2> = t.to_vec();
    let planes: [(Vec2, f32); 4] = [
        (Vec2::X, lo.x),
        (Vec2::NEG_X, -hi.x),
        (Vec2::Y, lo.y),
        (Vec2::NEG_Y, -hi.y),
    ];
    for (n, d) in planes {
        let mut out = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (da, db) = (a.dot(n) - d, b.dot(n) - d);
            if da >= 0.0 {
                out.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                out.push(a + (b - a) * (da / (da - db)));
            }
        }
        poly = out;
        if poly.is_empty() {
            return 0.0;
        }
    }
    let mut twice = 0.0f64;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        twice += a.x as f64 * b.y as f64 - b.x as f64 * a.y as f64;
    }
    0.5 * twice.abs()
}

/// The grid's geometry: which instances count, and how a point maps to a cell.
struct Grid<'a> {
    on_surface: &'a [bool],
    origin: Vec3,
    u: Vec3,
    v: Vec3,
    inv_cell: Vec2,
    columns: u32,
    rows: u32,
    /// The tally of the whole surface, after the cells'.
    whole: u32,
}

impl Grid<'_> {
    #[inline]
    fn cell(&self, p: Vec3) -> usize {
        let d = p - self.origin;
        let c = ((d.dot(self.u) * self.inv_cell.x) as i64).clamp(0, self.columns as i64 - 1);
        let r = ((d.dot(self.v) * self.inv_cell.y) as i64).clamp(0, self.rows as i64 - 1);
        (r * self.columns as i64 + c) as usize
    }
}

/// One chunk's per-cell tallies.
struct CellTally<'a> {
    grid: &'a Grid<'a>,
    /// The surface as one target to connect departures to; `None` counts arrivals alone.
    connect: Option<(&'a Targets, &'a Accel)>,
    tallies: GroupTallies,
}

impl PathVisitor for CellTally<'_> {
    #[inline]
    fn depart(&mut self, from: &Departure, sampler: &mut Sampler<'_>) {
        if let Some((surface, accel)) = self.connect
            && let Some(c) = surface.connect(0, from, accel, sampler)
        {
            let cell = self.grid.cell(c.point);
            self.tallies.add(cell as u32, c.lumens);
            self.tallies.add(self.grid.whole, c.lumens);
        }
    }

    #[inline]
    fn arrive(&mut self, at: &Interaction, _dir: Vec3, power: Rgb, _bounce: u32, from: &Departure) {
        if !self.grid.on_surface[at.instance.index()] {
            return;
        }
        let w = match self.connect {
            Some((surface, _)) => {
                surface.arrival_weight(0, from.arrival_density(at.point, at.normal))
            }
            None => 1.0,
        };
        let c = self.grid.cell(at.point);
        let lumens = (luminance(power) * w) as f64;
        self.tallies.arrive(c as u32, lumens);
        self.tallies.arrive(self.grid.whole, lumens);
    }

    #[inline]
    fn escape(&mut self, _power: Rgb) {}

    #[inline]
    fn end_group(&mut self) {
        self.tallies.end_group();
    }
}

/// Measures the illuminance over a grid of cells at most `settings.cell` wide on the
/// planar surface `surface`. Every photon arrival on the surface counts (either side,
/// every bounce, as in `invlight_photon::measure`). `progress` receives photons traced.
pub fn illuminance_map(
    scene: &Scene,
    accel: &Accel,
    surface: SurfaceId,
    settings: &MapSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<IlluminanceMap, MapError> {
    if !(settings.cell > 0.0 && settings.cell.is_finite()) {
        return Err(MapError::BadCell(settings.cell));
    }
    let plane = plane_of(scene, surface)?;
    let columns = ((plane.size.x / settings.cell).ceil() as u64).max(1);
    let rows = ((plane.size.y / settings.cell).ceil() as u64).max(1);
    if columns * rows > MAX_CELLS {
        return Err(MapError::TooManyCells(columns * rows));
    }
    let (columns, rows) = (columns as u32, rows as u32);
    let cell = Vec2::new(plane.size.x / columns as f32, plane.size.y / rows as f32)
        .max(Vec2::splat(f32::MIN_POSITIVE));
    let n_cells = (columns * rows) as usize;
    let mut areas = vec![0.0f64; n_cells];
    for t in &plane.triangles {
        let lo = t[0].min(t[1]).min(t[2]);
        let hi = t[0].max(t[1]).max(t[2]);
        let c0 = ((lo.x / cell.x).floor().max(0.0) as u32).min(columns - 1);
        let c1 = ((hi.x / cell.x).floor().max(0.0) as u32).min(columns - 1);
        let r0 = ((lo.y / cell.y).floor().max(0.0) as u32).min(rows - 1);
        let r1 = ((hi.y / cell.y).floor().max(0.0) as u32).min(rows - 1);
        for r in r0..=r1 {
            for c in c0..=c1 {
                let a = Vec2::new(c as f32, r as f32) * cell;
                areas[(r * columns + c) as usize] += clipped_area(t, a, a + cell);
            }
        }
    }
    let mut on_surface = vec![false; scene.instances.len()];
    for &i in &scene.surfaces[surface].instances {
        on_surface[i.index()] = true;
    }
    let grid = Grid {
        on_surface: &on_surface,
        origin: plane.origin,
        u: plane.u,
        v: plane.v,
        inv_cell: Vec2::ONE / cell,
        columns,
        rows,
        whole: n_cells as u32,
    };
    let mut totals = vec![Tally::default(); n_cells + 1];
    let emitters = Emitters::new(scene);
    // Whole stratified groups, as for surfaces: each cell's standard error comes from the
    // spread of the group totals.
    let photons = photons_traced(settings.trace.photons)
        .ok_or(MapError::TooManyPhotons(settings.trace.photons))?;
    let trace = TraceSettings {
        photons,
        ..settings.trace
    };
    let whole = Targets::new(scene, &[surface]);
    trace_chunks(
        scene,
        accel,
        &emitters,
        &trace,
        || CellTally {
            grid: &grid,
            connect: (settings.estimator == Estimator::Connected).then_some((&whole, accel)),
            tallies: GroupTallies::new(n_cells + 1),
        },
        |part| part.tallies.add_to(&mut totals),
        progress,
    );
    let cells = (0..n_cells)
        .map(|i| {
            let area = areas[i];
            // A sliver below a millionth of the cell is rounding, not surface.
            if area <= 1e-6 * (cell.x * cell.y) as f64 {
                return None;
            }
            let (c, r) = (i as u32 % columns, i as u32 / columns);
            let t = &totals[i];
            let centre = plane.origin
                + plane.u * ((c as f32 + 0.5) * cell.x)
                + plane.v * ((r as f32 + 0.5) * cell.y);
            Some(MapCell {
                index: (c, r),
                centre,
                area,
                estimate: t.estimate(area, photons, emitters.total_flux()),
                hits: t.hits,
            })
        })
        .collect();
    let area: f64 = areas.iter().sum();
    let mean = totals[n_cells].estimate(area, photons, emitters.total_flux());
    Ok(IlluminanceMap {
        mean,
        origin: plane.origin,
        u: plane.u,
        v: plane.v,
        columns,
        rows,
        cell_u: cell.x,
        cell_v: cell.y,
        cells,
        photons,
    })
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
    /// The largest cell side asked for, m.
    pub cell: f32,
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
    /// Emin / Eavg.
    pub u0: f64,
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
        format!(
            "{}: {}×{} cells of {:.3}×{:.3} m, {} photons, {:.2} s\nEmin {} lx  Eavg {} lx  Emax {} lx  U0 = Emin/Eavg {:.3}\n",
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
            self.u0
        )
    }
}

impl IlluminanceMap {
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
            cell: settings.cell,
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
            u0: summary.u0,
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
        let eavg = if area > 0.0 { sum / area } else { 0.0 };
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
    fn clipping_gives_the_covered_area() {
        let t = [Vec2::ZERO, Vec2::new(2.0, 0.0), Vec2::new(0.0, 2.0)];
        // Whole unit square inside the triangle's corner: area 1.
        assert!((clipped_area(&t, Vec2::ZERO, Vec2::ONE) - 1.0).abs() < 1e-9);
        // The square [1,2]² touches the triangle only along its hypotenuse corner.
        assert!(clipped_area(&t, Vec2::ONE, Vec2::splat(2.0)).abs() < 1e-9);
        // A square straddling the hypotenuse: half of [0.5,1.5]² lies below x + y = 2.
        assert!((clipped_area(&t, Vec2::splat(0.5), Vec2::splat(1.5)) - 0.5).abs() < 1e-6);
    }
}
