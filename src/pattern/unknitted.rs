//! Stitches knitwear recognises but does not knit yet, and why: the reader names them for
//! what they are instead of offering the nearest stitch it knows (`kfb` is no misspelt `k`,
//! and a knitter who took that advice would knit a different fabric).
//!
//! Most of them change the stitch count within a row: an increase that is not a yarn-over or
//! a made stitch (`kfb`, a lifted increase, `1-to-5 inc`), a bind-off or cast-on within the
//! fabric, a short row. Knitwear's rows each keep one stitch count (see [`super::rows`]).
//! Spellings are matched in the vocabulary's normal form ([`super::vocabulary::normal_form`]:
//! lower case, `-` and `_` as spaces), as stitch-maps.com and printed patterns write them.

use super::vocabulary::normal_form;

/// What a recognised stitch does, for its message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Makes `out` stitches of `from` loops (`from` 0: a new loop between stitches).
    Increase { from: usize, out: usize },
    /// Binds stitches off (`bo`, `cast off`).
    BindOff,
    /// Casts stitches on (`co`, `backward loop co`).
    CastOn,
    /// Turns the work before the row's end (`turn`, `w&t`).
    ShortRow,
    /// Brioche: a stitch worked with the yarn-over it was slipped with the row before.
    Brioche,
    /// Drops a loop to unravel down the fabric (`drop st`).
    Drop,
    /// Works into the stitch below (`k1b`), or Barbara Walker's twisted stitch (`K1-b`).
    Below,
    /// Gathers loops and works stitches out of them (`3-to-3 gather`).
    Gather,
}

/// One recognised stitch: its spellings (normal form) and what it does.
struct Recognised {
    /// Whole phrases.
    phrases: &'static [&'static str],
    /// Names that may be followed by a count (`bo 3`, `cast on 2 sts`).
    counted: &'static [&'static str],
    /// Words after the count that change nothing.
    ignored: &'static [&'static str],
    what: &'static str,
    kind: Kind,
}

const fn inc(
    phrases: &'static [&'static str],
    what: &'static str,
    from: usize,
    out: usize,
) -> Recognised {
    Recognised {
        phrases,
        counted: &[],
        ignored: &[],
        what,
        kind: Kind::Increase { from, out },
    }
}

const RECOGNISED: &[Recognised] = &[
    inc(
        &[
            "kfb",
            "k1fb",
            "kf&b",
            "k1f&b",
            "k f&b",
            "knit front and back",
            "knit into front and back",
        ],
        "knits into the front and then the back of one stitch",
        1,
        2,
    ),
    inc(
        &[
            "pfb",
            "p1fb",
            "pf&b",
            "p1f&b",
            "p f&b",
            "purl front and back",
            "purl into front and back",
        ],
        "purls into the front and then the back of one stitch",
        1,
        2,
    ),
    inc(
        &["kfbf", "k1fbf"],
        "knits into the front, back and front of one stitch",
        1,
        3,
    ),
    inc(
        &[
            "incl",
            "incr",
            "inclp",
            "incrp",
            "lli",
            "rli",
            "left lifted increase",
            "right lifted increase",
        ],
        "lifts a loop of the row below a stitch onto the needle and works it as a new stitch",
        0,
        1,
    ),
    inc(
        &[
            "ctr dbl inc",
            "centered double increase",
            "centred double increase",
            "cdi",
        ],
        "works three stitches out of one (a centred double increase)",
        1,
        3,
    ),
    Recognised {
        phrases: &["bo", "bind off", "cast off"],
        counted: &["bo", "bind off", "cast off"],
        ignored: &["st", "sts", "stitch", "stitches"],
        what: "binds stitches off",
        kind: Kind::BindOff,
    },
    Recognised {
        phrases: &["co", "cast on"],
        counted: &[
            "co",
            "cast on",
            "backward loop co",
            "cable co",
            "knitted co",
        ],
        ignored: &["st", "sts", "stitch", "stitches"],
        what: "casts stitches on",
        kind: Kind::CastOn,
    },
    Recognised {
        phrases: &[
            "turn",
            "w&t",
            "w & t",
            "wrap and turn",
            "wrap & turn",
            "w+t",
            "gs",
            "german short row",
        ],
        counted: &[],
        ignored: &[],
        what: "turns the work before the row's end (a short row)",
        kind: Kind::ShortRow,
    },
    Recognised {
        phrases: &[
            "brk",
            "brp",
            "brsl",
            "brk1",
            "brp1",
            "sl1yo",
            "brioche knit",
            "brioche purl",
            "brioche slip",
        ],
        counted: &[],
        ignored: &[],
        what: "is a brioche stitch, worked together with the yarn-over it was slipped with",
        kind: Kind::Brioche,
    },
    Recognised {
        phrases: &[
            "k1b",
            "kb",
            "k1 b",
            "k b",
            "k1 below",
            "k below",
            "knit 1 below",
            "p1b",
            "pb",
            "p1 b",
            "p b",
            "p1 below",
            "p below",
            "purl 1 below",
        ],
        counted: &[],
        ignored: &[],
        what: "works into the stitch of the row below the next one (k1 below)",
        kind: Kind::Below,
    },
    Recognised {
        phrases: &["drop st", "drop stitch", "drop 1", "dip st"],
        counted: &[],
        ignored: &[],
        what: "drops or dips a loop down the rows below",
        kind: Kind::Drop,
    },
];

/// Why `token` (a stitch phrase the vocabulary does not read) is not knitted, if knitwear
/// recognises it: a sentence naming what the stitch does, what knitwear does instead, and
/// what to write. `None` for a phrase it does not recognise either.
pub fn unknitted(token: &str) -> Option<String> {
    let (what, kind, count) = recognise(&normal_form(token))?;
    let said = format!("\"{}\" {what}", token.trim().trim_end_matches('.'));
    let rows = "knitwear knits every row at one stitch count, across the whole piece";
    Some(match kind {
        Kind::Increase { from, out } => {
            let makes = if from == 0 {
                "one new stitch".to_string()
            } else {
                format!("{out} stitches of {from}")
            };
            format!(
                "{said}, making {makes}: {rows}, and knits no increase but a yarn-over (yo) or \
                 a made stitch (m1l, m1r) yet, each balanced by a decrease in the same row as \
                 lace balances them; rows whose stitch count changes are not knitted yet"
            )
        }
        Kind::BindOff | Kind::CastOn => format!(
            "{said}{}: {rows}, so it does not bind off or cast on within the fabric yet \
             (a buttonhole, a bobble worked over rows); leave out a pattern's cast-on and \
             bind-off rows: knitwear casts on and binds off each piece at its surface's edges",
            count.map_or(String::new(), |n| format!(" ({n})"))
        ),
        Kind::ShortRow => format!(
            "{said}: {rows}, so short rows are not knitted yet; shape with the surface \
             instead (its outline and curvature give the fabric its shape)"
        ),
        // Walker's treasuries write `K1-b` / `P1-b` for a stitch worked through the back loop,
        // stitch-maps and most others `k1b` for knit 1 below: the text cannot tell which.
        Kind::Below => format!(
            "{said}, so that the loop of the row below is caught by two rows: knitwear does \
             not knit it yet. Barbara Walker's treasuries write K1-b and P1-b for a stitch \
             worked through the back loop: if the pattern means that, write k1 tbl or p1 tbl"
        ),
        Kind::Brioche | Kind::Drop | Kind::Gather => {
            format!("{said}: knitwear does not knit it yet")
        }
    })
}

/// What the recognised stitch `norm` (normal form) does, and its count where one was
/// written (`bo 3`).
fn recognise(norm: &str) -> Option<(&'static str, Kind, Option<usize>)> {
    if let Some(r) = RECOGNISED.iter().find(|r| r.phrases.contains(&norm)) {
        return Some((r.what, r.kind, None));
    }
    // `n to m inc` (stitch-maps' `1-to-5-inc`) and `n to m gather` (`3-to-3-gather`).
    let words: Vec<&str> = norm.split(' ').collect();
    if let [n, "to", m, kind] = words.as_slice() {
        if let (Ok(from), Ok(out)) = (n.parse::<usize>(), m.parse::<usize>()) {
            match *kind {
                "inc" | "increase" => {
                    return Some((
                        "works several stitches out of one",
                        Kind::Increase { from, out },
                        None,
                    ))
                }
                "gather" => {
                    return Some((
                        "gathers loops together and works stitches out of them",
                        Kind::Gather,
                        None,
                    ))
                }
                _ => {}
            }
        }
    }
    for r in RECOGNISED {
        for name in r.counted {
            let Some(rest) = norm.strip_prefix(name) else {
                continue;
            };
            let rest = rest.trim_start();
            let digits = rest.chars().take_while(char::is_ascii_digit).count();
            let Ok(n) = rest[..digits].parse::<usize>() else {
                continue;
            };
            if rest[digits..]
                .split_whitespace()
                .all(|w| r.ignored.contains(&w))
            {
                return Some((r.what, r.kind, Some(n)));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pattern::vocabulary::parse_stitch;

    /// Every spelling here is one the vocabulary does not read: a stitch is either knitted or
    /// explained, never both.
    #[test]
    fn no_recognised_phrase_is_a_knitted_stitch() {
        for r in RECOGNISED {
            for p in r.phrases {
                assert!(unknitted(p).is_some(), "{p}");
                assert!(parse_stitch(p).is_none(), "{p} is knitted and explained");
            }
            for name in r.counted {
                let p = format!("{name} 3");
                assert!(unknitted(&p).is_some(), "{p}");
                assert!(parse_stitch(&p).is_none(), "{p} is knitted and explained");
            }
        }
    }

    #[test]
    fn messages_say_what_the_stitch_does_and_counts_it() {
        let m = unknitted("kfb").unwrap();
        assert!(
            m.contains("\"kfb\" knits into the front and then the back"),
            "{m}"
        );
        assert!(m.contains("making 2 stitches of 1"), "{m}");
        let m = unknitted("1-to-5-inc").unwrap();
        assert!(m.contains("making 5 stitches of 1"), "{m}");
        let m = unknitted("incl").unwrap();
        assert!(m.contains("making one new stitch"), "{m}");
        let m = unknitted("BO 3 sts").unwrap();
        assert!(m.contains("\"BO 3 sts\" binds stitches off (3)"), "{m}");
        assert!(m.contains("casts on and binds off each piece"), "{m}");
        let m = unknitted("w&t").unwrap();
        assert!(m.contains("short rows are not knitted yet"), "{m}");
        assert!(unknitted("3-to-3-gather").is_some());
        assert!(unknitted("brsl").is_some());
        let m = unknitted("K1-b").unwrap();
        assert!(m.contains("write k1 tbl or p1 tbl"), "{m}");
        assert!(unknitted("p1 below").is_some());
        // Not stitches it recognises.
        for other in ["kf", "bob", "bo x", "turnip", "1 to five inc", "k2"] {
            assert_eq!(unknitted(other), None, "{other}");
        }
    }
}
