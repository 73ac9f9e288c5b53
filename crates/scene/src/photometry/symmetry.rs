//! Expanding a file's planes to the whole sphere by the symmetry its angles (IES) or its
//! symmetry indicator (EULUMDAT) declare, so that the rest of the code sees one kind of
//! table. Each mirrored plane is a copy of the measured plane it mirrors.

use std::fmt;

/// The symmetries of a type C table's horizontal angles (LM-63-2002 §5.13; EULUMDAT
/// Isym).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Symmetry {
    /// One plane: the same in every C-plane (IES one horizontal angle; Isym 1).
    Rotational,
    /// C0–C90 measured, mirrored about the C0–C180 and C90–C270 planes (IES last
    /// angle 90; Isym 4).
    Quadrant,
    /// C0–C180 measured, mirrored about the C0–C180 plane (IES last angle 180; Isym 2).
    AboutC0,
    /// C90–C270 measured, mirrored about the C90–C270 plane (IES-1995 first angle 90,
    /// last 270; Isym 3).
    AboutC90,
    /// The whole circle measured (IES 0..360; Isym 0).
    None,
}

/// Horizontal angles that no symmetry expands to the whole sphere; the readers put the
/// file and line in front.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum SymmetryError {
    /// An IES type C range other than the ones LM-63 defines.
    TypeCRange { first: f64, last: f64 },
    /// Type B angles beyond ±90°.
    TypeBRange { first: f64, last: f64 },
    /// The mirrored planes stop short of the range they must cover (`range` says which;
    /// empty for type B).
    Unreached { range: &'static str },
}

impl fmt::Display for SymmetryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SymmetryError::TypeCRange { first, last } => write!(
                f,
                "horizontal angles from {first}° to {last}°: type C files run 0 to 0, 90, 180 or 360°, or 90 to 270°"
            ),
            SymmetryError::TypeBRange { first, last } => write!(
                f,
                "type B angles from {first}° to {last}°: they lie within −90° and 90°"
            ),
            SymmetryError::Unreached { range } => {
                write!(f, "the expanded planes do not reach {range}")
            }
        }
    }
}

impl std::error::Error for SymmetryError {}

impl Symmetry {
    /// The symmetry an IES file's horizontal angles declare, or what was expected.
    pub(crate) fn of_ies(first: f64, last: f64, count: usize) -> Result<Symmetry, SymmetryError> {
        let is = |a: f64, b: f64| (a - b).abs() < 1e-6;
        Ok(if count == 1 {
            Symmetry::Rotational
        } else if is(first, 0.0) && is(last, 90.0) {
            Symmetry::Quadrant
        } else if is(first, 0.0) && is(last, 180.0) {
            Symmetry::AboutC0
        } else if is(first, 90.0) && is(last, 270.0) {
            Symmetry::AboutC90
        } else if is(first, 0.0) && is(last, 360.0) {
            Symmetry::None
        } else {
            return Err(SymmetryError::TypeCRange { first, last });
        })
    }

    /// The angle a measured plane at `a` is copied to by each mirror of the symmetry.
    fn images(self, a: f64) -> Vec<f64> {
        match self {
            Symmetry::Rotational => vec![0.0, 360.0],
            Symmetry::Quadrant => vec![a, 180.0 - a, 180.0 + a, 360.0 - a],
            Symmetry::AboutC0 => vec![a, 360.0 - a],
            Symmetry::AboutC90 => vec![a, (540.0 - a) % 360.0],
            Symmetry::None => vec![a],
        }
    }
}

/// The type C planes at `angles` (degrees, increasing; `rows[k]` the intensities of
/// plane k) expanded over 0..=360° by `symmetry`: the angles and, for each, the measured
/// plane it copies. The plane at 0° is repeated at 360° (and back), so the table wraps.
pub(crate) fn expand_c(
    angles: &[f64],
    symmetry: Symmetry,
) -> Result<Vec<(f64, usize)>, SymmetryError> {
    let mut out: Vec<(f64, usize)> = Vec::new();
    for (k, &a) in angles.iter().enumerate() {
        for image in symmetry.images(a) {
            out.push((image, k));
        }
    }
    let wrap: Vec<(f64, usize)> = out
        .iter()
        .filter_map(|&(a, k)| {
            if a.abs() < 1e-6 {
                Some((360.0, k))
            } else if (a - 360.0).abs() < 1e-6 {
                Some((0.0, k))
            } else {
                None
            }
        })
        .collect();
    out.extend(wrap);
    finish(out, 0.0, 360.0, "0° and 360°")
}

/// Type B horizontal angles expanded over −90..=90°: a file whose angles start at 0 is
/// laterally symmetric (LM-63-2002 §5.13), one angle is the same everywhere.
pub(crate) fn expand_b(angles: &[f64]) -> Result<Vec<(f64, usize)>, SymmetryError> {
    let mut out: Vec<(f64, usize)> = Vec::new();
    if angles.len() == 1 {
        return Ok(vec![(-90.0, 0), (90.0, 0)]);
    }
    let mirrored = angles[0].abs() < 1e-6;
    for (k, &a) in angles.iter().enumerate() {
        out.push((a, k));
        if mirrored {
            out.push((-a, k));
        }
    }
    let (lo, hi) = (
        out.iter().map(|p| p.0).fold(f64::INFINITY, f64::min),
        out.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max),
    );
    if lo < -90.0 - 1e-6 || hi > 90.0 + 1e-6 {
        return Err(SymmetryError::TypeBRange {
            first: angles[0],
            last: angles[angles.len() - 1],
        });
    }
    finish(out, lo, hi, "")
}

/// Sorts, merges angles closer than 10⁻⁶° and checks the range reaches `lo`..`hi`.
fn finish(
    mut out: Vec<(f64, usize)>,
    lo: f64,
    hi: f64,
    range: &'static str,
) -> Result<Vec<(f64, usize)>, SymmetryError> {
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.dedup_by(|b, a| (b.0 - a.0).abs() < 1e-6);
    let (first, last) = (out[0].0, out[out.len() - 1].0);
    if (first - lo).abs() > 1e-6 || (last - hi).abs() > 1e-6 {
        return Err(SymmetryError::Unreached { range });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn angles(e: &[(f64, usize)]) -> Vec<f64> {
        e.iter().map(|p| p.0).collect()
    }

    #[test]
    fn each_symmetry_covers_the_circle() {
        let q = expand_c(&[0.0, 45.0, 90.0], Symmetry::Quadrant).unwrap();
        assert_eq!(
            angles(&q),
            [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0, 360.0]
        );
        assert_eq!(
            q.iter().map(|p| p.1).collect::<Vec<_>>(),
            [0, 1, 2, 1, 0, 1, 2, 1, 0]
        );
        let c0 = expand_c(&[0.0, 90.0, 180.0], Symmetry::AboutC0).unwrap();
        assert_eq!(angles(&c0), [0.0, 90.0, 180.0, 270.0, 360.0]);
        assert_eq!(c0.iter().map(|p| p.1).collect::<Vec<_>>(), [0, 1, 2, 1, 0]);
        let c90 = expand_c(&[90.0, 180.0, 270.0], Symmetry::AboutC90).unwrap();
        assert_eq!(angles(&c90), [0.0, 90.0, 180.0, 270.0, 360.0]);
        assert_eq!(c90.iter().map(|p| p.1).collect::<Vec<_>>(), [1, 0, 1, 2, 1]);
        // EULUMDAT lists 0..345 for the full circle: 360 is the plane at 0.
        let full = expand_c(&[0.0, 120.0, 240.0], Symmetry::None).unwrap();
        assert_eq!(angles(&full), [0.0, 120.0, 240.0, 360.0]);
        assert_eq!(
            expand_c(&[0.0], Symmetry::Rotational).unwrap(),
            [(0.0, 0), (360.0, 0)]
        );
        assert_eq!(
            expand_c(&[10.0, 90.0], Symmetry::None)
                .unwrap_err()
                .to_string(),
            "the expanded planes do not reach 0° and 360°"
        );
    }

    #[test]
    fn ies_symmetry_from_the_range() {
        assert_eq!(Symmetry::of_ies(0.0, 0.0, 1), Ok(Symmetry::Rotational));
        assert_eq!(Symmetry::of_ies(0.0, 90.0, 3), Ok(Symmetry::Quadrant));
        assert_eq!(Symmetry::of_ies(90.0, 270.0, 3), Ok(Symmetry::AboutC90));
        assert!(
            Symmetry::of_ies(0.0, 200.0, 3)
                .unwrap_err()
                .to_string()
                .contains("0 to 0, 90, 180 or 360")
        );
    }

    #[test]
    fn type_b_lateral_symmetry() {
        let b = expand_b(&[0.0, 30.0, 90.0]).unwrap();
        assert_eq!(angles(&b), [-90.0, -30.0, 0.0, 30.0, 90.0]);
        assert_eq!(b.iter().map(|p| p.1).collect::<Vec<_>>(), [2, 1, 0, 1, 2]);
        assert_eq!(
            expand_b(&[-100.0, 90.0]).unwrap_err().to_string(),
            "type B angles from -100° to 90°: they lie within −90° and 90°"
        );
    }
}
