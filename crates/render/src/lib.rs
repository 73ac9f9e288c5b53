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
//! - [`assess`], [`Compliance`]: whether a grid meets Em and U0 (EN 12464-1:2021 tasks in
//!   [`TASKS`], its grid rule `invlight_photon::en12464_spacing`) with a stated confidence: meets,
//!   fails, or cannot tell at this photon count.
//! - [`SearchPlot`], [`ConvergencePlot`], [`MapPlan`]: what a search visited (a plan in
//!   world metres, a sun chart, a value plot), how it converged, and an illuminance grid
//!   as a plan with isolux lines — drawn with `plotters` as SVG or as pictures, in the
//!   embedded DejaVu Sans, coloured by viridis over the data's range ([`ColourScale`]).
#![deny(missing_docs)]

mod areas;
mod camera;
mod chart;
mod colour_map;
mod compliance;
mod false_colour;
mod integrator;
mod map;
mod photon_map;
mod picture;
mod plan;
mod plot;
mod tonemap;

pub use areas::{AreaReport, AreaVerdict, CylindricalReport, area_requirement, overall};
pub use camera::View;
pub use chart::{ChartError, FONT, captioned, draw_on, to_image, to_svg};
pub use colour_map::{ColourScale, nice_ticks, tick_label, viridis};
pub use compliance::{
    Compliance, Criterion, Requirement, RequirementError, Verdict, assess, plain,
};
pub use false_colour::{auto_scale, false_colour, legend_width};
/// The `image` crate the pictures are made with, so callers can save them without
/// depending on it themselves.
pub use image;
pub use image::RgbImage;
pub use integrator::{
    AreaLights, IlluminanceImage, Image, Integrator, RenderSettings, render, render_illuminance,
};
pub use invlight_scene::en12464::{ROOM_U0, SURROUNDING_U0, TASKS, Task, surrounding_em, task};
pub use map::{
    GridSpacing, GridSpacingError, IlluminanceMap, MapCell, MapCsvRow, MapError, MapPoint,
    MapReport, MapSettings, MapSummary, MapTarget, MapsAndMeans, illuminance_map,
    illuminance_map_across, illuminance_maps_across, illuminance_maps_and_means,
};
pub use photon_map::{Paths, PhotonMap, PhotonSettings, Store};
pub use picture::{
    Look, MAX_PIXELS, MapFigures, PictureSettings, Renderer, SaveError, ViewError, choose_view,
    picture_format, save_picture,
};
pub use plan::{MapPlan, PLAN_WIDTH, isolines, seen_from};
pub use plot::{
    ConvergencePlot, ConvergencePoint, Frame, Mark, PLOT_SIZE, PlanAxis, PlanFrame, PlotKind,
    PlotPoint, SearchPlot,
};
pub use tonemap::{Exposure, ToneMap, log_average, srgb_encode, tone_map};
