//! A target's light kept apart by where it came from and which side it arrived on, so
//! that one trace answers every question a lighting intention asks of it.
//!
//! Illuminance is linear in each light's output: if the photons of a trace are tallied
//! per *component* (a group of lights dimmed together, [`Components`]) the illuminance
//! at any dimming levels w is Σ_k w_k·E_k, with its standard error from the groups'
//! cross products ([`ChannelSums`]). A problem whose only variables are dimming levels
//! traces once; one that also moves things traces once per arrangement.
//!
//! Each arrival and connection also knows which side of the target it reached: the
//! front, which its triangles' counter-clockwise normal faces, or the back. A desk is
//! measured on its top, a ceiling on its room side, and a designer is told when much of
//! a surface's light arrives from behind.

use crate::emit::{Emitters, SourceOrigin};
use invlight_scene::{InstanceId, LightId, Scene};
use invlight_stats::ChannelSums;

/// Which side of a surface counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Side {
    /// The side the surface's counter-clockwise normal faces: a desk's top, a screen's
    /// display.
    Front,
    /// The other side.
    Back,
    /// Every arrival, whichever side (the thesis' rule, and the default).
    #[default]
    Both,
}

/// A `--side` that names no side: the text given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SideParseError(pub String);

impl std::fmt::Display for SideParseError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "'{}': expected front, back or both", self.0)
    }
}

impl std::error::Error for SideParseError {}

impl std::str::FromStr for Side {
    type Err = SideParseError;

    /// The spelling of `--side` and of a problem file's `side`: `front`, `back` or `both`.
    fn from_str(s: &str) -> Result<Side, SideParseError> {
        Side::parse(s).ok_or_else(|| SideParseError(s.to_string()))
    }
}

impl Side {
    /// The problem-file spelling: `front`, `back` or `both`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Front => "front",
            Side::Back => "back",
            Side::Both => "both",
        }
    }

    /// Parses the problem-file spelling.
    pub fn parse(s: &str) -> Option<Side> {
        [Side::Front, Side::Back, Side::Both]
            .into_iter()
            .find(|side| side.name() == s)
    }

    /// Whether light reaching the front (`front`) or the back counts.
    #[inline]
    pub fn counts(self, front: bool) -> bool {
        match self {
            Side::Front => front,
            Side::Back => !front,
            Side::Both => true,
        }
    }
}

/// Which component each light and each emissive instance belongs to: the lights dimmed
/// together (a `lightPower` variable) share one; the rest, and the sky (daylight, which
/// no variable dims), are component 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Components {
    count: usize,
    of_light: Vec<u32>,
    of_instance: Vec<u32>,
}

impl Components {
    /// One component holding every light of `scene`.
    pub fn one(scene: &Scene) -> Components {
        Components::new(scene, 1)
    }

    /// `count` components (at least one) over `scene`'s lights, every light in
    /// component 0 until [`Components::set_light`] or [`Components::set_instance`]
    /// moves it.
    pub fn new(scene: &Scene, count: usize) -> Components {
        Components {
            count: count.max(1),
            of_light: vec![0; scene.lights.len()],
            of_instance: vec![0; scene.instances.len()],
        }
    }

    /// The number of components.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Puts light `light` in component `k`.
    ///
    /// # Panics
    /// If `k` is not below [`Components::count`] or the light is not the scene's.
    pub fn set_light(&mut self, light: LightId, k: usize) {
        assert!(k < self.count, "component {k} of {}", self.count);
        self.of_light[light.index()] = k as u32;
    }

    /// Puts the emissive triangles of instance `instance` in component `k`.
    ///
    /// # Panics
    /// If `k` is not below [`Components::count`] or the instance is not the scene's.
    pub fn set_instance(&mut self, instance: InstanceId, k: usize) {
        assert!(k < self.count, "component {k} of {}", self.count);
        self.of_instance[instance.index()] = k as u32;
    }

    /// The component of light `light`.
    pub fn of_light(&self, light: LightId) -> usize {
        self.of_light.get(light.index()).map_or(0, |&k| k as usize)
    }

    /// The component of instance `instance`'s emissive triangles.
    pub fn of_instance(&self, instance: InstanceId) -> usize {
        self.of_instance
            .get(instance.index())
            .map_or(0, |&k| k as usize)
    }

    /// The component of every source of `emitters`, by source index.
    pub fn of_sources(&self, emitters: &Emitters) -> Vec<u32> {
        (0..emitters.len() as u32)
            .map(|s| match emitters.origin(s) {
                SourceOrigin::Light(l) => self.of_light.get(l.index()).copied().unwrap_or(0),
                SourceOrigin::Instance(i) => self.of_instance.get(i.index()).copied().unwrap_or(0),
                SourceOrigin::Sky => 0,
            })
            .collect()
    }

    /// The luminous flux of each component, lm, as `emitters` emit it.
    pub fn flux(&self, emitters: &Emitters) -> Vec<f64> {
        let mut flux = vec![0.0; self.count];
        for (s, k) in self.of_sources(emitters).into_iter().enumerate() {
            flux[k as usize] += emitters.flux(s as u32);
        }
        flux
    }
}

/// The channel of a target's light from component `k` of `components` on a side: the
/// front's channels first, then the back's.
#[inline]
pub(crate) fn channel(front: bool, k: u32, components: usize) -> usize {
    if front {
        k as usize
    } else {
        components + k as usize
    }
}

/// The channel weights of `side` at component weights `w`: `w` on the channels of the
/// sides that count, 0 on the others.
pub(crate) fn side_weights(side: Side, w: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 * w.len());
    for front in [true, false] {
        let on = side.counts(front);
        out.extend(w.iter().map(|&x| if on { x } else { 0.0 }));
    }
    out
}

/// One chunk's sums over the measured surfaces, built photon by photon: a group's
/// channel totals per target are summed first and folded into the target's
/// [`ChannelSums`] at [`SurfaceTallies::end_group`]. Only the targets the group touched
/// are visited then, so a photon costs its contributions, not the number of targets.
/// Each group's totals are also kept in order ([`SurfaceTallies::groups`]): the search
/// compares two configurations by their groups' paired differences, and
/// copying a group's few channels per target is nothing beside tracing its 64 photons.
#[derive(Debug, Clone)]
pub(crate) struct SurfaceTallies {
    channels: usize,
    pub(crate) sums: Vec<ChannelSums>,
    pub(crate) hits: Vec<u64>,
    /// Every group's channel totals, group by group, target by target within a group,
    /// when kept.
    pub(crate) groups: Vec<f64>,
    keep_groups: bool,
    current: Vec<f64>,
    touched: Vec<u32>,
    is_touched: Vec<bool>,
}

impl SurfaceTallies {
    /// Empty sums of `targets` targets with `components` components (2 per side),
    /// keeping every group's totals when `keep_groups`.
    pub(crate) fn new(targets: usize, components: usize, keep_groups: bool) -> SurfaceTallies {
        let channels = 2 * components;
        SurfaceTallies {
            channels,
            sums: vec![ChannelSums::new(channels); targets],
            hits: vec![0; targets],
            groups: Vec::new(),
            keep_groups,
            current: vec![0.0; targets * channels],
            touched: Vec::new(),
            is_touched: vec![false; targets],
        }
    }

    /// The current photon brings `lumens` to `target` on `channel`.
    #[inline]
    pub(crate) fn add(&mut self, target: u32, channel: usize, lumens: f64) {
        if lumens == 0.0 {
            return;
        }
        let t = target as usize;
        if !self.is_touched[t] {
            self.is_touched[t] = true;
            self.touched.push(target);
        }
        self.current[t * self.channels + channel] += lumens;
    }

    /// A photon arrived on `target`.
    #[inline]
    pub(crate) fn hit(&mut self, target: u32) {
        self.hits[target as usize] += 1;
    }

    /// The current group ended: its totals join the sums.
    #[inline]
    pub(crate) fn end_group(&mut self) {
        if self.keep_groups {
            self.groups.extend_from_slice(&self.current);
        }
        for &t in &self.touched {
            let t = t as usize;
            let x = &mut self.current[t * self.channels..(t + 1) * self.channels];
            self.sums[t].add_group(x);
            x.fill(0.0);
            self.is_touched[t] = false;
        }
        self.touched.clear();
    }

    /// Adds these sums to `sums` and `hits`, target by target.
    pub(crate) fn add_to(&self, sums: &mut [ChannelSums], hits: &mut [u64]) {
        for (total, s) in sums.iter_mut().zip(&self.sums) {
            total.merge(s);
        }
        for (total, h) in hits.iter_mut().zip(&self.hits) {
            *total += h;
        }
    }

    /// Appends what [`SurfaceTallies::add_to`] and the kept groups hand on to `out`
    /// (a chunk's, for a shared trace, [`crate::Pack`]).
    pub(crate) fn pack(&self, out: &mut Vec<u64>) {
        self.sums.iter().for_each(|s| s.pack(out));
        out.extend(&self.hits);
        out.push(self.groups.len() as u64);
        out.extend(self.groups.iter().map(|x| x.to_bits()));
    }

    /// Reads back what [`SurfaceTallies::pack`] wrote, into tallies of the same targets.
    pub(crate) fn unpack(&mut self, words: &mut impl Iterator<Item = u64>) {
        self.sums.iter_mut().for_each(|s| s.unpack(words));
        let mut next = || words.next().expect("packed tallies of as many targets");
        for h in &mut self.hits {
            *h = next();
        }
        let kept = next() as usize;
        self.groups = (0..kept).map(|_| f64::from_bits(next())).collect();
    }

    /// Bytes held, for sizing the blocks of chunks traced at a time.
    pub(crate) fn bytes(&self) -> usize {
        let per = self.channels * (self.channels + 5) / 2;
        let groups = (crate::chunks::CHUNK / crate::estimator::GROUP) as usize;
        let kept = if self.keep_groups {
            groups * self.current.len()
        } else {
            0
        };
        8 * (self.sums.len() * (per + 2) + kept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn side_weights_pick_the_sides_channels() {
        let w = [2.0, 0.5];
        assert_eq!(side_weights(Side::Front, &w), [2.0, 0.5, 0.0, 0.0]);
        assert_eq!(side_weights(Side::Back, &w), [0.0, 0.0, 2.0, 0.5]);
        assert_eq!(side_weights(Side::Both, &w), [2.0, 0.5, 2.0, 0.5]);
        assert_eq!(channel(true, 1, 2), 1);
        assert_eq!(channel(false, 1, 2), 3);
        for side in [Side::Front, Side::Back, Side::Both] {
            assert_eq!(Side::parse(side.name()), Some(side));
        }
    }

    #[test]
    fn a_group_is_summed_before_it_is_squared() {
        let mut t = SurfaceTallies::new(2, 1, true);
        t.add(1, 0, 1.0);
        t.add(1, 0, 2.0);
        t.add(1, 1, 4.0);
        t.end_group();
        t.add(1, 0, 1.0);
        t.end_group();
        let both = [1.0, 1.0];
        assert_eq!(t.sums[1].total(&both), 8.0);
        // Groups (3, 4) and (1, 0): Σ (x·1)² = 7² + 1².
        assert_eq!(t.sums[1].product(&both, &both), 50.0);
        assert_eq!(t.sums[0].total(&both), 0.0);
        // Both groups kept in order, target 0's two channels before target 1's.
        assert_eq!(t.groups, [0.0, 0.0, 3.0, 4.0, 0.0, 0.0, 1.0, 0.0]);
    }
}
