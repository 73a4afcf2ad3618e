//! How tall the rows of leaning loops stand: the [`RowHeights`] a pattern's cables and
//! decreases ask for at a given stitch size.
//!
//! A loop leaning `L` columns within one row of height `h` runs at a slope of about
//! `h / (L w)`; the gap between its two legs, and between it and the loops it crosses, shrinks
//! with that slope. Below [`room_needed`] the yarns cannot clear a diameter whatever their
//! offsets, so the rows where loops lean are made that tall in the columns they lean across
//! (the tiles they leave and the ones they land in, and the node lines between), and the
//! other rows of those columns gather up to pay for it, never below [`SHORTEST`] of a row.
//! Columns where no loop leans keep regular rows. This is what real cables do: the crossed
//! stitches stretch and the cable draws up the rows round them.
//!
//! How tall is a choice the tuning makes ([`ROOM_PER_LEAN`]): a pure function of the
//! pattern, the stitch proportions (in yarn diameters) and that choice.

use crate::lattice::{Lattice, RowHeights};
use crate::pattern::StitchPattern;

/// Shortest a row may gather to, in regular rows: the plain stitches in a cable between its
/// crossings stay clear of each other down to rows of this height at the default proportions.
pub const SHORTEST: f32 = 0.75;

/// Candidate heights per column of lean (in stitch widths, see [`room_needed`]), in the
/// order the tuning tries them ([`super::tuning`]): the first is best on most presets, and
/// where its relieved patch falls short the others are tried and the best kept. Which one
/// clears best depends on the pattern and the stitch proportions in ways no single rule
/// caught (measured at the default gauge: 0.38 clears C4, horseshoe and honeycomb on all three
/// test surfaces and C6 on the sheet, 0.34 C6 on the cylinder; 0.3 and 0.46 are the fallbacks
/// that came closest elsewhere).
pub const ROOM_PER_LEAN: &[f32] = &[0.38, 0.34, 0.3, 0.46];

/// The height (in yarn diameters) a row needs for a loop leaning `lean` columns of `width`
/// diameters to clear its neighbours: `width (0.25 + per_lean lean)`.
pub fn room_needed(lean: usize, width: f32, per_lean: f32) -> f32 {
    if lean == 0 {
        return 0.0;
    }
    width * (0.25 + per_lean * lean as f32)
}

/// Whether any loop of `pattern` leans across columns.
pub fn leans(pattern: &StitchPattern) -> bool {
    (0..pattern.height())
        .any(|r| (0..pattern.width()).any(|w| pattern.stitch(r, w).land_offset != 0))
}

/// The row heights of `pattern` knitted with stitches `width x height` yarn diameters and
/// `per_lean` stitch widths of height per column of lean, or `None` where every row is tall
/// enough already (or no row can give any height away).
pub fn leaning_row_heights(
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    per_lean: f32,
) -> Option<RowHeights> {
    let (rows, cols) = (pattern.height(), pattern.width());
    if !(width.is_finite() && height.is_finite() && width > 0.0 && height > 0.0) {
        return None;
    }
    // The height each (row, node column) needs, in regular rows (0: no leaning loop).
    let mut need = vec![0.0f32; rows * cols];
    for r in 0..rows {
        for w in 0..cols {
            let s = pattern.stitch(r, w);
            if s.land_offset == 0 {
                continue;
            }
            let lean = s.land_offset.unsigned_abs() as usize;
            let h = room_needed(lean, width, per_lean) / height;
            let (lo, hi) = if s.land_offset > 0 {
                (w as isize, w as isize + s.land_offset as isize + 1)
            } else {
                (w as isize + s.land_offset as isize, w as isize + 1)
            };
            for c in lo..=hi {
                let c = c.rem_euclid(cols as isize) as usize;
                need[r * cols + c] = need[r * cols + c].max(h);
            }
        }
    }
    let mut heights = vec![1.0f32; rows * cols];
    for c in 0..cols {
        let tall: Vec<usize> = (0..rows).filter(|&r| need[r * cols + c] > 1.0).collect();
        let rest = rows - tall.len();
        if tall.is_empty() || rest == 0 {
            continue;
        }
        let extra: f32 = tall.iter().map(|&r| need[r * cols + c] - 1.0).sum();
        // The rest gather by `extra / rest` each, at most down to SHORTEST.
        let room = (1.0 - SHORTEST) * rest as f32;
        let scale = (room / extra).min(1.0);
        let given = extra * scale;
        for r in 0..rows {
            heights[r * cols + c] = if tall.contains(&r) {
                1.0 + (need[r * cols + c] - 1.0) * scale
            } else {
                1.0 - given / rest as f32
            };
        }
    }
    RowHeights::new(rows, cols, heights)
}

/// `lattice` with the row heights `pattern` asks for at stitches `width x height` diameters
/// and `per_lean` (see [`leaning_row_heights`]).
pub fn shaped(
    lattice: Lattice,
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    per_lean: f32,
) -> Lattice {
    match leaning_row_heights(pattern, width, height, per_lean) {
        Some(h) => lattice.with_row_heights(&h),
        None => lattice,
    }
}
