//! An illuminance grid drawn as a lighting designer's plan (the false-colour plan with
//! isolux lines that DIALux and Relux reports show): the cells in the viridis colour of
//! their means over the data's range, isolux contours at round values, axes in world
//! metres, which side of the surface is seen, each cell's value where it fits, and
//! Emin, Eavg (with its interval), Emax and U0 printed above.

use crate::chart::{ChartError, colour_bar, rgb, text, to_image, to_svg};
use crate::colour_map::{ColourScale, tick_label};
use crate::compliance::plain;
use crate::map::IlluminanceMap;
use crate::plot::Frame;
use glam::Vec3;
use image::RgbImage;
use invlight_stats::{Confidence, significant};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Width of a plan picture, pixels; its height follows the grid's proportions.
pub const PLAN_WIDTH: u32 = 960;

/// Font size of a plan's labels, pixels; the title and the smaller labels are sized
/// from it.
const FONT: u32 = 18;

/// The segments where the bilinear surface through the cell centres crosses `level`,
/// by marching squares (Lorensen & Cline 1987, in two dimensions): every square of four
/// covered neighbouring centres is cut where its edges cross the level, linearly
/// between their ends; a saddle (two opposite corners above) is resolved by the
/// square's centre value. Coordinates are in cells, a cell's centre at (c + ½, r + ½).
pub fn isolines(
    values: &[Option<f64>],
    columns: usize,
    rows: usize,
    level: f64,
) -> Vec<[(f64, f64); 2]> {
    let at = |c: usize, r: usize| values[r * columns + c];
    let mut out = Vec::new();
    for r in 0..rows.saturating_sub(1) {
        for c in 0..columns.saturating_sub(1) {
            // Corners counter-clockwise from bottom-left.
            let (Some(a), Some(b), Some(d), Some(e)) =
                (at(c, r), at(c + 1, r), at(c + 1, r + 1), at(c, r + 1))
            else {
                continue;
            };
            let v = [a, b, d, e];
            let p = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
            let cut = |i: usize| {
                let j = (i + 1) % 4;
                let t = (level - v[i]) / (v[j] - v[i]);
                (
                    c as f64 + 0.5 + p[i].0 + t * (p[j].0 - p[i].0),
                    r as f64 + 0.5 + p[i].1 + t * (p[j].1 - p[i].1),
                )
            };
            let above: Vec<bool> = v.iter().map(|&x| x >= level).collect();
            let edges: Vec<usize> = (0..4).filter(|&i| above[i] != above[(i + 1) % 4]).collect();
            match edges.len() {
                2 => out.push([cut(edges[0]), cut(edges[1])]),
                4 => {
                    let centre_above = 0.25 * v.iter().sum::<f64>() >= level;
                    // Join each edge to the one that keeps the centre's side together.
                    if centre_above == above[0] {
                        out.push([cut(0), cut(1)]);
                        out.push([cut(2), cut(3)]);
                    } else {
                        out.push([cut(3), cut(0)]);
                        out.push([cut(1), cut(2)]);
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// A cell's value with three significant digits and no exponent: 5.69, 520, 12 400.
fn three_digits(e: f64) -> String {
    let decimals = if e.abs() >= 100.0 || e == 0.0 {
        0
    } else {
        (2 - e.abs().log10().floor() as i32).clamp(0, 4) as usize
    };
    format!("{e:.decimals$}")
}

/// How a grid's in-plane axis reads in the world: a world axis, or metres along it.
fn axis_name(axis: Vec3) -> (String, Option<(usize, f32)>) {
    for (k, name) in ["x", "y", "z"].iter().enumerate() {
        if axis[k].abs() > 0.9999 {
            return (name.to_string(), Some((k, axis[k].signum())));
        }
    }
    let d = axis.to_array().map(|c| format!("{c:.2}"));
    (format!("along ({}, {}, {})", d[0], d[1], d[2]), None)
}

/// The side a surface of normal `n` is seen from, in words.
pub fn seen_from(n: Vec3) -> String {
    let names = ["x", "y", "z"];
    let k = (0..3)
        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(2);
    let sign = if n[k] >= 0.0 { "+" } else { "−" };
    if n[k].abs() > 0.9999 {
        format!(
            "seen from {sign}{} (the side its normal points to)",
            names[k]
        )
    } else {
        format!(
            "seen along −({:.2}, {:.2}, {:.2}), its normal",
            n.x, n.y, n.z
        )
    }
}

/// A grid's plan, ready to draw.
pub struct MapPlan<'a> {
    map: &'a IlluminanceMap,
    title: String,
    confidence: Confidence,
    /// Whether rows run down the page: a grid whose normal points down, drawn as seen
    /// from above.
    flip: bool,
}

impl<'a> MapPlan<'a> {
    /// The plan of `map` titled `title`, Eavg's interval at `confidence`.
    pub fn new(map: &'a IlluminanceMap, title: &str, confidence: Confidence) -> MapPlan<'a> {
        MapPlan {
            map,
            title: title.to_string(),
            confidence,
            flip: false,
        }
    }

    /// The plan seen from above in a scene whose up axis is `up`, when the surface is
    /// horizontal and its normal points down (a floor whose triangles face the ground,
    /// a ceiling): mirrored, so that a plan reads as on a drawing.
    pub fn from_above(self, up: Vec3) -> MapPlan<'a> {
        let n = self.map.u.cross(self.map.v);
        MapPlan {
            flip: n.dot(up.normalize_or_zero()) < -0.7,
            ..self
        }
    }

    /// The scale: the cell means' range.
    pub fn scale(&self) -> ColourScale {
        ColourScale::of(self.map.cells.iter().flatten().map(|c| c.estimate.mean))
    }

    /// The isolux levels: round values inside the data's range.
    pub fn levels(&self) -> Vec<f64> {
        let s = self.scale();
        s.ticks(6)
            .into_iter()
            .filter(|&v| v > s.min && v < s.max)
            .collect()
    }

    fn size(&self) -> (u32, u32) {
        let m = self.map;
        let (w, h) = (
            m.columns as f64 * m.cell_u as f64,
            m.rows as f64 * m.cell_v as f64,
        );
        let plot_w = (PLAN_WIDTH - 230) as f64;
        let height = (plot_w * h / w.max(1e-9)) as u32 + 200;
        (PLAN_WIDTH, height.clamp(420, 1600))
    }

    /// The plan as an SVG document.
    pub fn svg(&self) -> Result<String, ChartError> {
        to_svg(self.size(), |root| self.draw(root).map(|_| ()))
    }

    /// The plan as a picture, with where its data (metres along the grid's axes from
    /// its corner) lands.
    pub fn image(&self) -> Result<(RgbImage, Frame), ChartError> {
        let mut frame = None;
        let image = to_image(self.size(), |root| {
            frame = Some(self.draw(root)?);
            Ok(())
        })?;
        Ok((image, frame.expect("drawing sets the frame")))
    }

    /// Draws the plan and writes it as a PNG or JPEG.
    pub fn write(&self, path: &std::path::Path) -> Result<(), crate::SaveError> {
        let (image, _) = self.image().map_err(crate::SaveError::Chart)?;
        crate::save_picture(&image, path)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<Frame, ChartError>
    where
        DB::ErrorType: 'static,
    {
        let m = self.map;
        root.fill(&WHITE)?;
        let (w, h) = root.dim_in_pixel();
        let (head, body) = root.split_vertically(3 * FONT + 10);
        self.draw_heading(&head)?;
        let (main, bar) = body.split_horizontally(w - 110);
        let scale = self.scale();
        colour_bar(&bar.margin(20, 70, 0, 0), &scale, "lx", FONT - 2)?;
        let (gw, gh) = (
            m.columns as f64 * m.cell_u as f64,
            m.rows as f64 * m.cell_v as f64,
        );
        // Equal metres per pixel: the grid's box scaled into the plotting area.
        let (label_x, label_y, margin) = (3 * FONT + 14, 4 * FONT, 12u32);
        let pw = (w - 110 - label_y - 2 * margin) as f64;
        let ph = (h - 3 * FONT - 10 - label_x - 2 * margin) as f64;
        let k = (gw / pw).max(gh / ph);
        let x = (0.5 * gw - 0.5 * k * pw, 0.5 * gw + 0.5 * k * pw);
        let y = (0.5 * gh - 0.5 * k * ph, 0.5 * gh + 0.5 * k * ph);
        let mut chart = ChartBuilder::on(&main)
            .margin(margin)
            .x_label_area_size(label_x)
            .y_label_area_size(label_y)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
        let page = PlanPage {
            cell: (m.cell_u as f64, m.cell_v as f64),
            height: gh,
            flip: self.flip,
        };
        self.draw_axes(&mut chart, page)?;
        let (cu, cv) = page.cell;
        chart.draw_series(m.cells.iter().enumerate().map(|(i, cell)| {
            let (c, r) = ((i as u32 % m.columns) as f64, (i as u32 / m.columns) as f64);
            let colour = match cell {
                Some(cell) => rgb(scale.colour(cell.estimate.mean)).filled(),
                None => RGBColor(230, 230, 230).filled(),
            };
            Rectangle::new(
                [
                    (c * cu, page.y(r * cv)),
                    ((c + 1.0) * cu, page.y((r + 1.0) * cv)),
                ],
                colour,
            )
        }))?;
        self.draw_isolux(&mut chart, &scale, page)?;
        let frame = {
            let (columns, rows) = chart.plotting_area().get_pixel_range();
            Frame {
                x,
                y,
                columns: (columns.start, columns.end - 1),
                rows: (rows.end - 1, rows.start),
            }
        };
        let cell_px = (cu / k, cv / k);
        if cell_px.0 >= 48.0 && cell_px.1 >= 22.0 {
            self.draw_cell_values(&mut chart, &scale, page)?;
        }
        chart.draw_series(std::iter::once(Rectangle::new(
            [(0.0, 0.0), (gw, gh)],
            BLACK.stroke_width(1),
        )))?;
        Ok(frame)
    }

    /// Draws the title and the figures a designer checks first (Emin, Eavg with its
    /// interval, Emax, U0 and the cells) above the plan.
    fn draw_heading<DB: DrawingBackend>(
        &self,
        head: &DrawingArea<DB, Shift>,
    ) -> Result<(), ChartError>
    where
        DB::ErrorType: 'static,
    {
        let m = self.map;
        let s = m.summary();
        let i = m.mean.interval(self.confidence.z());
        let figures = format!(
            "Emin {} lx · Eavg {} lx [{}, {}] · Emax {} lx · U0 = Emin/Eavg {:.2} · {}×{} cells of {}×{} m",
            significant(s.emin),
            significant(s.eavg),
            significant(i.low),
            significant(i.high),
            significant(s.emax),
            s.u0,
            m.columns,
            m.rows,
            significant(m.cell_u as f64),
            significant(m.cell_v as f64),
        );
        head.draw(&Text::new(self.title.clone(), (12, 6), text(FONT + 2)))?;
        head.draw(&Text::new(
            figures,
            (12, 8 + FONT as i32 + 6),
            text(FONT - 3),
        ))?;
        Ok(())
    }

    /// Draws the axes in world metres (ticks read as the coordinates along the world
    /// axis each grid axis follows, when it follows one) and says which side is seen.
    fn draw_axes<DB: DrawingBackend>(
        &self,
        chart: &mut PlanChart<'_, DB>,
        page: PlanPage,
    ) -> Result<(), ChartError>
    where
        DB::ErrorType: 'static,
    {
        let m = self.map;
        let (un, ua) = axis_name(m.u);
        let (vn, va) = axis_name(m.v);
        let (o, ou, ov) = (m.origin, ua, va);
        let fu = move |s: &f64| match ou {
            Some((k, sign)) => tick_label(o[k] as f64 + sign as f64 * s, 0.01),
            None => tick_label(*s, 0.01),
        };
        let fv = move |s: &f64| {
            let t = page.y(*s);
            match ov {
                Some((k, sign)) => tick_label(o[k] as f64 + sign as f64 * t, 0.01),
                None => tick_label(t, 0.01),
            }
        };
        let normal = if self.flip {
            -m.u.cross(m.v)
        } else {
            m.u.cross(m.v)
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("{un} (m) — {}", seen_from(normal)))
            .y_desc(format!("{vn} (m)"))
            .x_label_formatter(&fu)
            .y_label_formatter(&fv)
            .label_style(text(FONT - 2))
            .axis_desc_style(text(FONT - 2))
            .draw()?;
        Ok(())
    }

    /// Draws the isolux lines, each level labelled once: at its segment farthest from
    /// the labels placed before (nearest the centre among equals), so labels do not
    /// pile up; in black over light colours and white over dark ones.
    fn draw_isolux<DB: DrawingBackend>(
        &self,
        chart: &mut PlanChart<'_, DB>,
        scale: &ColourScale,
        page: PlanPage,
    ) -> Result<(), ChartError>
    where
        DB::ErrorType: 'static,
    {
        let m = self.map;
        let values: Vec<Option<f64>> = m.cells.iter().map(|c| c.map(|c| c.estimate.mean)).collect();
        let mut placed: Vec<(f64, f64)> = Vec::new();
        let centre = (0.5 * m.columns as f64, 0.5 * m.rows as f64);
        for level in self.levels() {
            let segments = isolines(&values, m.columns as usize, m.rows as usize, level);
            let ink = if scale.fraction(level) > 0.6 {
                BLACK
            } else {
                WHITE
            };
            chart.draw_series(segments.iter().map(|[a, b]| {
                PathElement::new(vec![page.at(*a), page.at(*b)], ink.stroke_width(2))
            }))?;
            let mid = |s: &[(f64, f64); 2]| (0.5 * (s[0].0 + s[1].0), 0.5 * (s[0].1 + s[1].1));
            let d2 = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2);
            let score = |s: &[(f64, f64); 2]| {
                let m = mid(s);
                let far = placed
                    .iter()
                    .map(|&p| d2(m, p))
                    .fold(f64::INFINITY, f64::min)
                    .min(4.0);
                (far, -d2(m, centre))
            };
            if let Some(best) = segments.iter().max_by(|p, q| {
                let (a, b) = (score(p), score(q));
                a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1))
            }) {
                let at = mid(best);
                placed.push(at);
                chart.draw_series(std::iter::once(Text::new(
                    format!("{} lx", plain(level)),
                    page.at(at),
                    text(FONT - 4)
                        .color(&ink)
                        .pos(Pos::new(HPos::Center, VPos::Bottom)),
                )))?;
            }
        }
        Ok(())
    }

    /// Writes each cell's value in its middle, in black over light colours and white
    /// over dark ones (only called when the cells have room for it).
    fn draw_cell_values<DB: DrawingBackend>(
        &self,
        chart: &mut PlanChart<'_, DB>,
        scale: &ColourScale,
        page: PlanPage,
    ) -> Result<(), ChartError>
    where
        DB::ErrorType: 'static,
    {
        let (cu, cv) = page.cell;
        chart.draw_series(self.map.cells.iter().flatten().map(|cell| {
            let (c, r) = (cell.index.0 as f64, cell.index.1 as f64);
            let e = cell.estimate.mean;
            let ink: &'static RGBColor = if scale.fraction(e) > 0.55 {
                &BLACK
            } else {
                &WHITE
            };
            Text::new(
                three_digits(e),
                ((c + 0.5) * cu, page.y((r + 0.5) * cv)),
                text(FONT - 4)
                    .color(ink)
                    .pos(Pos::new(HPos::Center, VPos::Center)),
            )
        }))?;
        Ok(())
    }
}

/// The chart a plan draws on: metres along the grid's axes.
type PlanChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Where the grid lands on the plan: a cell's size in metres, the grid's height, and
/// whether rows run down the page ([`MapPlan::from_above`]).
#[derive(Debug, Clone, Copy)]
struct PlanPage {
    /// A cell's sides along u and v, m.
    cell: (f64, f64),
    /// The grid's extent along v, m.
    height: f64,
    /// Whether rows run down the page.
    flip: bool,
}

impl PlanPage {
    /// The chart's y of the grid coordinate `t` (m along v), which is also its inverse.
    fn y(self, t: f64) -> f64 {
        if self.flip { self.height - t } else { t }
    }

    /// The chart's point of a point in cells (a cell's centre at (c + ½, r + ½)).
    fn at(self, p: (f64, f64)) -> (f64, f64) {
        (p.0 * self.cell.0, self.y(p.1 * self.cell.1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isolines_cross_where_the_values_do() {
        // A ramp along columns: 0, 10, 20 in every row; the 15 lx line runs straight up
        // halfway between the centres of columns 1 and 2 (x = 2).
        let values: Vec<Option<f64>> = (0..9).map(|i| Some((i % 3) as f64 * 10.0)).collect();
        let segments = isolines(&values, 3, 3, 15.0);
        assert_eq!(segments.len(), 2);
        for [a, b] in segments {
            assert!((a.0 - 2.0).abs() < 1e-12 && (b.0 - 2.0).abs() < 1e-12);
            assert!((a.1 - b.1).abs() == 1.0);
        }
        // A hole stops the line: no square touching it is cut.
        let mut holed = values.clone();
        holed[4] = None;
        assert!(isolines(&holed, 3, 3, 15.0).len() < 2);
        // Nothing crosses a level outside the data.
        assert!(isolines(&values, 3, 3, 25.0).is_empty());
    }

    #[test]
    fn orientations_read_in_world_terms() {
        assert_eq!(axis_name(Vec3::NEG_Z).1, Some((2, -1.0)));
        assert!(seen_from(Vec3::Z).starts_with("seen from +z"));
        assert!(seen_from(Vec3::NEG_Y).starts_with("seen from −y"));
    }
}
