//! Civil dates and clock times as an architect writes them (`2003-10-17`, `12:30:30`),
//! checked against the calendar when they are read, and the Julian day the solar
//! position algorithm starts from.
//!
//! The calendar is the proleptic Gregorian one (ISO 8601): a date before 1582 is counted
//! as if the Gregorian rules had always held. NREL's `spa.c` switches to the Julian
//! calendar before 1582-10-15; no building problem reaches back that far.

use super::DaylightError;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::str::FromStr;

/// A calendar date, validated: `2003-02-29` and `2003-13-01` cannot be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Date {
    year: i32,
    month: u32,
    day: u32,
}

/// A clock time within a day, validated: hours 0–23, minutes 0–59, seconds in [0, 60).
/// There is no `24:00` (ISO 8601's end of day is the next day's `00:00`) and no leap
/// second: SPA takes UTC as UT1, which leap seconds do not change.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
pub struct TimeOfDay {
    hour: u32,
    minute: u32,
    second: f64,
}

const MONTHS: [&str; 12] = [
    "January",
    "February",
    "March",
    "April",
    "May",
    "June",
    "July",
    "August",
    "September",
    "October",
    "November",
    "December",
];

/// Whether `year` has a 29 February (Gregorian rule: every 4th year, except centuries
/// not divisible by 400).
pub fn is_leap_year(year: i32) -> bool {
    (year % 4 == 0 && year % 100 != 0) || year % 400 == 0
}

/// Days in `month` (1–12) of `year`.
fn days_in_month(year: i32, month: u32) -> u32 {
    match month {
        2 if is_leap_year(year) => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

impl Date {
    /// The date `year-month-day`, or why there is no such date.
    pub fn new(year: i32, month: u32, day: u32) -> Result<Date, DaylightError> {
        let text = format!("{year:04}-{month:02}-{day:02}");
        let bad = |problem: String| DaylightError::Date {
            text: text.clone(),
            problem,
        };
        if !(1..=12).contains(&month) {
            return Err(bad(format!(
                "there is no month {month}; months are 01 to 12"
            )));
        }
        let days = days_in_month(year, month);
        if day == 0 || day > days {
            return Err(bad(format!(
                "{} {year} has {days} days",
                MONTHS[month as usize - 1]
            )));
        }
        Ok(Date { year, month, day })
    }

    /// The year (astronomical numbering: 0 is 1 BC).
    pub fn year(&self) -> i32 {
        self.year
    }

    /// The month, 1–12.
    pub fn month(&self) -> u32 {
        self.month
    }

    /// The day of the month, from 1.
    pub fn day(&self) -> u32 {
        self.day
    }

    /// The day of the year: 1 on 1 January, 365 or 366 on 31 December.
    pub fn day_of_year(&self) -> u32 {
        (1..self.month)
            .map(|m| days_in_month(self.year, m))
            .sum::<u32>()
            + self.day
    }

    /// Days from 1970-01-01 to this date (negative before it). H. Hinnant's
    /// `days_from_civil` ("chrono-Compatible Low-Level Date Algorithms", 2013): exact
    /// integer arithmetic over 400-year eras, with March as the first month so that the
    /// leap day falls at the end of the counted year.
    pub fn days_since_1970(&self) -> i64 {
        let (m, d) = (self.month as i64, self.day as i64);
        let y = self.year as i64 - (m <= 2) as i64;
        let era = y.div_euclid(400);
        let year_of_era = y - era * 400;
        let day_of_year = (153 * ((m + 9) % 12) + 2) / 5 + d - 1;
        let day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
        era * 146_097 + day_of_era - 719_468
    }

    /// The date `days` after 1970-01-01 (before it when negative): the inverse of
    /// [`Date::days_since_1970`], H. Hinnant's `civil_from_days` (same paper).
    pub fn from_days_since_1970(days: i64) -> Date {
        let z = days + 719_468;
        let era = z.div_euclid(146_097);
        let day_of_era = z - era * 146_097;
        let year_of_era =
            (day_of_era - day_of_era / 1460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
        let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
        let mp = (5 * day_of_year + 2) / 153;
        let day = (day_of_year - (153 * mp + 2) / 5 + 1) as u32;
        let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
        let year = (year_of_era + era * 400 + (month <= 2) as i64) as i32;
        Date { year, month, day }
    }
}

impl FromStr for Date {
    type Err = DaylightError;

    /// Reads `YYYY-MM-DD` (ISO 8601's extended calendar date, four-digit year).
    fn from_str(text: &str) -> Result<Date, DaylightError> {
        let bad = |problem: &str| DaylightError::Date {
            text: text.to_string(),
            problem: problem.to_string(),
        };
        let fields: Vec<&str> = text.trim().split('-').collect();
        let [y, m, d] = fields[..] else {
            return Err(bad("expected a date as YYYY-MM-DD, like 2003-10-17"));
        };
        if y.len() != 4 || m.len() != 2 || d.len() != 2 {
            return Err(bad(
                "expected a four-digit year, a two-digit month and a two-digit day, like 2003-10-17",
            ));
        }
        let (Some(year), Some(month), Some(day)) = (digits(y), digits(m), digits(d)) else {
            return Err(bad("expected digits in YYYY-MM-DD, like 2003-10-17"));
        };
        Date::new(year as i32, month, day).map_err(|e| match e {
            DaylightError::Date { problem, .. } => DaylightError::Date {
                text: text.to_string(),
                problem,
            },
            other => other,
        })
    }
}

/// Whether `s` is one or more ASCII digits.
fn all_digits(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit())
}

/// The value of a short string of ASCII digits only.
fn digits(s: &str) -> Option<u32> {
    all_digits(s).then(|| s.parse().ok()).flatten()
}

impl fmt::Display for Date {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }
}

impl Serialize for Date {
    /// As it is written: `"2003-10-17"`.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl TimeOfDay {
    /// The time `hour:minute:second`, or why it is not a clock time.
    pub fn new(hour: u32, minute: u32, second: f64) -> Result<TimeOfDay, DaylightError> {
        let bad = |problem: &str| DaylightError::Time {
            text: format!("{hour:02}:{minute:02}:{second:02}"),
            problem: problem.to_string(),
        };
        if hour == 24 {
            return Err(bad(
                "there is no 24:00; the end of a day is 00:00 of the next day",
            ));
        }
        if hour > 23 {
            return Err(bad("hours are 00 to 23"));
        }
        if minute > 59 {
            return Err(bad("minutes are 00 to 59"));
        }
        if !(0.0..60.0).contains(&second) {
            return Err(bad(if (60.0..61.0).contains(&second) {
                "seconds are 00 to 59 (leap seconds are not supported)"
            } else {
                "seconds are 00 to 59"
            }));
        }
        Ok(TimeOfDay {
            hour,
            minute,
            second,
        })
    }

    /// The hour, 0–23.
    pub fn hour(&self) -> u32 {
        self.hour
    }

    /// The minute, 0–59.
    pub fn minute(&self) -> u32 {
        self.minute
    }

    /// The second, in [0, 60).
    pub fn second(&self) -> f64 {
        self.second
    }

    /// Seconds since midnight.
    pub fn seconds_of_day(&self) -> f64 {
        (self.hour * 3600 + self.minute * 60) as f64 + self.second
    }
}

impl FromStr for TimeOfDay {
    type Err = DaylightError;

    /// Reads `HH:MM`, `HH:MM:SS` or `HH:MM:SS.s…` (24-hour clock).
    fn from_str(text: &str) -> Result<TimeOfDay, DaylightError> {
        let bad = |problem: &str| DaylightError::Time {
            text: text.to_string(),
            problem: problem.to_string(),
        };
        let fields: Vec<&str> = text.trim().split(':').collect();
        let (h, m, s) = match fields[..] {
            [h, m] => (h, m, "0"),
            [h, m, s] => (h, m, s),
            _ => return Err(bad("expected a time as HH:MM or HH:MM:SS, like 12:30:30")),
        };
        if h.len() != 2 || m.len() != 2 {
            return Err(bad(
                "expected two-digit hours and minutes (24-hour clock), like 09:05",
            ));
        }
        let (Some(hour), Some(minute)) = (digits(h), digits(m)) else {
            return Err(bad("expected digits in HH:MM:SS, like 12:30:30"));
        };
        let (whole, fraction) = s.split_once('.').unwrap_or((s, "0"));
        let two_digits = whole.len() == 2 || fields.len() == 2;
        if !two_digits || !all_digits(whole) || !all_digits(fraction) {
            return Err(bad(
                "expected two-digit seconds, optionally with a decimal fraction, like 30 or 30.25",
            ));
        }
        let second: f64 = s.parse().map_err(|_| bad("unreadable seconds"))?;
        TimeOfDay::new(hour, minute, second).map_err(|e| match e {
            DaylightError::Time { problem, .. } => DaylightError::Time {
                text: text.to_string(),
                problem,
            },
            other => other,
        })
    }
}

impl fmt::Display for TimeOfDay {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:02}:{:02}:", self.hour, self.minute)?;
        if self.second.fract() == 0.0 {
            write!(f, "{:02}", self.second as u32)
        } else {
            let s = format!("{:.6}", self.second);
            let s = s.trim_end_matches('0').trim_end_matches('.');
            write!(f, "{}{s}", if self.second < 10.0 { "0" } else { "" })
        }
    }
}

impl Serialize for TimeOfDay {
    /// As it is written: `"12:30:30"`.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for TimeOfDay {
    /// As [`TimeOfDay`]'s `FromStr` reads it, so that what is written reads back.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<TimeOfDay, D::Error> {
        let text = String::deserialize(d)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}

impl TimeOfDay {
    /// The clock time `minutes` after midnight, to the nearest second (held within the
    /// day: 00:00:00 to 23:59:59).
    pub fn from_minutes(minutes: f64) -> TimeOfDay {
        let s = (minutes * 60.0).round().clamp(0.0, 86_399.0) as u32;
        TimeOfDay {
            hour: s / 3600,
            minute: s / 60 % 60,
            second: (s % 60) as f64,
        }
    }
}

/// The Julian day (UT) of local clock time `time` on `date` at `timezone` hours east of
/// Greenwich: days since noon UT of 1 January 4713 BC (Julian calendar), the time scale
/// of SPA's step 3.1.1 (Reda & Andreas 2004, eq. 4). 1970-01-01 00:00 UT is
/// JD 2 440 587.5. The zone is subtracted here, as `spa.c`'s `julian_day` does, so a
/// local time whose UT falls on the day before or after needs no date arithmetic.
pub fn julian_day(date: &Date, time: &TimeOfDay, timezone: f64) -> f64 {
    date.days_since_1970() as f64
        + 2_440_587.5
        + (time.seconds_of_day() - timezone * 3600.0) / 86_400.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A clock time from minutes (a `sunTime`'s steps) rounds to the second and stays in
    /// the day; what is serialised reads back.
    #[test]
    fn dates_from_day_counts() {
        for text in [
            "1970-01-01",
            "2000-02-29",
            "2026-12-31",
            "1900-03-01",
            "1969-12-31",
        ] {
            let d: Date = text.parse().unwrap();
            assert_eq!(Date::from_days_since_1970(d.days_since_1970()), d, "{text}");
        }
        let mut d: Date = "2023-12-30".parse().unwrap();
        for _ in 0..800 {
            let next = Date::from_days_since_1970(d.days_since_1970() + 1);
            assert!(next > d && Date::new(next.year(), next.month(), next.day()).is_ok());
            d = next;
        }
        assert_eq!(d.to_string(), "2026-03-09");
    }

    #[test]
    fn times_from_minutes_and_back_from_json() {
        let t = TimeOfDay::from_minutes(530.25);
        assert_eq!(t.to_string(), "08:50:15");
        assert_eq!(TimeOfDay::from_minutes(-3.0).to_string(), "00:00:00");
        assert_eq!(TimeOfDay::from_minutes(1440.0).to_string(), "23:59:59");
        let json = serde_json::to_string(&t).unwrap();
        assert_eq!(json, "\"08:50:15\"");
        assert_eq!(serde_json::from_str::<TimeOfDay>(&json).unwrap(), t);
        let e = serde_json::from_str::<TimeOfDay>("\"24:00\"").unwrap_err();
        assert!(e.to_string().contains("24:00"), "{e}");
    }

    fn date_problem(text: &str) -> String {
        match text.parse::<Date>() {
            Err(DaylightError::Date { problem, .. }) => problem,
            other => panic!("{text}: expected a date error, got {other:?}"),
        }
    }

    fn time_problem(text: &str) -> String {
        match text.parse::<TimeOfDay>() {
            Err(DaylightError::Time { problem, .. }) => problem,
            other => panic!("{text}: expected a time error, got {other:?}"),
        }
    }

    #[test]
    fn reads_dates_and_rejects_what_the_calendar_lacks() {
        let d: Date = "2003-10-17".parse().unwrap();
        assert_eq!((d.year(), d.month(), d.day()), (2003, 10, 17));
        assert_eq!(d.to_string(), "2003-10-17");
        assert!("2000-02-29".parse::<Date>().is_ok());
        assert!("2024-02-29".parse::<Date>().is_ok());
        assert_eq!(date_problem("2003-02-30"), "February 2003 has 28 days");
        assert_eq!(date_problem("1900-02-29"), "February 1900 has 28 days");
        assert_eq!(date_problem("2004-02-30"), "February 2004 has 29 days");
        assert_eq!(date_problem("2003-04-31"), "April 2003 has 30 days");
        assert_eq!(date_problem("2003-01-00"), "January 2003 has 31 days");
        assert!(date_problem("2003-13-01").contains("no month 13"));
        assert!(date_problem("2003-00-10").contains("no month 0"));
        for text in [
            "17/10/2003",
            "2003-10",
            "2003-1-17",
            "03-10-17",
            "2003-10-1x",
            "",
        ] {
            assert!(date_problem(text).starts_with("expected"), "{text}");
        }
    }

    #[test]
    fn reads_times_and_rejects_what_a_clock_never_shows() {
        let t: TimeOfDay = "12:30:30".parse().unwrap();
        assert_eq!((t.hour(), t.minute(), t.second()), (12, 30, 30.0));
        assert_eq!(t.seconds_of_day(), 45_030.0);
        assert_eq!(t.to_string(), "12:30:30");
        assert_eq!(
            "09:05".parse::<TimeOfDay>().unwrap().to_string(),
            "09:05:00"
        );
        let f: TimeOfDay = "23:59:59.25".parse().unwrap();
        assert!("12:00:00.123456789012".parse::<TimeOfDay>().is_ok());
        assert_eq!((f.second(), f.to_string().as_str()), (59.25, "23:59:59.25"));
        assert_eq!(
            "00:00:05.5".parse::<TimeOfDay>().unwrap().to_string(),
            "00:00:05.5"
        );
        assert!(time_problem("24:00").contains("no 24:00"));
        assert!(time_problem("24:00:00").contains("no 24:00"));
        assert!(time_problem("25:00").contains("hours are 00 to 23"));
        assert!(time_problem("12:60").contains("minutes"));
        assert!(time_problem("23:59:60").contains("leap seconds"));
        assert!(time_problem("12:30:75").contains("seconds are 00 to 59"));
        for text in [
            "1230",
            "12:30:30:00",
            "9:05",
            "12:5",
            "12:30:3",
            "12:30:xx",
            "12:30:30.",
            "noon",
        ] {
            assert!(time_problem(text).starts_with("expected"), "{text}");
        }
    }

    #[test]
    fn day_of_year_counts_the_leap_day() {
        let doy = |s: &str| s.parse::<Date>().unwrap().day_of_year();
        assert_eq!(doy("2003-01-01"), 1);
        assert_eq!(doy("2003-10-17"), 290);
        assert_eq!(doy("2003-12-31"), 365);
        assert_eq!(doy("2004-03-01"), 61);
        assert_eq!(doy("2004-12-31"), 366);
    }

    /// Julian days of Meeus ("Astronomical Algorithms", 2nd ed., 1998, ch. 7: J2000.0 and
    /// examples 7.a) and of the SPA paper's worked example (Reda & Andreas 2004, table A4.1:
    /// 2003-10-17 12:30:30 at −7 h is JD 2452930.312847).
    #[test]
    fn julian_days_of_published_examples() {
        let jd =
            |d: &str, t: &str, tz: f64| julian_day(&d.parse().unwrap(), &t.parse().unwrap(), tz);
        assert_eq!(jd("2000-01-01", "12:00", 0.0), 2_451_545.0);
        assert_eq!(jd("1970-01-01", "00:00", 0.0), 2_440_587.5);
        // 1957 October 4.81 (Sputnik 1): 0.81 d = 19:26:24.
        assert!((jd("1957-10-04", "19:26:24", 0.0) - 2_436_116.31).abs() < 1e-6);
        assert!((jd("2003-10-17", "12:30:30", -7.0) - 2_452_930.312_847).abs() < 1e-6);
        // The same instant written in another zone, across midnight.
        assert_eq!(
            jd("2003-10-17", "12:30:30", -7.0),
            jd("2003-10-18", "05:30:30", 10.0)
        );
        // Before the Gregorian reform and in year 0 (proleptic Gregorian: 1 BC).
        assert_eq!(jd("1582-10-15", "12:00", 0.0), 2_299_161.0);
        assert_eq!(jd("0000-03-01", "12:00", 0.0), 1_721_120.0);
    }
}
