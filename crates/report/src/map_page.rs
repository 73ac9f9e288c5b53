//! The page of one illuminance grid (`invlight map --report`), and the grid section the
//! solve report shares: the plan with isolux lines, Emin/Eavg/Emax/U0, the compliance
//! with a requirement at a stated confidence, and every cell's value.

use crate::html::{Page, escape, figure, table};
use invlight_photon::Side;
use invlight_render::{
    AreaReport, Compliance, Criterion, CylindricalReport, IlluminanceMap, MapPlan, MapReport,
    Requirement, Verdict, plain,
};
use invlight_scene::Vec3;
use invlight_stats::{Confidence, significant};

/// The most cells listed in a page's table; a larger grid points to its CSV.
const MAX_TABLE_CELLS: usize = 600;

fn verdict_class(v: Verdict) -> &'static str {
    match v {
        Verdict::Meets => "meets",
        Verdict::Fails => "fails",
        Verdict::CannotTell => "cannot",
    }
}

/// What a requirement asks, in words: "EN 12464-1:2021 'Offices: writing, …':
/// Em ≥ 500 lx, U0 ≥ 0.60, maintenance factor 0.8".
pub fn requirement_words(r: &Requirement) -> String {
    let mut parts = Vec::new();
    if let Some(em) = r.em {
        parts.push(format!("Em ≥ {} lx", plain(em)));
    }
    if let Some(u0) = r.u0 {
        parts.push(format!("U0 ≥ {u0:.2}"));
    }
    parts.push(format!(
        "maintenance factor {}",
        plain(r.maintenance_factor)
    ));
    match &r.task {
        Some(t) => format!(
            "EN 12464-1:2021, “{}” (--task {}): {}",
            t.description,
            t.name,
            parts.join(", ")
        ),
        None => parts.join(", "),
    }
}

/// The compliance as the terminal prints it, the same verdicts as the page's
/// (`compliance_html`): the grid's sentence, then a line per criterion.
pub fn compliance_text(c: &Compliance) -> String {
    let pct = format!("{} %", plain(c.confidence * 100.0));
    let what = requirement_words(&c.requirement);
    let mut out = match c.verdict {
        Verdict::Meets => format!("the grid meets {what} with {pct} confidence\n"),
        Verdict::Fails => format!("the grid fails {what} with {pct} confidence\n"),
        Verdict::CannotTell => {
            format!(
                "cannot tell at this photon count whether the grid meets {what}: trace more photons\n"
            )
        }
    };
    for k in &c.criteria {
        let (value, low, high, unit) = figures(k);
        out += &format!(
            "  {} {value} [{low}, {high}]{unit}: {}\n",
            k.name,
            k.sentence(c.confidence)
        );
    }
    out
}

/// The cells of an area's row, as the terminal and the page print them: the area, its
/// size, what it must meet, maintained Ēm with its bounds, U0 with its bounds, and the
/// verdict.
fn area_cells(a: &AreaReport) -> [String; 6] {
    let size = if a.area == "wall" || a.area == "ceiling" {
        format!("{:.2} m × {:.2} m", a.size[0], a.size[1])
    } else {
        format!("{} m band", plain(a.size[0]))
    };
    let bound = |x: Option<f64>| x.map_or("∞".to_string(), |x| format!("{x:.2}"));
    let name = if a.area == "wall" {
        a.surface.clone()
    } else {
        a.area.clone()
    };
    [
        name,
        size,
        format!(
            "Em ≥ {} lx, U0 ≥ {:.2}",
            plain(a.required_em),
            a.required_u0
        ),
        format!(
            "{} lx [{}, {}]",
            significant(a.em),
            significant(a.em_bounds[0]),
            significant(a.em_bounds[1])
        ),
        format!(
            "{:.2} [{}, {}]",
            a.u0,
            bound(a.u0_bounds[0]),
            bound(a.u0_bounds[1])
        ),
        a.verdict.clone(),
    ]
}

/// The cells of the cylindrical illuminance's row, as [`area_cells`] gives an area's:
/// Ēz in the Em column, no U0.
fn cylindrical_cells(c: &CylindricalReport) -> [String; 6] {
    [
        "cylindrical illuminance".into(),
        "task area and surrounding, at eye height".into(),
        format!("Ēz ≥ {} lx", plain(c.required_ez)),
        format!(
            "Ēz {} lx [{}, {}]",
            significant(c.ez),
            significant(c.ez_bounds[0]),
            significant(c.ez_bounds[1])
        ),
        "—".into(),
        c.verdict.clone(),
    ]
}

/// EN 12464-1's areas around a task area as the terminal prints them, a line each,
/// the cylindrical illuminance last.
pub fn areas_text(
    areas: &[AreaReport],
    cylindrical: Option<&CylindricalReport>,
    confidence: f64,
) -> String {
    if areas.is_empty() && cylindrical.is_none() {
        return String::new();
    }
    let mut out = format!(
        "EN 12464-1's areas around it (maintained values, all verdicts together at {} % confidence):
",
        plain(confidence * 100.0)
    );
    for a in areas {
        let [name, size, asked, em, u0, verdict] = area_cells(a);
        out += &format!("  {name} ({size}): {asked}: Em {em}, U0 {u0}: {verdict}\n");
    }
    if let Some(c) = cylindrical {
        let [name, size, asked, ez, _, verdict] = cylindrical_cells(c);
        out += &format!("  {name} ({size}): {asked}: {ez}: {verdict}\n");
    }
    out
}

/// A criterion's value and one-sided bounds as both forms print them, and the unit
/// after the bounds: lx for Em, none for U0 (whose upper bound may be unbounded, ∞).
fn figures(k: &Criterion) -> (String, String, String, &'static str) {
    match k.name {
        "Em" => (
            format!("{} lx", significant(k.value)),
            significant(k.bounds.0),
            significant(k.bounds.1),
            " lx",
        ),
        _ => (
            format!("{:.3}", k.value),
            format!("{:.3}", k.bounds.0),
            if k.bounds.1.is_finite() {
                format!("{:.3}", k.bounds.1)
            } else {
                "∞".into()
            },
            "",
        ),
    }
}

/// The compliance as HTML: the grid's sentence, then a row per criterion.
pub fn compliance_html(c: &Compliance) -> String {
    let pct = format!("{} %", plain(c.confidence * 100.0));
    let sentence = match c.verdict {
        Verdict::Meets => format!(
            "The grid <span class=\"meets\">meets</span> {} with {pct} confidence.",
            escape(&requirement_words(&c.requirement))
        ),
        Verdict::Fails => format!(
            "The grid <span class=\"fails\">fails</span> {} with {pct} confidence.",
            escape(&requirement_words(&c.requirement))
        ),
        Verdict::CannotTell => format!(
            "<span class=\"cannot\">Cannot tell</span> at this photon count whether the grid meets {} — trace more photons.",
            escape(&requirement_words(&c.requirement))
        ),
    };
    let rows: Vec<Vec<String>> = c
        .criteria
        .iter()
        .map(|k| {
            let (value, low, high, unit) = figures(k);
            let bounds = format!("{low} to {high}{unit}");
            vec![
                k.name.to_string(),
                if k.name == "Em" {
                    format!("≥ {} lx", plain(k.required))
                } else {
                    format!("≥ {:.2}", k.required)
                },
                value,
                bounds,
                format!("{} %", plain(100.0 * k.level)),
                format!(
                    "<span class=\"{}\">{}</span>",
                    verdict_class(k.verdict),
                    escape(&k.sentence(c.confidence))
                ),
            ]
        })
        .collect();
    format!(
        "<p>{sentence}</p>\n{}<p class=\"sub\">Em is the maintained mean (maintenance factor × the surface's mean, whose standard error is the whole surface's own estimate). Each bound is one-sided at the level shown: the run's error rate is split between the criteria, and U0's among the grid's cells (Bonferroni), with an error bound that holds whatever the cells' correlation (see invlight_render::compliance). The cells are means over the grid's cells, centred on its points.</p>\n",
        table(
            &[
                "criterion",
                "required",
                "estimate",
                "bounds",
                "each bound at",
                "verdict"
            ],
            &rows
        )
    )
}

/// The grid section: the plan, the figures, the compliance when asked, the cells.
pub fn grid_section(
    map: &IlluminanceMap,
    up: Vec3,
    title: &str,
    confidence: Confidence,
    requirement: Option<&Requirement>,
) -> Result<String, invlight_render::ChartError> {
    let plan = MapPlan::new(map, title, confidence).from_above(up);
    let s = map.summary();
    let (i, u0) = (
        map.mean.interval(confidence.z()),
        map.u0.interval(confidence.z()),
    );
    let mut out = figure(
        &plan.svg()?,
        &format!(
            "{}: each cell in the colour of its mean illuminance (viridis over the cells' range, {}–{} lx), isolux lines at {} lx.",
            escape(title),
            significant(plan.scale().min),
            significant(plan.scale().max),
            plan.levels()
                .iter()
                .map(|l| plain(*l))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    );
    out += &format!(
        "<dl><dt>Eavg</dt><dd>{} lx [{}, {}] ({} % interval)</dd><dt>Emin</dt><dd>{} lx</dd><dt>Emax</dt><dd>{} lx</dd><dt>U0 = Emin/Eavg</dt><dd>{:.3} [{:.3}, {:.3}]</dd><dt>Emax/Emin</dt><dd>{}</dd><dt>Grid</dt><dd>{} × {} cells of {} × {} m, {} photons; {}</dd></dl>\n",
        significant(s.eavg),
        significant(i.low),
        significant(i.high),
        plain(confidence.level() * 100.0),
        significant(s.emin),
        significant(s.emax),
        s.u0,
        u0.low.max(0.0),
        u0.high,
        s.max_ratio()
            .map_or("∞ (Emin is 0)".into(), |r| format!("{r:.2}")),
        map.columns,
        map.rows,
        significant(map.cell_u as f64),
        significant(map.cell_v as f64),
        map.photons,
        escape(&map.spacing_rule)
    );
    if let Some(r) = requirement {
        out += &compliance_html(&map.compliance(r, confidence));
    }
    let rows = map.csv_rows(confidence);
    if rows.len() <= MAX_TABLE_CELLS {
        let cells: Vec<Vec<String>> = rows
            .iter()
            .map(|r| {
                vec![
                    format!("{}, {}", r.column, r.row),
                    format!("({:.2}, {:.2}, {:.2})", r.x, r.y, r.z),
                    significant(r.mean),
                    significant(r.low),
                    significant(r.high),
                    format!("{:.3}", r.area),
                ]
            })
            .collect();
        out += &format!(
            "<details><summary>Every cell's value ({} cells)</summary>{}</details>\n",
            rows.len(),
            table(
                &[
                    "cell (column, row)",
                    "centre (m)",
                    "mean (lx)",
                    "low",
                    "high",
                    "area (m²)"
                ],
                &cells
            )
        );
    } else {
        out += &format!(
            "<p>{} cells: their values are in the grid's CSV.</p>\n",
            rows.len()
        );
    }
    Ok(out)
}

/// The page of `invlight map --report`.
pub struct MapPage<'a> {
    /// The grid.
    pub map: &'a IlluminanceMap,
    /// Its `--json` report: the surface, the estimator, the confidence, the seconds.
    pub report: &'a MapReport,
    /// The scene file.
    pub scene: String,
    /// The scene's up axis: a horizontal grid is drawn as seen from above.
    pub up: Vec3,
    /// What the grid must meet, if anything.
    pub requirement: Option<&'a Requirement>,
}

impl<'a> MapPage<'a> {
    /// The page of `map` (reported as `report`) of a surface of the scene file `scene`
    /// whose up axis is `up`, checked against `requirement`.
    pub fn new(
        map: &'a IlluminanceMap,
        report: &'a MapReport,
        scene: String,
        up: Vec3,
        requirement: Option<&'a Requirement>,
    ) -> MapPage<'a> {
        MapPage {
            map,
            report,
            scene,
            up,
            requirement,
        }
    }

    /// Writes the page to `path` (atomically).
    pub fn write(&self, path: &std::path::Path) -> Result<(), crate::ReportError> {
        let html = self.html()?;
        invlight_scene::write_atomically(path, |w| std::io::Write::write_all(w, html.as_bytes()))
            .map_err(|e| crate::ReportError::Io(path.to_path_buf(), e))
    }

    /// The page's HTML.
    pub fn html(&self) -> Result<String, invlight_render::ChartError> {
        let r = self.report;
        let confidence = Confidence::new(r.confidence).unwrap_or_default();
        let mut page = Page::new(
            &format!("Illuminance on {}", r.surface.as_str()),
            &format!("{} — invlight {}", &self.scene, env!("CARGO_PKG_VERSION")),
        );
        let s = self.map.summary();
        let i = self.map.mean.interval(confidence.z());
        let mut answer = format!(
            "<div class=\"answer\"><p><b>{}</b> gets <b>{} lx</b> on average [{}, {}] at {} % confidence; Emin {} lx, Emax {} lx, U0 {:.2}.</p>",
            escape(r.surface.as_str()),
            significant(s.eavg),
            significant(i.low),
            significant(i.high),
            plain(confidence.level() * 100.0),
            significant(s.emin),
            significant(s.emax),
            s.u0
        );
        if let Some(r) = self.requirement {
            let c = self.map.compliance(r, confidence);
            answer += &format!(
                "<p>{}: <span class=\"{}\">{}</span></p>",
                escape(&requirement_words(r)),
                verdict_class(c.verdict),
                escape(&c.verdict.to_string())
            );
        }
        answer += "</div>";
        page.section("The answer", &answer);
        page.section(
            &format!("Light on {}", r.surface.as_str()),
            &grid_section(
                self.map,
                self.up,
                r.surface.as_str(),
                confidence,
                self.requirement,
            )?,
        );
        if !r.areas.is_empty() || r.cylindrical.is_some() {
            let rows: Vec<Vec<String>> = r
                .areas
                .iter()
                .map(|a| area_cells(a).to_vec())
                .chain(r.cylindrical.iter().map(|c| cylindrical_cells(c).to_vec()))
                .collect();
            page.section(
                "EN 12464-1's areas around it",
                &format!(
                    "<p>The immediate surrounding (a band of 0.5 m around the task area, in its plane), the background (3 m around that, within the room), the walls and the ceiling (calculation rectangles 1 cm inside the room, facing into it), and where the task asks an Ēz the cylindrical illuminance over the task area and its surrounding at a seated eye's 1.2 m (small vertical prisms at the grid's points), traced with the same photons, on EN 12464-1's grids. Values are maintained; the bounds are one-sided, and every verdict of the table holds together with the others at {} % confidence (Bonferroni).</p>{}",
                    plain(confidence.level() * 100.0),
                    table(
                        &["Area", "Size", "Required", "Em (maintained)", "U0", "Verdict"],
                        &rows
                    )
                ),
            );
        }
        page.section(
            "How it was measured",
            &format!(
                "<p>{} photons traced ({} estimator: each departure connected to a point on the surface unless “arrivals”), every arrival on the {} at every bounce counted; each cell's standard error from the spread of the stratified photon groups. {:.1} s.</p>",
                self.map.photons,
                escape(&r.estimator),
                match self.map.side {
                    Side::Front => "front (the side the surface's normal faces)",
                    Side::Back => "back",
                    Side::Both => "either side",
                },
                r.seconds
            ),
        );
        Ok(page.finish())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requirements_read_as_the_norm_states_them() {
        let r = Requirement::of_task(invlight_render::task("office").unwrap(), 0.8);
        let w = requirement_words(&r);
        assert!(
            w.contains("Em ≥ 500 lx") && w.contains("U0 ≥ 0.60") && w.contains("0.8"),
            "{w}"
        );
    }

    fn wall(verdict: &str) -> AreaReport {
        AreaReport {
            area: "wall".into(),
            surface: "wall x = 9.00 m".into(),
            size: [7.18, 2.98],
            cells: [8, 4],
            cell_size: [0.9, 0.75],
            required_em: 75.0,
            required_u0: 0.1,
            em: 469.1,
            em_bounds: [468.6, 469.7],
            u0: 0.44,
            u0_bounds: [Some(0.43), None],
            level: 0.99,
            verdict: verdict.into(),
        }
    }

    /// Each area's line says what it must meet, its maintained values with their
    /// bounds (an unbounded U0 as ∞) and its verdict, a wall by its own name and a band
    /// by its width; the cylindrical illuminance comes last with Ēz alone.
    #[test]
    fn the_areas_lines_say_what_each_must_meet_and_whether_it_does() {
        let mut band = wall("cannot tell");
        band.area = "immediate surrounding".into();
        band.surface = "immediate surrounding".into();
        band.size = [0.5, 0.5];
        let ez = CylindricalReport {
            surface: "cylindrical illuminance".into(),
            required_ez: 150.0,
            ez: 265.4,
            ez_bounds: [264.3, 266.6],
            level: 0.99,
            verdict: "meets".into(),
        };
        let text = areas_text(&[wall("fails"), band], Some(&ez), 0.95);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 4, "{text}");
        assert!(lines[0].contains("95 % confidence"), "{text}");
        assert_eq!(
            lines[1],
            "  wall x = 9.00 m (7.18 m × 2.98 m): Em ≥ 75 lx, U0 ≥ 0.10: Em 469.1 lx [468.6, 469.7], U0 0.44 [0.43, ∞]: fails"
        );
        assert!(
            lines[2].starts_with("  immediate surrounding (0.5 m band)")
                && lines[2].ends_with(": cannot tell"),
            "{text}"
        );
        assert!(
            lines[3].contains("Ēz ≥ 150 lx: Ēz 265.4 lx [264.3, 266.6]: meets"),
            "{text}"
        );
        assert_eq!(areas_text(&[], None, 0.95), "");
        assert_eq!(areas_text(&[], Some(&ez), 0.95).lines().count(), 2);
    }

    /// The grid's sentence follows its verdict: "cannot tell" asks for more photons
    /// rather than saying meets or fails, and each criterion prints its bounds.
    #[test]
    fn the_compliance_sentence_follows_the_verdict() {
        let office = Requirement::of_task(invlight_render::task("office").unwrap(), 1.0);
        let cell = |mean: f64, std_error: f64| invlight_stats::Estimate {
            mean,
            std_error,
            samples: 100_000,
        };
        let confidence = Confidence::new(0.95).unwrap();
        let judge = |cells: &[invlight_stats::Estimate], mean| {
            compliance_text(&invlight_render::assess(cells, &mean, &office, confidence))
        };
        let lit = [cell(520.0, 1.0), cell(560.0, 1.0), cell(600.0, 1.0)];
        let meets = judge(&lit, cell(560.0, 1.0));
        assert!(
            meets.starts_with("the grid meets EN 12464-1:2021"),
            "{meets}"
        );
        assert!(
            meets.contains("  Em 560.0 lx [558.0, 562.0] lx: meets Em ≥ 500 lx"),
            "{meets}"
        );
        let dark = [cell(200.0, 1.0), cell(400.0, 1.0), cell(420.0, 1.0)];
        let fails = judge(&dark, cell(340.0, 1.0));
        assert!(fails.starts_with("the grid fails"), "{fails}");
        let near = judge(&lit, cell(500.0, 20.0));
        assert!(
            near.starts_with("cannot tell at this photon count"),
            "{near}"
        );
        assert!(near.contains("trace more photons"), "{near}");
    }
}
