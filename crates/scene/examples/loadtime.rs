//! Measures how long scene files take to load: `cargo run --release -p invlight-scene
//! --example loadtime -- FILE...` prints, per file, the best of 5 wall-clock loads and the
//! scene's size.

use invlight_scene::{LoadOptions, load};
use std::path::Path;
use std::time::Instant;

fn main() -> std::process::ExitCode {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        eprintln!("usage: loadtime FILE...");
        return std::process::ExitCode::from(2);
    }
    for file in &files {
        let mut best = f64::INFINITY;
        let mut summary = String::new();
        for _ in 0..5 {
            let start = Instant::now();
            match load(Path::new(file), &LoadOptions::default()) {
                Ok(scene) => {
                    best = best.min(start.elapsed().as_secs_f64());
                    let triangles: usize = scene
                        .instances
                        .iter()
                        .map(|i| scene.meshes[i.mesh].triangles.len())
                        .sum();
                    summary = format!(
                        "{triangles} triangles, {} surfaces, {} materials",
                        scene.surfaces.len(),
                        scene.materials.len()
                    );
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    return std::process::ExitCode::FAILURE;
                }
            }
        }
        println!("{file}: {:.1} ms (best of 5); {summary}", best * 1e3);
    }
    std::process::ExitCode::SUCCESS
}
