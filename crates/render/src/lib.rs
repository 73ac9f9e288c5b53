//! Pictures of lit scenes (thesis §2.6.3, appendix A; DESIGN.md §5): photon-mapped
//! renders from a camera, false-colour illuminance pictures, illuminance grids over a
//! surface with their intervals, and plots of the configurations a search visited.
//!
//! - [`PhotonMap`]: photons stored where they arrive (indirect light and caustics) in a
//!   hashed grid, and the density estimate of irradiance (thesis eq. 2.6).
//! - [`Renderer`], [`choose_view`]: a picture from start to end — the view from a camera
//!   name and a size, the photon maps, the pixels — as `render` and `solve` make them.
//! - [`Integrator`], [`render`]: camera rays, direct light by shadow rays to every
//!   light kind, the photon map for indirect light, mirrors and glass followed with
//!   Fresnel; pixels in parallel, the same image on any number of threads.
//! - [`tone_map`]: exposure and a filmic curve to 8-bit sRGB.
//! - [`render_illuminance`], [`false_colour`]: illuminance seen through each pixel as
//!   false colour with a legend in lux.
//! - [`illuminance_map`]: mean illuminance over the cells of a grid on a planar surface,
//!   each with its confidence interval, and Emin, Eavg, Emax, U0 (EN 12464-1).
//! - [`SearchPlot`]: what a search visited, drawn as `search.png`.
#![deny(missing_docs)]

mod camera;
mod draw;
mod false_colour;
mod integrator;
mod map;
mod photon_map;
mod picture;
mod plot;
mod tonemap;

pub use camera::View;
pub use draw::{legend_width, nice_ceil, scale_colour};
pub use false_colour::{auto_max, false_colour};
/// The `image` crate the pictures are made with, so callers can save them without
/// depending on it themselves.
pub use image;
pub use image::RgbImage;
pub use integrator::{
    AreaLights, IlluminanceImage, Image, Integrator, RenderSettings, render, render_illuminance,
};
pub use map::{
    IlluminanceMap, MAX_CELLS, MapCell, MapCsvRow, MapError, MapPoint, MapReport, MapSettings,
    MapSummary, illuminance_map,
};
pub use photon_map::{Paths, PhotonMap, PhotonSettings, Store};
pub use picture::{
    Look, MAX_PIXELS, MapFigures, PictureSettings, Renderer, SaveError, ViewError, choose_view,
    picture_format, save_picture,
};
pub use plot::{Mark, PLOT_SIZE, PlotKind, PlotPoint, SearchPlot, draw_search_plot};
pub use tonemap::{Exposure, ToneMap, log_average, srgb_encode, tone_map};
