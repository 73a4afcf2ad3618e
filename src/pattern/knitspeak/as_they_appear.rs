//! `K the knit sts and p the purl sts.` / `Work sts as they appear.`: a row that keeps every
//! column's face, knitting each loop that shows as a knit to the knitter and purling each
//! that shows as a purl. Written patterns say so for the wrong-side rows of ribs, textures
//! and cables rather than spell out the stitches again. `K the purl sts and p the knit sts.`
//! swaps every column's face instead (seed and moss stitch from a rib).
//!
//! The row is read as a one-stitch open repeat (it fits any width, one stitch per loop) and,
//! once the rows around it are laid out, takes from the row below it each column's face on
//! the right side: a knit stays a knit (worked as a purl from the wrong side) and a purl a
//! purl. A yarn-over or a slipped stitch below shows as a knit, as knitters purl a yarn-over
//! from the wrong side; a twisted stitch below is worked plain.

use crate::error::{KnitError, Result};
use crate::pattern::instruction::Instruction;
use crate::pattern::rows::{cells_from_rows, WrittenRow};
use crate::pattern::stitch::Face;

/// How a row takes its faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) enum Faces {
    /// As its stitches are written.
    #[default]
    Written,
    /// Those of the row below (`k the knit sts and p the purl sts`).
    Kept,
    /// Those of the row below, swapped (`k the purl sts and p the knit sts`).
    Swapped,
    /// Every stitch showing this face on the right side, whichever side the row is worked
    /// from (`Work in St st.`: knit from the right side, purled from the wrong side).
    Shown(Face),
}

/// The face a row `Work in St st.` (or stockinette, stocking stitch) or `Work in rev St st.`
/// shows on the right side, if its body says that.
pub(super) fn fabric_named(body: &str) -> Option<Face> {
    let lower = body.trim().trim_end_matches('.').trim().to_lowercase();
    let lower = lower
        .strip_prefix("work")
        .map_or(lower.as_str(), str::trim_start);
    let lower = lower.strip_prefix("even").map_or(lower, str::trim_start);
    let lower = lower.strip_prefix("in").map_or(lower, str::trim_start);
    let (purl, name) = match ["reverse ", "rev. ", "rev "]
        .iter()
        .find_map(|w| lower.strip_prefix(w))
    {
        Some(rest) => (true, rest),
        None => (false, lower),
    };
    let name = name.trim();
    let stockinette = [
        "st st",
        "st. st.",
        "stst",
        "stockinette",
        "stockinette st",
        "stockinette stitch",
        "stocking st",
        "stocking stitch",
    ]
    .contains(&name);
    stockinette.then_some(if purl { Face::Purl } else { Face::Knit })
}

/// How a row's body says to take its faces from the row below, if it does: kept (any case
/// and spelling of `k the knit sts and p the purl sts`, either way round, or `work (all) sts
/// as they appear`) or swapped (`k the purl sts and p the knit sts`, either way round).
pub(super) fn as_they_appear(body: &str) -> Option<Faces> {
    let lower = body.trim().trim_end_matches('.').trim().to_lowercase();
    let words: Vec<&str> = lower
        .split_whitespace()
        .filter(|w| !["the", "all", "every"].contains(w))
        .map(|w| match w {
            "knit" | "knits" => "k",
            "purl" | "purls" => "p",
            "stitches" | "stitch" | "st" => "sts",
            w => w,
        })
        .collect();
    let text = words.join(" ");
    let sts = text.replace(" sts", "");
    match sts.as_str() {
        "k k and p p"
        | "p p and k k"
        | "work as they appear"
        | "work as they present themselves" => Some(Faces::Kept),
        "k p and p k" | "p k and k p" => Some(Faces::Swapped),
        _ if text == "work sts as they appear" => Some(Faces::Kept),
        _ => None,
    }
}

/// Gives each row that takes its faces from the row below (`faces`, per row of `written`, in
/// the order laid out, bottom up) its stitches from the row below it (the last row's for the
/// first). Rows of that kind stacked on each other take their faces in turn.
pub(super) fn settle(faces: &[Faces], written: &mut [WrittenRow]) -> Result<()> {
    // A row that names its fabric shows that face whatever the row below shows.
    for (row, f) in written.iter_mut().zip(faces) {
        if let Faces::Shown(face) = *f {
            let worked = if (face == Face::Knit) == row.right_side {
                Instruction::Knit
            } else {
                Instruction::Purl
            };
            row.instructions.iter_mut().for_each(|i| *i = worked);
        }
    }
    let appear: Vec<bool> = faces
        .iter()
        .map(|f| matches!(f, Faces::Kept | Faces::Swapped))
        .collect();
    if !appear.contains(&true) {
        return Ok(());
    }
    if appear.iter().all(|&a| a) {
        return Err(KnitError::Pattern(
            "every row works its stitches as they appear: give at least one row's stitches".into(),
        ));
    }
    let h = written.len();
    // A row of this kind above another takes its faces once that one has them: at most one
    // pass per row.
    for _ in 0..h {
        let cells = cells_from_rows(written)?;
        let mut changed = false;
        for r in (0..h).filter(|&r| appear[r]) {
            let below = &cells[(r + h - 1) % h];
            let right_side = written[r].right_side;
            // Working order: right to left from the right side, left to right from the wrong.
            let mut shown: Vec<Face> = below.iter().map(|s| s.face).collect();
            if right_side {
                shown.reverse();
            }
            let swap = faces[r] == Faces::Swapped;
            let instructions: Vec<Instruction> = shown
                .into_iter()
                .map(|face| match ((face == Face::Knit) != swap, right_side) {
                    (true, true) | (false, false) => Instruction::Knit,
                    _ => Instruction::Purl,
                })
                .collect();
            if instructions != written[r].instructions {
                written[r].instructions = instructions;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ways_knitters_write_it_are_read() {
        for text in [
            "K the knit sts and p the purl sts.",
            "Knit the knits and purl the purls.",
            "knit the knit stitches and purl the purl stitches",
            "P the purl sts and k the knit sts.",
            "Work sts as they appear.",
            "Work all sts as they appear",
            "work the stitches as they appear.",
        ] {
            assert_eq!(as_they_appear(text), Some(Faces::Kept), "{text}");
        }
        for text in [
            "K the purl sts and p the knit sts.",
            "Purl the knit sts and knit the purl sts.",
        ] {
            assert_eq!(as_they_appear(text), Some(Faces::Swapped), "{text}");
        }
        for text in ["Knit.", "K2, p2.", "Work in pattern.", "p the knit sts"] {
            assert_eq!(as_they_appear(text), None, "{text}");
        }
        for (text, face) in [
            ("Work in St st.", Some(Face::Knit)),
            ("Work even in stockinette stitch", Some(Face::Knit)),
            ("Stocking stitch.", Some(Face::Knit)),
            ("Work in rev St st.", Some(Face::Purl)),
            ("reverse stockinette", Some(Face::Purl)),
            ("Work in pattern.", None),
            ("St st 4 rows.", None),
        ] {
            assert_eq!(fabric_named(text), face, "{text}");
        }
    }
}
