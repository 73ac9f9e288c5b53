//! The objective by photon tracing (thesis §3.3, §4.9.2): apply the configuration to
//! the scene, rebuild the acceleration structure's top level if an instance moved (the
//! instances no variable moves are baked into one tree once), trace, and read the
//! objective surface's tally.
//!
//! Every evaluation uses the same photon seed (common random numbers, DESIGN.md §2):
//! photon i of two configurations starts from the same random numbers, so their
//! difference is far less noisy than either value, and a fast estimate with n photons
//! is the first n photons of the full one.

use crate::apply::Binding;
use crate::space::Configuration;
use crate::vns::Evaluate;
use invlight_photon::{Estimate, TraceSettings, trace};
use invlight_scene::Scene;
use invlight_trace::Accel;
use std::convert::Infallible;

/// Evaluates configurations of a bound problem by photon tracing.
pub struct PhotonEvaluator<'b> {
    binding: &'b Binding,
    scene: Scene,
    accel: Accel,
    area: f64,
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
        let area = scene.surface_area(binding.objective) as f64;
        PhotonEvaluator {
            binding,
            scene,
            accel,
            area,
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
            photons,
            seed: self.seed,
            max_bounces: self.max_bounces,
            connect: true,
        };
        let r = trace(
            &self.scene,
            &self.accel,
            &[self.binding.objective],
            &settings,
            None,
        );
        self.rays += r.rays;
        self.photons += r.photons;
        Ok(r.estimate(0, self.area))
    }
}
