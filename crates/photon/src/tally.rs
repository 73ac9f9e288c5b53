//! One chunk's tally of photons on the measured targets ([`ChunkTally`]): which targets
//! an instance belongs to, which grids lie on each target and which component each
//! source's light counts for, and the visitor that adds each arrival and connection to
//! the surfaces' and the grids' sums.

use crate::cells::CellTallies;
use crate::channels::{SurfaceTallies, channel};
use crate::cluster::Pack;
use crate::connect::{Departure, Targets};
use crate::measure::{GridRequest, GridValues};
use crate::path::PathVisitor;
use crate::sampler::Sampler;
use glam::Vec3;
use invlight_scene::{InstanceId, Rgb, Scene, SurfaceId, luminance};
use invlight_trace::{Accel, Interaction};

/// Which targets each instance belongs to (a compressed sparse row table: an instance
/// may be under several names, e.g. a node and its parent).
pub(crate) struct TargetMap {
    offsets: Vec<u32>,
    targets: Vec<u32>,
}

impl TargetMap {
    pub(crate) fn new(scene: &Scene, targets: &[SurfaceId]) -> TargetMap {
        let mut per_instance: Vec<Vec<u32>> = vec![Vec::new(); scene.instances.len()];
        for (t, &s) in targets.iter().enumerate() {
            for &i in &scene.surfaces[s].instances {
                per_instance[i.index()].push(t as u32);
            }
        }
        let mut offsets = vec![0u32];
        let mut flat = Vec::new();
        for list in per_instance {
            flat.extend(list);
            offsets.push(flat.len() as u32);
        }
        TargetMap {
            offsets,
            targets: flat,
        }
    }

    #[inline]
    fn of(&self, instance: InstanceId) -> &[u32] {
        let i = instance.index();
        &self.targets[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}

/// What a chunk's tally shares with every other: the maps from instances to targets,
/// from targets to their grids and from sources to components.
pub(crate) struct Plan<'a> {
    pub(crate) map: TargetMap,
    /// The grids of each target, by index in the request's grids.
    pub(crate) grids_of: Vec<Vec<usize>>,
    pub(crate) grids: &'a [GridRequest],
    pub(crate) component_of: Vec<u32>,
    pub(crate) components: usize,
}

/// Tallies one chunk of photons on the measured targets.
pub(crate) struct ChunkTally<'a> {
    pub(crate) plan: &'a Plan<'a>,
    /// The targets to connect departures to; `None` counts arrivals alone.
    pub(crate) connect: Option<(&'a Targets, &'a Accel)>,
    pub(crate) surfaces: SurfaceTallies,
    pub(crate) cells: Vec<CellTallies>,
    pub(crate) escaped: f64,
    pub(crate) connection_rays: u64,
    /// The point of the last departure connected, and the solid angles its connections
    /// drew by, per target ([`Targets::solid_angles`]): the photon's next arrival comes
    /// from it and weighs itself by them.
    pub(crate) departed: Vec3,
    pub(crate) solid: Vec<Option<f64>>,
}

/// How light reached a target: by the photon's own ray (an arrival) or a connection,
/// whether straight from a point, spot or photometric light, and whether straight from
/// any light.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Arrival {
    arrived: bool,
    direct: bool,
    emitted: bool,
}

impl Arrival {
    fn new(arrived: bool, from: &Departure) -> Arrival {
        Arrival {
            arrived,
            direct: from.lobe.leaves_point_source(),
            emitted: from.emitted,
        }
    }

    /// Whether a grid reading `values` leaves this light out of its cells: a grid read
    /// at points computes its point lights' direct light instead, an indirect one counts
    /// no light's direct light.
    #[inline]
    fn left_out_of(self, values: GridValues) -> bool {
        match values {
            GridValues::Points => self.direct,
            GridValues::CellMeans => false,
            GridValues::Indirect => self.emitted,
        }
    }
}

impl ChunkTally<'_> {
    /// The current photon, of component `k`, brings `lumens` to target `t` at `point`
    /// on its front (`front`) or back.
    #[inline]
    fn add(&mut self, t: u32, k: u32, front: bool, point: Vec3, lumens: f64, from: Arrival) {
        let plan = self.plan;
        self.surfaces
            .add(t, channel(front, k, plan.components), lumens);
        for &g in &plan.grids_of[t as usize] {
            let request = &plan.grids[g];
            if request.side.counts(front) && !from.left_out_of(request.values) {
                self.cells[g].add(request.grid.cell_of(point), k, lumens, from.arrived);
            }
        }
    }
}

impl PathVisitor for ChunkTally<'_> {
    #[inline]
    fn depart(&mut self, from: &Departure, sampler: &mut Sampler<'_>) {
        if let Some((targets, accel)) = self.connect {
            let k = self.plan.component_of[from.source as usize];
            self.departed = from.point;
            for t in 0..targets.len() {
                let solid = targets.solid_angles(t, from);
                self.solid[t] = solid.map(|s| s.total);
                if let Some(c) = targets.connect(t, from, solid.as_ref(), accel, sampler) {
                    self.connection_rays += 1;
                    self.add(
                        t as u32,
                        k,
                        c.front,
                        c.point,
                        c.lumens,
                        Arrival::new(false, from),
                    );
                }
            }
        }
    }

    #[inline]
    fn arrive(&mut self, at: &Interaction, dir: Vec3, power: Rgb, _bounce: u32, from: &Departure) {
        let plan = self.plan;
        let on = plan.map.of(at.instance);
        if on.is_empty() {
            return;
        }
        let lumens = luminance(power);
        let weighing = self
            .connect
            .map(|(targets, _)| (targets, from.arrival_density(at.point, at.normal)));
        let k = plan.component_of[from.source as usize];
        let front = dir.dot(at.normal) < 0.0;
        for &t in on {
            let w = match weighing {
                Some((targets, density)) => {
                    let t = t as usize;
                    let solid = if from.point == self.departed {
                        self.solid[t]
                    } else {
                        targets.solid_angles(t, from).map(|s| s.total)
                    };
                    targets.arrival_weight(t, (from, at.point, at.normal), density, solid)
                }
                None => 1.0,
            };
            self.surfaces.hit(t);
            self.add(
                t,
                k,
                front,
                at.point,
                (lumens * w) as f64,
                Arrival::new(true, from),
            );
        }
    }

    /// A calculation surface receives as any target does: the crossing is an arrival
    /// that the photon survives unchanged.
    #[inline]
    fn cross(&mut self, at: &Interaction, dir: Vec3, power: Rgb, bounce: u32, from: &Departure) {
        self.arrive(at, dir, power, bounce, from);
    }

    #[inline]
    fn escape(&mut self, power: Rgb) {
        self.escaped += luminance(power) as f64;
    }

    #[inline]
    fn end_group(&mut self) {
        self.surfaces.end_group();
        for c in &mut self.cells {
            c.end_group();
        }
    }

    fn bytes(&self) -> usize {
        self.surfaces.bytes() + self.cells.iter().map(CellTallies::bytes).sum::<usize>()
    }
}

impl Pack for ChunkTally<'_> {
    fn pack(&self, out: &mut Vec<u64>) {
        self.surfaces.pack(out);
        self.cells.iter().for_each(|c| c.sums.pack(out));
        out.extend([self.escaped.to_bits(), self.connection_rays]);
    }

    fn unpack(&mut self, mut words: &mut dyn Iterator<Item = u64>) {
        self.surfaces.unpack(&mut words);
        self.cells
            .iter_mut()
            .for_each(|c| c.sums.unpack(&mut words));
        let mut next = || {
            words
                .next()
                .expect("a packed chunk's escaped flux and rays")
        };
        self.escaped = f64::from_bits(next());
        self.connection_rays = next();
    }
}
