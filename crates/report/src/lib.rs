//! invlight-report: what a solve leaves for people to look at, made from the run's
//! files and the scene — above the tracer (`invlight-render`) and the search
//! (`invlight-ilp`), which know nothing of each other.
//!
//! - [`Pictures`]: every ISOC member rendered from the scene's camera with photon
//!   mapping (`isoc-NN.png`, as the thesis' tool showed each optimal configuration,
//!   §2.6.3), captioned, and a plot per variable of the configurations the search
//!   visited (`search.png`, the thesis' figures 5.6, 5.8, 5.11) in world terms.
//! - [`SolveReport`]: `report.html`, one self-contained page for a client — the problem
//!   in words, the answer first, the ISOC gallery, the plots, the objective's plan with
//!   isolux lines and its compliance with a requirement at a stated confidence, every
//!   member in a table, and the time taken; [`MapPage`] the same for one grid.
//! - [`file_safe`]: a name as a file name; [`Progress`], a bar on stderr for long work.
#![deny(missing_docs)]

mod describe;
mod html;
mod map_page;
mod pictures;
mod plots;
mod progress;
mod solve_page;

pub use html::{Page, external_references};
pub use map_page::{MapPage, areas_text, compliance_text};
pub use pictures::{PictureError, Pictures, file_safe};
pub use plots::{convergence, search_plot};
pub use progress::Progress;
pub use solve_page::{GridOptions, ReportError, SolveFolder, SolveReport, Written};
