//! `invlight render`: a photon-mapped picture of a scene from its camera, or a
//! false-colour picture of the illuminance with a legend in lux.

use crate::InputError;
use crate::args::LoadArgs;
use crate::progress;
use clap::Args;
use glam::DVec3;
use invlight_ilp::{Binding, Configuration, Domain, Problem};
use invlight_photon::DEFAULT_MAX_BOUNCES;
use invlight_render::{
    Exposure, Integrator, Lights, Paths, PhotonMap, PhotonSettings, RenderSettings, Store, ToneMap,
    View, auto_max, false_colour, render, render_illuminance, tone_map,
};
use invlight_scene::Scene;
use invlight_trace::Accel;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `invlight render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file: glTF 2.0 (.gltf, .glb), COLLADA (.dae) or Wavefront OBJ (.obj); with
    /// --config, the problem file (.xml) the solve read.
    pub scene: PathBuf,
    /// Render a configuration a solve found: RESULT#K is member K of the ISOC in RESULT
    /// (a result.json written by `invlight solve`), counted from 1 in result.json's
    /// order, as the solve's pictures isoc-01.png, isoc-02.png, … are (RESULT alone is
    /// member 1, the highest mean). SCENE must then be the problem file, whose scene is
    /// loaded and changed as the configuration says.
    #[arg(long, value_name = "RESULT#K")]
    pub config: Option<String>,
    /// PNG file to write.
    #[arg(long, short = 'o', value_name = "FILE")]
    pub output: PathBuf,
    /// The camera to render from, by name (default: the scene's first camera, or a view
    /// of the whole scene when it has none). `invlight scene FILE` lists the cameras.
    #[arg(long, value_name = "NAME")]
    pub camera: Option<String>,
    /// Image width, pixels.
    #[arg(long, default_value_t = 640, value_name = "W")]
    pub width: u32,
    /// Image height, pixels (default: from the camera's aspect ratio, else 3/4 of the
    /// width).
    #[arg(long, value_name = "H")]
    pub height: Option<u32>,
    /// Photons emitted for the photon map (indirect light and caustics); 0 renders
    /// direct light only.
    #[arg(long, short = 'n', default_value_t = 1_000_000, value_name = "N")]
    pub photons: u64,
    /// Photon gather radius, m (default: from the mean photon density, so that a disc
    /// holds about 100 photons). Smaller is sharper and noisier.
    #[arg(long, value_name = "R")]
    pub radius: Option<f32>,
    /// Final gather: rays per visible diffuse point that collect its indirect light from
    /// the photons where they land (smooth; the cost grows with G); 0 shows the photon
    /// density at the point itself (about twice as fast, blotchy).
    #[arg(long, default_value_t = 8, value_name = "G")]
    pub final_gather: u32,
    /// Camera rays per pixel (anti-aliasing; also averages area-light noise).
    #[arg(long, default_value_t = 4, value_name = "S")]
    pub samples: u32,
    /// Shadow rays to area lights (emissive surfaces) per shading point.
    #[arg(long, default_value_t = 2, value_name = "K")]
    pub light_samples: u32,
    /// Mirror and glass bounces followed from the camera.
    #[arg(long, default_value_t = 8, value_name = "K")]
    pub max_depth: u32,
    /// Surface interactions a photon follows after its first hit (a safety cap; Russian
    /// roulette ends paths on its own).
    #[arg(long, default_value_t = DEFAULT_MAX_BOUNCES, value_name = "K")]
    pub max_bounces: u32,
    /// Seed of the random streams: the same seed gives the same picture on any number of
    /// threads.
    #[arg(long, default_value_t = 1, value_name = "S")]
    pub seed: u64,
    /// Exposure compensation in stops (+1 is twice as bright), applied to the automatic
    /// exposure (the image's log-average luminance shown as middle grey) or to
    /// --luminance.
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "EV",
        allow_negative_numbers = true
    )]
    pub exposure: f32,
    /// A fixed exposure: this luminance in cd/m² is shown as middle grey. Use the same
    /// value to compare pictures of several configurations.
    #[arg(long, value_name = "CD_M2")]
    pub luminance: Option<f32>,
    /// Colour every visible surface point by its illuminance (direct light plus the
    /// photon map) instead of rendering it, with a legend bar in lux on the right.
    #[arg(long, alias = "false-color")]
    pub false_colour: bool,
    /// Top of the false-colour scale, lx (default: the 99th percentile of what is seen,
    /// rounded up).
    #[arg(long, value_name = "LX", requires = "false_colour")]
    pub max_lux: Option<f64>,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "T")]
    pub threads: Option<usize>,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// The view and image size the options ask for.
fn view_of(args: &RenderArgs, scene: &Scene) -> anyhow::Result<(View, u32, u32)> {
    let camera =
        match &args.camera {
            Some(name) => Some(scene.cameras.iter().find(|c| &c.name == name).ok_or_else(
                || {
                    let names: Vec<String> = scene
                        .cameras
                        .iter()
                        .map(|c| format!("'{}'", c.name))
                        .collect();
                    InputError(format!(
                        "{}: no camera named '{name}'{}",
                        args.scene.display(),
                        if names.is_empty() {
                            " (the scene has no camera; leave out --camera for a default view)"
                                .to_string()
                        } else {
                            format!("\n  hint: its cameras are {}", names.join(", "))
                        }
                    ))
                },
            )?),
            None => scene.cameras.first(),
        };
    let width = args.width;
    let height = args.height.unwrap_or_else(|| {
        let aspect = camera.and_then(|c| c.aspect).unwrap_or(4.0 / 3.0);
        ((width as f32 / aspect).round() as u32).max(1)
    });
    if width == 0 || height == 0 || width as u64 * height as u64 > 1 << 28 {
        return Err(InputError(format!(
            "an image of {width}×{height} pixels cannot be rendered"
        ))
        .into());
    }
    let aspect = width as f32 / height as f32;
    let view = match camera {
        Some(c) => View::from_camera(c, aspect),
        None => View::default_for(scene, aspect)
            .ok_or_else(|| InputError(format!("{}: the scene is empty", args.scene.display())))?,
    };
    Ok((view, width, height))
}

/// Runs `invlight render`.
pub fn run(args: RenderArgs) -> anyhow::Result<()> {
    if let Some(l) = args.luminance
        && !(l > 0.0 && l.is_finite())
    {
        return Err(InputError(format!("--luminance {l} must be a positive luminance")).into());
    }
    if let Some(m) = args.max_lux
        && !(m > 0.0 && m.is_finite())
    {
        return Err(InputError(format!("--max-lux {m} must be a positive illuminance")).into());
    }
    if let Some(r) = args.radius
        && !(r > 0.0 && r.is_finite())
    {
        return Err(InputError(format!("--radius {r} must be a positive length")).into());
    }
    let scene = match &args.config {
        Some(config) => configured_scene(&args, config)?,
        None => args.load.load(&args.scene)?,
    };
    let (view, width, height) = view_of(&args, &scene)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()?;
    let start = Instant::now();
    let accel = Accel::new(&scene);
    let photon_settings = PhotonSettings {
        photons: args.photons,
        seed: args.seed,
        max_bounces: args.max_bounces,
        store: if args.false_colour {
            Store::All
        } else {
            Store::Diffuse
        },
        radius: args.radius,
        paths: if args.final_gather > 0 {
            Paths::All
        } else {
            Paths::Indirect
        },
        ..PhotonSettings::default()
    };
    let build = |settings: &PhotonSettings| {
        let bar = progress::bar(settings.photons, "photons");
        let report = |done: u64| bar.set_position(done);
        let map = pool.install(|| PhotonMap::build(&scene, &accel, settings, Some(&report)));
        bar.finish_and_clear();
        map
    };
    let map = (args.photons > 0).then(|| build(&photon_settings));
    // A final gather reads the global map at precomputed points (a sixteenth of the
    // photons), thousands of times faster per lookup than the density estimate.
    let gather_map = match &map {
        Some(global) if args.final_gather > 0 => Some(pool.install(|| global.precompute(16))),
        _ => None,
    };
    // With a final gather, the map above is the global one and caustics get their own,
    // gathered within the same radius.
    let caustics = match &map {
        Some(global) if args.final_gather > 0 => Some(build(&PhotonSettings {
            paths: Paths::Caustic,
            radius: Some(global.radius()),
            ..photon_settings
        })),
        _ => None,
    };
    let lights = Lights::new(&scene);
    let settings = RenderSettings {
        width,
        height,
        samples: args.samples.max(1),
        light_samples: args.light_samples,
        max_depth: args.max_depth,
        seed: args.seed,
    };
    let integrator = match (&gather_map, &caustics) {
        (Some(global), Some(caustics)) => {
            Integrator::new(&scene, &accel, &lights, Some(caustics), settings)
                .with_final_gather(global, args.final_gather)
        }
        _ => Integrator::new(&scene, &accel, &lights, map.as_ref(), settings),
    };
    let render_start = Instant::now();
    let bar = progress::bar(height as u64, "rows");
    let report = |done: u64| bar.set_position(done);
    let picture = if args.false_colour {
        let lux = pool.install(|| render_illuminance(&integrator, &view, Some(&report)));
        let max = args.max_lux.unwrap_or_else(|| auto_max(&lux.lux));
        false_colour(&lux, max)
    } else {
        let image = pool.install(|| render(&integrator, &view, Some(&report)));
        let tone = ToneMap {
            exposure: args.luminance.map_or(Exposure::Auto, Exposure::Luminance),
            compensation: args.exposure,
        };
        tone_map(&image, &tone)
    };
    bar.finish_and_clear();
    let render_seconds = render_start.elapsed().as_secs_f64();
    save_png(&picture, &args.output)?;
    let stored = map.as_ref().map_or(0, |m| m.len());
    let radius = map.as_ref().map_or(0.0, |m| m.radius());
    let (trace_s, grid_s) = map.as_ref().map_or((0.0, 0.0), |m| m.seconds());
    eprintln!(
        "{}: {width}×{height}; photon map: {} photons traced in {trace_s:.2} s, {stored} stored, grid built in {grid_s:.3} s (radius {radius:.4} m); pixels in {render_seconds:.2} s; {:.2} s in all",
        args.output.display(),
        args.photons,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The scene of the problem file `args.scene` with ISOC member K of `config`
/// ("RESULT#K") applied: each variable's world value in result.json (placement point,
/// sun direction or colour value) is turned back into the problem's coordinates and
/// applied as `invlight solve` applies it.
fn configured_scene(args: &RenderArgs, config: &str) -> anyhow::Result<Scene> {
    let (file, number) = match config.rsplit_once('#') {
        Some((f, k)) => (
            PathBuf::from(f),
            k.parse::<usize>()
                .ok()
                .filter(|&k| k >= 1)
                .ok_or_else(|| {
                    InputError(format!(
                        "--config {config}: '{k}' is not an ISOC member number (they count from 1, as isoc-01.png, isoc-02.png, …)"
                    ))
                })?,
        ),
        None => (PathBuf::from(config), 1),
    };
    let member = number - 1;
    let problem = Problem::read(&args.scene).map_err(|e| InputError(e.to_string()))?;
    let mut scene = args.load.load(&problem.scene)?;
    let binding = Binding::new(&problem, &mut scene).map_err(|e| InputError(e.to_string()))?;
    let text = std::fs::read_to_string(&file)
        .map_err(|e| InputError(format!("cannot read {}: {e}", file.display())))?;
    let json: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| InputError(format!("{}: not JSON: {e}", file.display())))?;
    let members = json["isoc"].as_array().map_or(0, |a| a.len());
    let variables = &json["isoc"][member]["variables"];
    if !variables.is_object() {
        return Err(InputError(format!(
            "{}: no ISOC member {number} (it has {members})",
            file.display()
        ))
        .into());
    }
    let vector = |v: &serde_json::Value| -> Option<DVec3> {
        let a = v.as_array()?;
        Some(DVec3::new(
            a.first()?.as_f64()?,
            a.get(1)?.as_f64()?,
            a.get(2)?.as_f64()?,
        ))
    };
    let mut coords = Vec::new();
    for var in binding.space.variables() {
        let value = &variables[&var.id];
        let missing = || {
            InputError(format!(
                "{}: ISOC member {member} has no usable value for variable '{}'",
                file.display(),
                var.id
            ))
        };
        match &var.domain {
            Domain::Rectangle(r) => {
                let (s, t) = r.coords(vector(&value["position"]).ok_or_else(missing)?);
                coords.extend([s, t]);
            }
            Domain::Hemisphere(h) => {
                let (phi, theta) = h.coords(vector(&value["direction"]).ok_or_else(missing)?);
                coords.extend([phi, theta]);
            }
            Domain::Segment { min, max } => {
                let v = value["value"].as_f64().ok_or_else(missing)?;
                coords.push(if max > min {
                    (v - min) / (max - min)
                } else {
                    0.0
                });
            }
        }
    }
    binding.apply(&mut scene, &Configuration { coords });
    Ok(scene)
}

/// Writes a PNG, naming the file in the error.
pub fn save_png(image: &invlight_render::RgbImage, path: &Path) -> anyhow::Result<()> {
    image
        .save_with_format(path, invlight_render::image::ImageFormat::Png)
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))
}
