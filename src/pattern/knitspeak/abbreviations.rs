//! A pattern's own abbreviations for its cables, as printed patterns define them in their key
//! (`C3B = sl 1 st to cn, hold at back, k2, k1 from cn.`, `Cr3L: Slip next 2 sts onto cable
//! needle and leave at front of work, P1, then K2 from cable needle.`): each definition a
//! cable needle's working spells out is read as the cross it works, and the pattern's rows
//! then read its name as that cross, before the reader's own reading of the name (a
//! publisher's `T3B` may not be the reader's). Definitions of anything else are left to the
//! lines around the pattern, which the reader passes over.

use crate::pattern::instruction::{Instruction, MAX_CROSS_SIDE};
use crate::pattern::vocabulary::normal_form;

/// The abbreviations a text defines: `(name in normal form, the cross it works)`, in the
/// order written.
pub(super) type Defined = Vec<(String, Instruction)>;

/// Every cable definition among the sentences of `text` ([`definition`]): a key may share a
/// line with the rows (a pattern pasted into one line of the add-on's field).
pub(super) fn defined(text: &str) -> Defined {
    text.lines()
        .flat_map(|line| line.split('.'))
        .filter_map(definition)
        .collect()
}

/// `text` with each cable needle's working written out inside a row (`P2, *slip 2 sts to
/// cn and hold in front, k2, k2 from cn, p2; rep from *`, as older books print cables) read
/// as the cross it works (`2/2 LC`): a run of instructions from one that slips to the cable
/// needle to the first that works from it, which [`worked_cross`] reads whole. A definition
/// in the key (`C4F = ...`, [`definition`]) is left for [`defined`] to read; a run that is
/// no cross (a bobble, stitches worked from the needle in two goes) is left as written,
/// for the row's reader to refuse.
pub(super) fn inline_crosses(text: &str) -> std::borrow::Cow<'_, str> {
    let lower = text.to_ascii_lowercase();
    if !lower.contains("from cn") && !lower.contains("cable needle") {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    for (k, sentence) in text.split('.').enumerate() {
        if k > 0 {
            out.push('.');
        }
        if definition(sentence).is_some() {
            out.push_str(sentence);
        } else {
            out.push_str(&sentence_crosses(sentence));
        }
    }
    std::borrow::Cow::Owned(out)
}

/// The longest working [`inline_crosses`] reads, in bytes.
const MAX_WORKING: usize = 160;

/// One sentence of [`inline_crosses`]: ASCII lower case keeps byte offsets, so the runs
/// found in `lower` index `sentence` too.
fn sentence_crosses(sentence: &str) -> String {
    let lower = sentence.to_ascii_lowercase();
    let ends = [
        "from the cable needle",
        "from cable needle",
        "from the cn",
        "from cn",
    ];
    let mut out = String::new();
    let mut copied = 0;
    let mut at = 0;
    while at < lower.len() {
        // An instruction starts after a separator; the working starts with a slip.
        let starts = lower[..at]
            .trim_end()
            .chars()
            .last()
            .is_none_or(|c| matches!(c, ',' | ';' | '*' | '[' | '(' | ':'));
        let rest = &lower[at..];
        if starts
            && (rest.starts_with("sl ")
                || rest.starts_with("slip ")
                || rest.starts_with("sl1")
                || rest.starts_with("sl2")
                || rest.starts_with("sl3")
                || rest.starts_with("sl4"))
        {
            // Looked for within the longest working only: the scan stays linear.
            let mut reach = rest.len().min(MAX_WORKING);
            while !rest.is_char_boundary(reach) {
                reach -= 1;
            }
            let end = ends
                .iter()
                .filter_map(|e| rest[..reach].find(e).map(|i| i + e.len()))
                .min();
            let span = end
                .map(|end| &rest[..end])
                .filter(|span| !span.contains(['*', ';', '[', ']', '(', ')']));
            if let Some(cross) = span.and_then(worked_cross) {
                out.push_str(&sentence[copied..at]);
                out.push_str(&cross.name());
                at += span.map_or(0, str::len);
                copied = at;
                continue;
            }
        }
        at += rest.chars().next().map_or(1, char::len_utf8);
    }
    out.push_str(&sentence[copied..]);
    out
}

/// Whether `line` holds nothing but cable definitions (`C3B = sl 1 to cn, hold at back, k2,
/// k1 from cn. C3F = ...`): a line of the key, which the rows do not read.
pub(super) fn only_definitions(line: &str) -> bool {
    let mut sentences = line.split('.').filter(|s| !s.trim().is_empty()).peekable();
    sentences.peek().is_some() && sentences.all(|s| definition(s).is_some())
}

/// `sentence` read as a cable's definition: a name, then `=`, `:` or a dash, then the working
/// of a cross with a cable needle. The name is the word before the separator, or the two
/// words of a cross's name (`2/1 RPC`), so a heading may come before it (`Special
/// abbreviations: C3B = ...`). `None` for any other sentence (row statements included).
pub(super) fn definition(sentence: &str) -> Option<(String, Instruction)> {
    let s = sentence.trim();
    // A row statement (`Row 1 (RS): ...`) defines nothing.
    if s.split_once(':')
        .is_some_and(|(header, _)| super::headers::parse_header(header).is_ok())
    {
        return None;
    }
    let mut seps: Vec<(usize, usize)> = [
        " = ",
        "=",
        ": ",
        " - ",
        " \u{2013} ",
        " \u{2014} ",
        "\u{2014}",
    ]
    .iter()
    .flat_map(|sep| s.match_indices(sep).map(|(at, m)| (at, m.len())))
    .collect();
    seps.sort_unstable();
    seps.into_iter().find_map(|(at, len)| {
        let words: Vec<&str> = s[..at].split_whitespace().collect();
        let name = match words.as_slice() {
            [.., a, b] if a.contains('/') => format!("{a} {b}"),
            [.., b] => (*b).to_string(),
            [] => return None,
        };
        if name.len() > 12 {
            return None;
        }
        Some((normal_form(&name), worked_cross(&s[at + len..])?))
    })
}

/// One step of a cable needle's working.
#[derive(Debug, PartialEq)]
enum Step {
    /// `sl 2 to cn`: stitches slipped to the cable needle.
    ToNeedle(usize),
    /// `hold at back` (false) / `hold in front` (true).
    Hold { front: bool },
    /// `k2`, `p1`: stitches worked off the left needle.
    Work { purl: bool, count: usize },
    /// `k2 from cn`: the held stitches worked.
    FromNeedle { purl: bool, count: usize },
}

/// The cross `text` (a definition's working) spells out, or `None` where it is not exactly
/// "slip to a cable needle, hold it in front or at back, work from the left needle, work
/// from the cable needle" with the front group knitted.
fn worked_cross(text: &str) -> Option<Instruction> {
    let steps = steps(text)?;
    let [Step::ToNeedle(held), Step::Hold { front }, Step::Work { purl, count }, Step::FromNeedle {
        purl: held_purl,
        count: held_count,
    }] = steps.as_slice()
    else {
        return None;
    };
    if held != held_count {
        return None;
    }
    let (worked, held) = (*count, *held);
    // Held in front, the held stitches travel left in front and the worked ones pass behind
    // (purled in an `LPC`); held at back, the worked stitches travel right in front.
    let (m, n, front_purl, back_purl) = if *front {
        (held, worked, *held_purl, *purl)
    } else {
        (worked, held, *purl, *held_purl)
    };
    let side = 1..=usize::from(MAX_CROSS_SIDE);
    if front_purl || !side.contains(&m) || !side.contains(&n) {
        return None;
    }
    Some(Instruction::Cross {
        m: m as u8,
        n: n as u8,
        left: *front,
        purl_back: back_purl,
    })
}

/// The steps of a cable needle's working, in order; `None` where a word is none of them.
fn steps(text: &str) -> Option<Vec<Step>> {
    let lower = text
        .to_lowercase()
        .replace("cable needle", "cn")
        .replace(['.', ',', ';', '(', ')'], " ");
    // Words that say nothing the steps need.
    const FILLER: [&str; 14] = [
        "next", "the", "of", "work", "then", "and", "a", "st", "sts", "stitch", "stitches",
        "needle", "left", "to",
    ];
    let words: Vec<&str> = lower
        .split_whitespace()
        .filter(|w| !FILLER.contains(w))
        .collect();
    let mut steps = Vec::new();
    let mut i = 0;
    // A count written after its verb (`k 2`, `slip 2`), or none (1).
    let count_at = |i: usize| -> (usize, usize) {
        match words.get(i).and_then(|w| w.parse::<usize>().ok()) {
            Some(n) => (n, 1),
            None => (1, 0),
        }
    };
    while i < words.len() {
        let w = words[i];
        let (verb, glued) = split_count(w)?;
        match verb {
            "sl" | "slip" => {
                let (n, used) = glued.map_or_else(|| count_at(i + 1), |n| (n, 0));
                i += 1 + used;
                // `onto cn`, `on cn`, `to cn` (`to` is filler).
                while matches!(words.get(i), Some(&("onto" | "on"))) {
                    i += 1;
                }
                if words.get(i) != Some(&"cn") {
                    return None;
                }
                i += 1;
                steps.push(Step::ToNeedle(n));
            }
            "hold" | "leave" | "held" => {
                i += 1;
                while matches!(words.get(i), Some(&("at" | "in" | "to"))) {
                    i += 1;
                }
                let front = match words.get(i) {
                    Some(&"front") => true,
                    Some(&"back") => false,
                    _ => return None,
                };
                i += 1;
                steps.push(Step::Hold { front });
            }
            "k" | "knit" | "p" | "purl" => {
                let purl = matches!(verb, "p" | "purl");
                let (count, used) = glued.map_or_else(|| count_at(i + 1), |n| (n, 0));
                i += 1 + used;
                if words.get(i) == Some(&"from") {
                    if words.get(i + 1) != Some(&"cn") {
                        return None;
                    }
                    i += 2;
                    steps.push(Step::FromNeedle { purl, count });
                } else {
                    steps.push(Step::Work { purl, count });
                }
            }
            _ => return None,
        }
    }
    Some(steps)
}

/// `k2` -> (`k`, Some(2)); `slip` -> (`slip`, None); `2k` -> None.
fn split_count(word: &str) -> Option<(&str, Option<usize>)> {
    let digits = word.len() - word.trim_end_matches(|c: char| c.is_ascii_digit()).len();
    let (verb, count) = word.split_at(word.len() - digits);
    if verb.is_empty() {
        return None;
    }
    if count.is_empty() {
        return Some((verb, None));
    }
    Some((verb, Some(count.parse().ok()?)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cross(m: u8, n: u8, left: bool, purl_back: bool) -> Instruction {
        Instruction::Cross {
            m,
            n,
            left,
            purl_back,
        }
    }

    #[test]
    fn cable_definitions_read_as_the_cross_they_work() {
        let cases = [
            (
                "C4B = sl 2 to cn, hold at back, k2, k2 from cn.",
                "c4b",
                cross(2, 2, false, false),
            ),
            (
                "C3B: slip 1 st to cn, hold in back, k2, k1 from cn",
                "c3b",
                cross(2, 1, false, false),
            ),
            (
                "Cr3L - Slip next 2 sts onto cable needle and leave at front of work, P1, then K2 \
                 from cable needle.",
                "cr3l",
                cross(2, 1, true, true),
            ),
            (
                "T3B = sl1 to cn, hold at back, k2, p1 from cn",
                "t3b",
                cross(2, 1, false, true),
            ),
            (
                "C6F: sl 3 sts to cn and hold in front, knit 3, knit 3 from cn",
                "c6f",
                cross(3, 3, true, false),
            ),
            (
                "2/1 LPC: sl 2 to cn, hold in front, p1, k2 from cn",
                "2/1 lpc",
                cross(2, 1, true, true),
            ),
        ];
        for (line, name, ins) in cases {
            assert_eq!(definition(line), Some((name.to_string(), ins)), "{line}");
        }
    }

    #[test]
    fn other_lines_define_nothing() {
        for line in [
            "Row 1 (RS): *P2, C4B, p2; rep from *.",
            "C4B = sl 2 to cn, hold at back, k2, k3 from cn.",
            "C4B = sl 2 to cn, hold at back, p2, k2 from cn.",
            "C4F = sl 2 to cn, hold in front, k2, p2 from cn.",
            "MB = (k1, p1, k1) in next st, turn, p3, turn, sk2p.",
            "Tw2 = k2tog leaving sts on needle, knit first st again.",
            "C14B = sl 7 to cn, hold at back, k7, k7 from cn.",
            "Note: slip sts purlwise.",
            "C4B = sl 2 to cn, k2, k2 from cn.",
        ] {
            assert_eq!(definition(line), None, "{line}");
        }
    }
}
