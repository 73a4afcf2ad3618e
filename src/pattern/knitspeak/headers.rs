//! Row headers (`Row 1 (RS):`, `Rows 2-4:`, `Rnd 3:`, `All WS rows:`): which rows a statement
//! is for ([`parse_header`]), and, over all the statements, which statement and which side
//! each row of the repeat has ([`RowSheet`]).

use super::MAX_KNITSPEAK_ROWS;
use crate::error::{KnitError, Result};

/// Which rows a statement is for.
pub(super) enum Rows {
    Numbers(Vec<usize>),
    AllOfSide(bool),
    AllEven,
    AllOdd,
}

/// What a header says.
pub(super) struct Header {
    rows: Rows,
    /// `Rnd` / `Round`: worked in the round.
    round: bool,
    /// `(RS)` / `(WS)`, if given: whether its rows are right-side rows.
    side: Option<bool>,
    /// `Set-up row (WS):`, `Foundation row:`: a row worked once before the repeat, which
    /// the repeat does not hold (its numbers, if any, are its own).
    pub(super) setup: bool,
    /// The row named before the rows of a side or parity (`Row 1` of `Row 1 and every alt
    /// row`, `Row 2` of `Row 2 and all WS rows`): one of them, and numbered, so that the
    /// repeat starts no higher than it.
    first: Option<usize>,
}

impl Header {
    /// The rows it numbers, in order (`None` for `All WS rows` and the like).
    pub(super) fn numbers(&self) -> Option<Vec<usize>> {
        match &self.rows {
            Rows::Numbers(n) => Some(n.clone()),
            _ => None,
        }
    }

    /// The side its header gives (`(RS)`, `(WS)`), if any.
    pub(super) fn side(&self) -> Option<bool> {
        self.side
    }

    /// Whether it is worked in the round (`Rnd`, `Round`).
    pub(super) fn round(&self) -> bool {
        self.round
    }

    /// The same header for row `row` alone (one of those it numbers).
    pub(super) fn only(&self, row: usize) -> Header {
        Header {
            rows: Rows::Numbers(vec![row]),
            round: self.round,
            side: self.side,
            setup: self.setup,
            first: None,
        }
    }
}

/// Reads a header (the text before a statement's `:`).
pub(super) fn parse_header(header: &str) -> Result<Header> {
    let h = header.trim().to_lowercase();
    // `Rib row 1`, `Patt row 3`, `Pattern rnd 2`: the rows of the part named.
    let h = strip_any(&h, &["rib ", "patt ", "pattern "])
        .filter(|r| ["row", "rnd", "round"].iter().any(|w| r.starts_with(w)))
        .map_or_else(|| h.clone(), str::to_string);
    // `Row 1 RS`: a side written without brackets, as the header's last word.
    let bare_side = h
        .rsplit_once(' ')
        .and_then(|(_, last)| match last {
            "rs" => Some(true),
            "ws" => Some(false),
            _ => None,
        })
        .filter(|_| !h.starts_with("all ") && !h.starts_with("every "));
    let side = if h.contains("(rs)") || h.contains("right side") {
        Some(true)
    } else if h.contains("(ws)") || h.contains("wrong side") {
        Some(false)
    } else {
        bare_side
    };
    let first = h
        .split_once(" and ")
        .and_then(|(first, _)| {
            strip_any(
                first,
                &["rows ", "row ", "rnds ", "rnd ", "rounds ", "round "],
            )
        })
        .and_then(|n| n.trim().parse::<usize>().ok());
    if let Some(rows) = alternate_rows(&h) {
        let round = ["rnd", "round"].iter().any(|w| h.contains(w));
        return Ok(Header {
            rows,
            round,
            side: None,
            setup: false,
            first,
        });
    }
    // `All WS rows`, `Every RS row`, `Odd rows`, and `Row 2 and all foll WS rows` (row 2 is
    // one of them).
    let all = strip_any(&h, &["all ", "every "])
        .or_else(|| {
            let (first, rest) = h.split_once(" and ")?;
            strip_any(first, &["rows ", "row ", "rnds ", "rnd "])?;
            strip_any(rest.trim_start(), &["all ", "every "])
        })
        .map_or_else(|| all_rows(&h), all_rows);
    if let Some(rows) = all {
        // "All WS rows" says its side by what it covers, not by a (WS).
        return Ok(Header {
            rows,
            round: false,
            side: None,
            setup: false,
            first,
        });
    }
    if h.starts_with("all ") {
        return Err(bad_header(header));
    }
    // `Set-up row (WS)`, `Foundation rnd`, `Row 1 (set-up row)`.
    let setup = ["set-up", "set up", "setup", "foundation"]
        .iter()
        .any(|w| h.contains(w));
    let h = strip_any(&h, &["set-up ", "set up ", "setup ", "foundation "])
        .map_or(h.as_str(), str::trim_start)
        .to_string();
    let (words, round) = if let Some(r) = strip_any(&h, &["rounds", "round", "rnds", "rnd"]) {
        (r, true)
    } else if let Some(r) = strip_any(&h, &["rows", "row"]) {
        (r, false)
    } else {
        return Err(bad_header(header));
    };
    // `Rows 1 (RS) and 3`: what is in brackets says the side, not which rows.
    let words = match bare_side {
        Some(_) => words.trim_end()[..words.trim_end().len() - 2].trim_end(),
        None => words,
    };
    let mut words = words.to_string();
    while let Some(open) = words.find(['(', '[']) {
        let close = words[open..]
            .find([')', ']'])
            .map_or(words.len(), |c| open + c + 1);
        words.replace_range(open..close, " ");
    }
    let mut numbers = Vec::new();
    // `Rows 1 to 4`, `Rows 1 through 4` are `Rows 1-4`.
    let words = [" to ", " through ", " thru "]
        .iter()
        .fold(words, |w, to| w.replace(to, "-"));
    for part in words.replace(" and ", ",").replace('&', ",").split(',') {
        let part = part.trim().trim_start_matches("and ").trim();
        if part.is_empty() {
            continue;
        }
        if let Some((a, b)) = part.split_once(['-', '–']) {
            let (a, b) = (number(a, header)?, number(b, header)?);
            if b < a {
                return Err(KnitError::Pattern(format!(
                    "\"{}\": a range of rows runs upwards, e.g. \"Rows {b}-{a}:\"",
                    header.trim()
                )));
            }
            numbers.extend(a..=b);
        } else {
            numbers.push(number(part, header)?);
        }
    }
    if numbers.is_empty() && !setup {
        return Err(bad_header(header));
    }
    Ok(Header {
        rows: Rows::Numbers(numbers),
        round,
        side,
        setup,
        first: None,
    })
}

/// `Row 2 and every alt row`, `Row 2 and every foll alternate row`, `Every other row`, `All
/// alt rnds` (lower case): every second row, counted from the row named (the even rows where
/// none is). `None` for any other header.
fn alternate_rows(h: &str) -> Option<Rows> {
    let (base, rest) = match h.split_once(" and ") {
        Some((first, rest)) => {
            let n = strip_any(
                first,
                &["rows ", "row ", "rnds ", "rnd ", "rounds ", "round "],
            )?;
            (Some(n.trim().parse::<usize>().ok()?), rest.trim_start())
        }
        None => (None, h),
    };
    let rest = strip_any(rest, &["all ", "every "])?;
    let rest = strip_any(rest, &["foll ", "following "]).unwrap_or(rest);
    let rest = strip_any(rest, &["alt ", "alternate ", "other "])?;
    ["rows", "row", "rnds", "rnd", "rounds", "round"]
        .iter()
        .any(|w| rest.starts_with(w))
        .then_some(())?;
    Some(if base.unwrap_or(2) % 2 == 0 {
        Rows::AllEven
    } else {
        Rows::AllOdd
    })
}

/// `rs rows`, `wrong side rows`, `even numbered rows`, `foll ws rows`, `odd rows` (after
/// `all` / `every`, or alone for odd and even): the rows of a side or of a parity.
fn all_rows(rest: &str) -> Option<Rows> {
    let rest = rest.replace('-', " ");
    let rest = strip_any(&rest, &["foll ", "following ", "other ", "remaining "])
        .unwrap_or(&rest)
        .trim_start();
    let rows_word = |r: &str| {
        let r = r.trim_start().trim_start_matches("numbered").trim_start();
        ["rows", "row", "rnds", "rnd", "rounds", "round"]
            .iter()
            .any(|w| r.starts_with(w))
    };
    [
        ("rs", Rows::AllOfSide(true)),
        ("right side", Rows::AllOfSide(true)),
        ("ws", Rows::AllOfSide(false)),
        ("wrong side", Rows::AllOfSide(false)),
        ("even", Rows::AllEven),
        ("odd", Rows::AllOdd),
    ]
    .into_iter()
    .find_map(|(word, rows)| {
        rest.strip_prefix(word)
            .filter(|r| rows_word(r))
            .map(|_| rows)
    })
}

fn strip_any<'a>(s: &'a str, words: &[&str]) -> Option<&'a str> {
    words.iter().find_map(|w| s.strip_prefix(w))
}

/// A row number, at most [`MAX_KNITSPEAK_ROWS`]: a header can name no row a pattern cannot
/// have, so a range such as `Rows 1-100000000` is refused before anything is made of it.
fn number(s: &str, header: &str) -> Result<usize> {
    let s = s.trim();
    if !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) {
        return match s.parse::<usize>() {
            Ok(n) if (1..=MAX_KNITSPEAK_ROWS).contains(&n) => Ok(n),
            _ => Err(KnitError::Pattern(format!(
                "\"{}\": row {s} is outside the rows 1 to {MAX_KNITSPEAK_ROWS} a pattern may \
                 number",
                header.trim()
            ))),
        };
    }
    Err(bad_header(header))
}

pub(super) fn bad_header(header: &str) -> KnitError {
    KnitError::Pattern(format!(
        "\"{}\" is not a row header: write \"Row 1 (RS):\", \"Rows 2 and 4:\", \"Rnd 3:\" or \
         \"All WS rows:\"",
        header.trim()
    ))
}

/// What the headers, taken together, say about the rows: which statement each row reads and
/// on which side it is worked. Statements are numbered from 0 in the order written.
#[derive(Default)]
pub(super) struct RowSheet {
    /// Some header says `Rnd` / `Round`: every row is a right-side row.
    in_round: bool,
    /// (row, is RS) from the first header that says its side.
    side_ref: Option<(usize, bool)>,
    /// Per row number, the side its header gave.
    explicit: Vec<Option<bool>>,
    /// Per row number, the statement that names it.
    defined: Vec<Option<usize>>,
    /// `All WS rows` / `All RS rows`, by `usize::from(is RS)`.
    by_side: [Option<usize>; 2],
    /// `All even-numbered rows`.
    even: Option<usize>,
    /// `All odd-numbered rows`.
    odd: Option<usize>,
}

impl RowSheet {
    /// Records that statement `index`, whose header `what` reads as `header`, covers its rows.
    pub(super) fn cover(&mut self, header: Header, what: &str, index: usize) -> Result<()> {
        self.in_round |= header.round;
        if let Some(n) = header.first {
            // Numbered as `Row n:` is, so that the repeat starts no higher than row n.
            self.cover(
                Header {
                    rows: Rows::Numbers(vec![n]),
                    round: header.round,
                    side: None,
                    setup: false,
                    first: None,
                },
                what,
                index,
            )?;
        }
        match header.rows {
            Rows::AllOfSide(rs) => self.by_side[usize::from(rs)] = Some(index),
            Rows::AllEven => self.even = Some(index),
            Rows::AllOdd => self.odd = Some(index),
            Rows::Numbers(numbers) => {
                for n in numbers {
                    if n == 0 || n > MAX_KNITSPEAK_ROWS {
                        return Err(KnitError::Pattern(format!(
                            "{what}: row numbers run from 1 to {MAX_KNITSPEAK_ROWS}, not {n}"
                        )));
                    }
                    if self.defined.len() < n {
                        self.defined.resize(n, None);
                        self.explicit.resize(n, None);
                    }
                    if self.defined[n - 1].is_some() {
                        return Err(KnitError::Pattern(format!(
                            "{what}: row {n} is given twice (an earlier statement gives it \
                             too): give each row once"
                        )));
                    }
                    self.defined[n - 1] = Some(index);
                    if let Some(rs) = header.side {
                        self.explicit[n - 1] = Some(rs);
                        self.side_ref.get_or_insert((n, rs));
                    }
                }
            }
        }
        Ok(())
    }

    /// The statement that gives row `row`, if one does: by its number, else as a row of its
    /// side (`All WS rows`) or an even row, as [`Self::plan`] finds it.
    pub(super) fn statement_of(&self, row: usize) -> Option<usize> {
        if row == 0 || row < self.first() || row > self.height() {
            return None;
        }
        self.defined
            .get(row - 1)
            .copied()
            .flatten()
            .or(self.by_side[usize::from(self.side_of(row))])
            .or(self.even.filter(|_| row % 2 == 0))
            .or(self.odd.filter(|_| row % 2 == 1))
    }

    /// The rows of one vertical repeat, bottom up: (row number, is RS, statement). Flat
    /// knitting with an odd number of rows that alternate sides turns over between repeats,
    /// so its rows come twice, the second time on the other side and numbered on from the
    /// first (see the module docs of [`super`]).
    pub(super) fn plan(&self) -> Result<Vec<(usize, bool, usize)>> {
        let (ref_row, ref_rs) = self.parity_ref();
        let parity_rs = |row: usize| self.in_round || ((row % 2 == ref_row % 2) == ref_rs);
        let (first, height) = (self.first(), self.height());
        let by_side = self.by_side;
        let mut plan: Vec<(usize, bool, usize)> = Vec::with_capacity(height);
        for row in first..=height {
            let rs = self.side_of(row);
            let index = self
                .defined
                .get(row - 1)
                .copied()
                .flatten()
                .or(by_side[usize::from(rs)])
                .or(self.even.filter(|_| row % 2 == 0))
                .or(self.odd.filter(|_| row % 2 == 1))
                .ok_or_else(|| {
                    KnitError::Pattern(format!(
                        "row {row} has no instructions (rows {first} to {height} must all be \
                         given, or covered by \"All WS rows\" / \"All RS rows\")"
                    ))
                })?;
            plan.push((row, rs, index));
        }
        // Flat knitting with an odd number of rows turns over between repeats (unless the
        // headers say otherwise).
        let alternating = plan.iter().all(|&(row, rs, _)| rs == parity_rs(row));
        let count = plan.len();
        if !self.in_round && count % 2 == 1 && alternating {
            for r in 0..count {
                let (row, rs, index) = plan[r];
                plan.push((row + count, !rs, index));
            }
        }
        Ok(plan)
    }

    /// The first row of the repeat: the lowest row numbered (a pattern copied from the middle
    /// of a text may start at `Row 3`), or 1.
    pub(super) fn first(&self) -> usize {
        self.defined
            .iter()
            .position(Option::is_some)
            .map_or(1, |i| i + 1)
    }

    /// The row (and its side) the alternation of sides is counted from.
    fn parity_ref(&self) -> (usize, bool) {
        self.side_ref.unwrap_or((1, true))
    }

    /// The side of `row`: its header's, or by alternation.
    fn side_of(&self, row: usize) -> bool {
        let (ref_row, ref_rs) = self.parity_ref();
        self.explicit
            .get(row - 1)
            .copied()
            .flatten()
            .unwrap_or(self.in_round || ((row % 2 == ref_row % 2) == ref_rs))
    }

    /// The rows the headers give, 1 to this: the highest row numbered, at least 2 with an
    /// "All WS rows" kind of header, and a whole pair where such a header covers the next.
    pub(super) fn height(&self) -> usize {
        let by_side = self.by_side;
        let height = self.defined.len().max(
            if by_side.iter().any(Option::is_some) || self.even.is_some() || self.odd.is_some() {
                2
            } else {
                0
            },
        );
        // "All WS rows" after "Row 7" means row 8 too: the repeat ends on a whole pair of rows.
        if height % 2 == 1
            && (by_side[usize::from(self.side_of(height + 1))].is_some()
                || self.even.is_some()
                || self.odd.is_some())
        {
            height + 1
        } else {
            height
        }
    }
}

/// `These 4 rows form the pattern.`, `Last 2 rnds form patt.` (lower case): a note on which
/// rows repeat, which [`check_repeat_note`] checks.
pub(super) fn forms_the_pattern(lower: &str) -> bool {
    let l = lower.trim();
    ["these ", "the last ", "last "]
        .iter()
        .any(|w| l.starts_with(w))
        && [" rows ", " row ", " rnds ", " rounds "]
            .iter()
            .any(|w| l.contains(w))
        && (l.contains(" form ") || l.contains(" forms "))
        && !l.contains(':')
}

/// Checks a note (`Repeat rows 1-4.`) against the `height` rows the headers give: one that
/// repeats every row says what the chart does anyway; one that repeats only some is an error
/// (the rows outside it are knitted once, and the chart repeats all of its rows), as is one
/// that names a row not given or says more than this reader understands. Other notes
/// (`Multiple of 6 sts plus 5.`) pass.
pub(super) fn check_repeat_note(note: &str, first_row: usize, height: usize) -> Result<()> {
    let lower = note.trim().to_lowercase();
    if forms_the_pattern(&lower) {
        return check_rows_formed(note, &lower, first_row, height);
    }
    let Some(rest) = strip_any(&lower, &["repeat ", "rep "]) else {
        return Ok(());
    };
    let Some(rest) = strip_any(
        rest.trim_start(),
        &["rows", "row", "rounds", "round", "rnds", "rnd"],
    ) else {
        return Ok(());
    };
    let shown = note.trim();
    let unread = |what: &str| {
        KnitError::Pattern(format!(
            "\"{shown}\": cannot read \"{what}\" (write e.g. \"Repeat rows 1-4.\")"
        ))
    };
    let digits = |s: &str| -> (Option<usize>, usize) {
        let s = s.trim_start();
        let n = s.len() - s.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        (s[..n].parse().ok(), s.len() - n)
    };
    let rest = rest.trim();
    let (first, left) = digits(rest);
    let first = first.ok_or_else(|| unread(rest))?;
    let mut tail = rest[rest.len() - left..].trim_start();
    let mut last = first;
    for sep in ["-", "\u{2013}", "to ", "through ", "and ", ","] {
        if let Some(after) = tail.strip_prefix(sep) {
            let (n, left) = digits(after);
            if let Some(n) = n {
                last = n;
                tail = after[after.len() - left..].trim_start();
            }
            break;
        }
    }
    let tail = tail.trim_end_matches('.').trim();
    // What a note may end with changes nothing here: `for pattern`, and how long to go on
    // (`until piece measures 10 in`, `throughout`, `as required`), which is the surface's to
    // say.
    let how_long = [
        "until ",
        "for ",
        "as ",
        "to desired",
        "to the desired",
        "to length",
    ]
    .iter()
    .any(|w| tail.starts_with(w))
        || ["throughout", "to end"].contains(&tail);
    if !tail.is_empty() && !how_long {
        return Err(unread(tail));
    }
    if first == 0 || last < first {
        return Err(unread(rest));
    }
    for row in [first, last] {
        if row < first_row || row > height {
            return Err(KnitError::Pattern(format!(
                "\"{shown}\": row {row} is not given (the rows run from {first_row} to \
                 {height})"
            )));
        }
    }
    if (first, last) != (first_row, height) {
        return Err(KnitError::Pattern(format!(
            "\"{shown}\": the rows outside {first} to {last} are knitted once (set-up or \
             finishing rows), and knitwear repeats every row it is given over the whole \
             surface: give rows {first} to {last} alone to knit the repeat"
        )));
    }
    Ok(())
}

/// `These 4 rows form the pattern.`: the count must be the rows given (`first_row` to
/// `height`), since knitwear repeats all of them; a count in words is read too.
fn check_rows_formed(note: &str, lower: &str, first_row: usize, height: usize) -> Result<()> {
    let given = height + 1 - first_row;
    let count = lower
        .trim_start_matches("the ")
        .trim_start_matches("these ")
        .trim_start_matches("last ")
        .split(' ')
        .next()
        .and_then(super::numbers::count);
    match count {
        Some(n) if n == given => Ok(()),
        Some(n) => Err(KnitError::Pattern(format!(
            "\"{}\": the pattern gives {given} rows ({first_row} to {height}), and knitwear \
             repeats every row it is given, not the last {n}: give the {n} rows that repeat alone",
            note.trim()
        ))),
        // `These rows form the pattern`: all of them.
        None => Ok(()),
    }
}
