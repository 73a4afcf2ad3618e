//! A knitter's gauge (stitches and rows per 10 cm, measured on the fabric) to stitch counts.

use crate::error::{KnitError, Result};

/// Most stitches along one direction of a knit or a plush.
pub const MAX_STITCHES_PER_DIRECTION: usize = crate::settings::COURSES.max as usize;

/// `(courses, wales)`: the counts given, or those a `gauge` (stitches, rows per 0.1 scene
/// units) gives over a surface `extent` long along u (a course) and v (a wale), at least 1.
/// A gauge that would give more than [`MAX_STITCHES_PER_DIRECTION`] is a budget error naming
/// the count, before anything is allocated.
pub fn stitch_counts(
    extent: (f32, f32),
    gauge: (f32, f32),
    courses: Option<usize>,
    wales: Option<usize>,
) -> Result<(usize, usize)> {
    let from_gauge = |len: f32, per10: f32, what: &str| -> Result<usize> {
        let n = (len as f64 * per10 as f64 / 0.1).round();
        if !n.is_finite() || n > MAX_STITCHES_PER_DIRECTION as f64 {
            return Err(KnitError::Budget(format!(
                "the gauge gives {n:.0} {what} (surface {len} long); at most \
                 {MAX_STITCHES_PER_DIRECTION} are allowed: use a coarser gauge"
            )));
        }
        Ok((n as usize).max(1))
    };
    let wales = match wales {
        Some(n) => n,
        None => from_gauge(extent.0, gauge.0, "stitches per course")?,
    };
    let courses = match courses {
        Some(n) => n,
        None => from_gauge(extent.1, gauge.1, "rows")?,
    };
    Ok((courses, wales))
}

/// The whole number of pattern repeats nearest `count` stitches, as a knitter casts on for
/// knitting in the round: a `repeat`-stitch pattern closes on itself only over a multiple of
/// `repeat` (otherwise the seam cuts a cable or a lace motif in two, and loops crossing it
/// land on stitches of another motif). Counts under half a repeat stay as they are: the
/// pattern cannot go round once, and rounding up would change the gauge out of all measure.
pub fn whole_repeats(count: usize, repeat: usize) -> usize {
    if repeat <= 1 {
        return count;
    }
    let repeats = (count + repeat / 2) / repeat;
    if repeats == 0 {
        count
    } else {
        repeats.saturating_mul(repeat)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_from_gauge_or_given() {
        // 12 x 10 cm at 20 stitches and 28 rows per 10 cm.
        assert_eq!(
            stitch_counts((0.12, 0.10), (20.0, 28.0), None, None),
            Ok((28, 24))
        );
        assert_eq!(
            stitch_counts((0.12, 0.10), (20.0, 28.0), Some(5), None),
            Ok((5, 24))
        );
        assert_eq!(
            stitch_counts((1e-9, 1e-9), (20.0, 28.0), None, None),
            Ok((1, 1))
        );
        let err = stitch_counts((1e6, 1.0), (20.0, 28.0), None, None).unwrap_err();
        assert!(matches!(err, KnitError::Budget(m) if m.contains("stitches per course")));
    }

    #[test]
    fn in_the_round_counts_are_whole_repeats() {
        assert_eq!(whole_repeats(38, 1), 38);
        assert_eq!(whole_repeats(38, 12), 36);
        assert_eq!(whole_repeats(42, 12), 48);
        assert_eq!(whole_repeats(6, 12), 12);
        assert_eq!(whole_repeats(5, 12), 5);
        assert_eq!(whole_repeats(0, 4), 0);
        for n in 1..200 {
            for r in 1..30 {
                let m = whole_repeats(n, r);
                assert!(m % r == 0 || (m == n && 2 * n < r), "{n} {r} -> {m}");
                assert!(2 * m.abs_diff(n) <= r, "{n} {r} -> {m}");
            }
        }
    }
}
