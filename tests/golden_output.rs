//! Every preset's knit, bit for bit: the digests of its output buffers on a small sheet at
//! the default settings and the add-on's irregularity (kappa 0.005), with live loops (the
//! fabric alone: recorded before the house was rearranged, "One source per setting", and
//! unchanged by the cast-on and bind-off since; eyelet rows and the lace diamond re-recorded
//! when a yarn-over whose decrease the sheet's edge cuts off came to be knitted plain) and
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
    ("stockinette", 0xaffb4933f930e6ad, 0xa94f769c292c538a),
    (
        "reverse_stockinette",
        0x6476f4c5fe9cf23b,
        0x3bae139bcd74d30a,
    ),
    ("garter", 0xb1d0347263fe4473, 0x9c5d0c06ffc45e5d),
    ("rib_1x1", 0xb8eb86692f6c8535, 0x45b381bc841c092d),
    ("rib_2x2", 0x9c35a7de37bebe66, 0xe43b0cf25a2a1607),
    ("seed", 0x5846a169bb7d5154, 0xf63da38f4be7874f),
    ("moss", 0x0d58bf4a6d83cfdc, 0x4b82415e6d85a11d),
    ("basketweave", 0x9d0e3af21725634d, 0x7d42b1982eb4f875),
    ("twisted_rib", 0xc2b1796ba892fcf7, 0x650b0b473d769a8f),
    ("cable_c4", 0x515f80b0b1287013, 0x63282183404f564b),
    ("cable_c6", 0xfe9d979665934e9a, 0xbb15f2ef1908bb0a),
    ("horseshoe_cable", 0x783a325f74e55286, 0xf1b09b7bc294ca5d),
    ("honeycomb_cable", 0x94610e4c0e348ef9, 0xc067df07279b1998),
    ("mock_cable_rib", 0x5c0a5278c8b99f18, 0x4d971d7c0c91e464),
    ("twisted_cable_rib", 0xc5eb3cb9ff63bb65, 0xa8929f5fbaaf0d65),
    ("diamond", 0xcd62ef5ddab3fe95, 0xc69dcd91d035529b),
    ("chevron", 0xd325fe2956366fbe, 0xa5032ba9f198a1bf),
    ("feather_and_fan", 0xdf7f82d655682c9e, 0x439b4766cfc6a858),
    ("eyelet_rows", 0xc6b7e7c20abe614b, 0x8ca17b46e8565757),
    ("lace_diamond", 0x9508ae5c13ce63bc, 0xf65ad5f183f783ef),
    ("bobbles", 0x588c7771c9f2f1d6, 0x92a2a7b9fd3beb5c),
    ("linen_stitch", 0x8cf9c905926ffba1, 0xd14978b13c74eb51),
    ("fair_isle", 0xaffb4933f930e6ad, 0xa94f769c292c538a),
    ("fair_isle+band", 0xc32d63cf5fa6b9fe, 0xa0f6ded36d05344a),
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
