//! A constraint's line in the terminal's table of an answer: the estimate with the
//! one-sided bound that decides it, the limit as the file states it (maintained, with
//! the maintenance factor that turned it into the new installation's), the standard's
//! name for it when a `<task>` asked it, and the verdict.

use super::result::{ConstraintInfo, ResultConstraint};
use invlight_photon::glare::rating;
use invlight_stats::significant;

impl ResultConstraint {
    /// Its line in the table, for the constraint `info`, at the run's `level` %: the
    /// estimate with the one-sided bound that decides it, the limit and the verdict. A
    /// UGR reads as a rating ("UGR 18.9", below CIE 117's scale "< 10": [`rating`]).
    pub(super) fn line(&self, info: &ConstraintInfo, level: f64) -> String {
        let ugr = info.bound == "maxUGR";
        let cu = match info.unit.as_str() {
            "" => String::new(),
            u => format!(" {u}"),
        };
        let sign = match info.bound.as_str() {
            "maxLux" | "maxUGR" => "≤",
            _ => "≥",
        };
        let (prefix, value): (&str, fn(f64) -> String) = if ugr {
            ("UGR ", rating)
        } else {
            ("", significant)
        };
        let maintained = match (info.maintained_limit, info.maintenance_factor) {
            (Some(m), Some(f)) if !ugr => {
                format!(" ({}{cu} maintained ÷ MF {f})", significant(m))
            }
            _ => String::new(),
        };
        let named = info
            .standard
            .as_ref()
            .map_or(String::new(), |s| format!(" ({s})"));
        // The one-sided bound is what decides a one-sided constraint; a file
        // written before it was recorded shows its two-sided interval.
        let read = match self.bound {
            Some(b) => format!(
                "{prefix}{}{cu} ({sign} {}{cu} at {level} %, one-sided)",
                value(self.estimate.mean),
                if ugr {
                    rating(b)
                } else {
                    invlight_stats::significant_beside(b, info.limit)
                }
            ),
            None => format!(
                "{prefix}{}{cu} [{}, {}]",
                value(self.estimate.mean),
                value(self.estimate.low),
                value(self.estimate.high)
            ),
        };
        format!(
            "       {}{named}: {read}, {sign} {}{cu}{maintained}: {}\n",
            self.label,
            significant(info.limit),
            self.verdict
        )
    }
}
