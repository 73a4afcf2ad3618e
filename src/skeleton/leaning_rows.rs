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

use super::stitch_shape::{landing, wale_knits_whole};
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
/// enough already (or no row can give any height away). One repeat wide: node column `c` is
/// the line between pattern columns `c - 1` and `c`.
pub fn leaning_row_heights(
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    per_lean: f32,
) -> Option<RowHeights> {
    let need = pattern_needs(pattern, width, height, per_lean)?;
    heights_from_needs(pattern.height(), pattern.width(), &need)
}

/// The row heights of a whole piece knitted on `lattice` (not a window): the pattern's
/// ([`leaning_row_heights`]) repeated, one node column per node column of the lattice, except
/// on the node lines of wales the piece knits straight ([`wale_knits_whole`]: its edge cuts
/// a crossing or a decrease there), which take only what the piece's own loops need
/// ([`landing`]): regular rows where nothing leans. With `mark_leaning`, the heights also
/// know which node columns leaning loops join ([`RowHeights::leaning`]).
pub fn fabric_row_heights(
    lattice: &Lattice,
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    per_lean: f32,
    mark_leaning: bool,
) -> Option<RowHeights> {
    let (rows, cols) = (pattern.height(), pattern.width());
    let periodic = pattern_needs(pattern, width, height, per_lean)?;
    let marked = |heights: RowHeights, cols: usize, need: &[f32]| {
        if mark_leaning {
            heights.leaning(leaning_columns(rows, cols, need))
        } else {
            Some(heights)
        }
    };
    let wales = lattice.wales;
    let straight: Vec<usize> = (0..wales)
        .filter(|&w| !wale_knits_whole(lattice, pattern, w))
        .collect();
    if straight.is_empty() {
        return marked(heights_from_needs(rows, cols, &periodic)?, cols, &periodic);
    }
    let node_cols = if lattice.cyclic_u { wales } else { wales + 1 };
    let own = needs(
        rows,
        wales,
        node_cols,
        |r, w| landing(lattice, pattern, r, w) - w as isize,
        width,
        height,
        per_lean,
    );
    let mut need: Vec<f32> = (0..rows * node_cols)
        .map(|i| periodic[(i / node_cols) * cols + (i % node_cols) % cols])
        .collect();
    for w in straight {
        for c in [w, (w + 1) % node_cols] {
            for r in 0..rows {
                need[r * node_cols + c] = own[r * node_cols + c];
            }
        }
    }
    marked(
        heights_from_needs(rows, node_cols, &need)?,
        node_cols,
        &need,
    )
}

/// The height each (row, node column) of one repeat of `pattern` needs (see [`needs`]), or
/// `None` for proportions that are not finite and positive.
fn pattern_needs(
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    per_lean: f32,
) -> Option<Vec<f32>> {
    if !(width.is_finite() && height.is_finite() && width > 0.0 && height > 0.0) {
        return None;
    }
    let cols = pattern.width();
    Some(needs(
        pattern.height(),
        cols,
        cols,
        |r, w| isize::from(pattern.stitch(r, w).land_offset),
        width,
        height,
        per_lean,
    ))
}

/// The height, in regular rows, each (row, node column) needs for `rows` rows of `stitches`
/// columns whose loop at (row, column) leans `lean(row, column)` columns (0: no leaning loop
/// there), row-major over `node_cols` node columns; a node column past the last wraps round
/// to the first (`node_cols == stitches` is cyclic).
fn needs(
    rows: usize,
    stitches: usize,
    node_cols: usize,
    lean: impl Fn(usize, usize) -> isize,
    width: f32,
    height: f32,
    per_lean: f32,
) -> Vec<f32> {
    let cols = node_cols;
    let mut need = vec![0.0f32; rows * cols];
    for r in 0..rows {
        for w in 0..stitches {
            let offset = lean(r, w);
            if offset == 0 {
                continue;
            }
            let h = room_needed(offset.unsigned_abs(), width, per_lean) / height;
            let (lo, hi) = if offset > 0 {
                (w as isize, w as isize + offset + 1)
            } else {
                (w as isize + offset, w as isize + 1)
            };
            for c in lo..=hi {
                let c = c.rem_euclid(cols as isize) as usize;
                need[r * cols + c] = need[r * cols + c].max(h);
            }
        }
    }
    need
}

/// Row heights from what each (row, node column) needs ([`needs`]): the rows that need more
/// than a regular row get it and the rest of the column gathers to pay for it.
fn heights_from_needs(rows: usize, cols: usize, need: &[f32]) -> Option<RowHeights> {
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

/// Per node column of `need` (`rows x cols`, see [`needs`]): whether a loop leans across it or
/// stands on it in some row.
fn leaning_columns(rows: usize, cols: usize, need: &[f32]) -> Vec<bool> {
    (0..cols)
        .map(|c| (0..rows).any(|r| need[r * cols + c] > 0.0))
        .collect()
}

/// How a lattice whose courses end inside a repeat of rows ramps the remainder out
/// ([`RowHeights::node_displacements`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ramp {
    /// Every column alike: the patches and strips the loop shapes are tuned and relieved on,
    /// which only stand for the body of the fabric.
    Alike,
    /// By blocks of the node columns that leaning loops join ([`RowHeights::leaning`]): a
    /// piece's own lattice, where a column no loop leans across keeps regular rows up to its
    /// top, level with the cable beside it, and the bind-off runs flat over it. Its body's
    /// tiles are those of [`Ramp::Alike`] up to a shear of the remainder (at most a row)
    /// spread over all its courses.
    ByBlock,
}

/// `lattice` with the row heights `pattern` asks for at stitches `width x height` diameters
/// and `per_lean` (see [`leaning_row_heights`]), the remainder of a repeat ramped out as
/// `ramp` says (a window's always alike).
pub fn shaped(
    lattice: Lattice,
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    per_lean: f32,
    ramp: Ramp,
) -> Lattice {
    let heights = if lattice.window {
        leaning_row_heights(pattern, width, height, per_lean)
    } else {
        fabric_row_heights(
            &lattice,
            pattern,
            width,
            height,
            per_lean,
            ramp == Ramp::ByBlock,
        )
    };
    match heights {
        Some(h) => lattice.with_row_heights(&h),
        None => lattice,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::UvRect;
    use glam::Vec2;

    fn lattice(wales: usize, cyclic_u: bool) -> Lattice {
        let domain = UvRect {
            min: Vec2::ZERO,
            max: Vec2::new(wales as f32, 28.0),
        };
        Lattice::regular(domain, 28, wales, cyclic_u, false)
    }

    #[test]
    fn a_cut_repeat_keeps_regular_rows_and_whole_ones_the_patterns() {
        let pattern = StitchPattern::preset("feather_and_fan").unwrap();
        let (w, h, k) = (5.0, 3.5, ROOM_PER_LEAN[0]);
        let own = leaning_row_heights(&pattern, w, h, k).unwrap();
        // 24 wales: one whole 18-stitch repeat, then 6 whose decreases the edge cuts.
        let cut = lattice(24, false);
        assert!((0..18).all(|x| wale_knits_whole(&cut, &pattern, x)));
        assert!((18..24).all(|x| !wale_knits_whole(&cut, &pattern, x)));
        let fabric = fabric_row_heights(&cut, &pattern, w, h, k, true).unwrap();
        for r in 0..pattern.height() {
            // The node lines of the whole repeat's wales keep the pattern's heights (line 18
            // borders a cut wale and takes only what the whole repeat's loops need there).
            for c in 0..18 {
                assert_eq!(fabric.height(r, c), own.height(r, c), "row {r} line {c}");
            }
            // Nothing leans in the cut wales: regular rows.
            for c in 19..=24 {
                assert_eq!(fabric.height(r, c), 1.0, "row {r} line {c}");
            }
        }
        // Whole repeats (here round a tube): the pattern's heights, repeated.
        let whole = lattice(36, true);
        assert!((0..36).all(|x| wale_knits_whole(&whole, &pattern, x)));
        let fabric = fabric_row_heights(&whole, &pattern, w, h, k, true).unwrap();
        for r in 0..pattern.height() {
            for c in 0..36 {
                assert_eq!(fabric.height(r, c), own.height(r, c % 18));
            }
        }
    }

    #[test]
    fn straightened_patterns_do_not_lean() {
        let pattern = StitchPattern::preset("cable_c6").unwrap();
        assert!(pattern.has_crossings() && leans(&pattern));
        let straight = pattern.straightened();
        assert!(!straight.has_crossings() && !leans(&straight));
        assert_eq!(straight.width(), pattern.width());
        for r in 0..pattern.height() {
            for w in 0..pattern.width() {
                assert_eq!(straight.stitch(r, w).face, pattern.stitch(r, w).face);
                assert_eq!(straight.stitch(r, w).form, pattern.stitch(r, w).form);
            }
        }
        assert!(leaning_row_heights(&straight, 5.0, 3.5, ROOM_PER_LEAN[0]).is_none());
    }
}
