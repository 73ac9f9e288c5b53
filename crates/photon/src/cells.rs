//! Illuminance on the cells of a [`SurfaceGrid`], per component, and what lighting
//! standards read from them (EN 12464-1:2021 §5.4): Emin, Eavg, Emax and the
//! uniformity U0 = Emin/Eavg, each with a standard error.
//!
//! A cell's estimate is its group sums over its area, as a surface's is; the grid's
//! mean is the whole grid's light over its covered area, so Eavg is the area-weighted
//! mean of the cells. For U0 the delta method (first-order Taylor expansion of the
//! ratio; e.g. Casella & Berger, *Statistical Inference*, §5.5.4) gives
//! Var(U) ≈ [Var(E_m) − 2U·Cov(E_m, Eavg) + U²·Var(Eavg)] / Eavg², m the cell of least
//! mean. The covariance needs, per cell, the groups' products of the cell's totals with
//! the grid's: [`CellTallies`] keeps them. Emin is the least cell mean, biased low by
//! the noise of the cells it is the least of; the intervals say how much light that is
//! (tests check their coverage).

use crate::channels::Side;
use crate::grid::SurfaceGrid;
use invlight_stats::{ChannelSums, Estimate};

/// Index of (i, j), i ≤ j, in the upper triangle of a K × K matrix stored by rows.
#[inline]
fn upper(k: usize, i: usize, j: usize) -> usize {
    i * k - i * (i + 1) / 2 + j
}

/// Per-cell sums over groups of a grid's light, per component: Σ x, Σ x xᵀ and Σ x Tᵀ
/// with x a cell's group totals and T the grid's.
#[derive(Debug, Clone, PartialEq)]
pub struct CellSums {
    components: usize,
    /// Σ_g x_{g,c} per cell, K each.
    sum: Vec<f64>,
    /// Σ_g x x ᵀ per cell, upper triangles of K × K.
    cross: Vec<f64>,
    /// Σ_g x Tᵀ per cell, K × K by rows.
    with_total: Vec<f64>,
    /// Arrivals per cell.
    hits: Vec<u64>,
    /// The grid's total per group.
    total: ChannelSums,
}

impl CellSums {
    /// The bytes its sums take on the heap.
    pub(crate) fn heap_bytes(&self) -> usize {
        (self.sum.len() + self.cross.len() + self.with_total.len()) * size_of::<f64>()
            + self.hits.len() * size_of::<u64>()
            + self.total.heap_bytes()
    }

    fn new(cells: usize, components: usize) -> CellSums {
        let k = components;
        CellSums {
            components: k,
            sum: vec![0.0; cells * k],
            cross: vec![0.0; cells * k * (k + 1) / 2],
            with_total: vec![0.0; cells * k * k],
            hits: vec![0; cells],
            total: ChannelSums::new(k),
        }
    }

    fn cells(&self) -> usize {
        self.hits.len()
    }

    fn merge(&mut self, other: &CellSums) {
        let add = |a: &mut [f64], b: &[f64]| a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
        add(&mut self.sum, &other.sum);
        add(&mut self.cross, &other.cross);
        add(&mut self.with_total, &other.with_total);
        self.hits
            .iter_mut()
            .zip(&other.hits)
            .for_each(|(x, y)| *x += y);
        self.total.merge(&other.total);
    }

    /// Appends the sums to `out` (a chunk's, for a shared trace, [`crate::Pack`]).
    pub(crate) fn pack(&self, out: &mut Vec<u64>) {
        let reals = self.sum.iter().chain(&self.cross).chain(&self.with_total);
        out.extend(reals.map(|x| x.to_bits()));
        out.extend(&self.hits);
        self.total.pack(out);
    }

    /// Reads back what [`CellSums::pack`] wrote, into sums of the same grid.
    pub(crate) fn unpack(&mut self, words: &mut impl Iterator<Item = u64>) {
        let mut next = || words.next().expect("packed sums of as many cells");
        let reals = self.sum.iter_mut().chain(&mut self.cross);
        for x in reals.chain(&mut self.with_total) {
            *x = f64::from_bits(next());
        }
        for h in &mut self.hits {
            *h = next();
        }
        self.total.unpack(words);
    }

    /// Σ_g w·x_g of cell `i`.
    fn total_of(&self, i: usize, w: &[f64]) -> f64 {
        let k = self.components;
        self.sum[i * k..(i + 1) * k]
            .iter()
            .zip(w)
            .map(|(s, w)| s * w)
            .sum()
    }

    /// Σ_g (w·x_g)² of cell `i`.
    fn square_of(&self, i: usize, w: &[f64]) -> f64 {
        let k = self.components;
        let c = &self.cross[i * k * (k + 1) / 2..(i + 1) * k * (k + 1) / 2];
        let mut out = 0.0;
        for a in 0..k {
            for b in a..k {
                let f = if a == b { 1.0 } else { 2.0 };
                out += f * w[a] * w[b] * c[upper(k, a, b)];
            }
        }
        out
    }

    /// Σ_g (w·x_g)(w·T_g) of cell `i`.
    fn with_total_of(&self, i: usize, w: &[f64]) -> f64 {
        let k = self.components;
        let c = &self.with_total[i * k * k..(i + 1) * k * k];
        let mut out = 0.0;
        for a in 0..k {
            for b in 0..k {
                out += w[a] * w[b] * c[a * k + b];
            }
        }
        out
    }
}

/// One chunk's per-cell tallies of a grid, built photon by photon like the surfaces'
/// (a group's totals first, folded in at [`CellTallies::end_group`]).
#[derive(Debug, Clone)]
pub(crate) struct CellTallies {
    pub(crate) sums: CellSums,
    current: Vec<f64>,
    touched: Vec<u32>,
    is_touched: Vec<bool>,
    group_total: Vec<f64>,
}

impl CellTallies {
    pub(crate) fn new(cells: usize, components: usize) -> CellTallies {
        CellTallies {
            sums: CellSums::new(cells, components),
            current: vec![0.0; cells * components],
            touched: Vec::new(),
            is_touched: vec![false; cells],
            group_total: vec![0.0; components],
        }
    }

    /// The current photon brings `lumens` of component `k` to cell `cell`; `arrived`
    /// when it is an arrival (not a connection).
    #[inline]
    pub(crate) fn add(&mut self, cell: usize, k: u32, lumens: f64, arrived: bool) {
        if arrived {
            self.sums.hits[cell] += 1;
        }
        if lumens == 0.0 {
            return;
        }
        if !self.is_touched[cell] {
            self.is_touched[cell] = true;
            self.touched.push(cell as u32);
        }
        self.current[cell * self.sums.components + k as usize] += lumens;
    }

    /// The current group ended: its cell totals join the sums.
    pub(crate) fn end_group(&mut self) {
        let k = self.sums.components;
        self.group_total.fill(0.0);
        for &c in &self.touched {
            let c = c as usize;
            for (t, x) in self.group_total.iter_mut().zip(&self.current[c * k..]) {
                *t += x;
            }
        }
        let tri = k * (k + 1) / 2;
        for &c in &self.touched {
            let c = c as usize;
            let x = &mut self.current[c * k..(c + 1) * k];
            let cross = &mut self.sums.cross[c * tri..(c + 1) * tri];
            let with_total = &mut self.sums.with_total[c * k * k..(c + 1) * k * k];
            for a in 0..k {
                self.sums.sum[c * k + a] += x[a];
                for b in a..k {
                    cross[upper(k, a, b)] += x[a] * x[b];
                }
                for b in 0..k {
                    with_total[a * k + b] += x[a] * self.group_total[b];
                }
            }
            x.fill(0.0);
            self.is_touched[c] = false;
        }
        self.touched.clear();
        self.sums.total.add_group(&self.group_total);
    }

    /// Bytes held, for sizing the blocks of chunks traced at a time.
    pub(crate) fn bytes(&self) -> usize {
        let k = self.sums.components;
        let cells = self.sums.cells();
        cells * (8 * (2 * k + k * (k + 1) / 2 + k * k + 1) + 9)
    }
}

/// What a measurement found on one grid.
#[derive(Debug, Clone, PartialEq)]
pub struct GridMeasurement {
    /// The grid.
    pub grid: SurfaceGrid,
    /// The side whose light was counted.
    pub side: Side,
    pub(crate) sums: CellSums,
    pub(crate) photons: u64,
    pub(crate) flux: f64,
    /// For a grid read at points ([`crate::GridValues::Points`]): each cell's centre's
    /// computed direct light per component, lx (cells × K), which the sums leave out;
    /// empty when the cells read means.
    pub(crate) direct: Vec<f64>,
}

/// U0 and the figures it is made of, at one dimming of the lights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Uniformity {
    /// U0 = Emin/Eavg.
    pub u0: Estimate,
    /// Emin: the least cell mean among the cells the surface covers at least half of
    /// (all covered cells when none is), lx.
    pub min: Estimate,
    /// Eavg: the grid's light over its covered area, lx.
    pub average: Estimate,
    /// Emax: the greatest cell mean among the same cells as Emin, lx.
    pub max: Estimate,
    /// The cell of Emin.
    pub min_cell: usize,
    /// The cell of Emax.
    pub max_cell: usize,
}

impl GridMeasurement {
    pub(crate) fn new(grid: SurfaceGrid, side: Side, sums: CellSums) -> GridMeasurement {
        GridMeasurement {
            grid,
            side,
            sums,
            photons: 0,
            flux: 0.0,
            direct: Vec::new(),
        }
    }

    pub(crate) fn merge(&mut self, part: &CellSums) {
        self.sums.merge(part);
    }

    fn groups(&self) -> u64 {
        self.photons.div_ceil(crate::GROUP)
    }

    /// A cell's or the grid's estimate from its sums over `area`; what nothing reached
    /// keeps one arrival's worth of doubt ([`crate::Measurement::estimate_of`]'s rule).
    fn estimate(&self, sum: f64, square: f64, area: f64, w: &[f64]) -> Estimate {
        let inv = 1.0 / area;
        let mut e =
            Estimate::from_groups(sum * inv, square * inv * inv, self.groups(), self.photons);
        if sum <= 0.0 && self.photons > 0 {
            let w_max = w.iter().copied().fold(0.0, f64::max);
            e.std_error = w_max * self.flux * inv / self.photons as f64;
        }
        e
    }

    /// Arrivals counted in cell `i`.
    pub fn hits(&self, i: usize) -> u64 {
        self.sums.hits[i]
    }

    /// Whether a cell's value is the illuminance at its centre
    /// ([`crate::GridValues::Points`]) rather than its mean.
    pub fn at_points(&self) -> bool {
        !self.direct.is_empty()
    }

    /// The computed direct light at cell `i`'s centre at weights `w`, lx: 0 when the
    /// cells read means.
    fn direct_of(&self, i: usize, w: &[f64]) -> f64 {
        let k = self.sums.components;
        self.direct
            .get(i * k..(i + 1) * k)
            .map_or(0.0, |d| d.iter().zip(w).map(|(d, w)| d * w).sum())
    }

    /// The value of cell `i` at component weights `w` (one per component, the dimming
    /// levels), lx: the illuminance at its centre when the grid is read at points (the
    /// computed direct light plus the photons' mean of the rest over the cell, whose
    /// interval it keeps), else its mean; `None` for a cell the surface does not cover.
    pub fn cell(&self, i: usize, w: &[f64]) -> Option<Estimate> {
        if !self.grid.is_covered(i) {
            return None;
        }
        let (sum, square) = (self.sums.total_of(i, w), self.sums.square_of(i, w));
        let mut e = self.estimate(sum, square, self.grid.areas[i], w);
        e.mean += self.direct_of(i, w);
        Some(e)
    }

    /// The cells Emin and Emax are read on, and whose centres a grid read at points
    /// averages: those the surface covers at least half of, or every covered cell when
    /// none is.
    pub fn points(&self) -> Vec<usize> {
        let covered = (0..self.grid.cells()).filter(|&i| self.grid.is_covered(i));
        let full: Vec<usize> = covered.clone().filter(|&i| self.grid.is_full(i)).collect();
        if full.is_empty() {
            covered.collect()
        } else {
            full
        }
    }

    /// The covered area, m².
    pub fn area(&self) -> f64 {
        (0..self.grid.cells())
            .filter(|&i| self.grid.is_covered(i))
            .map(|i| self.grid.areas[i])
            .sum()
    }

    /// The grid's mean illuminance at weights `w`, lx: the whole grid's light over its
    /// covered area; read at points, the mean of the points' computed direct light plus
    /// that mean of the rest (the photons' indirect light is smooth, and its area mean
    /// keeps the covariance with each cell that U0's interval needs).
    pub fn average(&self, w: &[f64]) -> Estimate {
        let t = &self.sums.total;
        let mut e = self.estimate(t.total(w), t.product(w, w), self.area(), w);
        if self.at_points() {
            let points = self.points();
            let direct: f64 = points.iter().map(|&i| self.direct_of(i, w)).sum();
            e.mean += direct / points.len().max(1) as f64;
        }
        e
    }

    /// Emin, Eavg, Emax and U0 at weights `w`.
    pub fn uniformity(&self, w: &[f64]) -> Uniformity {
        let pool: Vec<(usize, Estimate)> = self
            .points()
            .into_iter()
            .filter_map(|i| self.cell(i, w).map(|e| (i, e)))
            .collect();
        let (min_cell, min) = pool
            .iter()
            .copied()
            .min_by(|a, b| a.1.mean.total_cmp(&b.1.mean))
            .expect("a grid covers at least one cell");
        let (max_cell, max) = pool
            .iter()
            .copied()
            .max_by(|a, b| a.1.mean.total_cmp(&b.1.mean))
            .expect("a grid covers at least one cell");
        let average = self.average(w);
        let u0 = if average.mean > 0.0 {
            let u = min.mean / average.mean;
            let g = self.groups() as f64;
            let n = self.photons as f64;
            // Cov of the per-photon means of the cell's and the grid's light, over their
            // areas: the groups' sample covariance (G − 1) over G, scaled to photons.
            let (a_m, a) = (self.grid.areas[min_cell], self.area());
            let (s_m, s_t) = (self.sums.total_of(min_cell, w), self.sums.total.total(w));
            let cov_groups = (self.sums.with_total_of(min_cell, w) - s_m * s_t / g) / (g - 1.0);
            let cov = cov_groups * g / (n * n) / (a_m * a);
            let var = min.std_error.powi(2) - 2.0 * u * cov + u * u * average.std_error.powi(2);
            Estimate {
                mean: u,
                std_error: var.max(0.0).sqrt() / average.mean,
                samples: self.photons,
            }
        } else {
            // No light on the grid: U0 is undefined; every value in [0, 1] is as likely.
            Estimate {
                mean: 0.0,
                std_error: 1.0,
                samples: self.photons,
            }
        };
        Uniformity {
            u0,
            min,
            average,
            max,
            min_cell,
            max_cell,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The per-cell products add up the way the groups' totals do by hand.
    #[test]
    fn cell_sums_match_the_groups_by_hand() {
        let mut t = CellTallies::new(2, 2);
        // Group 1: cell 0 gets (1, 2), cell 1 gets (0, 3). Group 2: cell 0 (2, 0).
        t.add(0, 0, 1.0, true);
        t.add(0, 1, 2.0, true);
        t.add(1, 1, 3.0, false);
        t.end_group();
        t.add(0, 0, 2.0, true);
        t.end_group();
        let s = &t.sums;
        let w = [1.0, 0.5];
        // Cell 0: w·x = 2, then 2; Σ = 4, Σ² = 8.
        assert_eq!(s.total_of(0, &w), 4.0);
        assert_eq!(s.square_of(0, &w), 8.0);
        // Grid totals: (1, 5) → 3.5, (2, 0) → 2. Σ (w·x_0)(w·T) = 2·3.5 + 2·2 = 11.
        assert_eq!(s.with_total_of(0, &w), 11.0);
        assert_eq!(s.total.total(&w), 5.5);
        assert_eq!(s.hits, [3, 0]);
    }
}
