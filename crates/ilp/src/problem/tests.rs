use super::variables::parse_mesh;
use super::*;
use crate::intention::{Grid, Side};

fn parse(text: &str) -> Result<Problem, Diagnostic> {
    Problem::parse(Path::new("/p/problem.xml"), text)
}

/// `<site>`, `<sun>` and `<sky>` read into the problem's daylight; mistakes name
/// their line and show the element's form.
#[test]
fn daylight_elements() {
    use invlight_scene::daylight::SkyKind;
    let body = "<scene path=\"s.gltf\"/><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives>";
    let with = |extra: &str| parse(&format!("<input>{body}\n{extra}</input>"));
    let p = with(
        r#"<site latitude="-34.9" longitude="-56.2" timezone="-3" north="30"/>
<sun date="2025-12-21" time="10:00"/><sky type="cie-overcast" horizontalLux="10000"/>"#,
    )
    .unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    let site = p.daylight.site.unwrap();
    assert_eq!((site.latitude(), site.north()), (-34.9, 30.0));
    assert_eq!(p.daylight.sun.unwrap().time.hour(), 10);
    let sky = p.daylight.sky.unwrap();
    assert_eq!(
        (sky.kind, sky.horizontal_lux),
        (SkyKind::CieOvercast, 10_000.0)
    );
    assert!(with("").unwrap().daylight.is_empty());
    let night = with(
        r#"<site latitude="-34.9" longitude="-56.2" timezone="-3"/>
<sun date="2025-12-21" time="23:00"/>"#,
    )
    .unwrap();
    assert_eq!(night.warnings.len(), 1, "{:?}", night.warnings);
    assert_eq!(night.warnings[0].line, Some(3));
    assert!(night.warnings[0].to_string().contains("below the horizon"));
    for (extra, what) in [
        (r#"<sun date="2025-12-21" time="10:00"/>"#, "needs the site"),
        (
            r#"<sky type="cie-sunny" horizontalLux="5"/>"#,
            "cie-overcast or cie-clear",
        ),
        (r#"<sky type="cie-overcast"/>"#, "horizontalLux"),
        (
            r#"<site latitude="-94" longitude="0" timezone="0"/>"#,
            "latitude",
        ),
        (r#"<site latitude="10" timezone="0"/>"#, "longitude"),
    ] {
        let e = with(extra).unwrap_err();
        assert_eq!(e.line, Some(2), "{extra}: {e}");
        assert!(e.to_string().contains(what), "{extra}: {e}");
    }
}

/// `<sunTime>`: whole steps between two clock times of one date, at the problem's
/// site; mistakes name their line.
#[test]
fn sun_time_variable() {
    let with = |site: &str, sky: &str, var: &str| {
        parse(&format!(
            "<input><scene path=\"s.gltf\"/>{site}{sky}\n<conditions>{var}</conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>"
        ))
    };
    let site = r#"<site latitude="0" longitude="0" timezone="0"/>"#;
    let var = r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="18:00" step="30"/>"#;
    let p = with(site, "", var).unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    let VariableKind::SunTime {
        date,
        from,
        to,
        step,
    } = &p.variables[0].kind
    else {
        panic!("{:?}", p.variables);
    };
    assert_eq!((date.day(), *from, *to, *step), (21, 480.0, 1080.0, 30.0));
    let default_step = r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="09:00"/>"#;
    let p = with(site, "", default_step).unwrap();
    assert!(matches!(
        p.variables[0].kind,
        VariableKind::SunTime { step: 10.0, .. }
    ));
    let clear =
        r#"<sun date="2026-12-21" time="12:00"/><sky type="cie-clear" horizontalLux="9000"/>"#;
    let mean = r#"<color id="W" hue="0" saturation="0"/><sunTime id="Sun" days="2026-01-01..2026-12-31" dayStep="7" from="08:00" to="18:00" step="60" objective="mean"/>"#;
    with(site, clear, var).expect("a sunTime variable's clear sky follows its sun");
    let p = with(site, "", mean).unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    assert_eq!(p.variables.len(), 1);
    let (id, schedule, line) = p.sun_schedule.as_ref().unwrap();
    assert_eq!((id.as_str(), *line), ("Sun", 2));
    assert_eq!(schedule.instants().len(), 53 * 11);
    let df = parse(&format!(
        "<input><scene path=\"s.gltf\"/>{site}\n<conditions>{mean}</conditions><objectives><maximizeDaylightFactor surface=\"F\"/></objectives></input>"
    ))
    .unwrap_err();
    assert!(df.to_string().contains("daylight-factor"), "{df}");
    for (site, sky, var, what) in [
        ("", "", mean, "no <site>"),
        (site, "", &mean.replace("..", "/"), "FIRST..LAST"),
        (
            site,
            "",
            &mean.replace("\"mean\"", "\"max\""),
            "expected mean",
        ),
        (
            site,
            "",
            &mean.replace("days=", "date=\"2026-01-01\" days="),
            "not both",
        ),
        (
            site,
            "",
            &mean.replace("dayStep=\"7\"", "dayStep=\"0\""),
            "dayStep",
        ),
        (
            site,
            "",
            &mean.replace("2026-12-31", "2025-12-31"),
            "first day first",
        ),
        ("", "", var, "no <site>"),
        (site, clear, mean, "cie-clear"),
        (
            site,
            "",
            r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="18:05" step="30"/>"#,
            "whole number of steps",
        ),
        (
            site,
            "",
            r#"<sunTime id="Sun" date="2026-12-21" from="18:00" to="08:00"/>"#,
            "from before to",
        ),
        (
            site,
            "",
            r#"<sunTime id="Sun" date="2026-02-30" from="08:00" to="09:00"/>"#,
            "28 days",
        ),
        (
            site,
            "",
            r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="24:00"/>"#,
            "24:00",
        ),
        (
            site,
            "",
            r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="09:00" step="0"/>"#,
            "step",
        ),
    ] {
        let e = with(site, sky, var).unwrap_err();
        assert_eq!(e.line, Some(2), "{var}: {e}");
        assert!(e.to_string().contains(what), "{var}: {e}");
    }
}

/// `<maximizeDaylightFactor>` and `minDaylightFactor` read as the goal and bound of
/// that name, in per cent, with the line a daylight-factor problem reports.
#[test]
fn daylight_factor_intentions() {
    let p = parse(
        r#"<input><scene path="s.gltf"/><conditions><holeSize id="H"/></conditions>
<objectives><maximizeDaylightFactor surface="Desk" side="front"/>
<constraint surface="Floor" minDaylightFactor="2"/></objectives></input>"#,
    )
    .unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    assert_eq!(p.goal.element(), "maximizeDaylightFactor");
    assert_eq!(p.goal.unit(), "DF %");
    assert_eq!(p.goal.surface().unwrap().side, Side::Front);
    assert_eq!(p.settings().sense, Sense::Maximize);
    assert_eq!(p.constraints[0].bound, Bound::MinDaylightFactor(2.0));
    assert_eq!(p.constraints[0].label(), "Floor.minDaylightFactor");
    assert_eq!(p.daylight_factor_line(), Some(2));
    let lux = parse(
        r#"<input><scene path="s.gltf"/><conditions><holeSize id="H"/></conditions>
<objectives><maximizeRadiance surface="Desk"/>
<constraint surface="Floor" minDaylightFactor="2"/></objectives></input>"#,
    )
    .unwrap();
    assert_eq!(lux.daylight_factor_line(), Some(3));
    let e = parse(
        r#"<input><scene path="s.gltf"/><conditions><holeSize id="H"/></conditions>
<objectives><maximizeRadiance surface="Desk"/>
<constraint surface="Floor" minDaylightFactor="120"/></objectives></input>"#,
    )
    .unwrap_err();
    assert_eq!(e.line, Some(3), "{e}");
    assert!(e.to_string().contains("[0, 100]"), "{e}");
}

#[test]
fn later_form_with_everything() {
    let p = parse(
        r#"<?xml version="1.0"?>
<input>
  <scene path="room.gltf" scale="0.001" up="z"/>
  <output path="out"/>
  <conditions meshSize="20x6">
<objectInSurface id="Cone" surface="Cone__Geometry" vertexAIndex="3" vertexBIndex="0" vertexCIndex="2" vertexDIndex="1"/>
<lightInSurface id="Lamp" surface="Ceiling" anchor="centre"/>
<holeInSurface id="Hole" surface="Roof"/>
<directionalLight id="Sun"/>
<color id="Walls" hue="39" saturation="0.23" max="0.9"/>
  </conditions>
  <objectives maxIterations="50" fastEvaluationQuality="0.0078125" strategy="REFINE_ISOC_ON_END" photons="5000" seed="3" confidence="0.9" maxBounces="4">
<maximizeRadiance surface="Floor" maxRadiosity="300"/>
  </objectives>
</input>"#,
    )
    .unwrap();
    assert_eq!(p.scene.path, Path::new("/p/room.gltf"));
    assert_eq!((p.scene.scale, p.scene.up), (Some(0.001), Some(UpAxis::Z)));
    assert_eq!(p.output, Path::new("/p/out"));
    assert_eq!(p.cells_per_dimension, vec![20, 6]);
    assert_eq!(p.variables.len(), 5);
    assert_eq!(
        p.variables[0].kind,
        VariableKind::ObjectInSurface(PlacementSpec {
            surface: "Cone__Geometry".into(),
            vertices: [3, 0, 2, 1],
            anchor: Anchor::VertexA,
        })
    );
    assert_eq!(
        p.variables[1].kind.placement().map(|p| p.anchor),
        Some(Anchor::Centre)
    );
    assert_eq!(p.variables[0].line, 6);
    assert_eq!(
        p.variables[4].kind,
        VariableKind::Color {
            hue: 39.0,
            saturation: 0.23,
            min: 0.0,
            max: 0.9
        }
    );
    assert!(matches!(
        p.goal,
        Goal::Maximize {
            cap: Some(300.0),
            ..
        }
    ));
    assert_eq!(p.strategy, Strategy::RefineOnEnd);
    assert_eq!(
        (p.photons, p.seed, p.max_bounces, p.max_iterations),
        (5000, 3, Some(4), 50)
    );
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}

#[test]
fn thesis_form_with_bare_attribute() {
    let p = parse(
        "<input>\n<scene path=\"cube.dae\"/>\n<conditions>\n<directionalLight id=\"Sun\"/>\n</conditions>\n<objectives maxIterations=1000>\n<maximizeRadiance surface=\"S\"/>\n</objectives>\n</input>",
    )
    .unwrap();
    assert_eq!(p.max_iterations, 1000);
    assert_eq!(p.cells_per_dimension, vec![20]);
    assert_eq!(p.warnings.len(), 1);
    assert_eq!(p.warnings[0].line, Some(6));
    assert_eq!(p.strategy, Strategy::RaceOnEnd);
    assert_eq!((p.photons, p.confidence), (100_000, Confidence::DEFAULT));
}

/// A file naming no strategy gets `RACE_ISOC_ON_END`, the fastest; a file naming one
/// keeps it, the thesis' strategies included, whatever the default.
#[test]
fn the_race_is_the_default_and_a_named_strategy_is_kept() {
    let with = |attribute: &str| {
        parse(&format!("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions><objectives{attribute}><maximizeRadiance surface=\"F\"/></objectives></input>"))
            .unwrap()
            .strategy
    };
    assert_eq!(with(""), Strategy::RaceOnEnd);
    for strategy in Strategy::ALL {
        assert_eq!(
            with(&format!(" strategy=\"{}\"", strategy.name())),
            strategy
        );
    }
}

#[test]
fn unknown_things_are_warnings() {
    let p = parse(
        "<input><scene path=\"s.obj\" units=\"mm\"/><camera/>\n<conditions meshSize=\"4\"><color id=\"W\" hue=\"0\" saturation=\"0\"/><spin id=\"x\"/></conditions>\n<objectives><maximizeRadiance surface=\"F\"/><spectralMatch/></objectives></input>",
    )
    .unwrap();
    let msgs: Vec<String> = p.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(msgs.len(), 4, "{msgs:?}");
    assert!(
        msgs.iter()
            .any(|m| m.contains("'units'") && m.starts_with("/p/problem.xml:1:"))
    );
    assert!(msgs.iter().any(|m| m.contains("<camera>")));
    assert!(
        msgs.iter()
            .any(|m| m.contains("<spin>") && m.contains(":2:"))
    );
    assert!(
        msgs.iter()
            .any(|m| m.contains("<spectralMatch>") && m.contains(":3:"))
    );
}

#[test]
fn a_misspelt_name_is_named_with_its_line_and_the_nearest_known_one() {
    // A British spelling of the only goal: the error is at that element, not at
    // <objectives>, and says what it most likely meant.
    let e = parse(
        "<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions>\n<objectives>\n<constraint surface=\"F\" minLux=\"500\"/>\n<minimisePower/>\n</objectives></input>",
    )
    .unwrap_err();
    assert_eq!(e.line, Some(4), "{e}");
    assert!(e.message.contains("<minimisePower> is not one"), "{e}");
    assert_eq!(
        e.hint.as_deref(),
        Some("did you mean <minimizePower>?"),
        "{e}"
    );
    // Misspelt variables, attributes and top-level elements are warnings with the
    // same hint; a name near nothing known gets none.
    let p = parse(
        "<input><scene path=\"s.obj\" scael=\"2\"/><conditons/>\n<conditions><directionalLigth id=\"S\"/><directionalLight id=\"T\"/></conditions>\n<objectives><maximizeRadiance surface=\"F\"/><spectralMatch/></objectives></input>",
    )
    .unwrap();
    let hints: Vec<(Option<u32>, Option<&str>)> = p
        .warnings
        .iter()
        .map(|w| (w.line, w.hint.as_deref()))
        .collect();
    for expected in [
        (Some(1), Some("did you mean 'scale'?")),
        (Some(1), Some("did you mean <conditions>?")),
        (Some(2), Some("did you mean <directionalLight>?")),
        (Some(3), None),
    ] {
        assert!(hints.contains(&expected), "{expected:?} not in {hints:?}");
    }
}

#[test]
fn a_maintenance_factor_holds_the_new_installation_to_the_maintained_limits() {
    let text = |mf: &str| {
        format!(
            "<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions>\n<objectives{mf}>\n<minimizePower/>\n<constraint surface=\"F\" minLux=\"500\"/><constraint surface=\"G\" maxLux=\"1000\"/><constraint surface=\"F\" minUniformity=\"0.6\"/><constraint surface=\"H\" minPointLux=\"200\"/></objectives></input>"
        )
    };
    let p = parse(&text(" maintenanceFactor=\"0.8\"")).unwrap();
    assert_eq!(p.maintenance_factor, 0.8);
    let limits: Vec<(f64, f64, f64)> = p
        .constraints
        .iter()
        .map(|c| (c.bound.limit(), c.maintenance_factor, c.maintained_limit()))
        .collect();
    // 500 lx maintained is 625 lx new, a cap likewise; U0 is a ratio, unchanged.
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9 * b.max(1.0);
    for (got, want) in limits.iter().zip([
        (625.0, 0.8, 500.0),
        (1250.0, 0.8, 1000.0),
        (0.6, 1.0, 0.6),
        (250.0, 0.8, 200.0),
    ]) {
        assert!(
            close(got.0, want.0) && got.1 == want.1 && close(got.2, want.2),
            "{got:?} against {want:?}"
        );
    }
    // Without one, the limits are the file's.
    let p = parse(&text("")).unwrap();
    assert_eq!(p.maintenance_factor, 1.0);
    assert_eq!(p.constraints[0].bound.limit(), 500.0);
    for bad in ["0", "1.5", "-0.8", "NaN"] {
        let e = parse(&text(&format!(" maintenanceFactor=\"{bad}\""))).unwrap_err();
        assert!(
            e.message.contains("maintenanceFactor") && e.line == Some(2),
            "{e}"
        );
    }
}

#[test]
fn nonsense_values_are_errors() {
    for (objectives, what) in [
        (
            "<maximizeRadiance surface=\"F\" maxRadiosity=\"NaN\"/>",
            "maxRadiosity",
        ),
        (
            "<maximizeRadiance surface=\"F\" maxRadiosity=\"0\"/>",
            "positive",
        ),
        (
            "<maximizeRadiance surface=\"F\" maxRadiosity=\"-3\"/>",
            "positive",
        ),
    ] {
        let e = parse(&format!("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions>\n<objectives>{objectives}</objectives></input>")).unwrap_err();
        assert_eq!(e.line, Some(2), "{e}");
        assert!(e.to_string().contains(what), "{e}");
    }
    let e = parse("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions><objectives confidence=\"inf\"><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
    assert!(e.message.contains("confidence"), "{e}");
    let e = parse("<input><scene path=\"s.obj\" scale=\"-1\"/><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
    assert!(e.message.contains("scale"), "{e}");
    let e = parse("<input><scene path=\"s.obj\" up=\"x\"/><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
    assert!(e.message.contains("'up'"), "{e}");
    let e = parse("<input><scene path=\"s.obj\"/><conditions><lightInSurface id=\"L\" surface=\"C\" anchor=\"middle\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
    assert!(e.message.contains("centre"), "{e}");
}

/// Every intention element reads, with its sides and grids; mistakes are errors on
/// their line.
#[test]
fn intentions_read_and_their_mistakes_are_errors() {
    let wrap = |objectives: &str| {
        format!(
            "<input><scene path=\"s.obj\"/><conditions><lightPower id=\"L\" min=\"0.2\"/><lightInSurface id=\"L\" surface=\"C\"/></conditions>\n<objectives>{objectives}</objectives></input>"
        )
    };
    let p = parse(&wrap(
        "<minimizePower/><constraint surface=\"Desk\" side=\"front\" minLux=\"500\"/><constraint surface=\"Desk\" side=\"front\" minUniformity=\"0.6\"/><constraint surface=\"Screen\" maxLux=\"300\"/><constraint surface=\"Desk\" minPointLux=\"300\" grid=\"0.25\"/>",
    ))
    .unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    assert_eq!(p.goal, Goal::MinimizePower);
    let labels: Vec<String> = p.constraints.iter().map(Constraint::label).collect();
    assert_eq!(
        labels,
        [
            "Desk.front.minLux",
            "Desk.front.minUniformity",
            "Screen.maxLux",
            "Desk.minPointLux"
        ]
    );
    assert_eq!(
        p.constraints[1].bound,
        Bound::MinUniformity(0.6, Grid::AUTO)
    );
    assert_eq!(
        p.constraints[3].bound,
        Bound::MinPointLux(300.0, Grid::metres(0.25))
    );
    assert_eq!(
        p.variables[0].kind,
        VariableKind::LightPower { min: 0.2, max: 1.0 }
    );
    assert_eq!(VariableSpec::key(&p.variables, 0), "L.power");
    assert_eq!(VariableSpec::key(&p.variables, 1), "L");
    let settings = p.settings();
    assert_eq!(settings.sense, Sense::Minimize);
    assert_eq!(settings.constraints.len(), 4);
    for (goal, sense) in [
        (
            "<targetRadiance surface=\"D\" lux=\"500\"/>",
            Sense::Target(500.0),
        ),
        (
            "<minimizeRadiance surface=\"D\" side=\"back\"/>",
            Sense::Minimize,
        ),
        (
            "<maximizeUniformity surface=\"D\" grid=\"auto\"/>",
            Sense::Maximize,
        ),
    ] {
        assert_eq!(
            parse(&wrap(goal)).unwrap().settings().sense,
            sense,
            "{goal}"
        );
    }
    for (objectives, what) in [
        ("", "no goal"),
        ("<minimizePower/><minimizePower/>", "a second goal"),
        ("<targetRadiance surface=\"D\"/>", "'lux'"),
        ("<targetRadiance surface=\"D\" lux=\"-5\"/>", "positive"),
        ("<minimizePower/><constraint surface=\"D\"/>", "no bound"),
        (
            "<minimizePower/><constraint surface=\"D\" minLux=\"1\" maxLux=\"2\"/>",
            "exactly one",
        ),
        (
            "<minimizePower/><constraint surface=\"D\" minUniformity=\"1.5\"/>",
            "minUniformity",
        ),
        (
            "<minimizePower/><constraint surface=\"D\" minLux=\"5\" side=\"top\"/>",
            "front, back or both",
        ),
        (
            "<minimizePower/><constraint surface=\"D\" minPointLux=\"5\" grid=\"-1\"/>",
            "grid",
        ),
        (
            "<minimizePower/><constraint surface=\"D\" minLux=\"5\"/><constraint surface=\"D\" minLux=\"7\"/>",
            "a second minLux",
        ),
    ] {
        let e = parse(&wrap(objectives)).unwrap_err();
        assert!(e.to_string().contains(what), "{objectives}: {e}");
        assert!(e.line.is_some(), "{e}");
    }
    for (conditions, what) in [
        (
            "<lightPower id=\"L\" min=\"0.6\" max=\"0.5\"/>",
            "min ≤ max",
        ),
        ("<lightPower id=\"L\" min=\"-1\"/>", "≥ 0"),
        (
            "<lightPower id=\"L\"/><lightPower id=\"L\"/>",
            "a second variable",
        ),
        (
            "<color id=\"L\" hue=\"0\" saturation=\"0\"/><lightPower id=\"L\"/>",
            "a second variable",
        ),
    ] {
        let text = format!(
            "<input><scene path=\"s.obj\"/><conditions>{conditions}</conditions><objectives><minimizePower/></objectives></input>"
        );
        let e = parse(&text).unwrap_err();
        assert!(e.to_string().contains(what), "{conditions}: {e}");
    }
    // 'grid' on a bound of the mean makes it the mean of the grid's points (Ēm); on a
    // daylight factor it is ignored with a warning.
    let p = parse(&wrap(
        "<minimizePower/><constraint surface=\"D\" minLux=\"5\" grid=\"1\"/>",
    ))
    .unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    assert_eq!(p.constraints[0].average_over, Some(Grid::metres(1.0)));
    let p = parse(&wrap(
        "<minimizePower/><constraint surface=\"D\" minLux=\"5\" values=\"cell-means\"/>",
    ))
    .unwrap();
    let over = p.constraints[0].average_over.unwrap();
    assert_eq!(over.values, crate::GridValues::CellMeans);
    let p = parse(&wrap(
        "<minimizePower/><constraint surface=\"D\" minDaylightFactor=\"2\" grid=\"1\"/>",
    ))
    .unwrap();
    assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
    let e = parse(&wrap(
        "<minimizePower/><constraint surface=\"D\" minUniformity=\"0.5\" values=\"centres\"/>",
    ))
    .unwrap_err();
    assert!(
        e.to_string().contains("expected points or cell-means"),
        "{e}"
    );
}

/// A scene path that does not exist is named with the problem file's line and the
/// folder it is relative to.
#[test]
fn a_missing_scene_says_where_paths_are_relative_to() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("problem.xml");
    std::fs::write(&path, "<input>\n<scene path=\"nowhere.gltf\"/><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap();
    let mut p = Problem::read(&path).unwrap();
    let e = p
        .load_scene(&LoadOptions::default(), None, None, &[])
        .unwrap_err();
    assert_eq!(e.line, Some(2));
    let text = e.to_string();
    assert!(
        text.contains("nowhere.gltf") && text.contains("relative to the problem file"),
        "{text}"
    );
    assert!(text.contains(&dir.path().display().to_string()), "{text}");
}

#[test]
fn errors_name_line_and_expectation() {
    let e = parse("<input>\n<scene path=\"s.obj\"/>\n<conditions>\n<lightInSurface id=\"L\"/>\n</conditions>\n<objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
    assert_eq!(e.line, Some(4));
    assert!(e.message.contains("'surface'"), "{e}");
    let e = parse("<input>\n<scene path=\"s.obj\"/>\n<conditions meshSize=\"20y\"><directionalLight id=\"S\"/></conditions>\n<objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
    assert_eq!(e.line, Some(3));
    assert!(e.message.contains("meshSize"), "{e}");
    let e = parse("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions>\n\n<objectives strategy=\"FAST\"><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
    assert_eq!(e.line, Some(3));
    assert!(e.message.contains("REFINE_ISOC_ON_END"), "{e}");
    let e = parse("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions></input>").unwrap_err();
    assert!(e.message.contains("<objectives>"), "{e}");
    let e = parse("<input><scene path=\"s.obj\"/>\n<conditions><color id=\"W\" hue=\"400\" saturation=\"0.2\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
    assert_eq!(e.line, Some(2));
    assert!(e.message.contains("[0, 360]"), "{e}");
    let e = parse("<input><scene path=\"s.obj\"></input>").unwrap_err();
    assert!(e.message.contains("XML"), "{e}");
}

#[test]
fn mesh_sizes() {
    assert_eq!(parse_mesh("20"), Some(vec![20]));
    assert_eq!(parse_mesh(" 20x6 "), Some(vec![20, 6]));
    assert_eq!(parse_mesh("0"), None);
    assert_eq!(parse_mesh("x"), None);
}

#[cfg(test)]
mod files {
    use super::*;

    #[test]
    fn ilpsolver_examples_parse() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/ilpsolver");
        let mut n = 0;
        for entry in std::fs::read_dir(&dir).expect("tests/data/ilpsolver") {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "xml") {
                let p = Problem::read(&path).unwrap_or_else(|e| panic!("{e}"));
                assert!(p.warnings.is_empty(), "{:?}", p.warnings);
                assert!(!p.variables.is_empty());
                n += 1;
            }
        }
        assert_eq!(n, 7);
        let cone = Problem::read(&dir.join("cornell-move-cone.xml")).unwrap();
        assert_eq!(cone.cells_per_dimension, vec![200]);
        assert_eq!(cone.strategy, Strategy::RefineOnEnd);
        assert_eq!(cone.fast_quality, 0.00390625);
        let color = Problem::read(&dir.join("sponza-color.xml")).unwrap();
        assert!(matches!(
            color.goal,
            Goal::Maximize {
                cap: Some(0.0003),
                ..
            }
        ));
    }

    #[test]
    fn thesis_appendix_d_parses() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/ilp/appendix-d.xml");
        let p = Problem::read(&path).unwrap();
        let kinds: Vec<&str> = p.variables.iter().map(|v| v.kind.name()).collect();
        assert_eq!(
            kinds,
            [
                "holeInSurface",
                "directionalLight",
                "lightInSurface",
                "objectInSurface",
                "color"
            ]
        );
        assert_eq!(p.max_iterations, 1000);
        assert_eq!(p.warnings.len(), 1, "the unquoted maxIterations");
        assert_eq!(p.warnings[0].line, Some(28));
        assert_eq!(p.goal.surface().unwrap().name, "Suzzane");
    }
}

/// `<lightArray>`: lamps by name or by a numbered run, columns and rows as a count or
/// a range; mistakes name their line and say what was expected.
#[test]
fn a_light_array_reads_its_lamps_and_ranges() {
    let with = |array: &str| {
        parse(&format!(
            "<input><scene path=\"s.gltf\"/><conditions>\n{array}\n</conditions><objectives><minimizePower/></objectives></input>"
        ))
    };
    let p = with(
        r#"<lightArray id="Grid" lights="L1 … L4 Spare" surface="Ceiling" columns="2..4" rows="2"/>"#,
    )
    .unwrap();
    let VariableKind::LightArray(a) = &p.variables[0].kind else {
        panic!("{:?}", p.variables);
    };
    assert_eq!(a.lights, ["L1", "L2", "L3", "L4", "Spare"]);
    assert_eq!(
        (a.columns, a.rows, a.surface.as_str()),
        ((2, 4), (2, 2), "Ceiling")
    );
    // The array's id stands for its lamps to <lightPower> and <lightAim>.
    let groups = p.lamp_groups();
    assert_eq!((groups[0].id.as_str(), groups[0].lights.len()), ("Grid", 5));
    // A zero-padded run keeps its width; "..." is read as "…".
    let p = with(r#"<lightArray id="G" lights="D08 ... D11" surface="C" columns="2" rows="2"/>"#)
        .unwrap();
    let VariableKind::LightArray(a) = &p.variables[0].kind else {
        panic!();
    };
    assert_eq!(a.lights, ["D08", "D09", "D10", "D11"]);
    for (array, what) in [
        (
            r#"<lightArray id="G" lights="L1 L2 L3" surface="C" columns="2" rows="2"/>"#,
            "needs at least 2 × 2 = 4 lamps and names 3",
        ),
        (
            r#"<lightArray id="G" lights="L1 L2" surface="C" columns="3..2" rows="1"/>"#,
            "'columns' of <lightArray> is '3..2'",
        ),
        (
            r#"<lightArray id="G" lights="L1 L2" surface="C" columns="0" rows="1"/>"#,
            "expected a count of lamps",
        ),
        (
            r#"<lightArray id="G" lights="… L2" surface="C" columns="1" rows="1"/>"#,
            "a run of numbered lamps",
        ),
        (
            r#"<lightArray id="G" lights="L1 … Lamp4" surface="C" columns="1" rows="1"/>"#,
            "a run of numbered lamps",
        ),
        (
            r#"<lightArray id="G" lights="L1 L2 L1" surface="C" columns="1" rows="1"/>"#,
            "'L1' is named twice",
        ),
        (
            r#"<lightArray id="G" lights="L1 L2" columns="1" rows="1"/>"#,
            "surface",
        ),
    ] {
        let e = with(array).unwrap_err();
        assert_eq!(e.line, Some(2), "{array}: {e}");
        assert!(e.to_string().contains(what), "{array}: {e}");
    }
    // An array and a placement of the same id are one mistake; a misspelt attribute
    // is named with the one meant.
    let e = with(
        "<lightArray id=\"G\" lights=\"L1 L2\" surface=\"C\" columns=\"2\" rows=\"1\"/>\n<lightInSurface id=\"G\" surface=\"C\"/>",
    )
    .unwrap_err();
    assert!(
        e.to_string().contains("a second variable with id 'G'"),
        "{e}"
    );
    let p = with(r#"<lightArray id="G" lights="L1 L2" surface="C" columns="2" row="1"/>"#);
    assert!(p.is_err(), "rows is required");
}

/// `<luminaire rotation>` turns a fitting about its aim, in degrees; a turn past a
/// whole turn or not a number names its line.
#[test]
fn a_luminaire_takes_its_rotation() {
    let with = |attrs: &str| {
        parse(&format!(
            "<input><scene path=\"s.gltf\">\n<luminaire light=\"L\" file=\"l.ldt\" {attrs}/></scene><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>"
        ))
    };
    assert_eq!(with("").unwrap().scene.luminaires[0].rotation, 0.0);
    assert_eq!(
        with("rotation=\"90\"").unwrap().scene.luminaires[0].rotation,
        90.0
    );
    let e = with("rotation=\"400\"").unwrap_err().to_string();
    assert!(e.contains(":2:") && e.contains("[-360, 360]"), "{e}");
}

/// The classroom example's scene with its twelve luminaires in one `<lightArray>` of
/// the attributes `array`, each `<luminaire>` with `rotation`, loaded from a copy in
/// `dir`.
fn classroom(dir: &Path, array: &str, rotation: &str) -> (Problem, invlight_scene::Scene) {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/classroom");
    for f in ["scene.gltf", "scene.bin", "classroom.ldt"] {
        std::fs::copy(example.join(f), dir.join(f)).unwrap();
    }
    let luminaires: String = (1..=12)
        .map(|k| format!("<luminaire light=\"Lamp{k}\" file=\"classroom.ldt\"{rotation}/>"))
        .collect();
    let text = format!(
        "<input><scene path=\"scene.gltf\">{luminaires}</scene><conditions><lightArray id=\"Grid\" lights=\"Lamp1 … Lamp12\" surface=\"LampZone__Geometry\" columns=\"2..4\" rows=\"2..4\"{array}/></conditions><objectives><minimizePower/></objectives></input>"
    );
    let path = dir.join("p.xml");
    std::fs::write(&path, text).unwrap();
    let mut p = Problem::read(&path).unwrap();
    let scene = p
        .load_scene(&invlight_scene::LoadOptions::default(), None, None, &[])
        .unwrap();
    (p, scene)
}

/// Each light's frame, a luminaire's.
fn frames(scene: &invlight_scene::Scene) -> Vec<glam::Mat3> {
    scene
        .lights
        .iter()
        .map(|l| match &l.kind {
            invlight_scene::LightKind::Goniometric { frame, .. } => *frame,
            _ => panic!("a luminaire"),
        })
        .collect()
}

/// `<luminaire size="L,W">` is the fitting's length and width as installed, metres;
/// a value that is not two positive numbers names its line and shows the form.
#[test]
fn a_luminaire_takes_its_size_as_installed() {
    let with = |attrs: &str| {
        parse(&format!(
            "<input><scene path=\"s.gltf\">\n<luminaire light=\"L\" file=\"l.ldt\" {attrs}/></scene><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>"
        ))
    };
    assert!(with("").unwrap().scene.sizes.is_empty());
    assert_eq!(
        with("size=\" 1.5 , 0.2\"").unwrap().scene.sizes,
        [FittingSize {
            light: "L".into(),
            length: 1.5,
            width: 0.2,
        }]
    );
    for bad in [
        "1.5",
        "1.5,0",
        "-1,0.2",
        "1.5;0.2",
        "a,b",
        "1.5,0.2,3",
        "inf,1",
    ] {
        let e = with(&format!("size=\"{bad}\"")).unwrap_err();
        assert!(
            e.to_string().contains(":2:") && e.message.contains("both positive"),
            "{bad}: {e}"
        );
        assert!(
            e.hint
                .as_deref()
                .is_some_and(|h| h.contains("size=\"1.5,0.1\"")),
            "{e:?}"
        );
    }
}

#[test]
fn an_arrays_orientation_turns_its_lamps_as_each_luminaires_rotation_does() {
    let dir = tempfile::tempdir().unwrap();
    let frames = |array: &str, rotation: &str| frames(&classroom(dir.path(), array, rotation).1);
    let (along, across) = (frames("", ""), frames(" orientation=\"90\"", ""));
    let each = frames("", " rotation=\"90\"");
    for ((a, b), c) in along.iter().zip(&across).zip(&each) {
        // A quarter turn about the aim: C0 goes where C90 was, the aim stays.
        assert!(b.x_axis.abs_diff_eq(a.y_axis, 1e-5), "{a} {b}");
        assert!(b.z_axis.abs_diff_eq(a.z_axis, 1e-5), "{a} {b}");
        assert!(b.abs_diff_eq(*c, 1e-6), "orientation {b} and rotation {c}");
    }
    let refused = |o: &str| {
        let text = format!(
            "<input><scene path=\"s.gltf\"/><conditions><lightArray id=\"G\" lights=\"A B\" surface=\"Z\" columns=\"1\" rows=\"1\" orientation=\"{o}\"/></conditions><objectives><minimizePower/></objectives></input>"
        );
        Problem::parse(Path::new("/p/problem.xml"), &text).unwrap_err()
    };
    assert!(refused("45").message.contains("expected 0, 90"));
}

/// What a folder records of each luminaire as installed, so that `--resume` refuses
/// rows traced another way: an array's fixed orientation adds to each `<luminaire
/// rotation>`, a searched one is the rows' own, and a `size` is kept.
#[test]
fn a_luminaire_is_recorded_turned_and_sized_as_installed() {
    let dir = tempfile::tempdir().unwrap();
    let (p, _) = classroom(dir.path(), " orientation=\"90\"", " rotation=\"90\"");
    assert_eq!(p.turn_as_installed("Lamp3"), Some(180.0));
    let (p, _) = classroom(dir.path(), " orientation=\"90\"", "");
    assert_eq!(p.turn_as_installed("Lamp3"), Some(90.0));
    let (p, _) = classroom(dir.path(), " orientation=\"search\"", "");
    assert_eq!(p.turn_as_installed("Lamp3"), None);
    assert_eq!(p.size_as_installed("Lamp3"), None);
    let (p, _) = classroom(dir.path(), "", " size=\"1.6,0.35\"");
    assert_eq!(p.size_as_installed("Lamp3"), Some([1.6, 0.35]));
}

/// `continuous` is true or false; anything else is refused with its line and a hint.
#[test]
fn an_arrays_continuous_is_true_or_false() {
    let with = |c: &str| {
        parse(&format!(
            "<input><scene path=\"s.gltf\"/><conditions>\n<lightArray id=\"G\" lights=\"A B\" surface=\"Z\" columns=\"1\" rows=\"1\"{c}/></conditions><objectives><minimizePower/></objectives></input>"
        ))
    };
    let continuous = |c: &str| match &with(c).unwrap().variables[0].kind {
        VariableKind::LightArray(a) => a.continuous,
        k => panic!("{k:?}"),
    };
    assert!(!continuous(""));
    assert!(!continuous(" continuous=\"false\""));
    assert!(continuous(" continuous=\" true \""));
    let e = with(" continuous=\"yes\"").unwrap_err();
    assert!(
        e.to_string().contains(":2:") && e.message.contains("is 'yes', expected true"),
        "{e}"
    );
    assert!(e.hint.is_some_and(|h| h.contains("end to end")));
}

/// `orientation="search"`: a configuration at 90° gives every lamp the frame
/// `rotation="90"` on each `<luminaire>` gives it, and one at 0° the frame as loaded,
/// set from the loaded frame each time: 90° twice is 90°, 90° then 0° is 0°.
#[test]
fn a_searched_orientation_sets_each_lamp_as_its_rotation_would() {
    let dir = tempfile::tempdir().unwrap();
    let along = frames(&classroom(dir.path(), "", "").1);
    let across = frames(&classroom(dir.path(), "", " rotation=\"90\"").1);
    let (p, mut scene) = classroom(dir.path(), " orientation=\"search\"", "");
    assert_eq!(frames(&scene), along, "loaded as authored");
    let b = crate::Binding::new(&p, &mut scene).unwrap();
    assert_eq!(b.space.dimensions(), 5);
    let at = |orientation: f64| {
        b.configuration(&[crate::VariableValue::Array(crate::ArrayShape {
            columns: 4,
            rows: 3,
            walls: [0.5, 0.5],
            orientation: Some(orientation),
        })])
        .unwrap()
    };
    let same = |got: &[glam::Mat3], want: &[glam::Mat3], what: &str| {
        for (g, w) in got.iter().zip(want) {
            assert!(g.abs_diff_eq(*w, 1e-6), "{what}: {g} and {w}");
        }
    };
    b.apply(&mut scene, &at(90.0));
    same(&frames(&scene), &across, "90°");
    b.apply(&mut scene, &at(90.0));
    same(&frames(&scene), &across, "90° twice");
    b.apply(&mut scene, &at(0.0));
    same(&frames(&scene), &along, "90° then 0°");
}
