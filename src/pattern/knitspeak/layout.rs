//! From rows to one repeat: the rows, each with its side and body, laid out on a notional
//! piece as a knitter works them, and the chart cut from it ([`lay_out`]; the module docs of
//! [`super`] say how the repeats are phased). Also the repeat arithmetic the chart reader
//! shares: [`normalised`], [`wrap`], [`lcm`].

use super::body::{Body, Until};
use super::width_note::WidthNote;
use super::MAX_KNITSPEAK_WIDTH;
use crate::error::{KnitError, Result};
use crate::pattern::instruction::Instruction;
use crate::pattern::rows::{cells_from_rows, WrittenRow};
use crate::pattern::vocabulary::Stitched;
use crate::pattern::{Stitch, StitchPattern};

/// A row to lay out: its number for messages, side, header and body.
pub(super) struct RowPlan<'a> {
    pub number: usize,
    pub right_side: bool,
    pub what: &'a str,
    pub body: &'a Body,
}

impl RowPlan<'_> {
    /// The instructions of `v` as worked on this row's side.
    fn resolve(&self, v: &[Stitched]) -> Vec<Instruction> {
        v.iter().map(|s| s.on_side(self.right_side)).collect()
    }
    /// Loops of the row below that `v` works.
    fn ins_in(&self, v: &[Stitched]) -> usize {
        v.iter().map(|s| s.ins.stitches_in()).sum()
    }
    /// Stitches worked outside an open repeat, and the repeat's width (`None`: a fixed row).
    fn widths(&self) -> (usize, Option<usize>) {
        self.body.widths()
    }
    /// The row over a piece `n` stitches wide, in working order.
    fn over(&self, n: usize) -> Vec<Instruction> {
        self.resolve(&self.body.over(n))
    }
    /// The widths this row fits, for messages.
    fn describe_width(&self) -> String {
        match self.widths() {
            (e, None) => format!("{e} stitches"),
            (0, Some(w)) => format!("a multiple of {w} stitches"),
            (e, Some(w)) => format!("a multiple of {w} stitches plus {e}"),
        }
    }
}

/// Lays the rows out on a piece and cuts one repeat (see the module docs of [`super`]).
/// `widths`: the text's width notes, each with where it was written, which the widths the
/// rows fit must agree with.
pub(super) fn lay_out(rows: &[RowPlan], widths: &[(String, WidthNote)]) -> Result<StitchPattern> {
    for row in rows {
        if let Some((unit, until)) = &row.body.repeat {
            let w = row.ins_in(unit);
            if w == 0 {
                return Err(KnitError::Pattern(format!(
                    "{}: the repeat works no stitches of the row below, so it cannot fill the row",
                    row.what
                )));
            }
            if let Until::Last(n) = until {
                let after = row.ins_in(&row.body.after);
                if after != *n {
                    let (to, left) = match n {
                        1 => ("to last st".to_string(), "1 stitch".to_string()),
                        n => (format!("to last {n} sts"), format!("{n} stitches")),
                    };
                    let follow = match after {
                        0 => "no stitches follow it: write what is worked in them".to_string(),
                        1 => "1 stitch follows it".to_string(),
                        a => format!("{a} stitches follow it"),
                    };
                    return Err(KnitError::Pattern(format!(
                        "{}: the repeat runs \"{to}\", leaving {left}, but {follow}",
                        row.what
                    )));
                }
            }
        }
    }
    // A row of a fixed width makes the chart a panel.
    if let Some(fixed) = rows.iter().find(|r| r.widths().1.is_none()) {
        let n = fixed.widths().0;
        if n > MAX_KNITSPEAK_WIDTH {
            return Err(KnitError::Pattern(format!(
                "{}: {n} stitches is wider than the {MAX_KNITSPEAK_WIDTH} a chart may be",
                fixed.what
            )));
        }
        for (note, w) in widths {
            let agrees = match *w {
                WidthNote::Over(m) => m == n,
                WidthNote::Multiple { multiple, plus } => n >= plus && (n - plus) % multiple == 0,
            };
            if !agrees {
                return Err(disagreeing_note(note, *w, &format!("{n} stitches")));
            }
        }
        let mut written = Vec::with_capacity(rows.len());
        for row in rows {
            let (edges, repeat) = row.widths();
            let fits = match repeat {
                None => edges == n,
                Some(w) => n >= edges && (n - edges) % w == 0,
            };
            if !fits {
                return Err(KnitError::Pattern(format!(
                    "Row {} needs {} but Row {} is {n} stitches wide: the rows do not fit one \
                     piece",
                    row.number,
                    row.describe_width(),
                    fixed.number
                )));
            }
            let instructions = row.over(n);
            if let Some(count) = row.body.count {
                let out: usize = instructions.iter().map(|i| i.stitches_out()).sum();
                if out != count {
                    return Err(KnitError::Pattern(format!(
                        "{}: the row says ({count} sts) but leaves {out} stitches",
                        row.what
                    )));
                }
            }
            written.push(WrittenRow {
                number: row.number,
                right_side: row.right_side,
                instructions,
            });
        }
        super::as_they_appear::settle(&faces(rows), &mut written)?;
        return StitchPattern::from_written_rows("knitspeak", &written);
    }

    // All-over: one repeat W wide, cut from the middle of the piece, so that the stitches
    // outside each row's repeat (its edges) are not knitted.
    for row in rows {
        check_no_edge_shaping(row)?;
    }
    let mut width = 1usize;
    for row in rows {
        let w = row.widths().1.unwrap_or(1);
        width = lcm(width, w);
        if width > MAX_KNITSPEAK_WIDTH {
            return Err(KnitError::Pattern(format!(
                "the rows' repeats need a chart over {MAX_KNITSPEAK_WIDTH} stitches wide to line \
                 up (Row {} repeats over {w})",
                row.number
            )));
        }
    }
    // The piece width, modulo W: every row's edges plus whole repeats.
    let fits = |n: usize, r: &RowPlan| {
        let (edges, w) = r.widths();
        let w = w.unwrap_or(1);
        n % w == edges % w
    };
    let Some(n0) = (0..width).find(|&n| rows.iter().all(|r| fits(n, r))) else {
        let (a, b) = rows
            .iter()
            .enumerate()
            .flat_map(|(i, a)| rows[i + 1..].iter().map(move |b| (a, b)))
            .find(|(a, b)| !fits_any_with(a, b))
            .unwrap_or((&rows[0], &rows[rows.len() - 1]));
        return Err(KnitError::Pattern(format!(
            "Row {} needs {} but Row {} needs {}: no width fits both",
            a.number,
            a.describe_width(),
            b.number,
            b.describe_width()
        )));
    };
    for (note, w) in widths {
        let agrees = match *w {
            WidthNote::Over(m) => m % width == n0,
            WidthNote::Multiple { multiple, plus } => multiple % width == 0 && plus % width == n0,
        };
        if !agrees {
            let rows_need = match n0 {
                0 => format!("a multiple of {width} stitches"),
                e => format!("a multiple of {width} stitches plus {e}"),
            };
            return Err(disagreeing_note(note, *w, &rows_need));
        }
    }
    // Stitch counts per repeat, with the row-balance messages of `rows`.
    let per_repeat: Vec<WrittenRow> = rows
        .iter()
        .map(|r| {
            let unit = r.body.repeat.as_ref().map_or(&[][..], |(u, _)| &u[..]);
            let w = r.ins_in(unit).max(1);
            let unit = r.resolve(unit);
            WrittenRow {
                number: r.number,
                right_side: r.right_side,
                instructions: unit
                    .iter()
                    .copied()
                    .cycle()
                    .take(unit.len() * (width / w))
                    .collect(),
            }
        })
        .collect();
    cells_from_rows(&per_repeat).map_err(|e| match e {
        KnitError::Pattern(m) => {
            KnitError::Pattern(format!("{m} (counted over one {width}-stitch repeat)"))
        }
        other => other,
    })?;

    for row in rows {
        if let Some(count) = row.body.count {
            check_stated_count(row, count, rows)?;
        }
    }

    let max_edges = rows.iter().map(|r| r.widths().0).max().unwrap_or(0);
    let min_n = 2 * max_edges + 4 * width;
    let n = min_n + (n0 + width - min_n % width) % width;
    let mut written: Vec<WrittenRow> = rows
        .iter()
        .map(|r| WrittenRow {
            number: r.number,
            right_side: r.right_side,
            instructions: r.over(n),
        })
        .collect();
    super::as_they_appear::settle(&faces(rows), &mut written)?;
    let cells = cells_from_rows(&written)?;
    // Columns (from the piece's left edge) where each row has an instruction boundary with as
    // many loops worked as stitches made so far.
    let mut clean = vec![true; n + 1];
    for row in &written {
        let mut row_clean = vec![false; n + 1];
        let (mut i, mut o) = (0usize, 0usize);
        row_clean[if row.right_side { n } else { 0 }] = true;
        for ins in &row.instructions {
            i += ins.stitches_in();
            o += ins.stitches_out();
            if i == o && i <= n {
                row_clean[if row.right_side { n - i } else { i }] = true;
            }
        }
        for (c, ok) in clean.iter_mut().zip(row_clean) {
            *c &= ok;
        }
    }
    // Prefer the chart a knitter draws: the first row's repeat starting at the chart's edge
    // where that row starts (the right edge for a RS row).
    let lo = max_edges + width;
    let first = &rows[0];
    let before = first.ins_in(&first.body.before);
    let preferred = if first.right_side {
        lo + (n - before - lo % width) % width
    } else {
        lo + (before + width - lo % width) % width
    };
    let start = std::iter::once(preferred)
        .chain(lo..lo + width)
        .find(|&a| clean[a])
        .unwrap_or(lo);
    let window = cells
        .iter()
        .map(|row| row[start..start + width].to_vec())
        .collect();
    StitchPattern::from_rows("knitspeak", normalised(window, width))
}

/// Per row, how it takes its faces ([`super::as_they_appear`]).
fn faces(rows: &[RowPlan]) -> Vec<super::as_they_appear::Faces> {
    rows.iter().map(|r| r.body.faces).collect()
}

/// An all-over row's edges must keep the stitch count: a decrease or increase there
/// (`ssk, k to last st, m1r, k1`) shapes the piece's edge, which knitwear does not knit (the
/// surface's outline gives the fabric its shape), and dropping it without a word would knit
/// something else than the text says.
fn check_no_edge_shaping(row: &RowPlan) -> Result<()> {
    // An edge that balances its own yarn-overs and decreases (a lace row ending in a part
    // repeat, `to last 5 sts, yo, sk2p, yo, k2`) keeps the count: it shapes nothing.
    let balances = |edge: &[Stitched]| {
        let sum = |f: fn(Instruction) -> usize| edge.iter().map(|s| f(s.ins)).sum::<usize>();
        sum(Instruction::stitches_in) == sum(Instruction::stitches_out)
    };
    if balances(&row.body.before) && balances(&row.body.after) {
        return Ok(());
    }
    let unbalanced = |edge: &'_ Vec<Stitched>| !balances(edge);
    let shaping: Vec<String> = [&row.body.before, &row.body.after]
        .into_iter()
        .filter(|e| unbalanced(e))
        .flatten()
        .filter(|s| s.ins.stitches_in() != s.ins.stitches_out())
        .map(|s| s.ins.name())
        .collect();
    let mut names: Vec<String> = Vec::new();
    for n in shaping {
        if !names.contains(&n) {
            names.push(n);
        }
    }
    let list = names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ");
    Err(KnitError::Pattern(format!(
        "{}: {list} outside the repeat change the stitch count at the edges of the piece \
         (edge shaping). knitwear knits the repeat over the whole surface, whose outline gives \
         the fabric its shape, so it has no edges to shape: leave the edge increases and \
         decreases out, or write the row without a repeat (a panel of fixed width)",
        row.what
    )))
}

/// A stated count (`(14 sts)`) on an all-over row must be a width the piece can have: one
/// that every row fits, and that this row leaves.
fn check_stated_count(row: &RowPlan, count: usize, rows: &[RowPlan]) -> Result<()> {
    for other in rows {
        let (edges, repeat) = other.widths();
        let w = repeat.unwrap_or(1);
        if count < edges || (count - edges) % w != 0 {
            return Err(KnitError::Pattern(format!(
                "{}: the row says ({count} sts), but Row {} needs {}",
                row.what,
                other.number,
                other.describe_width()
            )));
        }
    }
    let out: usize = row.over(count).iter().map(|i| i.stitches_out()).sum();
    if out != count {
        return Err(KnitError::Pattern(format!(
            "{}: the row says ({count} sts) but leaves {out} stitches",
            row.what
        )));
    }
    Ok(())
}

/// Whether two rows' repeats can share a piece width.
fn fits_any_with(a: &RowPlan, b: &RowPlan) -> bool {
    let (ea, wa) = a.widths();
    let (eb, wb) = b.widths();
    let (wa, wb) = (wa.unwrap_or(1), wb.unwrap_or(1));
    (0..lcm(wa, wb)).any(|n| n % wa == ea % wa && n % wb == eb % wb)
}

/// Cells whose offsets were measured on a wider piece, with their offsets wrapped the shorter
/// way round a chart `width` wide (as [`cells_from_rows`] writes them).
pub(crate) fn normalised(mut cells: Vec<Vec<Stitch>>, width: usize) -> Vec<Vec<Stitch>> {
    for row in &mut cells {
        for c in row.iter_mut() {
            c.source_offset = wrap(c.source_offset.into(), width);
            c.land_offset = wrap(c.land_offset.into(), width);
        }
    }
    cells
}

/// `d` columns along a row `width` wide that repeats, the shorter way round; half the width
/// either way is as short, and keeps the way `d` goes (a loop crossing half of a repeat,
/// a 1/2/1 cross beside p2 or a ssk in a 2-stitch repeat, lands in its own repeat, not
/// the neighbouring one, and leans the way it is worked).
pub(crate) fn shorter_way(d: i64, width: usize) -> i64 {
    let w = width as i64;
    let mut r = d.rem_euclid(w);
    if r > w / 2 || (2 * r == w && d < 0) {
        r -= w;
    }
    r
}

/// [`shorter_way`] for an offset that fits a cell (one measured from a cell's own offset).
pub(crate) fn wrap(d: i64, width: usize) -> i8 {
    shorter_way(d, width) as i8
}

/// A width note the rows do not fit: the note, what it says and what the rows need.
fn disagreeing_note(note: &str, says: WidthNote, rows_need: &str) -> KnitError {
    KnitError::Pattern(format!(
        "\"{note}\" says the pattern is worked over {}, but its rows need {rows_need}: \
         check the rows and the note against the pattern as printed",
        says.describe()
    ))
}

/// The least common multiple of two repeat widths.
pub(crate) fn lcm(a: usize, b: usize) -> usize {
    let gcd = |mut x: usize, mut y: usize| {
        while y != 0 {
            (x, y) = (y, x % y);
        }
        x
    };
    a / gcd(a, b) * b
}
