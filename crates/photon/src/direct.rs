//! Direct light at the points of a grid, computed rather than traced, as EN 12464-1
//! reads a grid (its §5.4: illuminance at points centred in the cells, not cell means)
//! and as DIALux and Relux compute it: each point, spot or photometric light's
//! intensity toward the point × cos θ / r², times its visibility, one shadow ray per
//! light and point of its luminous opening (DESIGN.md §6d).
//!
//! Why: a photon estimate of a cell is the cell's mean. A search judged by cell means
//! learns to hide dark points between cell centres (a classroom's answer read U0 0.62 by
//! cell means and 0.57 at the points). The direct part is the light that varies fast
//! over a grid; the light that has bounced comes from whole walls and ceilings and is
//! smooth, so the photons' cell mean of it is its value at the cell's centre to second
//! order. A point's illuminance is therefore this exact direct part plus the photons'
//! indirect cell mean ([`crate::GridMeasurement`]), and its interval is the indirect
//! part's alone: the direct part carries no photon noise. Both are linear in each
//! light's level, so the least-power program keeps the direct part per component as it
//! keeps the photons' tallies.
//!
//! A light with a luminous opening is taken, at a point nearer than [`FIVE_TIMES`] its
//! largest dimension, as [`OPENING_SAMPLES`]² points spread over it, each carrying an
//! equal share of its intensity (the far-field table applied at each), so a linear
//! luminaire close to a point is not treated as a point source. Farther away it is one
//! point at its photometric centre: the photometric distance rule (the inverse-square
//! law holds to about 1 % beyond five times a source's largest dimension; IES LM-63 and
//! CIE 121 measure luminaires at such distances). The sun, the sky and emissive surfaces
//! keep their direct light in the photons.

use crate::channels::Side;
use crate::emit::Emitters;
use crate::grid::SurfaceGrid;
use glam::Vec3;
use invlight_trace::{Accel, Ray, crossing_slack};
use rayon::prelude::*;

/// Points per side of a luminous opening's stratified points: 16 for a rectangle,
/// disk or ellipse.
pub const OPENING_SAMPLES: u32 = 4;

/// The distance, in the opening's largest dimension, beyond which a luminaire is one
/// point (the module doc's five-times rule).
pub const FIVE_TIMES: f32 = 5.0;

/// The direct illuminance, lx, of every point, spot and photometric light of
/// `emitters` at each cell's centre of `grid`, counted on `side`, per component
/// (`component_of` maps sources to the `k` components): cells × k values, row by row,
/// zero for the cells the surface does not cover.
pub(crate) fn direct_on_grid(
    emitters: &Emitters,
    accel: &Accel,
    grid: &SurfaceGrid,
    side: Side,
    component_of: &[u32],
    k: usize,
) -> Vec<f64> {
    let sources: Vec<_> = (0..emitters.len())
        .filter_map(|s| {
            emitters
                .point_source(s, OPENING_SAMPLES)
                .map(|p| (component_of[s] as usize, p))
        })
        .collect();
    let mut out = vec![0.0; grid.cells() * k];
    out.par_chunks_mut(k).enumerate().for_each(|(i, cell)| {
        if !grid.is_covered(i) {
            return;
        }
        let y = grid.centre(i);
        if accel.in_hole(y) {
            return;
        }
        for (c, source) in &sources {
            let far = [source.centre];
            let points = if y.distance(source.centre) >= FIVE_TIMES * source.size {
                &far[..]
            } else {
                &source.points[..]
            };
            let share = source.flux / points.len() as f64;
            let mut e = 0.0;
            for &x in points {
                e += share
                    * at_point(accel, x, y, grid.normal, side, |w| {
                        let (pdf, weight) = source.lobe.pdf_and_weight(w);
                        (pdf * weight) as f64
                    });
            }
            cell[*c] += e;
        }
    });
    out
}

/// The illuminance at `y` (unit normal `n`, counted on `side`) per lumen of a source at
/// `x` whose intensity per lumen toward the unit direction ω is `intensity(ω)`, cd/lm:
/// I·|cos θ|/r² when nothing hides y from x, else 0.
fn at_point(
    accel: &Accel,
    x: Vec3,
    y: Vec3,
    n: Vec3,
    side: Side,
    intensity: impl Fn(Vec3) -> f64,
) -> f64 {
    let d = y - x;
    let r = d.length();
    if !(r > 0.0 && r.is_finite()) {
        return 0.0;
    }
    let w = d / r;
    let cos = w.dot(n);
    // The light travels along w: it arrives on the front when against the normal.
    if cos == 0.0 || !side.counts(cos < 0.0) {
        return 0.0;
    }
    let i = intensity(w);
    if i <= 0.0 {
        return 0.0;
    }
    // Hidden as a connection to a calculation surface is: by a hit before the point,
    // within the rounding of the two ends ([`crossing_slack`]).
    let ray = Ray {
        origin: x,
        dir: w,
        t_max: r - crossing_slack(x, y),
    };
    if ray.t_max > 0.0 && accel.occluded(&ray) {
        return 0.0;
    }
    i * cos.abs() as f64 / (r as f64 * r as f64)
}
