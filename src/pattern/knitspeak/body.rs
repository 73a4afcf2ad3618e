//! A row's body, the text after its header's `:` (`P2, *k2tog, yo, k1; rep from * to last 2
//! sts, p2 (18 sts)`), read into the stitches before its repeat, the repeat and how it ends,
//! the stitches after it, and its stitch count ([`parse_body`]). Each stitch phrase is read by
//! [`parse_stitch`] from the one vocabulary.

use super::lexer::{tokens, Tok};
use super::numbers;
use super::{MAX_BRACKET_DEPTH, MAX_KNITSPEAK_WIDTH};
use crate::error::{KnitError, Result};
use crate::pattern::instruction::MAX_CROSS_SIDE;
use crate::pattern::unknitted::unknitted;
use crate::pattern::vocabulary::{
    after_repeat_from, is_knit_or_purl_name, is_marker, normal_form, odd_cable_alias, parse_stitch,
    suggest, Stitched,
};

/// The longest instruction read, in bytes (`k2tog through the back loops 3 times` is 36).
const MAX_INSTRUCTION: usize = 160;

/// How an open repeat ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Until {
    /// Across the row (`rep from * to end`, or the stitches after it follow).
    End,
    /// `to last N sts`.
    Last(usize),
    /// `rep from * 2 more times`: this many times in all.
    Times(usize),
    /// `to m`, `to 2 sts before m`: to this many stitches before the next stitch marker (or
    /// the row's end, where the marker is the beginning of the round).
    Marker(usize),
}

/// One row's body: stitches before the repeat, the repeat, stitches after it (working order).
#[derive(Debug, Clone, Default)]
pub(super) struct Body {
    pub before: Vec<Stitched>,
    pub repeat: Option<(Vec<Stitched>, Until)>,
    pub after: Vec<Stitched>,
    /// `(18 sts)`
    pub count: Option<usize>,
    /// Width notes written in it (`(multiple of 2 sts, plus 2)`), as text, for the layout to
    /// check ([`super::width_note`]).
    pub notes: Vec<String>,
    /// `K the knit sts and p the purl sts` (or the purl sts knitted): a one-stitch open repeat
    /// whose stitches the layout takes from the row below ([`super::as_they_appear`]).
    pub faces: super::as_they_appear::Faces,
    /// Where stitch markers part the row (`K4, pm, p12, pm, k4`; `K to m, sm, p12, sm, k to
    /// end`), its parts between them in working order, each read as a body of its own (a run
    /// `to m` runs to the end of its part); empty where no marker parts the row (or where its
    /// parts cannot be read apart, `K2, pm, *k2, p2; rep from * to last 2 sts, k2`, whose
    /// repeat counts from the row's end).
    pub segments: Vec<Body>,
    /// A part other than the last has no fixed width (`k to m`): its width comes from the
    /// rows that count it ([`super::markers`]), and `before` / `repeat` / `after` are unread.
    pub to_marker: bool,
}

/// Loops of the row below that `v` works.
pub(super) fn loops_in(v: &[Stitched]) -> usize {
    v.iter().map(|s| s.ins.stitches_in()).sum()
}

impl Body {
    /// Stitches worked outside an open repeat, and the repeat's width (`None`: a fixed row).
    pub(super) fn widths(&self) -> (usize, Option<usize>) {
        let edges = loops_in(&self.before) + loops_in(&self.after);
        match &self.repeat {
            Some((unit, Until::Times(t))) => (edges + t * loops_in(unit), None),
            Some((unit, _)) => (edges, Some(loops_in(unit))),
            None => (edges, None),
        }
    }

    /// Its stitches over a piece (or a part between markers) `n` stitches wide, in working
    /// order; `n` is one the row fits ([`Self::widths`]).
    pub(super) fn over(&self, n: usize) -> Vec<Stitched> {
        let (edges, repeat) = self.widths();
        let mut out = self.before.clone();
        if let Some((unit, until)) = &self.repeat {
            let times = match (until, repeat) {
                (Until::Times(t), _) => *t,
                (_, Some(w)) => n.saturating_sub(edges) / w.max(1),
                _ => 0,
            };
            for _ in 0..times {
                out.extend_from_slice(unit);
            }
        }
        out.extend_from_slice(&self.after);
        out
    }
}

/// One element of a body, in the order written.
#[derive(Debug, Clone)]
enum El {
    Stitch(Stitched),
    /// `k to end`, `k to last 3 sts`, `Knit.`: a one-stitch open repeat.
    Fill(Stitched, Until, usize),
    /// A repeat opens at this instruction, marked with this many stars.
    RepStart(usize, u8),
    RepEnd(Until, usize),
    Count(usize),
    /// `pm`, `sm`: a stitch marker between two stitches.
    Marker,
    /// `yf` / `yb`: the yarn brought to the front or taken to the back, as British patterns
    /// write a slip with the yarn in front (`yf, sl1, yb`); `yarn_over`: the spelling is also
    /// a yarn-over's (`yf`, `yfwd`), which it is where no slip follows. At its instruction.
    YarnTo {
        front: bool,
        yarn_over: bool,
        at: usize,
    },
}

/// Reads a body's tokens into its elements, brackets expanded.
struct BodyParser<'a> {
    /// The pattern's own abbreviations ([`super::abbreviations`]), read before the
    /// vocabulary.
    defined: &'a [(String, crate::pattern::Instruction)],
    toks: Vec<Tok>,
    /// The next token.
    at: usize,
    what: &'a str,
    /// Instructions read so far (for messages, counted from 1).
    instruction: usize,
    /// A `Repeat rows 1-4` or `Multiple of 6 sts` phrase was met: what follows is no row.
    stop: bool,
    /// The body is one phrase (`Knit.`): a bare `k` or `knit` fills the row.
    single: bool,
    /// Width notes met, as text.
    notes: Vec<String>,
}

/// `3 times`, `three times`, `twice`, `once`, `3x` -> the count.
fn times(s: &str) -> Option<usize> {
    let s = s.trim().to_lowercase();
    match s.as_str() {
        "once" => return Some(1),
        "twice" => return Some(2),
        "thrice" => return Some(3),
        _ => {}
    }
    // `3 times`, `3x`; `x 3`, `x3`, `\u{d7} 3` as British patterns write it.
    let n = s
        .strip_suffix("times")
        .or_else(|| s.strip_suffix("x"))
        .or_else(|| s.strip_prefix('x'))
        .or_else(|| s.strip_prefix('\u{d7}'))?
        .trim();
    numbers::count(n).filter(|&n| n >= 1)
}

/// `6 sts`, `six stitches`, `1 st` (lower case) -> the stitch count.
fn stitch_count(lower: &str) -> Option<usize> {
    let n = lower
        .strip_suffix("stitches")
        .or_else(|| lower.strip_suffix("sts"))
        .or_else(|| lower.strip_suffix("st"))?;
    numbers::count(n)
}

/// Whether a bracket opening with `lower` is a note on the pattern's width, as in `k1
/// (multiple of 2 sts, plus 2).`, rather than stitches.
fn width_note(lower: &str) -> bool {
    [
        "multiple of",
        "a multiple of",
        "worked over",
        "over a multiple",
    ]
    .iter()
    .any(|w| lower.starts_with(w))
}

/// Instructions written in `toks` outside stitch counts (`(6 sts)`) and width notes: a body
/// of one (`Purl (6 sts).`) fills the row with it.
fn instructions_outside_counts(toks: &[Tok]) -> usize {
    let mut n = 0;
    let mut i = 0;
    while i < toks.len() {
        if let Tok::Open(_) = toks[i] {
            // The next bracket after this one: a group is set aside only if it is flat.
            let next = toks[i + 1..]
                .iter()
                .position(|t| matches!(t, Tok::Close(_) | Tok::Open(_)))
                .map(|k| i + 1 + k);
            if let Some(j) = next.filter(|&j| matches!(toks[j], Tok::Close(_))) {
                let texts: Vec<String> = toks[i + 1..j]
                    .iter()
                    .filter_map(|t| match t {
                        Tok::Text(t) => Some(t.trim().to_lowercase()),
                        _ => None,
                    })
                    .collect();
                let aside = match texts.first() {
                    Some(first) if width_note(first) => true,
                    Some(_) => texts.iter().all(|t| stitch_count(t).is_some()),
                    None => false,
                };
                if aside {
                    i = j + 1;
                    continue;
                }
            }
        }
        if !matches!(toks[i], Tok::Sep) {
            n += 1;
        }
        i += 1;
    }
    n
}

/// `k2tog 3 times` -> (`k2tog`, 3); a phrase without a count -> (phrase, 1).
fn split_times(s: &str) -> (String, usize) {
    for (word, n) in [("once", 1), ("twice", 2), ("thrice", 3)] {
        if let Some(head) = s.strip_suffix(word) {
            if head.ends_with(' ') {
                return (head.trim().to_string(), n);
            }
        }
    }
    if let Some((head, n)) = s
        .strip_suffix("times")
        .and_then(|h| h.trim().rsplit_once(' '))
        .and_then(|(h, n)| Some((h, numbers::count(n).filter(|&n| n >= 1)?)))
    {
        return (head.trim().to_string(), n);
    }
    (s.to_string(), 1)
}

/// Whether a stitch phrase (`p2`, `k1 tbl`, `knit two`; not `p`, `k tbl`) has its count
/// written.
fn written_count(phrase: &str) -> bool {
    phrase.contains(|c: char| c.is_ascii_digit())
        || phrase.split(' ').any(|w| numbers::count(w).is_some())
}

/// `to end`, `across`, `to last 3 sts`, `to last st` -> how a repeat ends.
fn until(s: &str) -> Option<Until> {
    let s = s.trim().to_lowercase();
    let s = s.trim_start_matches("and").trim();
    // `across to last 2 sts`: `across` says nothing more than `to`.
    let s = s
        .strip_prefix("across to ")
        .map_or(s.to_string(), |r| format!("to {r}"));
    let s = s.as_str();
    match s {
        ""
        | "to end"
        | "to the end"
        | "across"
        | "to end of row"
        | "to end of rnd"
        | "to end of round"
        | "to the end of the row"
        | "across row"
        | "across the row"
        | "all sts"
        | "all stitches"
        | "all the sts"
        | "all the stitches"
        | "every st"
        | "every stitch"
        | "each st"
        | "each stitch"
        | "all"
        | "around"
        | "all around" => return Some(Until::End),
        "to last st" | "to the last st" | "to last stitch" => return Some(Until::Last(1)),
        _ => {}
    }
    if let Some(n) = to_marker(s) {
        return Some(Until::Marker(n));
    }
    // `until 2 sts remain`, `until 1 st remains`.
    if let Some(rest) = s.strip_prefix("until ") {
        let n = rest
            .trim_end_matches("remain")
            .trim_end_matches("remains")
            .trim_end_matches("are left")
            .trim()
            .trim_end_matches("stitches")
            .trim_end_matches("sts")
            .trim_end_matches("st")
            .trim();
        return numbers::count(n).filter(|&n| n >= 1).map(Until::Last);
    }
    if let Some(rest) = s
        .strip_prefix("to last")
        .or_else(|| s.strip_prefix("to the last"))
    {
        let n = rest
            .trim()
            .trim_end_matches("stitches")
            .trim_end_matches("sts")
            .trim_end_matches("st");
        return numbers::count(n).map(Until::Last);
    }
    let more = ["more times", "times more", "more time", "time more"]
        .iter()
        .find_map(|w| s.strip_suffix(w))
        .map(numbers::count);
    // `3 times in all`: the count of the whole, as plainly as `2 more times` says the rest.
    let in_all = [
        "times in all",
        "times in total",
        "times total",
        "times altogether",
    ]
    .iter()
    .find_map(|w| s.strip_suffix(w))
    .or_else(|| s.strip_prefix("a total of")?.strip_suffix("times"))
    .map(numbers::count);
    match (s, more, in_all) {
        ("once more", ..) => Some(Until::Times(2)),
        ("twice more", ..) => Some(Until::Times(3)),
        (_, Some(Some(n)), _) => Some(Until::Times(n.saturating_add(1))),
        (_, _, Some(Some(n))) if n >= 1 => Some(Until::Times(n)),
        _ => None,
    }
}

/// Why `rest` (what follows `rep from *`) is no repeat's end: a plain count of times
/// (`2 times`, `twice`) is read two ways by knitters, as the times in all or the times more
/// than the first, and the row does not say which.
fn repeat_end_refused(rest: &str) -> String {
    let s = rest.trim().to_lowercase();
    let times = match s.as_str() {
        "once" => Some(1),
        "twice" => Some(2),
        "thrice" => Some(3),
        _ => s
            .strip_suffix("times")
            .or_else(|| s.strip_suffix("time"))
            .and_then(numbers::count),
    };
    match times {
        Some(n) if n >= 1 => format!(
            "\"{}\" is read two ways, {n} in all or {n} more after the first: write \
             \"{n} times in all\" or \"{n} more times\"",
            rest.trim()
        ),
        _ => "expected \"to end\", \"to last N sts\" or \"N more times\"".into(),
    }
}

/// `psso` (1) or `p2sso` (2), spelled out or not: how many slipped stitches are passed over
/// the stitches worked after them.
fn passes_over(lower: &str) -> Option<usize> {
    let norm = lower.trim().trim_end_matches('.').replace('-', " ");
    match norm.as_str() {
        "psso"
        | "pso"
        | "pass slipped st over"
        | "pass slipped stitch over"
        | "pass sl st over"
        | "pass the slipped st over"
        | "pass the slipped stitch over" => Some(1),
        "p2sso"
        | "pass 2 slipped sts over"
        | "pass two slipped sts over"
        | "pass the 2 slipped sts over"
        | "pass 2 sl sts over" => Some(2),
        _ => None,
    }
}

/// `in next st`, `into same st`, `all in next st`: what follows a bracket of stitches worked
/// into one loop (`(k1, p1, k1) in next st`).
fn worked_into_one(text: &str) -> bool {
    let t = text.trim().to_lowercase();
    let t = t.trim_start_matches("all ");
    ["in ", "into "].iter().any(|w| {
        t.strip_prefix(w).is_some_and(|r| {
            let r = r.trim_start_matches("the ");
            [
                "next st",
                "next stitch",
                "same st",
                "same stitch",
                "1 st",
                "one st",
                // `(k1, p1) into double yo`: the loop a double yarn-over made.
                "double yo",
                "double yarn over",
                "yo",
                "yarn over",
            ]
            .iter()
            .any(|s| r.starts_with(s))
        })
    })
}

/// `to m`, `to next marker`, `to 2 sts before m`, `to st before m` (lower case, trimmed) ->
/// the stitches the run leaves before the marker.
fn to_marker(s: &str) -> Option<usize> {
    let s = s.strip_prefix("to ")?.trim();
    let marker = |t: &str| {
        let t = t
            .trim()
            .trim_start_matches("the ")
            .trim_start_matches("next ");
        matches!(t, "m" | "marker")
    };
    if marker(s) {
        return Some(0);
    }
    let (n, m) = s.split_once(" before ")?;
    if !marker(m) {
        return None;
    }
    let n = n
        .trim()
        .trim_start_matches("the ")
        .trim_start_matches("last ");
    if matches!(n, "st" | "stitch") {
        return Some(1);
    }
    let n = n
        .trim_end_matches("stitches")
        .trim_end_matches("sts")
        .trim_end_matches("st")
        .trim();
    numbers::count(n).filter(|&n| n >= 1)
}

impl BodyParser<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.at)
    }

    /// Passes over the rest of a bracket opened with `open`, nested brackets included.
    fn skip_to_close(&mut self, open: char) -> Result<()> {
        let mut depth = 1usize;
        while let Some(tok) = self.peek() {
            match tok {
                Tok::Open(_) => depth += 1,
                Tok::Close(_) => depth -= 1,
                _ => {}
            }
            self.at += 1;
            if depth == 0 {
                return Ok(());
            }
        }
        Err(self.err(&open.to_string(), "this bracket is never closed"))
    }

    /// The text of tokens `from..to`, separators as commas.
    fn texts(&self, from: usize, to: usize) -> String {
        let mut out = String::new();
        for t in &self.toks[from..to] {
            match t {
                Tok::Text(t) => {
                    if !out.is_empty() && !out.ends_with(", ") {
                        out.push(' ');
                    }
                    out.push_str(t.trim());
                }
                Tok::Sep => out.push_str(", "),
                _ => {}
            }
        }
        out
    }

    fn err(&self, token: &str, why: &str) -> KnitError {
        KnitError::Pattern(format!(
            "{}, instruction {} (\"{token}\"): {why}",
            self.what, self.instruction
        ))
    }

    /// Elements up to a closing bracket (`close`) or the end.
    fn list(&mut self, close: Option<char>, depth: usize) -> Result<Vec<El>> {
        let mut els = Vec::new();
        while let Some(tok) = self.peek().cloned() {
            if self.stop {
                break;
            }
            self.at += 1;
            match tok {
                Tok::Sep => {}
                Tok::Star(stars) => {
                    if depth > 0 {
                        return Err(self.err("*", "a repeat cannot start inside brackets"));
                    }
                    els.push(El::RepStart(self.instruction + 1, stars));
                }
                Tok::Close(c) => {
                    if close.is_some() {
                        return Ok(els);
                    }
                    return Err(self.err(&c.to_string(), "a closing bracket with no opening one"));
                }
                Tok::Open(c) => {
                    // `(multiple of 2 sts, plus 2)`: says what the chart's repeat does anyway.
                    if let Some(Tok::Text(t)) = self.peek() {
                        if width_note(t.trim().to_lowercase().as_str()) {
                            let from = self.at;
                            self.skip_to_close(c)?;
                            let note = self.texts(from, self.at);
                            self.notes.push(note);
                            continue;
                        }
                    }
                    // Written patterns nest brackets two or three deep; a bound keeps the
                    // recursion far from the end of any thread's stack.
                    if depth >= MAX_BRACKET_DEPTH {
                        return Err(self.err(
                            &c.to_string(),
                            &format!("brackets nest more than {MAX_BRACKET_DEPTH} deep"),
                        ));
                    }
                    let inner = self.list(Some(c), depth + 1)?;
                    // `(18 sts)`: a stitch count.
                    if let [El::Count(n)] = inner.as_slice() {
                        els.push(El::Count(*n));
                        continue;
                    }
                    // `[k1, p1] to end`, `(k2, p2) across`: the group repeated across the row.
                    if let Some(Tok::Text(t)) = self.peek().cloned() {
                        // `[k2, p2] rep to end` says it twice.
                        let lower = t.trim().to_lowercase();
                        let said = after_repeat_from(&lower).unwrap_or(&lower);
                        let open_ended = until(said).filter(|u| !matches!(u, Until::Times(_)));
                        if let (Some(u), 0) = (open_ended, depth) {
                            self.at += 1;
                            self.instruction += 1;
                            els.push(El::RepStart(self.instruction, 0));
                            els.extend(inner);
                            els.push(El::RepEnd(u, self.instruction));
                            continue;
                        }
                    }
                    // `(k1, p1, k1) in next st`: several stitches worked into one loop.
                    if let Some(Tok::Text(t)) = self.peek().cloned() {
                        if worked_into_one(&t) {
                            let made = inner
                                .iter()
                                .filter(|el| matches!(el, El::Stitch(_)))
                                .count();
                            return Err(self.err(
                                &t,
                                &format!(
                                    "works {made} stitches into one loop (a 1-to-{made} \
                                     increase): knitwear does not knit a loop that several \
                                     stitches are pulled through yet, even where a decrease in \
                                     the same row balances it"
                                ),
                            ));
                        }
                    }
                    let mut n = 1;
                    if let Some(Tok::Text(t)) = self.peek().cloned() {
                        self.at += 1;
                        n = times(&t)
                            .ok_or_else(|| self.err(&t, "expected \"N times\" after brackets"))?;
                    }
                    if inner.len().saturating_mul(n) + els.len() > 16 * MAX_KNITSPEAK_WIDTH {
                        return Err(self.err(&format!("{n} times"), "far too many stitches"));
                    }
                    for _ in 0..n {
                        els.extend(inner.iter().cloned());
                    }
                }
                Tok::Text(t) => self.text(&t, &mut els, close.is_some())?,
            }
        }
        if let Some(c) = close {
            return Err(self.err(&c.to_string(), "this bracket is never closed"));
        }
        Ok(els)
    }

    /// `sl1, k1, psso` written as three instructions: the slipped stitches and the stitch
    /// worked after them, already read, become the decrease they make together (`skp`, `sk2p`,
    /// `cdd`, `cddp`), as the one-phrase spellings (`sl1-k1-psso`) read.
    fn pass_over(&self, t: &str, slipped: usize, els: &mut Vec<El>) -> Result<()> {
        use crate::pattern::Instruction as I;
        let tail: Vec<I> = els
            .iter()
            .rev()
            .take(slipped + 1)
            .map_while(|el| match el {
                El::Stitch(s) => Some(s.ins),
                _ => None,
            })
            .collect();
        let slip = |i: &I| matches!(i, I::Slip { .. });
        let made = match (slipped, tail.as_slice()) {
            (1, [I::Knit, s]) if slip(s) => Some(I::Ssk),
            (1, [I::K2tog, s]) if slip(s) => Some(I::Sk2p),
            (2, [I::Knit, a, b]) if slip(a) && slip(b) => Some(I::Cdd),
            (2, [I::Purl, a, b]) if slip(a) && slip(b) => Some(I::Cddp),
            _ => None,
        };
        let Some(made) = made else {
            return Err(self.err(
                t,
                "passes slipped stitches over the stitches worked after them: knitwear reads \
                 \"sl1, k1, psso\" (skp), \"sl1, k2tog, psso\" (sk2p), \"sl2, k1, p2sso\" \
                 (cdd) and \"sl2, p1, p2sso\" (cddp); a slipped stitch passed over two or more \
                 stitches, each keeping its loop, is not knitted yet",
            ));
        };
        els.truncate(els.len() - slipped - 1);
        els.push(El::Stitch(Stitched {
            ins: made,
            slip_default: false,
        }));
        Ok(())
    }

    /// Closes the repeat opened by `stars` stars (0: by the last one opened, for `rep` and
    /// `rep *` spellings that do not say) with `u`. A row holds one repeat that the body
    /// keeps as such ([`Body::repeat`]); a repeat worked a set number of times inside or
    /// beside another (`*k1, **p1, k1; rep from ** twice more, p1; rep from *`) is written
    /// out in place, as a knitter works it.
    fn close_repeat(&self, t: &str, u: Until, stars: u8, els: &mut Vec<El>) -> Result<()> {
        let starts = |els: &[El]| {
            els.iter()
                .enumerate()
                .filter_map(|(i, el)| match el {
                    El::RepStart(_, s) => Some((i, *s)),
                    _ => None,
                })
                .collect::<Vec<_>>()
        };
        let open = starts(els);
        let matching = open
            .iter()
            .rev()
            .find(|&&(_, s)| stars == 0 || s == stars || (stars == 1 && s == 0))
            .or(open.last());
        let Some(&(at, _)) = matching else {
            // `K2, p2, rep to end`: a `rep` that names no `*`, after stitches only, repeats the
            // row so far, as `K2, p2 to end` does. A `rep from *` with no `*` before it is
            // left for the body to report: where its star was lost is a guess.
            let row_so_far = stars == 0
                && !matches!(u, Until::Times(_))
                && !els.is_empty()
                && els.iter().all(|el| matches!(el, El::Stitch(_)));
            if row_so_far {
                els.insert(0, El::RepStart(1, 0));
            }
            els.push(El::RepEnd(u, self.instruction));
            return Ok(());
        };
        let others = open.len() > 1;
        match u {
            Until::Times(n) if others || stars > 1 => {
                if els[at + 1..].iter().any(|el| matches!(el, El::RepEnd(..))) {
                    return Err(self.err(t, "a repeat that holds another open-ended repeat"));
                }
                let unit: Vec<El> = els.drain(at..).skip(1).collect();
                if unit.len().saturating_mul(n) + els.len() > 16 * MAX_KNITSPEAK_WIDTH {
                    return Err(self.err(t, "far too many stitches"));
                }
                for _ in 0..n {
                    els.extend(unit.iter().cloned());
                }
            }
            _ => {
                // A repeat worked a set number of times before this one is written out, so
                // that the row keeps one repeat.
                let closed = open
                    .iter()
                    .filter(|&&(i, _)| i < at)
                    .find_map(|&(first, _)| {
                        els[first..at]
                            .iter()
                            .enumerate()
                            .find_map(|(e, el)| match el {
                                El::RepEnd(Until::Times(n), _) => Some((first, first + e, *n)),
                                _ => None,
                            })
                    });
                if let Some((first, end, n)) = closed {
                    let unit: Vec<El> = els[first + 1..end].to_vec();
                    let tail: Vec<El> = els.drain(first..).skip(end - first + 1).collect();
                    for _ in 0..n {
                        els.extend(unit.iter().cloned());
                    }
                    els.extend(tail);
                }
                els.push(El::RepEnd(u, self.instruction));
            }
        }
        Ok(())
    }

    fn text(&mut self, t: &str, els: &mut Vec<El>, in_brackets: bool) -> Result<()> {
        let lower = t.to_lowercase();
        let lower = lower.trim();
        if in_brackets {
            if let Some(n) = stitch_count(lower) {
                els.push(El::Count(n));
                return Ok(());
            }
        }
        if [
            "repeat rows",
            "rep rows",
            "repeat rnds",
            "rep rnds",
            "work rows",
            "multiple of",
        ]
        .iter()
        .any(|w| lower.starts_with(w))
            || super::headers::forms_the_pattern(lower)
        {
            if width_note(lower) {
                // The sentence runs to the body's end: `Multiple of 4 sts, plus 2.`
                let note = self.texts(self.at.saturating_sub(1), self.toks.len());
                self.notes.push(note);
            }
            self.stop = true;
            return Ok(());
        }
        self.instruction += 1;
        // No instruction is this long; reading one (its runs split at every space, its
        // closest stitch) costs the square of its length.
        if lower.len() > MAX_INSTRUCTION {
            let cut: String = t.trim().chars().take(40).collect();
            return Err(KnitError::Pattern(format!(
                "{}, instruction {}: \"{cut}...\" runs {} characters without a comma or a \
                 full stop: no instruction is that long (separate the instructions with commas)",
                self.what,
                self.instruction,
                t.trim().chars().count()
            )));
        }
        if is_marker(lower) {
            els.push(El::Marker);
            return Ok(());
        }
        if let Some((front, yarn_over)) = yarn_to(lower) {
            els.push(El::YarnTo {
                front,
                yarn_over,
                at: self.instruction,
            });
            return Ok(());
        }
        if let Some(slipped) = passes_over(lower) {
            return self.pass_over(t, slipped, els);
        }
        // `*k1, p1; rep from *, ending k1`: the stitches the row ends with, after its repeat.
        // `end last rep k1` says the same: the last repeat stops after its first stitch.
        if matches!(els.last(), Some(El::RepEnd(..))) {
            let ending = [
                "ending last rep with ",
                "ending last repeat with ",
                "end last rep with ",
                "end last repeat with ",
                "ending last rep ",
                "ending last repeat ",
                "end last rep ",
                "end last repeat ",
                "ending with ",
                "end with ",
                "ending ",
                "end ",
            ]
            .iter()
            .find_map(|w| lower.strip_prefix(w));
            if let Some(rest) = ending {
                self.instruction -= 1;
                return self.text(rest, els, in_brackets);
            }
        }
        if let Some(rest) = after_repeat_from(lower) {
            // `rep from beg`, `repeat from beginning of row`: the row so far is the repeat, as
            // a `rep` that names no star reads.
            let from = rest.trim_start();
            let from = from.strip_prefix("from").map_or(from, str::trim_start);
            let from = from.strip_prefix("the ").unwrap_or(from);
            let from_start = ["beginning", "beg"]
                .iter()
                .find_map(|w| from.strip_prefix(w))
                .filter(|r| r.is_empty() || r.starts_with([' ', '.', ',']))
                .map(|r| {
                    let r = r.trim_start_matches(['.', ',']).trim_start();
                    [
                        "of the row",
                        "of row",
                        "of the rnd",
                        "of rnd",
                        "of the round",
                        "of round",
                    ]
                    .iter()
                    .find_map(|w| r.strip_prefix(w))
                    .unwrap_or(r)
                });
            if let Some(tail) = from_start {
                let u = until(tail).ok_or_else(|| self.err(t, &repeat_end_refused(tail)))?;
                return self.close_repeat(t, u, 0, els);
            }
            // `rep from **`: the phrase read its first star.
            let more = rest.trim_start().len() - rest.trim_start().trim_start_matches('*').len();
            let stars = if rest.trim_start().starts_with('*') || lower.contains("from *") {
                1 + more as u8
            } else {
                0
            };
            let tail = rest.trim_start().trim_start_matches('*');
            let u = until(tail).ok_or_else(|| self.err(t, &repeat_end_refused(tail)))?;
            if let Until::Times(n) = u {
                // No row is that wide: refused before the repeat is worked out (a count near
                // the integer's range wrapped, or filled the memory).
                if n > MAX_KNITSPEAK_WIDTH {
                    return Err(self.err(
                        t,
                        &format!(
                            "a repeat worked {n} times: a pattern's row holds at most \
                             {MAX_KNITSPEAK_WIDTH} stitches"
                        ),
                    ));
                }
            }
            return self.close_repeat(t, u, stars, els);
        }
        // `Knit 1 row.` says what `Knit.` says.
        let lower = [
            "1 row",
            "one row",
            "1 rnd",
            "one rnd",
            "1 round",
            "one round",
        ]
        .iter()
        .find_map(|w| lower.strip_suffix(w))
        .map(str::trim)
        .filter(|name| self.single && is_knit_or_purl_name(name))
        .unwrap_or(lower);
        // A one-stitch open repeat: `Knit`, `k to end`, `p to last 3 sts`, `knit across`.
        let bare = self.single && is_knit_or_purl_name(lower);
        for (i, _) in lower.match_indices(' ') {
            let (head, tail) = lower.split_at(i);
            let (Some(u), Some((s, count))) = (until(tail), parse_stitch(head)) else {
                continue;
            };
            if tail.trim().is_empty() || s.ins.stitches_in() != 1 {
                continue;
            }
            // `K2, p2 to end`, `K1, p1 to last st, k1`: a run with its count written repeats
            // the row so far (a count means nothing on a run of one stitch): as printed
            // patterns write rib, `[k2, p2] to end`. `K1, p to end` is one knit stitch and a
            // run of purls.
            if written_count(head) && els.iter().all(|el| matches!(el, El::Stitch(_))) {
                els.insert(0, El::RepStart(1, 0));
                els.extend(std::iter::repeat_n(El::Stitch(s), count));
                els.push(El::RepEnd(u, self.instruction));
                return Ok(());
            }
            if count == 1 {
                els.push(El::Fill(s, u, self.instruction));
                return Ok(());
            }
        }
        // `k2tog 3 times`
        let (phrase, n) = split_times(lower);
        let own = normal_form(&phrase);
        let own = self
            .defined
            .iter()
            .find(|(name, _)| *name == own)
            .map(|&(_, ins)| (Stitched::plain(ins), 1));
        let Some((s, count)) = own.or_else(|| parse_stitch(&phrase)) else {
            if n == 1 {
                if let Some(stitches) = without_commas(&phrase) {
                    if stitches.len() + els.len() > 16 * MAX_KNITSPEAK_WIDTH {
                        return Err(self.err(t, "far too many stitches"));
                    }
                    els.extend(stitches.into_iter().map(El::Stitch));
                    return Ok(());
                }
            }
            return Err(unknown(self.what, self.instruction, t));
        };
        if bare && !in_brackets {
            els.push(El::Fill(s, Until::End, self.instruction));
            return Ok(());
        }
        let total = count.saturating_mul(n);
        if total > MAX_KNITSPEAK_WIDTH {
            return Err(self.err(t, &format!("more than {MAX_KNITSPEAK_WIDTH} stitches")));
        }
        els.extend(std::iter::repeat_n(El::Stitch(s), total));
        Ok(())
    }
}

/// `k2 p2`, `yo k2tog`: stitches written one after another without the commas between
/// them, as quick notes write rib. Each word must be a stitch with its count written (`k2`,
/// not `k`, whose run would fill the row) or one that works a set count (`yo`, `ssk`); a
/// word that is no stitch (`tbl`, `tog`, `below`, a number) reads nothing, so a stitch's
/// own words are never split apart. `None` for one word, or where any word is none.
fn without_commas(phrase: &str) -> Option<Vec<Stitched>> {
    let words: Vec<&str> = phrase.split_whitespace().collect();
    if words.len() < 2 {
        return None;
    }
    let mut out = Vec::new();
    for word in words {
        let (s, count) = parse_stitch(word)?;
        let counted = word.bytes().any(|b| b.is_ascii_digit());
        if !counted && is_knit_or_purl_name(word) {
            return None;
        }
        out.extend(std::iter::repeat_n(s, count.min(MAX_KNITSPEAK_WIDTH + 1)));
    }
    Some(out)
}

/// `yf`, `yarn to front` -> (front, also a yarn-over's spelling); `yb`, `yarn to back` ->
/// (back, no). `None` for any other phrase.
fn yarn_to(lower: &str) -> Option<(bool, bool)> {
    let norm = lower.trim().trim_end_matches('.');
    if ["yf", "yfwd", "yarn forward", "yarn fwd"].contains(&norm) {
        return Some((true, true));
    }
    if [
        "ytf",
        "yarn to front",
        "bring yarn to front",
        "bring yarn forward",
    ]
    .contains(&norm)
    {
        return Some((true, false));
    }
    if [
        "yb",
        "ybk",
        "ytb",
        "yarn back",
        "yarn bk",
        "yarn to back",
        "take yarn to back",
        "take yarn back",
    ]
    .contains(&norm)
    {
        return Some((false, false));
    }
    None
}

/// The yarn moves of `els` read: stitches slipped between a move of the yarn and its move
/// back (`yf, sl1, yb`, `yb, sl2, yf`) are slipped with the yarn on the side it was moved
/// to, as `sl1 wyif` says; a `yf` (or `yfwd`) that no slip and move back follow is the
/// yarn-over British patterns mean by it (`k1, yf, k2tog`). Any other move is refused.
fn slips_between_yarn_moves(els: Vec<El>, what: &str) -> Result<Vec<El>> {
    use crate::pattern::Instruction as I;
    let mut out = Vec::with_capacity(els.len());
    let mut i = 0;
    while i < els.len() {
        let El::YarnTo {
            front,
            yarn_over,
            at,
        } = els[i]
        else {
            out.push(els[i].clone());
            i += 1;
            continue;
        };
        let slips = els[i + 1..]
            .iter()
            .take_while(|el| matches!(el, El::Stitch(s) if matches!(s.ins, I::Slip { .. })))
            .count();
        let back = els
            .get(i + 1 + slips)
            .is_some_and(|el| matches!(el, El::YarnTo { front: f, .. } if *f != front));
        if slips > 0 && back {
            let slip = Stitched {
                ins: I::Slip { yarn_front: front },
                slip_default: false,
            };
            out.extend(std::iter::repeat_n(El::Stitch(slip), slips));
            i += slips + 2;
            continue;
        }
        if front && yarn_over {
            out.push(El::Stitch(Stitched {
                ins: I::YarnOver,
                slip_default: false,
            }));
            i += 1;
            continue;
        }
        return Err(KnitError::Pattern(format!(
            "{what}, instruction {at}: a move of the yarn to the {} is read only around \
             slipped stitches, moved back after them (\"yf, sl1, yb\": sl1 wyif)",
            if front { "front" } else { "back" }
        )));
    }
    Ok(out)
}

/// A row's body (after its header's `:`), in working order.
pub(super) fn parse_body(
    body: &str,
    what: &str,
    defined: &[(String, crate::pattern::Instruction)],
) -> Result<Body> {
    let toks = tokens(body);
    let single = instructions_outside_counts(&toks) == 1;
    let mut p = BodyParser {
        defined,
        single,
        toks,
        at: 0,
        what,
        instruction: 0,
        stop: false,
        notes: Vec::new(),
    };
    let els = slips_between_yarn_moves(p.list(None, 0)?, what)?;
    let notes = std::mem::take(&mut p.notes);
    let count = els.iter().fold(None, |c, el| match el {
        El::Count(n) => Some(*n),
        _ => c,
    });
    let parts = parted(els);
    let open_part = parts.len() > 1
        && parts[..parts.len() - 1]
            .iter()
            .any(|part| part.iter().any(runs_to_marker));
    let segments = if parts.len() > 1 {
        let last = parts.len() - 1;
        let read: Result<Vec<Body>> = parts
            .iter()
            .enumerate()
            .map(|(i, part)| body_of(part.clone(), what, body, i == last))
            .collect();
        match read {
            Ok(segments) => segments,
            // A part that cannot be read alone (a repeat counted from the row's end) matters
            // only where a run ends at a marker; elsewhere the markers change nothing.
            Err(e) if open_part => return Err(e),
            Err(_) => Vec::new(),
        }
    } else {
        Vec::new()
    };
    let mut out = if open_part {
        Body {
            to_marker: true,
            ..Body::default()
        }
    } else {
        body_of(parts.concat(), what, body, true)?
    };
    out.count = count;
    out.notes = notes;
    out.segments = segments;
    Ok(out)
}

/// Whether `el` is a run or a repeat that stops at a marker (`k to m`, `rep from * to 2 sts
/// before m`).
fn runs_to_marker(el: &El) -> bool {
    matches!(
        el,
        El::Fill(_, Until::Marker(_), _) | El::RepEnd(Until::Marker(_), _)
    )
}

/// A body's elements parted at its stitch markers, the markers dropped. A run `to m` ends its
/// part where no marker follows it at once (`K to m, p to end`: the marker is slipped without
/// a word), and a run `to 2 sts before m` ends it 2 stitches later (a yarn-over straight after
/// those stays in it: `k to 2 sts before m, k2tog, yo, k1`). Markers inside a `*`
/// repeat, and those before the first stitch or after the last, part nothing.
fn parted(els: Vec<El>) -> Vec<Vec<El>> {
    let mut parts = vec![Vec::new()];
    let mut in_repeat = false;
    // Loops still to be worked before a run's marker: `Some(0)` parts at the next element.
    let mut pending: Option<usize> = None;
    for el in els {
        let part_here = match (&el, pending) {
            (El::Marker, _) => {
                pending = None;
                !in_repeat
            }
            (El::Count(_), _) => false,
            // A yarn-over right after the stitches before the marker stays with them.
            (El::Stitch(s), Some(0)) if s.ins.stitches_in() == 0 => false,
            (El::Stitch(_), Some(0)) | (El::Fill(..) | El::RepStart(..), Some(_)) => {
                pending = None;
                true
            }
            _ => false,
        };
        if part_here && !parts.last().is_some_and(Vec::is_empty) {
            parts.push(Vec::new());
        }
        match &el {
            El::RepStart(..) => in_repeat = true,
            El::RepEnd(u, _) => {
                in_repeat = false;
                if let Until::Marker(n) = u {
                    pending = Some(*n);
                }
            }
            El::Fill(_, Until::Marker(n), _) => pending = Some(*n),
            El::Stitch(s) => {
                if let Some(n) = pending.as_mut() {
                    *n = n.saturating_sub(s.ins.stitches_in());
                }
            }
            _ => {}
        }
        if !matches!(el, El::Marker) {
            parts.last_mut().expect("one part at least").push(el);
        }
    }
    parts.retain(|p| p.iter().any(|el| !matches!(el, El::Count(_))));
    if parts.is_empty() {
        parts.push(Vec::new());
    }
    parts
}

/// The body of `els`, a whole row or one part of it between markers: its stitches before its
/// repeat, the repeat and those after. `last`: the part runs to the row's end, so `to end` and
/// `to last N sts` may end its repeat; a run `to m` ends at the part's end either way.
fn body_of(els: Vec<El>, what: &str, body: &str, last: bool) -> Result<Body> {
    let mut out = Body::default();
    // A run to a marker runs to its part's end, as `to end` / `to last N sts` runs to the
    // row's.
    let to_end = |u: Until, at: usize| match u {
        Until::Marker(0) => Ok(Until::End),
        Until::Marker(n) => Ok(Until::Last(n)),
        Until::End | Until::Last(_) if !last => Err(KnitError::Pattern(format!(
            "{what}, instruction {at}: a run to the end of the row before a stitch marker: \
             end it at the marker (\"to m\")"
        ))),
        u => Ok(u),
    };
    // 0: before the repeat, 1: inside it, 2: after it, 3: inside a second repeat that works
    // the stitches the first left (`*k2, p2; rep from * to last 4 sts, *k1, p1; rep from *
    // to end`).
    let mut stage = 0;
    let mut unit = Vec::new();
    let mut star_at = 0;
    // Stitches the first repeat left, for a second one.
    let mut left = 0;
    for el in els {
        match el {
            El::Count(n) => out.count = Some(n),
            El::Marker | El::YarnTo { .. } => {}
            El::Stitch(s) => match stage {
                0 => out.before.push(s),
                1 | 3 => unit.push(s),
                _ => out.after.push(s),
            },
            El::RepStart(at, _) => {
                if let (2, Some((_, Until::Last(n)))) = (stage, &out.repeat) {
                    left = *n;
                    stage = 3;
                    star_at = at;
                    continue;
                }
                if stage != 0 {
                    return Err(KnitError::Pattern(format!(
                        "{what}, instruction {at}: a second '*' repeat in one row; knitwear \
                         reads one repeat per row"
                    )));
                }
                stage = 1;
                star_at = at;
            }
            El::RepEnd(u, at) if stage == 3 => {
                // Worked over what the first repeat left, less the stitches between them and
                // those this one leaves in turn.
                let worked = loops_in(&out.after);
                let width = loops_in(&unit);
                let times = match u {
                    Until::Times(t) => Some(t),
                    Until::End | Until::Last(_) | Until::Marker(_) => {
                        let leaves = match to_end(u, at)? {
                            Until::Last(m) => m,
                            _ => 0,
                        };
                        let span = left.saturating_sub(worked + leaves);
                        (width > 0 && span > 0 && span % width == 0).then(|| span / width)
                    }
                };
                let Some(times) = times else {
                    return Err(KnitError::Pattern(format!(
                        "{what}, instruction {at}: this repeat of {width} stitches does not \
                         fill the {left} stitches the repeat before it left ({worked} already \
                         worked)"
                    )));
                };
                for _ in 0..times {
                    out.after.extend_from_slice(&unit);
                }
                unit.clear();
                stage = 2;
            }
            El::RepEnd(u, at) => {
                if stage != 1 {
                    return Err(KnitError::Pattern(format!(
                        "{what}, instruction {at} (\"rep from *\"): a repeat with no '*' \
                         before it"
                    )));
                }
                out.repeat = Some((std::mem::take(&mut unit), to_end(u, at)?));
                stage = 2;
            }
            El::Fill(s, u, at) => {
                let u = to_end(u, at)?;
                if stage != 0 {
                    // A run after one that stopped `to last N sts` works what that one left,
                    // less the stitches worked between and those it leaves in turn:
                    // `k to last 2 sts, p to end` is `k to last 2 sts, p2`.
                    let left = match (&out.repeat, stage) {
                        (Some((_, Until::Last(n))), 2) => Some(*n),
                        _ => None,
                    };
                    let leaves = match u {
                        Until::End => Some(0),
                        Until::Last(m) => Some(m),
                        Until::Times(_) | Until::Marker(_) => None,
                    };
                    let worked: usize = out.after.iter().map(|x| x.ins.stitches_in()).sum();
                    if let (Some(n), Some(m)) = (left, leaves) {
                        if n > worked + m {
                            out.after.extend(std::iter::repeat_n(s, n - worked - m));
                            continue;
                        }
                    }
                    let to = match u {
                        Until::Last(1) => "to last st".to_string(),
                        Until::Last(n) => format!("to last {n} sts"),
                        _ => "to end".to_string(),
                    };
                    return Err(KnitError::Pattern(format!(
                        "{what}, instruction {at}: \"{} {to}\" inside or after another \
                         repeat",
                        s.ins.name()
                    )));
                }
                out.repeat = Some((vec![s], u));
                stage = 2;
            }
        }
    }
    if stage == 1 || stage == 3 {
        return Err(KnitError::Pattern(format!(
            "{what}: the repeat that starts with '*' (instruction {star_at}) never says \
             \"rep from *\""
        )));
    }
    // `rep from *` followed by stitches: the repeat stops where they start.
    if out.before.is_empty() && out.repeat.is_none() && out.after.is_empty() {
        return Err(KnitError::Pattern(format!(
            "{what}: no stitches in \"{}\"",
            body.trim()
        )));
    }
    Ok(out)
}

/// An unknown stitch, with the closest one the vocabulary offers.
fn unknown(what: &str, instruction: usize, token: &str) -> KnitError {
    // `p0`: a stitch the vocabulary knows, worked no times.
    let lower = token.trim().to_lowercase();
    let head = lower.trim_end_matches(|c: char| c.is_ascii_digit());
    if head.len() < lower.len()
        && numbers::count(&lower[head.len()..]) == Some(0)
        && parse_stitch(&format!("{head}1")).is_some()
    {
        return KnitError::Pattern(format!(
            "{what}, instruction {instruction}: \"{}\" works no stitches: a stitch count is 1 \
             or more (leave the instruction out)",
            token.trim()
        ));
    }
    // A stitch knitwear knows but does not knit (`kfb`, `bo 2`, `w&t`): say what it is, not
    // which known stitch it is spelled like.
    if let Some(why) = unknitted(token) {
        return KnitError::Pattern(format!("{what}, instruction {instruction}: {why}"));
    }
    // `Work even`, `Work in patt`: a row that says only "as before", which a stitch pattern's
    // rows do not set.
    let as_set = [
        "work even",
        "work in patt",
        "work in pattern",
        "cont in patt",
        "continue in patt",
        "continue in pattern",
        "work as set",
        "work in patt as set",
    ];
    if as_set.iter().any(|w| lower.starts_with(w)) {
        return KnitError::Pattern(format!(
            "{what}, instruction {instruction}: \"{}\" works the row as earlier rows set it, \
             which a stitch pattern's own rows do not say: write the row's stitches (\"k the \
             knit sts and p the purl sts\" where each stitch is worked as it faces you), or \
             leave the row out",
            token.trim()
        ));
    }
    if let Some(why) = odd_cable_alias(token) {
        return KnitError::Pattern(format!("{what}, instruction {instruction}: {why}"));
    }
    let closest = suggest(token);
    // A well-formed cross too wide for the vocabulary is "closest" to itself: say why instead.
    if closest.eq_ignore_ascii_case(token.trim()) {
        let why = if token.matches('/').count() == 2 {
            format!(
                "a cable around a centre (m/c/n) moves each group at most {MAX_CROSS_SIDE} \
                 columns: m + c and c + n are at most {MAX_CROSS_SIDE} (e.g. \"3/3/3 RC\")"
            )
        } else if token.contains('/') {
            format!(
                "a cable or twist crosses at most {MAX_CROSS_SIDE} stitches over \
                 {MAX_CROSS_SIDE} (e.g. \"6/6 RC\")"
            )
        } else {
            "it is not in knitwear's stitch vocabulary".to_string()
        };
        return KnitError::Pattern(format!(
            "{what}, instruction {instruction}: unknown stitch \"{token}\": {why}"
        ));
    }
    KnitError::Pattern(format!(
        "{what}, instruction {instruction}: unknown stitch \"{token}\" (did you mean \
         \"{closest}\"?)"
    ))
}
