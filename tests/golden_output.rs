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
    ("stockinette", 0xaffb4933f930e6ad, 0x04e23d0764f9d0ff),
    (
        "reverse_stockinette",
        0x6476f4c5fe9cf23b,
        0xdc6e8d27c80adede,
    ),
    ("garter", 0xb1d0347263fe4473, 0x6343c5e7c7dbe21a),
    ("rib_1x1", 0xb8eb86692f6c8535, 0xba19013070e841fc),
    ("rib_2x2", 0x9c35a7de37bebe66, 0xbddfcd27365b6291),
    ("seed", 0x5846a169bb7d5154, 0x62f8c15da4791d77),
    ("moss", 0x0d58bf4a6d83cfdc, 0x5328a2257b68f3b8),
    ("basketweave", 0x9d0e3af21725634d, 0x6943afb8073403d9),
    ("twisted_rib", 0xc2b1796ba892fcf7, 0x83a27ced0870e12a),
    ("cable_c4", 0x515f80b0b1287013, 0xe069f817a9a0e56e),
    ("cable_c6", 0xfe9d979665934e9a, 0xd35dff1ca61c9cfb),
    ("horseshoe_cable", 0x783a325f74e55286, 0x3797403f12021285),
    ("honeycomb_cable", 0x94610e4c0e348ef9, 0xec57e704a87734ad),
    ("mock_cable_rib", 0x5c0a5278c8b99f18, 0x6df064414ebd3163),
    ("twisted_cable_rib", 0xc5eb3cb9ff63bb65, 0x0ec36e3a752cb3aa),
    ("diamond", 0xcd62ef5ddab3fe95, 0xcdaa97dd4b491024),
    ("chevron", 0xd325fe2956366fbe, 0xc799c2b9d9b72256),
    ("feather_and_fan", 0xdf7f82d655682c9e, 0x4d914b896e53d3ff),
    ("eyelet_rows", 0xc6b7e7c20abe614b, 0x8f03485ccff0d736),
    ("lace_diamond", 0x9508ae5c13ce63bc, 0x554c278d1cdb1c94),
    ("bobbles", 0x588c7771c9f2f1d6, 0x622de1fffa94b733),
    ("linen_stitch", 0x8cf9c905926ffba1, 0xe8c9b44f21b3f2a9),
    ("fair_isle", 0xaffb4933f930e6ad, 0x04e23d0764f9d0ff),
    ("fair_isle+band", 0xc32d63cf5fa6b9fe, 0x90662a15cee148d4),
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
