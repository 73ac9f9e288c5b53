//! The objective by photon tracing (thesis §3.3, §4.9.2): apply the configuration to
//! the scene, rebuild the acceleration structure's top level if an instance moved (the
//! instances no variable moves are baked into one tree once), trace, and read the
//! objective surface's tally.
//!
//! Every evaluation uses the same photon seed (common random numbers, DESIGN.md §2):
//! photon i of two configurations starts from the same random numbers, so their
//! difference is far less noisy than either value, and a fast estimate with n photons
//! is the first n photons of the full one.

use crate::binding::Binding;
use crate::space::Configuration;
use crate::vns::Evaluate;
use invlight_photon::{Estimator, TraceSettings, measure, photons_traced};
use invlight_scene::Scene;
use invlight_stats::Estimate;
use invlight_trace::Accel;
use std::convert::Infallible;

/// Evaluates configurations of a bound problem by photon tracing.
pub struct PhotonEvaluator<'b> {
    binding: &'b Binding,
    scene: Scene,
    accel: Accel,
    seed: u64,
    max_bounces: u32,
    rays: u64,
    photons: u64,
}

impl<'b> PhotonEvaluator<'b> {
    /// An evaluator owning `scene` (already prepared by [`Binding::new`]); photons use
    /// `seed` and at most `max_bounces` bounces.
    pub fn new(binding: &'b Binding, scene: Scene, seed: u64, max_bounces: u32) -> Self {
        let accel = Accel::with_movable(&scene, &binding.movable_instances());
        PhotonEvaluator {
            binding,
            scene,
            accel,
            seed,
            max_bounces,
            rays: 0,
            photons: 0,
        }
    }

    /// Rays cast and photons traced so far.
    pub fn work(&self) -> (u64, u64) {
        (self.rays, self.photons)
    }
}

impl Evaluate for PhotonEvaluator<'_> {
    type Error = Infallible;

    fn evaluate(&mut self, config: &Configuration, photons: u64) -> Result<Estimate, Infallible> {
        if self.binding.apply(&mut self.scene, config) {
            self.accel.update_instances(&self.scene);
        }
        let settings = TraceSettings {
            photons: self.samples(photons),
            seed: self.seed,
            max_bounces: self.max_bounces,
        };
        let m = measure(
            &self.scene,
            &self.accel,
            &[self.binding.objective],
            &settings,
            Estimator::Connected,
            None,
        );
        self.rays += m.rays + m.connection_rays;
        self.photons += m.photons;
        Ok(m.estimate(0))
    }

    /// Whole groups of photons, at least the tracer's minimum; a count past `u64` is
    /// held at the largest whole number of groups (no run gets near either).
    fn samples(&self, requested: u64) -> u64 {
        photons_traced(requested).unwrap_or(u64::MAX - u64::MAX % invlight_photon::GROUP)
    }

    fn refuses(&self, config: &Configuration) -> Option<String> {
        self.binding
            .leaves_scene(config)
            .map(|id| format!("it puts '{id}' outside the scene"))
    }
}
