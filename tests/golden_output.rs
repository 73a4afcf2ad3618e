//! Every preset's knit, bit for bit: the digests of its output buffers on a small sheet at
//! the default settings and the add-on's irregularity (kappa 0.005), with live loops (the
//! fabric alone: recorded before the house was rearranged, "One source per setting", and
//! unchanged by the cast-on and bind-off since; eyelet rows and the lace diamond re-recorded
//! when a yarn-over whose decrease the sheet's edge cuts off came to be knitted plain; all
//! re-recorded when the bundles' triangles came to lie along the tube and again when every
//! knit came to carry the tube's shading normals, issue 16) and
//! finished with them (the default). A
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
    ("stockinette", 0x20fa5bebc926ccb2, 0xee165a701b788334),
    (
        "reverse_stockinette",
        0x42f09492cd63fc47,
        0x13f7371dbee74381,
    ),
    ("garter", 0x4585735960ebdc15, 0x3ff5c7d3e52933f6),
    ("rib_1x1", 0x44d888dc62b979a1, 0x343e1b0a9f1447cb),
    ("rib_2x2", 0xc8491ba775c459be, 0xd81ab199190f3bdf),
    ("seed", 0xe892b566a6c50be0, 0x48a8a48760e563c1),
    ("moss", 0xdb1b5175deb2b16e, 0x22730792c332f74a),
    ("basketweave", 0xed8acffb9d37a52c, 0xf79074b3838b8f11),
    ("twisted_rib", 0xd34459e024a0e7b1, 0xe2f94ad8b77c3ccd),
    ("cable_c4", 0xbefd4b3f1ee64ceb, 0x69f1fd1d4de24340),
    ("cable_c6", 0xc3ee2fd0b863349c, 0xc1047e7dd548df91),
    ("horseshoe_cable", 0xb8c0b8d8fee744c3, 0xd103b259eaf0ce1c),
    ("honeycomb_cable", 0x619427a77194411a, 0x0584d3c37ed43346),
    ("mock_cable_rib", 0xf56839165356a8bb, 0x3d4c118f91fd2d2b),
    ("twisted_cable_rib", 0x4f28a9d4f41471b9, 0x18d65077630cf951),
    ("diamond", 0x846f111dd43e3dd0, 0x3bb030c829019716),
    ("chevron", 0xd0ace08b3ce6380b, 0xab924bc2e52fc39a),
    ("feather_and_fan", 0x69fa8d1eaf6132de, 0xba58c3a39ecaf5e6),
    ("eyelet_rows", 0xf0e39796815c0107, 0xff4de4a5786d4e64),
    ("lace_diamond", 0x9853e4910681fece, 0xa2a2955dbae13d63),
    ("bobbles", 0xd1d87d1df23d5c3c, 0x6076a07fe4d34922),
    ("linen_stitch", 0xdd95caed95fbb7db, 0x5a5bb3a077c50121),
    ("fair_isle", 0x20fa5bebc926ccb2, 0xee165a701b788334),
    ("fair_isle+band", 0x21fd9acf8b614caa, 0xebf002c6f37a2864),
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
