//! Written row instructions in Knitspeak (the stitch-maps dialect knitters paste from books
//! and websites), read into the chart of one horizontal and vertical repeat of the fabric.
//!
//! # What it reads
//!
//! - Row headers: `Row 1 (RS):`, `Row 2:`, `Rows 2, 3, and 4:`, `Rows 5-8:`, `Rnd 1:` /
//!   `Rnds 1 and 2:` / `Round 3:` (in the round every row is worked from the right side),
//!   `All WS rows:`, `All RS rows:`, `All even-numbered rows:`, `Odd rows:`, `Every WS row:`,
//!   `Row 2 and all foll WS rows:`, `Rows 1 (RS) and 3:`. Statements may share a line
//!   (`Row 1: Knit. Row 2: Purl.`). A width note (`Multiple of 6 sts plus 5.`, `(multiple
//!   of 2 sts, plus 2)` in a row or opening the text, `(worked over 12 sts)`) is checked
//!   against the widths the rows fit, and one they disagree with is an error naming both
//!   ([`width_note`]); a note with more in it stays an unread note. `Repeat rows 1-4.` is
//!   accepted (also `Repeat row 1`, `Rep rows 1 and 2 for pattern`) where it repeats every row given; one that repeats only
//!   some (`Repeat rows 7-18.` after six set-up rows) is an error that says so, since the
//!   rows outside it are knitted once and the chart repeats all its rows. Each row number
//!   may be given once. Title lines in parentheses before the first row (`(Seed stitch)`)
//!   are skipped. The rows need not start at 1 (rows copied from the middle of a text): the
//!   repeat runs from the lowest row given to the highest, each row numbered as written. A
//!   row whose body says to work another row again (`Row 4: Rep row 2.`, `Work as row 2`,
//!   `Same as rnd 1`, `Rep last row`; row by row, `Rows 5-8: Rep rows 1-4.` and `Repeat last
//!   4 rows`) takes that row's instructions and works them on its own side ([`same_as`]).
//!   A row that says `K the knit sts and p the purl sts` / `Work sts as they appear` keeps
//!   the faces of the row below it ([`as_they_appear`]).
//! - Stitch markers: `pm`, `sm`, `slm`, `rm`, `place marker`, `pm A` work no stitch. A run
//!   may end at one (`K to m, sm, p2, 2/2 RC, p2, sm, k to end`, `rep from * to m`, `k to 2
//!   sts before m`; a marker a run reaches may be slipped without a word); the row that
//!   places the markers with its counts fixes the width of each part between them, and the
//!   pattern is then a panel of fixed width ([`markers`]).
//! - Set-up rows (`Set-up row (WS):`, `Foundation row:`, `Row 1 (set-up row):`), worked once
//!   before the repeat: read, and the markers they place counted (with the stitches they
//!   add), but not knitted, since the repeat covers the surface. `These 4 rows form the
//!   pattern.` is a note checked against the rows given. `sl1, k1, psso`, `sl1, k2tog, psso`,
//!   `sl2, k1, p2sso` (and `p1`) written as separate instructions read as `skp`, `sk2p`,
//!   `cdd` and `cddp`. `*k1, p1; rep from *, ending k1` ends the row with those stitches;
//!   `[k1, p1] to end` / `(k1, p1) across` repeats a group across the row; `As row 1` works
//!   row 1 again; `K the purl sts and p the knit sts` swaps the faces of the row below (seed
//!   from a rib). Barbara Walker's em dash after a header (`Row 1 (Wrong side)—Knit.`) reads
//!   as a `:`.
//! - Sides: a header's `(RS)` / `(WS)` sets the side of its rows; other rows of flat knitting
//!   alternate from it (row 1 is RS when nothing says otherwise). Flat knitting with an odd
//!   number of rows turns over between repeats, so the chart holds the rows twice, the second
//!   time on the other side (rows `h+1 .. 2h` in messages).
//! - Repeats: `*k2, p2; rep from *` (also `rep to end`, `rep * to end`, `*k2, p2* rep to end`,
//!   `work from * to end`, `[k2, p2] rep to end`, `until 2 sts remain`, `across to last 2
//!   sts`), `rep from * to end` / `across` / `around`, `rep from * to last 3
//!   sts, k3` (the stitches after the repeat must be exactly that many), `rep from * 2 more
//!   times` (a fixed count), stitches before and after the repeat, `[k1, p1] 3 times`, `(yo,
//!   k1) twice`, `k2tog 3 times`, `k to end` / `k to last 3 sts` / `Knit.` / `Purl.` (a
//!   one-stitch repeat; also `Purl (6 sts).`; after a repeat that stops `to last N sts`, such
//!   a run works what that one left: `k to last 2 sts, p to end` is `k to last 2 sts, p2`),
//!   and stitch counts `(18 sts)`: on a row of a
//!   fixed width the count it leaves, on an all-over row a width the piece can have. Counts
//!   may be words (`three times`, `to last two sts`, `(six sts)`, `knit two`). A width note in brackets
//!   is a note, not stitches.
//! - Edges: the stitches outside an all-over row's repeat are not knitted (see below), so
//!   edge shaping there (`ssk, k to last st, m1r, k1`) is an error that says so, never
//!   dropped without a word.
//! - Stitches (any case; `-` and spaces are interchangeable), as listed once in
//!   [`super::vocabulary`]: `k`, `p` with counts (`k2`, `K 2`, `knit 2`), `k tbl` / `k1-tbl` /
//!   `p2 tbl`, `sl1` / `sl 2 pwise wyif` / `sl1 wyib` (without `wyib`/`wyif` the yarn is held on
//!   the wrong side: in back on a RS row, in front on a WS row), `yo`, `m1` = `m1l`, `m1r`
//!   (`m1lp`, `m1rp`: the same new loops), `k2tog`, `ssk` (`skp`), `p2tog`, `ssp`, `k3tog`,
//!   `sssk`, `p3tog`, `sssp`, `k4tog`, `p4tog`, `k5tog`, `p5tog`, `k2tog tbl`, `p2tog tbl`,
//!   `k3tog tbl`, `p3tog tbl`, `sk2p` (`sl1-k2tog-psso`), `cdd` (`s2kp`, `sl2-k1-p2sso`), `cddp` (`sl2-p1-p2sso`), `MB`
//!   (bobble), crosses `m/n RC`, `LC`, `RPC`, `LPC` with `m, n` up to 6, `1/1 RT`, `LT`,
//!   `RPT`, `LPT`, and the aliases `C4B` = `2/2 RC`, `C4F` = `2/2 LC` (any even
//!   `CnB`/`CnF`), `T2B`/`T2F` = `1/1 RT`/`LT`, `T3B`/`T3F` = `2/1 RPC`/`LPC`,
//!   `T4B`/`T4F` = `2/2 RPC`/`LPC`.
//!
//! An unknown stitch or a malformed row is an error naming the row, the instruction (counted
//! from 1 in the order written) and the token, with the closest stitch this reader knows:
//! nothing is knitted from a pattern it only half understood.
//!
//! # From rows to one repeat (the phase of the repeats)
//!
//! The rows are laid out on a notional flat piece, exactly as a knitter works it: a RS row
//! from the right edge leftwards, a WS row from the left edge rightwards, each with its
//! stitches before the repeat, the repeat as many times as fits, and its stitches after.
//!
//! - If some row has no open-ended repeat (a panel such as `P2, k12, p2`), the piece is that
//!   wide, every other row must fit it (its repeat filling what its edge stitches leave), and
//!   the chart is the whole piece.
//! - Otherwise the chart is one horizontal repeat, `W` = the least common multiple of the rows'
//!   repeat widths (in stitches worked), at most [`MAX_KNITSPEAK_WIDTH`]. The piece width `N`
//!   must fit every row (`N = before + after + k * repeat`); a row that wants a multiple of 4
//!   and another a multiple of 4 plus 2 is an error. Because RS rows are measured from the
//!   right edge and WS rows from the left, `N` fixes how the rows' repeats line up, which is
//!   what a knitter's "multiple of 6 plus 5" means. The chart is the `W` columns of a wide
//!   piece (`N` a valid width, large enough to have edges well away from the middle) starting
//!   at the first column, counted from the piece's left edge, where no row has an instruction
//!   across the chart's edge; if every column cuts some row's cable, the chart still starts
//!   there and the chart's cells carry the cable across its edge (the fabric is the same).
//!
//! Stitch counts are checked per chart repeat before anything is laid out: every row must
//! work the loops the row below left (wrapping from the last row to the first) and, since
//! knitwear knits on a lattice of a fixed width, keep its own count (see [`super::rows`]).
//!
//! # Files
//!
//! This file is the front door ([`parse_knitspeak`], [`looks_like_knitspeak`]) and runs the
//! steps, each in its own file: [`lexer`] cuts the text into `(header, body)` statements and a
//! body into tokens; [`headers`] reads a header and works out which statement and side each
//! row of the repeat has; [`body`] reads a row body (its stitches, its repeat, its stitch
//! count, its parts between markers); [`markers`] counts the parts of rows that work to a
//! marker; [`layout`] lays the rows out on a piece and cuts one repeat.

mod abbreviations;
mod as_they_appear;
mod body;
mod headers;
mod layout;
mod lexer;
mod markers;
pub(super) mod numbers;
mod same_as;
mod width_note;

pub(crate) use layout::{lcm, normalised, shorter_way, wrap};

use self::as_they_appear::Faces;
use self::body::{parse_body, Body};
use self::headers::{parse_header, RowSheet};
use self::layout::{lay_out, RowPlan};
use self::lexer::statements;
use self::same_as::SameAs;
use self::width_note::WidthNote;
use super::StitchPattern;
use crate::error::{KnitError, Result};

/// Widest chart a Knitspeak pattern may make (the least common multiple of its rows' repeats,
/// or a panel's width).
pub const MAX_KNITSPEAK_WIDTH: usize = crate::pattern::MAX_PATTERN_WIDTH;
/// Deepest brackets may nest (`[k1, (p1, k1) 2 times] 3 times` is two deep).
pub const MAX_BRACKET_DEPTH: usize = 16;
/// Most rows a Knitspeak pattern may number.
pub const MAX_KNITSPEAK_ROWS: usize = crate::pattern::MAX_PATTERN_ROWS;

/// What a statement gives its rows: a body, or another row's (`Rep row 2.`).
enum Given {
    Body(Body),
    SameAs(usize),
}

/// Reads Knitspeak text (see the module docs) into a pattern whose chart is as seen on the
/// right side, row 1 at the bottom.
pub fn parse_knitspeak(text: &str) -> Result<StitchPattern> {
    let text = lexer::walker_dashes(text);
    let text = lexer::ordinal_rows(&text);
    let text = lexer::spaced_dashes(&text);
    let text = lexer::next_rows(&text);
    let defined = abbreviations::defined(&text);
    let text = abbreviations::inline_crosses(&text);
    let lexed = statements(&text);
    let statements = lexed.rows;
    // Only text around a pattern, one line of it a header that is no row's (`Stitch 1:`).
    if let (true, Some(header)) = (statements.is_empty(), lexed.skipped.first()) {
        return Err(headers::bad_header(header));
    }
    if statements.is_empty() {
        return Err(KnitError::Pattern(
            "no Knitspeak rows found: write e.g. \"Row 1 (RS): *k2, p2; rep from *.\"".into(),
        ));
    }
    // Statement by statement, so that the first error in the text is the one reported.
    let mut sheet = RowSheet::default();
    let mut read = Vec::with_capacity(statements.len());
    // Set-up rows, worked once before the repeat: (header, body, side given, in the round).
    let mut setups: Vec<(String, Body, Option<bool>, bool)> = Vec::new();
    for (header, body) in &statements {
        let rows = parse_header(header)?;
        let what = header.trim().to_string();
        if rows.setup {
            // Read, so that a stitch it misspells is reported and the markers it places are
            // counted, but not knitted: the repeat covers the surface.
            setups.push((
                what.clone(),
                parse_body(body, &what, &defined)?,
                rows.side(),
                rows.round(),
            ));
            continue;
        }
        match same_as::same_as(body) {
            None => {
                let faces = as_they_appear::as_they_appear(body)
                    .or_else(|| as_they_appear::fabric_named(body).map(Faces::Shown));
                let parsed = match faces {
                    Some(faces) => Body {
                        faces,
                        ..parse_body("Knit.", &what, &defined)?
                    },
                    None => parse_body(body, &what, &defined)?,
                };
                sheet.cover(rows, &what, read.len())?;
                read.push((what, Given::Body(parsed)));
            }
            // `Row 4: Rep row 2.` takes row 2's body once every row is known; `Rows 5-8: Rep
            // rows 1-4.` is a statement per row, each naming the row it repeats.
            Some(reference) => match rows.numbers() {
                None => {
                    let SameAs::Rows(target) = &reference else {
                        return Err(KnitError::Pattern(format!(
                            "{what}: \"{}\" names no rows of its own to count back from: \
                             name the row it repeats",
                            body.trim()
                        )));
                    };
                    let [target] = target[..] else {
                        return Err(KnitError::Pattern(format!(
                            "{what}: repeats {} rows: name one",
                            target.len()
                        )));
                    };
                    sheet.cover(rows, &what, read.len())?;
                    read.push((what, Given::SameAs(target)));
                }
                Some(numbers) => {
                    for (row, target) in same_as::pairs(&numbers, &reference, &what)? {
                        sheet.cover(rows.only(row), &what, read.len())?;
                        read.push((what.clone(), Given::SameAs(target)));
                    }
                }
            },
        }
    }
    let mut bodies = Vec::with_capacity(read.len());
    for (what, parsed) in &read {
        let mut body = parsed;
        // Follow a chain of references (`Row 6: Rep row 4.`, `Row 4: Rep row 2.`); one that
        // comes back to itself is refused.
        for _ in 0..=read.len() {
            let Given::SameAs(row) = body else { break };
            let index = sheet.statement_of(*row).ok_or_else(|| {
                KnitError::Pattern(format!(
                    "{what}: repeats row {row}, which the pattern does not give"
                ))
            })?;
            body = &read[index].1;
        }
        match body {
            Given::Body(b) => bodies.push((what.clone(), b.clone())),
            Given::SameAs(_) => {
                return Err(KnitError::Pattern(format!(
                    "{what}: the rows it repeats come back to it: write one of them out"
                )))
            }
        }
    }
    for note in &lexed.notes {
        headers::check_repeat_note(note, sheet.first(), sheet.height())?;
    }
    // Width notes, the text's own and those written in rows, with where each was written.
    let mut widths: Vec<(String, WidthNote)> = lexed
        .notes
        .iter()
        .filter_map(|n| width_note::read(n).map(|w| (n.trim().to_string(), w)))
        .collect();
    for (what, body) in &bodies {
        for n in &body.notes {
            if let Some(w) = width_note::read(n) {
                widths.push((format!("{what} ({n})"), w));
            }
        }
    }
    let rows: Vec<RowPlan> = sheet
        .plan()?
        .into_iter()
        .map(|(number, right_side, index)| RowPlan {
            number,
            right_side,
            what: &bodies[index].0,
            body: &bodies[index].1,
        })
        .collect();
    // Rows that work to a stitch marker become rows of a fixed width, counted by the rows that
    // place the markers.
    let setup_rows = setup_plans(&setups, &rows);
    if let Some(resolved) = markers::resolve(&rows, &setup_rows)? {
        let rows: Vec<RowPlan> = rows
            .iter()
            .zip(&resolved)
            .map(|(r, body)| RowPlan { body, ..*r })
            .collect();
        return lay_out(&rows, &widths);
    }
    lay_out(&rows, &widths)
}

/// The set-up rows as rows worked before the repeat's first row: each on the side its header
/// gives, or else on the other side from the row after it (in the round, the right side).
fn setup_plans<'a>(
    setups: &'a [(String, Body, Option<bool>, bool)],
    rows: &[RowPlan],
) -> Vec<RowPlan<'a>> {
    let mut next_rs = rows.first().is_none_or(|r| r.right_side);
    let mut plans: Vec<RowPlan> = setups
        .iter()
        .rev()
        .map(|(what, body, side, round)| {
            let right_side = side.unwrap_or(*round || !next_rs);
            next_rs = right_side;
            RowPlan {
                number: 0,
                right_side,
                what,
                body,
            }
        })
        .collect();
    plans.reverse();
    plans
}

/// Whether `text` looks like Knitspeak rather than a symbol chart: some line opens with a row
/// header (`Row 1 (RS):`), whatever title, notes or cast-on come before it.
pub fn looks_like_knitspeak(text: &str) -> bool {
    lexer::next_rows(&lexer::spaced_dashes(&lexer::ordinal_rows(
        &lexer::walker_dashes(text),
    )))
    .lines()
    .any(|line| lexer::first_row_statement(line).is_some())
}
