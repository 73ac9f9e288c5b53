//! `result.json`'s answer as the terminal prints it: a sentence that says what the rows
//! are, each member's value and variables in words, its constraints' lines
//! (`constraint_line.rs`), its layouts, and the best regular array beside a free answer.

use super::result::{ResultFile, ResultValue};
use crate::binding::Binding;
use crate::problem::VariableSpec;
use invlight_stats::significant;

impl ResultFile {
    /// The ISOC as a table for people, best first, each placed thing at its anchor
    /// with its placement point P beside it, and each member's constraints; when no
    /// configuration met the constraints, the closest.
    pub fn table(&self, binding: &Binding) -> String {
        let level = self.confidence * 100.0;
        let mut out = self.headline(binding, level);
        let unit = match self.objective.unit.as_str() {
            "" => String::new(),
            u => format!(" {u}"),
        };
        let rows = if self.isoc.is_empty() {
            &self.closest
        } else {
            &self.isoc
        };
        for (k, m) in rows.iter().enumerate() {
            let vars: Vec<String> = binding
                .specs
                .iter()
                .enumerate()
                .filter_map(|(i, spec)| {
                    let value = m.variables.get(&VariableSpec::key(&binding.specs, i))?;
                    Some(value_words(&spec.id, value))
                })
                .collect();
            let e = &m.estimate;
            out += &format!(
                "{:>3}. {}{unit} [{}, {}]  {}\n",
                k + 1,
                significant(e.mean),
                significant(e.low),
                significant(e.high),
                vars.join(", ")
            );
            for (c, info) in m.constraints.iter().zip(&self.constraints) {
                out += &c.line(info, level);
            }
            for l in &m.layouts {
                out += &format!("       {}\n", l.description);
            }
            if let Some(v) = m.violation {
                out += &format!("       short by {} %\n", significant(100.0 * v));
            }
            if let (0, Some((have, need))) = (
                k,
                m.lamps_needed(&self.constraints, |n| binding.lit_only_by(n)),
            ) {
                out += &format!(
                    "       every one of the {have} lamps is at full output: by the lumen method, about {need} such lamps would give the minimum\n"
                );
            }
        }
        out += &self.regular_lines(&unit);
        if let Some(why) = &self.stopped {
            out += &format!("stopped: {why}\n");
        }
        out
    }

    /// The sentence above the rows: what the rows are (the design as authored, the
    /// ISOC, the closest to feasible) and at which confidence.
    fn headline(&self, binding: &Binding, level: f64) -> String {
        let goal = self.objective.words();
        // The verb agrees with the count; the goal's words are left alone (they may hold
        // "light" too: "the most light of 'Desk'", "the largest daylight factor").
        let subject = |one: bool| {
            let s = if one { "s" } else { "" };
            match (&self.objective.surface, self.objective.element.as_str()) {
                (Some(name), "maximizeRadiance") => format!("light{s} '{name}' best"),
                _ => format!("give{s} {goal}"),
            }
        };
        match (self.isoc.len(), self.closest.is_empty()) {
            // A problem without variables checks the design as it is.
            (0, false) if binding.specs.is_empty() => format!(
                "The design as authored (the problem has no variables) does not meet every constraint at {level} % confidence:\n"
            ),
            (_, _) if binding.specs.is_empty() && !self.isoc.is_empty() => format!(
                "The design as authored (the problem has no variables) meets every constraint at {level} % confidence:\n"
            ),
            _ if self.unlit => format!(
                "No configuration tried lights {}: none could be told from 0 at {level} % confidence. The initial one:\n",
                self.objective
                    .surface
                    .as_ref()
                    .map_or("the goal's surface".into(), |s| format!("'{s}'"))
            ),
            (0, true) => {
                "No configuration could be ranked: every one tried was invalid.\n".to_string()
            }
            (0, false) => format!(
                "No configuration tried meets every constraint at {level} % confidence. Those closest to meeting them (largest shortfall of a mean from its limit):\n"
            ),
            (1, _) => format!(
                "One configuration {}, better at {level} % confidence than every other one tried:\n",
                subject(true)
            ),
            (n, _) => format!(
                "{n} configurations {}: the ISOC, those that cannot be told apart at {level} % confidence, each better than every one left out (thesis §3.3.4):\n",
                subject(false)
            ),
        }
    }

    /// The best regular array beside a free answer, and how far the answer is from it.
    fn regular_lines(&self, unit: &str) -> String {
        let mut out = String::new();
        if let (Some(r), Some(best)) = (self.regular_beside(), self.isoc.first()) {
            let e = &r.estimate;
            out += &format!(
                "The best regular array tried: {}{unit} [{}, {}] ({} photons)",
                significant(e.mean),
                significant(e.low),
                significant(e.high),
                e.photons
            );
            if e.mean != 0.0 {
                out += &format!(
                    ", the answer {} % {}",
                    significant((100.0 * (best.estimate.mean - e.mean) / e.mean).abs()),
                    if best.estimate.mean < e.mean {
                        "below it"
                    } else {
                        "above it"
                    }
                );
            }
            out += "\n";
            for l in &r.layouts {
                out += &format!("       {}\n", l.description);
            }
        }
        out
    }
}

/// A variable's value in words for the table: `Lamp1 at (…) (P = (…))`, `Lamp1 at 55 %`.
fn value_words(id: &str, value: &ResultValue) -> String {
    let v3 = |p: [f64; 3]| {
        format!(
            "({}, {}, {})",
            significant(p[0]),
            significant(p[1]),
            significant(p[2])
        )
    };
    match *value {
        ResultValue::ObjectInSurface { position, anchor }
        | ResultValue::LightInSurface { position, anchor }
        | ResultValue::HoleInSurface { position, anchor } => {
            format!("{id} at {} (P = {})", v3(anchor), v3(position))
        }
        ResultValue::DirectionalLight { direction } => {
            format!("{id} along {}", v3(direction))
        }
        ResultValue::LightAim { direction } => {
            format!("{id} aimed along {}", v3(direction))
        }
        ResultValue::SunTime {
            time, direction, ..
        } => format!("{id} at {time}, along {}", v3(direction)),
        ResultValue::Color { value, .. } => format!("{id} V = {}", significant(value)),
        ResultValue::LightPower { value } => {
            format!("{id} at {} %", significant(100.0 * value))
        }
        ResultValue::HoleSize { scale } => {
            format!("{id} × {}", significant(scale))
        }
        ResultValue::ObjectRotation { degrees } => {
            format!("{id} turned {}°", significant(degrees))
        }
        ResultValue::LightArray {
            columns,
            rows,
            walls,
            orientation,
        } => format!(
            "{id} {rows} × {columns} ({} × {} of a spacing from the rectangle's edges){}",
            significant(walls[0]),
            significant(walls[1]),
            orientation.map_or(String::new(), |o| format!(", turned {}°", significant(o)))
        ),
    }
}
