//! Stitch and colour patterns: what each stitch of the fabric is and what colour its yarn is.
//!
//! A pattern is a small chart repeated over the whole fabric, as knitters repeat a stitch
//! pattern across a row and up the piece. Coordinates: `course` counts rows from the bottom of
//! the fabric (v), `wale` counts columns from the left (u), as seen from the right side (RS,
//! the front, the side the surface normal points to).

mod chart;
mod color;
mod color_image;
pub mod instruction;
mod knitspeak;
mod presets;
pub mod rows;
mod stitch;
mod unknitted;
mod vocabulary;

pub use chart::parse_chart;
pub use color::ColorPattern;
pub use color_image::ColorImage;
pub use instruction::Instruction;
pub(crate) use knitspeak::lcm;
pub use knitspeak::{looks_like_knitspeak, parse_knitspeak};
pub use presets::{color_preset, COLOR_PRESETS, FAIR_ISLE_BAND, PRESETS};
pub use rows::WrittenRow;
pub use stitch::{Face, Form, Stitch};
pub use unknitted::unknitted;
pub use vocabulary::reads_stitch;

use crate::error::{KnitError, Result};

/// Widest repeat a pattern may have, in stitches. Real repeats are at most a few dozen
/// stitches (a whole Aran panel is under 100); the tuning and relief work grows with the
/// repeat, so the bound keeps every first knit bounded.
pub const MAX_PATTERN_WIDTH: usize = 256;
/// Most rows a pattern's repeat may have.
pub const MAX_PATTERN_ROWS: usize = 1024;

/// Refuses a repeat over [`MAX_PATTERN_WIDTH`] x [`MAX_PATTERN_ROWS`].
pub fn check_size(width: usize, height: usize) -> Result<()> {
    if width > MAX_PATTERN_WIDTH || height > MAX_PATTERN_ROWS {
        return Err(KnitError::Pattern(format!(
            "the pattern's repeat is {width} stitches x {height} rows; a repeat may be at most \
             {MAX_PATTERN_WIDTH} stitches x {MAX_PATTERN_ROWS} rows (for a picture in colour, \
             use a colour chart or image instead of a stitch chart)"
        )));
    }
    Ok(())
}

/// A stitch pattern: a `width x height` chart repeated over the fabric in both directions.
/// Invariant: `width >= 1`, `height >= 1`, `cells.len() == width * height`; row 0 is the
/// bottom row of the chart.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct StitchPattern {
    name: String,
    width: usize,
    height: usize,
    cells: Vec<Stitch>,
}

impl StitchPattern {
    /// Builds a pattern from rows given bottom row first. Every row must have the same width.
    pub fn from_rows(name: &str, rows_bottom_up: Vec<Vec<Stitch>>) -> Result<Self> {
        let height = rows_bottom_up.len();
        let width = rows_bottom_up.first().map_or(0, Vec::len);
        if height == 0 || width == 0 {
            return Err(KnitError::Pattern("the chart has no stitches".into()));
        }
        check_size(width, height)?;
        if let Some((i, r)) = rows_bottom_up
            .iter()
            .enumerate()
            .find(|(_, r)| r.len() != width)
        {
            return Err(KnitError::Pattern(format!(
                "row {} has {} stitches but row 1 has {width}: every chart row must be equally wide",
                i + 1,
                r.len()
            )));
        }
        Ok(Self {
            name: name.to_string(),
            width,
            height,
            cells: rows_bottom_up.into_iter().flatten().collect(),
        })
    }

    /// Builds a pattern from rows as written (instructions in working order, right or wrong
    /// side), checking that stitch counts balance (see [`rows`]).
    pub fn from_written_rows(name: &str, rows: &[WrittenRow]) -> Result<Self> {
        Self::from_rows(name, rows::cells_from_rows(rows)?)
    }

    /// Parses a text chart (see [`parse_chart`] for the symbols).
    pub fn from_chart(text: &str) -> Result<Self> {
        parse_chart(text)
    }

    /// Parses Knitspeak row instructions (see [`parse_knitspeak`] for what is supported).
    pub fn from_knitspeak(text: &str) -> Result<Self> {
        parse_knitspeak(text)
    }

    /// Knitspeak or a chart, told apart by content: Knitspeak starts with a row header (see
    /// [`looks_like_knitspeak`]).
    pub fn from_text(text: &str) -> Result<Self> {
        if looks_like_knitspeak(text) {
            parse_knitspeak(text)
        } else {
            parse_chart(text)
        }
    }

    /// A named preset (case, spaces and hyphens are ignored: "Rib 2x2" finds `rib_2x2`).
    pub fn preset(name: &str) -> Result<Self> {
        let key = normalise_name(name);
        let found = PRESETS.iter().find(|(n, _)| normalise_name(n) == key);
        match found {
            Some((n, text)) => {
                let mut p = if looks_like_knitspeak(text) {
                    parse_knitspeak(text)
                } else {
                    parse_chart(text)
                }
                .map_err(|e| KnitError::Internal(format!("preset {n}: {e}")))?;
                p.name = (*n).to_string();
                Ok(p)
            }
            None => Err(KnitError::Pattern(format!(
                "unknown preset {name:?}; presets are: {}",
                Self::presets().join(", ")
            ))),
        }
    }

    /// The names of the presets, in display order.
    pub fn presets() -> Vec<&'static str> {
        PRESETS.iter().map(|(n, _)| *n).collect()
    }

    pub fn name(&self) -> &str {
        &self.name
    }
    pub fn width(&self) -> usize {
        self.width
    }
    pub fn height(&self) -> usize {
        self.height
    }

    /// The pattern with every loop straight: no crossing, no gathering (each loop lands in
    /// its own column, in no layer), every stitch's face and form kept. This is what a piece
    /// knits where its edge cuts a crossing or a decrease ([`crate::skeleton::stitch_shape`]):
    /// the partial repeat worked plain, as a knitter works the stitches a repeat does not fit.
    pub fn straightened(&self) -> Self {
        let mut p = self.clone();
        p.name = format!("{} (straight)", self.name);
        for c in &mut p.cells {
            c.land_offset = 0;
            c.land_layer = 0;
        }
        p
    }

    /// The chart started `shift` columns further right: column `c` of the result is column
    /// `(c + shift) % width` of this one. The same fabric (offsets are relative), drawn from
    /// another column of its repeat.
    pub fn columns_rotated(&self, shift: usize) -> Self {
        let w = self.width;
        let mut p = self.clone();
        for (i, cell) in p.cells.iter_mut().enumerate() {
            let (row, col) = (i / w, i % w);
            *cell = self.cells[row * w + (col + shift) % w];
        }
        p
    }

    /// How many stitches reach across the boundary between columns `col - 1` and `col` (mod
    /// the width) to the loops they are pulled through: the crossings, gathers and leans a
    /// chart starting at `col` would cut at its edge.
    pub fn cuts_at_column(&self, col: usize) -> usize {
        let w = self.width as i64;
        let col = col as i64;
        self.cells
            .iter()
            .enumerate()
            .filter(|(_, c)| c.sources > 0)
            .filter(|&(i, c)| {
                let here = i as i64 % w;
                let first = here + i64::from(c.source_offset);
                let last = first + i64::from(c.sources) - 1;
                let (lo, hi) = (here.min(first), here.max(last));
                // A boundary `b` (between columns b - 1 and b) with lo < b <= hi, b = col mod w.
                let b = lo + 1 + (col - lo - 1).rem_euclid(w);
                b <= hi
            })
            .count()
    }

    /// The smallest repeat of the chart: the least `h x w` (dividing the height and the
    /// width) whose cells, repeated, give every cell of this one. A chart drawn as several
    /// repeats of one motif knits exactly as that motif.
    pub fn minimal_repeat(&self) -> Self {
        let divisors = |n: usize| (1..=n).filter(move |d| n % d == 0);
        let repeats = |h: usize, w: usize| {
            (0..self.height).all(|c| {
                (0..self.width).all(|x| {
                    self.cells[c * self.width + x] == self.cells[(c % h) * self.width + x % w]
                })
            })
        };
        let w = divisors(self.width)
            .find(|&w| repeats(self.height, w))
            .unwrap_or(self.width);
        let h = divisors(self.height)
            .find(|&h| repeats(h, w))
            .unwrap_or(self.height);
        let mut p = self.clone();
        p.width = w;
        p.height = h;
        p.cells = (0..h)
            .flat_map(|c| (0..w).map(move |x| (c, x)))
            .map(|(c, x)| self.cells[c * self.width + x])
            .collect();
        p
    }

    /// The faces of the first `rows x cols` cells as plain loops: every loop lands in the
    /// stitch above it (no crossing, decrease, yarn-over or slip), each cell keeping its face
    /// (knit or purl) and a twisted or bobble form. A stand-in that knits like the chart's
    /// mix of faces, for work that cannot afford the whole of a very large chart.
    pub fn plain_window(&self, rows: usize, cols: usize) -> Self {
        let (h, w) = (rows.clamp(1, self.height), cols.clamp(1, self.width));
        let mut p = self.clone();
        p.name = format!("{} ({w} x {h} plain window)", self.name);
        p.width = w;
        p.height = h;
        p.cells = (0..h)
            .flat_map(|c| (0..w).map(move |x| (c, x)))
            .map(|(c, x)| {
                let s = self.cells[c * self.width + x];
                Stitch {
                    form: match s.form {
                        Form::Twisted | Form::Bobble => s.form,
                        _ => Form::Plain,
                    },
                    source_offset: 0,
                    sources: 1,
                    land_offset: 0,
                    land_layer: 0,
                    rise: 0,
                    ..s
                }
            })
            .collect();
        p
    }

    /// Refuses what the skeleton cannot knit as the pattern says, naming where: a column
    /// whose loop is slipped in every row of the repeat. A slipped stitch carries the loop
    /// below it up a row ([`Stitch::rise`]), and slipped again, another
    /// (`skeleton::stitch_shape::carried_rise`: slip columns, mosaic knitting); slipped in
    /// every row, the loop would rise for ever and never be knitted, and knitting on would
    /// make another fabric. The pattern still reads and charts.
    pub fn check_knittable(&self) -> Result<()> {
        let (w, h) = (self.width(), self.height());
        for c in 0..w {
            // Follow the loop from the first row up through the stitches that slip it.
            let (mut col, mut rises) = (c, 0);
            while rises < h && self.stitch(rises, col).rise > 0 {
                let offset = isize::from(self.stitch(rises, col).land_offset);
                col = (col as isize + offset).rem_euclid(w as isize) as usize;
                rises += 1;
            }
            if rises == h {
                return Err(KnitError::Pattern(format!(
                    "column {} from the left (as seen on the right side) slips its stitch in \
                     every row of the repeat: its loop would be carried up for ever and never \
                     knitted; work that stitch in at least one row",
                    c + 1
                )));
            }
        }
        Ok(())
    }

    /// Whether every stitch is a knit or purl loop pulled through the loop straight below,
    /// its own loop landing straight above: nothing leans, gathers, slips, twists, makes a
    /// new loop or a bobble. Such a chart knits exactly as its
    /// [`plain_window`](Self::plain_window)s do, cell for cell.
    pub fn is_plain_loops(&self) -> bool {
        self.cells.iter().all(|c| {
            *c == Stitch {
                face: c.face,
                ..Stitch::KNIT
            }
        })
    }

    /// Whether any loop crosses or is gathered with another (a cable, a decrease).
    pub fn has_crossings(&self) -> bool {
        self.cells
            .iter()
            .any(|c| c.land_offset != 0 || c.land_layer != 0)
    }

    /// The columns, relative to `wale`, of the smallest run of stitches of its row that the
    /// loop of stitch (course, wale) crosses or is gathered with: `(lo, hi)` with
    /// `lo <= 0 <= hi`, such that every loop of columns `wale + lo ..= wale + hi` lands in
    /// that run and every loop landing in it comes from it (a cable's crossing, a decrease's
    /// loops). `(0, 0)` for a loop that neither leans nor is gathered. A piece of fabric that holds only part
    /// of a run cannot cross it (its loops would land on stitches that are not there, or on
    /// one another), so it knits the whole run straight.
    pub fn landing_group(&self, course: usize, wale: usize) -> (isize, isize) {
        let w = self.width as isize;
        let row = (course % self.height) * self.width;
        let lean = |x: isize| isize::from(self.cells[row + x.rem_euclid(w) as usize].land_offset);
        let own = self.cells[row + wale % self.width];
        if own.land_offset == 0 && own.land_layer == 0 {
            return (0, 0);
        }
        let reach = (0..self.width)
            .map(|x| self.cells[row + x].land_offset.unsigned_abs() as isize)
            .max()
            .unwrap_or(0);
        let x0 = wale as isize;
        let d0 = x0 + lean(x0);
        let (mut lo, mut hi) = (x0.min(d0), x0.max(d0));
        // Each pass widens the run to close it; it is closed within a few repeats, or the row
        // leans without end (then the loop is only held to its own landing column).
        for _ in 0..4 * self.width + 4 {
            let mut changed = false;
            for x in lo - reach..=hi + reach {
                let d = x + lean(x);
                if (lo..=hi).contains(&x) != (lo..=hi).contains(&d) {
                    lo = lo.min(x).min(d);
                    hi = hi.max(x).max(d);
                    changed = true;
                }
            }
            if !changed {
                return (lo - x0, hi - x0);
            }
        }
        (d0.min(x0) - x0, d0.max(x0) - x0)
    }

    /// The stitch at (course, wale) of the fabric, the chart repeated in both directions.
    pub fn stitch(&self, course: usize, wale: usize) -> Stitch {
        self.cells[(course % self.height) * self.width + wale % self.width]
    }

    /// The chart as text, top row first. A pattern of plain knit and purl stitches is drawn
    /// with `k` and `p` only; any other gets symbols and a legend (see [`chart`]). Either way
    /// [`StitchPattern::from_chart`] reads it back to an equal pattern.
    pub fn chart(&self) -> String {
        chart::write_chart(self)
    }

    /// Per chart row, bottom row first: (loops of the row below it works, stitches it makes).
    /// Every row of a pattern keeps its count, so both equal [`Self::width`]: this is the
    /// stitch-count conservation a parsed pattern guarantees, exposed for tests.
    pub fn stitch_counts(&self) -> Vec<(usize, usize)> {
        (0..self.height)
            .map(|r| {
                let row = &self.cells[r * self.width..(r + 1) * self.width];
                let worked = row.iter().map(|c| usize::from(c.sources)).sum();
                (worked, self.width)
            })
            .collect()
    }
}

fn normalise_name(name: &str) -> String {
    name.chars()
        .filter(|c| !matches!(c, ' ' | '-' | '_'))
        .flat_map(char::to_lowercase)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chart(rows: &[&str]) -> StitchPattern {
        StitchPattern::from_chart(&rows.join("\n")).unwrap()
    }

    #[test]
    fn the_smallest_repeat_of_a_tiled_chart_is_its_motif() {
        let motif = ["kkpp", "kkpp", "ppkk", "ppkk"];
        let tiled: Vec<String> = (0..3)
            .flat_map(|_| motif.iter().map(|r| r.repeat(3)))
            .collect();
        let tiled = chart(&tiled.iter().map(String::as_str).collect::<Vec<_>>());
        let m = tiled.minimal_repeat();
        assert_eq!((m.width(), m.height()), (4, 4));
        assert_eq!(m.chart(), chart(&motif).chart());
        // A chart with no smaller repeat is its own.
        let c4 = StitchPattern::preset("cable_c4").unwrap();
        assert_eq!(c4.minimal_repeat(), c4);
    }

    #[test]
    fn a_plain_window_keeps_faces_and_lets_every_loop_land_straight() {
        let lace = StitchPattern::preset("lace_diamond").unwrap();
        let w = lace.plain_window(3, 5);
        assert_eq!((w.width(), w.height()), (5, 3));
        for c in 0..3 {
            for x in 0..5 {
                let (s, o) = (w.stitch(c, x), lace.stitch(c, x));
                assert_eq!(s.face, o.face);
                assert_eq!(
                    (s.sources, s.source_offset, s.land_offset, s.land_layer),
                    (1, 0, 0, 0)
                );
                assert!(matches!(s.form, Form::Plain | Form::Twisted | Form::Bobble));
            }
        }
        assert!(!w.has_crossings());
    }

    #[test]
    fn repeats_over_the_limit_are_refused() {
        assert!(check_size(MAX_PATTERN_WIDTH, MAX_PATTERN_ROWS).is_ok());
        let e = check_size(MAX_PATTERN_WIDTH + 1, 1)
            .unwrap_err()
            .to_string();
        assert!(e.contains("257 stitches"), "{e}");
        assert!(check_size(1, MAX_PATTERN_ROWS + 1).is_err());
    }
}
