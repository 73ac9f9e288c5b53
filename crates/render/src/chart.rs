//! What every chart shares: the embedded font, the two outputs (an SVG document, crisp
//! in print and embedded as it is in report.html; an 8-bit picture for the PNG files)
//! drawn by the same code through `plotters`' backends, the colour bar, and the errors.
//!
//! The font is DejaVu Sans (Bitstream Vera licence, `fonts/LICENSE-DejaVu.txt`),
//! compiled in and registered with `plotters`' `ab_glyph` text renderer, so a picture
//! looks the same on every machine and needs no font installed; the SVG output names
//! the same family and lets the browser fall back to its sans-serif.

use crate::colour_map::{ColourScale, tick_label};
use image::RgbImage;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::fmt;
use std::sync::Once;

/// The font's family name as charts ask for it.
pub const FONT: &str = "DejaVu Sans";

static FONT_BYTES: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");

/// Registers the embedded font once, before the first text is laid out.
pub(crate) fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are the file compiled in above; a parse failure would be a broken
        // checkout, which the tests of every chart would show.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES);
    });
}

/// A chart that could not be drawn (a backend refused a primitive).
#[derive(Debug, Clone, PartialEq)]
pub struct ChartError(pub String);

impl fmt::Display for ChartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot draw the chart: {}", self.0)
    }
}

impl std::error::Error for ChartError {}

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for ChartError {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        ChartError(e.to_string())
    }
}

/// Text in the chart font at `size` pixels.
pub(crate) fn text(size: u32) -> TextStyle<'static> {
    (FONT, size as f64).into_font().color(&BLACK)
}

/// An sRGB colour as `plotters` takes it.
pub(crate) fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// Draws with `draw` on a `size` SVG document and returns its text.
pub fn to_svg<F>(size: (u32, u32), draw: F) -> Result<String, ChartError>
where
    F: FnOnce(&DrawingArea<SVGBackend, Shift>) -> Result<(), ChartError>,
{
    register_font();
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        draw(&root)?;
        root.present()?;
    }
    Ok(out)
}

/// Draws with `draw` on a `size` picture, white where nothing is drawn.
pub fn to_image<F>(size: (u32, u32), draw: F) -> Result<RgbImage, ChartError>
where
    F: FnOnce(&DrawingArea<BitMapBackend, Shift>) -> Result<(), ChartError>,
{
    let mut image = RgbImage::from_pixel(size.0, size.1, image::Rgb([255, 255, 255]));
    draw_on(&mut image, draw)?;
    Ok(image)
}

/// Draws with `draw` over an existing picture (a render gets its legend so).
pub fn draw_on<F>(image: &mut RgbImage, draw: F) -> Result<(), ChartError>
where
    F: FnOnce(&DrawingArea<BitMapBackend, Shift>) -> Result<(), ChartError>,
{
    register_font();
    let size = image.dimensions();
    let root = BitMapBackend::with_buffer(image.as_mut(), size).into_drawing_area();
    draw(&root)?;
    root.present()?;
    Ok(())
}

/// A vertical colour bar filling `area`: the scale from its bottom (`scale.min`) to its
/// top (`scale.max`), round ticks inside labelled on the right, `unit` above.
pub(crate) fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scale: &ColourScale,
    unit: &str,
    font: u32,
) -> Result<(), ChartError>
where
    DB::ErrorType: 'static,
{
    let ticks = scale.ticks(5);
    let step = if ticks.len() > 1 {
        ticks[1] - ticks[0]
    } else {
        scale.max - scale.min
    };
    let mut chart = ChartBuilder::on(area)
        .margin_top(font + font / 2)
        .margin_bottom(font / 2)
        .margin_left(2)
        .margin_right(font * 4)
        .caption(unit, text(font))
        .build_cartesian_2d(0.0..1.0, scale.min..scale.max)?;
    let (_, rows) = chart.plotting_area().get_pixel_range();
    let n = (rows.end - rows.start).max(1) as usize;
    let dy = (scale.max - scale.min) / n as f64;
    chart.draw_series((0..n).map(|i| {
        let y0 = scale.min + i as f64 * dy;
        let colour = rgb(scale.colour(y0 + 0.5 * dy));
        Rectangle::new([(0.0, y0), (1.0, y0 + dy)], colour.filled())
    }))?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .disable_y_mesh()
        .disable_x_axis()
        .y_labels(0)
        .draw()?;
    let (bx, by) = area.get_base_pixel();
    let style = text(font).pos(Pos::new(HPos::Left, VPos::Center));
    for &v in &ticks {
        let (x, y) = chart.backend_coord(&(1.0, v));
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(0.75, v), (1.0, v)],
            BLACK.stroke_width(1),
        )))?;
        area.draw(&Text::new(
            tick_label(v, step),
            (x - bx + 4, y - by),
            style.clone(),
        ))?;
    }
    Ok(())
}

/// `image` with `lines` of caption in a white strip under it, and each of `marks` (a
/// pixel of the image and a label) circled and labelled on the picture, so that a
/// render says what it shows and where the thing that moved is.
pub fn captioned(
    image: &RgbImage,
    lines: &[String],
    marks: &[((f32, f32), String)],
) -> Result<RgbImage, ChartError> {
    let font = (image.width() / 34).clamp(12, 28);
    let strip = lines.len() as u32 * (font + font / 3) + font / 2;
    let (w, h) = image.dimensions();
    let mut out = RgbImage::from_pixel(w, h + strip, image::Rgb([255; 3]));
    image::imageops::replace(&mut out, image, 0, 0);
    draw_on(&mut out, |root| {
        for (k, line) in lines.iter().enumerate() {
            let y = h as i32 + font as i32 / 4 + k as i32 * (font + font / 3) as i32;
            root.draw(&Text::new(line.clone(), (8, y), text(font)))?;
        }
        let r = (font as i32).max(10);
        for ((x, y), label) in marks {
            let (x, y) = (*x as i32, *y as i32);
            if x < 0 || y < 0 || x >= w as i32 || y >= h as i32 {
                continue;
            }
            root.draw(&Circle::new((x, y), r, WHITE.stroke_width(4)))?;
            root.draw(&Circle::new(
                (x, y),
                r,
                RGBColor(214, 39, 40).stroke_width(2),
            ))?;
            let style = text(font).color(&WHITE);
            root.draw(&Text::new(label.clone(), (x + r + 5, y - r - 1), style))?;
            root.draw(&Text::new(
                label.clone(),
                (x + r + 4, y - r - 2),
                text(font),
            ))?;
        }
        Ok(())
    })?;
    Ok(out)
}
