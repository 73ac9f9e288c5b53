//! A problem file's daylight: `<site>`, `<sun>` and `<sky>` under `<input>`,
//! read into an [`invlight_scene::daylight::Daylight`] that [`super::Problem::load_scene`]
//! puts on the scene. What is worth a warning (a sun below the horizon, a clock far from
//! the site's meridian) is warned of here, with the line.

use super::{Node, Reader};
use crate::Diagnostic;
use invlight_scene::Scene;
use invlight_scene::daylight::{Daylight, DaylightError, Site, SkySpec, SunAt};

impl Reader<'_, '_> {
    /// A daylight error on `node`'s line, with what the element looks like.
    fn daylight_error(&self, node: Node, e: DaylightError, example: &str) -> Diagnostic {
        self.error(node, format!("<{}>: {e}", node.tag_name().name()))
            .with_hint(format!("for example {example}"))
    }

    /// `<site latitude longitude timezone [north] [elevation]>`, `<sun date time
    /// [illuminance]>` and `<sky type horizontalLux>`, each at most once.
    pub(super) fn daylight(
        &self,
        site: Option<Node>,
        sun: Option<Node>,
        sky: Option<Node>,
    ) -> Result<Daylight, Diagnostic> {
        let site = match site {
            None => None,
            Some(n) => {
                const EXAMPLE: &str =
                    "<site latitude=\"-34.9\" longitude=\"-56.2\" timezone=\"-3\" north=\"0\"/>";
                self.check_attributes(
                    n,
                    &["latitude", "longitude", "timezone", "north", "elevation"],
                );
                let degrees = |a: &str| -> Result<f64, Diagnostic> {
                    self.real(n, a, "a number")?.ok_or_else(|| {
                        self.error(n, format!("<site> needs '{a}'"))
                            .with_hint(format!("for example {EXAMPLE}"))
                    })
                };
                let e = |e| self.daylight_error(n, e, EXAMPLE);
                let mut s = Site::new(
                    degrees("latitude")?,
                    degrees("longitude")?,
                    degrees("timezone")?,
                )
                .map_err(e)?;
                if let Some(north) = self.real(n, "north", "degrees clockwise")? {
                    s = s.with_north(north).map_err(e)?;
                }
                if let Some(m) = self.real(n, "elevation", "metres")? {
                    s = s.with_elevation(m).map_err(e)?;
                }
                Some(s)
            }
        };
        let sun_node = sun;
        let sun = match sun {
            None => None,
            Some(n) => {
                const EXAMPLE: &str = "<sun date=\"2025-12-21\" time=\"10:00\"/>";
                self.check_attributes(n, &["date", "time", "illuminance"]);
                let mut text = format!(
                    "{},{}",
                    self.required(n, "date")?,
                    self.required(n, "time")?
                );
                if let Some(lux) = n.attribute("illuminance") {
                    text = format!("{text},{lux}");
                }
                Some(
                    text.parse::<SunAt>()
                        .map_err(|e| self.daylight_error(n, e, EXAMPLE))?,
                )
            }
        };
        let sky = match sky {
            None => None,
            Some(n) => {
                const EXAMPLE: &str = "<sky type=\"cie-overcast\" horizontalLux=\"10000\"/>";
                self.check_attributes(n, &["type", "horizontalLux"]);
                let text = format!(
                    "{}:{}",
                    self.required(n, "type")?,
                    self.required(n, "horizontalLux")?
                );
                Some(
                    text.parse::<SkySpec>()
                        .map_err(|e| self.daylight_error(n, e, EXAMPLE))?,
                )
            }
        };
        if let (Some(n), None) = (sun_node, site) {
            return Err(self.daylight_error(
                n,
                DaylightError::NeedsSite,
                "<site latitude=\"-34.9\" longitude=\"-56.2\" timezone=\"-3\"/>",
            ));
        }
        if let (Some(n), Some(_)) = (sun_node, site) {
            // The sun alone on an empty scene: its warnings do not depend on the scene.
            let sun_only = Daylight {
                site,
                sun,
                sky: None,
            };
            let warnings = sun_only.apply(&mut Scene::default()).map_err(|e| {
                self.daylight_error(n, e, "<sun date=\"2025-12-21\" time=\"10:00\"/>")
            })?;
            warnings.into_iter().for_each(|w| self.warn(n, w));
        }
        Ok(Daylight { site, sun, sky })
    }
}
