//! Written row instructions in Knitspeak (the stitch-maps dialect knitters paste from books
//! and websites), read into the chart of one horizontal and vertical repeat of the fabric.
//!
//! # What it reads
//!
//! - Row headers: `Row 1 (RS):`, `Row 2:`, `Rows 2, 3, and 4:`, `Rows 5-8:`, `Rnd 1:` /
//!   `Rnds 1 and 2:` / `Round 3:` (in the round every row is worked from the right side),
//!   `All WS rows:`, `All RS rows:`, `All even-numbered rows:`. Statements may share a line
//!   (`Row 1: Knit. Row 2: Purl.`). `Repeat rows 1-4.` and `Multiple of 6 sts plus 5.` lines
//!   are accepted and ignored: the chart repeats anyway.
//! - Sides: a header's `(RS)` / `(WS)` sets the side of its rows; other rows of flat knitting
//!   alternate from it (row 1 is RS when nothing says otherwise). Flat knitting with an odd
//!   number of rows turns over between repeats, so the chart holds the rows twice, the second
//!   time on the other side (rows `h+1 .. 2h` in messages).
//! - Repeats: `*k2, p2; rep from *`, `rep from * to end` / `across`, `rep from * to last 3
//!   sts, k3` (the stitches after the repeat must be exactly that many), `rep from * 2 more
//!   times` (a fixed count), stitches before and after the repeat, `[k1, p1] 3 times`, `(yo,
//!   k1) twice`, `k2tog 3 times`, `k to end` / `k to last 3 sts` / `Knit.` / `Purl.` (a
//!   one-stitch repeat), and stitch counts `(18 sts)` (checked on rows of a fixed width).
//! - Stitches (any case; `-` and spaces are interchangeable): `k`, `p` with counts (`k2`,
//!   `K 2`, `knit 2`), `k tbl` / `k1-tbl` / `p2 tbl`, `sl1` / `sl 2 pwise wyif` / `sl1 wyib`
//!   (without `wyib`/`wyif` the yarn is held on the wrong side: in back on a RS row, in front
//!   on a WS row), `yo`, `m1` = `m1l`, `m1r`, `k2tog`, `ssk` (`skp`), `p2tog`, `ssp`, `k3tog`,
//!   `sssk`, `sk2p` (`sl1-k2tog-psso`), `cdd` (`s2kp`, `sl2-k1-p2sso`), `MB` (bobble), crosses
//!   `m/n RC`, `LC`, `RPC`, `LPC` with `m, n` up to 6, `1/1 RT`, `LT`, `RPT`, `LPT`, and the
//!   aliases `C4B` = `2/2 RC`, `C4F` = `2/2 LC` (any even `CnB`/`CnF`), `T2B`/`T2F` = `1/1
//!   RT`/`LT`, `T3B`/`T3F` = `2/1 RPC`/`LPC`, `T4B`/`T4F` = `2/2 RPC`/`LPC`.
//!
//! An unknown stitch or a malformed row is an error naming the row, the instruction (counted
//! from 1 in the order written) and the token, with the closest stitch this reader knows:
//! nothing is knitted from a pattern it only half understood.
//!
//! # From rows to one repeat (the phase of the repeats)
//!
//! The rows are laid out on a notional flat piece, exactly as a knitter works it: a RS row
//! from the right edge leftwards, a WS row from the left edge rightwards, each with its
//! stitches before the repeat, the repeat as many times as fits, and its stitches after.
//!
//! - If some row has no open-ended repeat (a panel such as `P2, k12, p2`), the piece is that
//!   wide, every other row must fit it (its repeat filling what its edge stitches leave), and
//!   the chart is the whole piece.
//! - Otherwise the chart is one horizontal repeat, `W` = the least common multiple of the rows'
//!   repeat widths (in stitches worked), at most [`MAX_KNITSPEAK_WIDTH`]. The piece width `N`
//!   must fit every row (`N = before + after + k * repeat`); a row that wants a multiple of 4
//!   and another a multiple of 4 plus 2 is an error. Because RS rows are measured from the
//!   right edge and WS rows from the left, `N` fixes how the rows' repeats line up, which is
//!   what a knitter's "multiple of 6 plus 5" means. The chart is the `W` columns of a wide
//!   piece (`N` a valid width, large enough to have edges well away from the middle) starting
//!   at the first column, counted from the piece's left edge, where no row has an instruction
//!   across the chart's edge; if every column cuts some row's cable, the chart still starts
//!   there and the chart's cells carry the cable across its edge (the fabric is the same).
//!
//! Stitch counts are checked per chart repeat before anything is laid out: every row must
//! work the loops the row below left (wrapping from the last row to the first) and, since
//! knitwear knits on a lattice of a fixed width, keep its own count (see [`super::rows`]).

use super::instruction::{Instruction, MAX_CROSS_SIDE};
use super::rows::{cells_from_rows, WrittenRow};
use super::{Stitch, StitchPattern};
use crate::error::{KnitError, Result};

/// Widest chart a Knitspeak pattern may make (the least common multiple of its rows' repeats,
/// or a panel's width).
pub const MAX_KNITSPEAK_WIDTH: usize = 256;
/// Most rows a Knitspeak pattern may number.
pub const MAX_KNITSPEAK_ROWS: usize = 1024;

/// Stitch names for "did you mean" suggestions.
const KNOWN: &[&str] = &[
    "k",
    "p",
    "knit",
    "purl",
    "k tbl",
    "p tbl",
    "sl1",
    "sl1 wyib",
    "sl1 wyif",
    "yo",
    "m1",
    "m1l",
    "m1r",
    "k2tog",
    "ssk",
    "p2tog",
    "ssp",
    "k3tog",
    "sssk",
    "sk2p",
    "sl1-k2tog-psso",
    "s2kp",
    "cdd",
    "MB",
    "1/1 RT",
    "1/1 LT",
    "1/1 RPT",
    "1/1 LPT",
    "2/2 RC",
    "2/2 LC",
    "2/2 RPC",
    "2/2 LPC",
    "3/3 RC",
    "3/3 LC",
    "2/1 RC",
    "2/1 LC",
    "2/1 RPC",
    "2/1 LPC",
    "C4B",
    "C4F",
    "C6B",
    "C6F",
    "T2B",
    "T2F",
    "T3B",
    "T3F",
    "T4B",
    "T4F",
    "rep from *",
    "rep from * to end",
    "rep from * to last 2 sts",
];

/// A parsed stitch phrase: the instruction, and whether it is a slip whose yarn side was not
/// given (held on the wrong side of the fabric: in back on a RS row, in front on a WS row).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Stitched {
    pub ins: Instruction,
    pub slip_default: bool,
}

impl Stitched {
    pub(crate) fn on_side(self, right_side: bool) -> Instruction {
        if self.slip_default {
            Instruction::Slip {
                yarn_front: !right_side,
            }
        } else {
            self.ins
        }
    }
}

/// Reads one stitch phrase (`k2`, `knit 2`, `k1 tbl`, `sl 1 wyif`, `2/2 RC`, `C4B`, `ssk`...)
/// into its instruction and count. `None` when it is not a stitch this reader knows.
pub(crate) fn parse_stitch(phrase: &str) -> Option<(Stitched, usize)> {
    use Instruction as I;
    let lower = phrase.trim().trim_end_matches('.').to_lowercase();
    let norm = lower
        .replace(['-', '_'], " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let plain = |ins| {
        Some((
            Stitched {
                ins,
                slip_default: false,
            },
            1,
        ))
    };
    let cross = |m: u8, n: u8, left: bool, purl_back: bool| {
        plain(I::Cross {
            m,
            n,
            left,
            purl_back,
        })
    };
    match norm.as_str() {
        "yo" | "yarn over" | "yfwd" | "yf" | "yrn" | "yon" => return plain(I::YarnOver),
        "m1" | "m1l" | "m1 l" | "make 1" | "make one" | "m1 left" => return plain(I::MakeOneLeft),
        "m1r" | "m1 r" | "m1 right" => return plain(I::MakeOneRight),
        "k2tog" | "k 2 tog" | "k2 tog" | "knit 2 together" => return plain(I::K2tog),
        "ssk" | "skp" | "skpo" | "sl1 k1 psso" | "sl 1 k1 psso" | "sl 1 k 1 psso"
        | "s1 k1 psso" => return plain(I::Ssk),
        "p2tog" | "p 2 tog" | "p2 tog" | "purl 2 together" => return plain(I::P2tog),
        "ssp" => return plain(I::Ssp),
        "k3tog" | "k 3 tog" | "k3 tog" => return plain(I::K3tog),
        "sssk" => return plain(I::Sssk),
        "sk2p" | "sk2po" | "sl1 k2tog psso" | "sl 1 k2tog psso" | "s1 k2tog psso" => {
            return plain(I::Sk2p)
        }
        "cdd"
        | "s2kp"
        | "s2kp2"
        | "sl2 k1 p2sso"
        | "sl 2 k1 p2sso"
        | "s2 k1 p2sso"
        | "centered double decrease"
        | "centred double decrease" => return plain(I::Cdd),
        "mb" | "bobble" | "make bobble" | "make a bobble" => return plain(I::Bobble),
        "rt" => return cross(1, 1, false, false),
        "lt" => return cross(1, 1, true, false),
        "rpt" => return cross(1, 1, false, true),
        "lpt" => return cross(1, 1, true, true),
        _ => {}
    }
    let squeezed: String = norm.chars().filter(|c| *c != ' ').collect();
    if let Some(c) = parse_cross(&squeezed) {
        return plain(c);
    }
    // Cable aliases: CnB / CnF (n/2 over n/2), TnB / TnF (twists).
    if let Some(rest) = squeezed
        .strip_prefix('c')
        .or_else(|| squeezed.strip_prefix('t'))
    {
        let twist = squeezed.starts_with('t');
        let (digits, dir) = rest.split_at(rest.len().saturating_sub(1));
        if let (Ok(n), "b" | "f") = (digits.parse::<u8>(), dir) {
            let left = dir == "f";
            return match (twist, n) {
                (false, n) if n % 2 == 0 && (2..=2 * MAX_CROSS_SIDE).contains(&n) => {
                    cross(n / 2, n / 2, left, false)
                }
                (true, 2) => cross(1, 1, left, false),
                (true, 3) => cross(2, 1, left, true),
                (true, 4) => cross(2, 2, left, true),
                _ => None,
            };
        }
    }
    counted(&norm)
}

/// `m/n RC`, `m/n lpc`, `1/1 rt` (spaces removed, lower case).
fn parse_cross(s: &str) -> Option<Instruction> {
    let (m, rest) = s.split_once('/')?;
    let digits = rest.chars().take_while(char::is_ascii_digit).count();
    let (n, kind) = rest.split_at(digits);
    let (m, n): (u8, u8) = (m.parse().ok()?, n.parse().ok()?);
    let (left, purl_back) = match kind {
        "rc" | "rt" => (false, false),
        "lc" | "lt" => (true, false),
        "rpc" | "rpt" => (false, true),
        "lpc" | "lpt" => (true, true),
        _ => return None,
    };
    let ok = |x: u8| (1..=MAX_CROSS_SIDE).contains(&x);
    (ok(m) && ok(n)).then_some(Instruction::Cross {
        m,
        n,
        left,
        purl_back,
    })
}

/// Counted stitches: `k`, `k2`, `knit 2`, `p2 tbl`, `k1 through back loop`, `sl1 wyif`,
/// `sl 2 pwise wyib`, `slip 1 knitwise`.
fn counted(norm: &str) -> Option<(Stitched, usize)> {
    const NAMES: &[(&str, u8)] = &[
        ("knit", b'k'),
        ("purl", b'p'),
        ("slip", b's'),
        ("sl", b's'),
        ("k", b'k'),
        ("p", b'p'),
    ];
    let (rest, kind) = NAMES
        .iter()
        .find_map(|(name, kind)| norm.strip_prefix(name).map(|r| (r, *kind)))?;
    let rest = rest.trim_start();
    let digits = rest.chars().take_while(char::is_ascii_digit).count();
    let count = if digits == 0 {
        1
    } else {
        rest[..digits].parse::<usize>().ok().filter(|&n| n >= 1)?
    };
    let modifiers = rest[digits..].trim();
    let twisted = |m: &str| {
        matches!(
            m,
            "tbl" | "through back loop" | "through the back loop" | "through back loops"
        )
    };
    let stitched = match kind {
        b'k' | b'p' => {
            let tbl = match modifiers {
                "" => false,
                m if twisted(m) => true,
                _ => return None,
            };
            let ins = match (kind, tbl) {
                (b'k', false) => Instruction::Knit,
                (b'k', true) => Instruction::KnitTbl,
                (_, false) => Instruction::Purl,
                (_, true) => Instruction::PurlTbl,
            };
            Stitched {
                ins,
                slip_default: false,
            }
        }
        _ => {
            let m = modifiers
                .replace("with yarn in back", "wyib")
                .replace("with yarn in front", "wyif");
            let mut yarn = None;
            for word in m.split_whitespace() {
                match word {
                    "wyib" | "wyb" => yarn = Some(false),
                    "wyif" | "wyf" => yarn = Some(true),
                    "pwise" | "purlwise" | "kwise" | "knitwise" | "st" | "sts" => {}
                    _ => return None,
                }
            }
            Stitched {
                ins: Instruction::Slip {
                    yarn_front: yarn.unwrap_or(false),
                },
                slip_default: yarn.is_none(),
            }
        }
    };
    Some((stitched, count))
}

/// How an open repeat ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Until {
    /// Across the row (`rep from * to end`, or the stitches after it follow).
    End,
    /// `to last N sts`.
    Last(usize),
    /// `rep from * 2 more times`: this many times in all.
    Times(usize),
}

/// One row's body: stitches before the repeat, the repeat, stitches after it (working order).
#[derive(Debug, Clone)]
struct Body {
    before: Vec<Stitched>,
    repeat: Option<(Vec<Stitched>, Until)>,
    after: Vec<Stitched>,
    /// `(18 sts)`
    count: Option<usize>,
}

/// Which rows a statement is for.
enum Rows {
    Numbers(Vec<usize>),
    AllOfSide(bool),
    AllEven,
}

/// A row to lay out: its number for messages, side, header and body.
struct RowPlan<'a> {
    number: usize,
    right_side: bool,
    what: &'a str,
    body: &'a Body,
}

impl RowPlan<'_> {
    fn resolve(&self, v: &[Stitched]) -> Vec<Instruction> {
        v.iter().map(|s| s.on_side(self.right_side)).collect()
    }
    fn ins_in(&self, v: &[Stitched]) -> usize {
        v.iter().map(|s| s.ins.stitches_in()).sum()
    }
    /// Stitches worked outside an open repeat, and the repeat's width (`None`: a fixed row).
    fn widths(&self) -> (usize, Option<usize>) {
        let edges = self.ins_in(&self.body.before) + self.ins_in(&self.body.after);
        match &self.body.repeat {
            Some((unit, Until::Times(t))) => (edges + t * self.ins_in(unit), None),
            Some((unit, _)) => (edges, Some(self.ins_in(unit))),
            None => (edges, None),
        }
    }
    /// The row over a piece `n` stitches wide, in working order.
    fn over(&self, n: usize) -> Vec<Instruction> {
        let (edges, repeat) = self.widths();
        let mut out = self.resolve(&self.body.before);
        if let Some((unit, until)) = &self.body.repeat {
            let times = match (until, repeat) {
                (Until::Times(t), _) => *t,
                (_, Some(w)) => (n - edges) / w,
                _ => 0,
            };
            let unit = self.resolve(unit);
            for _ in 0..times {
                out.extend_from_slice(&unit);
            }
        }
        out.extend(self.resolve(&self.body.after));
        out
    }
    fn describe_width(&self) -> String {
        match self.widths() {
            (e, None) => format!("{e} stitches"),
            (0, Some(w)) => format!("a multiple of {w} stitches"),
            (e, Some(w)) => format!("a multiple of {w} stitches plus {e}"),
        }
    }
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
    // (row, is RS) from the first header that says its side.
    let mut side_ref: Option<(usize, bool)> = None;
    let mut explicit: Vec<Option<bool>> = Vec::new();
    let mut defined: Vec<Option<usize>> = Vec::new();
    let mut by_side: [Option<usize>; 2] = [None, None];
    let mut even: Option<usize> = None;
    let mut bodies: Vec<(String, Body)> = Vec::new();
    for (header, body) in &statements {
        let (rows, round, side) = parse_header(header)?;
        in_round |= round;
        let what = header.trim().to_string();
        let parsed = parse_body(body, &what)?;
        let index = bodies.len();
        bodies.push((what.clone(), parsed));
        match rows {
            Rows::AllOfSide(rs) => by_side[usize::from(rs)] = Some(index),
            Rows::AllEven => even = Some(index),
            Rows::Numbers(numbers) => {
                for n in numbers {
                    if n == 0 || n > MAX_KNITSPEAK_ROWS {
                        return Err(KnitError::Pattern(format!(
                            "{what}: row numbers run from 1 to {MAX_KNITSPEAK_ROWS}, not {n}"
                        )));
                    }
                    if defined.len() < n {
                        defined.resize(n, None);
                        explicit.resize(n, None);
                    }
                    defined[n - 1] = Some(index);
                    if let Some(rs) = side {
                        explicit[n - 1] = Some(rs);
                        side_ref.get_or_insert((n, rs));
                    }
                }
            }
        }
    }
    let (ref_row, ref_rs) = side_ref.unwrap_or((1, true));
    let parity_rs = |row: usize| in_round || ((row % 2 == ref_row % 2) == ref_rs);
    let height = defined
        .len()
        .max(if by_side.iter().any(Option::is_some) || even.is_some() {
            2
        } else {
            0
        });
    // "All WS rows" after "Row 7" means row 8 too: the repeat ends on a whole pair of rows.
    let side_of = |row: usize| {
        explicit
            .get(row - 1)
            .copied()
            .flatten()
            .unwrap_or_else(|| parity_rs(row))
    };
    let height = if height % 2 == 1
        && (by_side[usize::from(side_of(height + 1))].is_some() || even.is_some())
    {
        height + 1
    } else {
        height
    };
    let mut plan: Vec<(usize, bool, usize)> = Vec::with_capacity(height);
    for row in 1..=height {
        let rs = side_of(row);
        let index = defined
            .get(row - 1)
            .copied()
            .flatten()
            .or(by_side[usize::from(rs)])
            .or(even.filter(|_| row % 2 == 0))
            .ok_or_else(|| {
                KnitError::Pattern(format!(
                    "row {row} has no instructions (rows 1 to {height} must all be given, or \
                     covered by \"All WS rows\" / \"All RS rows\")"
                ))
            })?;
        plan.push((row, rs, index));
    }
    // Flat knitting with an odd number of rows turns over between repeats (unless the headers
    // say otherwise).
    let alternating = plan.iter().all(|&(row, rs, _)| rs == parity_rs(row));
    if !in_round && height % 2 == 1 && alternating {
        for r in 0..height {
            let (row, rs, index) = plan[r];
            plan.push((row + height, !rs, index));
        }
    }
    let rows: Vec<RowPlan> = plan
        .iter()
        .map(|&(number, right_side, index)| RowPlan {
            number,
            right_side,
            what: &bodies[index].0,
            body: &bodies[index].1,
        })
        .collect();
    lay_out(&rows)
}

/// Lays the rows out on a piece and cuts one repeat (see the module docs).
fn lay_out(rows: &[RowPlan]) -> Result<StitchPattern> {
    for row in rows {
        if let Some((unit, until)) = &row.body.repeat {
            let w = row.ins_in(unit);
            if w == 0 {
                return Err(KnitError::Pattern(format!(
                    "{}: the repeat works no stitches of the row below, so it cannot fill the row",
                    row.what
                )));
            }
            if let Until::Last(n) = until {
                let after = row.ins_in(&row.body.after);
                if after != *n {
                    return Err(KnitError::Pattern(format!(
                        "{}: the repeat runs \"to last {n} sts\" but {after} stitches follow it",
                        row.what
                    )));
                }
            }
        }
    }
    // A row of a fixed width makes the chart a panel.
    if let Some(fixed) = rows.iter().find(|r| r.widths().1.is_none()) {
        let n = fixed.widths().0;
        if n > MAX_KNITSPEAK_WIDTH {
            return Err(KnitError::Pattern(format!(
                "{}: {n} stitches is wider than the {MAX_KNITSPEAK_WIDTH} a chart may be",
                fixed.what
            )));
        }
        let mut written = Vec::with_capacity(rows.len());
        for row in rows {
            let (edges, repeat) = row.widths();
            let fits = match repeat {
                None => edges == n,
                Some(w) => n >= edges && (n - edges) % w == 0,
            };
            if !fits {
                return Err(KnitError::Pattern(format!(
                    "Row {} needs {} but Row {} is {n} stitches wide: the rows do not fit one \
                     piece",
                    row.number,
                    row.describe_width(),
                    fixed.number
                )));
            }
            let instructions = row.over(n);
            if let Some(count) = row.body.count {
                let out: usize = instructions.iter().map(|i| i.stitches_out()).sum();
                if out != count {
                    return Err(KnitError::Pattern(format!(
                        "{}: the row says ({count} sts) but leaves {out} stitches",
                        row.what
                    )));
                }
            }
            written.push(WrittenRow {
                number: row.number,
                right_side: row.right_side,
                instructions,
            });
        }
        return StitchPattern::from_written_rows("knitspeak", &written);
    }

    // All-over: one repeat W wide.
    let mut width = 1usize;
    for row in rows {
        let w = row.widths().1.unwrap_or(1);
        width = lcm(width, w);
        if width > MAX_KNITSPEAK_WIDTH {
            return Err(KnitError::Pattern(format!(
                "the rows' repeats need a chart over {MAX_KNITSPEAK_WIDTH} stitches wide to line \
                 up (Row {} repeats over {w})",
                row.number
            )));
        }
    }
    // The piece width, modulo W: every row's edges plus whole repeats.
    let fits = |n: usize, r: &RowPlan| {
        let (edges, w) = r.widths();
        let w = w.unwrap_or(1);
        n % w == edges % w
    };
    let Some(n0) = (0..width).find(|&n| rows.iter().all(|r| fits(n, r))) else {
        let (a, b) = rows
            .iter()
            .enumerate()
            .flat_map(|(i, a)| rows[i + 1..].iter().map(move |b| (a, b)))
            .find(|(a, b)| !fits_any_with(a, b))
            .unwrap_or((&rows[0], &rows[rows.len() - 1]));
        return Err(KnitError::Pattern(format!(
            "Row {} needs {} but Row {} needs {}: no width fits both",
            a.number,
            a.describe_width(),
            b.number,
            b.describe_width()
        )));
    };
    // Stitch counts per repeat, with the row-balance messages of `rows`.
    let per_repeat: Vec<WrittenRow> = rows
        .iter()
        .map(|r| {
            let unit = r.body.repeat.as_ref().map_or(&[][..], |(u, _)| &u[..]);
            let w = r.ins_in(unit).max(1);
            let unit = r.resolve(unit);
            WrittenRow {
                number: r.number,
                right_side: r.right_side,
                instructions: unit
                    .iter()
                    .copied()
                    .cycle()
                    .take(unit.len() * (width / w))
                    .collect(),
            }
        })
        .collect();
    cells_from_rows(&per_repeat).map_err(|e| match e {
        KnitError::Pattern(m) => {
            KnitError::Pattern(format!("{m} (counted over one {width}-stitch repeat)"))
        }
        other => other,
    })?;

    let max_edges = rows.iter().map(|r| r.widths().0).max().unwrap_or(0);
    let min_n = 2 * max_edges + 4 * width;
    let n = min_n + (n0 + width - min_n % width) % width;
    let written: Vec<WrittenRow> = rows
        .iter()
        .map(|r| WrittenRow {
            number: r.number,
            right_side: r.right_side,
            instructions: r.over(n),
        })
        .collect();
    let cells = cells_from_rows(&written)?;
    // Columns (from the piece's left edge) where each row has an instruction boundary with as
    // many loops worked as stitches made so far.
    let mut clean = vec![true; n + 1];
    for row in &written {
        let mut row_clean = vec![false; n + 1];
        let (mut i, mut o) = (0usize, 0usize);
        row_clean[if row.right_side { n } else { 0 }] = true;
        for ins in &row.instructions {
            i += ins.stitches_in();
            o += ins.stitches_out();
            if i == o && i <= n {
                row_clean[if row.right_side { n - i } else { i }] = true;
            }
        }
        for (c, ok) in clean.iter_mut().zip(row_clean) {
            *c &= ok;
        }
    }
    // Prefer the chart a knitter draws: the first row's repeat starting at the chart's edge
    // where that row starts (the right edge for a RS row).
    let lo = max_edges + width;
    let first = &rows[0];
    let before = first.ins_in(&first.body.before);
    let preferred = if first.right_side {
        lo + (n - before - lo % width) % width
    } else {
        lo + (before + width - lo % width) % width
    };
    let start = std::iter::once(preferred)
        .chain(lo..lo + width)
        .find(|&a| clean[a])
        .unwrap_or(lo);
    let window = cells
        .iter()
        .map(|row| row[start..start + width].to_vec())
        .collect();
    StitchPattern::from_rows("knitspeak", normalised(window, width))
}

/// Whether two rows' repeats can share a piece width.
fn fits_any_with(a: &RowPlan, b: &RowPlan) -> bool {
    let (ea, wa) = a.widths();
    let (eb, wb) = b.widths();
    let (wa, wb) = (wa.unwrap_or(1), wb.unwrap_or(1));
    (0..lcm(wa, wb)).any(|n| n % wa == ea % wa && n % wb == eb % wb)
}

/// Cells whose offsets were measured on a wider piece, with their offsets wrapped the shorter
/// way round a chart `width` wide (as [`cells_from_rows`] writes them).
pub(crate) fn normalised(mut cells: Vec<Vec<Stitch>>, width: usize) -> Vec<Vec<Stitch>> {
    for row in &mut cells {
        for c in row.iter_mut() {
            c.source_offset = wrap(c.source_offset.into(), width);
            c.land_offset = wrap(c.land_offset.into(), width);
        }
    }
    cells
}

/// `d` columns along a row `width` wide that repeats, the shorter way round.
pub(crate) fn wrap(d: i64, width: usize) -> i8 {
    let w = width as i64;
    let mut d = d.rem_euclid(w);
    if d > w / 2 {
        d -= w;
    }
    d as i8
}

/// Whether `text` looks like Knitspeak rather than a symbol chart: it starts with a row header.
pub fn looks_like_knitspeak(text: &str) -> bool {
    let t = text.trim_start().to_lowercase();
    ["row", "rnd", "round", "all "]
        .iter()
        .any(|w| t.starts_with(w))
        && t.contains(':')
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
    ]
    .iter()
    .any(|w| l.starts_with(w))
        && !l.contains(':')
}

/// Splits the text into `(header, body)` statements. A header runs to its `:`; a body runs to
/// the next header (a new line, or a row word after a full stop).
fn statements(text: &str) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = Vec::new();
    for line in text.lines() {
        let mut rest = line.trim();
        while !rest.is_empty() {
            if ignorable(rest) {
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
        let header = ["row", "rnd", "round", "all "]
            .iter()
            .any(|w| next.starts_with(w))
            && next.contains(':');
        if header || ignorable(next) {
            return Some(start);
        }
        from = at;
    }
    None
}

fn parse_header(header: &str) -> Result<(Rows, bool, Option<bool>)> {
    let h = header.trim().to_lowercase();
    let side = if h.contains("(rs)") || h.contains("right side") {
        Some(true)
    } else if h.contains("(ws)") || h.contains("wrong side") {
        Some(false)
    } else {
        None
    };
    if let Some(rest) = h.strip_prefix("all ") {
        let rest = rest.replace('-', " ");
        let rows = if rest.starts_with("rs") || rest.starts_with("right side") {
            Rows::AllOfSide(true)
        } else if rest.starts_with("ws") || rest.starts_with("wrong side") {
            Rows::AllOfSide(false)
        } else if rest.starts_with("even") {
            Rows::AllEven
        } else {
            return Err(bad_header(header));
        };
        return Ok((rows, false, None));
    }
    let (words, round) = if let Some(r) = strip_any(&h, &["rounds", "round", "rnds", "rnd"]) {
        (r, true)
    } else if let Some(r) = strip_any(&h, &["rows", "row"]) {
        (r, false)
    } else {
        return Err(bad_header(header));
    };
    let words = words.split(['(', '[']).next().unwrap_or("");
    let mut numbers = Vec::new();
    for part in words.replace(" and ", ",").replace('&', ",").split(',') {
        let part = part.trim().trim_start_matches("and ").trim();
        if part.is_empty() {
            continue;
        }
        if let Some((a, b)) = part.split_once(['-', '–']) {
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

/// A lexical token of a row body.
#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Sep,
    Star,
    Open(char),
    Close(char),
    Text(String),
}

fn tokens(body: &str) -> Vec<Tok> {
    let mut out = Vec::new();
    let mut text = String::new();
    let flush = |text: &mut String, out: &mut Vec<Tok>| {
        let t = text.trim();
        if !t.is_empty() {
            out.push(Tok::Text(t.to_string()));
        }
        text.clear();
    };
    for ch in body.chars() {
        match ch {
            ',' | ';' | '.' => {
                flush(&mut text, &mut out);
                out.push(Tok::Sep);
            }
            '*' if text.trim_end().to_lowercase().ends_with("from") => text.push(ch),
            '*' => {
                flush(&mut text, &mut out);
                if out.last() != Some(&Tok::Star) {
                    out.push(Tok::Star);
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

/// One element of a body, in the order written.
#[derive(Debug, Clone)]
enum El {
    Stitch(Stitched),
    /// `k to end`, `k to last 3 sts`, `Knit.`: a one-stitch open repeat.
    Fill(Stitched, Until, usize),
    RepStart(usize),
    RepEnd(Until, usize),
    Count(usize),
}

struct BodyParser<'a> {
    toks: Vec<Tok>,
    at: usize,
    what: &'a str,
    /// Instructions read so far (for messages, counted from 1).
    instruction: usize,
    stop: bool,
    /// The body is one phrase (`Knit.`): a bare `k` or `knit` fills the row.
    single: bool,
}

/// `3 times`, `twice`, `once`, `3x` -> the count.
fn times(s: &str) -> Option<usize> {
    let s = s.trim().to_lowercase();
    match s.as_str() {
        "once" => return Some(1),
        "twice" => return Some(2),
        "thrice" | "three times" => return Some(3),
        "four times" => return Some(4),
        _ => {}
    }
    let n = s
        .strip_suffix("times")
        .or_else(|| s.strip_suffix("x"))?
        .trim();
    n.parse().ok().filter(|&n| n >= 1)
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
        .and_then(|(h, n)| Some((h, n.parse::<usize>().ok().filter(|&n| n >= 1)?)))
    {
        return (head.trim().to_string(), n);
    }
    (s.to_string(), 1)
}

/// `to end`, `across`, `to last 3 sts`, `to last st` -> how a repeat ends.
fn until(s: &str) -> Option<Until> {
    let s = s.trim().to_lowercase();
    let s = s.trim_start_matches("and").trim();
    match s {
        "" | "to end" | "to the end" | "across" | "to end of row" | "to end of rnd"
        | "to end of round" | "across row" | "all sts" | "all" => return Some(Until::End),
        "to last st" | "to the last st" | "to last stitch" => return Some(Until::Last(1)),
        _ => {}
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
        return n.trim().parse().ok().map(Until::Last);
    }
    let more = s
        .strip_suffix("more times")
        .or_else(|| s.strip_suffix("times more"))
        .map(|n| n.trim().parse::<usize>().ok());
    match (s, more) {
        ("once more", _) => Some(Until::Times(2)),
        ("twice more", _) => Some(Until::Times(3)),
        (_, Some(Some(n))) => Some(Until::Times(n + 1)),
        _ => None,
    }
}

impl BodyParser<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.at)
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
                Tok::Star => {
                    if depth > 0 {
                        return Err(self.err("*", "a repeat cannot start inside brackets"));
                    }
                    els.push(El::RepStart(self.instruction + 1));
                }
                Tok::Close(c) => {
                    if close.is_some() {
                        return Ok(els);
                    }
                    return Err(self.err(&c.to_string(), "a closing bracket with no opening one"));
                }
                Tok::Open(c) => {
                    let inner = self.list(Some(c), depth + 1)?;
                    // `(18 sts)`: a stitch count.
                    if let [El::Count(n)] = inner.as_slice() {
                        els.push(El::Count(*n));
                        continue;
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

    fn text(&mut self, t: &str, els: &mut Vec<El>, in_brackets: bool) -> Result<()> {
        let lower = t.to_lowercase();
        let lower = lower.trim();
        if in_brackets {
            let count = lower
                .trim_end_matches("stitches")
                .trim_end_matches("sts")
                .trim_end_matches("st")
                .trim();
            if count.len() < lower.len() {
                if let Ok(n) = count.parse() {
                    els.push(El::Count(n));
                    return Ok(());
                }
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
        {
            self.stop = true;
            return Ok(());
        }
        self.instruction += 1;
        if let Some(rest) = lower
            .strip_prefix("rep from *")
            .or_else(|| lower.strip_prefix("repeat from *"))
        {
            let u = until(rest).ok_or_else(|| {
                self.err(
                    t,
                    "expected \"to end\", \"to last N sts\" or \"N more times\"",
                )
            })?;
            els.push(El::RepEnd(u, self.instruction));
            return Ok(());
        }
        // A one-stitch open repeat: `Knit`, `k to end`, `p to last 3 sts`, `knit across`.
        let bare = self.single && matches!(lower, "knit" | "purl" | "k" | "p");
        for (i, _) in lower.match_indices(' ') {
            let (head, tail) = lower.split_at(i);
            if let (Some(u), Some((s, 1))) = (until(tail), parse_stitch(head)) {
                if !tail.trim().is_empty() && s.ins.stitches_in() == 1 {
                    els.push(El::Fill(s, u, self.instruction));
                    return Ok(());
                }
            }
        }
        // `k2tog 3 times`
        let (phrase, n) = split_times(lower);
        let Some((s, count)) = parse_stitch(&phrase) else {
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

/// A row's body (after its header's `:`), in working order.
fn parse_body(body: &str, what: &str) -> Result<Body> {
    let toks = tokens(body);
    let single = toks.iter().filter(|t| !matches!(t, Tok::Sep)).count() == 1;
    let mut p = BodyParser {
        single,
        toks,
        at: 0,
        what,
        instruction: 0,
        stop: false,
    };
    let els = p.list(None, 0)?;
    let mut out = Body {
        before: Vec::new(),
        repeat: None,
        after: Vec::new(),
        count: None,
    };
    // 0: before the repeat, 1: inside it, 2: after it.
    let mut stage = 0;
    let mut unit = Vec::new();
    let mut star_at = 0;
    for el in els {
        match el {
            El::Count(n) => out.count = Some(n),
            El::Stitch(s) => match stage {
                0 => out.before.push(s),
                1 => unit.push(s),
                _ => out.after.push(s),
            },
            El::RepStart(at) => {
                if stage != 0 {
                    return Err(KnitError::Pattern(format!(
                        "{what}, instruction {at}: a second '*' repeat in one row; knitwear \
                         reads one repeat per row"
                    )));
                }
                stage = 1;
                star_at = at;
            }
            El::RepEnd(u, at) => {
                if stage != 1 {
                    return Err(KnitError::Pattern(format!(
                        "{what}, instruction {at} (\"rep from *\"): a repeat with no '*' \
                         before it"
                    )));
                }
                out.repeat = Some((std::mem::take(&mut unit), u));
                stage = 2;
            }
            El::Fill(s, u, at) => {
                if stage != 0 {
                    return Err(KnitError::Pattern(format!(
                        "{what}, instruction {at}: \"{} to end\" inside or after another \
                         repeat",
                        s.ins.name()
                    )));
                }
                out.repeat = Some((vec![s], u));
                stage = 2;
            }
        }
    }
    if stage == 1 {
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

fn unknown(what: &str, instruction: usize, token: &str) -> KnitError {
    let closest = suggest(token);
    KnitError::Pattern(format!(
        "{what}, instruction {instruction}: unknown stitch \"{token}\" (did you mean \
         \"{closest}\"?)"
    ))
}

/// The known stitch closest to `token` (a cross with the same `m/n` for a cross-like token).
pub(crate) fn suggest(token: &str) -> String {
    let lower = token.trim().to_lowercase();
    let mut candidates: Vec<String> = KNOWN.iter().map(|s| s.to_string()).collect();
    if let Some((m, rest)) = lower.split_once('/') {
        let n: String = rest.chars().take_while(char::is_ascii_digit).collect();
        for kind in ["RC", "LC", "RPC", "LPC", "RT", "LT"] {
            candidates.push(format!("{}/{n} {kind}", m.trim()));
        }
    }
    let digits: String = lower.chars().filter(char::is_ascii_digit).collect();
    if !digits.is_empty() && digits.len() <= 3 {
        for base in ["k", "p", "sl"] {
            candidates.push(format!("{base}{digits}"));
        }
    }
    candidates
        .into_iter()
        .min_by_key(|k| edit_distance(&lower, &k.to_lowercase()))
        .unwrap_or_else(|| "k".into())
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

pub(crate) fn lcm(a: usize, b: usize) -> usize {
    let gcd = |mut x: usize, mut y: usize| {
        while y != 0 {
            (x, y) = (y, x % y);
        }
        x
    };
    a / gcd(a, b) * b
}
