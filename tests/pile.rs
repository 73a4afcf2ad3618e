//! Warp-knit plush (docs/design.md section 6): noise statistics, the slice criterion for every
//! pile, closed-form counts, determinism across thread counts, cheap camera updates equal to
//! full builds, and budget errors before allocation. Figures are printed (`--nocapture`), never
//! asserted on time.

use std::collections::HashSet;
use std::f32::consts::PI;
use std::time::Instant;

use glam::Vec3;
use knitwear::pile::fractal_noise::{base_noise, fractal_noise, NoiseField, NoiseParams};
use knitwear::pile::slices::{MASK_RECT, MASK_ROUND};
use knitwear::pile::{
    plush, Nominal, PileBuffers, PileColors, PileField, PileParams, PressMap, SliceCounts, View,
};
use knitwear::surface::{MeshSurface, PlaneSurface};
use knitwear::KnitError;

fn plane() -> PlaneSurface {
    PlaneSurface {
        width: 0.10,
        height: 0.08,
    }
}

fn params(courses: usize, wales: usize) -> PileParams {
    PileParams {
        courses: Some(courses),
        wales: Some(wales),
        seed: 7,
        ..Default::default()
    }
}

/// The eye of a perspective camera looking across the pile: the default pile leans 30 degrees
/// towards -v, and this eye, behind the pile 60 degrees above the fabric, sees most piles side
/// on (a mix of horizontal and vertical slices).
const SIDE_EYE: Vec3 = Vec3::new(0.05, 0.30, 0.15);

/// An eye close above the pile, from which the piles' ratios `2 r |cos a| / (l sin a)` run
/// from under to over the band where slice kinds mix (1 to 2).
const BAND_EYE: Vec3 = Vec3::new(0.05, 0.10, 0.10);

fn side_eye() -> View {
    View::Perspective { eye: SIDE_EYE }
}

/// Kolmogorov-Smirnov statistic of `samples` against the CDF `cdf`.
fn ks(mut samples: Vec<f64>, cdf: impl Fn(f64) -> f64) -> f64 {
    samples.sort_by(|a, b| a.total_cmp(b));
    let n = samples.len() as f64;
    samples
        .iter()
        .enumerate()
        .map(|(i, &x)| {
            let f = cdf(x);
            (f - i as f64 / n).abs().max((f - (i + 1) as f64 / n).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn base_noise_angles_follow_their_distributions() {
    let theta_max = 0.6f32;
    let p = NoiseParams {
        width: 256,
        height: 256,
        theta_max,
        scales: vec![1],
        seed: 42,
    };
    let noise = knitwear::parallel::run_in_pool(Some(2), || base_noise(&p))
        .unwrap()
        .unwrap();
    let thetas: Vec<f64> = noise
        .vectors
        .iter()
        .map(|v| (v.z.clamp(-1.0, 1.0) as f64).acos())
        .collect();
    let phis: Vec<f64> = noise
        .vectors
        .iter()
        .map(|v| {
            (v.y as f64)
                .atan2(v.x as f64)
                .rem_euclid(std::f64::consts::TAU)
        })
        .collect();
    for v in &noise.vectors {
        assert!((v.length() - 1.0).abs() < 1e-5);
    }
    let n = thetas.len() as f64;
    // Critical value of the KS statistic at the 0.1% level.
    let critical = 1.95 / n.sqrt();
    let d_theta = ks(thetas, |x| (x / theta_max as f64).clamp(0.0, 1.0));
    let d_phi = ks(phis, |x| (x / std::f64::consts::TAU).clamp(0.0, 1.0));
    println!(
        "base noise, {n} texels: KS D(theta ~ U(0, {theta_max})) = {d_theta:.5}, \
         D(phi ~ U(0, 2pi)) = {d_phi:.5}, critical (0.1%) = {critical:.5}"
    );
    assert!(d_theta < critical, "theta: D = {d_theta}");
    assert!(d_phi < critical, "phi: D = {d_phi}");
}

/// Mean angle (radians) between the deviations of horizontally and vertically neighbouring
/// texels, and the mean correlation of their x and y components.
fn neighbour_stats(f: &NoiseField) -> (f64, f64) {
    let (w, h) = (f.width, f.height);
    let mut angle = 0.0f64;
    let mut pairs = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let v = f.at(x, y);
            for (nx, ny) in [((x + 1) % w, y), (x, (y + 1) % h)] {
                let u = f.at(nx, ny);
                angle += (v.dot(u).clamp(-1.0, 1.0) as f64).acos();
                pairs.push((v, u));
            }
        }
    }
    let corr = |c: fn(Vec3) -> f32| {
        let n = pairs.len() as f64;
        let (ma, mb) = pairs.iter().fold((0.0, 0.0), |(a, b), (p, q)| {
            (a + c(*p) as f64 / n, b + c(*q) as f64 / n)
        });
        let (mut cov, mut va, mut vb) = (0.0, 0.0, 0.0);
        for (p, q) in &pairs {
            let (da, db) = (c(*p) as f64 - ma, c(*q) as f64 - mb);
            cov += da * db;
            va += da * da;
            vb += db * db;
        }
        cov / (va * vb).sqrt()
    };
    let r = 0.5 * (corr(|v| v.x) + corr(|v| v.y));
    (angle / pairs.len() as f64, r)
}

#[test]
fn fractal_noise_is_smooth_and_stays_within_theta_max() {
    let theta_max = 0.5f32;
    let mut p = NoiseParams {
        width: 192,
        height: 160,
        theta_max,
        scales: vec![1],
        seed: 3,
    };
    let base = fractal_noise(&p).unwrap();
    p.scales = vec![1, 2, 4, 8];
    let fractal = fractal_noise(&p).unwrap();
    let (base_angle, base_r) = neighbour_stats(&base);
    let (frac_angle, frac_r) = neighbour_stats(&fractal);
    println!(
        "neighbouring texels: base noise mean angle {:.2} deg, correlation {base_r:.3}; \
         fractal (1,2,4,8) mean angle {:.2} deg, correlation {frac_r:.3}; \
         angle ratio {:.2}, correlation margin {:.3}",
        base_angle.to_degrees(),
        frac_angle.to_degrees(),
        frac_angle / base_angle,
        frac_r - base_r
    );
    assert!(base_r.abs() < 0.05);
    assert!(frac_r > base_r + 0.5, "correlation {frac_r} vs {base_r}");
    assert!(frac_angle < 0.5 * base_angle);
    let cos_max = theta_max.cos() - 1e-6;
    for v in &fractal.vectors {
        assert!((v.length() - 1.0).abs() < 1e-5);
        assert!(v.z >= cos_max, "{v} strays beyond theta_max");
    }
    // The noise image is the paper's (x + 1) / 2 mapping.
    let rgb = fractal.to_rgb();
    assert_eq!(rgb.len(), 3 * fractal.vectors.len());
    for (c, v) in rgb.chunks_exact(3).zip(&fractal.vectors) {
        assert!(((c[0] * 2.0 - 1.0) - v.x).abs() < 1e-6);
        assert!(c.iter().all(|x| (0.0..=1.0).contains(x)));
    }
    assert_eq!(fractal.to_rgb8().len(), rgb.len());
    // A texel's base draw does not depend on the texture size.
    let small = fractal_noise(&NoiseParams {
        width: 10,
        height: 10,
        scales: vec![1],
        ..p.clone()
    })
    .unwrap();
    assert_eq!(small.at(3, 4), base.at(3, 4));
}

#[test]
fn pile_directions_stay_within_theta_max_of_the_nominal_direction() {
    let mut p = params(30, 40);
    p.theta_max = 0.4;
    p.nominal = Nominal::Lean {
        angle: 0.5,
        azimuth: 1.0,
    };
    let field = PileField::new(&plane(), &p).unwrap();
    let t = Vec3::new(
        0.5f32.sin() * 1.0f32.cos(),
        0.5f32.sin() * 1.0f32.sin(),
        0.5f32.cos(),
    );
    let mut largest = 0.0f32;
    for pile in &field.piles {
        // On the plane the fabric frame is the world frame.
        assert!((pile.a - Vec3::X).length() < 1e-5 && (pile.b - Vec3::Y).length() < 1e-5);
        largest = largest.max(pile.t.dot(t).clamp(-1.0, 1.0).acos());
    }
    println!("largest pile deviation {largest:.4} rad (theta_max 0.4)");
    assert!(largest <= 0.4 + 1e-4);
    assert!(largest > 0.1);
}

/// The criterion, recomputed from scratch: horizontal iff 2 r |cos a| >= k l sin a, with
/// `k = 1 + blend` the pile's threshold across the band (ratios 1 to 2) where the kinds mix.
fn expect_horizontal(root: Vec3, t: Vec3, eye: Vec3, r: f32, l: f32, blend: f32) -> bool {
    let to_eye = (eye - root).normalize();
    let alpha = t.dot(to_eye).clamp(-1.0, 1.0).acos();
    2.0 * r * alpha.cos().abs() >= (1.0 + blend) * l * alpha.sin()
}

#[test]
fn slice_choice_matches_the_criterion_for_every_pile() {
    let eye = BAND_EYE;
    let out = plush(&plane(), &params(40, 50), &View::Perspective { eye }).unwrap();
    let (field, b) = (&out.field, &out.buffers);
    let (r, l) = (field.pile_radius, field.slice_spacing());
    let s = field.slices;
    let mut disagree = 0;
    // [vertical, horizontal] counts of piles under the band, in it and over it.
    let mut kinds = [[0usize; 2]; 3];
    for (i, pile) in field.piles.iter().enumerate() {
        assert!((0.0..1.0).contains(&pile.blend));
        let want = expect_horizontal(pile.root, pile.t, eye, r, l, pile.blend);
        // Only a pile within rounding of the boundary may go either way.
        let to_eye = (eye - pile.root).normalize();
        let a = pile.t.dot(to_eye).acos();
        let k = 1.0 + pile.blend;
        let margin = (2.0 * r * a.cos().abs() - k * l * a.sin()).abs();
        if (b.horizontal[i] == 1) != want {
            assert!(margin < 1e-6, "pile {i}: margin {margin}");
            disagree += 1;
        }
        let ratio = 2.0 * r * a.cos().abs() / (l * a.sin());
        let bin = if ratio < 1.0 {
            0
        } else if ratio < 2.0 {
            1
        } else {
            2
        };
        kinds[bin][b.horizontal[i] as usize] += 1;
        // The geometry is the chosen kind.
        let corners = |q: usize| -> [Vec3; 4] {
            let v = 4 * (i * s + q);
            std::array::from_fn(|k| Vec3::from_slice(&b.positions[3 * (v + k)..3 * (v + k) + 3]))
        };
        for q in 0..s {
            let c = corners(q);
            let m = b.mask[4 * (i * s + q)];
            if b.horizontal[i] == 1 {
                assert_eq!(m, MASK_ROUND);
                // Parallel to the fabric (z = 0 plane), centred on the axis.
                assert!((c[0].z - c[2].z).abs() < 1e-6 && (c[1].z - c[3].z).abs() < 1e-6);
                let centre = (c[0] + c[2]) * 0.5;
                let want = pile.root + pile.t * l * (q as f32 + 0.5);
                assert!((centre - want).length() < 1e-6);
                assert!(((c[1] - c[0]).length() - 2.0 * r).abs() < 1e-6);
            } else {
                assert_eq!(m, MASK_RECT);
                // Contains the axis segment, width 2r across it, facing the eye.
                let ps = pile.root + pile.t * l * q as f32;
                let pe = pile.root + pile.t * l * (q as f32 + 1.0);
                assert!(((c[0] + c[1]) * 0.5 - ps).length() < 1e-6);
                assert!(((c[2] + c[3]) * 0.5 - pe).length() < 1e-6);
                assert!(((c[1] - c[0]).length() - 2.0 * r).abs() < 1e-6);
                let normal = (c[1] - c[0]).cross(c[3] - c[0]);
                assert!(normal.dot(eye - ps) > 0.0);
                assert!((c[1] - c[0]).dot(pile.t).abs() < 1e-6);
            }
        }
    }
    let h = b.stats.horizontal;
    println!(
        "camera across the pile: {h} horizontal, {} vertical of {} piles; {disagree} on the boundary",
        b.stats.vertical,
        field.piles.len()
    );
    println!("[vertical, horizontal] under, in and over the band: {kinds:?}");
    assert!(
        h > 0 && b.stats.vertical > 0,
        "the camera should see both kinds"
    );
    // Under the band never horizontal (it would show gaps), over it always; in it, both.
    assert_eq!(kinds[0][1], 0);
    assert_eq!(kinds[2][0], 0);
    assert!(
        kinds[1][0] > 50 && kinds[1][1] > 50,
        "the band mixes the kinds: {kinds:?}"
    );
    assert_eq!(h + b.stats.vertical, field.piles.len());
    assert_eq!(h, b.horizontal.iter().filter(|x| **x == 1).count());

    // Straight above an untilted pile: all horizontal; level with the fabric: all vertical.
    let mut p = params(10, 10);
    p.nominal = Nominal::Direction(Vec3::Z);
    p.theta_max = 0.0;
    let top = plush(&plane(), &p, &View::AlongNormal).unwrap();
    assert_eq!(top.buffers.stats.vertical, 0);
    let side = top
        .field
        .view(
            &View::Orthographic {
                direction: Vec3::new(0.0, 1.0, 0.0),
            },
            None,
        )
        .unwrap();
    assert_eq!(side.horizontal_count, 0);
}

fn check_topology(b: &PileBuffers, counts: &SliceCounts) {
    let (v, t, e) = (
        counts.vertices as usize,
        counts.triangles as usize,
        counts.edges as usize,
    );
    assert_eq!(b.positions.len(), 3 * v);
    assert_eq!(b.colors.len(), 4 * v);
    assert_eq!(b.uvs.len(), 2 * v);
    assert_eq!(b.mask.len(), v);
    assert_eq!(b.triangles.len(), 3 * t);
    assert_eq!(b.corner_edges.len(), counts.corner_edges as usize);
    assert_eq!(b.edges.len(), 2 * e);
    assert_eq!(b.horizontal.len(), counts.piles as usize);
    assert_eq!((b.stats.vertices, b.stats.triangles), (v, t));
    let edges: Vec<(i32, i32)> = b
        .edges
        .chunks_exact(2)
        .map(|c| (c[0].min(c[1]), c[0].max(c[1])))
        .collect();
    assert_eq!(
        edges.iter().collect::<HashSet<_>>().len(),
        e,
        "an edge twice"
    );
    let mut used = vec![false; e];
    for (tri, ce) in b
        .triangles
        .chunks_exact(3)
        .zip(b.corner_edges.chunks_exact(3))
    {
        for k in 0..3 {
            let (a, c) = (tri[k], tri[(k + 1) % 3]);
            assert!(a >= 0 && (a as usize) < v);
            let edge = edges[ce[k] as usize];
            assert_eq!(edge, (a.min(c), a.max(c)));
            used[ce[k] as usize] = true;
        }
    }
    assert!(used.iter().all(|u| *u), "an edge no triangle uses");
    assert!(b.positions.iter().all(|x| x.is_finite()));
    assert!(b.colors.iter().all(|x| (0.0..=1.0).contains(x)));
}

#[test]
fn counts_match_the_closed_forms() {
    let mut keys = HashSet::new();
    for (ppst, slices) in [(1, 8), (4, 3), (3, 1)] {
        let mut p = params(12, 9);
        p.piles_per_stitch = ppst;
        p.slices = slices;
        let out = plush(&plane(), &p, &side_eye()).unwrap();
        let counts = SliceCounts::of((12 * 9 * ppst) as u64, slices as u64);
        assert_eq!(out.field.counts(), counts);
        check_topology(&out.buffers, &counts);
        assert!(keys.insert(out.buffers.stats.topology_key));
        // Root darker than tip.
        let c = &out.buffers.colors;
        assert!(slices == 1 || c[0] < c[16 * (slices - 1)]);
    }
}

/// Each root lies at random within its own cell of the pile grid (no rows or columns for a
/// renderer to draw as a grid), and the piles' thresholds across the slice band cover `[0, 1)`
/// evenly, so the change of slice kind is spread over the band rather than drawn as a line.
#[test]
fn roots_stray_within_their_cells_and_blends_cover_the_band() {
    let (courses, wales) = (40, 50);
    let out = plush(&plane(), &params(courses, wales), &side_eye()).unwrap();
    let field = &out.field;
    assert_eq!(field.root_uvs.len(), courses * wales);
    let mut offsets = Vec::new();
    for (idx, uv) in field.root_uvs.iter().enumerate() {
        let (i, j) = (idx / wales, idx % wales);
        // Offset from the cell's centre, in cells.
        let du = uv.x * wales as f32 - (j as f32 + 0.5);
        let dv = uv.y * courses as f32 - (i as f32 + 0.5);
        assert!(
            du.abs() <= 0.5 + 1e-4 && dv.abs() <= 0.5 + 1e-4,
            "pile {idx}: {du}, {dv}"
        );
        offsets.push((du as f64, dv as f64));
    }
    // Uniform over the cell each way: standard deviation 1 / sqrt(12) = 0.289, and the
    // two ways independent of each other and of the neighbour's.
    let n = offsets.len() as f64;
    let sd = |f: &dyn Fn(&(f64, f64)) -> f64| {
        (offsets.iter().map(|o| f(o).powi(2)).sum::<f64>() / n).sqrt()
    };
    let (sd_u, sd_v) = (sd(&|o| o.0), sd(&|o| o.1));
    let cross = offsets.iter().map(|o| o.0 * o.1).sum::<f64>() / n / (sd_u * sd_v);
    let next = offsets.windows(2).map(|w| w[0].0 * w[1].0).sum::<f64>() / n / (sd_u * sd_u);
    println!("root offsets: sd {sd_u:.3} x {sd_v:.3} cells, correlation {cross:.3}, with the neighbour {next:.3}");
    for s in [sd_u, sd_v] {
        assert!((s - 0.289).abs() < 0.02, "offset spread {s}");
    }
    assert!(cross.abs() < 0.1 && next.abs() < 0.1);
    let blends: Vec<f64> = field.piles.iter().map(|p| p.blend as f64).collect();
    assert!(blends.iter().all(|b| (0.0..1.0).contains(b)));
    let d = ks(blends, |x| x.clamp(0.0, 1.0));
    println!("blend KS statistic {d:.4} over {} piles", field.piles.len());
    assert!(d < 0.04);

    // Another seed, other places; the same seed, the same ones.
    let again = plush(&plane(), &params(courses, wales), &side_eye()).unwrap();
    assert_eq!(again.field.root_uvs, field.root_uvs);
    let mut other = params(courses, wales);
    other.seed = 8;
    let moved = plush(&plane(), &other, &side_eye()).unwrap();
    assert_ne!(moved.field.root_uvs, field.root_uvs);
}

#[test]
fn piles_outside_the_uv_islands_are_skipped() {
    // One triangle: the UV square's lower-right half.
    let pos = [0.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.1, 0.1, 0.0];
    let nrm = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
    let uvs = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0];
    let mesh = MeshSurface::new(&pos, &nrm, &[0, 1, 2], &uvs).unwrap();
    let out = plush(&mesh, &params(20, 20), &side_eye()).unwrap();
    let s = &out.buffers.stats;
    println!(
        "half-island mesh: {} piles, {} skipped",
        s.piles, s.piles_skipped
    );
    assert_eq!(s.piles + s.piles_skipped, 400);
    assert!(s.piles_skipped > 150 && s.piles > 150);
    check_topology(&out.buffers, &out.field.counts());
    for uv in &out.field.root_uvs {
        assert!(uv.x >= uv.y);
    }
}

#[test]
fn output_is_bit_identical_for_any_thread_count() {
    let runs: Vec<_> = [1, 2, 8]
        .iter()
        .map(|&t| {
            let mut p = params(37, 29);
            p.piles_per_stitch = 2;
            p.threads = Some(t);
            plush(&plane(), &p, &side_eye()).unwrap()
        })
        .collect();
    for r in &runs[1..] {
        let (a, b) = (&runs[0].buffers, &r.buffers);
        assert_eq!(a.positions, b.positions);
        assert_eq!(a.colors, b.colors);
        assert_eq!(a.triangles, b.triangles);
        assert_eq!(a.edges, b.edges);
        assert_eq!(a.corner_edges, b.corner_edges);
        assert_eq!(a.uvs, b.uvs);
        assert_eq!(a.mask, b.mask);
        assert_eq!(a.horizontal, b.horizontal);
        assert_eq!(runs[0].field.noise, r.field.noise);
    }
    let mut p = params(37, 29);
    p.piles_per_stitch = 2;
    p.seed = 8;
    let other = plush(&plane(), &p, &side_eye()).unwrap();
    assert_ne!(other.buffers.positions, runs[0].buffers.positions);
}

#[test]
fn camera_update_equals_a_full_build() {
    let p = params(24, 30);
    let first = View::Perspective {
        eye: Vec3::new(0.3, 0.2, 0.5),
    };
    let views = [
        side_eye(),
        View::Orthographic {
            direction: Vec3::new(0.2, 1.0, -0.15),
        },
        View::AlongNormal,
    ];
    let mut out = plush(&plane(), &p, &first).unwrap();
    for view in views {
        let full = plush(&plane(), &p, &view).unwrap().buffers;
        out.field.update(&view, &mut out.buffers, Some(2)).unwrap();
        let mut updated = out.buffers.clone();
        updated.stats.seconds = full.stats.seconds;
        assert_eq!(updated, full);
        let fresh = out.field.view(&view, Some(1)).unwrap();
        assert_eq!(fresh.positions, full.positions);
        assert_eq!(fresh.mask, full.mask);
        assert_eq!(fresh.horizontal, full.horizontal);
        assert_eq!(fresh.horizontal_count, full.stats.horizontal);
    }
    // Buffers of another field are refused.
    let other = plush(&plane(), &params(5, 5), &first).unwrap();
    let mut b = other.buffers;
    assert!(matches!(
        out.field.update(&first, &mut b, None),
        Err(KnitError::Parameter(_))
    ));
}

#[test]
fn press_bends_the_pile_towards_the_fabric() {
    // Left half pressed.
    let mut weights = vec![0.0f32; 8 * 8];
    for y in 0..8 {
        for x in 0..3 {
            weights[y * 8 + x] = 1.0;
        }
    }
    let mut p = params(20, 20);
    p.press = Some(PressMap::new(8, 8, weights).unwrap());
    p.press_azimuth = Some(0.0);
    let field = PileField::new(&plane(), &p).unwrap();
    let (mut pressed, mut free) = (Vec::new(), Vec::new());
    for (pile, uv) in field.piles.iter().zip(&field.root_uvs) {
        if uv.x < 0.3 {
            pressed.push(pile.t.z);
        } else if uv.x > 0.5 {
            free.push(pile.t.z);
        }
    }
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    println!(
        "mean pile elevation (z of direction): pressed {:.3}, free {:.3}",
        mean(&pressed),
        mean(&free)
    );
    assert!(mean(&pressed) < 0.5 * mean(&free));
    assert!(pressed.iter().all(|z| *z > 0.0));
    assert!(PressMap::new(2, 2, vec![0.0, 0.5, 1.5, 0.0]).is_err());
    assert!(PressMap::new(2, 2, vec![0.0, f32::NAN, 1.0, 0.0]).is_err());
}

#[test]
fn colours_per_stitch_and_from_patterns() {
    let mut p = params(2, 3);
    let cs: Vec<[f32; 3]> = (0..6).map(|i| [i as f32 / 10.0, 0.5, 0.5]).collect();
    p.colors = PileColors::PerStitch(cs);
    p.slices = 2;
    let out = plush(&plane(), &p, &View::AlongNormal).unwrap();
    // Pile (course 1, wale 2) is stitch 5; its first slice is darkened by the root shade.
    let pile = 5;
    let c = out.buffers.colors[16 * 2 * pile];
    let shade = knitwear::pile::slices::ROOT_SHADE
        + (knitwear::pile::slices::TIP_SHADE - knitwear::pile::slices::ROOT_SHADE) * 0.25;
    assert!((c - 0.5 * shade).abs() < 1e-6);
    p.colors = PileColors::PerStitch(vec![[0.1; 3]; 5]);
    assert!(matches!(
        PileField::new(&plane(), &p),
        Err(KnitError::Parameter(_))
    ));
}

#[test]
fn bad_settings_are_parameter_errors() {
    let nan = f32::NAN;
    type Mutation = Box<dyn Fn(&mut PileParams)>;
    let cases: Vec<Mutation> = vec![
        Box::new(|p| p.slices = 0),
        Box::new(|p| p.slices = 1000),
        Box::new(|p| p.piles_per_stitch = 0),
        Box::new(|p| p.theta_max = PI / 4.0),
        Box::new(move |p| p.theta_max = nan),
        Box::new(|p| p.noise_scales = vec![]),
        Box::new(|p| p.noise_scales = vec![1, 0]),
        Box::new(|p| p.noise_size = Some((0, 4))),
        Box::new(move |p| p.pile_length = Some(nan)),
        Box::new(|p| p.pile_radius = Some(-1.0)),
        Box::new(|p| p.gauge = Some((0.0, 10.0))),
        Box::new(|p| p.courses = Some(0)),
        Box::new(move |p| {
            p.nominal = Nominal::Lean {
                angle: nan,
                azimuth: 0.0,
            }
        }),
        Box::new(|p| {
            p.nominal = Nominal::Lean {
                angle: 2.0,
                azimuth: 0.0,
            }
        }),
        Box::new(|p| p.nominal = Nominal::Direction(Vec3::new(0.0, 0.0, -1.0))),
        Box::new(|p| p.nominal = Nominal::Direction(Vec3::ZERO)),
        Box::new(|p| p.press_strength = 2.0),
        Box::new(move |p| p.press_azimuth = Some(nan)),
        Box::new(move |p| p.colors = PileColors::Solid([nan, 0.0, 0.0])),
        Box::new(|p| p.threads = Some(0)),
    ];
    for (i, mutate) in cases.iter().enumerate() {
        let mut p = params(4, 4);
        mutate(&mut p);
        match PileField::new(&plane(), &p) {
            Err(KnitError::Parameter(msg)) => assert!(!msg.is_empty()),
            other => panic!("case {i}: expected a parameter error, got {other:?}"),
        }
    }
    let field = PileField::new(&plane(), &params(4, 4)).unwrap();
    for view in [
        View::Perspective {
            eye: Vec3::new(nan, 0.0, 1.0),
        },
        View::Orthographic {
            direction: Vec3::ZERO,
        },
        View::Orthographic {
            direction: Vec3::new(f32::INFINITY, 0.0, 0.0),
        },
    ] {
        assert!(matches!(
            field.build(&view, None, u64::MAX),
            Err(KnitError::Parameter(_))
        ));
    }
    // An eye exactly on a root does not break anything.
    let root = field.piles[0].root;
    let b = field
        .build(&View::Perspective { eye: root }, None, u64::MAX)
        .unwrap();
    assert!(b.positions.iter().all(|x| x.is_finite()));
    // A degenerate surface.
    let flat = PlaneSurface {
        width: 0.0,
        height: 0.1,
    };
    assert!(matches!(
        PileField::new(&flat, &params(4, 4)),
        Err(KnitError::Surface(_))
    ));
}

#[test]
fn absurd_requests_fail_before_allocating() {
    let start = Instant::now();
    let mut p = params(1_000_000, 1_000_000);
    assert!(matches!(
        PileField::new(&plane(), &p),
        Err(KnitError::Budget(_))
    ));
    p = params(100, 100);
    p.budget_bytes = 1000;
    match PileField::new(&plane(), &p) {
        Err(KnitError::Budget(msg)) => assert!(msg.contains("budget"), "{msg}"),
        other => panic!("expected a budget error, got {other:?}"),
    }
    p = params(100, 100);
    p.noise_size = Some((1 << 15, 1 << 15));
    p.budget_bytes = 1 << 30;
    assert!(matches!(
        PileField::new(&plane(), &p),
        Err(KnitError::Budget(_))
    ));
    p = params(10, 10);
    p.gauge = Some((1e9, 1e9));
    p.courses = None;
    assert!(matches!(
        PileField::new(&plane(), &p),
        Err(KnitError::Budget(_))
    ));
    println!(
        "absurd requests refused in {:.2} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
}

#[test]
fn the_papers_384_by_240_fabric() {
    // The paper's figure 7: 384 courses x 240 wales, one pile per stitch, about 750 ms on a
    // 2016 GPU. A 24 x 30 cm cushion top.
    let surface = PlaneSurface {
        width: 0.24,
        height: 0.30,
    };
    let mut p = params(384, 240);
    let press: Vec<f32> = (0..64 * 64)
        .map(|i| {
            let (x, y) = ((i % 64) as f32 / 63.0 - 0.5, (i / 64) as f32 / 63.0 - 0.5);
            (1.0 - (x * x + y * y) * 8.0).clamp(0.0, 1.0)
        })
        .collect();
    p.press = Some(PressMap::new(64, 64, press).unwrap());
    let threads = knitwear::parallel::default_threads();
    // Warm the pool, then measure.
    let _ = plush(&surface, &params(8, 8), &side_eye()).unwrap();
    let start = Instant::now();
    let out = plush(&surface, &p, &side_eye()).unwrap();
    let core = start.elapsed().as_secs_f64();
    let s = &out.buffers.stats;
    let views = [
        View::Perspective {
            eye: Vec3::new(0.5, 0.6, 0.3),
        },
        View::Orthographic {
            direction: Vec3::new(0.0, 1.0, -0.2),
        },
        View::Perspective {
            eye: Vec3::new(0.12, 0.15, 0.6),
        },
    ];
    let mut buffers = out.buffers.clone();
    let mut update = f64::INFINITY;
    for v in &views {
        let t = Instant::now();
        out.field.update(v, &mut buffers, None).unwrap();
        update = update.min(t.elapsed().as_secs_f64());
    }
    let t = Instant::now();
    let fresh = out.field.view(&views[0], None).unwrap();
    let view_alloc = t.elapsed().as_secs_f64();
    println!(
        "384 x 240 plush on {threads} threads: {} piles x {} slices, {} vertices, {} triangles \
         ({} horizontal, {} vertical): core {:.1} ms (field {:.1} ms); camera update in place \
         {:.1} ms (best of 3), into new buffers {:.1} ms",
        s.piles,
        s.slices,
        s.vertices,
        s.triangles,
        s.horizontal,
        s.vertical,
        core * 1e3,
        out.field.stats.seconds * 1e3,
        update * 1e3,
        view_alloc * 1e3,
    );
    assert_eq!(s.piles, 384 * 240);
    assert_eq!(fresh.positions.len(), buffers.positions.len());
}
