//! `invlight sun`: where the sun stands at a site, date and time (NREL's SPA), and the
//! direction a scene's light takes from it ([`invlight_scene::daylight::SunReport`]).

use clap::Args;
use invlight_scene::daylight::{Date, Site, SunOptions, SunReport, TimeOfDay};
use std::process::ExitCode;

/// Options of `invlight sun`.
#[derive(Args, Debug)]
pub struct SunArgs {
    /// LAT,LON,TZ: degrees (longitude east positive) and the clock's hours east of UTC.
    #[arg(long, value_name = "LAT,LON,TZ", allow_hyphen_values = true)]
    pub site: Site,
    /// The local date, YYYY-MM-DD.
    #[arg(long)]
    pub date: Date,
    /// The local clock time, HH:MM or HH:MM:SS (24-hour, in the zone of --site).
    #[arg(long)]
    pub time: TimeOfDay,
    /// Metres above sea level: SPA's parallax, and the ISO 2533 air that refracts
    /// [default: 0].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub elevation: Option<f64>,
    /// True north, degrees clockwise seen from above from the scene's −Z (Y-up) or +Y
    /// (Z-up) [default: 0].
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub north: Option<f64>,
    /// The scene's up axis, for the direction.
    #[arg(long, value_name = "y|z", default_value = "y")]
    pub up: invlight_scene::UpAxis,
    /// Print one JSON object (site, date, time, position, altitude, up, direction,
    /// direct_normal_illuminance; docs/daylight.md) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs `invlight sun`.
pub fn run(args: SunArgs) -> anyhow::Result<ExitCode> {
    let site = args
        .site
        .with_elevation(args.elevation.unwrap_or(0.0))?
        .with_north(args.north.unwrap_or(0.0))?;
    let (options, up) = (SunOptions::default(), args.up.vector());
    let report = SunReport::new(&site, &args.date, &args.time, &options, up)?;
    if args.json {
        crate::print_json(&report)?;
    } else {
        crate::print(&report.to_string())?;
    }
    Ok(ExitCode::SUCCESS)
}
