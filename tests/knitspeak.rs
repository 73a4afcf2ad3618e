//! Knitspeak and charts (issue 3, stitch vocabulary): the shared pattern files and every preset
//! read, balance their stitch counts row by row and draw back to themselves; crosses,
//! decreases and wrong-side rows land in the cells `instruction.rs` and `rows.rs` describe;
//! every error names the row, the instruction or column, the token and a suggestion.

use std::path::Path;

use knitwear::pattern::{Face, Form, StitchPattern};
use knitwear::KnitError;

fn data_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/knitspeak")
}

/// A Knitspeak file of the team's shared patterns (copied into tests/data/knitspeak).
fn shared(name: &str) -> String {
    let path = data_dir().join(format!("{name}.ks"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn ks(text: &str) -> StitchPattern {
    StitchPattern::from_knitspeak(text).unwrap_or_else(|e| panic!("{text:?}: {e}"))
}

/// The chart of a pattern, top row first.
fn chart(text: &str) -> String {
    ks(text).chart()
}

fn pattern_error<T: std::fmt::Debug>(result: Result<T, KnitError>) -> String {
    match result {
        Err(KnitError::Pattern(m)) => m,
        other => panic!("not a pattern error: {other:?}"),
    }
}

/// Each text is refused with a pattern error whose message holds its phrase.
fn refused(cases: &[(&str, &str)]) {
    for (text, says) in cases {
        let m = pattern_error(StitchPattern::from_knitspeak(text));
        assert!(m.contains(says), "{text:?}: {m}");
    }
}

/// Each text reads as `expected`, as `same` compares them.
fn all_read_as(
    texts: &[&str],
    expected: &StitchPattern,
    same: fn(&StitchPattern, &StitchPattern) -> bool,
) {
    for text in texts {
        let read = ks(text);
        assert!(same(&read, expected), "{text}:\n{}", read.chart());
    }
}

/// Whether two patterns are the same fabric up to a horizontal shift (a chart may start at
/// any column of the repeat).
fn same_up_to_shift(a: &StitchPattern, b: &StitchPattern) -> bool {
    let (w, h) = (a.width(), a.height());
    (w, h) == (b.width(), b.height())
        && (0..w)
            .any(|s| (0..h).all(|r| (0..w).all(|c| a.stitch(r, c) == b.stitch(r, (c + s) % w))))
}

fn same_cells(a: &StitchPattern, b: &StitchPattern) -> bool {
    a.width() == b.width()
        && a.height() == b.height()
        && (0..a.height()).all(|r| (0..a.width()).all(|c| a.stitch(r, c) == b.stitch(r, c)))
}

/// Stitch-count conservation, a small size, and a chart that reads back to the same cells.
fn check_pattern(name: &str, p: &StitchPattern) {
    for (r, &(worked, made)) in p.stitch_counts().iter().enumerate() {
        assert_eq!(
            (worked, made),
            (p.width(), p.width()),
            "{name}: row {} does not keep its count",
            r + 1
        );
    }
    let drawn = p.chart();
    // A row no chart symbol shows is drawn as its faces, with a note: that is no round trip.
    assert!(!drawn.contains("# rows"), "{name}:\n{drawn}");
    let back = StitchPattern::from_chart(&drawn).unwrap_or_else(|e| panic!("{name}: {e}\n{drawn}"));
    assert!(
        same_cells(p, &back),
        "{name}: the chart does not read back:\n{drawn}"
    );
}

#[test]
fn every_shared_file_reads_balances_and_draws_back() {
    let mut seen = 0;
    for entry in std::fs::read_dir(data_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "ks") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let p = ks(&text);
        check_pattern(&path.display().to_string(), &p);
        seen += 1;
    }
    assert!(seen >= 13, "only {seen} shared files");
}

#[test]
fn the_shared_knit_and_purl_patterns_read_as_their_charts() {
    // Expected charts, drawn as knitters draw them (right side, top row first), up to where
    // the repeat starts.
    let expected = [
        ("stockinette", "k\nk\n"),
        ("garter", "p\nk\n"),
        ("rib-1x1", "kp\nkp\n"),
        ("rib-2x2", "kkpp\nkkpp\n"),
        ("seed", "pk\nkp\n"),
        ("double-moss", "pk\npk\nkp\nkp\n"),
        (
            "basketweave",
            "ppppkkkk\nppppkkkk\nppppkkkk\nppppkkkk\nkkkkpppp\nkkkkpppp\nkkkkpppp\nkkkkpppp\n",
        ),
    ];
    for (name, want) in expected {
        let got = ks(&shared(name));
        let want = StitchPattern::from_chart(want).unwrap();
        assert!(same_up_to_shift(&got, &want), "{name}:\n{}", got.chart());
    }
    // And the preset of the same name is that fabric.
    for (file, preset) in [
        ("rib-2x2", "rib_2x2"),
        ("seed", "seed"),
        ("double-moss", "moss"),
        ("basketweave", "basketweave"),
        ("garter", "garter"),
    ] {
        let p = StitchPattern::preset(preset).unwrap();
        let got = ks(&shared(file));
        let tall = |p: &StitchPattern| {
            let rows: Vec<String> = (0..got.height())
                .rev()
                .map(|r| (0..got.width()).map(|c| p.stitch(r, c).symbol()).collect())
                .collect();
            StitchPattern::from_chart(&rows.join("\n")).unwrap()
        };
        assert!(same_up_to_shift(&got, &tall(&p)), "{file} vs {preset}");
    }
}

#[test]
fn the_shared_cable_lace_and_bobble_patterns_read_as_knitters_chart_them() {
    // Knitspeak and the chart a knitter would draw for it are the same fabric.
    let pairs = [
        (
            "cable-4",
            "pkkkkp\npkkkkp\npkkkkp\npXXXXp\npkkkkp\npkkkkp\nX = 2/2 RC",
        ),
        (
            "horseshoe-cable",
            "ppkkkkkkkkkkkkpp\nppkkkkkkkkkkkkpp\nppkkkkkkkkkkkkpp\nppkkkkkkkkkkkkpp\n\
             ppkkkkkkkkkkkkpp\nppLLLLLLRRRRRRpp\nppkkkkkkkkkkkkpp\nppkkkkkkkkkkkkpp\n\
             R = 3/3 RC\nL = 3/3 LC",
        ),
        ("eyelet-rows", "kk\n/O\nkk\nkk\nkk\nkk"),
        (
            "feather-and-fan",
            "pppppppppppppppppp\n///kOkOkOkOkOkO///\nkkkkkkkkkkkkkkkkkk\nkkkkkkkkkkkkkkkkkk",
        ),
        ("bobbles", "kkkkkk\nkkBkkk\nkkkkkk\nkkkkkk"),
        ("twisted-rib", "Qp\nQp"),
    ];
    for (name, drawn) in pairs {
        let got = ks(&shared(name));
        let want = StitchPattern::from_chart(drawn).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            same_up_to_shift(&got, &want),
            "{name}: got\n{}\nwant\n{}",
            got.chart(),
            want.chart()
        );
    }
}

#[test]
fn presets_are_named_small_balanced_and_draw_back() {
    let names = StitchPattern::presets();
    assert!(names.len() >= 20, "{names:?}");
    for required in [
        "stockinette",
        "reverse_stockinette",
        "garter",
        "rib_1x1",
        "rib_2x2",
        "seed",
        "moss",
        "basketweave",
        "cable_c4",
        "cable_c6",
        "horseshoe_cable",
        "honeycomb_cable",
        "diamond",
        "chevron",
        "feather_and_fan",
        "eyelet_rows",
        "twisted_rib",
        "bobbles",
        "fair_isle",
    ] {
        assert!(names.contains(&required), "{required}");
    }
    for name in names {
        let p = StitchPattern::preset(name).unwrap();
        assert_eq!(p.name(), name);
        assert!(
            p.width() <= 24 && p.height() <= 24,
            "{name}: {}x{}",
            p.width(),
            p.height()
        );
        check_pattern(name, &p);
    }
    // The original knit/purl presets are unchanged, cell for cell.
    for (name, drawn) in [
        ("stockinette", "k\n"),
        ("garter", "p\nk\n"),
        ("rib_2x2", "kkpp\n"),
        ("moss", "pk\npk\nkp\nkp\n"),
    ] {
        assert_eq!(StitchPattern::preset(name).unwrap().chart(), drawn);
    }
    assert!(StitchPattern::preset("Horseshoe Cable").is_ok());
}

#[test]
fn a_cross_lands_its_loops_as_instruction_rs_says() {
    // 2/2 RC in the middle of a panel: the two left loops of the row below travel two
    // columns right, in front; the two right loops two columns left, behind.
    let p = ks("Row 1 (RS): p2, 2/2 RC, p2.\nRow 2: k2, p4, k2.");
    assert_eq!(p.width(), 8);
    let offsets: Vec<i8> = (2..6).map(|c| p.stitch(0, c).source_offset).collect();
    assert_eq!(offsets, [2, 2, -2, -2]);
    // Row 2 is below row 1 in the repeat: its loops land in the cross.
    let lands: Vec<(i8, i8)> = (2..6)
        .map(|c| (p.stitch(1, c).land_offset, p.stitch(1, c).land_layer))
        .collect();
    assert_eq!(lands, [(2, 1), (2, 1), (-2, -1), (-2, -1)]);
    assert!((2..6).all(|c| p.stitch(0, c).face == Face::Knit));

    // 2/2 LC: the right loops travel left in front.
    let p = ks("Row 1 (RS): p2, C4F, p2.\nRow 2: k2, p4, k2.");
    let lands: Vec<(i8, i8)> = (2..6)
        .map(|c| (p.stitch(1, c).land_offset, p.stitch(1, c).land_layer))
        .collect();
    assert_eq!(lands, [(2, -1), (2, -1), (-2, 1), (-2, 1)]);

    // 2/1 RPC (T3B): the stitch that passes behind is purled and shows as a purl bump.
    let p = ks("Row 1 (RS): p2, T3B, p2.\nRow 2: k2, p1, k4.");
    let faces: Vec<Face> = (2..5).map(|c| p.stitch(0, c).face).collect();
    assert_eq!(faces, [Face::Purl, Face::Knit, Face::Knit]);

    // Aliases name the same crosses.
    for (a, b) in [
        ("C4B", "2/2 RC"),
        ("C6F", "3/3 LC"),
        ("T2B", "1/1 RT"),
        ("T4F", "2/2 LPC"),
        ("RT", "1/1 rt"),
    ] {
        let row = |c: &str| format!("Rnd 1: p2, {c}, p2.");
        let (pa, pb) = (ks(&row(a)), ks(&row(b)));
        assert!(same_cells(&pa, &pb), "{a} vs {b}");
    }
}

#[test]
fn decreases_yarn_overs_and_slips_make_their_cells() {
    // k2tog worked right to left: one stitch through two loops, the left one on top.
    let p = ks("Rnd 1: k1, k2tog, yo, k1.");
    assert_eq!(p.width(), 4);
    // Columns left to right as seen from the front: k1 (last worked), yo, k2tog, k1 (first).
    // Read: the first instruction sits at the right edge.
    let forms: Vec<Form> = (0..4).map(|c| p.stitch(0, c).form).collect();
    assert_eq!(
        forms,
        [Form::Plain, Form::YarnOver, Form::Plain, Form::Plain]
    );
    assert_eq!(p.stitch(0, 2).sources, 2);
    assert_eq!(p.stitch(0, 1).sources, 0);
    // A slip without a yarn side holds the yarn on the wrong side: in back on a RS row, in
    // front on a WS row, which is behind the fabric either way.
    let p = ks("Row 1 (RS): k1, sl1.\nRow 2: sl1, p1.");
    assert_eq!(p.stitch(0, 0).form, Form::Slip { yarn_front: false });
    assert_eq!(p.stitch(1, 0).form, Form::Slip { yarn_front: false });
    assert_eq!(
        ks("Row 1 (RS): k1, sl1 wyif.\nRow 2: p2.")
            .stitch(0, 0)
            .form,
        Form::Slip { yarn_front: true }
    );
}

/// `p3tog` and `sssp` (issue 17's vocabulary, 221 and 22 stitch-maps patterns): `k3tog` and
/// `sssk` purled, one stitch through three loops leaning the same ways; worked from the wrong
/// side, `k3tog` and `sssk` show as them from the front, and charts draw and read them back.
#[test]
fn purled_double_decreases_gather_three_loops_and_chart() {
    let p = ks("Row 1 (RS): k1, yo, p3tog, yo, k1, yo, sssp, yo, k1.\nRow 2 (WS): Purl.");
    check_pattern("purled double decreases", &p);
    let k = ks("Row 1 (RS): k1, yo, k3tog, yo, k1, yo, sssk, yo, k1.\nRow 2 (WS): Purl.");
    // Columns left to right from the front: k1, yo, sssp, yo, k1, yo, p3tog, yo, k1.
    for (col, lean) in [(2, "sssp"), (6, "p3tog")] {
        let (purled, knit) = (p.stitch(0, col), k.stitch(0, col));
        assert_eq!(purled.face, Face::Purl, "{lean}");
        assert_eq!(purled.sources, 3, "{lean}");
        // The same gather as its knit twin, loop for loop, only purled.
        assert_eq!(
            (purled.sources, purled.form),
            (knit.sources, knit.form),
            "{lean}"
        );
        for c in 0..p.width() {
            assert_eq!(
                p.stitch(1, c),
                k.stitch(1, c),
                "{lean}: the loops below land alike"
            );
        }
    }
    // A k3tog and an sssk worked from the wrong side are these, seen from the front (the
    // row worked from the left edge).
    let ws = ks("Row 1 (RS): Knit.\nRow 2 (WS): p1, yo, k3tog, yo, p1, yo, sssk, yo, p1.");
    let front = ks("Row 1 (RS): Knit.\nRow 2 (RS): k1, yo, sssp, yo, k1, yo, p3tog, yo, k1.");
    assert!(same_cells(&ws, &front), "{}\n{}", ws.chart(), front.chart());
    check_pattern("double decreases from the wrong side", &ws);
    assert!(ws.chart().contains("p3tog"), "{}", ws.chart());
    assert!(ws.chart().contains("sssp"), "{}", ws.chart());
}

/// `k2tog tbl`, `p2tog tbl` and `cddp` (issue 17's vocabulary, 145, 124 and 62 stitch-maps
/// patterns): `ssk`, `ssp` and `cdd` with the stitch twisted or purled; from the wrong side
/// a `k2tog tbl` shows as a `p2tog tbl`, and charts draw and read them all back.
#[test]
fn twisted_decreases_and_the_purled_centred_decrease_chart() {
    let p =
        ks("Row 1 (RS): k1, yo, k2tog tbl, p1, yo, p2tog tbl, yo, cddp, yo.\nRow 2 (WS): Purl.");
    check_pattern("twisted and purled decreases", &p);
    let twin = ks("Row 1 (RS): k1, yo, ssk, p1, yo, ssp, yo, cdd, yo.\nRow 2 (WS): Purl.");
    // Columns left to right from the front: yo, cddp, yo, p2tog tbl, yo, p1, k2tog tbl, yo,
    // k1; each decrease gathers its loops as its twin does.
    for (col, face, form) in [
        (1, Face::Purl, Form::Plain),
        (3, Face::Purl, Form::Twisted),
        (6, Face::Knit, Form::Twisted),
    ] {
        let (ours, theirs) = (p.stitch(0, col), twin.stitch(0, col));
        assert_eq!((ours.face, ours.form), (face, form), "column {col}");
        assert_eq!(ours.sources, theirs.sources, "column {col}");
    }
    for c in 0..p.width() {
        assert_eq!(
            p.stitch(1, c),
            twin.stitch(1, c),
            "the loops below land alike"
        );
    }
    let ws = ks("Row 1 (RS): Knit.\nRow 2 (WS): p1, k2tog tbl, yo, p1.");
    let front = ks("Row 1 (RS): Knit.\nRow 2 (RS): k1, yo, p2tog tbl, k1.");
    assert!(same_cells(&ws, &front), "{}\n{}", ws.chart(), front.chart());
    check_pattern("a twisted decrease from the wrong side", &ws);

    // k3tog tbl (60 stitch-maps patterns) gathers three loops as sssk does, twisted; worked
    // from the wrong side it shows as p3tog tbl.
    let p = ks("Row 1 (RS): k1, yo, k3tog tbl, yo, p1, yo, p3tog tbl, yo.\nRow 2 (WS): Purl.");
    check_pattern("three-loop twisted decreases", &p);
    let twin = ks("Row 1 (RS): k1, yo, sssk, yo, p1, yo, sssp, yo.\nRow 2 (WS): Purl.");
    for (col, face) in [(1, Face::Purl), (5, Face::Knit)] {
        let (ours, theirs) = (p.stitch(0, col), twin.stitch(0, col));
        assert_eq!(
            (ours.face, ours.form),
            (face, Form::Twisted),
            "column {col}"
        );
        assert_eq!(
            (ours.sources, ours.source_offset),
            (3, theirs.source_offset)
        );
    }
    for c in 0..p.width() {
        assert_eq!(
            p.stitch(1, c),
            twin.stitch(1, c),
            "the loops below land alike"
        );
    }
    let ws = ks("Row 1 (RS): Knit.\nRow 2 (WS): p1, yo, k3tog tbl, yo, p1.");
    let front = ks("Row 1 (RS): Knit.\nRow 2 (RS): k1, yo, p3tog tbl, yo, k1.");
    assert!(same_cells(&ws, &front), "{}\n{}", ws.chart(), front.chart());
}

/// `m1lp` and `m1rp` (issue 17's vocabulary, 63 and 43 stitch-maps patterns): worked
/// purlwise, a made stitch is the same new loop as `m1l` and `m1r` (it has no loop below to be
/// pulled through to one side; the next row works it), as a `m1l` worked from the wrong side
/// is.
#[test]
fn purled_made_stitches_are_the_same_new_loops() {
    let p = ks("Row 1 (RS): p1, m1lp, p2tog, m1rp, p2tog.\nRow 2 (WS): Knit.");
    let k = ks("Row 1 (RS): p1, m1l, p2tog, m1r, p2tog.\nRow 2 (WS): Knit.");
    assert!(same_cells(&p, &k), "{}\n{}", p.chart(), k.chart());
    check_pattern("purled made stitches", &p);
    let ws = ks("Row 1 (RS): Knit.\nRow 2 (WS): p1, m1l, p2tog.");
    let front = ks("Row 1 (RS): Knit.\nRow 2 (RS): k2tog, m1lp, k1.");
    assert!(same_cells(&ws, &front), "{}\n{}", ws.chart(), front.chart());
}

/// `k4tog`, `k5tog`, `p4tog`, `p5tog` (issue 17's vocabulary, 76, 109, 7 and 37 stitch-maps
/// patterns): one stitch through four or five loops, leaning right as `k3tog` does; worked
/// from the wrong side a `k5tog` shows as a `p5tog`, and charts draw and read them back.
#[test]
fn four_and_five_loop_decreases_gather_and_chart() {
    let p = ks("Row 1 (RS): k1, yo, yo, k4tog, yo, yo, yo, p5tog, yo, yo, k1.\nRow 2 (WS): Purl.");
    check_pattern("four and five loop decreases", &p);
    // Columns left to right from the front: k1, yo, yo, p5tog, yo, yo, yo, k4tog, yo, yo, k1.
    for (col, face, sources) in [(3, Face::Purl, 5), (7, Face::Knit, 4)] {
        let s = p.stitch(0, col);
        assert_eq!((s.face, s.sources), (face, sources), "column {col}");
    }
    let ws = ks("Row 1 (RS): Knit.\nRow 2 (WS): p1, yo, yo, k5tog, yo, yo, p1.");
    let front = ks("Row 1 (RS): Knit.\nRow 2 (RS): k1, yo, yo, p5tog, yo, yo, k1.");
    assert!(same_cells(&ws, &front), "{}\n{}", ws.chart(), front.chart());
    check_pattern("a five loop decrease from the wrong side", &ws);
}

#[test]
fn wrong_side_rows_are_mirrored() {
    // Row 1 starts at the right edge; row 2 (WS) at the left edge, its knits show as purls.
    assert_eq!(chart("Row 1 (RS): k1, p3.\nRow 2: k1, p3."), "pkkk\npppk\n");
    // A WS p2tog shows as a k2tog on the front, a WS ssp as an ssk.
    let ws = ks("Row 1 (RS): Knit.\nRow 2 (WS): p1, p2tog, yo, ssp, yo, p1.");
    let drawn = ws.chart();
    assert!(drawn.starts_with("k/O\\Ok\n"), "{drawn}");
    // A first row on the wrong side turns the parity round.
    assert_eq!(chart("Row 1 (WS): Knit.\nRow 2: Knit."), "k\np\n");
    // Flat knitting with an odd number of rows turns over between repeats: seed stitch over
    // an odd count, one row repeated.
    let seed = ks("Row 1 (RS): *K1, p1; rep from * to last st, k1.\nRepeat row 1.");
    assert_eq!(seed.height(), 2);
    assert!(same_up_to_shift(
        &seed,
        &StitchPattern::preset("seed").unwrap()
    ));
}

#[test]
fn repeats_groups_counts_and_spelling() {
    // Brackets, parentheses and "N times" expand in place.
    let a = ks("Rnd 1: [k1, p1] 3 times, k2, p4.");
    let b = ks("Rnd 1: k1, p1, k1, p1, k1, p1, k2, p4.");
    assert!(same_cells(&a, &b));
    assert!(same_cells(
        &ks("Rnd 1: (k1, p1) twice, p2tog 2 times, yo twice."),
        &ks("Rnd 1: k1, p1, k1, p1, p2tog, p2tog, yo, yo.")
    ));
    // Case, spaces and long forms.
    for text in [
        "Rnd 1: *K2, P2; rep from *.",
        "rnd 1: *knit 2, purl 2, rep from * to end",
        "RND 1: *k 2; p 2; repeat from * across.",
        "Rnd 1: k2, p2.",
    ] {
        // The first stitch of a row sits at the right edge of its chart.
        assert_eq!(chart(text), "ppkk\n", "{text}");
    }
    // "to last N sts" with stitches before and after the repeat: a multiple of 4 plus 6.
    let p = ks("Rnd 1: p2, k1, *k2, p2; rep from * to last 3 sts, k1, p2.\nRnd 2: Knit.");
    assert_eq!(p.width(), 4);
    // Stitch counts in parentheses are checked on a panel.
    assert!(StitchPattern::from_knitspeak(
        "Row 1 (RS): p2, k12, p2. (16 sts)\nRow 2: k2, p12, k2."
    )
    .is_ok());
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): p2, k12, p2 (18 sts).\nRow 2: k2, p12, k2.",
    ));
    assert!(m.contains("18 sts") && m.contains("16"), "{m}");
    // Issue 17: a title line in parentheses before the first row is skipped (a chart is
    // still told from Knitspeak by its first row).
    let titled = "(Seed stitch)\nRow 1 (RS): *k1, p1; rep from *.\nRow 2: *p1, k1; rep from *.";
    assert!(knitwear::pattern::looks_like_knitspeak(titled));
    assert_eq!(
        chart(titled),
        chart("Row 1 (RS): *k1, p1; rep from *.\nRow 2: *p1, k1; rep from *.")
    );
    // Issue 17, the dialect: a row that says to work another row again is that row's
    // instructions, worked on its own side (here moss stitch, rows 3 and 4 as rows 2 and 1).
    let moss = "Row 1 (RS): *K1, p1; rep from * to end.\nRow 2: *K1, p1; rep from * to end.\n\
                Row 3: *P1, k1; rep from * to end.\nRow 4: *P1, k1; rep from * to end.";
    assert_eq!(
        chart(
            "Row 1 (RS): *K1, p1; rep from * to end.\nRow 2: Rep row 1.\n\
             Row 3: *P1, k1; rep from * to end.\nRow 4: Work as row 3."
        ),
        chart(moss)
    );
    // A chain of them reads through; one naming a row not given, or coming back round to
    // itself, is an error that says so.
    assert_eq!(
        chart("Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: Same as row 1.\nRow 4: Rep row 2."),
        chart("Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: Knit.\nRow 4: Purl.")
    );
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): Knit.\nRow 2: Rep row 5.",
    ));
    assert!(m.contains("Row 2") && m.contains("row 5"), "{m}");
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): Knit.\nRow 2: Rep row 3.\nRow 3: Rep row 2.\nRow 4: Purl.",
    ));
    assert!(m.contains("come back to it"), "{m}");
    // Ranges repeat row by row, and "last N rows" counts back from the statement's first
    // row; a row given by "All WS rows" can be named too.
    let written = "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.\n\
                   Row 3: *P2, k2; rep from *.\nRow 4: *P2, k2; rep from *.";
    let long = chart(&format!(
        "{written}\nRow 5: *K2, p2; rep from *.\nRow 6: *K2, p2; rep from *.\n\
         Row 7: *P2, k2; rep from *.\nRow 8: *P2, k2; rep from *."
    ));
    assert_eq!(chart(&format!("{written}\nRows 5-8: Rep rows 1-4.")), long);
    assert_eq!(
        chart(&format!("{written}\nRows 5-8: Repeat last 4 rows.")),
        long
    );
    assert_eq!(
        chart("Row 1 (RS): K1, *p1, k1; rep from *.\nRow 2: Rep last row."),
        chart("Row 1 (RS): K1, *p1, k1; rep from *.\nRow 2: K1, *p1, k1; rep from *.")
    );
    assert_eq!(
        chart(
            "Row 1 (RS): Knit.\nAll WS rows: Purl.\nRow 3: *K1, p1; rep from *.\nRow 5: Rep row 2."
        ),
        chart("Row 1 (RS): Knit.\nAll WS rows: Purl.\nRow 3: *K1, p1; rep from *.\nRow 5: Purl.")
    );
    refused(&[
        (
            "Row 1 (RS): Knit.\nRow 2: Rep last 2 rows.",
            "only 1 row comes before row 2",
        ),
        (
            "Row 1 (RS): Knit.\nRow 2: Purl.\nRows 3-5: Rep rows 1-2.",
            "is 3 rows but repeats 2",
        ),
    ]);
    // "K the knit sts and p the purl sts" keeps each column's face from the row below: a
    // rib, a cable's wrong-side row, a round, rows of it stacked; a yarn-over and a decrease
    // below show as knits, so they are purled from the wrong side.
    for (appearing, written) in [
        (
            "Row 1 (RS): *K2, p2; rep from *.\nRow 2: K the knit sts and p the purl sts.",
            "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.",
        ),
        (
            "Row 1 (RS): P2, *2/2 RC, p2; rep from *.\nRow 2: Knit the knits and purl the purls.",
            "Row 1 (RS): P2, *2/2 RC, p2; rep from *.\nRow 2: K2, *p4, k2; rep from *.",
        ),
        (
            "Rnd 1: *K1, p1; rep from *.\nRnd 2: Work sts as they appear.",
            "Rnd 1: *K1, p1; rep from *.\nRnd 2: *K1, p1; rep from *.",
        ),
        (
            "Row 1 (RS): K1, *p1, k1; rep from *.\nRow 2: Work sts as they appear.\n\
             Row 3: Work sts as they appear.\nRow 4: Work sts as they appear.",
            "Row 1 (RS): K1, *p1, k1; rep from *.\nRow 2: P1, *k1, p1; rep from *.\n\
             Row 3: K1, *p1, k1; rep from *.\nRow 4: P1, *k1, p1; rep from *.",
        ),
        (
            "Row 1 (RS): *K2tog, yo; rep from *.\nRow 2: Work sts as they appear.",
            "Row 1 (RS): *K2tog, yo; rep from *.\nRow 2: Purl.",
        ),
    ] {
        let (a, b) = (ks(appearing), ks(written));
        assert!(
            same_cells(&a, &b),
            "{appearing:?}\n{}\n{}",
            a.chart(),
            b.chart()
        );
    }
    refused(&[(
        "Row 1: Work sts as they appear.\nRow 2: K the knit sts and p the purl sts.",
        "give at least one row's stitches",
    )]);
    // In the round, "around" ends a repeat or a run as "to end" does.
    assert_eq!(
        chart("Rnd 1: *K2, p2; rep from * around.\nRnd 2: Knit around.\nRnd 3: K around."),
        chart("Rnd 1: *K2, p2; rep from * to end.\nRnd 2: Knit.\nRnd 3: Knit.")
    );
    // Each row is given once: a second "Row 1" is an error, not the one that wins.
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): Knit.\nRow 1: Purl.\nRow 2: Purl.",
    ));
    assert!(m.contains("row 1 is given twice"), "{m}");
    // "Repeat rows" that repeats every row is what the chart does; one that leaves set-up
    // rows out is an error that says so, as is one naming a row not given or saying more
    // than the reader understands.
    let four = "Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: *k1, p1; rep from *.\nRow 4: *k1, p1; rep from *.\n";
    for ok in [
        "Repeat rows 1-4.",
        "Rep rows 1-4 for pattern.",
        "Repeat rows 1 through 4.",
    ] {
        assert!(
            StitchPattern::from_knitspeak(&format!("{four}{ok}")).is_ok(),
            "{ok}"
        );
    }
    let m = pattern_error(StitchPattern::from_knitspeak(&format!(
        "{four}Repeat rows 3-4."
    )));
    assert!(
        m.contains("knitted once") && m.contains("rows 3 to 4 alone"),
        "{m}"
    );
    let m = pattern_error(StitchPattern::from_knitspeak(&format!(
        "{four}Repeat rows 1-6."
    )));
    assert!(m.contains("row 6 is not given"), "{m}");
    let m = pattern_error(StitchPattern::from_knitspeak(&format!(
        "{four}Repeat rows 1-4 and blah blah."
    )));
    assert!(
        m.contains("cannot read \"blah blah\"") || m.contains("and blah blah"),
        "{m}"
    );
    // "Repeat rows 1-4" and "Multiple of" lines are accepted.
    assert!(StitchPattern::from_knitspeak(
        "Multiple of 4 sts.\nRow 1 (RS): *k2, p2; rep from *.\nRow 2: *k2, p2; rep from *.\nRepeat rows 1 and 2."
    )
    .is_ok());
    // Every stitch of the vocabulary reads.
    for stitch in [
        "k1 tbl",
        "k1-tbl",
        "p tbl",
        "sl1",
        "sl 1 pwise wyif",
        "sl1 wyib",
        "m1",
        "m1l",
        "m1r",
        "sl1-k2tog-psso",
        "sk2p",
        "s2kp",
        "sl2-k1-p2sso",
        "cdd",
        "k3tog",
        "sssk",
        "p2tog",
        "ssp",
        "p3tog",
        "sssp",
        "k2tog tbl",
        "p2tog tbl",
        "cddp",
        "m1lp",
        "m1rp",
        "k4tog",
        "p5tog",
        "MB",
        "1/1 LPT",
        "2/1 LPC",
        "6/6 RC",
    ] {
        let p = StitchPattern::from_knitspeak(&format!("Rnd 1: {stitch}, k1."));
        if let Err(e) = &p {
            // Increases and decreases alone do not balance; only that may fail.
            let e = e.to_string();
            assert!(
                e.contains("turns") || e.contains("balance"),
                "{stitch}: {e}"
            );
        }
    }
}

/// Two open-ended runs in one row (issue 17's dialect): a run after one that stopped `to last
/// N sts` works what that one left, less what is worked between and what it leaves in turn,
/// so each row reads as the row written with that count. A run after one that left nothing
/// (`to end`, or as much as it leaves itself) is still refused.
#[test]
fn a_run_after_one_that_stops_short_works_what_it_left() {
    for (open, explicit) in [
        (
            "Row 1 (RS): *k2, p2; rep from * to last 2 sts, k to end.",
            "Row 1 (RS): *k2, p2; rep from * to last 2 sts, k2.",
        ),
        (
            "Row 1 (RS): p1, *k2, p2; rep from * to last 3 sts, k2, p to end.",
            "Row 1 (RS): p1, *k2, p2; rep from * to last 3 sts, k2, p1.",
        ),
        (
            "Row 1 (RS): *k1, p1; rep from * to last 3 sts, k to last st, p1.",
            "Row 1 (RS): *k1, p1; rep from * to last 3 sts, k2, p1.",
        ),
    ] {
        let rows = "\nRow 2: Purl.";
        let (a, b) = (
            ks(&format!("{open}{rows}")),
            ks(&format!("{explicit}{rows}")),
        );
        assert!(same_cells(&a, &b), "{open}\n{}\n{}", a.chart(), b.chart());
        assert_eq!(a.stitch_counts(), b.stitch_counts(), "{open}");
    }
    refused(&[
        (
            "Row 1 (RS): k to end, p to end.",
            "\"p to end\" inside or after another repeat",
        ),
        (
            "Row 1 (RS): k to last 2 sts, p to last 2 sts.",
            "\"p to last 2 sts\" inside or after another repeat",
        ),
    ]);
}

#[test]
fn counts_notes_words_and_numbering_as_patterns_write_them() {
    // Issue 17, bug 2: a stated count after a whole-row phrase is no stitch: `Purl (6 sts)`
    // purls the row, and 6 is a width the piece can have.
    assert_eq!(
        chart("Row 1 (RS): Knit.\nRow 2: Purl (6 sts)."),
        chart("Row 1 (RS): Knit.\nRow 2: Purl.")
    );
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): *k2, p2; rep from *.\nRow 2: Purl (6 sts).",
    ));
    assert!(
        m.contains("(6 sts)") && m.contains("Row 1 needs a multiple of 4"),
        "{m}"
    );
    // A stated count on an all-over row is checked against the piece it describes.
    let rib = "Row 2 (WS): p2, *k2, p2; rep from *.";
    assert!(StitchPattern::from_knitspeak(&format!(
        "Row 1 (RS): k2, *p2, k2; rep from * (14 sts).\n{rib}"
    ))
    .is_ok());
    let m = pattern_error(StitchPattern::from_knitspeak(&format!(
        "Row 1 (RS): k2, *p2, k2; rep from * (15 sts).\n{rib}"
    )));
    assert!(m.contains("(15 sts)") && m.contains("plus 2"), "{m}");
    // A width note in brackets is a note, not an unclosed bracket or a stitch.
    for note in ["(multiple of 2 sts, plus 2)", "(a multiple of 2 sts + 2)"] {
        assert_eq!(
            chart(&format!(
                "Row 1 (RS): *k1, p1; rep from * {note}.\nRow 2: Purl."
            )),
            chart("Row 1 (RS): *k1, p1; rep from *.\nRow 2: Purl."),
            "{note}"
        );
    }
    // Counts as words, wherever a count is written: after a stitch's name too.
    assert_eq!(
        chart("Row 1: knit two, purl three, k one tbl, slip one wyif.\nRow 2: Purl."),
        chart("Row 1: k2, p3, k1 tbl, sl1 wyif.\nRow 2: Purl.")
    );
    assert_eq!(
        chart("Rnd 1: [k1, p1] two times, k2tog three times, yo three times, p2."),
        chart("Rnd 1: [k1, p1] 2 times, k2tog 3 times, yo 3 times, p2.")
    );
    assert_eq!(
        chart("Rnd 1: *k2, p2; rep from * to last two sts, k2.\nRnd 2: Knit (six sts)."),
        chart("Rnd 1: *k2, p2; rep from * to last 2 sts, k2.\nRnd 2: Knit (6 sts).")
    );
    assert_eq!(
        chart("Rnd 1: *k2, p1; rep from * two more times."),
        chart("Rnd 1: k2, p1, k2, p1, k2, p1.")
    );
    // Bug 8: `p0` is a count of nothing, not a stitch to suggest.
    let m = pattern_error(StitchPattern::from_knitspeak("Row 1: k2, p0, k2."));
    assert!(m.contains("\"p0\" works no stitches"), "{m}");
    // ... and a run that stops short is named as written, not as "to end".
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1: *k1, p1; rep from *, purl to last st, k1.",
    ));
    assert!(m.contains("\"p to last st\" inside or after"), "{m}");
    // Rows copied from the middle of a text keep their numbers: the repeat is the rows
    // given, from the lowest, and its sides follow the numbers (odd rows RS).
    let p = ks("Row 3 (RS): *k1, p1; rep from *.\nRow 4: *k1, p1; rep from *.");
    assert_eq!(p.height(), 2);
    assert!(same_cells(
        &p,
        &ks("Row 1 (RS): *k1, p1; rep from *.\nRow 2: *k1, p1; rep from *.")
    ));
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 3 (RS): Knit.\nRow 5: Knit.",
    ));
    assert!(m.contains("row 4 has no instructions (rows 3 to 5"), "{m}");
    assert!(
        StitchPattern::from_knitspeak("Row 3 (RS): Knit.\nRow 4: Purl.\nRepeat rows 3 and 4.")
            .is_ok()
    );
}

#[test]
fn a_cable_worked_from_the_wrong_side_charts_and_reads_back() {
    // Issue 17, bug 6: the yo and p2tog beside a WS cable came back as knits and purls.
    let p = ks("Row 1 (RS): K2, p6, k2.\nRow 2 (WS): P2, 2/2 RC, yo, k2tog, p2.");
    check_pattern("WS cable", &p);
    let drawn = p.chart();
    assert!(
        drawn.contains("= 2/2 RC (WS)") && drawn.contains("= yo"),
        "{drawn}"
    );
    // Every cross, knit or purl, worked from the wrong side.
    for cross in ["2/1 RC", "1/2 LC", "3/3 LC", "2/2 RPC", "1/3 LPC"] {
        let (m, n) = cross.split_once(' ').unwrap().0.split_once('/').unwrap();
        let w: usize = m.parse::<usize>().unwrap() + n.parse::<usize>().unwrap();
        let p = ks(&format!(
            "Row 1 (RS): p2, k{w}, p2.\nRow 2 (WS): k2, {cross}, k2."
        ));
        check_pattern(cross, &p);
    }
}

#[test]
fn edge_shaping_is_refused_never_dropped() {
    // Issue 17, bug 3: the decrease and increase outside the repeat shape the piece's edges;
    // the chart is cut from the middle of the piece, so they would be dropped without a word.
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): ssk, k to last st, m1r, k1.\nRow 2: Purl.",
    ));
    assert!(
        m.contains("Row 1 (RS)")
            && m.contains("\"ssk\"")
            && m.contains("\"m1r\"")
            && m.contains("edge shaping"),
        "{m}"
    );
    // Edge stitches that keep the count (a selvedge) are still left out, as before.
    assert_eq!(
        chart("Row 1 (RS): sl1, *k1, p1; rep from * to last st, k1.\nRow 2: Purl."),
        chart("Row 1 (RS): *k1, p1; rep from *.\nRow 2: Purl.")
    );
    // A panel keeps its edges, shaping included: its count is checked as a whole.
    assert!(StitchPattern::from_knitspeak("Row 1 (RS): ssk, k3, yo, k1.\nRow 2: Purl.").is_ok());
    // Lace that ends a row on part of its repeat balances the yo's and decreases there: that
    // shapes nothing (it was refused as edge shaping; arrowhead and herringbone lace of the
    // corpus, tests/data/corpus, end rows so).
    let part = "Row 1 (RS): K2, *yo, sk2p, yo, k3; rep from * to last 5 sts, yo, sk2p, yo, k2.\n\
                Row 2: Purl.";
    let whole = "Row 1 (RS): *yo, sk2p, yo, k3; rep from *.\nRow 2: Purl.";
    assert!(same_up_to_shift(&ks(part), &ks(whole)), "{}", chart(part));
    // One edge balanced and the other not is still edge shaping.
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): yo, ssk, *k1, p1; rep from * to last 2 sts, k2tog.\nRow 2: Purl.",
    ));
    assert!(m.contains("\"k2tog\"") && m.contains("edge shaping"), "{m}");
    assert!(
        !m.contains("\"ssk\""),
        "the balanced edge is not named: {m}"
    );
}

#[test]
fn phases_of_repeats_line_up_from_the_piece_edges() {
    // Bobbles: a multiple of 6 plus 5; row 3's bobbles and row 7's are three columns apart
    // however the chart is cut.
    let p = StitchPattern::preset("bobbles").unwrap();
    let bobble_cols = |r: usize| -> Vec<usize> {
        (0..p.width())
            .filter(|&c| p.stitch(r, c).form == Form::Bobble)
            .collect()
    };
    let (a, b) = (bobble_cols(2), bobble_cols(6));
    assert_eq!((a.len(), b.len()), (1, 1));
    assert_eq!((a[0] + 6 - b[0]) % 6, 3);
    // Rows that need incompatible widths are an error naming both.
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Rnd 1: *k2, p2; rep from *.\nRnd 2: k1, *k2, p2; rep from * to last st, k1... ",
    ));
    let _ = m;
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Rnd 1: *k4; rep from *.\nRnd 2: k2, *p4; rep from *.",
    ));
    assert!(
        m.contains("Row 1") && m.contains("Row 2") && m.contains("plus 2"),
        "{m}"
    );
    // A panel and a repeat that does not fit it.
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): p2, k12, p2.\nRow 2: *k3, p3; rep from *.",
    ));
    assert!(m.contains("16") && m.contains("multiple of 6"), "{m}");
    // A travelling twist that every column boundary cuts in some row still knits, and its
    // chart carries the twist across the edge.
    let p = ks("Rnd 1: *1/1 RT, k2; rep from *.\n\
                Rnd 2: k1, *1/1 RT, k2; rep from * to last 3 sts, 1/1 RT, k1.\n\
                Rnd 3: k2, *1/1 RT, k2; rep from * to last 2 sts, 1/1 RT.\n\
                Rnd 4: k3, *1/1 RT, k2; rep from * to last st, k1.");
    check_pattern("travelling twist", &p);
}

#[test]
fn unbalanced_patterns_name_rows_and_counts() {
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1: *yo, k1; rep from *. Row 2: purl.",
    ));
    assert!(m.contains("Row 1 turns 1 stitches into 2"), "{m}");
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Rnd 1: *yo, k2tog, yo, k1; rep from *.",
    ));
    assert!(
        m.contains("Row 1") && m.contains("3") && m.contains("4"),
        "{m}"
    );
    // Issue 17, bug 8: a one-row flat pattern is worked again from the wrong side as "row 2",
    // a row the text never wrote: the message names the row that changes its count.
    let m = pattern_error(StitchPattern::from_knitspeak("Row 1: k2tog, k1."));
    assert!(
        m.contains("Row 1 turns 3 stitches into 2") && !m.contains("Row 2"),
        "{m}"
    );
    // A chart row with a yo and no decrease.
    let m = pattern_error(StitchPattern::from_chart("kkkk\nkOkk"));
    assert!(
        m.contains("row 1") && m.contains("3") && m.contains("4"),
        "{m}"
    );
}

#[test]
fn errors_name_the_row_the_instruction_the_token_and_a_suggestion() {
    let cases = [
        (
            "Row 1 (RS): *k2, k2tg; rep from *.",
            &[
                "Row 1",
                "instruction 2",
                "\"k2tg\"",
                "did you mean \"k2tog\"",
            ][..],
        ),
        (
            "Rows 1-3: k2, 2/2 RX, k2.",
            &[
                "Rows 1-3",
                "instruction 2",
                "2/2 RX",
                "did you mean \"2/2 RC\"",
            ],
        ),
        (
            "Row 1: k2, c4q.",
            &["instruction 2", "c4q", "did you mean \"C4B\""],
        ),
        // A cable or twist name ending in a character of more than one byte: once a panic.
        ("Row 1: k2, tü.", &["instruction 2", "tü"]),
        ("Row 1: c4é.", &["instruction 1", "c4é"]),
        ("Row 1: *k2, p2.", &["never says"]),
        ("Row 1: k2, rep from *.", &["no '*'"]),
        (
            "Row 1: *k2, p2; rep from * to last 3 sts, k2.",
            &[
                "to last 3 sts",
                "leaving 3 stitches, but 2 stitches follow it",
            ],
        ),
        // Echoes the knitter's words (it once said "to last 1 sts" here).
        (
            "Row 1: Purl to last st.",
            &["\"to last st\", leaving 1 stitch, but no stitches follow it"],
        ),
        ("Row 1: [k1, p1 3 times.", &["never closed"]),
        ("Row 1: Knit.\nRow 3: Knit.", &["row 2 has no instructions"]),
        ("Stitch 1: Knit.", &["not a row header"]),
        ("", &["no Knitspeak rows"]),
    ];
    for (text, needles) in cases {
        let m = pattern_error(StitchPattern::from_knitspeak(text));
        for needle in needles {
            assert!(m.contains(needle), "{text:?}: {m}");
        }
    }
}

/// A pattern's width note (issue 17: "every row's count matches the count the text
/// states") is checked against the widths its rows fit: a note they disagree with means the
/// rows or the note were copied wrong, and is refused naming both, never knitted past.
#[test]
fn width_notes_are_checked_against_the_rows() {
    let rib = "Row 1 (RS): k2, *p2, k2; rep from *.\nRow 2: p2, *k2, p2; rep from *.";
    for note in [
        "(multiple of 4 sts, plus 2)",
        "Multiple of 4 sts plus 2.",
        "(a multiple of 8 sts + 6)",
        "(worked over 14 sts)",
    ] {
        assert_eq!(chart(&format!("{note}\n{rib}")), chart(rib), "{note}");
    }
    // Written in a row, as stitch-maps does.
    let in_row = "Row 1 (RS): k2, *p2, k2; rep from * (multiple of 4 sts, plus 2).\nRow 2: Purl.";
    assert_eq!(
        chart(in_row),
        chart("Row 1 (RS): k2, *p2, k2; rep from *.\nRow 2: Purl.")
    );
    for (note, says, needs) in [
        (
            "(multiple of 5 sts plus 2)",
            "a multiple of 5 stitches plus 2",
            "a multiple of 4 stitches plus 2",
        ),
        (
            "Multiple of 4 sts.",
            "a multiple of 4 stitches",
            "a multiple of 4 stitches plus 2",
        ),
        (
            "(worked over 12 sts)",
            "12 stitches",
            "a multiple of 4 stitches plus 2",
        ),
    ] {
        let m = pattern_error(StitchPattern::from_knitspeak(&format!("{note}\n{rib}")));
        assert!(
            m.contains(&format!(
                "says the pattern is worked over {says}, but its rows need {needs}"
            )),
            "{note}: {m}"
        );
    }
    let m = pattern_error(StitchPattern::from_knitspeak(
        "Row 1 (RS): *k2, p2; rep from * (multiple of 3 sts).\nRow 2: Purl.",
    ));
    assert!(m.contains("Row 1 (RS) (multiple of 3 sts)"), "{m}");
    // A panel: the note gives its width.
    let panel = "Row 1 (RS): p2, k4, p2.\nRow 2: k2, p4, k2.";
    assert_eq!(
        chart(&format!("(worked over 8 sts)\n{panel}")),
        chart(panel)
    );
    let m = pattern_error(StitchPattern::from_knitspeak(&format!(
        "(worked over 10 sts)\n{panel}"
    )));
    assert!(m.contains("but its rows need 8 stitches"), "{m}");
    // A note with more in it than a width stays an unread note.
    assert_eq!(
        chart(&format!(
            "(multiple of 5 sts plus 2; a 2-row repeat)\n{rib}"
        )),
        chart(rib)
    );
}

/// The stitch-maps stitches knitwear does not knit yet are named for what they are (the
/// commonest of them, kfb, was once offered as a misspelt "k"), in Knitspeak and in a
/// chart's legend, with what to do.
#[test]
fn stitches_that_change_the_count_are_named_not_misread() {
    let cases = [
        (
            "Row 1 (RS): *k1, kfb; rep from *.\nRow 2: *p1, p2tog; rep from *.",
            &[
                "Row 1 (RS), instruction 2",
                "\"kfb\" knits into the front and then the back",
                "2 stitches of 1",
                "yo",
            ][..],
        ),
        (
            "Row 1: k2, pfb, k2.",
            &["instruction 2", "\"pfb\"", "2 stitches of 1"],
        ),
        (
            "Row 1: k1, M1L, incr, k1.",
            &["instruction 3", "\"incr\"", "one new stitch"],
        ),
        (
            "Row 1: k1, 1-to-5 inc, k1.",
            &["\"1-to-5 inc\"", "5 stitches of 1"],
        ),
        ("Row 1: k1, ctr dbl inc, k1.", &["3 stitches of 1"]),
        (
            "Row 1: k2, BO 2 sts, k2.",
            &[
                "instruction 2",
                "\"BO 2 sts\" binds stitches off (2)",
                "binds off each piece at its surface's edges",
            ],
        ),
        ("Row 2: p2, co 2, p2.", &["\"co 2\" casts stitches on (2)"]),
        (
            "Row 1: k3, w&t.",
            &["\"w&t\"", "short rows are not knitted yet"],
        ),
        ("Row 1: k3, turn.", &["\"turn\"", "short rows"]),
        ("Row 1: k1, brk, k1.", &["brioche"]),
    ];
    for (text, needles) in cases {
        let m = pattern_error(StitchPattern::from_knitspeak(text));
        assert!(!m.contains("did you mean"), "{text:?}: {m}");
        for needle in needles {
            assert!(m.contains(needle), "{text:?}: {m}");
        }
    }
    let m = pattern_error(StitchPattern::from_chart("kXk\nkkk\n\nX = kfb"));
    assert!(
        m.contains("legend \"X = kfb\": \"kfb\" knits into the front"),
        "{m}"
    );
}

#[test]
fn charts_with_a_legend() {
    // A legend gives symbols their stitches and overrides the defaults.
    let p = StitchPattern::from_chart("pXXXXp\npkkkkp\n\nX = 2/2 RC").unwrap();
    let q = ks("Rnd 1: p1, k4, p1.\nRnd 2: p1, 2/2 RC, p1.");
    assert!(same_cells(&p, &q));
    // `o = p` restores the old meaning of o.
    assert!(same_cells(
        &StitchPattern::from_chart("kkoo\no = p").unwrap(),
        &StitchPattern::from_chart("kkpp").unwrap()
    ));
    // Two adjacent crosses of one symbol are told apart by the width the legend gives.
    let two = StitchPattern::from_chart("XXXXXXXX\nX = 2/2 RC").unwrap();
    assert!(same_cells(&two, &ks("Rnd 1: 2/2 RC, 2/2 RC.")));
    // A run continuing across the chart's edge.
    let wrapped = StitchPattern::from_chart("XkkX\nX = 1/1 RT").unwrap();
    let straight = StitchPattern::from_chart("kkXX\nX = 1/1 RT").unwrap();
    assert!(same_up_to_shift(&wrapped, &straight) && !same_cells(&wrapped, &straight));
    check_pattern("wrapped", &wrapped);
    // The default symbols, and a WS slip in the legend.
    let p = StitchPattern::from_chart("kO/kO\\O^OkB Q\nkkkkkkkkkkkk").unwrap();
    check_pattern("defaults", &p);
    check_pattern(
        "linen",
        &StitchPattern::from_chart("kY\nXk\nX = sl1 wyif\nY = sl1 wyib (WS)").unwrap(),
    );

    // Errors: row and column, symbol, suggestion.
    let m = pattern_error(StitchPattern::from_chart("kkpp\nkxpp\nkkpp"));
    assert!(m.contains("row 2, column 2") && m.contains("'x'"), "{m}");
    let m = pattern_error(StitchPattern::from_chart("pXXXp\nX = 2/2 RC"));
    assert!(
        m.contains("row 1, column 2") && m.contains("2/2 RC") && m.contains("4"),
        "{m}"
    );
    let m = pattern_error(StitchPattern::from_chart("kk\nX = 2/2 RX"));
    assert!(
        m.contains("2/2 RX") && m.contains("did you mean \"2/2 RC\""),
        "{m}"
    );
    let m = pattern_error(StitchPattern::from_chart("kk\nXY = k"));
    assert!(m.contains("one symbol"), "{m}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(512))]

    /// Any text, as a whole pattern or as one stitch of a row, is a pattern or an error
    /// with a message: never a panic (a cable name ending in a two-byte character once
    /// split inside it).
    #[test]
    fn any_text_reads_as_a_pattern_or_an_error(text in "\\PC{0,40}", stitch in "[ckptCKPT]?[0-9]{0,2}\\PC{0,3}") {
        for input in [text.clone(), format!("Row 1: k2, {stitch}."), format!("Row 1 (RS): *{stitch}; rep from *.")] {
            if let Err(e) = StitchPattern::from_knitspeak(&input) {
                proptest::prop_assert!(!e.to_string().is_empty());
            }
            let _ = StitchPattern::from_chart(&input);
            let _ = StitchPattern::from_text(&input);
        }
    }
}

#[test]
fn a_chart_knows_which_of_its_columns_cut_a_stitch_across_its_edge() {
    // The twisted cable rib, pXXp with X = 1/1 LC: only the boundary inside the cross cuts.
    let rib = StitchPattern::from_chart("pkkp\npXXp\n\nX = 1/1 LC").unwrap();
    let cuts: Vec<usize> = (0..4).map(|c| rib.cuts_at_column(c)).collect();
    assert_eq!(cuts[0], 0);
    assert_eq!(cuts[1], 0);
    assert!(cuts[2] > 0, "{cuts:?}");
    assert_eq!(cuts[3], 0);
    // Rotating the chart moves the cut with it, and is the chart read from that column.
    let split = rib.columns_rotated(2);
    assert!(split.cuts_at_column(0) > 0);
    assert!(same_cells(
        &split,
        &StitchPattern::from_chart("kppk\nXppX\n\nX = 1/1 LC").unwrap()
    ));
    assert!(same_cells(&split.columns_rotated(2), &rib));
    // A decrease reaching across the edge is cut there too; a plain chart nowhere.
    let lace = StitchPattern::from_chart("kkkk\n/Okk").unwrap();
    assert!((0..4).any(|c| lace.cuts_at_column(c) > 0));
    assert!((0..4).all(|c| ks("Rnd 1: *k2, p2; rep from *.").cuts_at_column(c) == 0));
}

/// A stitch slipped in every row of the repeat would carry its loop up for ever: the
/// pattern reads and charts, but knitting it is refused naming the column. Slipped in two or
/// three rows running (slip columns, mosaic knitting), in alternate rows (heel stitch) or
/// columns (linen stitch), and every preset, knit.
#[test]
fn a_column_slipped_in_every_row_is_refused_at_the_knit() {
    let columns = ks(
        "Row 1 (RS): K1, *sl1 wyib, k3; rep from * to last 2 sts, sl1 wyib, k1.\n\
                      Row 2: P1, *sl1 wyif, p3; rep from * to last 2 sts, sl1 wyif, p1.",
    );
    let m = pattern_error(columns.check_knittable());
    assert!(
        m.contains("column 4 from the left") && m.contains("every row of the repeat"),
        "{m}"
    );
    for ok in [
        "Row 1 (RS): *Sl1 wyib, k1; rep from *.\nRow 2: Purl.",
        "Row 1 (RS): *K1, sl1 wyif; rep from *.\nRow 2: *P1, sl1 wyib; rep from *.",
        "Row 1 (RS): K1, *sl1 wyib, k3; rep from * to last 2 sts, sl1 wyib, k1.\n\
         Row 2: P1, *sl1 wyif, p3; rep from * to last 2 sts, sl1 wyif, p1.\n\
         Row 3: Knit.\nRow 4: Purl.",
        "Row 1 (RS): *K3, sl1 wyib; rep from *.\nRow 2: *Sl1 wyif, p3; rep from *.\n\
         Row 3: *K3, sl1 wyib; rep from *.\nRow 4: Purl.",
    ] {
        ks(ok)
            .check_knittable()
            .unwrap_or_else(|e| panic!("{ok:?}: {e}"));
    }
    for name in StitchPattern::presets() {
        let p = StitchPattern::preset(name).unwrap();
        p.check_knittable()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

/// A loop that crosses exactly half of its repeat (a 1/3 cross beside p2, a k2tog or ssk in a
/// 2-stitch repeat) is as far from its landing one way round the repeat as the other: it lands
/// the way its instruction moves it, in its own repeat. (It used to land half a repeat the
/// other way: in the neighbouring repeat's column, so a k2tog gathered the loop on its left
/// and leaned as a ssk does, and a cable at the sheet's edge left a stitch pulled through no
/// loop.) Charts draw them and read them back.
#[test]
fn a_loop_crossing_half_its_repeat_lands_the_way_it_is_worked() {
    for (text, want) in [
        (
            "Row 1 (RS): *P2, 1/3 LC; rep from *.\nRow 2: *P4, k2; rep from *.",
            &[-3][..],
        ),
        (
            "Row 1 (RS): *P2, 1/3 RC; rep from *.\nRow 2: *P4, k2; rep from *.",
            &[3],
        ),
        // The front loop three columns left, the back one three right.
        (
            "Row 1 (RS): *P2, 1/2/1 LPC; rep from *.\nRow 2: *P1, k2, p1, k2; rep from *.",
            &[-3, 3],
        ),
        // Right to left: the yo, then the k2tog of the next two loops, whose right one
        // moves left onto the k2tog's column; a ssk's left one moves right.
        ("Row 1 (RS): *yo, k2tog; rep from *.\nRow 2: Purl.", &[-1]),
        ("Row 1 (RS): *ssk, yo; rep from *.\nRow 2: Purl.", &[1]),
    ] {
        let p = ks(text);
        let half = (p.width() / 2) as i8;
        let mut lands: Vec<i8> = (0..p.width())
            .map(|w| p.stitch(p.height() - 1, w).land_offset)
            .filter(|l| l.abs() == half)
            .collect();
        lands.sort();
        assert_eq!(lands, want, "{text}");
        let drawn = p.chart();
        assert!(!drawn.contains("# rows"), "{drawn}");
        assert_eq!(StitchPattern::from_chart(&drawn).unwrap().chart(), drawn);
    }
}

/// Stitch markers (issue 17, the dialect): `pm` / `sm` / `place marker` mark a place and work no
/// stitch, and a run to a marker (`k to m`, `rep from * to 2 sts before m`) fills its part,
/// whose width the row that places the markers counts.
#[test]
fn stitch_markers_part_the_row_and_runs_fill_to_them() {
    // Markers that no run works to change nothing.
    let plain = ks("Row 1 (RS): K2, p4, k2.\nRow 2: P2, k4, p2.");
    let marked = [
        "Row 1 (RS): K2, pm, p4, pm, k2.\nRow 2: P2, sm, k4, sm, p2.",
        "Row 1 (RS): K2, place marker, p4, place marker, k2.\nRow 2: P2, slip marker, k4, slm, p2.",
        "Row 1 (RS): K2, pm, p4, pm, k2.\nRow 2: P2, sl m, k4, sl m, p2.",
        "Row 1 (RS): Pm for beg of rnd, k2, pm A, p4, pm B, k2.\nRow 2: P2, sm A, k4, sm B, p2.",
    ];
    all_read_as(&marked, &plain, same_cells);
    // A cable panel between markers, its runs to the markers counted by the set-up row: on
    // a RS row `k to m` fills the right part, on a WS row the left one.
    let panel = ks("Row 1 (RS): K3, pm, p2, k4, p2, pm, k5.\n\
                    Row 2: P to m, sm, k2, p4, k2, sm, p to end.\n\
                    Row 3: K to m, sm, p2, 2/2 RC, p2, sm, k to end.\n\
                    Row 4: Rep row 2.");
    let written = ks("Row 1 (RS): K3, p2, k4, p2, k5.\n\
                      Row 2: P5, k2, p4, k2, p3.\n\
                      Row 3: K3, p2, 2/2 RC, p2, k5.\n\
                      Row 4: Rep row 2.");
    assert!(
        same_cells(&panel, &written),
        "{}\n{}",
        panel.chart(),
        written.chart()
    );
    // A repeat to a marker, the marker slipped without a word, and a run that stops short of
    // the marker for the stitches that follow it.
    let lace = ks("Row 1 (RS): K1, pm, k8, pm, k1.\n\
                   Row 2: Purl.\n\
                   Row 3: K to m, *yo, k2tog; rep from * to m, sm, k1.\n\
                   Row 4: Purl.\n\
                   Row 5: K to m, sm, k to 2 sts before m, k2tog, yo, k1.\n\
                   Row 6: Purl.");
    let lace_written = ks("Row 1 (RS): K10.\nRow 2: Purl.\n\
                           Row 3: K1, [yo, k2tog] 4 times, k1.\nRow 4: Purl.\n\
                           Row 5: K7, k2tog, yo, k1.\nRow 6: Purl.");
    assert!(same_cells(&lace, &lace_written), "{}", lace.chart());
    // Counts stay checked: `(12 sts)` on a 10-stitch row is refused.
    refused(&[
        (
            "Row 1 (RS): K to m, sm, p4, sm, k to end.\nRow 2: Purl.",
            "no row counts the stitches before the first marker",
        ),
        (
            "Row 1 (RS): K3, pm, p4, pm, k3.\nRow 2: P2, sm, k4, sm, p to end.\n\
             Row 3: K to m, sm, p4, sm, k to end.\nRow 4: Purl.",
            "works 2 stitches after the last marker (from the right edge) but Row 1 (RS) works 3",
        ),
        (
            "Row 1 (RS): K3, pm, p4, pm, k3.\nRow 2: P to m, sm, k2, k2tog, yo, sm, p to end.\n\
             Row 3: K to m, sm, k2tog, p2, sm, yo, k to end.\nRow 4: Purl.",
            "Row 3: the stitches between markers 1 and 2 (from the right edge) change its \
             stitch count, so the markers would move",
        ),
        (
            // A WS row meets the parts from the left: its first is the last from the right.
            "Row 1 (RS): K3, pm, p4, pm, k3.\nRow 2: P2tog, p to m, sm, k4, sm, yo, p to end.",
            "Row 2: the stitches after the last marker (from the right edge) change",
        ),
        (
            "Row 1 (RS): K3, pm, p4, pm, k3.\nRow 2: P to m, sm, k4, p to end.\n\
             Row 3: K to m, sm, p4, sm, k to end.\nRow 4: Purl.",
            "Row 1 (RS) parts the row at 2 markers but Row 2 at 1 marker",
        ),
        (
            "Row 1 (RS): K3, pm, p5, pm, k3.\nRow 2: Purl.\n\
             Row 3: K to m, sm, *p2, k1; rep from * to m, sm, k to end.\nRow 4: Purl.",
            "the part between markers 1 and 2 (from the right edge) is 5 stitches wide, but \
             the row works a multiple of 3 stitches there",
        ),
        (
            "Row 1 (RS): K3, pm, p4, pm, k3 (12 sts).\nRow 2: P to m, sm, k4, sm, p to end.",
            "the row says (12 sts) but leaves 10 stitches",
        ),
    ]);
}

/// Set-up rows (`Set-up row (WS):`, `Foundation row:`, `Row 1 (set-up row):`) are worked once
/// before the repeat: read (a misspelt stitch in one is reported, the markers it places are
/// counted, with the stitches it adds) but not repeated.
#[test]
fn set_up_rows_are_read_but_not_repeated() {
    let rib = ks("Row 1 (RS): K2, *p2, k2; rep from *.\nRow 2: P2, *k2, p2; rep from *.");
    let with_setup = [
        "Set-up row (WS): P2, *k2, p2; rep from *.\n\
         Row 1 (RS): K2, *p2, k2; rep from *.\nRow 2: P2, *k2, p2; rep from *.",
        "Foundation row: Purl.\n\
         Row 1 (RS): K2, *p2, k2; rep from *.\nRow 2: P2, *k2, p2; rep from *.",
        "Row 1 (set-up row, WS): Purl.\n\
         Row 2 (RS): K2, *p2, k2; rep from *.\nRow 3: P2, *k2, p2; rep from *.",
    ];
    all_read_as(&with_setup, &rib, same_up_to_shift);
    // The set-up row places the markers and increases the cable's stitches: the parts it
    // leaves are 3, 8 and 3 stitches wide.
    let panel = ks("Set-up row (RS): P3, pm, k2, m1, k2, m1, k2, pm, p3.\n\
                    Row 1 (WS): K to m, sm, p8, sm, k to end.\n\
                    Row 2: P to m, sm, 4/4 RC, sm, p to end.\n\
                    Row 3: Rep row 1.\n\
                    Row 4: P to m, sm, k to m, sm, p to end.");
    let written = ks("Row 1 (WS): K3, p8, k3.\nRow 2: P3, 4/4 RC, p3.\n\
                      Row 3: K3, p8, k3.\nRow 4: P3, k8, p3.");
    assert!(same_cells(&panel, &written), "{}", panel.chart());
    refused(&[(
        "Set-up row (WS): P2, *k2, pp2; rep from *.\nRow 1 (RS): Knit.\nRow 2: Purl.",
        "Set-up row (WS), instruction 3: unknown stitch \"pp2\"",
    )]);
}

/// `sl1, k1, psso` and its kin written as separate instructions read as the decrease they
/// make together, as the one-phrase spellings do.
#[test]
fn a_slipped_stitch_passed_over_reads_as_its_decrease() {
    for (written, one_phrase) in [
        ("*Sl1, k1, psso, yo; rep from *", "*skp, yo; rep from *"),
        // British patterns write `s1` for `sl1`.
        ("*S1, k1, psso, yo; rep from *", "*skp, yo; rep from *"),
        ("*S1 wyif, k1; rep from *", "*sl1 wyif, k1; rep from *"),
        (
            "*Yo, sl 1, k2tog, pass slipped st over, yo, k1; rep from *",
            "*yo, sk2p, yo, k1; rep from *",
        ),
        (
            "*Yo, sl2, k1, p2sso, yo, k1; rep from *",
            "*yo, cdd, yo, k1; rep from *",
        ),
        (
            "*Yo, sl2, p1, p2sso, yo, p1; rep from *",
            "*yo, cddp, yo, p1; rep from *",
        ),
    ] {
        let a = ks(&format!("Row 1 (RS): {written}.\nRow 2: Purl."));
        let b = ks(&format!("Row 1 (RS): {one_phrase}.\nRow 2: Purl."));
        assert!(same_cells(&a, &b), "{written}");
    }
    refused(&[
        (
            "Row 1 (RS): *Sl1, k2, psso, yo; rep from *.\nRow 2: Purl.",
            "a slipped stitch passed over two or more stitches, each keeping its loop, is not \
             knitted yet",
        ),
        (
            "Row 1 (RS): *K1, psso, yo; rep from *.\nRow 2: Purl.",
            "instruction 2 (\"psso\"): passes slipped stitches over",
        ),
        (
            "Row 1 (RS): *(k1, p1, k1) in next st, p3tog; rep from *.\nRow 2: Purl.",
            "(\"in next st\"): works 3 stitches into one loop (a 1-to-3 increase)",
        ),
    ]);
}

/// `These 2 rows form the pattern.` is a note on the repeat, checked against the rows given;
/// `k2tog through back loop` is `k2tog tbl`.
#[test]
fn notes_that_name_the_repeating_rows_are_checked() {
    let rib = ks("Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.");
    let noted = [
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.\nThese 2 rows form the pattern.",
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *. These two rows form the patt.",
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.\nLast 2 rows form pattern.",
        // How long to go on is the surface's to say.
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.\n\
         Repeat rows 1-2 until piece measures 10 in from cast-on edge.",
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.\nRep rows 1-2 throughout.",
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.\nContinue in pattern as set.",
    ];
    all_read_as(&noted, &rib, same_cells);
    refused(&[
        (
            "Row 1 (RS): Knit.\nRow 2: Purl.\nRepeat rows 1-2 and blah blah.",
            "cannot read \"and blah blah\"",
        ),
        (
        "Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: Knit.\nRow 4: Knit.\nLast 2 rows form the pattern.",
        "the pattern gives 4 rows (1 to 4), and knitwear repeats every row it is given, not the \
         last 2",
        ),
    ]);
    assert!(same_cells(
        &ks("Row 1 (RS): *K2tog through back loop, yo; rep from *.\nRow 2: Purl."),
        &ks("Row 1 (RS): *K2tog tbl, yo; rep from *.\nRow 2: Purl."),
    ));
}

/// Headers as printed patterns write them: `Row 2 and all WS rows`, `Row 2 and all foll WS
/// rows`, `Every WS row`, `Odd rows`, `All odd-numbered rows`, and a side in brackets before
/// more row numbers (`Rows 1 (RS) and 3`); and a repeat `ending k1`.
#[test]
fn headers_that_name_a_row_and_its_kind_read_as_knitters_write_them() {
    let moss = ks("Row 1 (RS): *K2, p2; rep from *.\nRow 2: Purl.\n\
                   Row 3: *P2, k2; rep from *.\nRow 4: Purl.");
    let headers = [
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2 and all WS rows: Purl.\n\
         Row 3: *P2, k2; rep from *.",
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2 and all foll WS rows: Purl.\n\
         Row 3: *P2, k2; rep from *.",
        "Row 1 (RS): *K2, p2; rep from *.\nEvery WS row: Purl.\nRow 3: *P2, k2; rep from *.",
        "Row 1 (RS): *K2, p2; rep from *.\nEven rows: Purl.\nRow 3: *P2, k2; rep from *.",
        "Row 1 (RS): *K2, p2; rep from *.\nWS rows: Purl.\nRow 3: *P2, k2; rep from *.",
    ];
    all_read_as(&headers, &moss, same_cells);
    let stripes = ks("Row 1 (RS): Knit.\nRow 2: Purl.");
    let parities = [
        "All odd-numbered rows: Knit.\nAll even-numbered rows: Purl.",
        "Odd rows (RS): Knit.\nEven rows: Purl.",
        "RS rows: Knit.\nWS rows: Purl.",
    ];
    all_read_as(&parities, &stripes, same_cells);
    let four = ks("Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: Knit.\nRow 4: Purl.");
    all_read_as(
        &["Rows 1 (RS) and 3: Knit.\nRows 2 and 4: Purl."],
        &four,
        same_cells,
    );
    let rib = ks("Row 1 (RS): *K1, p1; rep from * to last st, k1.\n\
                  Row 2: *P1, k1; rep from * to last st, p1.");
    let ending = [
        "Row 1 (RS): *K1, p1; rep from *, ending k1.\nRow 2: *P1, k1; rep from *, end p1.",
        "Row 1 (RS): *K1, p1; rep from *, end with k1.\nRow 2: *P1, k1; rep from *, ending with p1.",
    ];
    all_read_as(&ending, &rib, same_cells);
    assert!(same_cells(
        &ks("Row 1 (RS): *Knit into back of st, p1; rep from *.\nRow 2: *K1, p1 tbl; rep from *."),
        &ks("Row 1 (RS): *K1 tbl, p1; rep from *.\nRow 2: *K1, p1 tbl; rep from *."),
    ));
    refused(&[(
        "All odd rows: Knit.\nAll sideways rows: Purl.",
        "\"All sideways rows\" is not a row header",
    )]);
}

/// Barbara Walker's treasuries write `Row 1 (Wrong side)—Knit.`; other texts `[K1, p1] to
/// end`, `As row 1`, and `K the purl sts and p the knit sts` (seed from a rib). A text that
/// opens with a set-up row or a Walker header is still told from a chart.
#[test]
fn walker_dashes_bracket_runs_and_swapped_faces_read() {
    let walker = "Row 1 (Wrong side)\u{2014}Purl.\n\
                  Row 2\u{2014}K1, *yo, k2tog; rep from *, end k1.\n\
                  Rows 3 and 5\u{2014}Purl.\n\
                  Row 4\u{2014}Knit.\n\
                  Row 6\u{2014}K1, *ssk, yo; rep from *, end k1.";
    let colons = "Row 1 (WS): Purl.\nRow 2: K1, *yo, k2tog; rep from * to last st, k1.\n\
                  Rows 3 and 5: Purl.\nRow 4: Knit.\nRow 6: K1, *ssk, yo; rep from * to last st, k1.";
    // Pasted into one line (the add-on's Custom Chart field), each header keeps its dash.
    let one_line = walker.replace('\n', " ");
    all_read_as(&[walker, &one_line], &ks(colons), same_cells);
    assert!(same_cells(
        &StitchPattern::from_text(walker).unwrap(),
        &ks(colons)
    ));
    let setup_first = "Set-up row (WS): Purl.\nRow 1 (RS): Knit.\nRow 2: Purl.";
    assert_eq!(StitchPattern::from_text(setup_first).unwrap().height(), 2);

    let rib = ks("Row 1 (RS): *K1, p1; rep from *.\nRow 2: *K1, p1; rep from *.");
    let bracketed = [
        "Row 1 (RS): [K1, p1] to end.\nRow 2: (K1, p1) across.",
        "Row 1 (RS): [K1, p1] to end.\nRow 2: As row 1.",
    ];
    all_read_as(&bracketed, &rib, same_cells);
    let seed = ks(
        "Row 1 (RS): *K1, p1; rep from *.\nRow 2: *K1, p1; rep from *.\n\
                   Row 3: *P1, k1; rep from *.\nRow 4: *P1, k1; rep from *.",
    );
    let swapped = [
        "Row 1 (RS): *K1, p1; rep from *.\nRow 2: K the knit sts and p the purl sts.\n\
         Row 3: K the purl sts and p the knit sts.\nRow 4: Work sts as they appear.",
        "Row 1 (RS): *K1, p1; rep from *.\nRow 2: Work sts as they appear.\n\
         Row 3: Purl the knit sts and knit the purl sts.\nRow 4: Work sts as they appear.",
    ];
    all_read_as(&swapped, &seed, same_cells);
}

/// The ways printed patterns end a repeat: `rep to end`, `rep * to end`, `*k2, p2* rep to
/// end`, `work from * to end`, `[k2, p2] rep to end`, `until 2 sts remain`, `across to last
/// 2 sts`.
#[test]
fn repeats_end_as_printed_patterns_end_them() {
    let rib = ks("Row 1 (RS): K2, *p2, k2; rep from *.\nRow 2: P2, *k2, p2; rep from *.");
    let rows = [
        "*P2, k2; rep to end",
        "*P2, k2; rep * to end",
        "*P2, k2; repeat * to end",
        "*P2, k2* rep to end",
        "*P2, k2; work from * to end",
        "[P2, k2] rep to end",
    ];
    let texts: Vec<String> = rows
        .iter()
        .map(|r| format!("Row 1 (RS): K2, {r}.\nRow 2: P2, *k2, p2; rep from *."))
        .collect();
    let texts: Vec<&str> = texts.iter().map(String::as_str).collect();
    all_read_as(&texts, &rib, same_cells);
    let ending = [
        "Row 1 (RS): *K2, p2; rep from * until 2 sts remain, k2.\nRow 2: P2, *k2, p2; rep from *.",
        "Row 1 (RS): *K2, p2; rep from * across to last 2 sts, k2.\nRow 2: P2, *k2, p2; rep from *.",
    ];
    all_read_as(&ending, &rib, same_up_to_shift);
}

/// Patterns are pasted with the text around them: a title without brackets, `Cast on a
/// multiple of 4 sts + 2.`, `Note: ...`, `Gauge: ...`, `Pattern:`, and `Bind off all sts.`
/// at the end. Such a text is told from a chart and reads as its rows; a width note among the
/// lines before the rows is still checked.
#[test]
fn the_text_around_a_pattern_is_passed_over() {
    let rib = ks("Row 1 (RS): K2, *p2, k2; rep from *.\nRow 2: P2, *k2, p2; rep from *.");
    let rows =
        "Row 1 (RS): K2, *p2, k2; rep from * to end.\nRow 2 (WS): P2, *k2, p2; rep from * to end.";
    let texts = [
        format!("Two by two rib\n{rows}"),
        format!("Cast on a multiple of 4 sts + 2.\n{rows}\nRep these 2 rows for pattern."),
        format!("Note: slip sts purlwise.\nGauge: 20 sts and 28 rows = 4 in.\nPattern:\n{rows}"),
        format!("CO 22 sts.\n{rows}\nNote: the rib draws in.\nBind off all sts in pattern."),
        // A title on the first row's line, and the whole text on one line (the add-on's
        // field): only what comes before the first row is passed over.
        format!("Two by two rib. {rows}"),
        format!("Two by two rib. Cast on a multiple of 4 sts + 2. {rows}").replace('\n', " "),
    ];
    for text in &texts {
        let read = StitchPattern::from_text(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert!(same_cells(&read, &rib), "{text}:\n{}", read.chart());
    }
    refused(&[
        (
            &format!("Cast on a multiple of 4 sts + 3.\n{rows}"),
            "says the pattern is worked over a multiple of 4 stitches plus 3",
        ),
        ("Stitch 1: Knit.", "\"Stitch 1\" is not a row header"),
        (
            &format!("Rib. Cast on a multiple of 4 sts + 3. {rows}").replace('\n', " "),
            "says the pattern is worked over a multiple of 4 stitches plus 3",
        ),
    ]);
    // A chart is still a chart.
    assert_eq!(StitchPattern::from_text("kkpp\nkkpp").unwrap().width(), 4);
}

/// Publishers' own abbreviations for twists and crosses read as the Knitspeak crosses they
/// are: `Tw2` (Rowan, Sirdar) the right twist, `Tw2L` the left; `Cr2R` / `Cr2L` the purled
/// twists; `Cr3R` / `Cr3L` a knit pair crossing a purl stitch. An odd-sized `C3B`, which
/// books split two ways, is refused with both readings offered.
#[test]
fn publishers_twists_and_crosses_read_as_their_crosses() {
    let cases = [
        ("Tw2, Tw2L", "1/1 RT, 1/1 LT"),
        ("Tw2R, Tw2F", "1/1 RT, 1/1 LT"),
        ("Cr2R, Cr2L", "1/1 RPT, 1/1 LPT"),
        ("Cr3R, Cr3L", "2/1 RPC, 2/1 LPC"),
        ("K2tog-b, yo, p2tog-b, yo", "k2tog tbl, yo, p2tog tbl, yo"),
        ("Yo, s2kpo, yo", "yo, s2kp, yo"),
        ("Sl1k, k1, sl1p, k1", "sl1 wyib, k1, sl1 wyib, k1"),
    ];
    for (spelled, knitspeak) in cases {
        let row = |body: &str| format!("Row 1 (RS): *P2, {body}, p2; rep from *.\nRow 2: Purl.");
        let expected = ks(&row(knitspeak));
        all_read_as(&[&row(spelled)], &expected, same_cells);
    }
    refused(&[
        (
            "Row 1: *P2, C3B; rep from *.\nRow 2: Purl.",
            "\"C3B\" crosses 3 stitches, which publishers split two ways: write it as \
             \"2/1 RC\" (2 stitches travel in front) or \"1/2 RC\"",
        ),
        (
            "Row 1: *P2, C5F; rep from *.\nRow 2: Purl.",
            "write it as \"3/2 LC\" (3 stitches travel in front) or \"2/3 LC\"",
        ),
    ]);
}

/// A repeat inside a repeat, marked `**` (as printed patterns mark the second level), is
/// worked its set number of times in place; a row whose only repeat is marked `**` reads as
/// one marked `*`; and a set-count repeat beside an open one is written out.
#[test]
fn repeats_marked_with_two_stars_nest() {
    all_read_as(
        &["Row 1 (RS): *K1, **p1, k1; rep from ** 2 more times, p1; rep from *.\nRow 2: Purl."],
        &ks("Row 1 (RS): *K1, p1, k1, p1, k1, p1, k1, p1; rep from *.\nRow 2: Purl."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): K1, **p1, k1; rep from ** to end.\nRow 2: Purl."],
        &ks("Row 1 (RS): K1, *p1, k1; rep from * to end.\nRow 2: Purl."),
        same_cells,
    );
    all_read_as(
        &[
            "Row 1 (RS): *K2, p1; rep from * once more, **k1, p2, k1; rep from ** to end.\n\
           Row 2: Purl.",
        ],
        &ks("Row 1 (RS): K2, p1, k2, p1, *k1, p2, k1; rep from * to end.\nRow 2: Purl."),
        same_cells,
    );
    all_read_as(
        &["Rnd 1: *K2, **p1, k1; rep from ** twice more; rep from * around.\nRnd 2: Knit."],
        &ks("Rnd 1: *K2, p1, k1, p1, k1, p1, k1; rep from * around.\nRnd 2: Knit."),
        same_cells,
    );
    // `rep from ** 2 times` says neither "in all" nor "more": refused as `*` is.
    refused(&[(
        "Row 1: *K1, **p1, k1; rep from ** 2 times, p1; rep from *.\nRow 2: Purl.",
        "write \"2 times in all\" or \"2 more times\"",
    )]);
}

/// `K2, p2 to end`: a run whose count is written repeats the row up to it, as printed
/// patterns write rib; `K1, p to end` stays one knit stitch and a run of purls. `Knit 1 row`
/// is `Knit`. Rows that only say "as before" and stitches worked into a yarn-over's loop
/// are refused with what they say.
#[test]
fn counted_runs_repeat_the_row_and_as_set_rows_are_refused() {
    all_read_as(
        &["Row 1 (RS): K2, p2 to end.\nRow 2: K2, p2 to end."],
        &ks("Row 1 (RS): *K2, p2; rep from * to end.\nRow 2: *K2, p2; rep from * to end."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): K1, p1 to last st, k1.\nRow 2: P1, k1 to last st, p1."],
        &ks("Row 1 (RS): *K1, p1; rep from * to last st, k1.\n\
             Row 2: *P1, k1; rep from * to last st, p1."),
        same_up_to_shift,
    );
    all_read_as(
        &["Row 1 (RS): P1, k1 tbl to end.\nRow 2: K1, p1 tbl to end."],
        &ks("Row 1 (RS): *P1, k1 tbl; rep from *.\nRow 2: *K1, p1 tbl; rep from *."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): K1, p to end.\nRow 2: P1, k to end."],
        &ks("Row 1 (RS): K1, *p1; rep from * to end.\nRow 2: P1, *k1; rep from * to end."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): Knit 1 row.\nRow 2: Purl one row."],
        &ks("Row 1 (RS): Knit.\nRow 2: Purl."),
        same_cells,
    );
    refused(&[
        (
            "Row 1 (RS): *K2, p2; rep from *.\nRow 2: Work even.",
            "\"Work even\" works the row as earlier rows set it",
        ),
        (
            "Row 1 (RS): *K2, p2; rep from *.\nRow 2: Work in patt.",
            "\"Work in patt\" works the row as earlier rows set it",
        ),
        (
            "Row 1 (RS): *K2tog, yo twice, ssk; rep from *.\n\
             Row 2: *P1, (k1, p1) into double yo, p1; rep from *.",
            "works 2 stitches into one loop (a 1-to-2 increase)",
        ),
    ]);
}

/// Rows numbered as British patterns number them (`1st row (RS):`, `2nd and every alt row:`,
/// `5th to 8th rows:`, `1st rnd:`, `As 3rd row.`) read as Knitspeak's `Row 1 (RS):`; so do
/// `Row 2 and every alt row:`, `Every other row:` and `Rows 1 to 4:` / `Rows 1 through 4:`.
#[test]
fn british_row_numbers_and_alternate_rows_read() {
    all_read_as(
        &[
            "1st row (RS): K2, *p2, k2; rep from * to end.\n\
             2nd row: P2, *k2, p2; rep from * to end.\n\
             3rd row: As 1st row.\n4th row: As 2nd row.\n5th to 8th rows: Knit.",
            "Rows 1 and 3 (RS): K2, *p2, k2; rep from * to end.\n\
             Rows 2 and 4: P2, *k2, p2; rep from * to end.\nRows 5 through 8: Knit.",
            "1st and 3rd rows (RS): K2, *p2, k2; rep from * to end.\n\
             2nd and 4th rows: P2, *k2, p2; rep from * to end.\n5th-8th rows: Knit.",
        ],
        &ks("Rows 1 and 3 (RS): K2, *p2, k2; rep from * to end.\n\
             Rows 2 and 4: P2, *k2, p2; rep from * to end.\nRows 5-8: Knit."),
        same_cells,
    );
    let lace = ks("Row 1 (RS): *K1, yo, k2tog; rep from *.\nRow 2: Purl.\n\
                   Row 3: *K2tog, yo, k1; rep from *.\nRow 4: Purl.");
    all_read_as(
        &[
            "1st row (RS): *K1, yo, k2tog; rep from *.\n2nd and every alt row: Purl.\n\
             3rd row: *K2tog, yo, k1; rep from *.",
            "Row 1 (RS): *K1, yo, k2tog; rep from *.\nRow 2 and every alternate row: Purl.\n\
             Row 3: *K2tog, yo, k1; rep from *.",
            "Row 1 (RS): *K1, yo, k2tog; rep from *.\nEvery other row: Purl.\n\
             Row 3: *K2tog, yo, k1; rep from *.",
            "1st row (RS): *K1, yo, k2tog; rep from *.\n2nd and every foll alt row: Purl.\n\
             3rd row: *K2tog, yo, k1; rep from *.",
        ],
        &lace,
        same_cells,
    );
    // The row named before `every alt row` is one of them, and the repeat starts at it.
    all_read_as(
        &["Row 1 and every alt row: Knit.\nRow 2: Purl.\nRow 4: *K1, p1; rep from *."],
        &ks("Rows 1 and 3: Knit.\nRow 2: Purl.\nRow 4: *K1, p1; rep from *."),
        same_cells,
    );
    all_read_as(
        &["1st rnd: Knit.\n2nd and every alt rnd: Purl.\n3rd rnd: *K1, p1; rep from *."],
        &ks("Rnd 1: Knit.\nRnd 2: Purl.\nRnd 3: *K1, p1; rep from *.\nRnd 4: Purl."),
        same_cells,
    );
    // A spaced dash for the colon, as pattern pages write it.
    all_read_as(
        &["Row 1 (RS) - Knit.\nRow 2 \u{2013} Purl.\nRow 3 - Purl. Row 4 - Knit."],
        &ks("Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: Purl.\nRow 4: Knit."),
        same_cells,
    );
    // A full stop for the colon, as some books print rows, the side before or after it.
    // The sides of these rows are checked too: a (WS) on row 1 would be refused.
    all_read_as(
        &[
            "Row 1. (RS) K2, *p2, k2; rep from *.\nRow 2. P2, *k2, p2; rep from *.",
            "Row 1 (RS). K2, *p2, k2; rep from *. Row 2. P2, *k2, p2; rep from *.",
            // The side after the colon, or without brackets.
            "Row 1: (RS) K2, *p2, k2; rep from *.\nRow 2: (WS) P2, *k2, p2; rep from *.",
            "Row 1 RS: K2, *p2, k2; rep from *.\nRow 2 WS: P2, *k2, p2; rep from *.",
        ],
        &ks("Row 1 (RS): K2, *p2, k2; rep from *.\nRow 2: P2, *k2, p2; rep from *."),
        same_cells,
    );
    // Rows named for the part they knit.
    all_read_as(
        &[
            "Rib rows are worked first.\nRib row 1 (RS): Knit.\nRib row 2: Purl.\n\
           Patt row 3: Purl. Pattern row 4: Knit.",
        ],
        &ks("Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: Purl.\nRow 4: Knit."),
        same_cells,
    );
    // `R1:` as pattern pages shorten it.
    all_read_as(
        &["R1 (RS): Knit.\nR2: Purl.\nR3: Purl.\nR4: Knit."],
        &ks("Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: Purl.\nRow 4: Knit."),
        same_cells,
    );
    // Ordinals that name no row are left alone.
    refused(&[(
        "1st row: K2, *p2, k2; rep from *.\n2nd row: 3rd st.",
        "unknown stitch \"3rd st\"",
    )]);
}

/// British patterns slip with the yarn in front by moving it (`yf, sl1, yb`) and use `yf` /
/// `yfwd` for a yarn-over elsewhere (`yf, k2tog`, `yf, sl1, k1, psso`); a move the reader
/// cannot place is refused.
#[test]
fn yarn_moved_round_a_slip_slips_it_on_that_side() {
    all_read_as(
        &[
            "Row 1 (RS): *K1, yf, sl1, yb; rep from *.\nRow 2: *P1, yb, sl1 purlwise, yf; rep from *.",
            "Row 1 (RS): *K1, yarn to front, sl1, yarn to back; rep from *.\n\
             Row 2: *P1, ytb, sl1, ytf; rep from *.",
        ],
        &ks("Row 1 (RS): *K1, sl1 wyif; rep from *.\nRow 2: *P1, sl1 wyib; rep from *."),
        same_cells,
    );
    all_read_as(
        &[
            "Row 1 (RS): *K1, yf, k2tog, yfwd, sl1, k1, psso; rep from *.\nRow 2: Purl.",
            "Row 1 (RS): *K1, yo, k2tog, yo, skp; rep from *.\nRow 2: Purl.",
        ],
        &ks("Row 1 (RS): *K1, yo, k2tog, yo, ssk; rep from *.\nRow 2: Purl."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): *K2, ytf, sl2, ytb; rep from *.\nRow 2: Purl."],
        &ks("Row 1 (RS): *K2, sl2 wyif; rep from *.\nRow 2: Purl."),
        same_cells,
    );
    refused(&[
        (
            "Row 1 (RS): *K1, yb, k1; rep from *.\nRow 2: Purl.",
            "a move of the yarn to the back is read only around slipped stitches",
        ),
        (
            "Row 1 (RS): *K1, ytf, k1; rep from *.\nRow 2: Purl.",
            "a move of the yarn to the front is read only around slipped stitches",
        ),
    ]);
}

/// A pattern's key of abbreviations, before or after its rows, defines its cables: each
/// definition that spells out a cable needle's working reads as the cross it works, and the
/// rows read the name as that cross, a name the reader already knows included (a publisher's
/// `T3B` may cross knit over knit).
#[test]
fn a_patterns_own_cable_abbreviations_read_as_they_are_defined() {
    let rows = "Row 1 (RS): *P2, C3B, p2, T3B; rep from *.\nRow 2: *P3, k2, p3, k2; rep from *.";
    let expected =
        ks("Row 1 (RS): *P2, 2/1 RC, p2, 2/1 RC; rep from *.\nRow 2: *P3, k2, p3, k2; rep from *.");
    let key = "Special abbreviations\n\
               C3B = slip next st onto cable needle and hold at back of work, K2, then K1 from \
               cable needle.\n\
               T3B: sl 1 to cn, hold in back, k2, k1 from cn.\n\
               MB = make bobble: (k1, p1, k1) in next st, turn, p3, turn, sk2p.";
    all_read_as(
        &[
            &format!("{key}\n{rows}"),
            &format!("{rows}\n{key}"),
            &format!("Cable rib\n{key}\nCast on a multiple of 10 sts.\n{rows}\nBind off."),
            // Pasted into one line (the add-on's field), a heading before the first name.
            &format!("Special abbreviations: {key} {rows}")
                .replace("Special abbreviations\n", "")
                .replace('\n', " "),
        ],
        &expected,
        same_cells,
    );
    // Without the key, C3B is refused with both readings and T3B is the reader's 2/1 RPC.
    refused(&[(
        rows,
        "\"C3B\" crosses 3 stitches, which publishers split two ways",
    )]);
    let left = ks("C3F = sl 2 to cn, hold in front, k1, k2 from cn.\n\
                   Row 1 (RS): *P2, C3F; rep from *.\nRow 2: *P3, k2; rep from *.");
    assert!(same_cells(
        &left,
        &ks("Row 1 (RS): *P2, 2/1 LC; rep from *.\nRow 2: *P3, k2; rep from *.")
    ));
}

/// A second repeat that works the stitches a first one left (`*k2, p2; rep from * to last 4
/// sts, *k1, p1; rep from * to end`) is worked over them in place; one that does not fill
/// them is refused with both counts.
#[test]
fn a_second_repeat_works_what_the_first_left() {
    all_read_as(
        &[
            "Row 1 (RS): *K2, p2; rep from * to last 4 sts, *k1, p1; rep from * to end.\n\
           Row 2: P4, *k2, p2; rep from *.",
        ],
        &ks(
            "Row 1 (RS): *K2, p2; rep from * to last 4 sts, k1, p1, k1, p1.\n\
             Row 2: P4, *k2, p2; rep from *.",
        ),
        same_cells,
    );
    all_read_as(
        &[
            "Row 1 (RS): *K2, p2; rep from * to last 6 sts, *k1, p1; rep from * to last 2 \
           sts, k2.\nRow 2: P6, *k2, p2; rep from *.",
        ],
        &ks(
            "Row 1 (RS): *K2, p2; rep from * to last 6 sts, k1, p1, k1, p1, k2.\n\
             Row 2: P6, *k2, p2; rep from *.",
        ),
        same_cells,
    );
    refused(&[(
        "Row 1 (RS): *K2, p2; rep from * to last 5 sts, *k1, p1; rep from * to end.\n\
         Row 2: Purl.",
        "this repeat of 2 stitches does not fill the 5 stitches the repeat before it left",
    )]);
}

/// An instruction run on for pages (no comma or full stop) is refused at once, by its
/// length, not read at every space of it.
#[test]
fn a_run_on_instruction_is_refused_by_its_length() {
    let text = format!("Row 1: {}\nRow 2: Purl.", "k1 + ".repeat(20_000).trim_end());
    refused(&[(
        &text,
        "runs 99999 characters without a comma or a full stop",
    )]);
}

/// A repeat's count of times: `N more times` and `N times in all` each say which count they
/// give; a plain `N times` or `twice` is read both ways by knitters, so it is refused with
/// both ways to write it (it was refused as "expected ... N more times").
#[test]
fn a_repeat_count_in_all_reads_and_a_bare_count_names_both_readings() {
    let written = ks("Row 1 (RS): *K1, p1; rep from * 2 more times, k2.\nRow 2: Purl.");
    all_read_as(
        &[
            "Row 1 (RS): *K1, p1; rep from * 3 times in all, k2.\nRow 2: Purl.",
            "Row 1 (RS): *K1, p1; rep from * three times total, k2.\nRow 2: Purl.",
            "Row 1 (RS): *K1, p1; rep from * a total of 3 times, k2.\nRow 2: Purl.",
            "Row 1 (RS): *K1, p1, rep from * 2 times more, k2.\nRow 2: Purl.",
        ],
        &written,
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): *K1, p1; rep from * 1 more time, k2.\nRow 2: Purl."],
        &ks("Row 1 (RS): K1, p1, k1, p1, k2.\nRow 2: Purl."),
        same_cells,
    );
    refused(&[
        (
            "Row 1 (RS): *K1, p1; rep from * 2 times, k2.\nRow 2: Purl.",
            "\"2 times\" is read two ways, 2 in all or 2 more after the first: write \
             \"2 times in all\" or \"2 more times\"",
        ),
        (
            "Row 1: *K1, p1; rep from * twice, k2. Row 2: Purl.",
            "write \"2 times in all\" or \"2 more times\"",
        ),
        (
            "Row 1: *K1, p1; rep from * until done. Row 2: Purl.",
            "expected \"to end\", \"to last N sts\" or \"N more times\"",
        ),
        // A count past any row's width is refused before it is worked out: the largest
        // integer's "more times" wrapped round to a repeat worked no times and read, and
        // a count near it filled the memory.
        (
            "Row 1: *K1, p1; rep from * 18446744073709551615 more times, k2. Row 2: Purl.",
            "a repeat worked 18446744073709551615 times: a pattern's row holds at most 256",
        ),
        (
            "Row 1: *K1, p1; rep from * 100000 times in all, k2. Row 2: Purl.",
            "a repeat worked 100000 times",
        ),
    ]);
}

/// A cable needle's working written out inside a row, as older books print cables, reads as
/// the cross it works; a pattern's key still defines its names, and a working that is no
/// cross is left for the row to refuse.
#[test]
fn a_cable_worked_out_inside_a_row_reads_as_its_cross() {
    all_read_as(
        &[
            "Row 1 (RS): P2, *slip 2 sts to cn and hold in front, k2, k2 from cn, p2; rep \
             from *.\nRow 2: K2, *p4, k2; rep from *.",
            "Row 1 (RS): P2, *Sl next 2 sts onto cable needle and hold at front of work, K2, \
             then K2 from cable needle, p2; rep from *.\nRow 2: K2, *p4, k2; rep from *.",
        ],
        &ks("Row 1 (RS): P2, *2/2 LC, p2; rep from *.\nRow 2: K2, *p4, k2; rep from *."),
        same_cells,
    );
    all_read_as(
        &[
            "Row 1 (RS): K1, *sl 1 to cn, hold at back, k2, p1 from cn, k1; rep from *. \
           Row 2: Purl.",
        ],
        &ks("Row 1 (RS): K1, *2/1 RPC, k1; rep from *. Row 2: Purl."),
        same_cells,
    );
    // The key's definition is read as a definition, and the rows read its name.
    all_read_as(
        &[
            "C4B = sl 2 to cn, hold at back, k2, k2 from cn. Row 1 (RS): P2, C4B, p2. \
           Row 2: K2, p4, k2.",
        ],
        &ks("Row 1 (RS): P2, 2/2 RC, p2.\nRow 2: K2, p4, k2."),
        same_cells,
    );
    refused(&[(
        "Row 1 (RS): P2, sl 2 to cn, hold in front, k2, k1 from cn, p2. Row 2: K2, p4, k2.",
        "unknown stitch \"sl 2 to cn\"",
    )]);
}

/// Stitches written without the commas between them, as quick notes write rib (`*k2 p2;
/// rep from *`), read as if the commas were there; words that belong to one stitch (`k2
/// tog`, `k1 tbl`) are never split apart, and a run of bare `k p` is no count at all.
#[test]
fn stitches_written_without_commas_read_as_written_with_them() {
    all_read_as(
        &[
            "Row 1 (RS): *k2 p2; rep from *.\nRow 2: *k2 p2; rep from *.",
            "Row 1 (RS): *K2 P2; rep from *.\nRow 2: *k2, p2; rep from *.",
        ],
        &ks("Row 1 (RS): *k2, p2; rep from *.\nRow 2: *k2, p2; rep from *."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): k1, *yo k2tog; rep from * to last st, k1. Row 2: Purl."],
        &ks("Row 1 (RS): k1, *yo, k2tog; rep from * to last st, k1. Row 2: Purl."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): *k2 tog, yo; rep from *. Row 2: Purl."],
        &ks("Row 1 (RS): *k2tog, yo; rep from *. Row 2: Purl."),
        same_cells,
    );
    refused(&[
        ("Row 1: k p. Row 2: p k.", "unknown stitch \"k p\""),
        (
            "Row 1: k2 tbl p2. Row 2: p4.",
            "unknown stitch \"k2 tbl p2\"",
        ),
    ]);
}

/// A repeat closed by a second `*` with how far it goes straight after (`*k2, p2* across`,
/// `K1, *p1, k1* to end`), and a bracket's count written `x 3` as British patterns write
/// it, read as their standard spellings.
#[test]
fn a_closing_star_with_its_extent_and_a_bracket_times_x_read() {
    all_read_as(
        &[
            "Row 1 (RS): *K2, P2* across.\nRow 2: *K2, P2* to end.",
            "Row 1 (RS): *K2, P2*; rep to end.\nRow 2: *K2, P2* all around.",
        ],
        &ks("Row 1 (RS): *K2, p2; rep from * to end.\nRow 2: *K2, p2; rep from * to end."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): K1, *p1, k1* to last st, k1.\nRow 2: Purl."],
        &ks("Row 1 (RS): K1, *p1, k1; rep from * to last st, k1.\nRow 2: Purl."),
        same_cells,
    );
    all_read_as(
        &[
            "Row 1 (RS): (K2, P2) x 3, k2.\nRow 2: P2, [k2, p2] x3.",
            "Row 1 (RS): (K2, P2) \u{d7} 3, k2.\nRow 2: P2, [k2, p2] 3x.",
        ],
        &ks("Row 1 (RS): [K2, p2] 3 times, k2.\nRow 2: P2, [k2, p2] 3 times."),
        same_cells,
    );
}

/// Rows written as garment patterns write a run of them, `Next row:` after `Next row:`,
/// read as numbered rows from 1, or from the row after the last one a header names.
#[test]
fn next_rows_read_as_the_rows_after_those_before_them() {
    let rib = ks(
        "Row 1 (RS): *K2, p2; rep from *.\nRow 2: *K2, p2; rep from *.\n\
                  Row 3: Knit.\nRow 4: Purl.",
    );
    all_read_as(
        &[
            "Cast on a multiple of 4 sts. Next row (RS): *K2, p2; rep from *. Next row: \
             *K2, p2; rep from *. Next row: Knit. Next row: Purl.",
            "Rows 1 and 2: *K2, p2; rep from *.\nNext row: Knit.\nNext row: Purl.",
        ],
        &rib,
        same_cells,
    );
}

/// `K2, p2, rep to end`: a `rep` that names no `*`, after stitches only, repeats the row so
/// far, as `K2, p2 to end` reads; a `rep from *` whose `*` is missing stays refused.
#[test]
fn a_rep_that_names_no_star_repeats_the_row_so_far() {
    all_read_as(
        &[
            "Row 1 (RS): K2, p2, rep to end.\nRow 2: K2, p2, rep to end.",
            "Row 1 (RS): K2, p2, repeat across.\nRow 2: K2, p2 to end.",
        ],
        &ks("Row 1 (RS): *K2, p2; rep from * to end.\nRow 2: *K2, p2; rep from * to end."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): K2, p2, rep to last 2 sts, k2.\nRow 2: P2, k2, rep to last 2 sts, p2."],
        &ks("Row 1 (RS): *K2, p2; rep from * to last 2 sts, k2.\n\
             Row 2: *P2, k2; rep from * to last 2 sts, p2."),
        same_cells,
    );
    refused(&[(
        "Row 1: P1, k1 tbl; rep from * to end.\nRow 2: K1, p1.",
        "a repeat with no '*' before it",
    )]);
}

/// `k2, p2 - repeat to end`: a dash between spaces, or a long dash, parts instructions as a
/// comma does; `Slip, slip, knit` (and `slip, slip, purl`), spelled out as some books print
/// ssk, reads as the decrease. `sl1, sl1, k1`, which may be two slips and a knit, is left as
/// written, and a hyphen inside a name is no dash.
#[test]
fn dashes_between_instructions_and_spelled_out_decreases_read() {
    all_read_as(
        &[
            "Row 1 (RS): k2, p2 - repeat to end.\nRow 2: k2, p2 \u{2013} rep to end.",
            "Row 1 (RS): *K2 - p2; rep from *.\nRow 2: K2, p2\u{2014}rep to end.",
        ],
        &ks("Row 1 (RS): *K2, p2; rep from * to end.\nRow 2: *K2, p2; rep from * to end."),
        same_cells,
    );
    all_read_as(
        &[
            "Row 1 (RS): *Slip, slip, knit, yarn over; rep from *.\nRow 2: Purl.",
            "Row 1 (RS): *SLIP,SLIP , KNIT, yo; rep from *.\nRow 2: Purl.",
        ],
        &ks("Row 1 (RS): *ssk, yo; rep from *.\nRow 2: Purl."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): *slip, slip, knit, yo; rep from *.\nRow 2: *Slip, slip, purl, yo; rep from *."],
        &ks("Row 1 (RS): *ssk, yo; rep from *.\nRow 2: *ssp, yo; rep from *."),
        same_cells,
    );
    // Counted slips are slips, not the decrease.
    let slips = ks("Row 1 (RS): *sl1, sl1, k1; rep from *.\nRow 2: Purl.");
    assert_eq!(slips.width(), 3);
    // `knit 2 together` after two slips is no ssk: the row is read word by word.
    let k2tog = ks("Row 1: *slip, slip, knit 2 together, yo; rep from *.\nRow 2: Purl.");
    assert_eq!(k2tog.width(), 4);
    all_read_as(
        &["Row 1 (RS): *k2tog-tbl, yo; rep from *.\nRow 2: Purl."],
        &ks("Row 1 (RS): *k2tog tbl, yo; rep from *.\nRow 2: Purl."),
        same_cells,
    );
}

/// `Knit all stitches.`, `Purl every st.`: the whole row, as `Knit.` reads; `rep from *, end
/// last rep k2`: the last repeat stops after its first two stitches, as `ending k2` reads.
#[test]
fn whole_rows_in_words_and_a_last_repeat_cut_short_read() {
    all_read_as(
        &[
            "Row 1: Knit all stitches.\nRow 2: Purl all sts.",
            "Row 1: Knit every stitch.\nRow 2: Purl each st.",
            "Row 1: K across the row.\nRow 2: P to the end of the row.",
        ],
        &ks("Row 1: Knit.\nRow 2: Purl."),
        same_cells,
    );
    let rib = ks("Row 1 (RS): *K2, p2; rep from *, ending k2.\nRow 2: P2, *k2, p2; rep from *.");
    all_read_as(
        &[
            "Row 1 (RS): *K2, p2; rep from *, end last rep k2.\nRow 2: P2, *k2, p2; rep from *.",
            "Row 1 (RS): *K2, p2; rep from *, ending last repeat with k2.\n\
             Row 2: P2, *k2, p2; rep from *.",
        ],
        &rib,
        same_cells,
    );
}

/// `Work in St st.` (stockinette, stocking stitch) shows knit on the right side whichever
/// side the row is worked from, and `Work in rev St st.` purl; `rep from beg` repeats the
/// row so far, as `rep` with no star does.
#[test]
fn a_row_that_names_its_fabric_and_a_repeat_from_the_beginning_read() {
    all_read_as(
        &["Rows 1-4: Work in St st."],
        &ks("Rows 1 and 3 (RS): Knit.\nRows 2 and 4: Purl."),
        same_cells,
    );
    all_read_as(
        &[
            "Row 1 (RS): Knit.\nRow 2: Work in stockinette stitch.",
            "Row 1 (RS): Work even in stocking stitch.\nRow 2: Purl.",
        ],
        &ks("Row 1 (RS): Knit.\nRow 2: Purl."),
        same_cells,
    );
    all_read_as(
        &["Row 1 (RS): Work in rev St st.\nRow 2: Work in reverse stockinette."],
        &ks("Row 1 (RS): Purl.\nRow 2: Knit."),
        same_cells,
    );
    // Set on the rows around it: garter below, stockinette above.
    let mixed = ks("Rows 1-4: Knit.\nRows 5-8: Work in St st.");
    let faces: Vec<char> = (0..8)
        .map(|r| match mixed.stitch(r, 0).face {
            knitwear::pattern::Face::Knit => 'k',
            knitwear::pattern::Face::Purl => 'p',
        })
        .collect();
    assert_eq!(faces.iter().collect::<String>(), "kpkpkkkk");
    all_read_as(
        &[
            "Row 1 (RS): K4, p4; rep from beg.\nRow 2: K4, p4; rep from beginning of row.",
            "Row 1 (RS): K4, p4; repeat from the beginning.\nRow 2: K4, p4, rep from beg to end.",
        ],
        &ks("Row 1 (RS): *K4, p4; rep from *.\nRow 2: *K4, p4; rep from *."),
        same_cells,
    );
}
