//! Plots of what a search visited (the thesis' figures 5.6, 5.8 and 5.11) and of how it
//! converged, from plain data the report fills:
//!
//! - a placement as a **plan** in world metres: the room's outline, the target's
//!   footprint, the placement rectangle, every evaluated cell in the colour of its mean,
//!   the start, the path of improvements and the ISOC;
//! - a sun direction on a **sun chart**: elevation against azimuth with the compass
//!   directions, the same marks;
//! - a colour value as the illuminance against V with its intervals;
//! - [`ConvergencePlot`]: the configuration the search stood on, its mean and interval,
//!   against the photons spent.
//!
//! Colours are viridis over the data's own range ([`crate::ColourScale`]); every plot
//! draws as SVG (for report.html) or as a picture (`search.png`) by the same code.

use crate::chart::{ChartError, colour_bar, rgb, text, to_image, to_svg};
use crate::colour_map::ColourScale;
use image::RgbImage;
use invlight_stats::significant;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Size of every search plot, pixels.
pub const PLOT_SIZE: (u32, u32) = (960, 720);

/// A world axis of a plan: which one and which way it runs on the page.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanAxis {
    /// Its name, `x`, `y` or `z`.
    pub name: String,
    /// +1 when plan coordinates are the world coordinate, −1 when they are its negative
    /// (the page's up is the world's −z when a Y-up floor is seen from above).
    pub sign: f64,
}

/// What a plan shows besides the visits, in plan coordinates (the two [`PlanAxis`]
/// values, metres).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanFrame {
    /// The page's horizontal and vertical axes.
    pub axes: [PlanAxis; 2],
    /// The scene's bounding box seen along the plane's normal: the room's outline.
    pub room: Option<[[f64; 2]; 2]>,
    /// The objective surface's triangles seen along the normal.
    pub target: Vec<[[f64; 2]; 3]>,
    /// Where the placed thing's anchor may go: the placement rectangle moved by the
    /// anchor's offset from P.
    pub range: [[f64; 2]; 4],
    /// The placement rectangle itself, when it differs from `range`.
    pub rectangle: Option<[[f64; 2]; 4]>,
    /// What moves, for the key ("Cone centre").
    pub moved: String,
    /// The objective surface's name, for the key.
    pub target_name: String,
}

/// What the coordinates of the points are.
#[derive(Debug, Clone, PartialEq)]
pub enum PlotKind {
    /// A plan: points are the anchor's plan coordinates, m.
    Plan(Box<PlanFrame>),
    /// A sun chart: points are (azimuth clockwise from north, elevation), degrees.
    Sky {
        /// Which scene direction is north, for the axis ("−z").
        north: String,
    },
    /// A scalar variable — a colour's value, a dimming level, a hole's scale, a turn:
    /// `at[0]` in [`min`, `max`].
    Value {
        /// Smallest value allowed.
        min: f64,
        /// Largest value allowed.
        max: f64,
        /// What the value is, for its axis (`HSV value V`, `level`, `turn (°)`).
        label: String,
    },
}

/// The role of a point in the search.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// The initial configuration.
    Start,
    /// An improvement the search moved to.
    Improvement,
    /// Evaluated, not moved to.
    Visited,
    /// Evaluated and invalid (above the cap).
    Invalid,
}

/// One evaluated cell.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotPoint {
    /// Where it is, in the [`PlotKind`]'s coordinates.
    pub at: [f64; 2],
    /// The cell's outline in the same coordinates (empty for a colour value).
    pub cell: Vec<[f64; 2]>,
    /// Mean, in the plot's unit.
    pub mean: f64,
    /// Lower end of its interval.
    pub low: f64,
    /// Upper end.
    pub high: f64,
    /// Its role.
    pub mark: Mark,
    /// Whether it is in the final ISOC.
    pub isoc: bool,
}

/// A search to plot: the points in the order they were evaluated.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchPlot {
    /// The title above the plot.
    pub title: String,
    /// What the coordinates are.
    pub kind: PlotKind,
    /// The unit of the means (`lx`).
    pub unit: String,
    /// What the means are, for the value axis (`mean illuminance`, `lamp power`).
    pub quantity: String,
    /// The objective's cap, drawn as a line on a value plot.
    pub cap: Option<f64>,
    /// Evaluations in order.
    pub points: Vec<PlotPoint>,
}

/// Where data lands on a drawn plot: the data ranges and the pixel range they span, as
/// `plotters` maps them (linear, y growing upwards).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Data range of the horizontal axis.
    pub x: (f64, f64),
    /// Data range of the vertical axis.
    pub y: (f64, f64),
    /// Pixel columns of x.0 and x.1.
    pub columns: (i32, i32),
    /// Pixel rows of y.0 (bottom) and y.1 (top).
    pub rows: (i32, i32),
}

impl Frame {
    fn of(
        chart: &ChartContext<'_, impl DrawingBackend, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        x: (f64, f64),
        y: (f64, f64),
    ) -> Frame {
        let (columns, rows) = chart.plotting_area().get_pixel_range();
        Frame {
            x,
            y,
            columns: (columns.start, columns.end - 1),
            rows: (rows.end - 1, rows.start),
        }
    }

    /// The pixel of the data point (`x`, `y`).
    pub fn pixel(&self, x: f64, y: f64) -> (i32, i32) {
        let fx = (x - self.x.0) / (self.x.1 - self.x.0);
        let fy = (y - self.y.0) / (self.y.1 - self.y.0);
        (
            self.columns.0 + (fx * (self.columns.1 - self.columns.0) as f64).round() as i32,
            self.rows.0 + (fy * (self.rows.1 - self.rows.0) as f64).round() as i32,
        )
    }
}

const ISOC: RGBColor = RGBColor(214, 39, 40);
const INVALID: RGBColor = RGBColor(170, 170, 170);
const OUTLINE: RGBColor = RGBColor(90, 90, 90);
const FONT: u32 = 18;

/// A plan coordinate as an axis label: metres with at most two decimals, no trailing
/// zeros.
fn metres(v: f64) -> String {
    let s = format!("{:.2}", v);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain, "Another
/// efficient algorithm for convex hulls in two dimensions", IPL 9(5), 1979).
fn convex_hull(mut points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    points.retain(|p| p[0].is_finite() && p[1].is_finite());
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * points.len());
    for pass in 0..2 {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for &p in ordered {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// Draws the axes of a plot of values against a quantity: light grid lines, the
/// labels' sizes of every plot, values to significant digits.
fn value_axes<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    x_desc: &str,
    y_desc: &str,
) -> Result<(), ChartError>
where
    DB::ErrorType: 'static,
{
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .y_label_formatter(&|v| significant(*v))
        .label_style(text(FONT - 2))
        .axis_desc_style(text(FONT))
        .light_line_style(WHITE)
        .bold_line_style(RGBColor(225, 225, 225))
        .draw()?;
    Ok(())
}

/// `lo..hi` widened by `pad` of its length on each side: a unit around `lo` when the
/// range is a point, and 0..1 when it has no finite end (no values, or only unbounded
/// intervals), since plotters loops forever looking for key points on an infinite axis.
fn padded(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    if !lo.is_finite() || !hi.is_finite() {
        return match (lo.is_finite(), hi.is_finite()) {
            (true, false) => (lo - 0.5, lo + 0.5),
            (false, true) => (hi - 0.5, hi + 0.5),
            _ => (0.0, 1.0),
        };
    }
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return (lo - 0.5, lo + 0.5);
    }
    let d = (hi - lo) * pad;
    (lo - d, hi + d)
}

impl SearchPlot {
    /// The colour scale of the means of the valid points.
    pub fn scale(&self) -> ColourScale {
        ColourScale::of(
            self.points
                .iter()
                .filter(|p| p.mark != Mark::Invalid)
                .map(|p| p.mean),
        )
    }

    /// The plot as an SVG document of [`PLOT_SIZE`].
    pub fn svg(&self) -> Result<String, ChartError> {
        to_svg(PLOT_SIZE, |root| self.draw(root).map(|_| ()))
    }

    /// The plot as a picture of [`PLOT_SIZE`], with where its data lands.
    pub fn image(&self) -> Result<(RgbImage, Frame), ChartError> {
        let mut frame = None;
        let image = to_image(PLOT_SIZE, |root| {
            frame = Some(self.draw(root)?);
            Ok(())
        })?;
        Ok((image, frame.expect("drawing sets the frame")))
    }

    /// Draws the plot and writes it as a PNG or JPEG.
    pub fn write(&self, path: &std::path::Path) -> Result<(), crate::SaveError> {
        let (image, _) = self.image().map_err(crate::SaveError::Chart)?;
        crate::save_picture(&image, path)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<Frame, ChartError>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (body, key) = root.split_vertically(PLOT_SIZE.1 - 2 * FONT);
        let (head, body) = body.split_vertically(2 * FONT);
        head.draw(&Text::new(self.title.clone(), (12, 8), text(FONT + 2)))?;
        let (main, bar) = body.split_horizontally(PLOT_SIZE.0 - 110);
        let scale = self.scale();
        colour_bar(&bar.margin(40, 50, 0, 0), &scale, &self.unit, FONT - 2)?;
        let frame = match &self.kind {
            PlotKind::Plan(plan) => self.plan(&main, plan, &scale)?,
            PlotKind::Sky { north } => self.sky(&main, north, &scale)?,
            PlotKind::Value { min, max, label } => {
                self.value(&main, (*min, *max), label, &scale)?
            }
        };
        self.key(&key)?;
        Ok(frame)
    }

    fn marks<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        at: impl Fn(&PlotPoint) -> (f64, f64),
    ) -> Result<(), ChartError>
    where
        DB::ErrorType: 'static,
    {
        let path: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter(|p| matches!(p.mark, Mark::Start | Mark::Improvement))
            .map(&at)
            .collect();
        chart.draw_series(std::iter::once(PathElement::new(
            path.clone(),
            BLACK.stroke_width(2),
        )))?;
        chart.draw_series(
            path.iter()
                .skip(1)
                .map(|&p| Circle::new(p, 3, BLACK.filled())),
        )?;
        chart.draw_series(
            self.points
                .iter()
                .filter(|p| p.isoc)
                .map(|p| Circle::new(at(p), 7, ISOC.stroke_width(2))),
        )?;
        chart.draw_series(
            self.points
                .iter()
                .filter(|p| p.mark == Mark::Start)
                .map(|p| {
                    let (x, y) = at(p);
                    EmptyElement::at((x, y))
                        + Rectangle::new([(-7, -7), (7, 7)], BLACK.stroke_width(2))
                }),
        )?;
        Ok(())
    }

    fn cells<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        scale: &ColourScale,
    ) -> Result<(), ChartError>
    where
        DB::ErrorType: 'static,
    {
        chart.draw_series(self.points.iter().filter(|p| p.cell.len() >= 3).map(|p| {
            let colour = match p.mark {
                Mark::Invalid => INVALID,
                _ => rgb(scale.colour(p.mean)),
            };
            Polygon::new(
                p.cell.iter().map(|c| (c[0], c[1])).collect::<Vec<_>>(),
                colour.filled(),
            )
        }))?;
        // A dot as well, so that cells smaller than a few pixels still show.
        chart.draw_series(self.points.iter().map(|p| {
            let colour = match p.mark {
                Mark::Invalid => INVALID,
                _ => rgb(scale.colour(p.mean)),
            };
            Circle::new((p.at[0], p.at[1]), 3, colour.filled())
        }))?;
        Ok(())
    }

    fn plan<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        plan: &PlanFrame,
        scale: &ColourScale,
    ) -> Result<Frame, ChartError>
    where
        DB::ErrorType: 'static,
    {
        // The extent: the room, else the range and the target, with a margin.
        let mut pts: Vec<[f64; 2]> = plan.range.to_vec();
        if let Some(r) = plan.room {
            pts.extend(r);
        } else {
            pts.extend(plan.target.iter().flatten());
        }
        pts.extend(plan.rectangle.iter().flatten());
        let lo = |k: usize| pts.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = |k: usize| pts.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
        let (mut x, mut y) = (padded(lo(0), hi(0), 0.04), padded(lo(1), hi(1), 0.04));
        // Equal metres per pixel on both axes: widen the shorter range about its centre.
        let (label_x, label_y, margin) = (2 * FONT + 12, 4 * FONT, 12);
        let (w, h) = area.dim_in_pixel();
        let pw = (w - label_y - 2 * margin) as f64;
        let ph = (h - label_x - 2 * margin) as f64;
        let k = ((x.1 - x.0) / pw).max((y.1 - y.0) / ph);
        let (cx, cy) = (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1));
        x = (cx - 0.5 * k * pw, cx + 0.5 * k * pw);
        y = (cy - 0.5 * k * ph, cy + 0.5 * k * ph);
        let mut chart = ChartBuilder::on(area)
            .margin(margin)
            .x_label_area_size(label_x)
            .y_label_area_size(label_y)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
        let [ax, ay] = &plan.axes;
        let (sx, sy) = (ax.sign, ay.sign);
        let fx = move |v: &f64| metres(sx * v);
        let fy = move |v: &f64| metres(sy * v);
        chart
            .configure_mesh()
            .x_desc(format!("{} (m)", ax.name))
            .y_desc(format!("{} (m)", ay.name))
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style(text(FONT - 2))
            .axis_desc_style(text(FONT))
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(225, 225, 225))
            .draw()?;
        if let Some([a, b]) = plan.room {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(a[0], a[1]), (b[0], b[1])],
                OUTLINE.stroke_width(2),
            )))?;
        }
        chart.draw_series(plan.target.iter().map(|t| {
            Polygon::new(
                t.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>(),
                RGBColor(255, 200, 120).mix(0.5).filled(),
            )
        }))?;
        let closed = |q: &[[f64; 2]; 4]| {
            let mut v: Vec<(f64, f64)> = q.iter().map(|p| (p[0], p[1])).collect();
            v.push(v[0]);
            v
        };
        if let Some(r) = &plan.rectangle {
            chart.draw_series(std::iter::once(PathElement::new(
                closed(r),
                OUTLINE.stroke_width(1),
            )))?;
        }
        self.cells(&mut chart, scale)?;
        // The target's outline over the cells, which may cover its fill.
        let mut hull = convex_hull(plan.target.iter().flatten().copied().collect());
        if hull.len() >= 3 {
            hull.push(hull[0]);
            chart.draw_series(std::iter::once(PathElement::new(
                hull.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>(),
                RGBColor(230, 120, 0).stroke_width(2),
            )))?;
        }
        chart.draw_series(std::iter::once(PathElement::new(
            closed(&plan.range),
            BLACK.stroke_width(2),
        )))?;
        self.marks(&mut chart, |p| (p.at[0], p.at[1]))?;
        Ok(Frame::of(&chart, x, y))
    }

    fn sky<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        north: &str,
        scale: &ColourScale,
    ) -> Result<Frame, ChartError>
    where
        DB::ErrorType: 'static,
    {
        let (x, y) = ((0.0, 360.0), (0.0, 90.0));
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(2 * FONT + 12)
            .y_label_area_size(4 * FONT)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(0)
            .y_labels(7)
            .y_label_formatter(&|v: &f64| format!("{}°", v.round()))
            .x_desc(format!(
                "azimuth, clockwise from north (the scene's {north})"
            ))
            .y_desc("elevation above the horizon")
            .label_style(text(FONT - 2))
            .axis_desc_style(text(FONT))
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(225, 225, 225))
            .draw()?;
        // The compass every 45°, its gridlines under the cells.
        let names = ["N", "NE", "E", "SE", "S", "SW", "W", "NW", "N"];
        let (bx, by) = area.get_base_pixel();
        let style = text(FONT - 2).pos(Pos::new(HPos::Center, VPos::Top));
        for (i, name) in names.iter().enumerate() {
            let az = 45.0 * i as f64;
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(az, 0.0), (az, 90.0)],
                RGBColor(225, 225, 225).stroke_width(1),
            )))?;
            let (px, py) = chart.backend_coord(&(az, 0.0));
            area.draw(&Text::new(
                format!("{name} {az}°"),
                (px - bx, py - by + 6),
                style.clone(),
            ))?;
        }
        self.cells(&mut chart, scale)?;
        self.marks(&mut chart, |p| (p.at[0], p.at[1]))?;
        Ok(Frame::of(&chart, x, y))
    }

    fn value<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        (min, max): (f64, f64),
        label: &str,
        scale: &ColourScale,
    ) -> Result<Frame, ChartError>
    where
        DB::ErrorType: 'static,
    {
        let x = padded(min, max, 0.02);
        let lows = self.points.iter().map(|p| p.low);
        let highs = self.points.iter().map(|p| p.high);
        let lo = lows.filter(|v| v.is_finite()).fold(f64::INFINITY, f64::min);
        let hi = highs
            .filter(|v| v.is_finite())
            .fold(f64::NEG_INFINITY, f64::max);
        let (lo, hi) = match self.cap {
            Some(c) => (lo.min(c), hi.max(c)),
            None => (lo, hi),
        };
        let y = padded(lo, hi, 0.05);
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(2 * FONT + 12)
            .y_label_area_size(5 * FONT)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
        let unit = match self.unit.as_str() {
            "" | "U0" | "UGR" => String::new(),
            u => format!(" ({u})"),
        };
        value_axes(&mut chart, label, &format!("{}{unit}", self.quantity))?;
        for p in &self.points {
            let colour = match p.mark {
                Mark::Invalid => INVALID,
                _ => rgb(scale.colour(p.mean)),
            };
            let v = p.at[0];
            chart.draw_series(std::iter::once(ErrorBar::new_vertical(
                v,
                p.low,
                p.mean,
                p.high,
                colour.stroke_width(2),
                8,
            )))?;
            chart.draw_series(std::iter::once(Circle::new(
                (v, p.mean),
                4,
                colour.filled(),
            )))?;
        }
        if let Some(cap) = self.cap {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(x.0, cap), (x.1, cap)],
                ISOC.stroke_width(1),
            )))?;
            chart.draw_series(std::iter::once(Text::new(
                format!("cap {} {}", significant(cap), self.unit),
                (x.0 + 0.01 * (x.1 - x.0), cap),
                text(FONT - 2)
                    .color(&ISOC)
                    .pos(Pos::new(HPos::Left, VPos::Bottom)),
            )))?;
        }
        self.marks(&mut chart, |p| (p.at[0], p.mean))?;
        Ok(Frame::of(&chart, x, y))
    }

    /// The key under the plot.
    fn key<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), ChartError>
    where
        DB::ErrorType: 'static,
    {
        let y = FONT as i32;
        let style = text(FONT - 2);
        let mut x = 24;
        let mut item = |shape: &dyn Fn(i32) -> Result<(), ChartError>, label: &str| {
            shape(x)?;
            area.draw(&Text::new(
                label.to_string(),
                (x + 18, y - 8),
                style.clone(),
            ))?;
            let (w, _) = area.estimate_text_size(label, &style)?;
            x += w as i32 + 36;
            Ok::<(), ChartError>(())
        };
        item(
            &|x| {
                area.draw(&Rectangle::new(
                    [(x - 6, y - 6), (x + 6, y + 6)],
                    BLACK.stroke_width(2),
                ))?;
                Ok(())
            },
            "start",
        )?;
        item(
            &|x| {
                area.draw(&PathElement::new(
                    vec![(x - 10, y), (x + 8, y)],
                    BLACK.stroke_width(2),
                ))?;
                area.draw(&Circle::new((x + 8, y), 3, BLACK.filled()))?;
                Ok(())
            },
            "improvements",
        )?;
        item(
            &|x| {
                area.draw(&Circle::new((x, y), 7, ISOC.stroke_width(2)))?;
                Ok(())
            },
            "ISOC",
        )?;
        if self.points.iter().any(|p| p.mark == Mark::Invalid) {
            item(
                &|x| {
                    area.draw(&Rectangle::new(
                        [(x - 6, y - 6), (x + 6, y + 6)],
                        INVALID.filled(),
                    ))?;
                    Ok(())
                },
                if self.cap.is_some() {
                    "over the cap or infeasible"
                } else {
                    "infeasible"
                },
            )?;
        }
        if let PlotKind::Plan(plan) = &self.kind {
            if !plan.target.is_empty() {
                let label = format!("{} (objective, as authored)", plan.target_name);
                item(
                    &|x| {
                        let patch = RGBColor(255, 200, 120).mix(0.5).filled();
                        area.draw(&Rectangle::new([(x - 6, y - 6), (x + 6, y + 6)], patch))?;
                        Ok(())
                    },
                    &label,
                )?;
            }
            let label = format!("where {} may go", plan.moved);
            item(
                &|x| {
                    area.draw(&PathElement::new(
                        vec![(x - 10, y), (x + 8, y)],
                        BLACK.stroke_width(2),
                    ))?;
                    Ok(())
                },
                &label,
            )?;
        }
        Ok(())
    }
}

/// One step of a search's convergence: the configuration it stood on after `photons`
/// photons in all, with its estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvergencePoint {
    /// Photons traced so far, every evaluation's counted.
    pub photons: u64,
    /// The mean of the configuration the search stood on.
    pub mean: f64,
    /// Lower end of its interval.
    pub low: f64,
    /// Upper end.
    pub high: f64,
}

/// How the search converged: its standing configuration's mean and interval against
/// the photons spent.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergencePlot {
    /// The title above the plot.
    pub title: String,
    /// The unit of the means.
    pub unit: String,
    /// Steps in order of photons.
    pub points: Vec<ConvergencePoint>,
}

impl ConvergencePlot {
    /// The plot as an SVG document of [`PLOT_SIZE`] wide and 3/5 as tall.
    pub fn svg(&self) -> Result<String, ChartError> {
        to_svg((PLOT_SIZE.0, PLOT_SIZE.1 * 3 / 5), |root| self.draw(root))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), ChartError>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let last = self.points.last().map_or(1, |p| p.photons.max(1));
        let x = (0.0, last as f64 / 1e6);
        let lo = self
            .points
            .iter()
            .map(|p| p.low)
            .fold(f64::INFINITY, f64::min);
        let hi = self
            .points
            .iter()
            .map(|p| p.high)
            .fold(f64::NEG_INFINITY, f64::max);
        let y = padded(lo, hi, 0.05);
        let mut chart = ChartBuilder::on(root)
            .margin(12)
            .margin_right(30)
            .caption(&self.title, text(FONT + 2))
            .x_label_area_size(2 * FONT + 12)
            .y_label_area_size(5 * FONT)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
        value_axes(
            &mut chart,
            "photons traced (millions)",
            &format!("standing configuration ({})", self.unit),
        )?;
        // Steps: each estimate holds until the next one replaces it.
        let mut band_top = Vec::new();
        let mut band_bottom = Vec::new();
        let mut line = Vec::new();
        for (i, p) in self.points.iter().enumerate() {
            let x0 = p.photons as f64 / 1e6;
            let x1 = self
                .points
                .get(i + 1)
                .map_or(x.1, |q| q.photons as f64 / 1e6);
            band_top.extend([(x0, p.high), (x1, p.high)]);
            band_bottom.extend([(x0, p.low), (x1, p.low)]);
            line.extend([(x0, p.mean), (x1, p.mean)]);
        }
        band_bottom.reverse();
        band_top.extend(band_bottom);
        let band = rgb(crate::colour_map::viridis(0.45));
        chart.draw_series(std::iter::once(Polygon::new(
            band_top,
            band.mix(0.3).filled(),
        )))?;
        chart.draw_series(std::iter::once(PathElement::new(
            line,
            BLACK.stroke_width(2),
        )))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_stay_finite_without_finite_values() {
        assert_eq!(padded(f64::INFINITY, f64::NEG_INFINITY, 0.05), (0.0, 1.0));
        assert_eq!(padded(2.0, f64::INFINITY, 0.05), (1.5, 2.5));
        assert_eq!(padded(f64::NEG_INFINITY, 2.0, 0.05), (1.5, 2.5));
        assert_eq!(padded(3.0, 3.0, 0.05), (2.5, 3.5));
        let empty = ConvergencePlot {
            title: "no standing configuration".into(),
            unit: "lm".into(),
            points: Vec::new(),
        };
        assert!(empty.svg().unwrap().contains("<svg"));
    }

    #[test]
    fn the_hull_keeps_the_outer_points_in_order() {
        let square = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.5, 0.5],
            [1.0, 0.0],
        ];
        let hull = convex_hull(square);
        assert_eq!(hull, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        assert_eq!(convex_hull(vec![[2.0, 2.0]]).len(), 1);
    }
}
