//! How much of stitch-maps.com the reader reads (issue 17, item 1): every stitch that the
//! 9,263 patterns counted in `tests/data/stitchmaps/stitch-freqs.csv` use, asked of the
//! reader's vocabulary, and the figures the manual (docs/stitches.md) states recomputed from it.
//!
//! The per-pattern stitch lists behind the counts are not published, so the share of
//! patterns read whole is bounded from below: a pattern the reader cannot read uses at least
//! one stitch it does not know, so at most the sum of those stitches' pattern counts are
//! refused. Every such count includes the patterns of longer names that contain it, which
//! only lowers the bound.

use std::path::Path;

use knitwear::pattern::{reads_stitch, unknitted, Instruction};

/// Patterns counted (the source's `munge.sh` reports 9,263 lines).
const PATTERNS: usize = 9_263;

/// A stitch used by at least this many patterns is one the issue asks the reader to know.
const COMMON: usize = 20;

/// `(munged name, patterns using it)`, most used first.
fn frequencies() -> Vec<(String, usize)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/stitchmaps/stitch-freqs.csv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|line| {
            let (name, count) = line.rsplit_once(',').expect("name,count");
            (name.to_string(), count.trim().parse().expect("a count"))
        })
        .collect()
}

/// The Knitspeak a munged name stands for: `munge.sh` dropped the counts (`k1` is `k`,
/// `sl1 wyif` is `slwyif`), wrote a cable's kind in lower case after a `-`, and `mb` for
/// `MB`; the other names are the Knitspeak with `-` for spaces, which the reader reads as is.
fn knitspeak(munged: &str) -> String {
    match munged {
        "k" => "k1".into(),
        "p" => "p1".into(),
        "slwyif" => "sl1 wyif".into(),
        "slwyib" => "sl1 wyib".into(),
        _ => {
            let cable = munged
                .split_once('-')
                .filter(|(sizes, _)| sizes.contains('/'))
                .map(|(sizes, kind)| format!("{sizes} {}", kind.to_uppercase()));
            cable.unwrap_or_else(|| munged.to_string())
        }
    }
}

/// What the reader makes of every counted stitch: `(name, patterns, instruction)`.
fn read_all() -> Vec<(String, usize, Option<Instruction>)> {
    frequencies()
        .into_iter()
        .map(|(name, count)| {
            let ins = reads_stitch(&knitspeak(&name));
            (name, count, ins)
        })
        .collect()
}

/// The names are read as the stitches they are, not merely accepted.
#[test]
fn stitch_maps_names_read_as_their_stitches() {
    let all = read_all();
    let read = |name: &str| {
        all.iter()
            .find(|(n, _, _)| n == name)
            .unwrap_or_else(|| panic!("{name} is not counted"))
            .2
    };
    use Instruction as I;
    let cross = |m, n, left, purl_back| I::Cross {
        m,
        n,
        left,
        purl_back,
    };
    let centre = |m, c, n, left, purl_centre| I::CentreCross {
        m,
        c,
        n,
        left,
        purl_centre,
    };
    for (name, ins) in [
        ("k", I::Knit),
        ("p", I::Purl),
        ("k-tbl", I::KnitTbl),
        ("p-tbl", I::PurlTbl),
        ("slwyif", I::Slip { yarn_front: true }),
        ("slwyib", I::Slip { yarn_front: false }),
        ("sl1-k2tog-psso", I::Sk2p),
        ("sl2-k1-p2sso", I::Cdd),
        ("mb", I::Bobble),
        ("p3tog", I::P3tog),
        ("sssp", I::Sssp),
        ("k2tog-tbl", I::K2togTbl),
        ("p2tog-tbl", I::P2togTbl),
        ("cddp", I::Cddp),
        ("m1lp", I::MakeOneLeft),
        ("m1rp", I::MakeOneRight),
        ("1/1-rc", cross(1, 1, false, false)),
        ("2/2-lpc", cross(2, 2, true, true)),
        ("2/1-rpc", cross(2, 1, false, true)),
        ("1/1-lt", cross(1, 1, true, false)),
        ("1/1/1-lpc", centre(1, 1, 1, true, true)),
        ("2/1/2-rpc", centre(2, 1, 2, false, true)),
        ("1/2/1-rc", centre(1, 2, 1, false, false)),
        ("3/1/3-lc", centre(3, 1, 3, true, false)),
        ("1/1/1-rpt", centre(1, 1, 1, false, true)),
    ] {
        assert_eq!(read(name), Some(ins), "{name}");
    }
    // `RCC` / `LCC`, centre crosses whose working knitwear does not know, are not read.
    for name in ["kfb", "bo", "turn", "w&t", "brsl", "drop-st", "1/2/1-rcc"] {
        assert_eq!(read(name), None, "{name}");
    }
}

/// The common stitches the reader does not knit because they change a row's stitch count
/// (or work loops across rows: brioche, dropped stitches) are named for what they are, never
/// answered with the nearest knitted stitch ("kfb": "did you mean k?").
#[test]
fn common_stitches_not_knitted_are_explained() {
    let all = read_all();
    let explained = [
        "kfb",
        "bo",
        "co",
        "turn",
        "incl",
        "incr",
        "pfb",
        "ctr-dbl-inc",
        "1-to-5-inc",
        "w&t",
        "brsl",
        "drop-st",
        "3-to-3-gather",
        "dip-st",
        "1-to-7-inc",
        "inclp",
        "1-to-4-inc",
        "pb",
        "p1b",
        "k1b",
    ];
    for name in explained {
        let (_, count, ins) = all
            .iter()
            .find(|(n, _, _)| n == name)
            .unwrap_or_else(|| panic!("{name} is not counted"));
        assert!(*count >= COMMON, "{name}");
        assert_eq!(*ins, None, "{name} is read");
        assert!(
            unknitted(&knitspeak(name)).is_some(),
            "{name} is not explained"
        );
    }
    let unexplained: Vec<&str> = all
        .iter()
        .filter(|(n, c, ins)| *c >= COMMON && ins.is_none() && unknitted(&knitspeak(n)).is_none())
        .map(|(n, _, _)| n.as_str())
        .collect();
    println!(
        "common stitches neither read nor explained: {}",
        unexplained.join(", ")
    );
}

/// The manual's stitch page states what this computes: the common stitches the reader knows, and the
/// lower bound on the patterns it reads whole.
#[test]
fn the_manual_states_the_vocabulary_coverage() {
    let all = read_all();
    let common: Vec<_> = all.iter().filter(|(_, c, _)| *c >= COMMON).collect();
    let known = common.iter().filter(|(_, _, ins)| ins.is_some()).count();
    let refused: usize = all
        .iter()
        .filter(|(_, _, ins)| ins.is_none())
        .map(|(_, c, _)| c)
        .sum();
    let bound = 100.0 * PATTERNS.saturating_sub(refused) as f64 / PATTERNS as f64;
    let missing: Vec<String> = common
        .iter()
        .filter(|(_, _, ins)| ins.is_none())
        .map(|(n, c, _)| format!("{n} ({c})"))
        .collect();
    println!(
        "common stitches read: {known} of {}; missing: {}",
        common.len(),
        missing.join(", ")
    );
    let sentence = format!(
        "reads {known} of the {} stitches that 20 or more of its 9,263 patterns use, and at \
         least {bound:.1}% of those patterns whole",
        common.len()
    );
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/stitches.md"))
            .expect("docs/stitches.md");
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains(&sentence),
        "docs/stitches.md should say that the reader {sentence:?}"
    );
}
