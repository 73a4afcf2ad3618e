//! Text charts: a grid of stitch symbols with a legend, as knitters draw them.
//!
//! # Reading
//!
//! One line per row, **top row first** as the chart is drawn on paper (the last line is row
//! 1, the first row knitted), one symbol per stitch **as it shows on the right side**, columns
//! left to right. A chart row is worked right to left on the right side (and left to right on
//! the wrong side, where each stitch is worked so that it shows as drawn: a knit cell on a WS
//! row is purled), so the chart always shows the fabric's front; knitwear reads every chart row
//! as its right-side equivalent, which makes the same fabric. Spaces and tabs between symbols,
//! empty lines, lines starting with `#` and a `Legend:` / `Key:` heading are ignored.
//!
//! Default symbols:
//!
//! | symbol | stitch |
//! |---|---|
//! | `k K \| v V` | knit |
//! | `p P - . • ·` | purl |
//! | `O o` | yo (a hole: the standard circle) |
//! | `/` | k2tog (right-leaning) |
//! | `\` | ssk (left-leaning) |
//! | `^` | cdd (centred double decrease) |
//! | `B` | bobble (MB) |
//! | `Q` | k tbl (twisted knit) |
//!
//! `o` and `O` meant purl before yarn-overs existed; they are yarn-overs now, as on printed
//! charts (a chart of only yarn-overs and knits does not balance and is refused, so an old
//! chart is never silently misread; `o = p` in its legend restores the old meaning).
//!
//! A legend line `SYMBOL = STITCH` (Knitspeak, one stitch: `X = 2/2 RC`, `s = sl1 wyif`,
//! `O = yo`, `o = p`) gives a symbol its stitch and overrides a default. `(WS)` after the
//! stitch (`Y = 2/2 RC (WS)`, `s = sl1 wyif (WS)`) means worked from the wrong side, drawn as
//! it shows on the right side. A stitch that makes
//! several stitches (a cable) is drawn as a run of its symbol over all its columns: `XXXX` with
//! `X = 2/2 RC`; a longer run is several of them side by side (`XXXXXXXX` is two 2/2 RCs), so a
//! run must be a whole number of them. A run may continue across the chart's right edge onto
//! its left edge (the chart repeats): `XkkX` with `X = 1/1 RT` crosses the last column over
//! the first. Other stitches are one cell each (a decrease is one cell, a yo one cell).
//!
//! A legend's stitch is read, and an unknown one answered with the closest known name, by
//! the same stitch vocabulary as Knitspeak rows ([`super::vocabulary`]).
//!
//! Every row must work as many loops of the row below as it makes stitches (a yo balanced by
//! a decrease in the same row), since knitwear knits on a lattice of a fixed width.
//!
//! Errors name the row (counted from the bottom, as knitters number rows), the column (from
//! the left, 1 = first) and the symbol.
//!
//! # Writing
//!
//! [`write_chart`] draws a pattern back: plain knit and purl patterns as `k`/`p` only; others
//! with the default symbols where they have one, letters for the rest, and a legend line for
//! every symbol other than `k` and `p`. The chart reads back to an equal pattern.

use std::collections::HashMap;

use super::instruction::{Instruction, MAX_CROSS_SIDE};
use super::knitspeak::{normalised, wrap};
use super::rows::{cells_from_rows, WrittenRow};
use super::stitch::{Face, Form};
use super::unknitted::unknitted;
use super::vocabulary::{parse_stitch, suggest};
use super::{Stitch, StitchPattern};
use crate::error::{KnitError, Result};

/// Symbols for a knit stitch (what shows on the front: a V).
pub const KNIT_SYMBOLS: &[char] = &['k', 'K', '|', 'v', 'V'];
/// Symbols for a purl stitch (a bump on the front; charts draw it as a dot or a dash).
pub const PURL_SYMBOLS: &[char] = &['p', 'P', '-', '.', '•', '·'];
/// The other default symbols.
pub const DEFAULT_SYMBOLS: &[(char, Instruction)] = &[
    ('O', Instruction::YarnOver),
    ('o', Instruction::YarnOver),
    ('/', Instruction::K2tog),
    ('\\', Instruction::Ssk),
    ('^', Instruction::Cdd),
    ('B', Instruction::Bobble),
    ('Q', Instruction::KnitTbl),
];
/// Symbols [`write_chart`] gives stitches that have no default, in order.
const SPARE_SYMBOLS: &str = "XYZACDEFGHJLMNRSTUWacdefghjlmnrstuwxyz0123456789";

/// A chart cell's stitch: a right-side instruction, and whether its stitches show the other
/// face (a stitch worked from the wrong side that differs from a right-side one only by its
/// face: `sl1 wyib (WS)`, `MB (WS)`).
type Charted = (Instruction, bool);

/// The right-side stitch that shows as `ws` worked from the wrong side, and whether its face
/// is flipped; `None` where no right-side stitch shows like it (`sk2p`, `cdd`, `cddp`).
///
/// A cross worked from the wrong side is seen from the right side with its two groups
/// swapped (`m/n` becomes `n/m`: the first group worked is at the other end) but leaning the
/// same way, and what the wrong side knits shows as purl: a knit cross shows as the
/// right-side cross with both groups purled (flipped), and a purl cross (`RPC`, knit group in
/// front from the wrong side, so behind from the right) as the right-side purl cross itself.
fn from_wrong_side(ws: Instruction) -> Option<Charted> {
    use Instruction as I;
    Some(match ws {
        I::Knit => (I::Purl, false),
        I::Purl => (I::Knit, false),
        I::KnitTbl => (I::PurlTbl, false),
        I::PurlTbl => (I::KnitTbl, false),
        I::K2tog => (I::P2tog, false),
        I::P2tog => (I::K2tog, false),
        I::Ssk => (I::Ssp, false),
        I::Ssp => (I::Ssk, false),
        I::P3tog => (I::K3tog, false),
        I::Sssp => (I::Sssk, false),
        I::K4tog => (I::P4tog, false),
        I::P4tog => (I::K4tog, false),
        I::K5tog => (I::P5tog, false),
        I::P5tog => (I::K5tog, false),
        I::K2togTbl => (I::P2togTbl, false),
        I::P2togTbl => (I::K2togTbl, false),
        I::K3togTbl => (I::P3togTbl, false),
        I::P3togTbl => (I::K3togTbl, false),
        I::YarnOver | I::MakeOneLeft | I::MakeOneRight => (ws, false),
        I::Slip { yarn_front } => (
            I::Slip {
                yarn_front: !yarn_front,
            },
            true,
        ),
        I::K3tog => (I::P3tog, false),
        I::Sssk => (I::Sssp, false),
        I::Bobble => (ws, true),
        I::Cross {
            m,
            n,
            left,
            purl_back,
        } => (
            I::Cross {
                m: n,
                n: m,
                left,
                purl_back,
            },
            !purl_back,
        ),
        // Seen from the right side, a centre cross worked from the wrong side has its centre
        // in front of both groups: no right-side stitch does that.
        I::Sk2p | I::Cdd | I::Cddp | I::CentreCross { .. } => return None,
    })
}

/// The legend text of a charted stitch.
fn legend_name((ins, flip): Charted) -> String {
    if !flip {
        return ins.name();
    }
    // The wrong-side stitch that `from_wrong_side` maps to `(ins, true)`.
    let ws = match ins {
        Instruction::Slip { yarn_front } => Instruction::Slip {
            yarn_front: !yarn_front,
        },
        Instruction::Cross {
            m,
            n,
            left,
            purl_back,
        } => Instruction::Cross {
            m: n,
            n: m,
            left,
            purl_back,
        },
        other => other,
    };
    format!("{} (WS)", ws.name())
}

fn default_symbol(ch: char) -> Option<Instruction> {
    if KNIT_SYMBOLS.contains(&ch) {
        Some(Instruction::Knit)
    } else if PURL_SYMBOLS.contains(&ch) {
        Some(Instruction::Purl)
    } else {
        DEFAULT_SYMBOLS
            .iter()
            .find(|(c, _)| *c == ch)
            .map(|(_, i)| *i)
    }
}

/// Parses a chart (see the module docs).
pub fn parse_chart(text: &str) -> Result<StitchPattern> {
    let mut legend: HashMap<char, Charted> = HashMap::new();
    let mut lines: Vec<&str> = Vec::new();
    for line in text.lines().map(str::trim) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if let Some((key, value)) = line.split_once('=') {
            let mut chars = key.trim().chars();
            let (Some(symbol), None) = (chars.next(), chars.next()) else {
                return Err(KnitError::Pattern(format!(
                    "legend \"{line}\": write one symbol, then '=', then its stitch, e.g. \
                     \"X = 2/2 RC\""
                )));
            };
            let value = value.trim();
            let (value, ws) = match value.to_lowercase().strip_suffix("(ws)") {
                Some(v) => (value[..v.len()].trim(), true),
                None => (value, false),
            };
            let stitch = match parse_stitch(value) {
                Some((s, 1)) if !ws => (s.ins, false),
                Some((s, 1)) => from_wrong_side(s.on_side(false)).ok_or_else(|| {
                    KnitError::Pattern(format!(
                        "legend \"{line}\": {} worked from the wrong side shows as no stitch a \
                         chart cell can draw; write that row in Knitspeak",
                        s.ins.name()
                    ))
                })?,
                _ => {
                    return Err(KnitError::Pattern(match unknitted(value) {
                        Some(why) => format!("legend \"{line}\": {why}"),
                        None => format!(
                            "legend \"{line}\": unknown stitch \"{value}\" (did you mean \
                             \"{}\"?)",
                            suggest(value)
                        ),
                    }))
                }
            };
            legend.insert(symbol, stitch);
            continue;
        }
        let lower = line.to_lowercase();
        if line.ends_with(':') && (lower.starts_with("legend") || lower.starts_with("key")) {
            continue;
        }
        lines.push(line);
    }
    if lines.is_empty() {
        return Err(KnitError::Pattern(
            "the chart is empty: write one line per row, e.g. \"kkpp\"".into(),
        ));
    }
    let n = lines.len();
    let symbols: Vec<Vec<char>> = lines
        .iter()
        .rev()
        .map(|l| l.chars().filter(|c| !matches!(c, ' ' | '\t')).collect())
        .collect();
    let width = symbols[0].len();
    // Before any row is read: a chart too large to knit is refused at once.
    super::check_size(width, n)?;
    if let Some((i, r)) = symbols.iter().enumerate().find(|(_, r)| r.len() != width) {
        return Err(KnitError::Pattern(format!(
            "row {} has {} stitches but row 1 has {width}: every chart row must be equally wide",
            i + 1,
            r.len()
        )));
    }
    let lookup = |ch: char| {
        legend
            .get(&ch)
            .copied()
            .or_else(|| default_symbol(ch).map(|i| (i, false)))
    };
    let mut flipped = Vec::new();
    let mut rows = Vec::with_capacity(n);
    let mut phases = Vec::with_capacity(n);
    for (r, row) in symbols.iter().enumerate() {
        let number = r + 1;
        let mut stitches = Vec::with_capacity(width);
        for (col, &ch) in row.iter().enumerate() {
            let ins = lookup(ch).ok_or_else(|| {
                KnitError::Pattern(format!(
                    "row {number}, column {}: unknown symbol {ch:?}; use k (knit) or p (purl), \
                     a default symbol (O yo, / k2tog, \\ ssk, ^ cdd, B bobble, Q k tbl) or add \
                     a legend line such as \"{ch} = 2/2 RC\"",
                    col + 1
                ))
            })?;
            stitches.push(ins.0);
            if ins.1 {
                flipped.push((r, col));
            }
        }
        let (instructions, phase) = row_instructions(row, &stitches, number)?;
        let worked: usize = instructions.iter().map(|i| i.stitches_in()).sum();
        if worked != width {
            return Err(KnitError::Pattern(format!(
                "row {number} works {worked} loops of the row below but makes {width} \
                 stitches: every chart row must keep its stitch count (each yo balanced by a \
                 decrease in the same row)"
            )));
        }
        rows.push(WrittenRow {
            number,
            right_side: true,
            instructions,
        });
        phases.push(phase);
    }
    let mut cells = cells_with_phases(&rows, &phases, width)?;
    for (r, col) in flipped {
        let cell = &mut cells[r][col];
        cell.face = match cell.face {
            Face::Knit => Face::Purl,
            Face::Purl => Face::Knit,
        };
    }
    StitchPattern::from_rows("custom", cells)
}

/// A chart row's instructions in working order (right to left), starting `phase` columns in
/// from the right edge when a cable's run continues across the edge.
fn row_instructions(
    row: &[char],
    stitches: &[Instruction],
    number: usize,
) -> Result<(Vec<Instruction>, usize)> {
    let w = row.len();
    let size = |i: Instruction| i.stitches_out();
    // A multi-column run that continues from the right edge onto the left edge.
    let last = w - 1;
    let mut phase = 0;
    if size(stitches[last]) > 1 && row[0] == row[last] && row.iter().any(|&c| c != row[0]) {
        let lead = row.iter().take_while(|&&c| c == row[0]).count();
        let k = size(stitches[last]);
        phase = (k - lead % k) % k;
    }
    let mut out = Vec::new();
    let mut i = 0; // cells consumed, in working order from `phase`
    while i < w {
        let col = (2 * w - 1 - phase - i) % w;
        let ins = stitches[col];
        let k = size(ins);
        for j in 1..k {
            let c = (2 * w - 1 - phase - i - j) % w;
            if i + j >= w || row[c] != row[col] {
                let run_start = (0..k)
                    .map(|d| (col + w - d) % w)
                    .take_while(|&c| row[c] == row[col])
                    .last()
                    .unwrap_or(col);
                return Err(KnitError::Pattern(format!(
                    "row {number}, column {}: '{}' ({}) covers {k} columns, so its run must be \
                     {k}, {} or more columns wide",
                    run_start.min(col) + 1,
                    row[col],
                    ins.name(),
                    2 * k
                )));
            }
        }
        out.push(ins);
        i += k;
    }
    Ok((out, phase))
}

/// The cells of right-side `rows` (each exactly `width` stitches), each row's instructions
/// starting `phases[r]` columns in from the right edge, the rest wrapping round.
pub(crate) fn cells_with_phases(
    rows: &[WrittenRow],
    phases: &[usize],
    width: usize,
) -> Result<Vec<Vec<Stitch>>> {
    // The counts, with messages about the chart as drawn.
    let cells = cells_from_rows(rows)?;
    if phases.iter().all(|&p| p == 0) {
        return Ok(cells);
    }
    // Three repeats side by side, each row shifted by its phase (plain knits fill the edges);
    // the middle repeat is exact.
    let wide: Vec<WrittenRow> = rows
        .iter()
        .zip(phases)
        .map(|(row, &p)| {
            let mut instructions = vec![Instruction::Knit; p];
            instructions.extend(row.instructions.iter().chain(&row.instructions));
            instructions.extend(std::iter::repeat_n(Instruction::Knit, width - p));
            WrittenRow {
                number: row.number,
                right_side: row.right_side,
                instructions,
            }
        })
        .collect();
    let cells = cells_from_rows(&wide)?
        .into_iter()
        .map(|r| r[width..2 * width].to_vec())
        .collect();
    Ok(normalised(cells, width))
}

/// Every instruction a chart cell can show, in the order [`write_chart`] tries them.
fn candidates() -> Vec<Charted> {
    use Instruction as I;
    let mut all = vec![
        I::Knit,
        I::Purl,
        I::KnitTbl,
        I::PurlTbl,
        I::Slip { yarn_front: false },
        I::Slip { yarn_front: true },
        I::YarnOver,
        I::MakeOneLeft,
        I::K2tog,
        I::Ssk,
        I::P2tog,
        I::Ssp,
        I::K3tog,
        I::Sssk,
        I::P3tog,
        I::Sssp,
        I::K2togTbl,
        I::P2togTbl,
        I::K3togTbl,
        I::P3togTbl,
        I::K4tog,
        I::P4tog,
        I::K5tog,
        I::P5tog,
        I::Sk2p,
        I::Cdd,
        I::Cddp,
        I::Bobble,
    ];
    for m in 1..=MAX_CROSS_SIDE {
        for n in 1..=MAX_CROSS_SIDE {
            for left in [false, true] {
                for purl_back in [false, true] {
                    all.push(I::Cross {
                        m,
                        n,
                        left,
                        purl_back,
                    });
                }
            }
        }
    }
    for m in 1..MAX_CROSS_SIDE {
        for c in 1..=MAX_CROSS_SIDE - m {
            for n in 1..=MAX_CROSS_SIDE - c {
                for left in [false, true] {
                    for purl_centre in [false, true] {
                        all.push(I::CentreCross {
                            m,
                            c,
                            n,
                            left,
                            purl_centre,
                        });
                    }
                }
            }
        }
    }
    let mut all: Vec<Charted> = all.into_iter().map(|i| (i, false)).collect();
    for i in [
        I::Slip { yarn_front: false },
        I::Slip { yarn_front: true },
        I::Bobble,
    ] {
        all.push((i, true));
    }
    // Knit crosses worked from the wrong side (see `from_wrong_side`).
    let flipped: Vec<Charted> = all
        .iter()
        .filter(|(i, flip)| {
            !flip
                && matches!(
                    i,
                    I::Cross {
                        purl_back: false,
                        ..
                    }
                )
        })
        .map(|&(i, _)| (i, true))
        .collect();
    all.extend(flipped);
    all
}

/// Whether `ins`, worked on the right side with its stitches ending `out_at` and its loops
/// `in_at` columns in from the right edge, makes exactly the cells of `row` and the landings
/// of `below`.
fn fits(
    (ins, flip): Charted,
    row: &[Stitch],
    below: &[Stitch],
    out_at: usize,
    in_at: usize,
) -> bool {
    let w = row.len();
    let worked = ins.worked();
    let (n_in, n_out) = (worked.loops.len(), worked.made.len());
    if n_out > w || n_in > w {
        return false;
    }
    // Leftmost columns, as `cells_from_rows` places them.
    let base_out = (3 * w - out_at - n_out) as i64;
    let base_in = (3 * w - in_at - n_in) as i64;
    let col = |c: i64| c.rem_euclid(w as i64) as usize;
    for (k, made) in worked.made.iter().enumerate() {
        let c = base_out + k as i64;
        let cell = row[col(c)];
        let source_offset = if made.sources == 0 {
            0
        } else {
            wrap(base_in + made.first_source as i64 - c, w)
        };
        let face = match (made.face, flip) {
            (f, false) => f,
            (Face::Knit, true) => Face::Purl,
            (Face::Purl, true) => Face::Knit,
        };
        if cell.face != face
            || cell.form != made.form
            || usize::from(cell.sources) != made.sources
            || cell.source_offset != source_offset
        {
            return false;
        }
    }
    for (k, fate) in worked.loops.iter().enumerate() {
        let s = base_in + k as i64;
        let cell = below[col(s)];
        let lands = wrap(base_out + fate.made_by as i64 - s, w);
        let rise = u8::from(matches!(worked.made[fate.made_by].form, Form::Slip { .. }));
        if cell.land_offset != lands || cell.land_layer != fate.layer || cell.rise != rise {
            return false;
        }
    }
    true
}

/// Row `r` of `p` as right-side instructions in working order starting `phase` columns in
/// from the right edge, if its cells are exactly what they make.
fn decode_row(p: &StitchPattern, r: usize, phase: usize, all: &[Charted]) -> Option<Vec<Charted>> {
    let w = p.width;
    let row = &p.cells[r * w..(r + 1) * w];
    let b = (r + p.height - 1) % p.height;
    let below = &p.cells[b * w..(b + 1) * w];
    let (mut at_in, mut at_out) = (phase, phase);
    let mut out = Vec::new();
    while at_out < phase + w {
        let c = all.iter().copied().find(|&c| {
            at_out + c.0.stitches_out() <= phase + w && fits(c, row, below, at_out, at_in)
        })?;
        at_out += c.0.stitches_out();
        at_in += c.0.stitches_in();
        out.push(c);
    }
    (at_in == phase + w).then_some(out)
}

/// The chart of `p` (see the module docs), top row first.
pub fn write_chart(p: &StitchPattern) -> String {
    let w = p.width;
    let mut s = String::with_capacity((w + 1) * p.height);
    if p.cells.iter().all(|c| c.is_plain()) {
        for r in (0..p.height).rev() {
            s.extend(p.cells[r * w..(r + 1) * w].iter().map(|c| c.symbol()));
            s.push('\n');
        }
        return s;
    }
    let all = candidates();
    let mut symbols: Vec<(Charted, char)> = vec![
        ((Instruction::Knit, false), 'k'),
        ((Instruction::Purl, false), 'p'),
    ];
    let mut spare = SPARE_SYMBOLS.chars();
    let mut grid: Vec<Vec<char>> = Vec::with_capacity(p.height);
    let mut approximated = Vec::new();
    for r in 0..p.height {
        let decoded = (0..w).find_map(|phase| {
            let cs = decode_row(p, r, phase, &all)?;
            // A row that is one run of a cable must start at the edge to read back.
            let k = cs[0].0.stitches_out();
            let single = cs.iter().all(|&c| c == cs[0]) && k > 1;
            (!(single && phase % k != 0)).then_some((cs, phase))
        });
        let Some((cs, phase)) = decoded else {
            // Not expressible in chart cells (e.g. a cable worked from the wrong side): draw
            // its faces, and say so.
            approximated.push(r + 1);
            grid.push(
                p.cells[r * w..(r + 1) * w]
                    .iter()
                    .map(|c| c.symbol())
                    .collect(),
            );
            continue;
        };
        let mut row = vec![' '; w];
        let mut at = phase;
        for c in cs {
            let sym = match symbols.iter().find(|(j, _)| *j == c) {
                Some((_, sym)) => *sym,
                None => {
                    let sym = DEFAULT_SYMBOLS
                        .iter()
                        .find(|(_, j)| !c.1 && *j == c.0)
                        .map(|(sym, _)| *sym)
                        .or_else(|| spare.next())
                        .unwrap_or('?');
                    symbols.push((c, sym));
                    sym
                }
            };
            for k in 0..c.0.stitches_out() {
                row[(2 * w - 1 - at - k) % w] = sym;
            }
            at += c.0.stitches_out();
        }
        grid.push(row);
    }
    for row in grid.iter().rev() {
        s.extend(row.iter());
        s.push('\n');
    }
    s.push('\n');
    for (c, sym) in &symbols[2..] {
        s.push_str(&format!("{sym} = {}\n", legend_name(*c)));
    }
    if !approximated.is_empty() {
        s.push_str(&format!(
            "# rows {approximated:?} have stitches worked from the wrong side that no chart \
             symbol shows; drawn as their knit and purl faces\n"
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every cross worked from the wrong side, alone in a row over knits, decodes as the
    /// right-side stitch `from_wrong_side` names, and its legend line reads back to it.
    #[test]
    fn wrong_side_crosses_chart_as_from_wrong_side_says() {
        for m in 1..=MAX_CROSS_SIDE {
            for n in 1..=MAX_CROSS_SIDE {
                for left in [false, true] {
                    for purl_back in [false, true] {
                        let ws = Instruction::Cross {
                            m,
                            n,
                            left,
                            purl_back,
                        };
                        let w = usize::from(m + n);
                        let rows = [
                            WrittenRow {
                                number: 1,
                                right_side: true,
                                instructions: vec![Instruction::Knit; w],
                            },
                            WrittenRow {
                                number: 2,
                                right_side: false,
                                instructions: vec![ws],
                            },
                        ];
                        let p = StitchPattern::from_rows("ws", cells_from_rows(&rows).unwrap())
                            .unwrap();
                        let want = from_wrong_side(ws).unwrap();
                        let fits_at = (0..w).any(|phase| {
                            decode_row(&p, 1, phase, &[want]).is_some_and(|d| d == [want])
                        });
                        assert!(fits_at, "{} (WS) is not {want:?}", ws.name());
                        if want.1 {
                            assert_eq!(legend_name(want), format!("{} (WS)", ws.name()));
                        }
                        // The chart draws it (no row left as faces) and reads back to it.
                        let chart = write_chart(&p);
                        assert!(!chart.contains("# rows"), "{}:\n{chart}", ws.name());
                        let back = parse_chart(&chart).unwrap();
                        assert_eq!(back.cells, p.cells, "{}:\n{chart}", ws.name());
                    }
                }
            }
        }
    }

    /// A centre cross charts as one run of its symbol, with its legend line, and reads back;
    /// worked from the wrong side it has no right-side symbol and is drawn as its faces.
    #[test]
    fn centre_crosses_chart_and_read_back() {
        for (ins, ws_drawn) in [
            (
                Instruction::CentreCross {
                    m: 1,
                    c: 1,
                    n: 1,
                    left: true,
                    purl_centre: true,
                },
                false,
            ),
            (
                Instruction::CentreCross {
                    m: 2,
                    c: 2,
                    n: 1,
                    left: false,
                    purl_centre: false,
                },
                true,
            ),
        ] {
            let w = ins.stitches_in() + 2;
            let mut cross_row = vec![Instruction::Purl, Instruction::Purl];
            cross_row.insert(1, ins);
            let rows = [
                WrittenRow {
                    number: 1,
                    right_side: !ws_drawn,
                    instructions: cross_row,
                },
                WrittenRow {
                    number: 2,
                    right_side: ws_drawn,
                    instructions: vec![Instruction::Knit; w],
                },
            ];
            let p = StitchPattern::from_rows("centre", cells_from_rows(&rows).unwrap()).unwrap();
            let chart = write_chart(&p);
            if ws_drawn {
                assert!(chart.contains("# rows [1]"), "{chart}");
            } else {
                assert!(!chart.contains("# rows"), "{chart}");
                assert!(chart.contains(&format!("= {}\n", ins.name())), "{chart}");
                let back = parse_chart(&chart).unwrap();
                assert_eq!(back.cells, p.cells, "{chart}");
            }
        }
    }
}
