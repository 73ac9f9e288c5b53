//! A seeded mutator of sample files, for the bounded fuzz tests of the loaders: stable
//! Rust, no dependency, the same cases on every run of the same seed, so a failure
//! replays. Each case applies one to four edits chosen among those that found the
//! loaders' faults before: flipped bits, structural characters, deleted and duplicated
//! runs, numbers replaced by hostile ones (huge, tiny, negative, NaN, counts past
//! 2³²), truncation.
//!
//! `INVLIGHT_FUZZ_CASES` sets the cases per target (default [`DEFAULT_CASES`], a few
//! seconds in all); `.ci/run` raises it. `INVLIGHT_FUZZ_SEED` changes the seed.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

/// Cases per target in a default test run.
pub const DEFAULT_CASES: usize = 300;

/// A case slower than this counts as a hang.
pub const HANG: Duration = Duration::from_secs(10);

/// Numbers that broke something once, or sit at a boundary of what is accepted.
const HOSTILE: &[&str] = &[
    "0",
    "-1",
    "1e9",
    "1.000001e9",
    "3e38",
    "3.4e38",
    "1e38",
    "-3e38",
    "1e-30",
    "1e-45",
    "NaN",
    "inf",
    "4294967295",
    "4294967296",
    "178956970",
    "2147483647",
    "-0",
    "1e20",
    "65535",
    "99999999999999999999",
];

/// Characters that make and break structure in JSON, XML, OBJ and MTL.
const STRUCTURE: &[u8] = b"0123456789-.eE \n/#<>\"{}[],:";

/// SplitMix64: small, fast, and the same everywhere.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (`n` > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The cases per target: `INVLIGHT_FUZZ_CASES`, else [`DEFAULT_CASES`].
pub fn cases() -> usize {
    std::env::var("INVLIGHT_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_CASES)
}

/// The seed: `INVLIGHT_FUZZ_SEED`, else 19.
pub fn seed() -> u64 {
    std::env::var("INVLIGHT_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(19)
}

/// The spans of the decimal numbers in `bytes`.
fn numbers(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() {
            let start = if i > 0 && bytes[i - 1] == b'-' {
                i - 1
            } else {
                i
            };
            let mut end = i;
            while end < bytes.len()
                && (bytes[end].is_ascii_digit() || b".eE+-".contains(&bytes[end]))
            {
                end += 1;
            }
            spans.push((start, end));
            i = end;
        } else {
            i += 1;
        }
    }
    spans
}

/// One mutant of `sample`.
pub fn mutate(sample: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut b = sample.to_vec();
    let edits = 1 + rng.below(4);
    for _ in 0..edits {
        if b.is_empty() {
            b.push(b'0');
        }
        let at = rng.below(b.len());
        match rng.below(7) {
            0 => b[at] ^= 1 << rng.below(8),
            1 => b[at] = STRUCTURE[rng.below(STRUCTURE.len())],
            2 => {
                let n = (1 + rng.below(16)).min(b.len() - at);
                b.drain(at..at + n);
            }
            3 => {
                let n = (1 + rng.below(64)).min(b.len() - at);
                let run: Vec<u8> = b[at..at + n].to_vec();
                let to = rng.below(b.len());
                b.splice(to..to, run);
            }
            4 | 5 => {
                let spans = numbers(&b);
                if !spans.is_empty() {
                    let (s, e) = spans[rng.below(spans.len())];
                    let h = HOSTILE[rng.below(HOSTILE.len())].as_bytes().to_vec();
                    b.splice(s..e, h);
                }
            }
            _ => b.truncate(at),
        }
    }
    b
}

/// What a fuzz run saw.
#[derive(Debug, Default)]
pub struct Tally {
    pub runs: usize,
    pub accepted: usize,
    pub panics: usize,
    pub hangs: usize,
    pub slowest: Duration,
    /// The first failing case: its number and what went wrong.
    pub first_failure: Option<(usize, String)>,
}

/// Runs `cases` mutants of `samples` through `check`, which returns whether the input
/// was accepted and panics on any broken promise. Prints the tally (runs, accepted,
/// panics, hangs, slowest) and fails on any panic or hang, naming the case to replay.
///
/// A target that refuses everything would pass that alone, and so would one that checks
/// nothing: every sample as it is must be accepted first, and of [`DECIDING`] mutants
/// or more some must be accepted and some refused.
pub fn run(target: &str, samples: &[Vec<u8>], mut check: impl FnMut(&[u8]) -> bool) -> Tally {
    for (i, sample) in samples.iter().enumerate() {
        let accepted = catch_unwind(AssertUnwindSafe(|| check(sample)));
        assert!(
            matches!(accepted, Ok(true)),
            "fuzz {target}: sample {i} as it is was not accepted: the target refuses valid input"
        );
    }
    let tally = mutants(target, samples, check);
    if tally.runs >= DECIDING {
        assert!(
            tally.accepted > 0,
            "fuzz {target}: none of {} mutants accepted: the target refuses what it should read",
            tally.runs
        );
        assert!(
            tally.accepted < tally.runs,
            "fuzz {target}: all {} mutants accepted: the target checks nothing",
            tally.runs
        );
    }
    tally
}

/// The number of mutants from which a target must have accepted some and refused some:
/// the rarest acceptance, a GLB's binary chunk surviving a mutation, is about 1 in 60.
const DECIDING: usize = 1000;

/// The mutant loop of [`run`].
fn mutants(target: &str, samples: &[Vec<u8>], mut check: impl FnMut(&[u8]) -> bool) -> Tally {
    let mut rng = Rng::new(
        seed()
            ^ target
                .bytes()
                .fold(0u64, |h, c| h.wrapping_mul(31) ^ c as u64),
    );
    let mut tally = Tally::default();
    for case in 0..cases() {
        let sample = &samples[rng.below(samples.len())];
        let input = mutate(sample, &mut rng);
        let start = Instant::now();
        let outcome = catch_unwind(AssertUnwindSafe(|| check(&input)));
        let took = start.elapsed();
        tally.runs += 1;
        tally.slowest = tally.slowest.max(took);
        match outcome {
            Ok(accepted) => tally.accepted += accepted as usize,
            Err(e) => {
                tally.panics += 1;
                let why = e
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                tally
                    .first_failure
                    .get_or_insert((case, format!("panic: {why}")));
            }
        }
        if took > HANG {
            tally.hangs += 1;
            tally
                .first_failure
                .get_or_insert((case, format!("took {took:?}")));
        }
    }
    eprintln!(
        "fuzz {target}: {} runs, {} accepted, {} panics, {} hangs, slowest {:?} (seed {})",
        tally.runs,
        tally.accepted,
        tally.panics,
        tally.hangs,
        tally.slowest,
        seed()
    );
    if let Some((case, why)) = &tally.first_failure {
        panic!(
            "fuzz {target}: case {case} of seed {} failed ({why}); replay with INVLIGHT_FUZZ_SEED={} INVLIGHT_FUZZ_CASES={}",
            seed(),
            seed(),
            case + 1
        );
    }
    tally
}
