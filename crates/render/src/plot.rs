//! Plots of what a search visited (the thesis' figures 5.6, 5.8 and 5.11), from plain
//! data that the solver or the command line fills: for a position on a placement
//! rectangle, the rectangle with every evaluated cell in the colour of its mean
//! illuminance; for a sun direction, the same on a (φ, θ) chart; for a colour value, the
//! illuminance against V with its intervals. The start, the path of improvements and the
//! ISOC are marked on all three.

use crate::draw::{self, fill_rect, line, ring, stroke_rect, text};
use image::RgbImage;

/// Size of every search plot, pixels.
pub const PLOT_SIZE: (u32, u32) = (800, 600);

/// What the coordinates of the points are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlotKind {
    /// A position on a placement rectangle: `coords` = (u, v) in metres from its vertex A
    /// along AB and AD; the rectangle is `width` × `height`.
    Position {
        /// |AB|, m.
        width: f64,
        /// |AD|, m.
        height: f64,
    },
    /// A direction: `coords` = (θ, φ) in degrees, θ from the zenith, φ the azimuth.
    Direction,
    /// A colour value: `coords[0]` = V, between `min` and `max`.
    Value {
        /// Smallest V allowed.
        min: f64,
        /// Largest V allowed.
        max: f64,
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

/// One evaluated configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotPoint {
    /// Coordinates as [`PlotKind`] says.
    pub coords: [f64; 2],
    /// Mean illuminance, lx.
    pub mean: f64,
    /// Lower end of its interval, lx.
    pub low: f64,
    /// Upper end of its interval, lx.
    pub high: f64,
    /// Its role.
    pub mark: Mark,
    /// Whether it is in the final ISOC.
    pub isoc: bool,
}

/// A search to plot: the points in the order they were evaluated.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchPlot {
    /// What the coordinates are.
    pub kind: PlotKind,
    /// Size of a cell in coordinate units (the tabu cells of thesis §4.8), drawn as the
    /// block a point colours; for `Value` only `cell[0]` is used (as the dot width).
    pub cell: [f64; 2],
    /// Evaluations in order.
    pub points: Vec<PlotPoint>,
}

const BACKGROUND: [u8; 3] = [16, 16, 16];
const AXIS: [u8; 3] = [200, 200, 200];
const WHITE: [u8; 3] = [255, 255, 255];
const ISOC: [u8; 3] = [255, 0, 255];
const INVALID: [u8; 3] = [90, 90, 90];

/// Maps coordinates to pixels in a plot frame.
struct Frame {
    x: (f64, f64),
    y: (f64, f64),
    left: i32,
    top: i32,
    w: u32,
    h: u32,
}

impl Frame {
    fn px(&self, cx: f64, cy: f64) -> (i32, i32) {
        let fx = (cx - self.x.0) / (self.x.1 - self.x.0);
        let fy = (cy - self.y.0) / (self.y.1 - self.y.0);
        (
            self.left + (fx * self.w as f64).round() as i32,
            self.top + self.h as i32 - (fy * self.h as f64).round() as i32,
        )
    }

    /// Axes with ticks and labels, and `x_name`/`y_name` at their ends.
    fn axes(&self, img: &mut RgbImage, x_name: &str, y_name: &str) {
        stroke_rect(img, self.left, self.top, self.w, self.h + 1, AXIS);
        let xt = draw::ticks(self.x.0, self.x.1, 6);
        let xs = step(&xt);
        for v in xt {
            let (x, y) = self.px(v, self.y.0);
            fill_rect(img, x, y, 1, 5, AXIS);
            let l = draw::label(v, xs);
            text(
                img,
                x - draw::text_width(&l, 1) as i32 / 2,
                y + 8,
                &l,
                1,
                AXIS,
            );
        }
        let yt = draw::ticks(self.y.0, self.y.1, 6);
        let ys = step(&yt);
        for v in yt {
            let (x, y) = self.px(self.x.0, v);
            fill_rect(img, x - 5, y, 5, 1, AXIS);
            let l = draw::label(v, ys);
            text(
                img,
                x - 8 - draw::text_width(&l, 1) as i32,
                y - 3,
                &l,
                1,
                AXIS,
            );
        }
        let (x, y) = self.px(self.x.1, self.y.0);
        text(
            img,
            x - draw::text_width(x_name, 1) as i32,
            y + 22,
            x_name,
            1,
            WHITE,
        );
        text(img, self.left - 50, self.top - 14, y_name, 1, WHITE);
    }
}

fn step(ticks: &[f64]) -> f64 {
    if ticks.len() > 1 {
        ticks[1] - ticks[0]
    } else {
        1.0
    }
}

/// Draws the plot on a [`PLOT_SIZE`] image.
pub fn draw_search_plot(plot: &SearchPlot) -> RgbImage {
    let (w, h) = PLOT_SIZE;
    let mut img = RgbImage::from_pixel(w, h, image::Rgb(BACKGROUND));
    let legend = draw::legend_width(1);
    let (left, top, right, bottom) = (70i32, 30i32, 20 + legend as i32, 50i32);
    let area_w = (w as i32 - left - right) as u32;
    let area_h = (h as i32 - top - bottom) as u32;
    let max_mean = plot
        .points
        .iter()
        .map(|p| p.mean)
        .filter(|m| m.is_finite())
        .fold(0.0f64, f64::max);
    let scale_max = draw::nice_ceil(max_mean);
    match plot.kind {
        PlotKind::Position { width, height } => {
            // Keep the rectangle's proportions.
            let (width, height) = (width.max(1e-9), height.max(1e-9));
            let k = (area_w as f64 / width).min(area_h as f64 / height);
            let frame = Frame {
                x: (0.0, width),
                y: (0.0, height),
                left,
                top,
                w: (width * k).round().max(1.0) as u32,
                h: (height * k).round().max(1.0) as u32,
            };
            cells(&mut img, &frame, plot, scale_max);
            frame.axes(&mut img, "u m", "v m");
            marks(&mut img, &frame, plot, |p| (p.coords[0], p.coords[1]));
        }
        PlotKind::Direction => {
            let theta_max = if plot.points.iter().any(|p| p.coords[0] > 90.0) {
                180.0
            } else {
                90.0
            };
            let frame = Frame {
                x: (0.0, 360.0),
                y: (0.0, theta_max),
                left,
                top,
                w: area_w,
                h: area_h,
            };
            // Cells are drawn with φ across and θ up.
            let swapped = SearchPlot {
                kind: plot.kind,
                cell: [plot.cell[1], plot.cell[0]],
                points: plot
                    .points
                    .iter()
                    .map(|p| PlotPoint {
                        coords: [p.coords[1], p.coords[0]],
                        ..*p
                    })
                    .collect(),
            };
            cells(&mut img, &frame, &swapped, scale_max);
            frame.axes(&mut img, "φ °", "θ °");
            marks(&mut img, &frame, plot, |p| (p.coords[1], p.coords[0]));
        }
        PlotKind::Value { min, max } => {
            let high = plot
                .points
                .iter()
                .map(|p| p.high)
                .filter(|v| v.is_finite())
                .fold(0.0f64, f64::max);
            let frame = Frame {
                x: (min, if max > min { max } else { min + 1.0 }),
                y: (0.0, draw::nice_ceil(high)),
                left,
                top,
                w: area_w,
                h: area_h,
            };
            frame.axes(&mut img, "V", "E lx");
            for p in &plot.points {
                let (x, y0) = frame.px(p.coords[0], p.low.max(0.0));
                let (_, y1) = frame.px(p.coords[0], p.high.max(0.0));
                let colour = if p.mark == Mark::Invalid {
                    INVALID
                } else {
                    draw::scale_colour((p.mean / scale_max) as f32)
                };
                line(&mut img, (x, y0), (x, y1), 1, colour);
                fill_rect(&mut img, x - 3, y0, 7, 1, colour);
                fill_rect(&mut img, x - 3, y1, 7, 1, colour);
                let (_, ym) = frame.px(p.coords[0], p.mean.max(0.0));
                draw::disc(&mut img, x, ym, 3, colour);
            }
            marks(&mut img, &frame, plot, |p| (p.coords[0], p.mean.max(0.0)));
        }
    }
    draw::legend(
        &mut img,
        w as i32 - legend as i32,
        top,
        area_h,
        scale_max,
        "lx",
        1,
    );
    // Key of the marks, under the plot.
    let y = h as i32 - 16;
    ring(&mut img, 80, y + 3, 6, 2, WHITE);
    text(&mut img, 92, y, "start", 1, WHITE);
    line(&mut img, (150, y + 3), (175, y + 3), 2, WHITE);
    text(&mut img, 182, y, "improvements", 1, WHITE);
    ring(&mut img, 275, y + 3, 6, 2, ISOC);
    text(&mut img, 287, y, "ISOC", 1, WHITE);
    img
}

/// Every evaluated cell as a block in the colour of its mean (invalid ones grey).
fn cells(img: &mut RgbImage, frame: &Frame, plot: &SearchPlot, scale_max: f64) {
    for p in &plot.points {
        let [cx, cy] = p.coords;
        let (x0, y0) = frame.px(cx - plot.cell[0] * 0.5, cy + plot.cell[1] * 0.5);
        let (x1, y1) = frame.px(cx + plot.cell[0] * 0.5, cy - plot.cell[1] * 0.5);
        let colour = if p.mark == Mark::Invalid {
            INVALID
        } else {
            draw::scale_colour((p.mean / scale_max) as f32)
        };
        fill_rect(
            img,
            x0,
            y0,
            (x1 - x0).max(3) as u32,
            (y1 - y0).max(3) as u32,
            colour,
        );
    }
}

/// The path of improvements from the start, the start and the ISOC members.
fn marks(
    img: &mut RgbImage,
    frame: &Frame,
    plot: &SearchPlot,
    at: impl Fn(&PlotPoint) -> (f64, f64),
) {
    let path: Vec<(i32, i32)> = plot
        .points
        .iter()
        .filter(|p| matches!(p.mark, Mark::Start | Mark::Improvement))
        .map(|p| {
            let (x, y) = at(p);
            frame.px(x, y)
        })
        .collect();
    for pair in path.windows(2) {
        line(img, pair[0], pair[1], 2, WHITE);
    }
    for p in &plot.points {
        let (x, y) = at(p);
        let (x, y) = frame.px(x, y);
        if p.mark == Mark::Start {
            ring(img, x, y, 8, 2, WHITE);
        }
        if p.isoc {
            ring(img, x, y, 6, 2, ISOC);
        }
    }
}

impl SearchPlot {
    /// Draws the plot and writes it as a PNG.
    pub fn write(&self, path: &std::path::Path) -> Result<(), crate::SaveError> {
        crate::save_picture(&draw_search_plot(self), path)
    }
}
