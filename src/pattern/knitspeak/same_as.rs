//! A row whose whole body says to work other rows again: `Row 4: Rep row 2.`, `Rnd 3:
//! Repeat rnd 1.`, `Row 6: Work as row 2.`, `Row 5: Same as row 1.`, `Rows 5-8: Rep rows
//! 1-4.`, `Row 3: Rep last row.`, `Rows 5 and 6: Rep last 2 rows.`. Written patterns say so
//! rather than write a row out twice; each row is worked with the named row's instructions on
//! its own side, as a knitter works it.

use super::headers::parse_header;
use super::numbers;
use crate::error::{KnitError, Result};

/// The rows a body refers to, if the body is only such a reference (any case, an optional
/// full stop).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum SameAs {
    /// `Rep row 2`, `Rep rows 1-4`: these rows, in order.
    Rows(Vec<usize>),
    /// `Rep last row`, `Rep last 2 rows`: the rows just below the statement's own, this many.
    Last(usize),
}

/// What `body` refers to, if it is only a reference to other rows.
pub(super) fn same_as(body: &str) -> Option<SameAs> {
    let lower = body.trim().trim_end_matches('.').trim().to_lowercase();
    let rest = [
        "repeat ",
        "rep ",
        "work as for ",
        "work as ",
        "work same as ",
        "same as ",
        "as ",
    ]
    .iter()
    .find_map(|p| lower.strip_prefix(p))?;
    let rest = rest.trim_start_matches("for ").trim();
    if let Some(last) = rest.strip_prefix("last ") {
        let last = last.trim();
        if ["row", "rnd", "round"].contains(&last) {
            return Some(SameAs::Last(1));
        }
        let (n, what) = last.split_once(' ')?;
        if !["rows", "rnds", "rounds"].contains(&what.trim()) {
            return None;
        }
        let n = n.parse().ok().or_else(|| numbers::count(n))?;
        return (n > 0).then_some(SameAs::Last(n));
    }
    // `row 2`, `rows 1-4`, `rnds 1 and 2`, read as a header names its rows; a number in words
    // (`round two`) too.
    if let Ok(rows) = parse_header(rest).map(|h| h.numbers()) {
        return rows.map(SameAs::Rows);
    }
    let number = ["row ", "rnd ", "round "]
        .iter()
        .find_map(|p| rest.strip_prefix(p))?;
    numbers::count(number.trim()).map(|n| SameAs::Rows(vec![n]))
}

/// Each of the statement's rows `numbers` with the row it repeats: one named row for them
/// all, or as many as they are, in order; `Last(k)` counts back from the first of them.
pub(super) fn pairs(
    numbers: &[usize],
    reference: &SameAs,
    what: &str,
) -> Result<Vec<(usize, usize)>> {
    let first = numbers.iter().copied().min().unwrap_or(1);
    let targets: Vec<usize> = match reference {
        SameAs::Rows(rows) => rows.clone(),
        SameAs::Last(k) => {
            if *k >= first {
                let before = match first - 1 {
                    0 => "no row comes".to_string(),
                    1 => "only 1 row comes".to_string(),
                    n => format!("only {n} rows come"),
                };
                return Err(KnitError::Pattern(format!(
                    "{what}: repeats the last {k} rows, but {before} before row {first}"
                )));
            }
            (first - k..first).collect()
        }
    };
    match targets.len() {
        1 => Ok(numbers.iter().map(|&n| (n, targets[0])).collect()),
        t if t == numbers.len() => Ok(numbers.iter().copied().zip(targets).collect()),
        t => Err(KnitError::Pattern(format!(
            "{what}: is {} rows but repeats {t}: name one row, or as many as it has",
            numbers.len()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_body_that_names_other_rows_is_read_as_their_numbers() {
        for (text, rows) in [
            ("Rep row 2.", vec![2]),
            ("Repeat Rnd 1", vec![1]),
            ("Work as row 12.", vec![12]),
            ("work as for row 3", vec![3]),
            ("Same as Row 1.", vec![1]),
            ("Rep round two.", vec![2]),
            ("Rep rows 1-4.", vec![1, 2, 3, 4]),
            ("Repeat rnds 1 and 3", vec![1, 3]),
        ] {
            assert_eq!(same_as(text), Some(SameAs::Rows(rows)), "{text}");
        }
        assert_eq!(same_as("Rep last row."), Some(SameAs::Last(1)));
        assert_eq!(same_as("Repeat last 2 rows"), Some(SameAs::Last(2)));
        assert_eq!(same_as("rep last two rnds"), Some(SameAs::Last(2)));
    }

    #[test]
    fn stitches_and_other_repeats_are_no_reference() {
        for text in [
            "K2, p2.",
            "rep from * to end",
            "rep row",
            "Knit.",
            "rep last 0 rows",
        ] {
            assert_eq!(same_as(text), None, "{text}");
        }
    }
}
