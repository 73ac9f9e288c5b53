//! `invlight render`: a photon-mapped picture of a scene from its camera, or a
//! false-colour picture of the illuminance with a legend in lux
//! ([`invlight_render::Renderer`]).

use crate::InputError;
use crate::args::{SceneArgs, TraceArgs, finite, positive};
use clap::Args;
use invlight_render::{
    Exposure, Look, PictureSettings, Renderer, SaveError, ToneMap, choose_view, picture_format,
    save_picture,
};
use invlight_report::Progress;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Options of `invlight render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Picture to write: .png, or .jpg/.jpeg (quality 90).
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
    #[command(flatten)]
    pub trace: TraceArgs,
    /// Photon gather radius, m (default: from the mean photon density, so that a disc
    /// holds about 100 photons). Smaller is sharper and noisier.
    #[arg(long, value_name = "R", value_parser = positive::<f32>)]
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
    /// Exposure compensation in stops (+1 is twice as bright), applied to the automatic
    /// exposure (the image's log-average luminance shown as middle grey) or to
    /// --luminance.
    #[arg(long, default_value_t = 0.0, value_name = "EV", allow_negative_numbers = true,
          value_parser = finite)]
    pub exposure: f32,
    /// A fixed exposure: this luminance in cd/m² is shown as middle grey. Use the same
    /// value to compare pictures of several configurations.
    #[arg(long, value_name = "CD_M2", value_parser = positive::<f32>)]
    pub luminance: Option<f32>,
    /// Colour every visible surface point by its illuminance (direct light plus the
    /// photon map) instead of rendering it, with a legend bar in lux on the right.
    #[arg(long, alias = "false-color")]
    pub false_colour: bool,
    /// Top of the false-colour scale, lx (default: the 99th percentile of what is seen;
    /// its bottom is the least seen).
    #[arg(long, value_name = "LX", requires = "false_colour", value_parser = positive::<f64>)]
    pub max_lux: Option<f64>,
}

/// Writes a picture, naming the file in the error (a wrong extension is bad input).
pub fn save_image(image: &invlight_render::RgbImage, path: &Path) -> anyhow::Result<()> {
    save_picture(image, path).map_err(|e| match e {
        SaveError::Format(_) => InputError(format!("{}: {e}", path.display())).into(),
        e => anyhow::anyhow!("cannot write {}: {e}", path.display()),
    })
}

/// Runs `invlight render`.
pub fn run(args: RenderArgs) -> anyhow::Result<ExitCode> {
    picture_format(&args.output)
        .map_err(|e| InputError(format!("{}: {e}", args.output.display())))?;
    let trace = args.trace.settings(1_000_000)?;
    let scene = args.scene.load()?;
    let (view, width, height) =
        choose_view(&scene, args.camera.as_deref(), args.width, args.height)
            .map_err(|e| InputError(format!("{}: {e}", args.scene.scene.display())))?;
    let pool = args.trace.pool()?;
    let start = Instant::now();
    let settings = PictureSettings {
        width,
        height,
        photons: trace.photons,
        radius: args.radius,
        final_gather: args.final_gather,
        samples: args.samples,
        light_samples: args.light_samples,
        max_depth: args.max_depth,
        max_bounces: trace.max_bounces,
        seed: trace.seed,
        illuminance: args.false_colour,
    };
    let bar = Progress::new(trace.photons, "photons", "the photon maps");
    let report = |done: u64, total: u64| bar.set_total(done, total);
    let renderer = pool.install(|| Renderer::new(&scene, &settings, Some(&report)));
    bar.finish();
    let pixels_start = Instant::now();
    let bar = Progress::new(height as u64, "rows", "the picture");
    let report = |done: u64| bar.set(done);
    let look = if args.false_colour {
        Look::FalseColour(args.max_lux)
    } else {
        Look::Tone(ToneMap {
            exposure: args.luminance.map_or(Exposure::Auto, Exposure::Luminance),
            compensation: args.exposure,
        })
    };
    let picture = pool.install(|| renderer.picture(&view, &look, Some(&report)))?;
    bar.finish();
    let pixel_seconds = pixels_start.elapsed().as_secs_f64();
    save_image(&picture, &args.output)?;
    eprintln!(
        "{}: {width}×{height}; {}; pixels in {pixel_seconds:.2} s; {:.2} s in all",
        args.output.display(),
        renderer.figures(),
        start.elapsed().as_secs_f64()
    );
    Ok(ExitCode::SUCCESS)
}
