use glam::Vec3;
use knitwear::knit::{KnitParams, PreparedKnit};
use knitwear::metrics::{close_pairs, YarnPolyline, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS};
use knitwear::pattern::StitchPattern;
use knitwear::surface::PlaneSurface;
fn main() {
    let txt = std::fs::read_to_string(std::env::args().nth(1).unwrap()).unwrap();
    let pattern = StitchPattern::from_knitspeak(&txt).unwrap();
    println!("{}", pattern.chart());
    let plane = PlaneSurface {
        width: 0.2,
        height: 0.15,
    };
    let t = std::time::Instant::now();
    let p = KnitParams {
        measure_clearance: true,
        ..KnitParams::default()
    };
    let knit = PreparedKnit::new(&plane, &pattern, &p).unwrap();
    let out = knit.build(&plane).unwrap();
    let s = &out.stats;
    println!(
        "{:.2} s clearance {:?} flat {} sw {} sh {} courses {} wales {}",
        t.elapsed().as_secs_f64(),
        s.clearance,
        s.flat_clearance,
        s.stitch_width,
        s.stitch_height,
        s.courses,
        s.wales
    );
    let pts: Vec<Vec3> = out
        .centerline
        .chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect();
    let yarns: Vec<YarnPolyline> = out
        .yarn_offsets
        .windows(2)
        .zip(&out.yarn_closed)
        .map(|(w, &c)| YarnPolyline {
            points: &pts[w[0] as usize..w[1] as usize],
            closed: c,
        })
        .collect();
    let d = 2.0 * out.yarn_radius;
    let mut pairs = close_pairs(&yarns, d, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS, 0.6).unwrap();
    pairs.sort_by(|a, b| a.distance.total_cmp(&b.distance));
    // segment id -> (yarn, point)
    let mut starts = vec![];
    let mut acc = 0;
    for y in &yarns {
        starts.push(acc);
        acc += y.points.len() - 1;
    }
    let loc = |seg: usize| {
        let y = starts.iter().rposition(|&s| s <= seg).unwrap();
        let k = seg - starts[y];
        let p = yarns[y].points[k];
        (
            y,
            out.yarn_course[y],
            p.x / s.stitch_width,
            p.y / s.stitch_height,
            p.z / d,
        )
    };
    println!("pairs < 0.6: {}", pairs.len());
    for pr in pairs.iter().take(12) {
        let (ya, ca, wa, ra, za) = loc(pr.a);
        let (yb, cb, wb, rb, zb) = loc(pr.b);
        println!("{:.3}  A y{ya} c{ca} wale {wa:.2} row {ra:.2} z {za:.2} | B y{yb} c{cb} wale {wb:.2} row {rb:.2} z {zb:.2}", pr.distance);
    }
}
