//! `invlight luminaire`: a photometric file's datasheet
//! ([`invlight_scene::LuminaireFacts`]).

use crate::InputError;
use clap::Args;
use invlight_scene::{LuminaireFacts, read_photometry};
use serde::Serialize;
use std::fmt::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// Options of `invlight luminaire`.
#[derive(Args, Debug)]
pub struct LuminaireArgs {
    /// IES LM-63 (.ies) or EULUMDAT (.ldt) files; each is read and its figures printed.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<PathBuf>,
    /// Print one JSON object instead of text: `luminaires`, one per file in order, with
    /// file, format, manufacturer, product, flux, lamp_flux, watts, efficacy,
    /// max_intensity, beam_angle and field_angle ([C0–C180, C90–C270] degrees),
    /// cie_flux_code (N1…N5 %), downward_fraction, opening, opening_size, opening_height,
    /// luminaire_size ([C0–C180, C90–C270, height] m), luminaire (in words) and warnings.
    #[arg(long)]
    pub json: bool,
}

/// One file's figures and what is doubtful in it, as `--json` writes them.
#[derive(Serialize)]
struct Sheet {
    #[serde(flatten)]
    facts: LuminaireFacts,
    warnings: Vec<String>,
}

/// What `--json` prints.
#[derive(Serialize)]
struct Sheets {
    luminaires: Vec<Sheet>,
}

/// Runs `invlight luminaire`.
pub fn run(args: LuminaireArgs) -> anyhow::Result<ExitCode> {
    let mut sheets = Vec::new();
    for file in &args.files {
        let p = read_photometry(file).map_err(|e| InputError(e.to_string()))?;
        sheets.push(Sheet {
            facts: LuminaireFacts::of(&p),
            warnings: p.warnings.clone(),
        });
    }
    if args.json {
        crate::print_json(&Sheets { luminaires: sheets })?;
    } else {
        let text: Vec<String> = sheets.iter().map(sheet).collect();
        crate::print(&text.join("\n"))?;
    }
    Ok(ExitCode::SUCCESS)
}

/// One file's datasheet as text.
fn sheet(s: &Sheet) -> String {
    let f = &s.facts;
    let mut t = format!("{} ({})\n", f.file, f.format);
    let mut line = |label: &str, value: String| {
        let _ = writeln!(t, "  {label:<18} {value}");
    };
    if let Some(m) = &f.manufacturer {
        line("manufacturer", m.clone());
    }
    if let Some(p) = &f.product {
        line("product", p.clone());
    }
    let lamps = f
        .lamp_flux
        .map(|l| format!(" (lamps {l:.0} lm)"))
        .unwrap_or_default();
    line("flux", format!("{:.0} lm{lamps}", f.flux));
    line(
        "power",
        f.watts.map_or("not stated".into(), |w| format!("{w:.1} W")),
    );
    line(
        "efficacy",
        f.efficacy
            .map_or("unknown (no watts)".into(), |e| format!("{e:.1} lm/W")),
    );
    line("peak intensity", format!("{:.0} cd", f.max_intensity));
    let [b0, b90] = f.beam_angle;
    let [f0, f90] = f.field_angle;
    line(
        "beam angle (50 %)",
        format!("{b0:.1}° in C0–C180, {b90:.1}° in C90–C270"),
    );
    line(
        "field angle (10 %)",
        format!("{f0:.1}° in C0–C180, {f90:.1}° in C90–C270"),
    );
    line(
        "CIE flux code",
        format!(
            "{} (downward {:.0} %)",
            f.flux_code(),
            100.0 * f.downward_fraction
        ),
    );
    let height = if f.opening_height > 0.0 {
        format!(", {:.0} mm high", 1000.0 * f.opening_height)
    } else {
        String::new()
    };
    line("luminous opening", format!("{}{height}", f.opening));
    if let Some(luminaire) = &f.luminaire {
        line("luminaire", luminaire.clone());
    }
    for w in &s.warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    t
}
