//! Digests of every preset's knit on a small sheet at default settings and the add-on's
//! irregularity, with live loops and finished: what `tests/golden_output.rs` holds against change (its
//! `GOLDEN` table is this example's output).
//! `cargo run --release --example output_digest [preset...]`
use knitwear::knit::{KnitParams, PreparedKnit};
use knitwear::pattern::StitchPattern;
use knitwear::surface::PlaneSurface;

#[path = "../tests/common/digest.rs"]
mod digest;
use digest::digest;

/// A colour chart preset in a fixed three-colour palette.
fn band(chart: &str) -> knitwear::pattern::ColorPattern {
    let palette = vec![[0.5, 0.05, 0.05], [0.8, 0.75, 0.65], [0.03, 0.1, 0.3]];
    knitwear::pattern::color_preset(&format!("fair_isle_{chart}"), palette).unwrap()
}

fn main() {
    let names: Vec<String> = {
        let a: Vec<String> = std::env::args().skip(1).collect();
        if a.is_empty() {
            StitchPattern::presets()
                .iter()
                .map(|s| s.to_string())
                .collect()
        } else {
            a
        }
    };
    let plane = PlaneSurface {
        width: 0.05,
        height: 0.04,
    };
    for name in names {
        // `fair_isle+band`: the Fair Isle preset in the colours of the `fair_isle_band` chart.
        let (preset, colors) = match name.split_once('+') {
            Some((preset, chart)) => (preset, Some(band(chart))),
            None => (name.as_str(), None),
        };
        let pattern = StitchPattern::preset(preset).unwrap();
        let t = std::time::Instant::now();
        // Live loops (the fabric alone), then finished with a cast-on and a bind-off.
        let digests = [true, false].map(|live_loops| {
            let p = KnitParams {
                kappa: 0.005,
                colors: colors.clone(),
                live_loops,
                ..KnitParams::default()
            };
            let knit = PreparedKnit::new(&plane, &pattern, &p).unwrap();
            digest(&knit.build(&plane).unwrap())
        });
        println!(
            "    (\"{name}\", 0x{:016x}, 0x{:016x}), // {:.1}s",
            digests[0],
            digests[1],
            t.elapsed().as_secs_f64()
        );
    }
}
