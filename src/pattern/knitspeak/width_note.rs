//! A pattern's note on the widths it is worked over (`(multiple of 6 sts, plus 5)`, `Multiple
//! of 4 sts + 2.`, `(worked over 12 sts)`), read so that the layout can check it: a note the
//! rows disagree with means the text or its reading is wrong, and knitting on would make a
//! fabric the pattern does not describe.
//!
//! Only notes read whole are checked; anything else in a note (`6-row rep`, a comment) makes
//! it a note the reader keeps no figure from, as before.

use super::numbers;

/// What a width note says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum WidthNote {
    /// The piece is `plus + k * multiple` stitches wide, for any whole `k`.
    Multiple { multiple: usize, plus: usize },
    /// The piece (a panel) is exactly this wide.
    Over(usize),
}

impl WidthNote {
    /// As knitters write it, for messages.
    pub(super) fn describe(self) -> String {
        match self {
            Self::Multiple { multiple, plus: 0 } => format!("a multiple of {multiple} stitches"),
            Self::Multiple { multiple, plus } => {
                format!("a multiple of {multiple} stitches plus {plus}")
            }
            Self::Over(n) => format!("{n} stitches"),
        }
    }
}

/// The note `text` (a bracket's or a line's text, brackets and a final full stop allowed),
/// if it is a width note read whole.
pub(super) fn read(text: &str) -> Option<WidthNote> {
    let lower = text.trim().trim_end_matches('.').to_lowercase();
    let inner = lower.trim_start_matches('(').trim_end_matches(')');
    // Words, with `+`, commas and semicolons as their own words or dropped.
    let spaced = inner.replace('+', " + ").replace([',', ';'], " ");
    let words: Vec<&str> = spaced.split_whitespace().collect();
    let mut w: &[&str] = &words;
    if let ["worked", rest @ ..] = w {
        w = rest;
    }
    // `worked over 12 sts` / `over 12 sts`.
    if let ["over", n, rest @ ..] = w {
        if *n != "a" {
            let n = numbers::count(n)?;
            return (n >= 1 && matches!(rest, [] | ["sts" | "stitches"]))
                .then_some(WidthNote::Over(n));
        }
        w = &w[1..];
    }
    if let ["a", rest @ ..] = w {
        w = rest;
    }
    let ["multiple", "of", n, rest @ ..] = w else {
        return None;
    };
    let multiple = numbers::count(n)?;
    let plus = match rest {
        [] | ["sts" | "stitches"] => 0,
        ["sts" | "stitches", "plus" | "+" | "and", n]
        | ["sts" | "stitches", "plus" | "+" | "and", n, "sts" | "stitches" | "st"]
        | ["plus" | "+", n]
        | ["plus" | "+", n, "sts" | "stitches" | "st"] => numbers::count(n)?,
        _ => return None,
    };
    (multiple >= 1).then_some(WidthNote::Multiple { multiple, plus })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_ways_patterns_write_it() {
        let m = |multiple, plus| Some(WidthNote::Multiple { multiple, plus });
        assert_eq!(read("(multiple of 4 sts, plus 2)"), m(4, 2));
        assert_eq!(read("multiple of 4 sts, plus 2"), m(4, 2));
        assert_eq!(read("Multiple of 6 sts plus 5."), m(6, 5));
        assert_eq!(read("(a multiple of 8 sts + 5)"), m(8, 5));
        assert_eq!(read("multiple of 4 + 2 sts"), m(4, 2));
        assert_eq!(read("(multiple of 2 sts)"), m(2, 0));
        assert_eq!(read("Multiple of six sts plus one."), m(6, 1));
        assert_eq!(read("(worked over 12 sts)"), Some(WidthNote::Over(12)));
        assert_eq!(read("over 9 stitches"), Some(WidthNote::Over(9)));
        // Notes with more in them are kept as notes, unread.
        assert_eq!(read("(multiple of 10 sts plus 1; 6-row rep)"), None);
        assert_eq!(read("multiple of 4 sts, plus 2 for the edges"), None);
        assert_eq!(read("(multiple of 0 sts)"), None);
        assert_eq!(read("Repeat rows 1-4."), None);
    }
}
