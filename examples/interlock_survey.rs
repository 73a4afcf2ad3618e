//! Interlock, clearance and cover of every preset on a flat sheet at the default gauge.
//! `cargo run --release --example interlock_survey [radius_per_stitch_width|default] [preset...]`
//! (a name ending `.ks` is read as a Knitspeak file).
//! (`default`: the yarn a knit gets when none is given, as the tests knit).
use glam::{Vec2, Vec3};
use knitwear::knit::{KnitParams, PreparedKnit};
use knitwear::metrics::cover;
use knitwear::pattern::StitchPattern;
use knitwear::surface::PlaneSurface;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let ratio: Option<f32> = match args.first().map(String::as_str) {
        None => Some(0.1),
        Some("default") => None,
        Some(a) => Some(a.parse().expect("a radius per stitch width, or `default`")),
    };
    let names: Vec<String> = if args.len() > 1 {
        args[1..].to_vec()
    } else {
        StitchPattern::presets()
            .iter()
            .map(|s| s.to_string())
            .collect()
    };
    let plane = PlaneSurface {
        width: 0.12,
        height: 0.1,
    };
    for name in names {
        let pattern = if name.ends_with(".ks") {
            let text = std::fs::read_to_string(&name).expect("a readable Knitspeak file");
            StitchPattern::from_text(&text).unwrap()
        } else {
            StitchPattern::preset(&name).unwrap()
        };
        let t = std::time::Instant::now();
        let p = KnitParams {
            yarn_radius: ratio.map(|r| r * 0.005),
            measure_clearance: true,
            ..KnitParams::default()
        };
        let knit = PreparedKnit::new(&plane, &pattern, &p).unwrap();
        let prep = t.elapsed().as_secs_f64();
        let out = knit.build(&plane).unwrap();
        let order = knit.crossing_order(&plane).unwrap();
        let pts: Vec<Vec3> = out
            .centerline
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect();
        let yarns: Vec<(&[Vec3], bool)> = out
            .yarn_offsets
            .windows(2)
            .zip(&out.yarn_closed)
            .map(|(w, &c)| (&pts[w[0] as usize..w[1] as usize], c))
            .collect();
        let c = cover(
            &yarns,
            out.yarn_radius,
            Vec2::new(0.02, 0.02),
            Vec2::new(0.1, 0.08),
            800,
        );
        let cl = out.stats.clearance.unwrap();
        // The furthest centreline point from the sheet, in diameters: half the fabric's
        // thickness less a radius.
        let depth = out
            .centerline
            .chunks(3)
            .fold(0.0f32, |m, c| m.max(c[2].abs()))
            / (2.0 * out.yarn_radius);
        println!(
            "{name:20} interlock {}/{} ({:.3}) buckets {}/{} other {}/{} undecided {} free loops {}/{} free feet {}/{} clearance {:.3} p01 {:.3} cover {:.3} depth {depth:.2} prep {:.2}s",
            order.interlock_agree, order.interlock_decided, order.interlock(),
            order.buckets_half_front, order.buckets,
            order.agree - order.interlock_agree, order.decided - order.interlock_decided,
            order.undecided, order.free_loops, order.loops, order.free_feet, order.feet,
            cl.0, cl.1, c, prep
        );
        if let Some(d) = &order.first_disagreement {
            println!("    first: {d}");
        }
    }
}
