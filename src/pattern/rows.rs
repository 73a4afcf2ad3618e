//! From rows as knitters write them (instructions in working order, right or wrong side) to
//! the chart of cells the skeleton builds: each stitch as it shows on the right side, where
//! its loop came from and where its own loop lands in the row above.
//!
//! Stitch counts: the chart repeats up the fabric and across it, so the loops a row leaves on
//! the needle (stitches-out) must be the loops the next row works (stitches-in), and the last
//! row's must be the first row's. The fabric is knitted on a lattice of a fixed number of
//! columns, so every row must also keep its count: a lace row balances each yarn-over with a
//! decrease in the same row, as nearly all lace does.

use super::instruction::{Instruction, Worked};
use super::knitspeak::shorter_way;
use super::stitch::{Face, Form, Stitch};
use crate::error::{KnitError, Result};

/// A row as written: its instructions in working order (the order they are read out).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WrittenRow {
    /// The row's number in the pattern (1 is the first row knitted), for messages.
    pub number: usize,
    /// Worked from the right side. A wrong-side row is worked from the back, left to right as
    /// seen from the front, and each of its stitches shows reversed on the front.
    pub right_side: bool,
    pub instructions: Vec<Instruction>,
}

impl WrittenRow {
    pub fn stitches_in(&self) -> usize {
        self.instructions.iter().map(|i| i.stitches_in()).sum()
    }
    pub fn stitches_out(&self) -> usize {
        self.instructions.iter().map(|i| i.stitches_out()).sum()
    }
}

/// Furthest a loop may travel between its own column and the one it lands in, in columns.
pub const MAX_TRAVEL: usize = 24;

/// The chart cells of `rows` (bottom row first, each row left to right as seen from the
/// right side). Errors name the row and both counts when stitch counts do not balance.
pub fn cells_from_rows(rows: &[WrittenRow]) -> Result<Vec<Vec<Stitch>>> {
    let h = rows.len();
    if h == 0 {
        return Err(KnitError::Pattern("the pattern has no rows".into()));
    }
    for row in rows {
        if row.instructions.is_empty() {
            return Err(KnitError::Pattern(format!(
                "Row {}: no stitches",
                row.number
            )));
        }
    }
    // A row that changes its own count first: that is the cause, and the row after it may be
    // one the text never wrote (flat knitting turned over, numbered on from the last).
    for row in rows {
        let (i, o) = (row.stitches_in(), row.stitches_out());
        if i != o {
            return Err(KnitError::Pattern(format!(
                "Row {} turns {i} stitches into {o}: knitwear keeps every row's stitch count, \
                 so a row's increases must be balanced by decreases in the same row",
                row.number
            )));
        }
    }
    for (r, row) in rows.iter().enumerate() {
        let next = &rows[(r + 1) % h];
        let (out, next_in) = (row.stitches_out(), next.stitches_in());
        if out != next_in {
            let wrap = if r + 1 == h {
                format!(" (the pattern repeats, so row {} follows it)", next.number)
            } else {
                String::new()
            };
            return Err(KnitError::Pattern(format!(
                "stitch counts do not balance: Row {} leaves {out} stitches but Row {} works \
                 {next_in}{wrap}",
                row.number, next.number
            )));
        }
    }
    let width = rows[0].stitches_in();
    let mut cells = vec![vec![Stitch::KNIT; width]; h];
    for (r, row) in rows.iter().enumerate() {
        let below = (r + h - 1) % h;
        // Place each instruction's stitches and loops; `pos` runs along the row in working
        // order: right to left on the right side, left to right on the wrong side.
        let mut pos_in = 0usize;
        let mut pos_out = 0usize;
        for ins in &row.instructions {
            let worked = oriented(ins.worked(), row.right_side);
            let (n_in, n_out) = (worked.loops.len(), worked.made.len());
            let (base_in, base_out) = if row.right_side {
                (width - pos_in - n_in, width - pos_out - n_out)
            } else {
                (pos_in, pos_out)
            };
            pos_in += n_in;
            pos_out += n_out;
            for (k, made) in worked.made.iter().enumerate() {
                let c = base_out + k;
                cells[r][c].face = made.face;
                cells[r][c].form = made.form;
                cells[r][c].sources = made.sources as u8;
                cells[r][c].source_offset = if made.sources == 0 {
                    0
                } else {
                    travel(base_in + made.first_source, c, width, row, ins)?
                };
            }
            for (k, fate) in worked.loops.iter().enumerate() {
                let s = base_in + k;
                let c = base_out + fate.made_by;
                let lands = travel(c, s, width, row, ins)?;
                let cell = &mut cells[below][s];
                cell.land_offset = lands;
                cell.land_layer = fate.layer;
                cell.rise = u8::from(matches!(worked.made[fate.made_by].form, Form::Slip { .. }));
            }
        }
    }
    Ok(cells)
}

/// An instruction's effect in right-side order: as worked on the right side, or mirrored for
/// a wrong-side row (its left and right swap, what was in front is behind, a knit shows as a
/// purl and a yarn held in front is behind the fabric).
fn oriented(w: Worked, right_side: bool) -> Worked {
    if right_side {
        return w;
    }
    let (n_in, n_out) = (w.loops.len(), w.made.len());
    let mut made: Vec<_> = w
        .made
        .iter()
        .rev()
        .map(|m| {
            let mut m = *m;
            m.face = match m.face {
                Face::Knit => Face::Purl,
                Face::Purl => Face::Knit,
            };
            if let Form::Slip { yarn_front } = m.form {
                m.form = Form::Slip {
                    yarn_front: !yarn_front,
                };
            }
            if m.sources > 0 {
                m.first_source = n_in - m.first_source - m.sources;
            }
            m
        })
        .collect();
    // A yarn-over or a made stitch has no face of its own: the next row works it.
    for m in &mut made {
        if m.sources == 0 {
            m.face = Face::Knit;
        }
    }
    let loops = w
        .loops
        .iter()
        .rev()
        .map(|f| {
            let mut f = *f;
            f.made_by = n_out - 1 - f.made_by;
            f.layer = -f.layer;
            f
        })
        .collect();
    Worked { made, loops }
}

/// The column offset from `from` to `to` along a row of `width` columns that repeats, the
/// shorter way round (half the row either way: the way the instruction moves it).
fn travel(to: usize, from: usize, width: usize, row: &WrittenRow, ins: &Instruction) -> Result<i8> {
    let d = shorter_way(to as i64 - from as i64, width);
    if d.unsigned_abs() as usize > MAX_TRAVEL {
        return Err(KnitError::Pattern(format!(
            "Row {}, \"{}\": a loop would travel {} columns; knitwear lets loops lean at most \
             {MAX_TRAVEL}",
            row.number,
            ins.name(),
            d.abs()
        )));
    }
    Ok(d as i8)
}
