//! The search's settings: the attributes of `<objectives>` (ILPSolver's
//! `maxIterations`, `fastEvaluationQuality` and `strategy`, thesis §4.7; invlight's
//! `photons`, `seed`, `confidence`, `maxBounces` and `maintenanceFactor`).

use super::{Node, Reader};
use crate::vns::Strategy;
use invlight_scene::Diagnostic;
use invlight_stats::Confidence;

/// The attributes of `<objectives>`, defaults filled in; [`super::Problem`]
/// documents each.
pub(super) struct Search {
    pub max_iterations: u64,
    pub fast_quality: f64,
    pub strategy: Strategy,
    pub photons: u64,
    pub seed: u64,
    pub confidence: Confidence,
    pub max_bounces: Option<u32>,
    pub maintenance_factor: f64,
}

impl Reader<'_, '_> {
    /// The search settings on `objectives`.
    pub(super) fn search(&self, objectives: Node) -> Result<Search, Diagnostic> {
        self.check_attributes(
            objectives,
            &[
                "maxIterations",
                "fastEvaluationQuality",
                "strategy",
                "photons",
                "seed",
                "confidence",
                "maxBounces",
                "maintenanceFactor",
            ],
        );
        let max_iterations = self
            .number(objectives, "maxIterations", "a non-negative integer")?
            .unwrap_or(1000);
        let fast_quality =
            match self.real(objectives, "fastEvaluationQuality", "a number in (0, 1]")? {
                Some(q) if !(q > 0.0 && q <= 1.0) => {
                    return Err(self.error(
                        objectives,
                        format!("fastEvaluationQuality is {q}, expected a number in (0, 1]"),
                    ));
                }
                q => q.unwrap_or(0.25),
            };
        let strategy = match objectives.attribute("strategy") {
            None => Strategy::DEFAULT,
            Some(s) => Strategy::parse(s.trim()).ok_or_else(|| {
                self.error(
                    objectives,
                    format!("strategy is '{s}', expected {}", Strategy::names()),
                )
            })?,
        };
        let photons = match self.number::<u64>(objectives, "photons", "a positive integer")? {
            Some(0) => {
                return Err(self.error(objectives, "photons is 0, expected a positive integer"));
            }
            p => p.unwrap_or(100_000),
        };
        let seed = self
            .number(objectives, "seed", "a non-negative integer")?
            .unwrap_or(1);
        let confidence = match self.real(objectives, "confidence", "a number in (0, 1)")? {
            None => Confidence::DEFAULT,
            Some(c) => Confidence::new(c).map_err(|e| self.error(objectives, e.to_string()))?,
        };
        let max_bounces = self.number(objectives, "maxBounces", "a non-negative integer")?;
        let maintenance_factor = match self.real(
            objectives,
            "maintenanceFactor",
            "a number in (0, 1]",
        )? {
            Some(f) if !(f > 0.0 && f <= 1.0) => {
                return Err(self
                        .error(
                            objectives,
                            format!("maintenanceFactor is {f}, expected a number in (0, 1]"),
                        )
                        .with_hint("the maintained share of the new installation's light (CIE 97:2005), e.g. 0.8 for a clean office"));
            }
            f => f.unwrap_or(1.0),
        };
        Ok(Search {
            max_iterations,
            fast_quality,
            strategy,
            photons,
            seed,
            confidence,
            max_bounces,
            maintenance_factor,
        })
    }
}
