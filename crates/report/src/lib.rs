//! invlight-report: what a solve leaves for people to look at, made from the run's
//! files and the scene — above the tracer (`invlight-render`) and the search
//! (`invlight-ilp`), which know nothing of each other.
//!
//! - [`Pictures`]: every ISOC member rendered from the scene's camera with photon
//!   mapping (`isoc-NN.png`, as the thesis' tool showed each optimal configuration,
//!   §2.6.3), and a plot per variable of the configurations the search visited
//!   (`search.png`, the thesis' figures 5.6, 5.8, 5.11).
//! - [`file_safe`]: a name as a file name.
#![deny(missing_docs)]

mod pictures;

pub use pictures::{PictureError, Pictures, file_safe};
