//! Where the Russian roulette starts ([`TraceSettings::roulette`]), chosen per scene and
//! targets by a short pilot trace.
//!
//! Why: the classic roulette (thesis Algorithm 2.2) lets a photon survive each
//! reflection with the reflectance as its probability, so the light a target gets from
//! the second reflection on hangs on survival draws, each of which doubles or zeroes a
//! path's remaining contribution in a room of reflectance 0.5. Reflecting the first
//! bounces without a draw, at reduced power, takes that variance away at the price of
//! longer paths. Whether that pays depends on how much of the target's variance is
//! reflected light: on the Mitsuba comparison's grey room (40 % of the floor's light
//! reflected) a share of 0.25 gives 1.4× the efficiency of the classic roulette, while on
//! a desk lit mostly directly (examples/office-target) it costs 40 %. No constant serves
//! both, so [`tune_roulette`] measures: it traces the same few photons under shares 1,
//! ½, ¼, … and keeps the one with the least relative variance × rays cast, the
//! efficiency of the trace that follows (Veach 1997, §2.4; rays stand in for time, so
//! the choice is the same on any machine and thread count). Efficiency-aware roulette
//! and splitting learns the same trade-off per path (Rath et al. 2022, "EARS"); one
//! share per trace keeps a search's configurations on common random numbers.

use crate::channels::Components;
use crate::channels::Side;
use crate::chunks::{CHUNK, TraceSettings};
use crate::cluster::{Cluster, cluster};
use crate::measure::{Estimator, Request, measure_across};
use invlight_scene::Scene;
use invlight_scene::SurfaceId;
use invlight_stats::mix;
use invlight_trace::Accel;

/// The shares tried, in order: the classic roulette first, halving while that pays.
pub const ROULETTE_SHARES: [f32; 5] = [1.0, 0.5, 0.25, 0.125, 0.0625];

/// The most photons a pilot trace takes per share tried (256 groups: a relative
/// variance known to about 9 %, and a sixty-fourth of a default measurement).
pub const PILOT_PHOTONS: u64 = 4 * CHUNK;

/// The least photons a pilot trace takes per share tried (64 groups); a trace of fewer
/// than 64 times this keeps the classic roulette, as a pilot would cost too large a
/// share of it.
pub const MIN_PILOT_PHOTONS: u64 = CHUNK;

/// One share a pilot tried.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RouletteTrial {
    /// The share of [`TraceSettings::roulette`].
    pub share: f32,
    /// The targets' relative variances summed, times the rays cast (path and
    /// connection rays): lower is better.
    pub cost: f64,
}

/// The share [`tune_roulette`] chose and what it measured on the way.
#[derive(Debug, Clone, PartialEq)]
pub struct RouletteChoice {
    /// The share chosen.
    pub share: f32,
    /// The shares tried, in order (empty when the trace was too short to tune).
    pub trials: Vec<RouletteTrial>,
    /// Photons the pilot traced, every share together.
    pub photons: u64,
    /// Rays the pilot cast (path and connection rays).
    pub rays: u64,
}

impl RouletteChoice {
    /// `settings` with the share chosen.
    pub fn apply(&self, settings: TraceSettings) -> TraceSettings {
        TraceSettings {
            roulette: self.share,
            ..settings
        }
    }

    /// `share`, given rather than tuned: no pilot.
    pub fn given(share: f32) -> RouletteChoice {
        RouletteChoice {
            share,
            trials: Vec::new(),
            photons: 0,
            rays: 0,
        }
    }
}

/// Chooses [`TraceSettings::roulette`] for tracing `settings.photons` photons of `scene`
/// toward `request`'s surfaces: a pilot of at most [`PILOT_PHOTONS`] per share, drawn from
/// a stream of its own (the trace that follows shares no numbers with it, and is the
/// same whatever the pilot found), tries [`ROULETTE_SHARES`] in turn and stops at the
/// first that costs more than the best before it. Targets nothing reached in the pilot
/// count nothing; with none reached the classic roulette is kept. The processes of
/// `cluster` share the pilot as [`measure_across`] does, and choose alike.
pub fn tune_roulette(
    scene: &Scene,
    accel: &Accel,
    request: &Request,
    settings: &TraceSettings,
    cluster: &dyn Cluster,
) -> RouletteChoice {
    let mut choice = RouletteChoice::given(1.0);
    let pilot = (settings.photons / 64 / CHUNK * CHUNK).min(PILOT_PHOTONS);
    if pilot < MIN_PILOT_PHOTONS {
        return choice;
    }
    let request = Request::means(request.surfaces, request.components, request.estimator);
    let weights = vec![1.0; request.components.count()];
    let mut best = f64::INFINITY;
    for share in ROULETTE_SHARES {
        let trial = TraceSettings {
            photons: pilot,
            seed: mix(settings.seed ^ 0x726f_756c_6574_7465),
            roulette: share,
            ..*settings
        };
        let m = measure_across(scene, accel, &request, &trial, None, cluster);
        let rays = m.rays + m.connection_rays;
        choice.photons += m.photons;
        choice.rays += rays;
        let variance: f64 = (0..request.surfaces.len())
            .map(|t| m.estimate_of(t, Side::Both, &weights))
            .filter(|e| e.mean > 0.0 && e.std_error.is_finite())
            .map(|e| (e.std_error / e.mean).powi(2))
            .sum();
        if variance <= 0.0 {
            break;
        }
        let cost = variance * rays as f64;
        choice.trials.push(RouletteTrial { share, cost });
        if cost >= best {
            break;
        }
        best = cost;
        choice.share = share;
    }
    choice
}

/// [`tune_roulette`] for [`crate::measure`]'s request: `targets`, every light together,
/// counted by `estimator`, on this process's cluster; the share `given` instead when
/// there is one.
pub fn tune_roulette_for(
    scene: &Scene,
    accel: &Accel,
    (targets, estimator): (&[SurfaceId], Estimator),
    settings: &TraceSettings,
    given: Option<f32>,
) -> RouletteChoice {
    if let Some(share) = given {
        return RouletteChoice::given(share);
    }
    let components = Components::one(scene);
    let request = Request::means(targets, &components, estimator);
    tune_roulette(scene, accel, &request, settings, cluster())
}
