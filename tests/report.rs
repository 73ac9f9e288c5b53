//! report.html in a real browser: headless Chromium opens the report of the
//! bundled cornell-cone example and a map's report, takes a screenshot, and the test
//! checks the page rendered — not blank, the size asked for — and that the file
//! references nothing outside itself, with the browser's networking blocked.
//!
//! Without Chromium the test says so and skips; with `INVLIGHT_REQUIRE_BROWSER=1`
//! (`.ci/run` sets it after installing Debian's `chromium`) a missing browser fails.
//! `INVLIGHT_SCREENSHOT=PATH` keeps the solve report's screenshot (docs/report.png).

use std::path::{Path, PathBuf};
use std::process::Command;

fn invlight() -> Command {
    Command::new(env!("CARGO_BIN_EXE_invlight"))
}

fn chromium() -> Option<PathBuf> {
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .find_map(|name| {
            let out = Command::new("which").arg(name).output().ok()?;
            out.status
                .success()
                .then(|| PathBuf::from(String::from_utf8_lossy(&out.stdout).trim()))
        })
}

/// A screenshot of `page`, `width` × `height` pixels, networking off.
fn screenshot(browser: &Path, page: &Path, shot: &Path, width: u32, height: u32) {
    let profile = tempfile::tempdir().unwrap();
    let status = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            // Every host resolves to nothing: a page that needed the network would show
            // its holes.
            "--host-resolver-rules=MAP * ~NOTFOUND",
            "--proxy-server=127.0.0.1:9",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("--screenshot={}", shot.display()))
        .arg(format!("--window-size={width},{height}"))
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "chromium: {}",
        String::from_utf8_lossy(&status.stderr)
    );
}

/// Checks a screenshot: the size asked for, and a page with text and pictures on it
/// (many distinct colours, a fair share of non-white pixels).
fn rendered(shot: &Path, width: u32, height: u32) {
    let img = invlight_render::image::open(shot).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (width, height));
    let ink = img
        .pixels()
        .filter(|p| p.0.iter().any(|&c| c < 200))
        .count();
    let colours: std::collections::HashSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
    assert!(
        ink > (width * height / 50) as usize,
        "{ink} inked pixels: a blank page"
    );
    assert!(
        colours.len() > 200,
        "{} colours: no pictures",
        colours.len()
    );
}

#[test]
fn reports_render_in_a_browser_and_reference_nothing_outside() {
    let Some(browser) = chromium() else {
        if std::env::var("INVLIGHT_REQUIRE_BROWSER").is_ok_and(|v| v == "1") {
            panic!("INVLIGHT_REQUIRE_BROWSER=1 but no chromium is installed");
        }
        eprintln!(
            "SKIPPED: no chromium on this machine (apt-get install chromium); the report's browser test did not run"
        );
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cone");
    let root = env!("CARGO_MANIFEST_DIR");
    let solve = invlight()
        .current_dir(root)
        .args([
            "solve",
            "examples/cornell-cone/problem.xml",
            "--iterations",
            "60",
        ])
        .args([
            "--image-photons",
            "50000",
            "--image-width",
            "320",
            "--output",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        solve.status.success(),
        "{}",
        String::from_utf8_lossy(&solve.stderr)
    );
    let map_page = dir.path().join("map.html");
    let map = invlight()
        .current_dir(root)
        .args([
            "map",
            "tests/data/gltf/room_area.gltf",
            "--surface",
            "Floor",
            "--grid",
            "auto",
        ])
        .args(["--photons", "200000", "--task", "office", "--report"])
        .arg(&map_page)
        .arg("--output")
        .arg(dir.path().join("floor"))
        .output()
        .unwrap();
    assert!(
        map.status.success(),
        "{}",
        String::from_utf8_lossy(&map.stderr)
    );
    // `invlight report` rebuilds the solve's page from the folder.
    let page = out.join("report.html");
    let first = std::fs::read_to_string(&page).unwrap();
    std::fs::remove_file(&page).unwrap();
    let rebuilt = invlight().arg("report").arg(&out).output().unwrap();
    assert!(
        rebuilt.status.success(),
        "{}",
        String::from_utf8_lossy(&rebuilt.stderr)
    );
    let answer = |html: &str| {
        let i = html.find("<div class=\"answer\">").unwrap();
        html[i..i + html[i..].find("</div>").unwrap()].to_string()
    };
    assert_eq!(
        answer(&std::fs::read_to_string(&page).unwrap()),
        answer(&first)
    );
    for (page, height) in [(page, 2400), (map_page, 1600)] {
        let html = std::fs::read_to_string(&page).unwrap();
        let external = invlight_report::external_references(&html);
        assert!(external.is_empty(), "{}: {external:?}", page.display());
        assert!(!html.contains("<script"));
        let shot = dir.path().join("shot.png");
        screenshot(&browser, &page, &shot, 1000, height);
        rendered(&shot, 1000, height);
        if let (Ok(keep), 2400) = (std::env::var("INVLIGHT_SCREENSHOT"), height) {
            std::fs::copy(&shot, keep).unwrap();
        }
    }
}
