//! End-to-end tests of the core pipeline: planted answers, closed-form counts, determinism,
//! clearance on the surfaces a user knits, and errors before allocation.

use std::f32::consts::{PI, TAU};
use std::time::Instant;

use glam::{Vec2, Vec3};
use knitwear::geometry::bundle_counts;
use knitwear::knit::{knit, measure, KnitOutput, KnitParams};
use knitwear::lattice::Tile;
use knitwear::pattern::{ColorPattern, StitchPattern};
use knitwear::skeleton::key_points;
use knitwear::surface::{GridSurface, MeshSurface, Surface};
use knitwear::KnitError;

mod common;
use common::surfaces::grid;

fn sheet() -> GridSurface {
    // 12 x 10 cm, gently waved: 24 wales x 28 courses at the default gauge.
    grid(40, 40, false, |u, v| {
        let z = 0.005 * (TAU * u).sin();
        let dz = 0.005 * TAU * (TAU * u).cos() / 0.12;
        (
            Vec3::new(0.12 * u, 0.10 * v, z),
            Vec3::new(-dz, 0.0, 1.0).normalize(),
        )
    })
}

fn cylinder() -> GridSurface {
    // Radius 3 cm, 8 cm tall, knitted in the round (cyclic u).
    grid(16, 96, true, |u, v| {
        let a = TAU * u;
        (
            Vec3::new(0.03 * a.cos(), 0.03 * a.sin(), 0.08 * v),
            Vec3::new(a.cos(), a.sin(), 0.0),
        )
    })
}

fn sphere_band() -> GridSurface {
    // Radius 5 cm between latitudes -50 and +50 degrees (the poles are the stability issue's).
    grid(80, 128, true, |u, v| {
        let a = TAU * u;
        let lat = (v - 0.5) * (100.0f32).to_radians();
        let n = Vec3::new(lat.cos() * a.cos(), lat.cos() * a.sin(), lat.sin());
        (0.05 * n, n)
    })
}

fn uv_mesh() -> MeshSurface {
    // A 10 x 10 cm sheet, bent into a shallow arc, as a triangle mesh with UVs = (x, y) / size.
    let k = 20;
    let (mut p, mut n, mut t, mut uv) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for i in 0..=k {
        for j in 0..=k {
            let (u, v) = (j as f32 / k as f32, i as f32 / k as f32);
            let a = (u - 0.5) * 0.8;
            p.extend([0.125 * a.sin(), 0.10 * v, 0.125 * a.cos()]);
            n.extend([a.sin(), 0.0, a.cos()]);
        }
    }
    let id = |i: usize, j: usize| (i * (k + 1) + j) as u32;
    let uv_of = |i: usize, j: usize| [j as f32 / k as f32, i as f32 / k as f32];
    for i in 0..k {
        for j in 0..k {
            for tri in [
                [(i, j), (i, j + 1), (i + 1, j + 1)],
                [(i, j), (i + 1, j + 1), (i + 1, j)],
            ] {
                for (a, b) in tri {
                    t.push(id(a, b));
                    uv.extend(uv_of(a, b));
                }
            }
        }
    }
    MeshSurface::new(&p, &n, &t, &uv).unwrap()
}

fn params() -> KnitParams {
    KnitParams {
        threads: Some(2),
        ..KnitParams::default()
    }
}

#[test]
fn key_points_are_the_papers() {
    let t = Tile {
        n0: Vec2::new(0.0, 1.0),
        n1: Vec2::new(1.0, 1.0),
        n2: Vec2::new(1.0, 0.0),
        n3: Vec2::new(0.0, 0.0),
        n4: Vec2::new(0.0, 2.0),
    };
    let k = key_points(&t, &knitwear::skeleton::LoopShape::PAPER);
    let want = [
        (0.0, -0.35),
        (0.375, 0.0),
        (0.125, 1.0),
        (0.5, 1.35),
        (0.875, 1.0),
        (0.625, 0.0),
    ];
    for (got, (x, y)) in k.iter().zip(want) {
        assert!(
            (*got - Vec2::new(x, y)).length() < 1e-6,
            "{got:?} != ({x}, {y})"
        );
    }
}

fn assert_topology(out: &KnitOutput, m: usize) {
    let nv = out.positions.len() / 3;
    let nt = out.triangles.len() / 3;
    let ne = out.edges.len() / 2;
    assert_eq!(out.colors.len(), 4 * nv);
    assert_eq!(out.corner_edges.len(), 3 * nt);
    // Counts from the closed forms, piece by piece.
    let mut want = (0, 0, 0);
    for (w, &closed) in out.yarn_offsets.windows(2).zip(&out.yarn_closed) {
        let c = bundle_counts((w[1] - w[0]) as usize, m, closed);
        want = (want.0 + c.vertices, want.1 + c.triangles, want.2 + c.edges);
    }
    assert_eq!((nv, nt, ne), want);
    // Every corner's edge joins that corner's vertex and the next corner's vertex.
    let mut used = vec![0u8; ne];
    for f in 0..nt {
        for c in 0..3 {
            let a = out.triangles[3 * f + c];
            let b = out.triangles[3 * f + (c + 1) % 3];
            let e = out.corner_edges[3 * f + c] as usize;
            let (x, y) = (out.edges[2 * e], out.edges[2 * e + 1]);
            assert!((x, y) == (a, b) || (x, y) == (b, a), "face {f} corner {c}");
            used[e] = used[e].saturating_add(1);
        }
    }
    // No edge is listed twice and every edge is used (ring edges by two faces, apex edges by one).
    assert!(used.iter().all(|&u| u == 1 || u == 2));
    let mut sorted: Vec<(i32, i32)> = out
        .edges
        .chunks(2)
        .map(|e| (e[0].min(e[1]), e[0].max(e[1])))
        .collect();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(sorted.len(), ne, "duplicate edges");
    assert!(out
        .positions
        .iter()
        .chain(&out.colors)
        .all(|x| x.is_finite()));
}

#[test]
fn counts_and_topology_match_the_closed_forms() {
    for m in [3, 6, 9] {
        let p = KnitParams {
            ring_segments: m,
            samples_per_loop: 13,
            courses: Some(7),
            wales: Some(9),
            ..params()
        };
        let out = knit(&sheet(), &StitchPattern::preset("seed").unwrap(), &p).unwrap();
        assert_eq!(out.stats.stitches, 63);
        // Seven courses, a cast-on and a bind-off.
        assert_eq!(out.yarn_offsets.len(), 7 + 2 + 1);
        assert_topology(&out, m);
        // Closed courses on a cylinder: as many ring pairs as rings.
        let out = knit(&cylinder(), &StitchPattern::preset("rib_2x2").unwrap(), &p).unwrap();
        assert!(out.yarn_closed.iter().all(|&c| c));
        assert_topology(&out, m);
    }
}

#[test]
fn bit_identical_with_1_2_and_8_threads() {
    let pattern = StitchPattern::preset("rib_1x1").unwrap();
    let colors = ColorPattern::stripes(vec![[0.8, 0.1, 0.1], [0.1, 0.1, 0.8]], 3).unwrap();
    let run = |threads| {
        let p = KnitParams {
            threads: Some(threads),
            seed: 7,
            colors: Some(colors.clone()),
            ..KnitParams::default()
        };
        knit(&sphere_band(), &pattern, &p).unwrap()
    };
    let a = run(1);
    for t in [2, 8] {
        let b = run(t);
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a.positions), bits(&b.positions), "{t} threads");
        assert_eq!(bits(&a.colors), bits(&b.colors));
        assert_eq!(bits(&a.centerline), bits(&b.centerline));
        assert_eq!(a.triangles, b.triangles);
        assert_eq!(a.edges, b.edges);
    }
    // And a different seed changes the fluff but not the skeleton.
    let p = KnitParams {
        threads: Some(2),
        seed: 8,
        colors: Some(colors),
        ..KnitParams::default()
    };
    let c = knit(&sphere_band(), &pattern, &p).unwrap();
    assert_eq!(a.centerline, c.centerline);
    assert_ne!(a.positions, c.positions);
}

/// Largest distance of a centreline sample from the surface point it was mapped from is not
/// known after the fact; instead bound it against the nearest surface sample's normal offset.
fn max_offset_from_plane_like(out: &KnitOutput, surface: &dyn Surface) -> f32 {
    // Project each sample back by the surface's own parameterisation: for the flat sheet
    // only. Used on the sheet test.
    let _ = surface;
    out.centerline
        .chunks(3)
        .map(|c| {
            let x = c[0] / 0.12;
            let z0 = 0.005 * (TAU * x).sin();
            (c[2] - z0).abs()
        })
        .fold(0.0, f32::max)
}

/// The clearance plain knit/purl textures keep at default settings, in diameters, with every
/// course interlocked. The earlier floor of 0.95 was reached by stacking the courses (sinkers
/// and leg tops flipped to the wrong side); inside the interlock the tuned loops keep
/// 0.86-0.97 on the sheet and less on curved surfaces, and 0.95 is the open work of
/// "Knitted, not stacked".
const PLAIN_FLOOR: f32 = 0.4;

/// The same with the irregularity of hand knitting up to the largest kappa.
const KAPPA_FLOOR: f32 = 0.3;

#[test]
fn clearance_at_default_settings_on_four_surfaces() {
    let surfaces: Vec<(&str, Box<dyn Surface>)> = vec![
        ("sheet", Box::new(sheet())),
        ("cylinder", Box::new(cylinder())),
        ("sphere band", Box::new(sphere_band())),
        ("uv mesh", Box::new(uv_mesh())),
    ];
    for name in ["stockinette", "garter", "rib_1x1", "rib_2x2", "seed"] {
        let pattern = StitchPattern::preset(name).unwrap();
        for (sname, s) in &surfaces {
            let out = knit(s.as_ref(), &pattern, &params()).unwrap();
            let (min, p01) = measure(&out);
            let st = &out.stats;
            println!(
                "{name:12} {sname:12} {}x{} clearance min {min:.3} p01 {p01:.3}",
                st.courses, st.wales
            );
            assert!(min >= PLAIN_FLOOR, "{name} on {sname}: clearance {min}");
            // The default yarn is a quarter of a stitch wide.
            assert!(2.0 * out.yarn_radius >= 0.25 * st.stitch_width * 0.999);
            assert!(st.stitches_skipped == 0 || *sname == "uv mesh");
        }
    }
}

#[test]
fn fabric_is_at_most_seven_diameters_thick() {
    let out = knit(
        &sheet(),
        &StitchPattern::preset("garter").unwrap(),
        &params(),
    )
    .unwrap();
    let d = 2.0 * out.yarn_radius;
    // Centrelines within 3 diameters of the surface. The tuned offsets reach one and a half
    // diameters (the quarter-stitch yarn needs the depth to clear), and interlocked garter
    // needs the contact relief on top of them (2.85 measured; 1.76 with the fifth-of-a-stitch
    // yarn and offsets within one diameter), which thickens the fabric to about 6.7
    // diameters: far thicker than real garter (about 3), one of the loop shapes that
    // "Knitted, not stacked" still has to relax.
    let off = max_offset_from_plane_like(&out, &sheet());
    assert!(off <= 3.0 * d, "max normal offset {off} for diameter {d}");
}

#[test]
fn stitches_outside_uv_islands_are_not_built() {
    // One triangle covering half the UV square: stitches in the other half have no surface.
    let p = [0.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.1, 0.1, 0.0, 0.0, 0.1, 0.0];
    let n = [0.0, 0.0, 1.0].repeat(4);
    let t = [0u32, 1, 2, 0, 2, 3];
    let uv = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let full = MeshSurface::new(&p, &n, &t, &uv).unwrap();
    let half = MeshSurface::new(&p, &n, &t[..3], &uv[..6]).unwrap();
    let pr = KnitParams {
        courses: Some(12),
        wales: Some(12),
        ..params()
    };
    let pattern = StitchPattern::preset("stockinette").unwrap();
    let a = knit(&full, &pattern, &pr).unwrap();
    let b = knit(&half, &pattern, &pr).unwrap();
    assert_eq!(a.stats.stitches_skipped, 0);
    assert!(
        b.stats.stitches_skipped > 50 && b.stats.stitches > 40,
        "{:?}",
        b.stats
    );
    assert_topology(&b, 6);
}

#[test]
fn absurd_requests_fail_fast_with_the_size() {
    let pattern = StitchPattern::preset("stockinette").unwrap();
    let t = Instant::now();
    let p = KnitParams {
        courses: Some(1_000_000),
        wales: Some(1_000),
        ..params()
    };
    match knit(&sheet(), &pattern, &p) {
        Err(KnitError::Budget(msg)) => assert!(
            msg.contains("1000000000 stitches") && msg.contains("GiB"),
            "{msg}"
        ),
        other => panic!("expected a budget error, got {other:?}"),
    }
    // Checked before allocating: far quicker than building anything.
    assert!(t.elapsed().as_secs_f64() < 1.0);
    let p = KnitParams {
        courses: Some(100),
        wales: Some(100),
        budget_bytes: 1 << 20,
        ..params()
    };
    assert!(matches!(
        knit(&sheet(), &pattern, &p),
        Err(KnitError::Budget(_))
    ));
    let p = KnitParams {
        gauge: Some((0.0, 28.0)),
        ..params()
    };
    assert!(matches!(
        knit(&sheet(), &pattern, &p),
        Err(KnitError::Parameter(_))
    ));
    let p = KnitParams {
        yarn_radius: Some(0.01),
        ..params()
    };
    match knit(&sheet(), &pattern, &p) {
        Err(KnitError::Parameter(msg)) => assert!(msg.contains("thicker than a stitch"), "{msg}"),
        other => panic!("expected a parameter error, got {other:?}"),
    }
    let p = KnitParams {
        ring_segments: 2,
        ..params()
    };
    assert!(matches!(
        knit(&sheet(), &pattern, &p),
        Err(KnitError::Parameter(_))
    ));
}

#[test]
fn pattern_errors_name_row_and_column() {
    match StitchPattern::from_chart("kkpp\nkxpp\nkkpp") {
        Err(KnitError::Pattern(msg)) => assert!(
            msg.contains("row 2, column 2") && msg.contains("'x'"),
            "{msg}"
        ),
        other => panic!("{other:?}"),
    }
    match StitchPattern::from_chart("kkpp\nkkp") {
        Err(KnitError::Pattern(msg)) => assert!(msg.contains("row 1 has 3"), "{msg}"),
        other => panic!("{other:?}"),
    }
    assert!(StitchPattern::from_chart("# only a comment\n").is_err());
    assert!(StitchPattern::preset("no such stitch").is_err());
    // Chart round trip and repeat.
    let p = StitchPattern::preset("Rib 2x2").unwrap();
    assert_eq!(
        StitchPattern::from_chart(&p.chart()).unwrap().chart(),
        p.chart()
    );
    assert_eq!(p.stitch(5, 6), p.stitch(0, 2));
    assert!(ColorPattern::new(vec![[1.0, 0.0, 0.0]], "01").is_err());
}

#[test]
fn colors_follow_the_colour_chart() {
    let red = [0.8, 0.05, 0.05];
    let blue = [0.05, 0.05, 0.8];
    let colors = ColorPattern::stripes(vec![red, blue], 2).unwrap();
    let p = KnitParams {
        courses: Some(8),
        wales: Some(6),
        colors: Some(colors),
        color_variation: 0.0,
        ..params()
    };
    let out = knit(&sheet(), &StitchPattern::preset("stockinette").unwrap(), &p).unwrap();
    // Ring vertices of course c's yarn carry stripe (c / 2) % 2.
    let nv = out.positions.len() / 3;
    let reds = out.colors.chunks(4).filter(|c| c[0] > 0.5).count();
    let blues = out.colors.chunks(4).filter(|c| c[2] > 0.5).count();
    assert_eq!(reds + blues, nv);
    assert!(reds > nv / 3 && blues > nv / 3);
    let _ = PI;
}

#[test]
fn irregularity_moves_stitches_and_keeps_the_yarn_apart() {
    // Clearance against kappa on the sheet (the figures behind the default), and the
    // perturbation actually moving the yarn.
    let regular = knit(
        &sheet(),
        &StitchPattern::preset("stockinette").unwrap(),
        &params(),
    );
    let regular = regular.unwrap();
    for kappa in [0.0025f32, 0.005, 0.01, 0.02] {
        for name in ["stockinette", "rib_1x1", "seed"] {
            let p = KnitParams { kappa, ..params() };
            let out = knit(&sheet(), &StitchPattern::preset(name).unwrap(), &p).unwrap();
            let (min, p01) = measure(&out);
            println!("kappa {kappa:.4} {name:12} clearance min {min:.3} p01 {p01:.3}");
            assert!(min >= KAPPA_FLOOR, "kappa {kappa} {name}: clearance {min}");
            assert!(out.positions.iter().all(|x| x.is_finite()));
            if name == "stockinette" {
                assert_eq!(out.triangles, regular.triangles, "same topology");
                assert_ne!(
                    out.positions, regular.positions,
                    "kappa {kappa} moved nothing"
                );
            }
        }
    }
    // A perturbed edge row must not lose stitches off a UV island that ends at the edge.
    for seed in 0..8 {
        let p = KnitParams {
            kappa: 0.02,
            seed,
            ..params()
        };
        let out = knit(&uv_mesh(), &StitchPattern::preset("seed").unwrap(), &p).unwrap();
        assert_eq!(out.stats.stitches_skipped, 0, "seed {seed}");
    }
    let p = KnitParams {
        kappa: 0.5,
        ..params()
    };
    let err = knit(&sheet(), &StitchPattern::preset("seed").unwrap(), &p);
    assert!(matches!(err, Err(KnitError::Parameter(_))));
}
