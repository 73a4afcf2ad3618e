//! Uneven row heights: a lattice whose rows are taller in some columns and shorter in others,
//! repeating with the pattern.
//!
//! A loop that leans across columns (a cable, a decrease) runs nearly flat in a row as short
//! as a plain one, and its legs come closer than a yarn diameter to each other and to the
//! loops it crosses. Knitted fabric makes room by itself: the crossed stitches stretch tall
//! and the plain rows of the cable above and below them gather up, so the cable stands
//! puckered in the fabric. [`RowHeights`] gives the lattice that shape: per pattern row and
//! node column, a tile height in tile units, each node column's heights summing to the
//! pattern's row count so that over one repeat of rows the lattice returns to the regular
//! one and the fabric keeps its size.

/// Tile heights per pattern row and node column, in units of the regular tile height.
///
/// Invariants: `heights.len() == rows * cols`; every height is positive and finite; each
/// column's heights sum to `rows` (up to rounding), so node rows a whole repeat apart are
/// as far apart as on the regular lattice; `leaning.len() == cols`.
#[derive(Debug, Clone, PartialEq)]
pub struct RowHeights {
    rows: usize,
    cols: usize,
    /// Row-major: `heights[row * cols + col]` is the height of pattern row `row` at node
    /// column `col` (the line between wale `col - 1` and wale `col`, modulo `cols`).
    heights: Vec<f32>,
    /// Per node column: whether a loop leans across it or onto it in some row (see
    /// [`RowHeights::leaning`]). All true unless told otherwise.
    leaning: Vec<bool>,
}

impl RowHeights {
    /// Heights `rows x cols`, row-major. `None` unless the invariants hold, or if every height
    /// is 1 (the regular lattice).
    pub fn new(rows: usize, cols: usize, heights: Vec<f32>) -> Option<Self> {
        if rows == 0 || cols == 0 || heights.len() != rows * cols {
            return None;
        }
        if heights.iter().any(|h| !(h.is_finite() && *h > 0.0)) {
            return None;
        }
        for c in 0..cols {
            let sum: f32 = (0..rows).map(|r| heights[r * cols + c]).sum();
            if (sum - rows as f32).abs() > 1e-3 * rows as f32 {
                return None;
            }
        }
        if heights.iter().all(|&h| h == 1.0) {
            return None;
        }
        Some(Self {
            rows,
            cols,
            leaning: vec![true; cols],
            heights,
        })
    }

    /// These heights, told which node columns a leaning loop crosses or stands on in some
    /// row (`leaning[col]`, one per column). A run of such columns keeps its rows' shape as
    /// one block where the courses end inside a repeat ([`Self::node_displacements`]), and
    /// a column no loop leans across keeps regular rows up to the top of the fabric. Without
    /// it, every column is taken to be leant across. `None` if `leaning` is not one per
    /// column.
    pub fn leaning(mut self, leaning: Vec<bool>) -> Option<Self> {
        if leaning.len() != self.cols {
            return None;
        }
        self.leaning = leaning;
        Some(self)
    }

    /// The height of course `course` at node column `col` (both repeating).
    pub fn height(&self, course: usize, col: usize) -> f32 {
        self.heights[(course % self.rows) * self.cols + col % self.cols]
    }

    /// How far node row `r` of node column `col` lies from its regular place, in rows:
    /// the sum of (height - 1) of the courses below it.
    fn displacement(&self, r: usize, col: usize) -> f64 {
        // Whole repeats add nothing: each column sums to `rows`.
        (0..r % self.rows)
            .map(|i| f64::from(self.height(i, col)) - 1.0)
            .sum()
    }

    /// The displacement (in rows) of every node `(r, c)` of a lattice of `courses` courses
    /// and `wales` wales, row-major `(courses + 2) x (wales + 1)`. The first node row stays
    /// where it is. Where the courses end inside a repeat, the remainder is spread evenly over
    /// the rows below so that row `courses` (the top of the last course) stays on the fabric:
    ///
    /// - along a cyclic v, column by column, so that row `courses` is row 0 a period on, and
    ///   row `courses + 1` repeats row 1;
    /// - along an open v, by the same amount in every column of a block of node columns that
    ///   leaning loops join (a run of columns some loop leans across or onto,
    ///   [`Self::leaning`]): the most any column of the block has over, so that every row of
    ///   the block keeps the pattern's shape. A column-by-column ramp shears the columns
    ///   against each other by up to the whole remainder at the top, where a loop leaning
    ///   three columns then lands a third of a row off (feather and fan's top course on the
    ///   test sleeve measured 0.945 diameters, against 0.953 or more on its courses below).
    ///   A block's top row is then scalloped, lower in columns that had less over, as the
    ///   cast-off edge of a lace is. A column no loop leans across has regular rows and
    ///   nothing over, and keeps them up to the top: ramped with the cable beside it, its
    ///   top stood lower by the cable's whole remainder (half a row and more) in one tile
    ///   beside the cable, and the bind-off loops over that step curled over each other
    ///   (C6's sheet: 8 crossings of its bind-off with itself). Row `courses + 1` follows
    ///   the top row a regular row up, so the last course's heads stand their usual height
    ///   above it.
    ///
    /// `cyclic_u`: node column `wales` is column 0 (a block may run across the seam).
    pub fn node_displacements(
        &self,
        courses: usize,
        wales: usize,
        cyclic_u: bool,
        cyclic_v: bool,
    ) -> Vec<f32> {
        let cols = wales + 1;
        let last = courses;
        let ends: Vec<f64> = (0..cols).map(|c| self.displacement(last, c)).collect();
        let block_ends = self.block_ends(&ends, cyclic_u);
        let mut d = vec![0.0f32; (courses + 2) * cols];
        for (c, &own_end) in ends.iter().enumerate() {
            let end = if cyclic_v { own_end } else { block_ends[c] };
            for r in 0..=last {
                let ramp = if last == 0 {
                    0.0
                } else {
                    end * r as f64 / last as f64
                };
                d[r * cols + c] = (self.displacement(r, c) - ramp) as f32;
            }
            d[(courses + 1) * cols + c] = if cyclic_v {
                if courses >= 1 {
                    d[cols + c]
                } else {
                    0.0
                }
            } else {
                d[courses * cols + c]
            };
        }
        d
    }

    /// Per node column (`ends.len()` of them, the last being column 0 again where
    /// `cyclic_u`), the most that any column of its block has over at the top (`ends`): a
    /// block is a run of consecutive leant-across columns, and a column no loop leans
    /// across is a block of its own.
    fn block_ends(&self, ends: &[f64], cyclic_u: bool) -> Vec<f64> {
        let n = ends.len();
        let leaning = |c: usize| self.leaning[c % self.cols];
        // Block ids: a new block starts at every column not joined to the one before it.
        let mut id = vec![0usize; n];
        for c in 1..n {
            let joined = leaning(c) && leaning(c - 1);
            id[c] = if joined { id[c - 1] } else { id[c - 1] + 1 };
        }
        // Round a cyclic u, the last column is the first: their blocks are one.
        let wrap = cyclic_u && n > 1;
        let merged = |i: usize| if wrap && i == id[n - 1] { 0 } else { i };
        let mut most = vec![0.0f64; id[n - 1] + 1];
        for c in 0..n {
            let b = merged(id[c]);
            most[b] = most[b].max(ends[c]);
        }
        (0..n).map(|c| most[merged(id[c])]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heights_must_sum_to_the_rows() {
        assert!(RowHeights::new(2, 1, vec![1.5, 0.5]).is_some());
        assert!(RowHeights::new(2, 1, vec![1.5, 0.6]).is_none());
        assert!(RowHeights::new(2, 1, vec![2.0, 0.0]).is_none());
        assert!(RowHeights::new(2, 1, vec![1.0, 1.0]).is_none());
        assert!(RowHeights::new(2, 2, vec![1.0; 3]).is_none());
    }

    #[test]
    fn whole_repeats_come_back_to_the_regular_rows() {
        let h = RowHeights::new(4, 2, vec![1.6, 1.0, 0.8, 1.0, 0.8, 1.0, 0.8, 1.0]).unwrap();
        let d = h.node_displacements(8, 3, false, false);
        let at = |r: usize, c: usize| d[r * 4 + c];
        // Column 1 (and 3, a repeat on) is regular; column 0's rows stretch and gather.
        for r in 0..10 {
            assert_eq!(at(r, 1), 0.0);
            assert_eq!(at(r, 3), 0.0);
        }
        // 8 courses (two whole repeats): the first and last rows stay put.
        assert_eq!(at(0, 0), 0.0);
        assert!(at(8, 0).abs() < 1e-6);
        assert_eq!(at(9, 0), 0.0);
        assert!((at(1, 0) - 0.6).abs() < 1e-5, "{}", at(1, 0));
        // 7 courses: the partial repeat's remainder (rows 4..6 of column 0 are 1.6, 0.8, 0.8
        // tall: 0.2 over at row 7) is spread evenly over the rows below.
        let d7 = h.node_displacements(7, 3, false, false);
        let end = 0.6 - 0.2 * 2.0;
        assert!(d7[7 * 4].abs() < 1e-6);
        assert!((d7[4] - (0.6 - end / 7.0)).abs() < 1e-5, "{}", d7[4]);
        // Along an open v every column ramps by the most any has over (0.2 rows, column 0's),
        // so the regular column 1 keeps regular rows, a little shorter, and its top row ends
        // that much lower (a scalloped top); row `courses + 1` follows the top row.
        assert!((d7[4 + 1] + 0.2 / 7.0).abs() < 1e-6, "{}", d7[4 + 1]);
        assert!((d7[7 * 4 + 1] + 0.2).abs() < 1e-6);
        for c in 0..4 {
            assert_eq!(d7[8 * 4 + c], d7[7 * 4 + c]);
            assert!(d7[7 * 4 + c] <= 1e-6);
        }
        // Tile heights stay positive.
        for r in 0..9 {
            assert!(1.0 + at(r + 1, 0) - at(r, 0) > 0.5);
        }
        // Cyclic v: row `courses` stays, row `courses + 1` repeats row 1, column by column.
        let c7 = h.node_displacements(7, 3, false, true);
        assert!(c7[7 * 4].abs() < 1e-6);
        assert_eq!(c7[7 * 4 + 1], 0.0);
        assert_eq!(c7[8 * 4], c7[4]);
        let d = h.node_displacements(8, 3, false, true);
        assert_eq!(d[8 * 4], 0.0);
        assert_eq!(d[9 * 4], d[4]);
    }

    #[test]
    fn a_column_no_loop_leans_across_keeps_regular_rows_to_the_top() {
        // Column 0 stretches and gathers (a cable's), column 1 beside it is regular.
        let heights = vec![1.6, 1.0, 0.8, 1.0, 0.8, 1.0, 0.8, 1.0];
        let h = RowHeights::new(4, 2, heights.clone())
            .unwrap()
            .leaning(vec![true, false])
            .unwrap();
        assert!(RowHeights::new(4, 2, heights)
            .unwrap()
            .leaning(vec![true])
            .is_none());
        // 7 courses: columns 0 and 2 have 0.2 rows over at the top, and ramp by their own.
        let d = h.node_displacements(7, 3, false, false);
        for r in 0..9 {
            assert_eq!(d[r * 4 + 1], 0.0, "row {r}");
            assert_eq!(d[r * 4 + 3], 0.0, "row {r}");
        }
        for c in [0, 2] {
            assert!(d[7 * 4 + c].abs() < 1e-6);
            assert!((d[4 + c] - (0.6 - 0.2 / 7.0)).abs() < 1e-5, "{}", d[4 + c]);
        }
    }

    #[test]
    fn a_block_of_leant_across_columns_ramps_as_one_and_wraps_round_a_cyclic_u() {
        // Columns 0 and 2 lean (over at the top of 2 courses: 0.4 and 0.6 rows), 1 does not.
        #[rustfmt::skip]
        let heights = vec![
            1.6, 1.0, 1.9,
            0.8, 1.0, 0.7,
            0.8, 1.0, 0.7,
            0.8, 1.0, 0.7,
        ];
        let h = RowHeights::new(4, 3, heights)
            .unwrap()
            .leaning(vec![true, false, true])
            .unwrap();
        let at = |d: &[f32], r: usize, c: usize| d[r * 4 + c];
        // Open u: node column 3 (pattern column 0) joins column 2's block, and both end the
        // block's most (0.6) lower; column 0, a block of its own, ends on the top.
        let open = h.node_displacements(2, 3, false, false);
        assert!(at(&open, 2, 0).abs() < 1e-6);
        assert!((at(&open, 2, 2)).abs() < 1e-6);
        assert!((at(&open, 2, 3) + 0.2).abs() < 1e-6, "{}", at(&open, 2, 3));
        assert_eq!(at(&open, 2, 1), 0.0);
        // Round a cyclic u column 3 is column 0: one block across the seam, the same nodes.
        let round = h.node_displacements(2, 3, true, false);
        for r in 0..4 {
            assert_eq!(at(&round, r, 3), at(&round, r, 0), "row {r}");
        }
        assert!(
            (at(&round, 2, 0) + 0.2).abs() < 1e-6,
            "{}",
            at(&round, 2, 0)
        );
    }
}
