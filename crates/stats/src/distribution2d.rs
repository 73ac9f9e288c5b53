//! A piecewise-constant density over a rectangular grid of cells, sampled by inversion
//! with its exact density (pbrt-v4 `PiecewiseConstant2D`, `util/sampling.h`: a marginal
//! distribution over rows and one conditional distribution per row). Unlike pbrt's, the
//! grid's breakpoints need not be equally spaced: a photometric file measures every 2.5°
//! near the beam and every 10° elsewhere, and its cells are sampled as they are.

use std::fmt;

/// Why a [`PiecewiseConstant2D`] could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum Distribution2DError {
    /// An axis has fewer than two breakpoints, or they are not finite and strictly
    /// increasing.
    BadAxis {
        /// `x` or `y`.
        axis: &'static str,
        /// Index of the first offending breakpoint.
        at: usize,
    },
    /// The masses are not one per cell.
    WrongCount {
        /// nx·ny.
        expected: usize,
        /// What was given.
        given: usize,
    },
    /// A mass is negative or not finite.
    BadMass {
        /// Row-major index of the cell.
        at: usize,
    },
    /// Every mass is zero: there is nothing to sample.
    Empty,
}

impl fmt::Display for Distribution2DError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Distribution2DError::BadAxis { axis, at } => write!(
                f,
                "the {axis} breakpoints must be at least two, finite and strictly increasing (breakpoint {at} is not)"
            ),
            Distribution2DError::WrongCount { expected, given } => {
                write!(f, "{given} cell masses given, {expected} expected")
            }
            Distribution2DError::BadMass { at } => {
                write!(f, "the mass of cell {at} is negative or not finite")
            }
            Distribution2DError::Empty => write!(f, "every cell has zero mass"),
        }
    }
}

impl std::error::Error for Distribution2DError {}

/// A draw from a [`PiecewiseConstant2D`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample2D {
    /// The point drawn.
    pub x: f64,
    /// The point drawn.
    pub y: f64,
    /// Its density per unit area of (x, y): the same number [`PiecewiseConstant2D::pdf`]
    /// gives there.
    pub pdf: f64,
    /// The cell it lies in, (column of x, row of y).
    pub cell: (usize, usize),
}

/// A density on [x₀, x_nx] × [y₀, y_ny] that is constant on each cell
/// [x_i, x_i+1] × [y_j, y_j+1], given by the cells' masses (their integrals, not their
/// densities): the density in cell (i, j) is m_ij / (M·Δx_i·Δy_j) with M = Σ m.
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseConstant2D {
    x: Vec<f64>,
    y: Vec<f64>,
    /// Over columns i, weights Σ_j m_ij.
    marginal: Guided,
    /// Per column i, over rows j, weights m_ij.
    conditional: Vec<Guided>,
    /// `density[i·ny + j]`: m_ij / (M·Δx_i·Δy_j), kept because a photon's draw and every
    /// connection toward a luminaire read it.
    density: Vec<f64>,
}

impl PiecewiseConstant2D {
    /// The distribution of the cells between breakpoints `x` (nx + 1 of them) and `y`
    /// (ny + 1) with masses `masses[i·ny + j]` for cell (i, j).
    pub fn new(
        x: Vec<f64>,
        y: Vec<f64>,
        masses: &[f64],
    ) -> Result<PiecewiseConstant2D, Distribution2DError> {
        check_axis(&x, "x")?;
        check_axis(&y, "y")?;
        let (nx, ny) = (x.len() - 1, y.len() - 1);
        if masses.len() != nx * ny {
            return Err(Distribution2DError::WrongCount {
                expected: nx * ny,
                given: masses.len(),
            });
        }
        if let Some(at) = masses.iter().position(|m| !(m.is_finite() && *m >= 0.0)) {
            return Err(Distribution2DError::BadMass { at });
        }
        let conditional: Vec<Guided> = masses
            .chunks_exact(ny)
            .map(|row| Guided::new(row.iter().copied()))
            .collect();
        let marginal = Guided::new(conditional.iter().map(|c| c.total()));
        let total = marginal.total();
        if total <= 0.0 {
            return Err(Distribution2DError::Empty);
        }
        let density = masses
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let (i, j) = (k / ny, k % ny);
                m / (total * (x[i + 1] - x[i]) * (y[j + 1] - y[j]))
            })
            .collect();
        Ok(PiecewiseConstant2D {
            x,
            y,
            marginal,
            conditional,
            density,
        })
    }

    /// Σ of the masses, M.
    pub fn total(&self) -> f64 {
        self.marginal.total()
    }

    /// The breakpoints of x.
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The breakpoints of y.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// The mass of cell (i, j).
    pub fn mass(&self, i: usize, j: usize) -> f64 {
        self.conditional[i].weight(j)
    }

    /// The density of cell (i, j) per unit area.
    #[inline]
    pub fn cell_pdf(&self, i: usize, j: usize) -> f64 {
        self.density[i * (self.y.len() - 1) + j]
    }

    /// The cell holding (x, y), `None` outside the grid. A point on a breakpoint
    /// belongs to the cell above it (the last breakpoint to the last cell).
    #[inline]
    pub fn cell(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        Some((locate(&self.x, x)?, locate(&self.y, y)?))
    }

    /// The density at (x, y) per unit area (0 outside the grid).
    #[inline]
    pub fn pdf(&self, x: f64, y: f64) -> f64 {
        self.cell(x, y).map_or(0.0, |(i, j)| self.cell_pdf(i, j))
    }

    /// A point drawn with the density, from two uniform numbers in [0, 1): `u[0]` picks
    /// the column by the marginal and its remainder the position across it, `u[1]` the
    /// row by that column's conditional and its remainder the position along it (pbrt-v4
    /// `PiecewiseConstant2D::Sample`). Cells of zero mass are never drawn.
    #[inline]
    pub fn sample(&self, u: [f64; 2]) -> Sample2D {
        let (i, rx) = self.marginal.sample_continuous(u[0]);
        let (j, ry) = self.conditional[i].sample_continuous(u[1]);
        let x = self.x[i] + rx * (self.x[i + 1] - self.x[i]);
        let y = self.y[j] + ry * (self.y[j + 1] - self.y[j]);
        Sample2D {
            x,
            y,
            pdf: self.cell_pdf(i, j),
            cell: (i, j),
        }
    }
}

/// A discrete distribution sampled by inversion through a guide table (H.-C. Chen and
/// Y. Asau, "On generating random variates from an empirical distribution", AIIE
/// Transactions 6(2), 1974): `guide[k]` is the first entry whose cumulative sum exceeds
/// k/n of the total, so a draw starts there and steps forward, one or two steps on
/// average, and returns the entry a binary search would (inversion, so stratified
/// uniforms stay stratified). A photon draws twice from these; perf put the two binary
/// searches they replace at a third of a luminaire's draw.
#[derive(Debug, Clone, PartialEq)]
struct Guided {
    cdf: Vec<f64>,
    guide: Vec<u32>,
}

impl Guided {
    fn new(weights: impl IntoIterator<Item = f64>) -> Guided {
        let mut acc = 0.0f64;
        let cdf: Vec<f64> = weights
            .into_iter()
            .map(|w| {
                acc += w;
                acc
            })
            .collect();
        let n = cdf.len();
        let mut guide = Vec::with_capacity(n);
        let mut i = 0;
        for k in 0..n {
            let target = k as f64 / n as f64 * acc;
            while i < n - 1 && cdf[i] <= target {
                i += 1;
            }
            guide.push(i as u32);
        }
        Guided { cdf, guide }
    }

    fn total(&self) -> f64 {
        self.cdf[self.cdf.len() - 1]
    }

    fn weight(&self, i: usize) -> f64 {
        self.cdf[i] - if i == 0 { 0.0 } else { self.cdf[i - 1] }
    }

    /// The first entry whose cumulative sum exceeds `u·total`, and where in its interval
    /// that falls, rescaled to [0, 1).
    #[inline]
    fn sample_continuous(&self, u: f64) -> (usize, f64) {
        let n = self.cdf.len();
        let target = u * self.total();
        let mut i = self.guide[((u * n as f64) as usize).min(n - 1)] as usize;
        while i < n - 1 && self.cdf[i] <= target {
            i += 1;
        }
        let below = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let w = self.cdf[i] - below;
        let r = if w > 0.0 { (target - below) / w } else { 0.0 };
        (i, r.clamp(0.0, 1.0 - f64::EPSILON / 2.0))
    }
}

fn check_axis(v: &[f64], axis: &'static str) -> Result<(), Distribution2DError> {
    if v.len() < 2 {
        return Err(Distribution2DError::BadAxis { axis, at: v.len() });
    }
    if let Some(at) = v.iter().position(|t| !t.is_finite()) {
        return Err(Distribution2DError::BadAxis { axis, at });
    }
    if let Some(at) = v.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Distribution2DError::BadAxis { axis, at: at + 1 });
    }
    Ok(())
}

/// The cell of `t` between breakpoints `v`.
#[inline]
fn locate(v: &[f64], t: f64) -> Option<usize> {
    let n = v.len() - 1;
    if !(t >= v[0] && t <= v[n]) {
        return None;
    }
    Some(v.partition_point(|&b| b <= t).saturating_sub(1).min(n - 1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Distribution1D, SplitMix64};

    /// The guide table finds the entry a binary search finds, zero weights included.
    #[test]
    fn guided_draws_are_the_binary_searchs() {
        let w = [0.0, 1.0, 0.0, 0.0, 3.0, 0.5, 0.0, 2.0, 0.0];
        let (g, d) = (Guided::new(w), Distribution1D::new(w));
        for k in 0..10_000 {
            let u = k as f64 / 10_000.0;
            assert_eq!(g.sample_continuous(u), d.sample_continuous(u), "u = {u}");
        }
    }

    /// An uneven grid with a zero cell, a zero row and masses spanning two decades.
    fn uneven() -> PiecewiseConstant2D {
        let x = vec![0.0, 0.5, 2.0, 2.5, 4.0];
        let y = vec![-1.0, 0.0, 0.25, 3.0];
        #[rustfmt::skip]
        let m = [
            1.0, 0.0, 4.0,
            0.1, 8.0, 2.0,
            0.0, 0.0, 0.0,
            3.0, 0.5, 10.0,
        ];
        PiecewiseConstant2D::new(x, y, &m).unwrap()
    }

    #[test]
    fn bad_input_is_refused() {
        let e = |x: Vec<f64>, y: Vec<f64>, m: &[f64]| PiecewiseConstant2D::new(x, y, m).err();
        assert_eq!(
            e(vec![0.0], vec![0.0, 1.0], &[]),
            Some(Distribution2DError::BadAxis { axis: "x", at: 1 })
        );
        assert_eq!(
            e(vec![0.0, 1.0], vec![0.0, 2.0, 2.0], &[1.0, 1.0]),
            Some(Distribution2DError::BadAxis { axis: "y", at: 2 })
        );
        assert_eq!(
            e(vec![0.0, 1.0], vec![0.0, 1.0], &[1.0, 1.0]),
            Some(Distribution2DError::WrongCount {
                expected: 1,
                given: 2
            })
        );
        assert_eq!(
            e(vec![0.0, 1.0], vec![0.0, 1.0], &[-1.0]),
            Some(Distribution2DError::BadMass { at: 0 })
        );
        assert_eq!(
            e(vec![0.0, 1.0], vec![0.0, 1.0], &[0.0]),
            Some(Distribution2DError::Empty)
        );
    }

    /// The density integrates to one: Σ over cells of density × area, and a midpoint
    /// rule over a fine grid that ignores the cells.
    #[test]
    fn pdf_integrates_to_one() {
        let d = uneven();
        let mut cells = 0.0;
        for i in 0..4 {
            for j in 0..3 {
                let area = (d.x[i + 1] - d.x[i]) * (d.y[j + 1] - d.y[j]);
                cells += d.cell_pdf(i, j) * area;
            }
        }
        assert!((cells - 1.0).abs() < 1e-12, "{cells}");
        // Steps of 1/400 put every breakpoint between two midpoints.
        let n = 1600;
        let (w, h) = (4.0 / n as f64, 4.0 / n as f64);
        let mut grid = 0.0;
        for a in 0..n {
            for b in 0..n {
                grid += d.pdf((a as f64 + 0.5) * w, -1.0 + (b as f64 + 0.5) * h) * w * h;
            }
        }
        assert!((grid - 1.0).abs() < 1e-9, "{grid}");
        assert_eq!(d.pdf(-0.1, 0.0), 0.0);
        assert_eq!(d.pdf(1.0, 3.5), 0.0);
    }

    /// pbrt-v4's sampling tests: every draw's density is what `pdf` says at the point
    /// drawn, no draw lands where the density is zero, and Σ 1/(p·N) estimates the area
    /// where the density is positive. Its standard error comes from the same draws.
    #[test]
    fn draws_carry_their_density() {
        let d = uneven();
        let mut rng = SplitMix64::new(11);
        let n = 200_000;
        let (mut s, mut s2) = (0.0, 0.0);
        for _ in 0..n {
            let p = d.sample([rng.next_f64(), rng.next_f64()]);
            assert!(p.pdf > 0.0);
            assert_eq!(p.pdf, d.pdf(p.x, p.y), "{p:?}");
            assert_eq!(Some(p.cell), d.cell(p.x, p.y));
            s += 1.0 / p.pdf;
            s2 += 1.0 / (p.pdf * p.pdf);
        }
        let mean = s / n as f64;
        let sigma = ((s2 / n as f64 - mean * mean) / n as f64).sqrt();
        // Support: the whole 4 × 4 grid less the zero cell (0.5 × 0.25) and the zero
        // column x ∈ [2, 2.5] (0.5 × 4).
        let support = 16.0 - 0.125 - 2.0;
        assert!((mean - support).abs() < 4.0 * sigma, "{mean} ± {sigma}");
    }

    /// A χ² test of the counts in each cell (and of the halves of each cell, which the
    /// remapped uniforms must fill evenly) against their expected numbers.
    #[test]
    fn chi_square_of_cell_counts() {
        let d = uneven();
        let mut rng = SplitMix64::new(5);
        let n = 100_000;
        let mut counts = [0u32; 4 * 3 * 4];
        for _ in 0..n {
            let p = d.sample([rng.next_f64(), rng.next_f64()]);
            let (i, j) = p.cell;
            let hx = (p.x > 0.5 * (d.x[i] + d.x[i + 1])) as usize;
            let hy = (p.y > 0.5 * (d.y[j] + d.y[j + 1])) as usize;
            counts[(i * 3 + j) * 4 + hx * 2 + hy] += 1;
        }
        let (mut chi2, mut bins) = (0.0, 0usize);
        for i in 0..4 {
            for j in 0..3 {
                let expected = n as f64 * d.mass(i, j) / d.total() / 4.0;
                for q in 0..4 {
                    let c = counts[(i * 3 + j) * 4 + q] as f64;
                    if expected == 0.0 {
                        assert_eq!(c, 0.0);
                    } else {
                        chi2 += (c - expected).powi(2) / expected;
                        bins += 1;
                    }
                }
            }
        }
        // χ² with k = bins − 1 degrees of freedom has mean k and sd √(2k); beyond
        // k + 6√(2k) it has probability below 10⁻⁶.
        let k = (bins - 1) as f64;
        assert!(chi2 < k + 6.0 * (2.0 * k).sqrt(), "χ² = {chi2} for {k} dof");
    }
}
