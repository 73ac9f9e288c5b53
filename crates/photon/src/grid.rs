//! Grids of cells over a planar surface, as lighting standards read illuminance
//! (EN 12464-1 §5.4: a regular grid, Emin, Eavg, Emax and uniformity U0 = Emin/Eavg):
//! the plane, its axes, the cells and the part of each the surface covers. A
//! measurement ([`crate::measure_with`]) tallies photons per cell; `invlight map` and
//! the search's uniformity intentions read them.

use glam::{Vec2, Vec3};
use invlight_scene::{Scene, SurfaceId};
use std::fmt;

/// The most cells a grid may have: a million cells of a few photons each measure
/// nothing.
pub const MAX_CELLS: u64 = 1 << 20;

pub use invlight_scene::en12464::{en12464_rule, en12464_spacing};

/// Why a grid cannot be laid on a surface.
#[derive(Debug, Clone, PartialEq)]
pub enum GridError {
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
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GridError::Empty => write!(f, "the surface has no area"),
            GridError::NotPlanar { deviation } => write!(
                f,
                "the surface is not planar: a vertex lies {deviation} m from its plane"
            ),
            GridError::BadCell(c) => write!(f, "the cell size {c} is not a positive length"),
            GridError::TooManyCells(n) => write!(
                f,
                "the grid would have {n} cells (at most {MAX_CELLS}): choose larger cells"
            ),
        }
    }
}

impl std::error::Error for GridError {}

/// A grid over a planar surface: cells of `cell_u × cell_v` metres along the in-plane
/// axes `u` (columns) and `v` (rows) from `origin`, u × v the surface's (area-weighted
/// mean) normal, so a cell's front is the side that normal faces.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceGrid {
    /// The surface.
    pub surface: SurfaceId,
    /// World position of the grid corner (u = v = 0).
    pub origin: Vec3,
    /// Unit in-plane axis of the columns.
    pub u: Vec3,
    /// Unit in-plane axis of the rows.
    pub v: Vec3,
    /// Unit normal, u × v.
    pub normal: Vec3,
    /// Cells along `u`.
    pub columns: u32,
    /// Cells along `v`.
    pub rows: u32,
    /// Cell side along `u`, m.
    pub cell_u: f32,
    /// Cell side along `v`, m.
    pub cell_v: f32,
    /// The part of each cell the surface covers, m², row by row (row 0 at v = 0).
    pub areas: Vec<f64>,
    /// The surface's extent along u and v, m.
    pub size: Vec2,
}

/// The surface's plane: a point, unit normal and in-plane axes, with its triangles in
/// plane coordinates.
struct Plane {
    origin: Vec3,
    u: Vec3,
    v: Vec3,
    normal: Vec3,
    size: Vec2,
    triangles: Vec<[Vec2; 3]>,
}

fn plane_of(scene: &Scene, surface: SurfaceId) -> Result<Plane, GridError> {
    let mut tris: Vec<[Vec3; 3]> = Vec::new();
    let calculation = scene.is_calculation_surface(surface);
    for &i in &scene.surfaces[surface].instances {
        // Holes are left out: photons pass through them, so they hold no light. A
        // calculation surface receives on every triangle, whatever its material.
        tris.extend(
            scene
                .world_triangles(i)
                .filter(|t| calculation || !scene.materials[t.material].hole)
                .map(|t| t.corners),
        );
    }
    let cross = |t: &[Vec3; 3]| (t[1] - t[0]).cross(t[2] - t[0]);
    let largest = tris
        .iter()
        .map(cross)
        .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
        .filter(|c| c.length_squared() > 0.0)
        .ok_or(GridError::Empty)?;
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
        return Err(GridError::NotPlanar { deviation });
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
        normal: n,
        size: hi2 - lo2,
        triangles,
    })
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

impl SurfaceGrid {
    /// A grid of cells at most `cell` wide over the planar surface `surface`.
    pub fn new(scene: &Scene, surface: SurfaceId, cell: f32) -> Result<SurfaceGrid, GridError> {
        if !(cell > 0.0 && cell.is_finite()) {
            return Err(GridError::BadCell(cell));
        }
        let plane = plane_of(scene, surface)?;
        SurfaceGrid::on(plane, surface, cell)
    }

    /// The grid EN 12464-1 lays on the surface ([`en12464_spacing`]).
    pub fn en12464(scene: &Scene, surface: SurfaceId) -> Result<SurfaceGrid, GridError> {
        let plane = plane_of(scene, surface)?;
        let p = en12464_spacing(plane.size.x as f64, plane.size.y as f64) as f32;
        SurfaceGrid::on(plane, surface, p)
    }

    fn on(plane: Plane, surface: SurfaceId, cell: f32) -> Result<SurfaceGrid, GridError> {
        let columns = ((plane.size.x / cell).ceil() as u64).max(1);
        let rows = ((plane.size.y / cell).ceil() as u64).max(1);
        if columns * rows > MAX_CELLS {
            return Err(GridError::TooManyCells(columns * rows));
        }
        let (columns, rows) = (columns as u32, rows as u32);
        let size = Vec2::new(plane.size.x / columns as f32, plane.size.y / rows as f32)
            .max(Vec2::splat(f32::MIN_POSITIVE));
        let mut areas = vec![0.0f64; (columns * rows) as usize];
        for t in &plane.triangles {
            let lo = t[0].min(t[1]).min(t[2]);
            let hi = t[0].max(t[1]).max(t[2]);
            let c0 = ((lo.x / size.x).floor().max(0.0) as u32).min(columns - 1);
            let c1 = ((hi.x / size.x).floor().max(0.0) as u32).min(columns - 1);
            let r0 = ((lo.y / size.y).floor().max(0.0) as u32).min(rows - 1);
            let r1 = ((hi.y / size.y).floor().max(0.0) as u32).min(rows - 1);
            for r in r0..=r1 {
                for c in c0..=c1 {
                    let a = Vec2::new(c as f32, r as f32) * size;
                    areas[(r * columns + c) as usize] += clipped_area(t, a, a + size);
                }
            }
        }
        Ok(SurfaceGrid {
            surface,
            origin: plane.origin,
            u: plane.u,
            v: plane.v,
            normal: plane.normal,
            columns,
            rows,
            cell_u: size.x,
            cell_v: size.y,
            areas,
            size: plane.size,
        })
    }

    /// The number of cells.
    pub fn cells(&self) -> usize {
        self.areas.len()
    }

    /// The cell a point of the surface falls in (points outside are clamped to the
    /// nearest cell).
    #[inline]
    pub fn cell_of(&self, p: Vec3) -> usize {
        let d = p - self.origin;
        let c = ((d.dot(self.u) / self.cell_u) as i64).clamp(0, self.columns as i64 - 1);
        let r = ((d.dot(self.v) / self.cell_v) as i64).clamp(0, self.rows as i64 - 1);
        (r * self.columns as i64 + c) as usize
    }

    /// Column and row of cell `i`.
    pub fn index(&self, i: usize) -> (u32, u32) {
        (i as u32 % self.columns, i as u32 / self.columns)
    }

    /// The world centre of cell `i`.
    pub fn centre(&self, i: usize) -> Vec3 {
        let (c, r) = self.index(i);
        self.origin
            + self.u * ((c as f32 + 0.5) * self.cell_u)
            + self.v * ((r as f32 + 0.5) * self.cell_v)
    }

    /// Whether cell `i` counts toward Emin and Emax: the surface covers at least half of
    /// it (a sliver's estimate rests on few photons and would decide the extremes by
    /// noise).
    pub fn is_full(&self, i: usize) -> bool {
        self.areas[i] >= 0.5 * (self.cell_u * self.cell_v) as f64
    }

    /// Whether cell `i` holds any surface (a sliver below a millionth of the cell is
    /// rounding, not surface).
    pub fn is_covered(&self, i: usize) -> bool {
        self.areas[i] > 1e-6 * (self.cell_u * self.cell_v) as f64
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

    /// EN 12464-1's published spacings, and the shorter side for long thin areas.
    #[test]
    fn the_standards_grid_spacings() {
        for (d, p) in [(1.0, 0.2), (5.0, 0.6), (10.0, 1.0), (100.0, 5.0)] {
            let got = en12464_spacing(d, d);
            assert!((got - p).abs() < 0.03 * p, "{d} m: {got}, EN gives {p}");
        }
        // A 20 m × 2 m corridor is spaced by its width: 0.2·5^log10(2) ≈ 0.32 m.
        assert!((en12464_spacing(20.0, 2.0) - 0.2 * 5f64.powf(2f64.log10())).abs() < 1e-12);
        assert_eq!(en12464_spacing(1e6, 1e6), 10.0);
        assert_eq!(
            en12464_rule(7.2, 4.8),
            format!(
                "EN 12464-1's grid rule: p = 0.2 × 5^log10(d) = {:.2} m, d = 7.20 m (the longer side)",
                0.2 * 5f64.powf(7.2f64.log10())
            )
        );
        assert!(en12464_rule(1.6, 0.8).contains("d = 0.80 m (the shorter side"));
        assert!(en12464_rule(1e6, 1e6).contains("= 10.00 m, at most 10 m"));
        // Exactly 2:1 is spaced by the shorter side, rounding aside.
        let p = en12464_spacing(1.5999999, 0.8000001);
        assert!((p - 0.2 * 5f64.powf(0.8f64.log10())).abs() < 1e-6, "{p}");
    }
}
