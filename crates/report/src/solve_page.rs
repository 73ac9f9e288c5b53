//! `report.html` of a solve: one page a lighting designer can hand a client — the
//! answer first (the best configuration, its value and interval, what moved, in world
//! coordinates), the problem in words, the ISOC as a gallery of captioned renders, the
//! search and convergence plots, the objective surface's plan with isolux lines and its
//! compliance, a table of every member, and the time it all took.

use crate::describe::{self, compass, subject};
use crate::html::{Page, escape, figure, img_png, table};
use crate::map_page::{grid_section, requirement_words};
use crate::plots::{convergence, search_plot};
use invlight_ilp::{
    Binding, Confidence, Diagnostic, Isoc, Member, Problem, Record, ResultFile, RunFile, Search,
    Solutions, Standing, Strategy,
};
use invlight_photon::{Alone, Estimator, GridError, GridValues, TraceSettings};
use invlight_render::{
    ChartError, GridSpacing, MapError, MapSettings, Requirement, illuminance_map_across, plain,
};
use invlight_scene::Scene;
use invlight_scene::daylight::Compass;
use invlight_stats::significant;
use invlight_trace::Accel;
use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Why a report cannot be made.
#[derive(Debug)]
pub enum ReportError {
    /// A run file is missing or unreadable.
    Folder(Diagnostic),
    /// A chart could not be drawn.
    Chart(ChartError),
    /// The page could not be written.
    Io(PathBuf, std::io::Error),
}

impl fmt::Display for ReportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReportError::Folder(d) => write!(f, "{d}"),
            ReportError::Chart(e) => write!(f, "{e}"),
            ReportError::Io(p, e) => write!(f, "cannot write {}: {e}", p.display()),
        }
    }
}

impl std::error::Error for ReportError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ReportError::Folder(d) => Some(d),
            ReportError::Chart(e) => Some(e),
            ReportError::Io(_, e) => Some(e),
        }
    }
}

impl From<ChartError> for ReportError {
    fn from(e: ChartError) -> Self {
        ReportError::Chart(e)
    }
}

impl GridOptions {
    /// `photons` photons traced with `seed` and the bounce cap `max_bounces`, the cells
    /// at EN 12464-1's spacing and read at its points.
    pub fn en(photons: u64, seed: u64, max_bounces: u32) -> GridOptions {
        GridOptions {
            trace: TraceSettings {
                photons,
                seed,
                max_bounces,
                ..TraceSettings::default()
            },
            spacing: GridSpacing::Auto,
            values: GridValues::Points,
        }
    }
}

/// What a solve left: its evaluations, the ISOC they make, result.json.
pub struct SolveFolder {
    /// The folder.
    pub dir: PathBuf,
    /// Every evaluation, in order.
    pub records: Vec<Record>,
    /// The final ISOC.
    pub isoc: Isoc,
    /// The configurations closest to meeting the constraints, least violation first.
    pub closest: Vec<(f64, Member)>,
    /// result.json.
    pub result: ResultFile,
}

impl SolveFolder {
    /// The folder `dir` of a run that has just ended with these records, standing and
    /// result.
    pub fn new(
        dir: &Path,
        records: Vec<Record>,
        standing: Standing<'_>,
        result: &ResultFile,
    ) -> Self {
        SolveFolder {
            dir: dir.to_path_buf(),
            records,
            isoc: standing.isoc.clone(),
            closest: standing.closest.to_vec(),
            result: result.clone(),
        }
    }

    /// What the page shows: the ISOC best first, or when no configuration met the
    /// constraints the closest ones (the pictures' order either way).
    pub fn members(&self) -> Vec<&Member> {
        match self.isoc.best_first() {
            m if m.is_empty() => self.closest.iter().map(|(_, m)| m).collect(),
            m => m,
        }
    }

    /// Reads `dir`'s solutions.csv and result.json, written for `problem` bound as
    /// `binding`; the ISOC is rebuilt by replaying the rows, as `--resume` does.
    pub fn read(
        dir: &Path,
        problem: &Problem,
        binding: &Binding,
    ) -> Result<SolveFolder, ReportError> {
        let rows =
            Solutions::read(&dir.join("solutions.csv"), binding).map_err(ReportError::Folder)?;
        let mut search = Search::new(&binding.space, problem.settings(), &binding.initial);
        search.replay(&rows.records);
        let result = ResultFile::read(&dir.join("result.json")).map_err(ReportError::Folder)?;
        Ok(SolveFolder::new(
            dir,
            rows.records,
            search.standing(),
            &result,
        ))
    }
}

impl SolveFolder {
    /// The problem solved in `dir`: the file `path`, else the one its result.json
    /// records, with the settings its run.json records (a solve's command-line
    /// overrides of photons, seed, confidence, bounces), so that replaying its rows
    /// rebuilds its ISOC.
    pub fn problem(dir: &Path, path: Option<&Path>) -> Result<Problem, ReportError> {
        let folder = ReportError::Folder;
        let path = match path {
            Some(p) => p.to_path_buf(),
            None => {
                let json = dir.join("result.json");
                let result = ResultFile::read(&json).map_err(folder)?;
                result.objective.problem.ok_or_else(|| {
                    folder(
                        Diagnostic::new(&json, "it does not record its problem file")
                            .with_hint("give it with --problem FILE"),
                    )
                })?
            }
        };
        let mut problem = Problem::read(&path).map_err(folder)?;
        if let Some(run) = RunFile::read(dir).map_err(folder)? {
            problem.seed = run.seed;
            problem.photons = run.photons;
            problem.fast_quality = run.fast_quality;
            problem.max_bounces = Some(run.max_bounces);
            problem.strategy = Strategy::parse(&run.strategy).unwrap_or(problem.strategy);
            problem.confidence = Confidence::new(run.confidence).unwrap_or(problem.confidence);
        }
        Ok(problem)
    }
}

/// How the objective surface's grid is measured for the report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridOptions {
    /// Photons, seed and bounce cap of the grid's trace.
    pub trace: TraceSettings,
    /// The cell size.
    pub spacing: GridSpacing,
    /// What a cell reads: the illuminance at its centre, or its mean.
    pub values: GridValues,
}

/// A solve's report, ready to write.
pub struct SolveReport<'a> {
    /// The problem as solved (command-line overrides applied).
    pub problem: &'a Problem,
    /// It bound to its scene.
    pub binding: &'a Binding,
    /// The scene as bound, before any configuration is applied.
    pub scene: &'a Scene,
    /// The run's files.
    pub folder: &'a SolveFolder,
    /// What the objective surface must meet, if anything.
    pub requirement: Option<&'a Requirement>,
    /// The objective's grid, or `None` to leave it out.
    pub grid: Option<GridOptions>,
}

/// What writing a report did.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// The page.
    pub path: PathBuf,
    /// Seconds it took, the grid's trace included.
    pub seconds: f64,
    /// Why the objective has no plan, when it has none.
    pub no_plan: Option<String>,
}

impl Written {
    /// What a command prints of it: the notes, then the page and its seconds.
    pub fn lines(&self) -> String {
        let notes = self.no_plan.iter().map(|n| format!("note: {n}\n"));
        let page = format!("{} in {:.1} s", self.path.display(), self.seconds);
        notes.collect::<String>() + &page
    }
}

impl<'a> SolveReport<'a> {
    /// The report of `folder`, a run of `problem` bound to `scene` as `binding`, with
    /// no requirement and no grid.
    pub fn new(
        problem: &'a Problem,
        binding: &'a Binding,
        scene: &'a Scene,
        folder: &'a SolveFolder,
    ) -> SolveReport<'a> {
        SolveReport {
            problem,
            binding,
            scene,
            folder,
            requirement: None,
            grid: None,
        }
    }

    /// The same report checking `requirement` on the objective's grid measured as
    /// `grid` says.
    pub fn with(self, requirement: Option<&'a Requirement>, grid: GridOptions) -> Self {
        SolveReport {
            requirement,
            grid: Some(grid),
            ..self
        }
    }

    /// Rebuilds the report of the run in `dir` of `problem` (as
    /// [`SolveFolder::problem`] reads it) from its files, with the scene loaded as the
    /// run loaded it, and writes it.
    pub fn rebuild(
        dir: &Path,
        problem: &Problem,
        mut scene: Scene,
        requirement: Option<&Requirement>,
        grid: GridOptions,
    ) -> Result<Written, ReportError> {
        let binding = Binding::new(problem, &mut scene).map_err(ReportError::Folder)?;
        let folder = SolveFolder::read(dir, problem, &binding)?;
        let report = SolveReport::new(problem, &binding, &scene, &folder);
        report.with(requirement, grid).write()
    }

    /// Writes `report.html` into the run's folder (atomically).
    pub fn write(&self) -> Result<Written, ReportError> {
        let started = Instant::now();
        let (html, no_plan) = self.html()?;
        let path = self.folder.dir.join("report.html");
        invlight_scene::write_atomically(&path, |w| w.write_all(html.as_bytes()))
            .map_err(|e| ReportError::Io(path.clone(), e))?;
        Ok(Written {
            path,
            seconds: started.elapsed().as_secs_f64(),
            no_plan,
        })
    }

    /// The page, and why the objective has no plan when it has none.
    pub fn html(&self) -> Result<(String, Option<String>), ReportError> {
        let (p, f) = (self.problem, self.folder);
        let goal = &f.result.objective;
        let name = p
            .path
            .file_name()
            .map_or("problem".into(), |n| n.to_string_lossy().to_string());
        let mut page = Page::new(
            &format!("{} — {name}", capitalised(&goal.words())),
            &format!(
                "invlight {} report of {}",
                env!("CARGO_PKG_VERSION"),
                p.path.display()
            ),
        );
        let facts = PageFacts {
            unit: goal.unit_suffix(),
            level: plain(p.confidence.level() * 100.0),
            compass: compass(self.scene),
            members: f.members(),
            feasible: !f.isoc.members().is_empty(),
        };
        page.section("The answer", &self.answer(&facts));
        page.section("The problem", &self.problem_words(&facts));
        page.section("The best configurations (ISOC)", &self.gallery(&facts));
        page.section("The search", &self.search(&facts)?);
        let no_plan = self.plan(&facts, &mut page)?;
        let title = if facts.feasible {
            "Every member of the ISOC"
        } else {
            "The configurations closest to meeting the constraints"
        };
        page.section(title, &self.member_table(&facts));
        let photons: u64 = f.records.iter().map(|r| r.evaluation.goal.samples).sum();
        let r = &f.result;
        page.section(
            "How long it took",
            &format!(
                "<p>{} evaluations ({} candidates refused untraced), {} photons traced in {:.1} s of search. The renders, plots and this page came after.</p>",
                r.evaluations, r.refused, photons, r.seconds
            ),
        );
        Ok((page.finish(), no_plan))
    }

    /// The answer: the best configuration (or the closest, when none is feasible) in
    /// world terms, its value and constraints, and why the search ended when it says.
    fn answer(&self, facts: &PageFacts<'_>) -> String {
        let f = self.folder;
        let answer = match facts.members.first() {
            Some(best) => self.best_answer(facts, best),
            None => "<div class=\"answer\"><p>No configuration could be ranked: every one tried was invalid.</p></div>".into(),
        };
        // Why the search ended: above all that no configuration tried lit the goal's
        // surface, which the answer's figures alone would not say.
        match &f.result.stopped {
            Some(why) => format!("{answer}<p>The search stopped: {}.</p>", escape(why)),
            None => answer,
        }
    }

    /// The answer about `best`, the first member shown: its value, what moved from
    /// where the scene has it, its layouts, the lamps a lumen method would ask for, the
    /// best regular array beside it, its constraints and how it stands to the others.
    fn best_answer(&self, facts: &PageFacts<'_>, best: &Member) -> String {
        let (p, b, f) = (self.problem, self.binding, self.folder);
        let (unit, level) = (&facts.unit, &facts.level);
        let goal = &f.result.objective;
        let e = &best.evaluation.goal;
        let i = e.interval(f.isoc.z());
        let words = capitalised(&goal.words());
        let opening = answer_opening(
            &words,
            (e.mean, i),
            unit,
            level,
            b.specs.is_empty(),
            facts.feasible,
        );
        let mut s = format!("<div class=\"answer\"><p>{opening}</p><ul>");
        let start = b.values(&b.initial);
        for ((spec, v), from) in b.specs.iter().zip(b.values(&best.config)).zip(&start) {
            s += &format!(
                "<li>{} is {} — {} from where the scene has it ({})</li>",
                escape(&subject(spec)),
                escape(&describe::value(&v, facts.compass.as_ref())),
                escape(&describe::moved(from, &v)),
                escape(&describe::value(from, facts.compass.as_ref()))
            );
        }
        s += "</ul>";
        for l in f.result.answer().iter().flat_map(|m| &m.layouts) {
            s += &format!("<p>As laid out: {}.</p>", escape(&l.description));
        }
        if let Some((have, need)) = f
            .result
            .closest
            .first()
            .and_then(|m| m.lamps_needed(&f.result.constraints, |n| b.lit_only_by(n)))
        {
            s += &format!(
                "<p>Every one of the {have} lamps is at full output: by the lumen method (illuminance in proportion to the lamps' count at the layout's utilisation factor), about {need} such lamps would give the minimum.</p>"
            );
        }
        if let Some(r) = f.result.regular_beside() {
            let e = &r.estimate;
            let layouts: Vec<&str> = r.layouts.iter().map(|l| l.description.as_str()).collect();
            s += &format!(
                "<p>The best regular array tried gives {}{unit} [{}, {}] (at {} photons): {}.</p>",
                significant(e.mean),
                significant(e.low),
                significant(e.high),
                e.photons,
                escape(&layouts.join("; "))
            );
        }
        s += &constraint_list(b, best, f.isoc.z(), p.confidence.z_one_sided());
        s += &match (facts.feasible, facts.members.len()) {
            (false, n) => {
                format!("<p>The {n} configurations that came closest are shown below.</p>")
            }
            (true, 1) => format!(
                "<p>It is better, at {level} % confidence, than every other configuration tried.</p>"
            ),
            (true, n) => format!(
                "<p>{} other configurations cannot be told apart from it at {level} % confidence (the ISOC, thesis §3.3.4); each is better than every configuration left out. All are shown below.</p>",
                n - 1
            ),
        };
        s + "</div>"
    }

    /// The problem in words: scene, goal, cap, constraints, variables, the photons and
    /// budget, and the requirement when one is checked.
    fn problem_words(&self, facts: &PageFacts<'_>) -> String {
        let (p, b, f) = (self.problem, self.binding, self.folder);
        let level = &facts.level;
        let goal = &f.result.objective;
        let mut words = String::from("<dl>");
        words += &format!(
            "<dt>Scene</dt><dd>{}</dd>",
            escape(&p.scene.path.display().to_string())
        );
        words += &format!("<dt>Goal</dt><dd>{}</dd>", escape(&goal.words()));
        if let Some(cap) = goal.cap {
            words += &format!(
                "<dt>Cap</dt><dd>its mean illuminance must not exceed {} lx</dd>",
                plain(cap)
            );
        }
        for c in &f.result.constraints {
            let sign = if matches!(c.bound.as_str(), "maxLux" | "maxUGR") {
                "≤"
            } else {
                "≥"
            };
            let cu = if c.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", c.unit)
            };
            words += &format!(
                "<dt>Constraint</dt><dd>{} ({}, {} side{}) {sign} {}{cu}, held at {level} % confidence (one-sided)</dd>",
                escape(&c.surface),
                escape(&c.bound),
                escape(&c.side),
                if c.side == "both" { "s" } else { "" },
                plain(c.limit)
            );
        }
        for (i, spec) in b.specs.iter().enumerate() {
            words += &format!(
                "<dt>Variable {}</dt><dd>{} ({}) within {}</dd>",
                i + 1,
                escape(&subject(spec)),
                spec.kind.name(),
                escape(&describe::range(b, i))
            );
        }
        words += &format!(
            "<dt>Photons</dt><dd>{} per full evaluation, {} % of that for a first look (fastEvaluationQuality), strategy {}</dd><dt>Confidence</dt><dd>{level} %: intervals and comparisons</dd><dt>Budget</dt><dd>{} candidates, seed {}</dd>",
            p.photons,
            plain(p.fast_quality * 100.0),
            p.strategy.name(),
            p.max_iterations,
            p.seed
        );
        if let Some(r) = self.requirement {
            words += &format!(
                "<dt>Requirement</dt><dd>{}</dd>",
                escape(&requirement_words(r))
            );
        }
        words + "</dl>"
    }

    /// The ISOC as captioned renders, from the pictures the solve left in its folder.
    fn gallery(&self, facts: &PageFacts<'_>) -> String {
        let (b, f) = (self.binding, self.folder);
        let unit = &facts.unit;
        let mut gallery = String::new();
        for (k, m) in facts.members.iter().enumerate() {
            let file = f.dir.join(format!("isoc-{:02}.png", k + 1));
            let Ok(bytes) = std::fs::read(&file) else {
                continue;
            };
            let i = m.evaluation.goal.interval(f.isoc.z());
            let what: Vec<String> = b
                .specs
                .iter()
                .zip(b.values(&m.config))
                .map(|(spec, v)| {
                    format!(
                        "{} {}",
                        subject(spec),
                        describe::value(&v, facts.compass.as_ref())
                    )
                })
                .collect();
            gallery += &figure(
                &img_png(&bytes, &format!("ISOC member {}", k + 1)),
                &escape(&format!(
                    "{}. {}{unit} [{}, {}]: {}",
                    k + 1,
                    significant(m.evaluation.goal.mean),
                    significant(i.low),
                    significant(i.high),
                    what.join("; ")
                )),
            );
        }
        if gallery.is_empty() {
            "<p>No renders in the folder (the solve ran with --no-images).</p>".into()
        } else {
            format!(
                "<p>Each member rendered from the scene's camera, best first, at one exposure (a brighter picture is a brighter configuration); the moved thing circled.</p><div class=\"gallery\">{gallery}</div>"
            )
        }
    }

    /// The search: a plot of what was tried for each searched variable, and the
    /// convergence of the best configuration against the photons traced.
    fn search(&self, facts: &PageFacts<'_>) -> Result<String, ReportError> {
        let (b, f) = (self.binding, self.folder);
        let goal = &f.result.objective;
        let level = &facts.level;
        let mut search = String::new();
        // Levels the evaluator solves are not searched: a plot of them would show
        // the arrangements' answers, not a walk.
        let solved: Vec<&str> = (0..b.specs.len())
            .filter(|&i| b.space.is_solved(i))
            .map(|i| b.specs[i].id.as_str())
            .collect();
        if !solved.is_empty() {
            search += &format!(
                "<p>The levels of {} are not searched: for every arrangement traced, the least-power levels that meet the constraints are solved exactly from its trace.</p>",
                escape(&solved.join(", "))
            );
        }
        for i in (0..b.specs.len()).filter(|&i| !b.space.is_solved(i)) {
            let plot = search_plot(self.scene, b, goal.cap, i, &f.records, &f.isoc);
            search += &figure(
                &plot.svg()?,
                "Each cell tried in the colour of the best mean found there (viridis over the evaluated range; grey: never feasible); the start (square), the improvements in order (line), the ISOC (red rings).",
            );
        }
        let conv = convergence(&f.records, &f.isoc, b);
        search += &figure(
            &conv.svg()?,
            &format!(
                "The best configuration so far (line) and its {level} % interval (band) against the photons traced; the last step is the final ISOC's best."
            ),
        );
        Ok(search)
    }

    /// Adds to `page` the light on the objective's surface in the best configuration,
    /// traced now, unless the report asks for no grid, nothing was ranked or the
    /// objective reads no surface. Returns why the surface has no plan when it has none.
    fn plan(&self, facts: &PageFacts<'_>, page: &mut Page) -> Result<Option<String>, ReportError> {
        let (p, b) = (self.problem, self.binding);
        let plan_surface = b.reading.plan_surface();
        let (Some(g), Some(best), Some((target, side))) =
            (self.grid, facts.members.first(), plan_surface)
        else {
            return Ok(None);
        };
        let surface = self.scene.surfaces[target].name.clone();
        let mut scene = self.scene.clone();
        b.apply(&mut scene, &best.config);
        let started = Instant::now();
        let settings = MapSettings {
            spacing: g.spacing,
            side,
            trace: g.trace,
            estimator: Estimator::Connected,
            values: g.values,
        };
        // Nothing moves: one world-space tree, as `invlight map` builds. The page is
        // rank 0's alone in a cluster job (the others have ended): its own trace.
        let accel = Accel::with_movable(&scene, &[]);
        let map = illuminance_map_across(&scene, &accel, target, &settings, None, &Alone);
        let title = format!("Light on {surface}");
        match map {
            Ok(map) => {
                let mut s = grid_section(
                    &map,
                    self.scene.up,
                    &format!("{surface} in the best configuration"),
                    p.confidence,
                    self.requirement,
                )?;
                s += &format!(
                    "<p class=\"sub\">Traced for this report in {:.1} s.</p>",
                    started.elapsed().as_secs_f64()
                );
                page.section(&title, &s);
                Ok(None)
            }
            Err(e) => {
                let why = match e {
                    MapError::Grid(GridError::NotPlanar { .. }) => {
                        format!("{surface} is not planar, so it has no plan or grid ({e})")
                    }
                    e => format!("no grid on {surface}: {e}"),
                };
                let mut s = format!("<p>{}.</p>", escape(&why));
                if self.requirement.is_some() {
                    s += "<p>The requirement cannot be checked without a grid.</p>";
                }
                page.section(&title, &s);
                Ok(Some(why))
            }
        }
    }

    /// Every member shown as a table row: its value, interval, standard error and
    /// photons, and its variables' values in world terms.
    fn member_table(&self, facts: &PageFacts<'_>) -> String {
        let (b, f) = (self.binding, self.folder);
        let goal = &f.result.objective;
        let mean = format!(
            "{}{}",
            goal.sense,
            if facts.unit.is_empty() {
                String::new()
            } else {
                format!(" ({})", goal.unit)
            }
        );
        let mut header = vec!["#", mean.as_str(), "low", "high", "σ", "photons"];
        let ids: Vec<String> = b.specs.iter().map(subject).collect();
        header.extend(ids.iter().map(String::as_str));
        let rows: Vec<Vec<String>> = facts
            .members
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let e = &m.evaluation.goal;
                let i = e.interval(f.isoc.z());
                let mut row = vec![
                    (k + 1).to_string(),
                    significant(e.mean),
                    significant(i.low),
                    significant(i.high),
                    significant(e.std_error),
                    e.samples.to_string(),
                ];
                row.extend(
                    b.values(&m.config)
                        .iter()
                        .map(|v| escape(&describe::value(v, facts.compass.as_ref()))),
                );
                row
            })
            .collect();
        table(&header, &rows)
    }
}

/// What several sections of a solve's page read, worked out once.
struct PageFacts<'r> {
    /// The goal's unit as a suffix of its values (` lx`), or empty.
    unit: String,
    /// The confidence as a percentage, in words (`95`).
    level: String,
    /// The scene's compass, for sun directions.
    compass: Option<Compass>,
    /// The members shown: the ISOC best first, or the closest configurations.
    members: Vec<&'r Member>,
    /// Whether some configuration met the constraints.
    feasible: bool,
}

/// The sentence that opens the answer: the goal's value `(mean, interval)` in `unit`
/// at `level` %, said of a design checked as authored (`fixed`: no variables), of the
/// best configuration when `feasible`, else of the closest one.
fn answer_opening(
    goal: &str,
    (mean, i): (f64, invlight_stats::Interval),
    unit: &str,
    level: &str,
    fixed: bool,
    feasible: bool,
) -> String {
    let (m, low, high) = (significant(mean), significant(i.low), significant(i.high));
    if fixed {
        format!(
            "The design as authored (the problem has no variables) <b>{}</b> every constraint at {level} % confidence. {} is <b>{m}{unit}</b> [{low}, {high}]:",
            if feasible { "meets" } else { "does not meet" },
            escape(goal),
        )
    } else if feasible {
        format!(
            "{} is <b>{m}{unit}</b> [{low}, {high}] ({level} % confidence) when:",
            escape(goal)
        )
    } else {
        format!(
            "No configuration tried meets every constraint at {level} % confidence. The closest gives {m}{unit} [{low}, {high}] when:"
        )
    }
}

/// `s` with its first letter capitalised.
fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next().map_or(String::new(), |f| {
        f.to_uppercase().collect::<String>() + c.as_str()
    })
}

/// A member's constraints as a list: each estimate with its interval, the bound and the
/// verdict (one-sided at `z_one_sided`).
fn constraint_list(b: &Binding, m: &Member, z: f64, z_one_sided: f64) -> String {
    if b.constraints.is_empty() {
        return String::new();
    }
    let mut s = String::from("<ul>");
    for (c, e) in b.constraints.iter().zip(&m.evaluation.constraints) {
        let i = e.interval(z);
        let unit = match c.unit() {
            "" => String::new(),
            u => format!(" {u}"),
        };
        let sign = if c.bound.is_lower() { "≥" } else { "≤" };
        let (maintained, limit) = if c.maintenance_factor == 1.0 {
            (
                String::new(),
                format!("{}{unit}", significant(c.bound.limit())),
            )
        } else {
            (
                format!(
                    " new, {}{unit} maintained (× MF {})",
                    significant(e.mean * c.maintenance_factor),
                    c.maintenance_factor
                ),
                format!(
                    "{}{unit} new for {}{unit} maintained",
                    significant(c.bound.limit()),
                    significant(c.maintained_limit())
                ),
            )
        };
        let named = c
            .standard_name()
            .map_or(String::new(), |s| format!(" ({})", escape(&s)));
        s += &format!(
            "<li>{}{named}: {}{unit} ({sign} {}{unit} at the run's confidence, one-sided; two-sided interval [{}, {}]){maintained}, {sign} {limit}: <b>{}</b></li>",
            escape(&c.label()),
            significant(e.mean),
            invlight_stats::significant_beside(c.one_sided_bound(e, z_one_sided), c.bound.limit()),
            significant(i.low),
            significant(i.high),
            c.verdict(e, z_one_sided).name()
        );
    }
    s + "</ul>"
}
