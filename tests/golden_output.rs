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
    ("stockinette", 0xeb53742a8d884b92, 0xc0030bcfdacbc623),
    (
        "reverse_stockinette",
        0x057c9efeacd74b1f,
        0xeb71469caade6f7a,
    ),
    ("garter", 0xda6fd2d75ef0b309, 0xd7fbf9dd90b914b3),
    ("rib_1x1", 0x62d9523f8c942769, 0xbadafe38d7b880d1),
    ("rib_2x2", 0xcbdb1b8b201297c4, 0x39258d0c41fe38f1),
    ("seed", 0xc39ad4044c277004, 0x65d4abcf715855d1),
    ("moss", 0xf968114150872504, 0x1c7e891167215e85),
    ("basketweave", 0xabca32c855822a89, 0x49b962781d29a792),
    ("twisted_rib", 0x1ec8c8bc5f3a10b3, 0x406db1e26af00561),
    ("cable_c4", 0x71ca6cf3c0a9d964, 0x0390c3fd4fec622d),
    ("cable_c6", 0x8b5aacfc92621e84, 0x3e3b6bbc413e2676),
    ("horseshoe_cable", 0x5041a1787cd81b80, 0x0c81f13e749d88a7),
    ("honeycomb_cable", 0xbd7e6e16ab480dd4, 0xd28a8d716e9c5430),
    ("mock_cable_rib", 0xe43f6c19062af8d3, 0xc3e26cb74a68be0d),
    ("twisted_cable_rib", 0x1d9a74e68fe19347, 0x723555d9673fedd7),
    ("diamond", 0xee9368b15ba67fd7, 0xcb15a7ce7b8a2647),
    ("chevron", 0x28511bf8fa5000e6, 0xe07671d576f65dd8),
    ("feather_and_fan", 0x0a67fbb8e808bc58, 0xeea5c93534cb06ba),
    ("eyelet_rows", 0xd7165898331db8cd, 0x9da208b8087c2a49),
    ("lace_diamond", 0x62b6d8c14ab28d26, 0x34b25ed9cb27df5d),
    ("bobbles", 0x6d0cc9c0106cbe63, 0xcec11043e005d8f5),
    ("linen_stitch", 0x51685d4f54ff1696, 0xc211d858cf05c2c1),
    ("fair_isle", 0xeb53742a8d884b92, 0xc0030bcfdacbc623),
    ("fair_isle+band", 0x069e22cd7eb097ad, 0xcab1f2b00f3d628f),
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
