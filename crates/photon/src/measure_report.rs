//! What `invlight measure` prints and writes: each surface's mean illuminance with its
//! interval, its front and back, a daylight factor where asked, and the warnings a
//! reader needs (light mostly from behind a one-sided count).

use crate::RouletteChoice;
use crate::channels::Side;
use crate::chunks::TraceSettings;
use crate::measure::{Estimator, Measurement};
use invlight_stats::Confidence;
use serde::{Deserialize, Serialize};

/// One surface of a [`MeasureReport`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceReport {
    /// Its name.
    pub name: String,
    /// Its area, m².
    pub area: f64,
    /// Mean illuminance, lx.
    pub mean: f64,
    /// Lower end of the interval at the report's confidence, lx.
    pub low: f64,
    /// Upper end, lx.
    pub high: f64,
    /// Standard error of the mean, lx.
    pub std_error: f64,
    /// Photon arrivals counted.
    pub hits: u64,
    /// The side counted: `front`, `back` or `both`.
    pub side: String,
    /// Mean illuminance of the front alone (the side its counter-clockwise normal
    /// faces), lx.
    pub front: f64,
    /// Mean illuminance of the back alone, lx.
    pub back: f64,
    /// The mean illuminance as a daylight factor, when measured as one
    /// ([`MeasureReport::with_daylight_factor`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub daylight_factor: Option<DaylightFactor>,
}

/// A daylight factor with its interval, % (CIE S 017:2020, International Lighting
/// Vocabulary, "daylight factor"): the illuminance a surface receives from a sky, direct
/// and reflected, over what the sky gives an unobstructed horizontal plane. That
/// denominator is the sky's `horizontalLux`, known exactly, so the factor's interval is
/// the illuminance's scaled by the same 100 / E_h.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DaylightFactor {
    /// DF of the mean illuminance, %.
    pub mean: f64,
    /// Lower end of the interval, %.
    pub low: f64,
    /// Upper end, %.
    pub high: f64,
    /// Standard error, %.
    pub std_error: f64,
}

impl SurfaceReport {
    /// The back's share of the surface's light when more than a tenth of it arrives
    /// there and both sides are counted ([`much_from_behind`]).
    pub fn much_from_behind(&self) -> Option<f64> {
        much_from_behind(&self.side, self.front, self.back)
    }

    /// The warning [`SurfaceReport::much_from_behind`] deserves ([`behind_warning`]).
    pub fn warning(&self) -> Option<String> {
        behind_warning(&self.name, &self.side, self.front, self.back)
    }
}

/// The back's share of a surface's light (`front` and `back` mean illuminances, lx)
/// when more than a tenth of it arrives there and `side` is `both`: the side a designer
/// rarely means (a ceiling lit from above, a desk from below), worth a warning.
pub fn much_from_behind(side: &str, front: f64, back: f64) -> Option<f64> {
    let total = front + back;
    let share = if total > 0.0 { back / total } else { 0.0 };
    (side == "both" && share > 0.1).then_some(share)
}

/// The warning for surface `name` counted on `side` when [`much_from_behind`], with
/// both figures and the flag that picks a side (`--side`, the same in `measure` and
/// `map`).
pub fn behind_warning(name: &str, side: &str, front: f64, back: f64) -> Option<String> {
    much_from_behind(side, front, back).map(|share| {
        format!(
            "'{name}' receives {:.0} % of its light on its back ({} lx on its back, {} lx on its front): add --side front if only the front counts, or --side back if its triangles face away from the room",
            100.0 * share,
            invlight_stats::significant(back),
            invlight_stats::significant(front)
        )
    })
}

/// `invlight measure --json`: a measurement with its settings and costs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeasureReport {
    /// The measured surfaces, in the order asked.
    pub surfaces: Vec<SurfaceReport>,
    /// Photons traced (whole groups).
    pub photons: u64,
    /// Rays along the photons' paths.
    pub rays: u64,
    /// Rays of connections to the surfaces.
    pub connection_rays: u64,
    /// [`Estimator::name`].
    pub estimator: String,
    /// The scene's luminous flux, lm.
    pub flux_lm: f64,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// Seed of the photon streams.
    pub seed: u64,
    /// Bounce cap.
    pub max_bounces: u32,
    /// [`TraceSettings::roulette`]: where the Russian roulette started, as a share of a
    /// photon's emitted power.
    #[serde(default = "classic_roulette")]
    pub roulette: f32,
    /// Photons of the pilot that chose `roulette` ([`crate::tune_roulette`]), beside
    /// `photons`; 0 when it was given.
    #[serde(default)]
    pub pilot_photons: u64,
    /// Rays of that pilot, beside `rays` and `connection_rays`.
    #[serde(default)]
    pub pilot_rays: u64,
    /// Seconds from the start of the build to the end of the trace.
    pub seconds: f64,
    /// Seconds building the acceleration structure.
    pub build_seconds: f64,
    /// The unobstructed horizontal illuminance of the overcast sky a daylight factor is
    /// measured under, lx; absent when the surfaces' factors are not asked for.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unobstructed_lux: Option<f64>,
}

/// The roulette of a report written before it was a setting.
fn classic_roulette() -> f32 {
    1.0
}

impl MeasureReport {
    /// The report with each surface's daylight factor under a sky that gives an
    /// unobstructed horizontal plane `unobstructed_lux` ([`DaylightFactor`]), when given.
    pub fn with_daylight_factor(mut self, unobstructed_lux: Option<f64>) -> MeasureReport {
        let Some(unobstructed_lux) = unobstructed_lux else {
            return self;
        };
        let k = 100.0 / unobstructed_lux;
        for s in &mut self.surfaces {
            s.daylight_factor = Some(DaylightFactor {
                mean: k * s.mean,
                low: k * s.low,
                high: k * s.high,
                std_error: k * s.std_error,
            });
        }
        self.unobstructed_lux = Some(unobstructed_lux);
        self
    }

    /// The report as a table for people: a row per surface, then the costs.
    pub fn table(&self) -> String {
        use invlight_stats::significant;
        let width = self
            .surfaces
            .iter()
            .map(|s| s.name.len())
            .max()
            .unwrap_or(7)
            .max(7);
        let percent = self.confidence * 100.0;
        let mut out = format!(
            "{:<width$}  {:>10}  {:>12}  {:>27}  {:>10}",
            "surface",
            "area m²",
            "mean lx",
            format!("{percent:.0} % interval lx"),
            "hits"
        );
        if self.unobstructed_lux.is_some() {
            out += &format!(
                "  {:>8}  {:>22}",
                "DF %",
                format!("{percent:.0} % interval DF %")
            );
        }
        out += "\n";
        for s in &self.surfaces {
            out += &format!(
                "{:<width$}  {:>10.4}  {:>12}  {:>27}  {:>10}",
                s.name,
                s.area,
                significant(s.mean),
                format!("[{}, {}]", significant(s.low), significant(s.high)),
                s.hits
            );
            if let Some(df) = &s.daylight_factor {
                let interval = format!("[{}, {}]", significant(df.low), significant(df.high));
                out += &format!("  {:>8}  {interval:>22}", significant(df.mean));
            }
            out += "\n";
        }
        if let Some(lux) = self.unobstructed_lux {
            out += &format!(
                "daylight factor: E / {} lx, the CIE overcast sky's on an unobstructed horizontal plane\n",
                significant(lux)
            );
        }
        out += &format!(
            "{} photons, {} rays and {} connection rays, {:.2} s ({:.2} M photons/s), {} lm emitted\n",
            self.photons,
            self.rays,
            self.connection_rays,
            self.seconds,
            self.photons as f64 / self.seconds / 1e6,
            significant(self.flux_lm)
        );
        if self.pilot_photons > 0 {
            out += &format!(
                "Russian roulette from {} of a photon's power, chosen by a pilot of {} photons and {} rays (--roulette)\n",
                self.roulette, self.pilot_photons, self.pilot_rays
            );
        }
        out
    }
}

impl Measurement {
    /// The report of this measurement of surfaces named `names` (in target order), each
    /// counted on `side`, with intervals at `confidence`, traced with `settings` and
    /// `estimator` after the pilot `roulette` chose its roulette.
    pub fn report(
        &self,
        names: &[String],
        side: Side,
        confidence: Confidence,
        (settings, estimator, roulette): (&TraceSettings, Estimator, &RouletteChoice),
        (seconds, build_seconds): (f64, f64),
    ) -> MeasureReport {
        let z = confidence.z();
        let all = vec![1.0; self.components()];
        MeasureReport {
            surfaces: names
                .iter()
                .enumerate()
                .map(|(i, name)| {
                    let e = self.estimate_of(i, side, &all);
                    let interval = e.interval(z);
                    SurfaceReport {
                        name: name.clone(),
                        area: self.areas[i],
                        mean: e.mean,
                        low: interval.low,
                        high: interval.high,
                        std_error: e.std_error,
                        hits: self.hits[i],
                        side: side.name().into(),
                        front: self.estimate_of(i, Side::Front, &all).mean,
                        back: self.estimate_of(i, Side::Back, &all).mean,
                        daylight_factor: None,
                    }
                })
                .collect(),
            photons: self.photons,
            rays: self.rays,
            connection_rays: self.connection_rays,
            estimator: estimator.name().into(),
            flux_lm: self.flux,
            confidence: confidence.level(),
            seed: settings.seed,
            max_bounces: settings.max_bounces,
            roulette: settings.roulette,
            pilot_photons: roulette.photons,
            pilot_rays: roulette.rays,
            seconds,
            build_seconds,
            unobstructed_lux: None,
        }
    }
}
