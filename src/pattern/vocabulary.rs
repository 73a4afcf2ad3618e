//! The Knitspeak stitch vocabulary: every stitch name and stitch pattern knitwear reads, each
//! once, with what it reads as.
//!
//! [`VOCABULARY`] is the one list. [`parse_stitch`] reads a stitch phrase with it (Knitspeak
//! row bodies, [`super::knitspeak`], and chart legend lines, [`super::chart`]); [`suggest`]
//! offers the closest of its names when a phrase is unknown; the Knitspeak body grammar takes
//! `rep from *` and the bare `Knit.` / `Purl.` names from it too. A spelling added to an entry
//! is therefore read, and a name added to its `offered` list suggested, everywhere at once.
//!
//! A phrase is read in its normal form ([`normal_form`]): lower case, a final full stop
//! dropped, `-` and `_` read as spaces, runs of spaces as one (`K1-tbl.` is `k1 tbl`). Crosses
//! and their aliases are read with the spaces removed as well (`2 / 2 RC`, `C 4 B`).
//!
//! No phrase reads as two entries (the tests below check every spelling), so the order of the
//! entries does not change what a phrase reads as. It does order the suggestions: of two
//! names equally close to an unknown token, the one listed first is offered.

use super::instruction::{Instruction, MAX_CROSS_SIDE};

/// A parsed stitch phrase: the instruction, and whether it is a slip whose yarn side was not
/// given (held on the wrong side of the fabric: in back on a RS row, in front on a WS row).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Stitched {
    pub ins: Instruction,
    pub slip_default: bool,
}

impl Stitched {
    /// The instruction as worked on a row of this side (a slip's default yarn side depends on
    /// it).
    pub(crate) fn on_side(self, right_side: bool) -> Instruction {
        if self.slip_default {
            Instruction::Slip {
                yarn_front: !right_side,
            }
        } else {
            self.ins
        }
    }

    pub(crate) fn plain(ins: Instruction) -> Self {
        Self {
            ins,
            slip_default: false,
        }
    }
}

/// One stitch (or family of stitches) of the vocabulary.
pub(crate) struct Entry {
    /// Which phrases it reads, and as what.
    pub reads: Reads,
    /// The names "did you mean" may offer for it, as knitters write them.
    pub offered: &'static [&'static str],
    /// Names "did you mean" offers with the unknown token's digits after them (`k2` for
    /// `kk2`): a count the knitter wrote is kept.
    pub offered_with_count: &'static [&'static str],
}

/// How an entry's phrases are spelled and what they read as.
pub(crate) enum Reads {
    /// The whole phrase, in normal form, is one of these: the instruction, once.
    Phrase(&'static [&'static str], Instruction),
    /// A knit or purl with a count: a name, an optional count (1 or more, 1 when left out),
    /// then nothing or a through-the-back-loop phrase: `k`, `K 2`, `knit 2`, `p2 tbl`,
    /// `k1 through back loop`. Each name comes with its plain and its twisted instruction; the
    /// first name the phrase starts with is the one read, so a longer name comes before its
    /// prefix (`knit` before `k`).
    KnitPurl {
        names: &'static [(&'static str, Instruction, Instruction)],
        tbl: &'static [&'static str],
    },
    /// A slip with a count: a name (first match, as for [`Reads::KnitPurl`]), an optional
    /// count, then any of the yarn words and the words that change nothing: `sl1`,
    /// `sl 2 pwise wyif`, `slip 1 with yarn in back`, and `s1` as British patterns write it.
    /// With no yarn word the yarn is held on the wrong side ([`Stitched::slip_default`]).
    Slip {
        names: &'static [&'static str],
        /// Yarn words: (word, yarn in front).
        yarn: &'static [(&'static str, bool)],
        /// Yarn phrases of several words, each read as the yarn word after it.
        spelled_out: &'static [(&'static str, &'static str)],
        ignored: &'static [&'static str],
    },
    /// `m/n KIND` (spaces removed, any case), `m` and `n` from 1 to [`MAX_CROSS_SIDE`]: `m`
    /// stitches cross over `n`; or `m/c/n KIND`, `m` stitches crossing over `n` around `c`
    /// centre stitches, with `m + c` and `c + n` at most [`MAX_CROSS_SIDE`]
    /// ([`Instruction::CentreCross`]; the `P` of the kind purls the centre).
    Cross(&'static [CrossKind]),
    /// `CnB` / `CnF` (spaces removed): a cable of `n/2` over `n/2` stitches, `n` even, at most
    /// `2 * MAX_CROSS_SIDE`; `B` (held in back) crosses to the right, `F` (in front) to the
    /// left.
    CableAlias,
    /// `TnB` / `TnF` (spaces removed): a twist of `n` stitches, the cross `m/n` listed for it
    /// as (n, m, n, purled behind); `B` and `F` as for [`Reads::CableAlias`].
    TwistAlias(&'static [(u8, u8, u8, bool)]),
    /// `rep from *`: not a stitch but the end of a `*` repeat, which the body grammar reads
    /// (with what follows it: `to end`, `to last 3 sts`). Here so that it is suggested, and
    /// spelled, in one place.
    RepeatFrom(&'static [&'static str]),
    /// A stitch marker placed, slipped or removed (`pm`, `sm`, `place marker`): not a stitch
    /// but a mark between two, which the body grammar reads (a run may end at it: `k to m`,
    /// `k to 2 sts before m`). A spelling may be followed by the marker's name, one letter or
    /// digit (`pm A`).
    Marker(&'static [&'static str]),
}

/// The kind of a cross `m/n KIND`.
pub(crate) struct CrossKind {
    /// As knitters write it (read in any case).
    pub name: &'static str,
    /// It crosses to the left (the `m` stitches travel left in front).
    pub left: bool,
    /// The stitches passing behind are purled (the `P` of `RPC`).
    pub purl_back: bool,
    /// Offered for a cross-like unknown token with that token's `m/n`.
    pub offered_any_size: bool,
}

const fn phrase(
    spellings: &'static [&'static str],
    ins: Instruction,
    offered: &'static [&'static str],
) -> Entry {
    Entry {
        reads: Reads::Phrase(spellings, ins),
        offered,
        offered_with_count: &[],
    }
}

const fn cross(m: u8, n: u8, left: bool, purl_back: bool) -> Instruction {
    Instruction::Cross {
        m,
        n,
        left,
        purl_back,
    }
}

const fn centre_cross(m: u8, c: u8, n: u8, left: bool, purl_centre: bool) -> Instruction {
    Instruction::CentreCross {
        m,
        c,
        n,
        left,
        purl_centre,
    }
}

const fn kind(name: &'static str, left: bool, purl_back: bool, offered: bool) -> CrossKind {
    CrossKind {
        name,
        left,
        purl_back,
        offered_any_size: offered,
    }
}

/// Every stitch knitwear reads (see the module docs). The `offered` names, in this order, are
/// the suggestions tried for an unknown token.
pub(crate) const VOCABULARY: &[Entry] = {
    use Instruction as I;
    &[
        Entry {
            reads: Reads::KnitPurl {
                names: &[
                    ("knit", I::Knit, I::KnitTbl),
                    ("purl", I::Purl, I::PurlTbl),
                    ("k", I::Knit, I::KnitTbl),
                    ("p", I::Purl, I::PurlTbl),
                ],
                tbl: &[
                    "tbl",
                    "through back loop",
                    "through the back loop",
                    "through back loops",
                    "into back of st",
                    "into the back of the st",
                    "into back of stitch",
                    "into back loop",
                    "into the back loop",
                    "in back loop",
                ],
            },
            offered: &["k", "p", "knit", "purl", "k tbl", "p tbl"],
            offered_with_count: &["k", "p"],
        },
        Entry {
            reads: Reads::Slip {
                names: &["slip", "sl"],
                yarn: &[
                    ("wyib", false),
                    ("wyb", false),
                    ("wyif", true),
                    ("wyf", true),
                ],
                spelled_out: &[
                    ("with yarn in back", "wyib"),
                    ("with yarn in front", "wyif"),
                ],
                // `sl1k` / `sl1p`: stitch-maps' knitwise and purlwise slips.
                ignored: &[
                    "pwise", "purlwise", "pw", "kwise", "knitwise", "kw", "st", "sts", "k", "p",
                ],
            },
            offered: &["sl1", "sl1 wyib", "sl1 wyif"],
            offered_with_count: &["sl"],
        },
        phrase(
            &["yo", "yarn over", "yfwd", "yf", "yrn", "yon"],
            I::YarnOver,
            &["yo"],
        ),
        phrase(
            &["m1", "m1l", "m1 l", "make 1", "make one", "m1 left"],
            I::MakeOneLeft,
            &["m1", "m1l"],
        ),
        phrase(&["m1r", "m1 r", "m1 right"], I::MakeOneRight, &["m1r"]),
        // Worked purlwise, a made stitch is the same new loop: it has no loop below to be
        // pulled through to one side, and the next row works it (see `rows::oriented`).
        phrase(
            &["m1lp", "m1p", "m1 lp", "m1 purlwise", "make 1 purlwise"],
            I::MakeOneLeft,
            &["m1lp", "m1p"],
        ),
        phrase(&["m1rp", "m1 rp"], I::MakeOneRight, &["m1rp"]),
        phrase(
            &["k2tog", "k 2 tog", "k2 tog", "knit 2 together"],
            I::K2tog,
            &["k2tog"],
        ),
        phrase(
            &[
                "ssk",
                "skp",
                "skpo",
                "sl1 k1 psso",
                "sl 1 k1 psso",
                "sl 1 k 1 psso",
                "s1 k1 psso",
            ],
            I::Ssk,
            &["ssk"],
        ),
        phrase(
            &["p2tog", "p 2 tog", "p2 tog", "purl 2 together"],
            I::P2tog,
            &["p2tog"],
        ),
        phrase(&["ssp"], I::Ssp, &["ssp"]),
        phrase(&["k3tog", "k 3 tog", "k3 tog"], I::K3tog, &["k3tog"]),
        phrase(&["sssk"], I::Sssk, &["sssk"]),
        phrase(
            &["p3tog", "p 3 tog", "p3 tog", "purl 3 together"],
            I::P3tog,
            &["p3tog"],
        ),
        phrase(&["sssp"], I::Sssp, &["sssp"]),
        phrase(&["k4tog", "k 4 tog", "k4 tog"], I::K4tog, &["k4tog"]),
        phrase(&["p4tog", "p 4 tog", "p4 tog"], I::P4tog, &["p4tog"]),
        phrase(&["k5tog", "k 5 tog", "k5 tog"], I::K5tog, &["k5tog"]),
        phrase(&["p5tog", "p 5 tog", "p5 tog"], I::P5tog, &["p5tog"]),
        phrase(
            &[
                "k2tog tbl",
                "k2 tog tbl",
                "k 2 tog tbl",
                "k2tog through back loops",
                "k2tog through back loop",
                "k2tog through the back loops",
                "k2tog through the back loop",
                // Barbara Walker's `-b`: through the back loops.
                "k2tog b",
                "k2togtbl",
            ],
            I::K2togTbl,
            &["k2tog tbl"],
        ),
        phrase(
            &[
                "p2tog tbl",
                "p2 tog tbl",
                "p 2 tog tbl",
                "p2tog through back loops",
                "p2tog through back loop",
                "p2tog through the back loops",
                "p2tog through the back loop",
                "p2tog b",
                "p2togtbl",
            ],
            I::P2togTbl,
            &["p2tog tbl"],
        ),
        phrase(
            &[
                "k3tog tbl",
                "k3 tog tbl",
                "k 3 tog tbl",
                "k3tog through back loops",
                "k3tog through back loop",
                "k3tog through the back loops",
                "k3tog through the back loop",
            ],
            I::K3togTbl,
            &["k3tog tbl"],
        ),
        phrase(
            &[
                "p3tog tbl",
                "p3 tog tbl",
                "p 3 tog tbl",
                "p3tog through back loops",
                "p3tog through back loop",
                "p3tog through the back loops",
                "p3tog through the back loop",
            ],
            I::P3togTbl,
            &["p3tog tbl"],
        ),
        phrase(
            &["cddp", "sl2 p1 p2sso", "sl 2 p1 p2sso", "s2 p1 p2sso"],
            I::Cddp,
            &["cddp"],
        ),
        phrase(
            &[
                "sk2p",
                "sk2po",
                "sl1 k2tog psso",
                "sl 1 k2tog psso",
                "s1 k2tog psso",
            ],
            I::Sk2p,
            &["sk2p", "sl1-k2tog-psso"],
        ),
        phrase(
            &[
                "cdd",
                "s2kp",
                "s2kp2",
                "s2kpo",
                "sl2 k1 p2sso",
                "sl 2 k1 p2sso",
                "s2 k1 p2sso",
                "centered double decrease",
                "centred double decrease",
            ],
            I::Cdd,
            &["s2kp", "cdd"],
        ),
        phrase(
            &["mb", "bobble", "make bobble", "make a bobble"],
            I::Bobble,
            &["MB"],
        ),
        Entry {
            reads: Reads::Cross(&[
                kind("RC", false, false, true),
                kind("LC", true, false, true),
                kind("RPC", false, true, true),
                kind("LPC", true, true, true),
                // A twist is a cross of single stitches, spelled with T.
                kind("RT", false, false, true),
                kind("LT", true, false, true),
                kind("RPT", false, true, false),
                kind("LPT", true, true, false),
            ]),
            offered: &[
                "1/1 RT", "1/1 LT", "1/1 RPT", "1/1 LPT", "2/2 RC", "2/2 LC", "2/2 RPC", "2/2 LPC",
                "3/3 RC", "3/3 LC", "2/1 RC", "2/1 LC", "2/1 RPC", "2/1 LPC",
            ],
            offered_with_count: &[],
        },
        // A twist's kind alone means the 1/1 twist.
        phrase(&["rt"], cross(1, 1, false, false), &[]),
        // Publishers' twists and crosses (Rowan, Debbie Bliss, Sirdar): `Tw2` knits the
        // second stitch then the first, a right twist; `Tw2L` / `Tw2F` the left one. `Cr2R` /
        // `Cr3R` cross a knit stitch (two) to the right over a purl one, the stitch behind
        // purled: `1/1 RPT` / `2/1 RPC`, and `Cr2L` / `Cr3L` the same to the left.
        phrase(
            &["tw2", "tw2r", "tw2b", "tw 2", "tw2 r", "tw2 b"],
            cross(1, 1, false, false),
            &["Tw2"],
        ),
        phrase(
            &["tw2l", "tw2f", "tw2 l", "tw2 f"],
            cross(1, 1, true, false),
            &["Tw2L"],
        ),
        phrase(&["cr2r", "cr2 r"], cross(1, 1, false, true), &["Cr2R"]),
        phrase(&["cr2l", "cr2 l"], cross(1, 1, true, true), &["Cr2L"]),
        phrase(&["cr3r", "cr3 r"], cross(2, 1, false, true), &["Cr3R"]),
        phrase(&["cr3l", "cr3 l"], cross(2, 1, true, true), &["Cr3L"]),
        phrase(&["lt"], cross(1, 1, true, false), &[]),
        phrase(&["rpt"], cross(1, 1, false, true), &[]),
        phrase(&["lpt"], cross(1, 1, true, true), &[]),
        Entry {
            reads: Reads::CableAlias,
            offered: &["C4B", "C4F", "C6B", "C6F"],
            offered_with_count: &[],
        },
        Entry {
            reads: Reads::TwistAlias(&[(2, 1, 1, false), (3, 2, 1, true), (4, 2, 2, true)]),
            offered: &["T2B", "T2F", "T3B", "T3F", "T4B", "T4F"],
            offered_with_count: &[],
        },
        Entry {
            // The longer spellings first: `rep` alone (`*k2, p2; rep to end`) is read last.
            reads: Reads::RepeatFrom(&[
                "rep from *",
                "repeat from *",
                "rep *",
                "repeat *",
                "work from *",
                "repeat",
                "rep",
            ]),
            offered: &[
                "rep from *",
                "rep from * to end",
                "rep from * to last 2 sts",
            ],
            offered_with_count: &[],
        },
        Entry {
            reads: Reads::Marker(&[
                "pm",
                "sm",
                "slm",
                "sl m",
                "slip m",
                "rm",
                "place marker",
                "slip marker",
                "remove marker",
                "place a marker",
                "pm for beg of rnd",
                "pm for beginning of rnd",
                "pm for beginning of round",
                "pm for beg of round",
                "place marker for beginning of round",
                "place beg of rnd marker",
                "place beginning of round marker",
                "place beginning of rnd marker",
            ]),
            // Not offered: "pm" is as close to many a mistyped purl as "p" is.
            offered: &[],
            offered_with_count: &[],
        },
    ]
};

/// A phrase in normal form (see the module docs).
pub(crate) fn normal_form(phrase: &str) -> String {
    phrase
        .trim()
        .trim_end_matches('.')
        .to_lowercase()
        .replace(['-', '_'], " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// Reads one stitch phrase (`k2`, `knit 2`, `k1 tbl`, `sl 1 wyif`, `2/2 RC`, `C4B`, `ssk`...)
/// into its instruction and count. `None` when it is not a stitch of [`VOCABULARY`].
pub(crate) fn parse_stitch(phrase: &str) -> Option<(Stitched, usize)> {
    let norm = normal_form(phrase);
    let squeezed: String = norm.chars().filter(|c| *c != ' ').collect();
    VOCABULARY
        .iter()
        .find_map(|entry| entry.reads.read(&norm, &squeezed))
}

/// The instruction a stitch phrase reads as (`"k2tog"`, `"sl1-k2tog-psso"`, `"2/2 LPC"`,
/// `"k1 tbl"`), whatever its count; `None` where the reader does not know the stitch.
pub fn reads_stitch(phrase: &str) -> Option<Instruction> {
    parse_stitch(phrase).map(|(stitched, _)| stitched.ins)
}

impl Reads {
    /// What `norm` (a phrase in normal form; `squeezed` is it without spaces) reads as, if it
    /// is one of this entry's phrases.
    fn read(&self, norm: &str, squeezed: &str) -> Option<(Stitched, usize)> {
        let once = |ins| Some((Stitched::plain(ins), 1));
        match *self {
            Self::Phrase(spellings, ins) => {
                spellings.contains(&norm).then(|| (Stitched::plain(ins), 1))
            }
            Self::KnitPurl { names, tbl } => {
                let (rest, plain, twisted) = names
                    .iter()
                    .find_map(|&(name, p, t)| norm.strip_prefix(name).map(|r| (r, p, t)))?;
                let (count, modifiers) = count_and_rest(rest)?;
                let ins = match modifiers {
                    "" => plain,
                    m if tbl.contains(&m) => twisted,
                    _ => return None,
                };
                Some((Stitched::plain(ins), count))
            }
            Self::Slip {
                names,
                yarn,
                spelled_out,
                ignored,
            } => {
                // `s1`, `s2 wyif` (British patterns): `s` with a count is `sl`.
                let british = norm
                    .strip_prefix('s')
                    .filter(|r| r.starts_with(|c: char| c.is_ascii_digit()))
                    .map(|r| format!("sl{r}"));
                let norm = british.as_deref().unwrap_or(norm);
                let rest = names.iter().find_map(|name| norm.strip_prefix(name))?;
                let (count, modifiers) = count_and_rest(rest)?;
                let mut words = modifiers.to_string();
                for (long, word) in spelled_out {
                    words = words.replace(long, word);
                }
                let mut front = None;
                for word in words.split_whitespace() {
                    if let Some(&(_, f)) = yarn.iter().find(|(w, _)| *w == word) {
                        front = Some(f);
                    } else if !ignored.contains(&word) {
                        return None;
                    }
                }
                let stitched = Stitched {
                    ins: Instruction::Slip {
                        yarn_front: front.unwrap_or(false),
                    },
                    slip_default: front.is_none(),
                };
                Some((stitched, count))
            }
            Self::Cross(kinds) => {
                let digits = squeezed
                    .chars()
                    .take_while(|c| c.is_ascii_digit() || *c == '/')
                    .count();
                let (sizes, written) = squeezed.split_at(digits);
                let k = kinds
                    .iter()
                    .find(|k| k.name.eq_ignore_ascii_case(written))?;
                let sizes: Vec<u8> = sizes
                    .split('/')
                    .map(|s| s.parse().ok().filter(|&x| x >= 1))
                    .collect::<Option<_>>()?;
                let side = |x: u8| x <= MAX_CROSS_SIDE;
                match sizes[..] {
                    [m, n] if side(m) && side(n) => once(cross(m, n, k.left, k.purl_back)),
                    // No loop of a centre cross travels further than one of a plain cross.
                    [m, c, n] if side(m.saturating_add(c)) && side(c.saturating_add(n)) => {
                        once(centre_cross(m, c, n, k.left, k.purl_back))
                    }
                    _ => None,
                }
            }
            Self::CableAlias => {
                // `Cable 4 back` / `cable 6 front` spelled out.
                let spelled = squeezed.strip_prefix("cable").and_then(|r| {
                    let (n, dir) = r
                        .strip_suffix("back")
                        .map(|n| (n, 'b'))
                        .or_else(|| r.strip_suffix("front").map(|n| (n, 'f')))?;
                    Some(format!("c{n}{dir}"))
                });
                let (n, left) = alias(spelled.as_deref().unwrap_or(squeezed), 'c')?;
                if n % 2 != 0 || !(2..=2 * MAX_CROSS_SIDE).contains(&n) {
                    return None;
                }
                once(cross(n / 2, n / 2, left, false))
            }
            Self::TwistAlias(sizes) => {
                let (count, left) = alias(squeezed, 't')?;
                let &(_, m, n, purl_back) = sizes.iter().find(|s| s.0 == count)?;
                once(cross(m, n, left, purl_back))
            }
            Self::RepeatFrom(_) | Self::Marker(_) => None,
        }
    }
}

/// A count, in digits or words (1 when none is written; 0 or a count too large to read is
/// no stitch), and the words after it, from what follows a stitch's name.
fn count_and_rest(rest: &str) -> Option<(usize, &str)> {
    let rest = rest.trim_start();
    let digits = rest.chars().take_while(char::is_ascii_digit).count();
    if digits == 0 {
        // A count in words, as some printed patterns spell it (`knit two`, `slip one`).
        let word = rest.split(' ').next().unwrap_or("");
        if let Some(n) = super::knitspeak::numbers::count(word).filter(|&n| n >= 1) {
            return Some((n, rest[word.len()..].trim()));
        }
    }
    let count = if digits == 0 {
        1
    } else {
        rest[..digits].parse::<usize>().ok().filter(|&n| n >= 1)?
    };
    Some((count, rest[digits..].trim()))
}

/// `CnB` / `TnF` (spaces removed) with the given letter: the stitch count and whether it
/// crosses to the left (`F`, held in front).
fn alias(squeezed: &str, letter: char) -> Option<(u8, bool)> {
    let rest = squeezed.strip_prefix(letter)?;
    // Splits off the last character (not byte: a stitch ending in `é` is an unknown stitch
    // to report, never a panic).
    let last = rest.char_indices().next_back().map_or(0, |(i, _)| i);
    let (digits, dir) = rest.split_at(last);
    let left = match dir {
        "b" => false,
        "f" => true,
        _ => return None,
    };
    Some((digits.parse().ok()?, left))
}

/// Why `token` is refused if it is a `C3B`-style cable of an odd stitch count: publishers
/// split those two ways (`C3B` is `2/1 RC` in some books and `1/2 RC` in others), so the
/// reader asks which rather than guess. `None` for any other token.
pub(crate) fn odd_cable_alias(token: &str) -> Option<String> {
    let squeezed: String = normal_form(token).chars().filter(|c| *c != ' ').collect();
    let (n, left) = alias(&squeezed, 'c')?;
    if n % 2 == 0 || !(3..=2 * MAX_CROSS_SIDE - 1).contains(&n) {
        return None;
    }
    let (big, small) = (n / 2 + 1, n / 2);
    let kind = if left { "LC" } else { "RC" };
    Some(format!(
        "\"{}\" crosses {n} stitches, which publishers split two ways: write it as \
         \"{big}/{small} {kind}\" ({big} stitches travel in front) or \"{small}/{big} {kind}\" \
         ({small} in front), as the pattern's abbreviations explain it, or paste that \
         explanation with the rows (\"{name} = sl {small} to cn, hold at back, k{big}, k{small} \
         from cn\")",
        token.trim(),
        name = token.trim(),
    ))
}

/// Whether `lower` (lower case) is a bare knit or purl name (`knit`, `p`): a row body of that
/// one word works it across the row.
pub(crate) fn is_knit_or_purl_name(lower: &str) -> bool {
    VOCABULARY.iter().any(|e| match e.reads {
        Reads::KnitPurl { names, .. } => names.iter().any(|(name, _, _)| *name == lower),
        _ => false,
    })
}

/// What follows `rep from *` (in any of its spellings) in `lower` (lower case), if it starts
/// with it.
pub(crate) fn after_repeat_from(lower: &str) -> Option<&str> {
    VOCABULARY.iter().find_map(|e| match e.reads {
        Reads::RepeatFrom(spellings) => spellings.iter().find_map(|s| lower.strip_prefix(s)),
        _ => None,
    })
}

/// Whether `lower` (a phrase, any case) is a stitch marker placed, slipped or removed
/// ([`Reads::Marker`]), its name included (`pm A`, `sm 2`).
pub(crate) fn is_marker(lower: &str) -> bool {
    let norm = normal_form(lower);
    let unnamed = match norm.rsplit_once(' ') {
        Some((head, name))
            if name.len() == 1 && name.chars().all(|c| c.is_ascii_alphanumeric()) =>
        {
            head
        }
        _ => norm.as_str(),
    };
    VOCABULARY.iter().any(|e| match e.reads {
        Reads::Marker(spellings) => {
            spellings.contains(&norm.as_str()) || spellings.contains(&unnamed)
        }
        _ => false,
    })
}

/// The known stitch closest to `token`: the nearest (Levenshtein distance, case ignored) of
/// the names [`VOCABULARY`] offers, of a cross with the token's `m/n` for a cross-like token,
/// and of a counted stitch with the token's digits.
pub(crate) fn suggest(token: &str) -> String {
    let lower = token.trim().to_lowercase();
    let mut candidates: Vec<String> = VOCABULARY
        .iter()
        .flat_map(|e| e.offered)
        .map(|s| s.to_string())
        .collect();
    // A cross-like token (`2/2 RX`, `1/1/1 LPX`) is offered every kind at its own sizes.
    let sizes: String = lower
        .chars()
        .take_while(|c| c.is_ascii_digit() || matches!(c, '/' | ' '))
        .filter(|c| *c != ' ')
        .collect();
    if sizes.contains('/') {
        let kinds = VOCABULARY.iter().flat_map(|e| match e.reads {
            Reads::Cross(kinds) => kinds,
            _ => &[],
        });
        for k in kinds.filter(|k| k.offered_any_size) {
            candidates.push(format!("{sizes} {}", k.name));
        }
    }
    let digits: String = lower.chars().filter(char::is_ascii_digit).collect();
    // Longer digit runs are no count a knitter means.
    if !digits.is_empty() && digits.len() <= 3 {
        for base in VOCABULARY.iter().flat_map(|e| e.offered_with_count) {
            candidates.push(format!("{base}{digits}"));
        }
    }
    // `min_by_key` keeps the first of equally close names: the vocabulary's order decides.
    candidates
        .into_iter()
        .min_by_key(|k| strsim::levenshtein(&lower, &k.to_lowercase()))
        .unwrap_or_else(|| "k".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every spelling of every entry (an example of each pattern), with whether it is a
    /// stitch (`rep from *` is not).
    fn spellings() -> Vec<(String, bool)> {
        let mut out = Vec::new();
        for e in VOCABULARY {
            let mut own: Vec<String> = e.offered.iter().map(|s| s.to_string()).collect();
            match e.reads {
                Reads::Phrase(s, _) | Reads::RepeatFrom(s) | Reads::Marker(s) => {
                    own.extend(s.iter().map(|s| s.to_string()))
                }
                Reads::KnitPurl { names, tbl } => {
                    for (name, _, _) in names {
                        own.push(name.to_string());
                        own.extend(tbl.iter().map(|t| format!("{name}2 {t}")));
                    }
                }
                Reads::Slip {
                    names,
                    yarn,
                    spelled_out,
                    ignored,
                } => {
                    for name in names {
                        own.push(format!("{name}1"));
                        own.extend(yarn.iter().map(|(w, _)| format!("{name} 2 {w}")));
                        own.extend(spelled_out.iter().map(|(w, _)| format!("{name} {w}")));
                        own.extend(ignored.iter().map(|w| format!("{name}1 {w}")));
                    }
                }
                Reads::Cross(kinds) => own.extend(kinds.iter().map(|k| format!("2/1 {}", k.name))),
                Reads::CableAlias | Reads::TwistAlias(_) => {}
            }
            let stitch = !matches!(e.reads, Reads::RepeatFrom(_) | Reads::Marker(_));
            out.extend(own.into_iter().map(|s| (s, stitch)));
        }
        out
    }

    /// The order of the entries must not change what a phrase reads as.
    #[test]
    fn no_phrase_reads_as_two_entries() {
        for (s, stitch) in spellings() {
            let norm = normal_form(&s);
            let squeezed: String = norm.chars().filter(|c| *c != ' ').collect();
            let readers = VOCABULARY
                .iter()
                .filter(|e| e.reads.read(&norm, &squeezed).is_some())
                .count();
            assert_eq!(
                readers,
                usize::from(stitch),
                "{s:?} is read by {readers} entries"
            );
        }
    }

    /// Every name a suggestion offers reads back (all but `rep from *`, which is no stitch).
    #[test]
    fn offered_names_read() {
        for e in VOCABULARY {
            if matches!(e.reads, Reads::RepeatFrom(_) | Reads::Marker(_)) {
                continue;
            }
            for name in e.offered {
                assert!(parse_stitch(name).is_some(), "{name}");
            }
            for name in e.offered_with_count {
                assert!(parse_stitch(&format!("{name}2")).is_some(), "{name}2");
            }
        }
    }

    /// What [`Instruction::name`] writes (chart legends, messages) reads back as the same
    /// instruction.
    #[test]
    fn written_names_read_back() {
        use Instruction as I;
        let mut all = vec![
            I::Knit,
            I::Purl,
            I::KnitTbl,
            I::PurlTbl,
            I::Slip { yarn_front: false },
            I::Slip { yarn_front: true },
            I::YarnOver,
            I::MakeOneLeft,
            I::MakeOneRight,
            I::K2tog,
            I::Ssk,
            I::P2tog,
            I::Ssp,
            I::K3tog,
            I::Sssk,
            I::P3tog,
            I::Sssp,
            I::K2togTbl,
            I::P2togTbl,
            I::K3togTbl,
            I::P3togTbl,
            I::Sk2p,
            I::Cdd,
            I::Cddp,
            I::K4tog,
            I::P4tog,
            I::K5tog,
            I::P5tog,
            I::Bobble,
        ];
        for m in 1..=MAX_CROSS_SIDE {
            for n in 1..=MAX_CROSS_SIDE {
                for (left, purl_back) in
                    [(false, false), (true, false), (false, true), (true, true)]
                {
                    all.push(cross(m, n, left, purl_back));
                }
            }
        }
        for m in 1..MAX_CROSS_SIDE {
            for c in 1..=MAX_CROSS_SIDE - m {
                for n in 1..=MAX_CROSS_SIDE - c {
                    for (left, purl) in [(false, false), (true, false), (false, true), (true, true)]
                    {
                        all.push(centre_cross(m, c, n, left, purl));
                    }
                }
            }
        }
        for ins in all {
            let read = parse_stitch(&ins.name()).map(|(s, n)| (s.ins, n));
            assert_eq!(read, Some((ins, 1)), "{}", ins.name());
        }
    }

    #[test]
    fn suggestions() {
        assert_eq!(suggest("k2tgo"), "k2tog");
        assert_eq!(suggest("2/2 RX"), "2/2 RC");
        assert_eq!(suggest("1/1/1 LPX"), "1/1/1 LPC");
        assert_eq!(suggest("kk3"), "k3");
        assert_eq!(suggest("rep frm *"), "rep from *");
    }
}
