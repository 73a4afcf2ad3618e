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
    ("stockinette", 0xaffb4933f930e6ad, 0xca1ff1231e4f3468),
    (
        "reverse_stockinette",
        0x6476f4c5fe9cf23b,
        0xfdbc156d088ad5b0,
    ),
    ("garter", 0xb1d0347263fe4473, 0x8952ae13b1f1fdcf),
    ("rib_1x1", 0xb8eb86692f6c8535, 0x035193e7bc3249bd),
    ("rib_2x2", 0x9c35a7de37bebe66, 0x361b38a09ff8a621),
    ("seed", 0x5846a169bb7d5154, 0xc364820226aa77b2),
    ("moss", 0x0d58bf4a6d83cfdc, 0x8bf45cd483f307e3),
    ("basketweave", 0x9d0e3af21725634d, 0xe59927c18eee991a),
    ("twisted_rib", 0xc2b1796ba892fcf7, 0xbbb2e590c42987e1),
    ("cable_c4", 0x7d4ee35afb0c322a, 0xce7f47efd0e9aff3),
    ("cable_c6", 0x5e2bfbb0304b55fe, 0xd1b91f8df1e7425d),
    ("horseshoe_cable", 0x475f7703cc11001d, 0x3878bcf868397689),
    ("honeycomb_cable", 0xabac5d899250d9ff, 0xf46314b2200149dc),
    ("mock_cable_rib", 0x5bb4897f891e215b, 0x5f0f33c25d219394),
    ("twisted_cable_rib", 0x8765ecbba11c152b, 0x7063fc03692ae27f),
    ("diamond", 0xcd62ef5ddab3fe95, 0x8dd26941c7fa5bce),
    ("chevron", 0xd325fe2956366fbe, 0x489089d71f067708),
    ("feather_and_fan", 0x2c0864d1d57157fc, 0xc37728a4c065c621),
    ("eyelet_rows", 0x23a1c9b9ec4bec5c, 0xb47882734c2d535f),
    ("lace_diamond", 0xb9645df5ff2039c3, 0x44218c3bbbe725f8),
    ("bobbles", 0x588c7771c9f2f1d6, 0x1735bf5923ef10c6),
    ("linen_stitch", 0x8cf9c905926ffba1, 0xdfaefc86e7c19aa5),
    ("fair_isle", 0xaffb4933f930e6ad, 0xca1ff1231e4f3468),
    ("fair_isle+band", 0xc32d63cf5fa6b9fe, 0xc3b89d249b31eda0),
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
