//! Every preset's knit, bit for bit: the digests of its output buffers on a small sheet at
//! the default settings and the add-on's irregularity (kappa 0.005), with live loops (the
//! fabric alone: recorded before the house was rearranged, "One source per setting", and
//! unchanged by the cast-on and bind-off since; eyelet rows and the lace diamond re-recorded
//! when a yarn-over whose decrease the sheet's edge cuts off came to be knitted plain; all
//! re-recorded when the bundles' triangles came to lie along the tube, when every knit came
//! to carry the tube's shading normals, and when it came to carry its fibre directions,
//! issue 16, and when a bind-off loop came to take its height from the taller side of the tile
//! under it, issue 17; eyelet rows re-recorded when a loop crossing half its 2-stitch repeat
//! came to land the way its decrease moves it; C6, the horseshoe cable and feather and fan
//! re-recorded when courses with a loop leaning three columns or more came to space their
//! spline's knots by their chords, issue 15) and finished with them (the default). A
//! refactor that changes one bit of any preset's yarn, colours or topology fails here; so
//! does a machine or thread count that knits differently from the one that recorded them.
//!
//! A change meant to alter the output records the new digests with
//! `cargo run --release --example output_digest` and says why in its commit.

use knitwear::knit::{KnitParams, PreparedKnit};
use knitwear::pattern::{color_preset, StitchPattern};
use knitwear::surface::PlaneSurface;

mod common;
use common::digest::digest;

/// (preset, digest with live loops, digest finished): `examples/output_digest.rs`'s output. `fair_isle+band` is the Fair
/// Isle preset in the `fair_isle_band` colour chart.
const GOLDEN: &[(&str, u64, u64)] = &[
    ("stockinette", 0xbf106a39e89445ee, 0xff538f4d7c29b86c),
    (
        "reverse_stockinette",
        0xb4930b04e5cf1238,
        0xe090f7744feeb59b,
    ),
    ("garter", 0x489cf315ce25581a, 0xbe3cfb04ba1a025a),
    ("rib_1x1", 0xae4d91426c8d39c8, 0x70666fb8e5ccad44),
    ("rib_2x2", 0xd297ed7f7c9ef835, 0x47c84180c9830697),
    ("seed", 0x0a20f005a02f369b, 0x950a06c1099e51dc),
    ("moss", 0xe61bbafaa6126879, 0x4aa88af0eea50f8f),
    ("basketweave", 0x7d0161614f21c3e3, 0x2208ce1a418d4cf3),
    ("twisted_rib", 0x749ce358e226bfb6, 0x7c510f83cf103a82),
    ("cable_c4", 0xcdeff1808f62eb09, 0x2833785f466b0dd6),
    ("cable_c6", 0xea1254f6107b2b97, 0x7416b6255f5c1ec7),
    ("horseshoe_cable", 0x07facd315ad07d43, 0xf2332aeb4edf93c4),
    ("honeycomb_cable", 0xfeac077ae66a2a31, 0x4191a0006f34514f),
    ("mock_cable_rib", 0x5936f7a0d3bf1644, 0xe176ad83256278fc),
    ("twisted_cable_rib", 0x511897c24ab46b9e, 0x8d4dbfcefae781aa),
    ("diamond", 0x536d6e039f587c7c, 0x3093eeea232caae2),
    ("chevron", 0x568aeb47f4053b7c, 0x5856631c783a9ad4),
    ("feather_and_fan", 0xb3073e485ada9e72, 0xf86acb41d4b311cc),
    ("eyelet_rows", 0x6922f5d7f1239a0b, 0xa46c51e979b22905),
    ("lace_diamond", 0xd840ba07223740d7, 0xe63f1b599c0fed51),
    ("bobbles", 0x801a512c5bc40178, 0x833e554be9678471),
    ("linen_stitch", 0xd4b88071912db2d7, 0x9ddce2add6dc24db),
    ("fair_isle", 0xbf106a39e89445ee, 0xff538f4d7c29b86c),
    ("fair_isle+band", 0xc46352b2758cb277, 0xeccde9abb01092a5),
];

#[test]
fn every_preset_knits_the_recorded_bits() {
    let plane = PlaneSurface {
        width: 0.05,
        height: 0.04,
    };
    assert_eq!(
        GOLDEN.len(),
        StitchPattern::presets().len() + 1,
        "a preset without a recorded digest"
    );
    let mut changed = Vec::new();
    for &(name, live, finished) in GOLDEN {
        let (preset, colors) = match name.split_once('+') {
            Some((preset, chart)) => {
                let palette = vec![[0.5, 0.05, 0.05], [0.8, 0.75, 0.65], [0.03, 0.1, 0.3]];
                let colors = color_preset(&format!("fair_isle_{chart}"), palette).unwrap();
                (preset, Some(colors))
            }
            None => (name, None),
        };
        let pattern = StitchPattern::preset(preset).unwrap();
        for (live_loops, want) in [(true, live), (false, finished)] {
            let p = KnitParams {
                kappa: 0.005,
                colors: colors.clone(),
                live_loops,
                ..KnitParams::default()
            };
            let knit = PreparedKnit::new(&plane, &pattern, &p).unwrap();
            let got = digest(&knit.build(&plane).unwrap());
            if got != want {
                let which = if live_loops { "live loops" } else { "finished" };
                changed.push(format!(
                    "{name} ({which}): {got:016x}, recorded {want:016x}"
                ));
            }
        }
    }
    assert!(changed.is_empty(), "{}", changed.join("\n"));
}
