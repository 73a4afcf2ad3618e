//! Written row instructions in Knitspeak (the stitch-maps dialect knitters paste from books
//! and websites), for patterns of knit and purl stitches.
//!
//! Supported so far: row headers `Row 1 (RS):`, `Row 2:`, `Rows 2, 3, and 4:`, `Rows 5-8:`,
//! `Rnd 1:` / `Rnds 1 and 2:` (in the round: every row is worked from the right side) and
//! `All WS rows:` / `All RS rows:`; bodies that are one whole-row repeat: `Knit.`, `Purl.`,
//! `*K2, p2, rep from *.`, `*k1, p1; rep from * to end.`, or a plain sequence such as
//! `k2, p2` (repeated across the row). Statements may share a line. Flat rows alternate right
//! side (RS) and wrong side (WS) from the first row's side; a WS row is worked from the back,
//! so its knits show as purl bumps on the front and its stitches run the other way.
//!
//! Anything else (cables, decreases, stitches outside the repeat, `to last N sts`) is an
//! error naming the row and the token, with the closest stitch this reader knows: nothing is
//! knitted from a pattern it only half understood.

use super::{Stitch, StitchPattern};
use crate::error::{KnitError, Result};

/// Widest chart a Knitspeak pattern may make (the least common multiple of its rows' repeats).
pub const MAX_KNITSPEAK_WIDTH: usize = 256;
/// Most rows a Knitspeak pattern may number.
pub const MAX_KNITSPEAK_ROWS: usize = 1024;

/// The stitch names this reader knows, for suggestions.
const KNOWN: &[&str] = &["k", "p", "knit", "purl", "rep from *", "rep from * to end"];

/// Which rows a statement is for.
enum Rows {
    Numbers(Vec<usize>),
    AllOfSide(bool),
}

/// Reads Knitspeak text (see the module docs) into a pattern whose chart is as seen on the
/// right side, row 1 at the bottom.
pub fn parse_knitspeak(text: &str) -> Result<StitchPattern> {
    let statements = statements(text);
    if statements.is_empty() {
        return Err(KnitError::Pattern(
            "no Knitspeak rows found: write e.g. \"Row 1 (RS): *k2, p2; rep from *.\"".into(),
        ));
    }
    let mut in_round = false;
    let mut first_side_rs = true;
    let mut defined: Vec<Option<Vec<Stitch>>> = Vec::new();
    let mut by_side: [Option<Vec<Stitch>>; 2] = [None, None];
    for (header, body) in &statements {
        let (rows, round, side) = parse_header(header)?;
        in_round |= round;
        let what = header.trim();
        let unit = parse_body(body, what)?;
        match rows {
            Rows::AllOfSide(rs) => by_side[usize::from(rs)] = Some(unit),
            Rows::Numbers(numbers) => {
                if let (Some(rs), Some(&1)) = (side, numbers.first()) {
                    first_side_rs = rs;
                }
                for n in numbers {
                    if n == 0 || n > MAX_KNITSPEAK_ROWS {
                        return Err(KnitError::Pattern(format!(
                            "{what}: row numbers run from 1 to {MAX_KNITSPEAK_ROWS}, not {n}"
                        )));
                    }
                    if defined.len() < n {
                        defined.resize(n, None);
                    }
                    defined[n - 1] = Some(unit.clone());
                }
            }
        }
    }
    let is_rs = |row: usize| in_round || ((row % 2 == 1) == first_side_rs);
    let height = defined.len().max(if by_side.iter().any(Option::is_some) {
        2
    } else {
        0
    });
    let mut units = Vec::with_capacity(height);
    for row in 1..=height {
        let unit = defined
            .get(row - 1)
            .cloned()
            .flatten()
            .or_else(|| by_side[usize::from(is_rs(row))].clone())
            .ok_or_else(|| {
                KnitError::Pattern(format!(
                    "row {row} has no instructions (rows 1 to {height} must all be given, or \
                     covered by \"All WS rows\" / \"All RS rows\")"
                ))
            })?;
        units.push(if is_rs(row) {
            unit
        } else {
            from_the_back(&unit)
        });
    }
    let width = units.iter().try_fold(1usize, |w, u| {
        let l = lcm(w, u.len());
        (l <= MAX_KNITSPEAK_WIDTH).then_some(l)
    });
    let width = width.ok_or_else(|| {
        KnitError::Pattern(format!(
            "the rows' repeats need a chart over {MAX_KNITSPEAK_WIDTH} stitches wide to line up"
        ))
    })?;
    let rows = units
        .iter()
        .map(|u| u.iter().copied().cycle().take(width).collect())
        .collect();
    StitchPattern::from_rows("knitspeak", rows)
}

/// Whether `text` looks like Knitspeak rather than a symbol chart: it starts with a row header.
pub fn looks_like_knitspeak(text: &str) -> bool {
    let t = text.trim_start().to_lowercase();
    ["row", "rnd", "round", "all "]
        .iter()
        .any(|w| t.starts_with(w))
        && t.contains(':')
}

/// A WS row as it shows on the front: worked from the back, so each stitch shows reversed
/// (knit as a purl bump) and the stitches run the other way.
fn from_the_back(unit: &[Stitch]) -> Vec<Stitch> {
    unit.iter()
        .rev()
        .map(|s| match s.face {
            super::Face::Knit => Stitch::PURL,
            super::Face::Purl => Stitch::KNIT,
        })
        .collect()
}

/// Splits the text into `(header, body)` statements. A header runs to its `:`; a body runs to
/// the next header (a new line, or a row word after a full stop).
fn statements(text: &str) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = Vec::new();
    for line in text.lines() {
        let mut rest = line.trim();
        while !rest.is_empty() {
            let Some(colon) = rest.find(':') else {
                // A continuation of the previous body.
                if let Some(last) = out.last_mut() {
                    last.1.push(' ');
                    last.1.push_str(rest);
                } else {
                    out.push((rest.to_string(), String::new()));
                }
                break;
            };
            let header = rest[..colon].to_string();
            let after = &rest[colon + 1..];
            let end = next_header(after).unwrap_or(after.len());
            out.push((header, after[..end].trim().to_string()));
            rest = after[end..].trim();
        }
    }
    out
}

/// Where the next statement starts in `s`: a row word right after a full stop.
fn next_header(s: &str) -> Option<usize> {
    // ASCII lower case keeps byte offsets, so they index `s` too.
    let lower = s.to_ascii_lowercase();
    let mut from = 0;
    while let Some(dot) = lower[from..].find('.') {
        let at = from + dot + 1;
        let next = lower[at..].trim_start();
        let start = lower.len() - next.len();
        if ["row", "rnd", "round", "all "]
            .iter()
            .any(|w| next.starts_with(w))
            && next.contains(':')
        {
            return Some(start);
        }
        from = at;
    }
    None
}

fn parse_header(header: &str) -> Result<(Rows, bool, Option<bool>)> {
    let h = header.trim().to_lowercase();
    let side = if h.contains("(rs)") {
        Some(true)
    } else if h.contains("(ws)") {
        Some(false)
    } else {
        None
    };
    if let Some(rest) = h.strip_prefix("all ") {
        let rs = if rest.starts_with("rs") {
            true
        } else if rest.starts_with("ws") {
            false
        } else {
            return Err(bad_header(header));
        };
        return Ok((Rows::AllOfSide(rs), false, None));
    }
    let (words, round) = if let Some(r) = strip_any(&h, &["rounds", "round", "rnds", "rnd"]) {
        (r, true)
    } else if let Some(r) = strip_any(&h, &["rows", "row"]) {
        (r, false)
    } else {
        return Err(bad_header(header));
    };
    let words = words.split('(').next().unwrap_or("");
    let mut numbers = Vec::new();
    for part in words.replace(" and ", ",").split(',') {
        let part = part.trim().trim_start_matches("and ").trim();
        if part.is_empty() {
            continue;
        }
        if let Some((a, b)) = part.split_once('-') {
            let (a, b) = (number(a, header)?, number(b, header)?);
            if b < a || b - a > MAX_KNITSPEAK_ROWS {
                return Err(bad_header(header));
            }
            numbers.extend(a..=b);
        } else {
            numbers.push(number(part, header)?);
        }
    }
    if numbers.is_empty() {
        return Err(bad_header(header));
    }
    Ok((Rows::Numbers(numbers), round, side))
}

fn strip_any<'a>(s: &'a str, words: &[&str]) -> Option<&'a str> {
    words.iter().find_map(|w| s.strip_prefix(w))
}

fn number(s: &str, header: &str) -> Result<usize> {
    s.trim().parse().map_err(|_| bad_header(header))
}

fn bad_header(header: &str) -> KnitError {
    KnitError::Pattern(format!(
        "\"{}\" is not a row header: write \"Row 1 (RS):\", \"Rows 2 and 4:\", \"Rnd 3:\" or \
         \"All WS rows:\"",
        header.trim()
    ))
}

/// The repeat of one row, as worked (left to right in working order).
fn parse_body(body: &str, what: &str) -> Result<Vec<Stitch>> {
    let b = body.trim().trim_end_matches('.').trim();
    match b.to_lowercase().as_str() {
        "knit" | "k all sts" | "knit all sts" => return Ok(vec![Stitch::KNIT]),
        "purl" | "p all sts" | "purl all sts" => return Ok(vec![Stitch::PURL]),
        _ => {}
    }
    let mut unit = Vec::new();
    let mut in_repeat = false;
    let mut after_repeat = false;
    for (column, raw) in b.split([',', ';']).enumerate() {
        let token = raw.trim();
        if token.is_empty() {
            continue;
        }
        let lower = token.to_lowercase();
        if lower == "rep from *" || lower == "rep from * to end" {
            if !in_repeat {
                return Err(unsupported(
                    what,
                    column,
                    token,
                    "a repeat with no '*' before it",
                ));
            }
            in_repeat = false;
            after_repeat = true;
            continue;
        }
        if after_repeat {
            return Err(unsupported(
                what,
                column,
                token,
                "stitches after the repeat",
            ));
        }
        let stitch = match lower.strip_prefix('*') {
            Some(rest) => {
                if !unit.is_empty() {
                    return Err(unsupported(
                        what,
                        column,
                        token,
                        "stitches before the repeat",
                    ));
                }
                in_repeat = true;
                rest.trim()
            }
            None => lower.as_str(),
        };
        let (kind, count) = stitch_token(stitch).ok_or_else(|| unknown(what, column, token))?;
        if unit.len() + count > MAX_KNITSPEAK_WIDTH {
            return Err(KnitError::Pattern(format!(
                "{what}: the repeat is wider than {MAX_KNITSPEAK_WIDTH} stitches"
            )));
        }
        unit.extend(std::iter::repeat_n(kind, count));
    }
    if in_repeat {
        return Err(KnitError::Pattern(format!(
            "{what}: the repeat that starts with '*' never says \"rep from *\""
        )));
    }
    if unit.is_empty() {
        return Err(KnitError::Pattern(format!(
            "{what}: no stitches in \"{body}\""
        )));
    }
    Ok(unit)
}

/// `k`, `k2`, `p`, `p12` (lower case): the stitch and how many.
fn stitch_token(t: &str) -> Option<(Stitch, usize)> {
    let kind = match t.chars().next()? {
        'k' => Stitch::KNIT,
        'p' => Stitch::PURL,
        _ => return None,
    };
    let digits = t[1..].trim();
    let count = if digits.is_empty() {
        1
    } else {
        digits.parse::<usize>().ok().filter(|&n| n >= 1)?
    };
    Some((kind, count))
}

fn unknown(what: &str, column: usize, token: &str) -> KnitError {
    let lower = token.to_lowercase();
    let closest = KNOWN
        .iter()
        .min_by_key(|k| edit_distance(&lower, k))
        .copied()
        .unwrap_or("k");
    KnitError::Pattern(format!(
        "{what}, instruction {}: unknown stitch \"{token}\" (did you mean \"{closest}\"?). This \
         reader knows knit and purl repeats so far: k, p, kN, pN, Knit, Purl, *...rep from *",
        column + 1
    ))
}

fn unsupported(what: &str, column: usize, token: &str, why: &str) -> KnitError {
    KnitError::Pattern(format!(
        "{what}, instruction {} (\"{token}\"): {why} is not supported yet; write the row as one \
         repeat, e.g. \"*k2, p2; rep from *\"",
        column + 1
    ))
}

/// Levenshtein distance (for the "did you mean" suggestion; inputs are a few characters).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut row = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            row[j + 1] = (prev[j] + usize::from(ca != cb))
                .min(prev[j + 1] + 1)
                .min(row[j] + 1);
        }
        prev = row;
    }
    prev[b.len()]
}

fn lcm(a: usize, b: usize) -> usize {
    let gcd = |mut x: usize, mut y: usize| {
        while y != 0 {
            (x, y) = (y, x % y);
        }
        x
    };
    a / gcd(a, b) * b
}
