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
/// as far apart as on the regular lattice.
#[derive(Debug, Clone, PartialEq)]
pub struct RowHeights {
    rows: usize,
    cols: usize,
    /// Row-major: `heights[row * cols + col]` is the height of pattern row `row` at node
    /// column `col` (the line between wale `col - 1` and wale `col`, modulo `cols`).
    heights: Vec<f32>,
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
            heights,
        })
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
    /// - along an open v, by the same amount in every column (the most any column has over),
    ///   so that every row keeps the pattern's shape: a column-by-column ramp shears the
    ///   columns against each other by up to the whole remainder at the top, where a loop
    ///   leaning three columns then lands a third of a row off (feather and fan's top
    ///   course on the test sleeve measured 0.945 diameters, against 0.953 or more on its
    ///   courses below). The top row is then scalloped, lower in columns that had less over,
    ///   as the cast-off edge of a cable or a lace is; row `courses + 1` follows it a
    ///   regular row up, so the last course's heads stand their usual height above it.
    pub fn node_displacements(&self, courses: usize, wales: usize, cyclic_v: bool) -> Vec<f32> {
        let cols = wales + 1;
        let last = courses;
        let ends: Vec<f64> = (0..cols).map(|c| self.displacement(last, c)).collect();
        let highest = ends.iter().copied().fold(0.0f64, f64::max);
        let mut d = vec![0.0f32; (courses + 2) * cols];
        for (c, &own_end) in ends.iter().enumerate() {
            let end = if cyclic_v { own_end } else { highest };
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
        let d = h.node_displacements(8, 3, false);
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
        let d7 = h.node_displacements(7, 3, false);
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
        let c7 = h.node_displacements(7, 3, true);
        assert!(c7[7 * 4].abs() < 1e-6);
        assert_eq!(c7[7 * 4 + 1], 0.0);
        assert_eq!(c7[8 * 4], c7[4]);
        let d = h.node_displacements(8, 3, true);
        assert_eq!(d[8 * 4], 0.0);
        assert_eq!(d[9 * 4], d[4]);
    }
}
