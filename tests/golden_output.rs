//! Every preset's knit, bit for bit: the digests of its output buffers on a small sheet at
//! the default settings and the add-on's irregularity (kappa 0.005), with live loops (the
//! fabric alone: recorded before the house was rearranged, "One source per setting", and
//! unchanged by the cast-on and bind-off since; eyelet rows and the lace diamond re-recorded
//! when a yarn-over whose decrease the sheet's edge cuts off came to be knitted plain; all
//! re-recorded when the bundles' triangles came to lie along the tube, issue 16) and
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
    ("stockinette", 0x18929ef2ca8f4b4f, 0xae8b79026cf2a16a),
    (
        "reverse_stockinette",
        0x65298e0dce6aefa7,
        0x9af5100442a0542c,
    ),
    ("garter", 0x773f5effc80e4c7b, 0xe4d8f52aeb53d105),
    ("rib_1x1", 0xe826a40c0f8e3a67, 0x44e222b887d904dc),
    ("rib_2x2", 0xf7fe5e0ce834594f, 0xf176d4a4f8f02611),
    ("seed", 0x5cce53a24cbbc578, 0x6a4834f78fc47789),
    ("moss", 0x131c1646bad705a6, 0xa10cf1ba3db56d01),
    ("basketweave", 0x4831000a5234c871, 0x4f73bd8569f054ad),
    ("twisted_rib", 0x05cce965de8046ce, 0xf71dabc52a36275e),
    ("cable_c4", 0x8931ef46ff8e429e, 0xa1b9911fa940d785),
    ("cable_c6", 0xf7347a06587c3e97, 0x6c438c0827051180),
    ("horseshoe_cable", 0x5fce88655748e5e8, 0x97308a1ba51a4154),
    ("honeycomb_cable", 0x6b4770b5810e7e60, 0x44dde8b8b81d0e3f),
    ("mock_cable_rib", 0xd26f2d1b1f00bbdb, 0x1bc7cd187254c032),
    ("twisted_cable_rib", 0xb8e3a72374fe2cad, 0x7d42c7a094fa0eb5),
    ("diamond", 0xb9dc0c8321e4910b, 0x92932e3de44abcb8),
    ("chevron", 0x3979033f06ba2b54, 0x1643fb9af98a3583),
    ("feather_and_fan", 0x5355e5b64ee39b04, 0xdc5dc24e53b3e65c),
    ("eyelet_rows", 0x5202b59eeae994f5, 0x4973e5fefe26ff8c),
    ("lace_diamond", 0x7fe8b3500fe8a69f, 0x9033602c20329aaa),
    ("bobbles", 0xc2c847dcf74f6853, 0x3d3c269405a5f863),
    ("linen_stitch", 0xe18a7a8221066da3, 0x732f414e2d59fa05),
    ("fair_isle", 0x18929ef2ca8f4b4f, 0xae8b79026cf2a16a),
    ("fair_isle+band", 0x42c17efaaaa68d7e, 0x97416ac6d4b8a367),
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
