//! `<lightGroup id lights>` (invlight): lamps a designer specifies together. A group
//! is switched and dimmed as one — a `<lightPower>` of the group's id gives every lamp
//! of it one level, as one circuit or DALI group is — and aimed as one by a
//! `<lightAim>` of its id; its lamps may still be placed one by one.

use super::{Node, Reader};
use invlight_scene::Diagnostic;

/// A group of lamps that share a dimming level and an aim.
#[derive(Debug, Clone, PartialEq)]
pub struct LightGroup {
    /// The group's id, which `<lightPower>` and `<lightAim>` name.
    pub id: String,
    /// Its lamps' names, in file order.
    pub lights: Vec<String>,
    /// The element's line.
    pub line: u32,
}

impl Reader<'_, '_> {
    /// `<lightGroup id lights>`: `lights` the names of two or more lamps, separated by
    /// white space, each in no other group.
    pub(super) fn light_group(
        &self,
        v: Node,
        groups: &[LightGroup],
    ) -> Result<LightGroup, Diagnostic> {
        self.check_attributes(v, &["id", "lights"]);
        let id = self.required(v, "id")?;
        let lights = self.lamp_names(v, "lights", &format!("<lightGroup id=\"{id}\">"))?;
        if lights.len() < 2 {
            return Err(self
                .error(
                    v,
                    format!(
                        "<lightGroup id=\"{id}\"> names {} lamp(s), expected two or more",
                        lights.len()
                    ),
                )
                .with_hint("lights=\"Lamp1 Lamp2 Lamp3\": the lamps' names, separated by spaces"));
        }
        if let Some(g) = groups.iter().find(|g| g.id == id) {
            return Err(self.error(
                v,
                format!("a second <lightGroup id=\"{id}\">, expected distinct ids (the first is on line {})", g.line),
            ));
        }
        for light in &lights {
            if let Some(g) = groups.iter().find(|g| g.lights.contains(light)) {
                return Err(self.error(
                    v,
                    format!(
                        "'{light}' is in <lightGroup id=\"{}\"> already (line {}), expected each lamp in one group",
                        g.id, g.line
                    ),
                ));
            }
        }
        Ok(LightGroup {
            id,
            lights,
            line: self.line(v),
        })
    }

    /// The lamp names of attribute `attr` of `v` (`what` names the element in
    /// messages): separated by white space, each once; "Lamp1 … Lamp6" (or "...")
    /// stands for the numbered names between, as a designer writes a run of lamps.
    pub(super) fn lamp_names(
        &self,
        v: Node,
        attr: &str,
        what: &str,
    ) -> Result<Vec<String>, Diagnostic> {
        let text = self.required(v, attr)?;
        let words: Vec<&str> = text.split_whitespace().collect();
        let mut out: Vec<String> = Vec::new();
        let mut k = 0;
        while k < words.len() {
            let word = words[k];
            if matches!(word, "…" | "...") {
                let run = match (out.last(), words.get(k + 1)) {
                    (Some(first), Some(last)) => numbered_run(first, last),
                    _ => None,
                };
                let Some(run) = run else {
                    return Err(self
                        .error(v, format!("'{attr}' of {what} has '{word}' where a run of numbered lamps was expected"))
                        .with_hint("write the first and last of the run around it, with one number each: \"Lamp1 … Lamp6\""));
                };
                out.extend(run);
                k += 2;
                continue;
            }
            out.push(word.to_string());
            k += 1;
        }
        for (k, light) in out.iter().enumerate() {
            if out[..k].contains(light) {
                return Err(self.error(v, format!("'{light}' is named twice in {what}")));
            }
        }
        Ok(out)
    }
}

/// The names after `first` up to `last` when both are one stem and a number ("Lamp1",
/// "Lamp6" → Lamp2 … Lamp6), the number's width kept when it is zero-padded ("L01").
fn numbered_run(first: &str, last: &str) -> Option<Vec<String>> {
    let split = |s: &str| {
        let digits = s.len() - s.trim_end_matches(|c: char| c.is_ascii_digit()).len();
        let (stem, number) = s.split_at(s.len() - digits);
        Some((stem.to_string(), number.len(), number.parse::<u64>().ok()?))
    };
    let (stem, width, a) = split(first)?;
    let (stem_b, _, b) = split(last)?;
    (stem == stem_b && b > a && b - a <= 10_000)
        .then(|| (a + 1..=b).map(|n| format!("{stem}{n:0width$}")).collect())
}
