//! Daylight as architects state it: a place and a time instead of a bare direction.
//!
//! - [`Site`] and [`Compass`]: latitude, longitude, the clock's zone and elevation; and
//!   where the scene's north and east lie, so that horizontal coordinates (zenith angle,
//!   azimuth clockwise from north) become scene vectors ([`Compass::to_sky`]).
//! - [`Date`], [`TimeOfDay`]: civil dates and clock times read from `2003-10-17` and
//!   `12:30:30`, refused when no calendar or clock has them.

mod site;
mod time;

pub use site::{Compass, Site};
pub use time::{Date, TimeOfDay, is_leap_year, julian_day};

use std::fmt;

/// Why a daylight input was refused. Each message says what was expected, so that the
/// command line and problem-file readers can pass it on as it is.
#[derive(Debug, Clone, PartialEq)]
pub enum DaylightError {
    /// Text that is not a `YYYY-MM-DD` date, or a date no calendar has.
    Date {
        /// The text or date as given.
        text: String,
        /// What is wrong with it.
        problem: String,
    },
    /// Text that is not an `HH:MM[:SS]` clock time, or a time no clock shows.
    Time {
        /// The text or time as given.
        text: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A number outside the range its quantity can take.
    OutOfRange {
        /// The quantity.
        what: &'static str,
        /// The value given.
        value: f64,
        /// What it may be.
        range: &'static str,
    },
}

impl fmt::Display for DaylightError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DaylightError::Date { text, problem } => write!(f, "date '{text}': {problem}"),
            DaylightError::Time { text, problem } => write!(f, "time '{text}': {problem}"),
            DaylightError::OutOfRange { what, value, range } => {
                write!(f, "{what} {value} is out of range: expected {range}")
            }
        }
    }
}

impl std::error::Error for DaylightError {}
