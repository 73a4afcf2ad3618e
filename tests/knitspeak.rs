//! Knitspeak for knit and purl patterns: the shared pattern files read to the charts knitters
//! draw for them, WS rows turn over, and what this reader does not know yet is an error that
//! names the row and the token.

use std::path::Path;

use knitwear::pattern::StitchPattern;
use knitwear::KnitError;

/// A Knitspeak file of the team's shared patterns (copied into tests/data/knitspeak).
fn shared(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/knitspeak")
        .join(format!("{name}.ks"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The chart of a pattern, top row first, as `parse_chart` reads it.
fn chart(text: &str) -> String {
    StitchPattern::from_knitspeak(text).unwrap().chart()
}

#[test]
fn the_shared_knit_and_purl_patterns_read_as_their_charts() {
    // Expected charts, drawn as knitters draw them (right side, top row first).
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
        let text = shared(name);
        assert_eq!(chart(&text), want, "{name}:\n{text}");
        // And it equals the preset of the same name, where there is one.
        if let Ok(preset) = StitchPattern::preset(name) {
            let got = StitchPattern::from_knitspeak(&text).unwrap();
            for c in 0..8 {
                for w in 0..8 {
                    assert_eq!(got.stitch(c, w), preset.stitch(c, w), "{name} at {c},{w}");
                }
            }
        }
    }
}

#[test]
fn what_is_not_supported_yet_is_named() {
    for name in [
        "twisted-rib",
        "cable-4",
        "horseshoe-cable",
        "bobbles",
        "eyelet-rows",
        "feather-and-fan",
    ] {
        let err = StitchPattern::from_knitspeak(&shared(name)).unwrap_err();
        let KnitError::Pattern(message) = err else {
            panic!("{name}: not a pattern error")
        };
        assert!(message.contains("Row"), "{name}: {message}");
        println!("{name}: {message}");
    }
}

#[test]
fn one_line_rounds_all_ws_rows_and_ranges() {
    // Statements on one line (as a UI text field holds them).
    assert_eq!(chart("Row 1 (RS): Knit. Row 2: Purl."), "k\nk\n");
    // In the round every row is worked from the right side: knit every round is stockinette.
    assert_eq!(chart("Rnd 1: Knit.\nRnd 2: Knit."), "k\nk\n");
    // "All WS rows" fills the even rows (worked from the back: purl shows as knit).
    assert_eq!(
        chart("Row 1 (RS): *k1, p1; rep from * to end.\nAll WS rows: Purl."),
        "kk\nkp\n"
    );
    assert_eq!(
        chart("Rows 1-3: k2, p2.\nRow 4: p2, k2."),
        "ppkk\nkkpp\nkkpp\nkkpp\n"
    );
    // A first row on the wrong side turns the parity round.
    assert_eq!(chart("Row 1 (WS): Knit.\nRow 2: Knit."), "k\np\n");
}

#[test]
fn errors_name_the_row_the_instruction_and_a_suggestion() {
    let cases = [
        ("Row 1 (RS): *k2, pp2; rep from *.", "pp2"),
        ("Row 1: k2, c4f.", "c4f"),
        ("Row 1: k2, *p2, rep from *.", "before the repeat"),
        ("Row 1: *k2, p2.", "never says"),
        ("Row 1: Knit.\nRow 3: Knit.", "row 2 has no instructions"),
        ("Stitch 1: Knit.", "not a row header"),
        ("", "no Knitspeak rows"),
    ];
    for (text, needle) in cases {
        let err = StitchPattern::from_knitspeak(text).unwrap_err();
        let KnitError::Pattern(message) = err else {
            panic!("{text}: not a pattern error")
        };
        assert!(message.contains(needle), "{text:?}: {message}");
    }
    let KnitError::Pattern(m) = StitchPattern::from_knitspeak("Row 1: kk2.").unwrap_err() else {
        panic!()
    };
    assert!(
        m.contains("did you mean \"k\"") && m.contains("Row 1"),
        "{m}"
    );
}
