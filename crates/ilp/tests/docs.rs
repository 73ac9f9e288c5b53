//! The problem files shown in docs/problem-file.md are read as they are written: an
//! element or attribute misspelt there would be ignored with a warning by the reader,
//! and a user copying the example would get a problem other than the one described.

use invlight_ilp::Problem;
use std::path::Path;

/// The `xml` blocks of the section of docs/problem-file.md titled `title`.
fn xml_blocks(title: &str) -> Vec<String> {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/problem-file.md");
    let text = std::fs::read_to_string(docs).unwrap();
    let start = text.find(&format!("\n## {title}\n")).expect("the section");
    let section = &text[start + 1..];
    let section = &section[..section[3..].find("\n## ").map_or(section.len(), |e| e + 3)];
    section
        .split("```xml\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap().to_string())
        .collect()
}

/// The worked room: its workplane and calculation surface, its sky and its lamp's
/// placement are read, and nothing in it is unknown.
#[test]
fn the_worked_room_is_read_without_warnings() {
    let blocks = xml_blocks("Building a room for a problem");
    assert_eq!(blocks.len(), 1, "{blocks:?}");
    let p = Problem::parse(Path::new("/rooms/problem.xml"), &blocks[0]).unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    let c = &p.scene.calculation;
    assert_eq!(c.surfaces.len(), 1);
    assert_eq!(c.surfaces[0].surface, "DeskTask");
    let w = &c.workplanes[0];
    assert_eq!((w.id.as_str(), w.height, w.border), ("Task", 0.8, 0.5));
    assert!(p.daylight.sky.is_some());
    assert_eq!(p.variables.len(), 1);
    assert_eq!(p.variables[0].id, "Lamp");
}
