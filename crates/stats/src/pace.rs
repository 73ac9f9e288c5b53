//! How long work under way will take, judged from its pace over its first seconds: a
//! photon count typed with three zeros too many should not run for days without a
//! word. The command line shows the warning; this module decides when one is due.

use crate::format::hours_or_days;
use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Work expected to take longer than this deserves a warning.
pub const LONG_WORK: Duration = Duration::from_secs(3600);
/// The pace is judged after this much of the work.
pub const PACE_SAMPLE: Duration = Duration::from_secs(3);

/// The pace of `total` units of work started at its creation.
#[derive(Debug)]
pub struct Pace {
    total: u64,
    start: Instant,
    warned: AtomicBool,
}

/// Work found to be long: what was done in how long, and the whole's expected time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LongWork {
    /// Units done.
    pub done: u64,
    /// Units in all.
    pub total: u64,
    /// Time spent so far.
    pub spent: Duration,
    /// The whole's expected duration at this pace.
    pub expected: Duration,
}

impl fmt::Display for LongWork {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "about {} at this pace ({} of {} done in {:.0} s)",
            hours_or_days(self.expected),
            self.done,
            self.total,
            self.spent.as_secs_f64()
        )
    }
}

impl Pace {
    /// The pace of `total` units starting now.
    pub fn new(total: u64) -> Pace {
        Pace {
            total,
            start: Instant::now(),
            warned: AtomicBool::new(false),
        }
    }

    /// With `done` units done: the first time, after [`PACE_SAMPLE`], that the whole
    /// is expected to last more than [`LONG_WORK`], what it will take; `None` before,
    /// after and otherwise (callable from worker threads).
    pub fn long_once(&self, done: u64) -> Option<LongWork> {
        self.long_after(done, self.start.elapsed())
    }

    fn long_after(&self, done: u64, spent: Duration) -> Option<LongWork> {
        if done == 0 || spent < PACE_SAMPLE || self.warned.load(Ordering::Relaxed) {
            return None;
        }
        let expected = spent.mul_f64(self.total as f64 / done as f64);
        (expected > LONG_WORK && !self.warned.swap(true, Ordering::Relaxed)).then_some(LongWork {
            done,
            total: self.total,
            spent,
            expected,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_work_is_told_once_after_the_sample() {
        let pace = Pace::new(1_000_000);
        let s = Duration::from_secs(4);
        // Too early to judge, then 1 % in 4 s: 400 s in all, not long.
        assert_eq!(pace.long_after(1, Duration::from_secs(1)), None);
        assert_eq!(pace.long_after(10_000, s), None);
        // 0.1 % in 4 s: 4000 s, told once.
        let long = pace.long_after(1_000, s).unwrap();
        assert_eq!(long.expected, Duration::from_secs(4000));
        assert!(
            long.to_string()
                .starts_with("about 1.1 hours at this pace (1000 of 1000000")
        );
        assert_eq!(pace.long_after(1_000, s), None);
    }
}
