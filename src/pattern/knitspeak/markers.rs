//! Stitch markers: rows that work to a marker (`K to m, sm, p2, k8, p2, sm, k to end`), read as
//! rows of a fixed width.
//!
//! A marker sits between the same two stitches from row to row, so it parts every row that
//! names it into the same parts, each as many stitches wide in every row. A row that counts a
//! part's stitches (`K4, pm, p2, k8, p2, pm, k4`, the set-up row) fixes its width; a run to a
//! marker (`k to m`, `rep from * to 2 sts before m`) fills what its part leaves. Markers are
//! counted from the right edge on a right-side row and from the left on a wrong-side row, as
//! the knitter meets them. Every part must keep its stitch count, or the markers would move.
//!
//! The parts' widths then make each such row a row of fixed width, and the pattern a panel
//! that wide ([`super::layout`]): a run to a marker is never guessed at.

use super::body::{loops_in, Body};
use super::layout::RowPlan;
use crate::error::{KnitError, Result};
use crate::pattern::Instruction;

/// Where `rows` work to a marker, their bodies as rows of fixed width (the others as they
/// were), in the order of `rows`; `None` where no row works to a marker. `setup`: set-up rows
/// worked before the repeat (numbered 0), which count the parts they leave but are not
/// knitted.
pub(super) fn resolve(rows: &[RowPlan], setup: &[RowPlan]) -> Result<Option<Vec<Body>>> {
    let Some(first) = rows.iter().find(|r| r.body.to_marker) else {
        return Ok(None);
    };
    let parts = first.body.segments.len();
    let marked: Vec<&RowPlan> = setup
        .iter()
        .chain(rows)
        .filter(|r| !r.body.segments.is_empty())
        .collect();
    for row in &marked {
        let n = row.body.segments.len();
        if n != parts {
            return Err(KnitError::Pattern(format!(
                "{} parts the row at {} but {} at {}: rows that work to a marker must name \
                 the same markers",
                row.what,
                markers(n - 1),
                first.what,
                markers(parts - 1)
            )));
        }
        for (j, part) in row.body.segments.iter().enumerate() {
            let sum = |f: fn(Instruction) -> usize| -> usize {
                [&part.before, &part.after]
                    .into_iter()
                    .chain(part.repeat.as_ref().map(|(u, _)| u))
                    .flatten()
                    .map(|s| f(s.ins))
                    .sum()
            };
            // A set-up row may increase (a cable's extra stitches): it counts what it leaves.
            if row.number > 0 && sum(Instruction::stitches_in) != sum(Instruction::stitches_out) {
                return Err(KnitError::Pattern(format!(
                    "{}: the stitches {} change its stitch count, so the markers would move: \
                     knitwear keeps each part's count (balance its increases and decreases \
                     between the same markers)",
                    row.what,
                    place(right_edge_order(j, parts, row.right_side), parts)
                )));
            }
        }
    }
    // Each part's width, counted from the right edge, with the row that counts it.
    let mut widths: Vec<Option<(usize, &str)>> = vec![None; parts];
    for row in &marked {
        for (j, part) in row.body.segments.iter().enumerate() {
            let at = right_edge_order(j, parts, row.right_side);
            if let (edges, None) = part.widths() {
                let edges = if row.number == 0 { made(part) } else { edges };
                match widths[at] {
                    None => widths[at] = Some((edges, row.what)),
                    Some((w, by)) if w != edges => {
                        return Err(KnitError::Pattern(format!(
                            "{} works {edges} stitches {} but {by} works {w}: the rows do not \
                             fit one piece",
                            row.what,
                            place(at, parts)
                        )))
                    }
                    Some(_) => {}
                }
            }
        }
    }
    let mut counted = Vec::with_capacity(parts);
    for (at, w) in widths.iter().enumerate() {
        let Some((w, _)) = w else {
            return Err(KnitError::Pattern(format!(
                "{} works to a marker, but no row counts the stitches {}: knitwear does not \
                 guess a run's length; give the set-up row that places the markers with its \
                 counts (such as \"K4, pm, p2, k8, p2, pm, k4\")",
                first.what,
                place(at, parts)
            )));
        };
        counted.push(*w);
    }
    let mut out = Vec::with_capacity(rows.len());
    for row in rows {
        if row.body.segments.is_empty() {
            out.push(row.body.clone());
            continue;
        }
        let mut before = Vec::new();
        for (j, part) in row.body.segments.iter().enumerate() {
            let at = right_edge_order(j, parts, row.right_side);
            let n = counted[at];
            check_fits(row, part, n, &place(at, parts))?;
            before.extend(part.over(n));
        }
        out.push(Body {
            before,
            count: row.body.count,
            notes: row.body.notes.clone(),
            faces: row.body.faces,
            ..Body::default()
        });
    }
    Ok(Some(out))
}

/// Stitches a part of fixed width leaves (those of a set-up row, which may increase).
fn made(part: &Body) -> usize {
    part.over(0).iter().map(|s| s.ins.stitches_out()).sum()
}

/// Part `j` of `parts` in working order as counted from the right edge: a wrong-side row meets
/// the parts from the left.
fn right_edge_order(j: usize, parts: usize, right_side: bool) -> usize {
    if right_side {
        j
    } else {
        parts - 1 - j
    }
}

/// `n` markers in words.
fn markers(n: usize) -> String {
    match n {
        1 => "1 marker".to_string(),
        n => format!("{n} markers"),
    }
}

/// Part `at` (counted from the right edge) in words, for messages.
fn place(at: usize, parts: usize) -> String {
    if at == 0 {
        "before the first marker (from the right edge)".to_string()
    } else if at + 1 == parts {
        "after the last marker (from the right edge)".to_string()
    } else {
        format!("between markers {at} and {} (from the right edge)", at + 1)
    }
}

/// A part of `row` must fill the `n` stitches counted for it: its stitches outside the run
/// plus whole repeats, and a repeat `to 2 sts before m` followed by those 2 stitches.
fn check_fits(row: &RowPlan, part: &Body, n: usize, place: &str) -> Result<()> {
    let (edges, repeat) = part.widths();
    let fits = match repeat {
        None => edges == n,
        Some(w) => n >= edges && (n - edges) % w == 0,
    };
    if !fits {
        let needs = match repeat {
            None => format!("{edges} stitches"),
            Some(w) if edges == 0 => format!("a multiple of {w} stitches"),
            Some(w) => format!("a multiple of {w} stitches plus {edges}"),
        };
        return Err(KnitError::Pattern(format!(
            "{}: the part {place} is {n} stitches wide, but the row works {needs} there",
            row.what
        )));
    }
    if let Some((_, super::body::Until::Last(left))) = &part.repeat {
        let after = loops_in(&part.after);
        if after != *left {
            return Err(KnitError::Pattern(format!(
                "{}: a run {place} stops {left} stitches before the marker, but {after} \
                 stitches follow it",
                row.what
            )));
        }
    }
    Ok(())
}
