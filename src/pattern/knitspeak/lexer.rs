//! Cutting Knitspeak text into pieces: the text into `(header, body)` statements
//! ([`statements`]), and a row body into tokens ([`tokens`]): separators, the `*` that starts
//! a repeat, brackets, and the text between them.

/// Words a statement's header starts with (lower case). Also how a Knitspeak text is told from
/// a chart ([`super::looks_like_knitspeak`]), so both read headers alike.
const HEADER_WORDS: [&str; 21] = [
    "row",
    // `Rib row 1:`, `Patt row 3:`, `Pattern rnd 2:`: a row of the named part.
    "rib row",
    "rib rnd",
    "patt row",
    "patt rnd",
    "pattern row",
    "pattern rnd",
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

/// How far a repeat goes, written straight after the `*` that closes it (`*k2, p2* across`).
const REPEAT_ENDS: [&str; 8] = [
    "across",
    "to end",
    "to the end",
    "to last",
    "to the last",
    "around",
    "all around",
    "until",
];

/// The longest header a spaced dash may follow, in bytes.
const MAX_HEADER: usize = 80;

/// `text` with a spaced hyphen or en dash after a row header (`Row 1 (RS) - K2, p2.`, as
/// pattern pages write it) read as the `:` other texts put there: each whose sentence (from
/// the line's start or the last full stop) opens with a header that reads as rows, with no
/// `:` before the dash or after it in that sentence (`Rows 1 - 4: Knit.` is a range).
///
/// A full stop after a header (`Row 1. K2, p2.`, `Row 2 (WS). Purl.`, as some books print
/// rows) is its colon too, where a statement follows it; a side written after the stop or
/// the colon (`Row 1. (RS) K2`, `Row 1: (RS) K2`) joins the header (`Row 1 (RS): K2`).
pub(super) fn spaced_dashes(text: &str) -> std::borrow::Cow<'_, str> {
    const DASHES: [&str; 2] = [" - ", " \u{2013} "];
    if !DASHES.iter().any(|d| text.contains(d)) && !text.contains(". ") && !text.contains(": (") {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    // Where the sentence being copied starts in `out`.
    let mut sentence = 0;
    let mut at = 0;
    while at < text.len() {
        let rest = &text[at..];
        let dash = DASHES.iter().find(|d| rest.starts_with(**d));
        // A header is short: a longer sentence is no header, and is not read again at each
        // dash it holds.
        if let Some(dash) = dash.filter(|_| out.len() - sentence <= MAX_HEADER) {
            let before = &out[sentence..];
            let lower = before.trim_start().to_lowercase();
            let header = HEADER_WORDS.iter().any(|w| lower.starts_with(w))
                && !before.contains(':')
                && super::headers::parse_header(before).is_ok();
            let colon_after = || {
                let after = &rest[dash.len()..];
                after[..after.find(['.', '\n']).unwrap_or(after.len())].contains(':')
            };
            if header && !colon_after() {
                out.push_str(": ");
                at += dash.len();
                continue;
            }
        }
        // `Row 1: (RS) K2`: a side written after the colon joins the header.
        if rest.starts_with(": (") && out.len() - sentence <= MAX_HEADER {
            if let Some((Some(side), read)) = header_stop(&out[sentence..], &rest[1..]) {
                out.push(' ');
                out.push_str(side);
                out.push_str(": ");
                at += 1 + read;
                continue;
            }
        }
        if rest.starts_with(". ") && out.len() - sentence <= MAX_HEADER {
            if let Some((side, read)) = header_stop(&out[sentence..], &rest[1..]) {
                if let Some(side) = side {
                    out.push(' ');
                    out.push_str(side);
                }
                out.push_str(": ");
                at += 1 + read;
                continue;
            }
        }
        let Some(ch) = rest.chars().next() else { break };
        out.push(ch);
        if matches!(ch, '.' | '\n') {
            sentence = out.len();
        }
        at += ch.len_utf8();
    }
    std::borrow::Cow::Owned(out)
}

/// Whether the full stop between `before` (a sentence so far) and `after` (the text after
/// the stop) ends a row header: `before` reads as one, and a statement follows on the same
/// line. Returns the side to add to the header (`(RS)` where `after` opens with it) and how
/// many bytes of `after` that and the spaces before the statement take.
fn header_stop<'a>(before: &str, after: &'a str) -> Option<(Option<&'a str>, usize)> {
    let lower = before.trim_start().to_lowercase();
    let is_header = |h: &str| {
        HEADER_WORDS.iter().any(|w| lower.starts_with(w))
            && !h.contains(':')
            && super::headers::parse_header(h).is_ok()
    };
    if !is_header(before) {
        return None;
    }
    let spaces = after.len() - after.trim_start_matches([' ', '\t']).len();
    let rest = &after[spaces..];
    // A side in brackets after the stop (or the colon) belongs to the header.
    let side = rest
        .starts_with('(')
        .then(|| rest.find(')'))
        .flatten()
        .map(|close| &rest[..=close])
        .filter(|side| {
            let inner = side[1..side.len() - 1].trim().to_ascii_lowercase();
            ["rs", "ws", "right side", "wrong side", "rs row", "ws row"].contains(&inner.as_str())
                && is_header(&format!("{before} {side}"))
        });
    let taken = match side {
        Some(side) => {
            let tail = &rest[side.len()..];
            let gap = tail.len() - tail.trim_start_matches([' ', '\t']).len();
            spaces + side.len() + gap
        }
        None => spaces,
    };
    let statement = &after[taken..];
    let statement = &statement[..statement.find('\n').unwrap_or(statement.len())];
    // A statement follows: not the end of the line, and not another sentence that is a
    // header or a note of its own (`Row 1. Row 2: ...`).
    let opens_header = {
        let l = statement.to_lowercase();
        HEADER_WORDS.iter().any(|w| l.starts_with(w))
    };
    (!statement.trim().is_empty() && !opens_header).then_some((side, taken))
}

/// `text` with each `Next row:` (`Next row (RS):`, `Next rnd:`), as garment patterns write a
/// run of rows, numbered as the row after the last one named before it (`Row 1 (RS):`;
/// after `Rows 1-4:` it is `Row 5:`), and the first as row 1. Only a header that opens a
/// statement (at a line's start or after a full stop) and ends at its `:` is numbered.
pub(super) fn next_rows(text: &str) -> std::borrow::Cow<'_, str> {
    // ASCII lower case keeps byte offsets, so they index `text` too.
    let lower = text.to_ascii_lowercase();
    if !lower.contains("next r") {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 16);
    let mut last = 0usize;
    let mut copied = 0;
    let mut start = true;
    for (at, ch) in lower.char_indices() {
        if matches!(ch, '.' | '\n') {
            start = true;
            continue;
        }
        if !start || ch.is_whitespace() {
            continue;
        }
        start = false;
        let rest = &lower[at..];
        let line = &rest[..rest.find(['\n', '.']).unwrap_or(rest.len())];
        let Some(colon) = line.find(':').filter(|&c| c <= MAX_HEADER) else {
            continue;
        };
        let header = &line[..colon];
        let next = ["next row", "next rnd", "next round"]
            .iter()
            .find(|w| header.starts_with(**w));
        if let Some(word) = next {
            let side = header[word.len()..].trim();
            let is_side = side.is_empty() || (side.starts_with('(') && side.ends_with(')'));
            if is_side && last < crate::pattern::MAX_PATTERN_ROWS {
                last += 1;
                let name = if *word == "next row" { "Row" } else { "Rnd" };
                out.push_str(&text[copied..at]);
                out.push_str(&format!("{name} {last}"));
                copied = at + word.len();
            }
        } else if HEADER_WORDS.iter().any(|w| header.starts_with(w)) {
            if let Some(numbers) = super::headers::parse_header(&text[at..at + colon])
                .ok()
                .and_then(|h| h.numbers())
            {
                last = last.max(numbers.into_iter().max().unwrap_or(0));
            }
        }
    }
    if copied == 0 {
        return std::borrow::Cow::Borrowed(text);
    }
    out.push_str(&text[copied..]);
    std::borrow::Cow::Owned(out)
}

/// `text` with rows numbered as British patterns number them (`1st row (RS):`, `2nd and
/// every alt row:`, `5th to 8th rows:`, `1st rnd:`, `Work as 3rd row.`) written as Knitspeak
/// numbers them (`Row 1 (RS):`, `Row 2 and every alt row:`, `Rows 5-8:`, `Rnd 1:`, `Work as
/// row 3.`): ordinals, joined by `,`, `and`, `to` or `-`, then a row word. Other text is
/// left as it is.
pub(super) fn ordinal_rows(text: &str) -> std::borrow::Cow<'_, str> {
    // ASCII lower case keeps byte offsets, so they index `text` too.
    let lower = text.to_ascii_lowercase();
    let mut out = String::new();
    let mut copied = 0;
    let mut at = 0;
    // The character just before `at`, and the last one before it that is no space or tab:
    // kept as the scan goes, so that the scan stays linear in the text.
    let mut prev: Option<char> = None;
    let mut last_solid: Option<char> = None;
    while at < lower.len() {
        let boundary = !prev.is_some_and(char::is_alphanumeric);
        let statement_start = last_solid.is_none_or(|c| matches!(c, '\n' | '.'));
        let short = statement_start
            .then(|| short_header(&lower[at..]))
            .flatten();
        let found = short.or_else(|| {
            (boundary && lower.as_bytes()[at].is_ascii_digit())
                .then(|| ordinal_header(&lower[at..]))
                .flatten()
        });
        let (len, rewritten) = match found {
            Some((len, rewritten)) => (len, Some(rewritten)),
            None => (lower[at..].chars().next().map_or(1, char::len_utf8), None),
        };
        let consumed = &lower[at..at + len];
        prev = consumed.chars().next_back().or(prev);
        last_solid = consumed
            .chars()
            .rev()
            .find(|c| !matches!(c, ' ' | '\t'))
            .or(last_solid);
        if let Some(rewritten) = rewritten {
            out.push_str(&text[copied..at]);
            out.push_str(&rewritten);
            copied = at + len;
        }
        at += len;
    }
    if copied == 0 {
        return std::borrow::Cow::Borrowed(text);
    }
    out.push_str(&text[copied..]);
    std::borrow::Cow::Owned(out)
}

/// `R1:`, `R2 (WS):` opening a statement -> (the length of `R1`, `Row 1`). `s` is lower case.
fn short_header(s: &str) -> Option<(usize, String)> {
    let rest = s.strip_prefix('r')?;
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    if digits == 0 || !rest[digits..].trim_start().starts_with([':', '(']) {
        return None;
    }
    Some((1 + digits, format!("Row {}", &rest[..digits])))
}

/// The most ordinals one header joins (`1st, 3rd, 5th and 7th rows`).
const MAX_ORDINALS: usize = 32;

/// One ordinal (`1st`, `22nd`, `3rd`, `4th`) at the start of `s`: its number and length.
fn ordinal(s: &str) -> Option<(usize, usize)> {
    let digits = s.bytes().take_while(u8::is_ascii_digit).count();
    let suffix = s.get(digits..digits + 2)?;
    if digits == 0 || !["st", "nd", "rd", "th"].contains(&suffix) {
        return None;
    }
    let end = digits + 2;
    if s[end..].starts_with(char::is_alphanumeric) {
        return None;
    }
    Some((s[..digits].parse().ok()?, end))
}

/// `1st and 3rd rows` -> (its length, `Rows 1 and 3`); `2nd and every alt row` -> `Row 2`
/// (the rest is a header the header reader knows). `s` is lower case.
fn ordinal_header(s: &str) -> Option<(usize, String)> {
    let (first, mut at) = ordinal(s)?;
    let mut numbers = first.to_string();
    let mut count = 1;
    // Further ordinals: `, 3rd`, ` and 5th`, ` to 8th`, `-8th`.
    loop {
        let rest = &s[at..];
        let joined = [
            (", ", ", "),
            (" and ", " and "),
            (" & ", " and "),
            (" to ", "-"),
            ("-", "-"),
            ("\u{2013}", "-"),
        ]
        .iter()
        .find_map(|(w, as_)| {
            let after = rest.strip_prefix(w)?;
            let (n, len) = ordinal(after)?;
            Some((rest.len() - after.len() + len, format!("{as_}{n}")))
        });
        let Some((len, part)) = joined else { break };
        numbers.push_str(&part);
        count += 1;
        at += len;
        // No header names this many rows one by one; a bound keeps a long run of ordinals
        // from being read again from each of them.
        if count >= MAX_ORDINALS {
            return None;
        }
    }
    let rest = &s[at..];
    let word = [
        ("rows", "Rows"),
        ("row", "Row"),
        ("rnds", "Rnds"),
        ("rnd", "Rnd"),
        ("rounds", "Rounds"),
        ("round", "Round"),
    ]
    .iter()
    .find_map(|(w, as_)| {
        let after = rest.strip_prefix(' ')?.strip_prefix(w)?;
        (!after.starts_with(char::is_alphanumeric)).then_some((w.len() + 1, *as_))
    });
    if let Some((len, as_)) = word {
        return Some((at + len, format!("{as_} {numbers}")));
    }
    // `2nd and every alt row`, `2nd and all foll WS rows`: a row word later in the header.
    let every = [" and every ", " and all ", " & every ", " & all "]
        .iter()
        .any(|w| rest.starts_with(w));
    if count == 1 && every {
        return Some((at, format!("Row {numbers}")));
    }
    None
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
    // A line opening with a part's name (`Rib rows are worked ...`) is a row only where its
    // header reads as one.
    let part = ["rib ", "patt ", "pattern "]
        .iter()
        .any(|w| lower.starts_with(w));
    title(line)
        || !HEADER_WORDS.iter().any(|w| lower.starts_with(w))
        || (part && !opens_row_statement(line))
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
    // Under a heading `Abbreviations` / `Special abbreviations`, up to the next row: the
    // pattern's key, whose cable definitions are read apart ([`super::abbreviations`]).
    let mut in_key = false;
    for line in text.lines() {
        let mut rest = line.trim();
        let heading = rest.trim_end_matches([':', '.']).trim().to_lowercase();
        if [
            "abbreviations",
            "special abbreviations",
            "abbreviations used",
            "key",
        ]
        .contains(&heading.as_str())
        {
            in_key = true;
            continue;
        }
        if in_key {
            if first_row_statement(rest) != Some(0) {
                continue;
            }
            in_key = false;
        }
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
        // A cable the pattern defines (`C3B = sl 1 to cn, ...`), read before the rows.
        if super::abbreviations::only_definitions(rest) {
            continue;
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

/// `body` with each decrease spelled out as its working (`Slip, slip, knit`, as some books
/// and pattern pages write ssk, and `slip, slip, purl`) written as its name. Only the bare
/// words count: `sl1, sl1, k1` may be two slipped stitches and a knit, and is left as
/// written.
fn spelled_decreases(body: &str) -> std::borrow::Cow<'_, str> {
    // ASCII lower case keeps byte offsets, so they index `body` too.
    let lower = body.to_ascii_lowercase();
    if !lower.contains("slip") {
        return std::borrow::Cow::Borrowed(body);
    }
    // The words after the first `slip`: `, slip, knit` with any spaces.
    let rest_of = |s: &str| -> Option<(usize, &'static str)> {
        let mut at = 0;
        for word in [",", "slip", ","] {
            let t = s[at..].trim_start();
            at = s.len() - t.len() + word.len();
            t.starts_with(word).then_some(())?;
        }
        let t = s[at..].trim_start();
        at = s.len() - t.len();
        let (word, name) = [("knit", "ssk"), ("purl", "ssp")]
            .into_iter()
            .find(|(w, _)| t.starts_with(w))?;
        at += word.len();
        // The word ends the instruction: `knit 2 together` or `knitwise` is something else.
        let after = s[at..].trim_start();
        (after.is_empty() || after.starts_with([',', ';', '.', '*', ')', ']']))
            .then_some((at, name))
    };
    let mut out = String::with_capacity(body.len());
    let mut copied = 0;
    let mut from = 0;
    while let Some(found) = lower[from..].find("slip") {
        let at = from + found;
        let starts = lower[..at]
            .trim_end()
            .chars()
            .last()
            .is_none_or(|c| matches!(c, ',' | ';' | '*' | '[' | '(' | ':'));
        let after_slip = at + "slip".len();
        match rest_of(&lower[after_slip..]).filter(|_| starts) {
            Some((len, name)) => {
                out.push_str(&body[copied..at]);
                out.push_str(name);
                copied = after_slip + len;
                from = copied;
            }
            None => from = after_slip,
        }
    }
    if copied == 0 {
        return std::borrow::Cow::Borrowed(body);
    }
    out.push_str(&body[copied..]);
    std::borrow::Cow::Owned(out)
}

/// A row body's tokens, in order.
pub(super) fn tokens(body: &str) -> Vec<Tok> {
    let body = &*spelled_decreases(body);
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
            // `*k2, p2* across`, `K1, *p1, k1* to end`: the closing `*` and how far the repeat
            // goes, with no `rep` between them, read as `rep from * across`.
            '*' if out.iter().any(|t| matches!(t, Tok::Star(_))) && {
                let after = body[at + 1..].trim_start_matches(' ').to_lowercase();
                REPEAT_ENDS.iter().any(|w| after.starts_with(w))
            } =>
            {
                flush(&mut text, &mut out);
                out.push(Tok::Sep);
                text.push_str("rep from * ");
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
            // `k2, p2 - repeat to end`, `k2, p2 \u{2013} rep to end`: a dash between
            // spaces (or any long dash) parts instructions as a comma does; a hyphen inside
            // a name (`k2tog-tbl`, `1-to-3-inc`) has no spaces round it.
            '\u{2013}' | '\u{2014}' => {
                flush(&mut text, &mut out);
                out.push(Tok::Sep);
            }
            '-' if body[..at].ends_with([' ', '\t']) && body[at + 1..].starts_with([' ', '\t']) => {
                flush(&mut text, &mut out);
                out.push(Tok::Sep);
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

#[cfg(test)]
mod tests {
    use super::ordinal_rows;

    #[test]
    fn a_spaced_dash_after_a_header_is_its_colon() {
        let cases = [
            (
                "Row 1 (RS) - K2, p2.\nRow 2 \u{2013} Purl.",
                "Row 1 (RS): K2, p2.\nRow 2: Purl.",
            ),
            ("Row 1 - Knit. Row 2 - Purl.", "Row 1: Knit. Row 2: Purl."),
            // A range, a dash in a body, and a dash after no header stay.
            ("Rows 1 - 4: Knit.", "Rows 1 - 4: Knit."),
            ("Row 1: K2 - p2.", "Row 1: K2 - p2."),
            ("Cable rib - a classic.", "Cable rib - a classic."),
            // A full stop after a header, with the side before or after it.
            ("Row 1. K2, p2. Row 2. Purl.", "Row 1: K2, p2. Row 2: Purl."),
            (
                "Row 1. (RS) K2, p2.\nRow 2 (WS). P2, k2.",
                "Row 1 (RS): K2, p2.\nRow 2 (WS): P2, k2.",
            ),
            ("Rows 3 and 4. Knit.", "Rows 3 and 4: Knit."),
            (
                "Row 1: (RS) K2. Row 2: (WS) P2.",
                "Row 1 (RS): K2. Row 2 (WS): P2.",
            ),
            // Brackets after a colon that are no side stay in the body.
            ("Row 1: (K1, p1) to end.", "Row 1: (K1, p1) to end."),
            // Sentences that end with a row's name, or a header with nothing after it.
            ("Work as row 1. Knit.", "Work as row 1. Knit."),
            ("Row 1. Row 2: Purl.", "Row 1. Row 2: Purl."),
            ("Row 1.\nK2.", "Row 1.\nK2."),
            (
                "Rows 1-4 form the pattern. Knit.",
                "Rows 1-4 form the pattern. Knit.",
            ),
        ];
        for (text, read) in cases {
            assert_eq!(super::spaced_dashes(text), read, "{text}");
        }
    }

    #[test]
    fn next_rows_are_numbered_after_the_rows_before_them() {
        let cases = [
            (
                "Next row (RS): K2. Next row: P2.",
                "Row 1 (RS): K2. Row 2: P2.",
            ),
            (
                "Rows 1-4: Knit.\nNext row: Purl.\nNext rnd: Knit.",
                "Rows 1-4: Knit.\nRow 5: Purl.\nRnd 6: Knit.",
            ),
            // Not a header that opens a statement: left as written.
            ("Knit the next row: k2.", "Knit the next row: k2."),
            ("Next row is plain. Knit.", "Next row is plain. Knit."),
        ];
        for (text, read) in cases {
            assert_eq!(super::next_rows(text), read, "{text}");
        }
    }

    #[test]
    fn ordinal_rows_are_numbered_as_knitspeak_numbers_them() {
        let cases = [
            ("1st row (RS): Knit.", "Row 1 (RS): Knit."),
            ("21st and 22nd rows: Purl.", "Rows 21 and 22: Purl."),
            ("1st, 3rd & 5th rows: K.", "Rows 1, 3 and 5: K."),
            ("5th to 8th rows: K.", "Rows 5-8: K."),
            ("5th\u{2013}8th Rows: K.", "Rows 5-8: K."),
            ("2nd and every alt row: P.", "Row 2 and every alt row: P."),
            ("3rd rnd: As 1st rnd.", "Rnd 3: As Rnd 1."),
            (
                "R1: K. R2 (WS): P.\n  R3: K.",
                "Row 1: K. Row 2 (WS): P.\n  Row 3: K.",
            ),
            ("K2, r1: k", "K2, r1: k"),
            // Not a row's number: left as written.
            ("K2, 3rd st, 1st", "K2, 3rd st, 1st"),
            ("k21st row", "k21st row"),
            (
                "1st rows\u{e9}: \u{e9}1st row",
                "1st rows\u{e9}: \u{e9}1st row",
            ),
        ];
        for (text, read) in cases {
            assert_eq!(ordinal_rows(text), read, "{text}");
        }
    }
}
