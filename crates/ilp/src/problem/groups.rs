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
        let lights: Vec<String> = self
            .required(v, "lights")?
            .split_whitespace()
            .map(str::to_string)
            .collect();
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
        for (k, light) in lights.iter().enumerate() {
            if lights[..k].contains(light) {
                return Err(self.error(
                    v,
                    format!("'{light}' is named twice in <lightGroup id=\"{id}\">"),
                ));
            }
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
}
