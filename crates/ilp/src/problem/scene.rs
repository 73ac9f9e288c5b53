//! `<scene path scale up>` with its `<luminaire>` children, and `<output path>`: what
//! the problem is posed on and where its results go, both relative to the problem
//! file's folder.

use super::{FittingSize, Node, Reader, SceneRef};
use invlight_scene::{Diagnostic, Luminaire, UpAxis};
use std::path::{Path, PathBuf};

impl<'a, 'i> Reader<'a, 'i> {
    /// `<scene path scale up>` under `root`, exactly once; `dir` is the problem file's
    /// folder.
    pub(super) fn scene_ref(&self, root: Node<'a, 'i>, dir: &Path) -> Result<SceneRef, Diagnostic> {
        let scene_el = self
            .only(root, "scene")?
            .ok_or_else(|| self.error(root, "no <scene path=\"…\"/>, expected one in <input>"))?;
        self.check_attributes(scene_el, &["path", "scale", "up"]);
        let scale = match self.real(scene_el, "scale", "metres per file unit (e.g. 0.001)")? {
            Some(s) if s <= 0.0 => {
                return Err(self.error(
                    scene_el,
                    format!("'scale' of <scene> is {s}, expected a positive number of metres per file unit (e.g. 0.001 for millimetres)"),
                ));
            }
            s => s.map(|s| s as f32),
        };
        let up = match scene_el.attribute("up").map(str::trim) {
            None => None,
            Some("y" | "Y") => Some(UpAxis::Y),
            Some("z" | "Z") => Some(UpAxis::Z),
            Some(other) => {
                return Err(self.error(
                    scene_el,
                    format!("'up' of <scene> is '{other}', expected y or z"),
                ));
            }
        };
        let (luminaires, sizes) = self.luminaires(scene_el)?;
        Ok(SceneRef {
            path: dir.join(self.required(scene_el, "path")?),
            scale,
            up,
            luminaires,
            sizes,
            calculation: self.calculation(scene_el)?,
            line: self.line(scene_el),
        })
    }

    /// `<scene>`'s `<luminaire light file multiplier rotation size>` children, and the
    /// sizes some give; the file is kept as written and resolved when the scene is
    /// loaded ([`Scene::set_luminaires`]), under the folder rule of the problem file.
    fn luminaires(&self, scene: Node) -> Result<(Vec<Luminaire>, Vec<FittingSize>), Diagnostic> {
        let (mut out, mut sizes) = (Vec::new(), Vec::new());
        for e in self.elements(scene) {
            if e.tag_name().name() != "luminaire" {
                if !super::calculation::ELEMENTS.contains(&e.tag_name().name()) {
                    self.warn(
                        e,
                        format!(
                            "unknown element <{}> in <scene> ignored (expected luminaire, calculationSurface or workplane)",
                            e.tag_name().name()
                        ),
                    );
                }
                continue;
            }
            self.check_attributes(e, &["light", "file", "multiplier", "rotation", "size"]);
            let what = "a positive factor on the file's candela";
            let multiplier = match self.real(e, "multiplier", what)? {
                Some(m) if m <= 0.0 || m as f32 > f32::MAX => {
                    return Err(self.error(
                        e,
                        format!("'multiplier' of <luminaire> is {m}, expected {what}"),
                    ));
                }
                m => m.unwrap_or(1.0) as f32,
            };
            let rotation = match self.real(e, "rotation", "degrees about its aim")? {
                Some(r) if !r.is_finite() || r.abs() > 360.0 => {
                    return Err(self
                        .error(
                            e,
                            format!("'rotation' of <luminaire> is {r}, expected degrees in [-360, 360]"),
                        )
                        .with_hint("rotation=\"90\" turns the luminaire a quarter turn about its aim, C0 toward C90"));
                }
                r => r.unwrap_or(0.0) as f32,
            };
            if let Some(text) = e.attribute("size") {
                let [length, width] = parse_size(text).ok_or_else(|| {
                    self.error(
                        e,
                        format!("'size' of <luminaire> is '{text}', expected the fitting's length and width in metres, both positive, with a comma between"),
                    )
                    .with_hint("size=\"1.5,0.1\": 1.5 m along the luminaire's C90–C270 axis (EULUMDAT's length), 0.1 m across")
                })?;
                sizes.push(FittingSize {
                    light: self.required(e, "light")?,
                    length,
                    width,
                });
            }
            out.push(Luminaire {
                light: self.required(e, "light")?,
                file: PathBuf::from(self.required(e, "file")?),
                multiplier,
                rotation,
                origin: Some((self.path.to_path_buf(), self.line(e))),
            });
        }
        Ok((out, sizes))
    }

    /// `<output path>` under `root`, at most once (default `output`); `dir` is the
    /// problem file's folder.
    pub(super) fn output(&self, root: Node<'a, 'i>, dir: &Path) -> Result<PathBuf, Diagnostic> {
        Ok(match self.only(root, "output")? {
            Some(o) => {
                self.check_attributes(o, &["path"]);
                dir.join(self.required(o, "path")?)
            }
            None => dir.join("output"),
        })
    }
}

/// `"1.5,0.1"` → [1.5, 0.1]: two finite positive numbers with a comma between.
fn parse_size(text: &str) -> Option<[f64; 2]> {
    let (a, b) = text.split_once(',')?;
    let metres = |t: &str| {
        t.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && *x > 0.0)
    };
    Some([metres(a)?, metres(b)?])
}
