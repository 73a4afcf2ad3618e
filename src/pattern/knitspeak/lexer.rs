//! Cutting Knitspeak text into pieces: the text into `(header, body)` statements
//! ([`statements`]), and a row body into tokens ([`tokens`]): separators, the `*` that starts
//! a repeat, brackets, and the text between them.

/// Words a statement's header starts with (lower case). Also how a Knitspeak text is told from
/// a chart ([`super::looks_like_knitspeak`]), so both read headers alike.
const HEADER_WORDS: [&str; 15] = [
    "row",
    "rnd",
    "round",
    "all ",
    "every ",
    "odd ",
    "even ",
    "rs ",
    "ws ",
    "right side ",
    "wrong side ",
    "set-up ",
    "set up ",
    "setup ",
    "foundation ",
];

/// `text` with the em dash that Barbara Walker's treasuries put after a row header (`Row 1
/// (Wrong side)—Knit.`) read as the `:` other texts put there: each dash whose sentence
/// (from the line's start or the last full stop) opens with a header word and holds no `:`.
pub(super) fn walker_dashes(text: &str) -> std::borrow::Cow<'_, str> {
    const DASH: char = '\u{2014}';
    if !text.contains(DASH) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    // The sentence so far: since the line's start or the last full stop.
    let mut sentence = String::new();
    for ch in text.chars() {
        if ch == DASH {
            let lower = sentence.trim_start().to_lowercase();
            if HEADER_WORDS.iter().any(|w| lower.starts_with(w)) && !lower.contains(':') {
                out.push(':');
                sentence.push(':');
                continue;
            }
        }
        out.push(ch);
        if matches!(ch, '.' | '\n') {
            sentence.clear();
        } else {
            sentence.push(ch);
        }
    }
    std::borrow::Cow::Owned(out)
}

/// Whether `lower` (lower case) starts with a row header: a header word, with a `:` after it.
pub(super) fn opens_statement(lower: &str) -> bool {
    HEADER_WORDS.iter().any(|w| lower.starts_with(w)) && lower.contains(':')
}

/// Whether `line` opens a row statement: a header that reads as rows (`Row 1 (RS):`,
/// `All WS rows:`, `Set-up row:`), then its `:`. `Note:` and `Gauge:` do not.
pub(super) fn opens_row_statement(line: &str) -> bool {
    let lower = line.trim().to_lowercase();
    opens_statement(&lower)
        && lower
            .split_once(':')
            .is_some_and(|(header, _)| super::headers::parse_header(header).is_ok())
}

/// Whether `line`, met before the first row, is the text around a pattern rather than a row:
/// a title (`(Seed stitch)`, `Seed Stitch`), a note (`Note: slip sts purlwise.`, `Gauge:
/// ...`), a cast-on (`Cast on a multiple of 4 sts + 2.`). A line that opens with a row word
/// is read as a row, so that a malformed header is reported, not skipped.
fn preamble(line: &str) -> bool {
    let lower = line.trim().to_lowercase();
    title(line) || !HEADER_WORDS.iter().any(|w| lower.starts_with(w))
}

/// Lines that say something true of the pattern but nothing a chart needs.
fn ignorable(line: &str) -> bool {
    let l = line.trim().to_lowercase();
    [
        "rep ",
        "repeat ",
        "multiple of",
        "(multiple of",
        "work rows",
        "work rnds",
        // `Continue in pattern as set.`: the rows go on repeating, as they do here.
        "continue in patt",
        "cont in patt",
        "continue as set",
        "cont as set",
        "continue as established",
        "cont as established",
        // Casting on and binding off: knitwear does both at the surface's edges.
        "cast on",
        "co ",
        "bind off",
        "bo ",
        "cast off",
    ]
    .iter()
    .any(|w| l.starts_with(w))
        && !l.contains(':')
        || super::headers::forms_the_pattern(&l)
}

/// Whether `line` is a title or comment in parentheses, as many pasted patterns open with
/// (`(Seed stitch)`). Only read before the first statement: after it, a line in brackets may
/// be a row's continuation (`(yo, k1)`).
fn title(line: &str) -> bool {
    let l = line.trim().trim_end_matches('.');
    l.starts_with('(') && l.ends_with(')')
}

/// The statements of a text and its notes.
pub(super) struct Statements {
    /// `(header, body)` in the order written.
    pub(super) rows: Vec<(String, String)>,
    /// The lines and sentences a chart needs nothing from (`Repeat rows 1-4.`, `Multiple of
    /// 6 sts plus 5.`), as written, for the checks that read them.
    pub(super) notes: Vec<String>,
    /// The headers of the statements skipped before the first row (`Note`, `Gauge`,
    /// `Stitch 1`), for the message when no row follows.
    pub(super) skipped: Vec<String>,
}

/// Splits the text into `(header, body)` statements. A header runs to its `:`; a body runs to
/// the next header (a new line, or a row word after a full stop). The lines before the first
/// row that are no row (titles, notes, a cast-on: [`preamble`]) are skipped, a width note
/// among them kept; so are `Note:` statements.
pub(super) fn statements(text: &str) -> Statements {
    let mut out: Vec<(String, String)> = Vec::new();
    let mut notes = Vec::new();
    let mut skipped = Vec::new();
    for line in text.lines() {
        let mut rest = line.trim();
        if out.is_empty() && preamble(rest) {
            // A row may follow on the same line (`Seed stitch. Row 1: *k1, p1; rep from *.`):
            // only the text before it is passed over.
            let row = first_row_statement(rest);
            let before = rest[..row.unwrap_or(rest.len())].trim();
            // `(multiple of 4 sts, plus 2)` opening a pattern is a note the layout checks.
            // `Cast on a multiple of 4 sts + 2.` says what its note says.
            let sentences: Vec<&str> = if title(before) {
                vec![before]
            } else {
                before.split('.').map(str::trim).collect()
            };
            for sentence in sentences {
                let note = ["cast on a ", "cast on ", "co a ", "co "]
                    .iter()
                    .find_map(|w| {
                        sentence
                            .get(..w.len())
                            .filter(|h| h.eq_ignore_ascii_case(w))
                            .map(|_| &sentence[w.len()..])
                    })
                    .unwrap_or(sentence);
                if super::width_note::read(note).is_some() {
                    notes.push(note.to_string());
                } else if let Some((header, _)) = sentence.split_once(':') {
                    skipped.push(header.trim().to_string());
                }
            }
            match row {
                Some(at) => rest = &rest[at..],
                None => continue,
            }
        }
        let lower = rest.to_lowercase();
        if ["note:", "notes:", "note ", "nb:"]
            .iter()
            .any(|w| lower.starts_with(w))
        {
            continue;
        }
        while !rest.is_empty() {
            if ignorable(rest) {
                notes.push(rest.to_string());
                break;
            }
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
    Statements {
        rows: out,
        notes,
        skipped,
    }
}

/// Where the first row statement of `line` starts ([`opens_row_statement`]): at its start, or
/// right after a full stop (`Seed stitch. Row 1: ...`).
pub(super) fn first_row_statement(line: &str) -> Option<usize> {
    if opens_row_statement(line) {
        return Some(0);
    }
    // ASCII lower case keeps byte offsets, so they index `line` too.
    let lower = line.to_ascii_lowercase();
    let mut from = 0;
    while let Some(dot) = lower[from..].find('.') {
        let at = from + dot + 1;
        let next = lower[at..].trim_start();
        if opens_row_statement(next) {
            return Some(lower.len() - next.len());
        }
        from = at;
    }
    None
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
        if opens_statement(next) || ignorable(next) {
            return Some(start);
        }
        from = at;
    }
    None
}

/// A lexical token of a row body.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Tok {
    /// `,`, `;` or `.`: between instructions.
    Sep,
    /// `*`, `**`: a repeat starts, marked with that many stars (a repeat nested in another
    /// is marked with more: `*k1, **p1, k1; rep from ** twice more; rep from *`).
    Star(u8),
    Open(char),
    Close(char),
    /// Everything else: an instruction, `3 times`, `rep from * to end`, `18 sts`.
    Text(String),
}

/// A row body's tokens, in order.
pub(super) fn tokens(body: &str) -> Vec<Tok> {
    let mut out = Vec::new();
    let mut text = String::new();
    let flush = |text: &mut String, out: &mut Vec<Tok>| {
        let t = text.trim();
        if !t.is_empty() {
            out.push(Tok::Text(t.to_string()));
        }
        text.clear();
    };
    for (at, ch) in body.char_indices() {
        match ch {
            ',' | ';' | '.' => {
                flush(&mut text, &mut out);
                out.push(Tok::Sep);
            }
            // The `*` of `rep from *` belongs to its text: the body grammar reads that phrase
            // whole (see `vocabulary::after_repeat_from`).
            '*' if ["from", "rep", "repeat"].iter().any(|w| {
                text.trim_end_matches([' ', '*'])
                    .to_lowercase()
                    .ends_with(w)
            }) =>
            {
                text.push(ch)
            }
            // `*k2, p2* rep to end`: a `*` that closes the repeat it opened, before the `rep`
            // that ends it, is no new repeat.
            '*' if out.iter().any(|t| matches!(t, Tok::Star(_)))
                && body[at + 1..]
                    .trim_start_matches([' ', ',', ';'])
                    .to_lowercase()
                    .starts_with("rep") =>
            {
                flush(&mut text, &mut out);
                out.push(Tok::Sep);
            }
            '*' => {
                let doubled = text.is_empty() && body[..at].ends_with('*');
                flush(&mut text, &mut out);
                match out.last_mut() {
                    Some(Tok::Star(n)) if doubled => *n = n.saturating_add(1),
                    Some(Tok::Star(_)) => {}
                    _ => out.push(Tok::Star(1)),
                }
            }
            '[' | '(' => {
                flush(&mut text, &mut out);
                out.push(Tok::Open(ch));
            }
            ']' | ')' => {
                flush(&mut text, &mut out);
                out.push(Tok::Close(ch));
            }
            _ => text.push(ch),
        }
    }
    flush(&mut text, &mut out);
    out
}
