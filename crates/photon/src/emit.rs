//! Photon emission from every light kind, each light chosen with probability proportional
//! to its luminous flux (thesis App. C.3; pbrt-v4 `PowerLightSampler`), and each photon
//! drawn from the light's own emission profile, so that every photon carries the same
//! luminous power: the scene's total flux. Equal powers keep the per-photon variance, and
//! so the reported intervals, as small as this estimator allows.
//!
//! The one exception is the goniometric light (a photometric file): its directions come
//! from a piecewise-constant density over the table's cells while its intensity is
//! bilinear inside them, so its photons carry the total flux times r = I/(Φ·p), whose
//! mean is 1 and which stays near 1 on the fine tables of real files (see
//! `connect`'s module doc; the variance grows by the factor E[r²]).
//!
//! The sky ([`Scene::sky`], a CIE sky of `invlight_scene::daylight`) is light from every
//! direction of the upper hemisphere. Each of its photons draws a direction ω from the
//! sky's luminance (density p(ω) = L(ω)/∫L dω, `Sky::sample`) and starts on a disk
//! across ω that covers the scene's bounding sphere, as the sun's do (thesis §4.5): the
//! sky's flux into the sphere is π r² ∫ L dω, and every photon carries its share of it
//! times L(ω)/(p(ω)·∫ L dω), 1 for the overcast sky and near 1 for the clear sky's
//! table, so that its expected power per steradian is the sky's (pbrt-v4's
//! `ImageInfiniteLight::SampleLe` draws the same way). For one ω the
//! photon is a parallel beam, so connections and their weights are the sun's
//! ([`Lobe::Parallel`]): the connection to a target point y along ω is the sky's
//! luminance toward ω times cos θ_y over p(ω), the next-event estimate of the sky with
//! the sky's own density, and p(ω) cancels between the two strategies' densities.

use crate::connect::Lobe;
use crate::sampler::Sampler;
use crate::sampling;
use glam::{Mat3, Vec3};
use invlight_scene::daylight::Sky;
use invlight_scene::{InstanceId, LightId, LightKind, Opening, Photometry, Rgb, Scene, luminance};
use invlight_stats::Distribution1D;
use std::f32::consts::PI;
use std::sync::Arc;

/// Where a photon starts, where it goes and the (RGB) power it carries, lm.
#[derive(Debug, Clone, Copy)]
pub struct EmitSample<'a> {
    /// Starting point.
    pub origin: Vec3,
    /// Unit direction of travel.
    pub dir: Vec3,
    /// Front-face normal when the photon leaves a surface (area lights), for offsetting.
    pub surface_normal: Option<Vec3>,
    /// RGB power, whose luminance is the scene's total flux (times the lobe's weight
    /// along `dir` for a goniometric light).
    pub power: Rgb,
    /// The luminance of the power a photon of this light carries along a direction of
    /// weight 1: the scene's total flux, lm (the departure's `lumens`).
    pub lumens: f32,
    /// The light's emission profile, which `dir` was drawn from (for connections).
    pub lobe: Lobe<'a>,
    /// Index of the source the photon left ([`Emitters::origin`] says which light or
    /// instance it is), so that tallies can keep each light's light apart.
    pub source: u32,
}

/// A light whose direct light is computed at points ([`Emitters::point_source`]).
#[derive(Debug, Clone)]
pub(crate) struct PointSource<'a> {
    /// Its emission profile: intensity toward ω is `flux` · p(ω) · r(ω)
    /// ([`Lobe::pdf_and_weight`]).
    pub lobe: Lobe<'a>,
    /// Its luminous flux, lm, undimmed.
    pub flux: f64,
    /// Its photometric centre.
    pub centre: Vec3,
    /// The largest dimension of its luminous opening, m (0 for a point).
    pub size: f32,
    /// The points its light leaves from, each carrying an equal share.
    pub points: Vec<Vec3>,
}

/// What a source of [`Emitters`] is in the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SourceOrigin {
    /// `scene.lights[i]`.
    Light(LightId),
    /// An emissive triangle of this instance.
    Instance(InstanceId),
    /// The sky ([`Scene::sky`]).
    Sky,
}

/// An emissive triangle of a scene, in world space: an area light that emits from its
/// front, counter-clockwise face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmissiveTriangle {
    /// Corners, counter-clockwise seen from the front.
    pub corners: [Vec3; 3],
    /// Unit front normal: the normalized cross product of the world-space edges, so a
    /// mirrored instance keeps its counter-clockwise front (as `invlight_trace` does).
    pub normal: Vec3,
    /// Luminance of the emission, RGB cd/m².
    pub emission: Rgb,
    /// Area, m² (positive: degenerate triangles are left out).
    pub area: f32,
}

/// Every emissive triangle of `scene`, instance by instance in scene order. The photon
/// emitters and the renderer's shadow-ray lights both read the lights here, so they
/// cannot disagree about where a light is or which way it faces.
pub fn emissive_triangles(scene: &Scene) -> impl Iterator<Item = EmissiveTriangle> + '_ {
    emissive_triangles_of(scene).map(|(_, t)| t)
}

/// [`emissive_triangles`] with the instance of each.
fn emissive_triangles_of(
    scene: &Scene,
) -> impl Iterator<Item = (InstanceId, EmissiveTriangle)> + '_ {
    // A calculation surface does not touch the light: it emits none either.
    let calculation = scene.calculation_instances();
    scene.all_world_triangles().filter_map(move |(i, t)| {
        if calculation[i.index()] {
            return None;
        }
        let emission = scene.materials[t.material].emission;
        let area = t.area();
        (emission.max_element() > 0.0 && area > 0.0).then(|| {
            (
                i,
                EmissiveTriangle {
                    corners: t.corners,
                    normal: t.normal(),
                    emission,
                    area,
                },
            )
        })
    })
}

/// One emitting thing, with the RGB power a photon carries when it is chosen.
#[derive(Debug, Clone)]
enum Source {
    Point {
        position: Vec3,
        power: Rgb,
    },
    /// glTF spot: full intensity inside the inner cone, falling as t² (t linear in cos θ)
    /// to zero at the outer cone.
    Spot {
        position: Vec3,
        axis: Vec3,
        cos_inner: f32,
        cos_outer: f32,
        /// Share of the flux inside the inner cone, which chooses between the two parts.
        flat_share: f32,
        power: Rgb,
    },
    /// Sun: a disk perpendicular to the direction, centred on the scene's bounding sphere
    /// and of its radius, placed outside it (thesis §4.5, fig. 4.8).
    Directional {
        direction: Vec3,
        centre: Vec3,
        radius: f32,
        power: Rgb,
    },
    /// A photometric table at `position` turned by `frame` (local → world), emitting
    /// from its luminous opening; `power` is what a photon of weight 1 carries.
    Goniometric {
        position: Vec3,
        frame: Mat3,
        photometry: Arc<Photometry>,
        power: Rgb,
    },
    /// The sky: a direction from its luminance, then a point on the disk across it
    /// that covers the bounding sphere (centre, radius), placed outside it.
    Sky {
        sky: Arc<Sky>,
        centre: Vec3,
        radius: f32,
        power: Rgb,
    },
    /// An emissive triangle (Lambertian, front face).
    Triangle {
        p0: Vec3,
        e1: Vec3,
        e2: Vec3,
        normal: Vec3,
        power: Rgb,
    },
}

/// The lights of a scene as a distribution to draw photons from.
#[derive(Debug, Clone, Default)]
pub struct Emitters {
    sources: Vec<Source>,
    /// What each source is.
    origins: Vec<SourceOrigin>,
    /// Each source's luminous flux, lm.
    flux: Vec<f64>,
    /// The sources by luminous flux.
    by_flux: Distribution1D,
}

impl Emitters {
    /// Collects every light of `scene`: point, spot and directional lights, every
    /// emissive triangle and the sky.
    pub fn new(scene: &Scene) -> Emitters {
        let mut flux_rgb: Vec<Rgb> = Vec::new();
        let mut sources = Vec::new();
        let (centre, radius) = match scene.bounds() {
            Some((lo, hi)) => ((lo + hi) * 0.5, ((hi - lo).length() * 0.5).max(1e-3)),
            None => (Vec3::ZERO, 1.0),
        };
        let mut origins = Vec::new();
        for (l, light) in scene.lights.iter().enumerate() {
            origins.push(SourceOrigin::Light(LightId::from_index(l)));
            let flux = light.kind.flux();
            match light.kind {
                LightKind::Point { position, .. } => sources.push(Source::Point {
                    position,
                    power: Vec3::ZERO,
                }),
                LightKind::Spot {
                    position,
                    direction,
                    inner,
                    outer,
                    ..
                } => {
                    let cos_inner = inner.cos();
                    let cos_outer = outer.cos().min(cos_inner);
                    let flat = 1.0 - cos_inner;
                    let ring = (cos_inner - cos_outer) / 3.0;
                    sources.push(Source::Spot {
                        position,
                        axis: direction.normalize(),
                        cos_inner,
                        cos_outer,
                        flat_share: flat / (flat + ring).max(f32::MIN_POSITIVE),
                        power: Vec3::ZERO,
                    })
                }
                LightKind::Goniometric {
                    position,
                    frame,
                    ref photometry,
                    ..
                } => sources.push(Source::Goniometric {
                    position,
                    frame,
                    photometry: photometry.clone(),
                    power: Vec3::ZERO,
                }),
                LightKind::Directional { direction, .. } => {
                    sources.push(Source::Directional {
                        direction: direction.normalize(),
                        centre,
                        radius,
                        power: Vec3::ZERO,
                    });
                    flux_rgb.push(flux * (PI * radius * radius));
                    continue;
                }
            }
            flux_rgb.push(flux);
        }
        for (i, t) in emissive_triangles_of(scene) {
            origins.push(SourceOrigin::Instance(i));
            let [a, b, c] = t.corners;
            sources.push(Source::Triangle {
                p0: a,
                e1: b - a,
                e2: c - a,
                normal: t.normal,
                power: Vec3::ZERO,
            });
            // A Lambertian emitter of radiance L sends π·L per unit area.
            flux_rgb.push(t.emission * (PI * t.area));
        }
        if let Some(sky) = &scene.sky {
            origins.push(SourceOrigin::Sky);
            sources.push(Source::Sky {
                sky: sky.clone(),
                centre,
                radius,
                power: Vec3::ZERO,
            });
            // White light of luminance L from each direction through a disk of π r².
            let flux = sky.dome_luminance() * std::f64::consts::PI * (radius as f64).powi(2);
            flux_rgb.push(Vec3::splat(flux as f32));
        }
        let by_flux = Distribution1D::new(flux_rgb.iter().map(|&f| luminance(f) as f64));
        let total = by_flux.total();
        for (source, flux) in sources.iter_mut().zip(&flux_rgb) {
            let y = luminance(*flux) as f64;
            // Chosen with probability y / total, a photon carries flux · total / y.
            let power = if y > 0.0 {
                *flux * (total / y) as f32
            } else {
                Vec3::ZERO
            };
            match source {
                Source::Point { power: p, .. }
                | Source::Spot { power: p, .. }
                | Source::Directional { power: p, .. }
                | Source::Goniometric { power: p, .. }
                | Source::Sky { power: p, .. }
                | Source::Triangle { power: p, .. } => *p = power,
            }
        }
        let flux = flux_rgb.iter().map(|&f| luminance(f) as f64).collect();
        Emitters {
            sources,
            origins,
            flux,
            by_flux,
        }
    }

    /// The number of sources (lights, emissive triangles and the sky).
    pub fn len(&self) -> usize {
        self.sources.len()
    }

    /// What source `i` (an [`EmitSample::source`]) is in the scene.
    pub fn origin(&self, i: u32) -> SourceOrigin {
        self.origins[i as usize]
    }

    /// The luminous flux of source `i`, lm.
    pub fn flux(&self, i: u32) -> f64 {
        self.flux[i as usize]
    }

    /// Total luminous flux of the scene's lights, lm (for the sun and the sky: what
    /// crosses the disks that cover the scene).
    pub fn total_flux(&self) -> f64 {
        self.by_flux.total()
    }

    /// Whether the scene has no light at all.
    pub fn is_empty(&self) -> bool {
        self.total_flux() <= 0.0
    }

    /// Source `i` as a light whose direct light at a point is computed rather than
    /// traced (`direct.rs`): a point, spot or photometric light, with the lobe its
    /// photons leave by, its luminous flux and the points of its luminous opening its
    /// light is taken to leave from (`n` × `n` stratified over the opening, the midpoint
    /// of each stratum; one for a point). `None` for the sun, the sky and emissive
    /// triangles, whose direct light the photons carry.
    pub(crate) fn point_source(&self, i: usize, n: u32) -> Option<PointSource<'_>> {
        let at = |position: Vec3| (position, 0.0, vec![position]);
        let (lobe, (centre, size, points)) = match self.sources[i] {
            Source::Point { position, .. } => (Lobe::Sphere, at(position)),
            Source::Spot {
                position,
                axis,
                cos_inner,
                cos_outer,
                flat_share,
                ..
            } => (
                Lobe::Spot {
                    axis,
                    cos_inner,
                    cos_outer,
                    flat_share,
                },
                at(position),
            ),
            Source::Goniometric {
                position,
                frame,
                ref photometry,
                ..
            } => {
                let points = match photometry.opening {
                    Opening::Point => at(position),
                    opening => {
                        let mid = |k: u32| (k as f32 + 0.5) / n as f32;
                        let [a, b] = opening.extents();
                        let points = (0..n * n)
                            .map(|k| position + frame * opening.point(mid(k % n), mid(k / n)))
                            .collect();
                        (position, a.max(b), points)
                    }
                };
                let lobe = Lobe::Goniometric {
                    to_local: frame.transpose(),
                    photometry,
                };
                (lobe, points)
            }
            Source::Directional { .. } | Source::Sky { .. } | Source::Triangle { .. } => {
                return None;
            }
        };
        Some(PointSource {
            lobe,
            flux: self.flux[i],
            centre,
            size,
            points,
        })
    }

    /// Draws a photon. Must not be called when [`Emitters::is_empty`]. Every light kind
    /// draws the same dimensions (which light, then two pairs), so the photons of a
    /// stratified group stay aligned dimension by dimension whichever light they leave.
    #[inline]
    pub fn sample(&self, sampler: &mut Sampler<'_>) -> EmitSample<'_> {
        let index = self.by_flux.sample(sampler.uniform());
        let (u1, u2) = sampler.uniform2();
        let (u3, u4) = sampler.uniform2();
        let draw = PhotonDraw {
            source: index as u32,
            u: [u1, u2, u3, u4],
        };
        match self.sources[index] {
            Source::Point { position, power } => draw.point(position, power),
            Source::Spot {
                position,
                axis,
                cos_inner,
                cos_outer,
                flat_share,
                power,
            } => draw.spot(position, axis, [cos_inner, cos_outer], flat_share, power),
            Source::Directional {
                direction,
                centre,
                radius,
                power,
            } => draw.directional(direction, centre, radius, power),
            Source::Sky {
                ref sky,
                centre,
                radius,
                power,
            } => draw.sky(sky, centre, radius, power),
            Source::Triangle {
                p0,
                e1,
                e2,
                normal,
                power,
            } => draw.triangle(p0, e1, e2, normal, power),
            Source::Goniometric {
                position,
                frame,
                ref photometry,
                power,
            } => draw.goniometric(position, frame, photometry, power),
        }
    }
}

/// What a photon has drawn before its light's kind shapes it: the source it leaves and
/// the four uniform numbers every kind reads, (u1, u2) the stratified pair. Each kind
/// turns them into a photon in a method of its own, inlined into [`Emitters::sample`].
#[derive(Debug, Clone, Copy)]
struct PhotonDraw {
    /// Index of the source (an [`EmitSample::source`]).
    source: u32,
    /// The uniform numbers u1 … u4.
    u: [f32; 4],
}

impl PhotonDraw {
    /// A point light's photon: a direction uniform over the sphere from (u1, u2).
    #[inline]
    fn point(self, position: Vec3, power: Rgb) -> EmitSample<'static> {
        let [u1, u2, _, _] = self.u;
        EmitSample {
            source: self.source,
            origin: position,
            dir: sampling::sphere(u1, u2),
            surface_normal: None,
            power,
            lumens: luminance(power),
            lobe: Lobe::Sphere,
        }
    }

    /// A spot light's photon: u3 chooses between the inner cone and the ring out to the
    /// outer cone (the inner cone with probability `flat_share`), u1 the angle from the
    /// axis within it and u2 the turn about the axis.
    #[inline]
    fn spot(
        self,
        position: Vec3,
        axis: Vec3,
        [cos_inner, cos_outer]: [f32; 2],
        flat_share: f32,
        power: Rgb,
    ) -> EmitSample<'static> {
        let [u1, u2, u3, _] = self.u;
        let cos_theta = if u3 < flat_share {
            // Uniform in solid angle inside the inner cone.
            1.0 - u1 * (1.0 - cos_inner)
        } else {
            // Density ∝ t² on t ∈ [0, 1]: t = u^(1/3).
            cos_outer + u1.cbrt() * (cos_inner - cos_outer)
        };
        EmitSample {
            source: self.source,
            origin: position,
            dir: sampling::cone(axis, cos_theta, u2),
            surface_normal: None,
            power,
            lumens: luminance(power),
            lobe: Lobe::Spot {
                axis,
                cos_inner,
                cos_outer,
                flat_share,
            },
        }
    }

    /// The sun's photon: along `direction`, from a point of the disk across it (from
    /// (u1, u2)) that covers the scene's bounding sphere, placed outside it.
    #[inline]
    fn directional(
        self,
        direction: Vec3,
        centre: Vec3,
        radius: f32,
        power: Rgb,
    ) -> EmitSample<'static> {
        let [u1, u2, _, _] = self.u;
        let (x, y) = sampling::disk(u1, u2);
        let (t, b) = sampling::basis(direction);
        EmitSample {
            source: self.source,
            origin: centre + (t * x + b * y - direction * 1.01) * radius,
            dir: direction,
            surface_normal: None,
            power,
            lumens: luminance(power),
            lobe: Lobe::Parallel {
                direction,
                area: PI * radius * radius,
            },
        }
    }

    /// The sky's photon: a direction from the sky's luminance (from the stratified pair
    /// (u1, u2)), then a point from (u3, u4) on the disk across it that covers the
    /// bounding sphere, its power weighted by r = L/(p·∫L dω).
    #[inline]
    fn sky(self, sky: &Sky, centre: Vec3, radius: f32, power: Rgb) -> EmitSample<'static> {
        let [u1, u2, u3, u4] = self.u;
        let drawn = sky.sample(u1, u2);
        let to_sky = drawn.to_sky;
        // r = L/(p·∫L dω): exactly 1 for the overcast sky, whose density is ∝ L;
        // near 1 for the clear sky's table, whose cells are uniform where L is not.
        let r = if drawn.pdf > 0.0 {
            (drawn.luminance as f64 / (drawn.pdf as f64 * sky.dome_luminance())) as f32
        } else {
            0.0
        };
        let (x, y) = sampling::disk(u3, u4);
        let (t, b) = sampling::basis(to_sky);
        EmitSample {
            source: self.source,
            origin: centre + (t * x + b * y + to_sky * 1.01) * radius,
            dir: -to_sky,
            surface_normal: None,
            power: power * r,
            lumens: luminance(power * r),
            lobe: Lobe::Parallel {
                direction: -to_sky,
                area: PI * radius * radius,
            },
        }
    }

    /// An emissive triangle's photon: a point uniform over the triangle from (u1, u2),
    /// leaving its front in a cosine-weighted direction from (u3, u4).
    #[inline]
    fn triangle(
        self,
        p0: Vec3,
        e1: Vec3,
        e2: Vec3,
        normal: Vec3,
        power: Rgb,
    ) -> EmitSample<'static> {
        let [u1, u2, u3, u4] = self.u;
        let (b1, b2) = sampling::triangle(u1, u2);
        EmitSample {
            source: self.source,
            origin: p0 + e1 * b1 + e2 * b2,
            dir: sampling::cosine_hemisphere(normal, u3, u4),
            surface_normal: Some(normal),
            power,
            lumens: luminance(power),
            lobe: Lobe::Cosine { normal },
        }
    }

    /// A photometric light's photon: a direction from the table's density (from
    /// (u1, u2)), weighted by the intensity over it, leaving a point of the luminous
    /// opening from (u3, u4).
    #[inline]
    fn goniometric(
        self,
        position: Vec3,
        frame: Mat3,
        photometry: &Photometry,
        power: Rgb,
    ) -> EmitSample<'_> {
        let [u1, u2, u3, u4] = self.u;
        let d = photometry.sample(u1, u2);
        let origin = match photometry.opening {
            Opening::Point => position,
            opening => position + frame * opening.point(u3, u4),
        };
        EmitSample {
            source: self.source,
            origin,
            dir: (frame * d.dir).normalize(),
            surface_normal: None,
            power: power * d.weight,
            lumens: luminance(power),
            lobe: Lobe::Goniometric {
                to_local: frame.transpose(),
                photometry,
            },
        }
    }
}
