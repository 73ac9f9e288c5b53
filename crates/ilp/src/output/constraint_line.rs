//! A constraint's line in the terminal's table of an answer: the estimate with the
//! one-sided bound that decides it, the limit as the file states it (maintained, with
//! the maintenance factor that turned it into the new installation's), the standard's
//! name for it when a `<task>` asked it, and the verdict.

use super::result::{ConstraintInfo, ResultConstraint};
use invlight_photon::glare::rating;
use invlight_stats::significant;

impl ResultConstraint {
    /// Its line in the table, for the constraint `info`, at the run's `level` %: the
    /// estimate with the one-sided bound that decides it, the limit and the verdict.
    pub(super) fn line(&self, info: &ConstraintInfo, level: f64) -> String {
        let cu = match info.unit.as_str() {
            "" => String::new(),
            u => format!(" {u}"),
        };
        let sign = match info.bound.as_str() {
            "maxLux" | "maxUGR" => "≤",
            _ => "≥",
        };
        if info.bound == "maxUGR" {
            return self.ugr_line(info, level);
        }
        let maintained = match (info.maintained_limit, info.maintenance_factor) {
            (Some(m), Some(f)) => format!(" ({}{cu} maintained ÷ MF {f})", significant(m)),
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
                "{}{cu} ({sign} {}{cu} at {level} %, one-sided)",
                significant(self.estimate.mean),
                invlight_stats::significant_beside(b, info.limit)
            ),
            None => format!(
                "{}{cu} [{}, {}]",
                significant(self.estimate.mean),
                significant(self.estimate.low),
                significant(self.estimate.high)
            ),
        };
        format!(
            "       {}{named}: {read}, {sign} {}{cu}{maintained}: {}\n",
            self.label,
            significant(info.limit),
            self.verdict
        )
    }
    /// A UGR limit's line: ratings to a tenth and below CIE 117's scale as "< 10"
    /// ([`rating`]), the one-sided upper bound that decides it.
    fn ugr_line(&self, info: &ConstraintInfo, level: f64) -> String {
        let named = info
            .standard
            .as_ref()
            .map_or(String::new(), |s| format!(" ({s})"));
        let read = match self.bound {
            Some(b) => format!(
                "UGR {} (≤ {} at {level} %, one-sided)",
                rating(self.estimate.mean),
                rating(b)
            ),
            None => format!(
                "UGR {} [{}, {}]",
                rating(self.estimate.mean),
                rating(self.estimate.low),
                rating(self.estimate.high)
            ),
        };
        format!(
            "       {}{named}: {read}, ≤ {}: {}\n",
            self.label,
            significant(info.limit),
            self.verdict
        )
    }
}
