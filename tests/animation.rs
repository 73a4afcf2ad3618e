//! A knit bound to its surface follows the surface as it deforms: the positions-only path
//! equals a full build bit for bit, the topology never changes, and a rigid motion of the
//! surface moves the yarn rigidly (no jitter).

use std::f32::consts::TAU;

use glam::{Mat3, Vec3};
use knitwear::knit::{knit, KnitParams, PreparedKnit};
use knitwear::pattern::StitchPattern;
use knitwear::surface::{GridSurface, MeshSurface, Surface};
use knitwear::KnitError;

/// A 10 x 8 cm sheet bent by `bend` (radians of arc across u), moved by `motion`.
fn sheet(bend: f32, cyclic_u: bool, motion: impl Fn(Vec3) -> Vec3, turn: Mat3) -> GridSurface {
    let (rows, cols) = (33, 41);
    let (mut p, mut n) = (Vec::new(), Vec::new());
    for i in 0..rows {
        for j in 0..cols {
            let u = j as f32 / (cols - 1) as f32;
            let v = i as f32 / (rows - 1) as f32;
            let (pos, nrm) = if bend.abs() < 1e-6 {
                (Vec3::new(0.10 * u, 0.08 * v, 0.0), Vec3::Z)
            } else {
                let r = 0.10 / bend;
                let a = (u - 0.5) * bend;
                (
                    Vec3::new(r * a.sin(), 0.08 * v, r * a.cos() - r),
                    Vec3::new(a.sin(), 0.0, a.cos()),
                )
            };
            p.extend(motion(pos).to_array());
            n.extend((turn * nrm).to_array());
        }
    }
    GridSurface::new(rows, cols, &p, &n, cyclic_u, false).unwrap()
}

fn rest() -> GridSurface {
    sheet(0.0, false, |p| p, Mat3::IDENTITY)
}

fn params() -> KnitParams {
    KnitParams {
        courses: Some(12),
        wales: Some(14),
        ring_segments: 5,
        samples_per_loop: 10,
        seed: 3,
        ..Default::default()
    }
}

fn stockinette() -> StitchPattern {
    StitchPattern::preset("stockinette").unwrap()
}

#[test]
fn positions_only_equals_a_full_build_bit_for_bit() {
    let p = params();
    let prepared = PreparedKnit::new(&rest(), &stockinette(), &p).unwrap();
    // The first call draws the fibres and keeps the draws; the frames after it sweep the
    // kept draws along another pose, and must still give that pose's build exactly.
    let bent = || sheet(1.2, false, |p| p, Mat3::IDENTITY);
    for surface in [rest(), bent(), rest()] {
        let full = prepared.build(&surface).unwrap();
        assert_eq!(full.triangles.len(), 3 * prepared.triangle_count());
        let mut positions = vec![f32::NAN; 3 * prepared.vertex_count()];
        prepared.positions_into(&surface, &mut positions).unwrap();
        assert_eq!(positions, full.positions);
        let (mut normals, mut tangents) = (positions.clone(), positions.clone());
        prepared
            .positions_and_shading_into(
                &surface,
                &mut positions,
                Some(&mut normals),
                Some(&mut tangents),
            )
            .unwrap();
        assert_eq!(positions, full.positions);
        assert_eq!(normals, full.normals);
        assert_eq!(tangents, full.tangents);
    }
    // And the one-shot `knit` is the prepared knit's build.
    let once = knit(&rest(), &stockinette(), &p).unwrap();
    assert_eq!(once.positions, prepared.build(&rest()).unwrap().positions);
    assert_eq!(once.triangles, prepared.build(&rest()).unwrap().triangles);
}

#[test]
fn topology_never_changes_as_the_surface_bends_and_stretches() {
    let prepared = PreparedKnit::new(&rest(), &stockinette(), &params()).unwrap();
    let first = prepared.build(&rest()).unwrap();
    for k in 1..=10 {
        let bend = 0.3 * k as f32;
        let stretch = 1.0 + 0.05 * k as f32;
        let surface = sheet(
            bend,
            false,
            |p| p * Vec3::new(1.0, stretch, 1.0),
            Mat3::IDENTITY,
        );
        let out = prepared.build(&surface).unwrap();
        assert_eq!(out.triangles, first.triangles);
        assert_eq!(out.edges, first.edges);
        assert_eq!(out.corner_edges, first.corner_edges);
        assert_eq!(
            out.colors, first.colors,
            "colours are bound to stitches, not to space"
        );
        assert_eq!(out.stats.topology_key, first.stats.topology_key);
        assert!(out.positions.iter().all(|x| x.is_finite()));
    }
}

#[test]
fn a_rigid_motion_moves_the_yarn_rigidly() {
    let prepared = PreparedKnit::new(&rest(), &stockinette(), &params()).unwrap();
    let at_rest = prepared.build(&rest()).unwrap();
    let radius = at_rest.yarn_radius;
    let turn = Mat3::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    let shift = Vec3::new(0.3, -1.2, 2.5);
    let moved_surface = sheet(0.0, false, |p| turn * p + shift, turn);
    let mut moved = vec![0.0; 3 * prepared.vertex_count()];
    prepared.positions_into(&moved_surface, &mut moved).unwrap();
    let mut worst = 0.0f32;
    for (a, b) in at_rest.positions.chunks_exact(3).zip(moved.chunks_exact(3)) {
        let expected = turn * Vec3::from_slice(a) + shift;
        worst = worst.max((expected - Vec3::from_slice(b)).length());
    }
    println!(
        "rigid motion: worst vertex deviation {:.2e} yarn radii",
        worst / radius
    );
    // All that is left is single-precision rounding: one ulp of a coordinate near 2.5 units
    // is 2.4e-7, a third of a thousandth of this 0.7 mm yarn radius, and the surface mapping
    // rounds a few times.
    assert!(
        worst < 1e-2 * radius,
        "jitter {worst} against radius {radius}"
    );
}

#[test]
fn a_pinned_stitch_size_keeps_loop_shapes_when_the_rest_pose_is_not_at_hand() {
    // A farm renders frame N alone: it prepares from the frame-N surface with the counts, yarn
    // radius and stitch size stored at bind time, and must get what the bound knit gets.
    let p = params();
    let bound = PreparedKnit::new(&rest(), &stockinette(), &p).unwrap();
    let stats = bound.stats().clone();
    let frame_n = sheet(1.5, false, |p| p * Vec3::new(1.0, 1.3, 1.0), Mat3::IDENTITY);
    let alone = PreparedKnit::new(
        &frame_n,
        &stockinette(),
        &KnitParams {
            yarn_radius: Some(bound.yarn_radius()),
            stitch_size: Some((stats.stitch_width, stats.stitch_height)),
            ..p.clone()
        },
    )
    .unwrap();
    let a = bound.build(&frame_n).unwrap();
    let b = alone.build(&frame_n).unwrap();
    assert_eq!(a.positions, b.positions);
    assert_eq!(a.triangles, b.triangles);
    // Without pinning, the stretched frame would re-measure the stitches and re-tune.
    let unpinned = PreparedKnit::new(&frame_n, &stockinette(), &p).unwrap();
    assert_ne!(unpinned.build(&frame_n).unwrap().positions, a.positions);
}

#[test]
fn a_changed_layout_or_buffer_size_is_an_error_not_a_panic() {
    let prepared = PreparedKnit::new(&rest(), &stockinette(), &params()).unwrap();
    let tube = sheet(TAU * 0.99, true, |p| p, Mat3::IDENTITY);
    assert!(matches!(prepared.build(&tube), Err(KnitError::Surface(_))));
    let mut short = vec![0.0; 5];
    assert!(matches!(
        prepared.positions_into(&rest(), &mut short),
        Err(KnitError::Parameter(_))
    ));
    let mesh = MeshSurface::new(
        &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        &[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0],
        &[0, 1, 2],
        &[0.0, 0.0, 0.5, 0.0, 0.0, 0.5],
    )
    .unwrap();
    assert_ne!(mesh.domain(), rest().domain());
    assert!(matches!(prepared.build(&mesh), Err(KnitError::Surface(_))));
}

#[test]
fn bad_pinned_stitch_sizes_are_refused() {
    for size in [(0.0, 0.01), (f32::NAN, 0.01), (0.01, -1.0)] {
        let p = KnitParams {
            stitch_size: Some(size),
            ..params()
        };
        assert!(matches!(
            PreparedKnit::new(&rest(), &stockinette(), &p),
            Err(KnitError::Parameter(_))
        ));
    }
}

/// Issue 23: the knit's clearance in another pose, measured without building the bundles, is
/// what a build in that pose measures; squashing the rows to 40% of their height pushes yarn
/// through yarn, and the figure says so.
#[test]
fn the_clearance_in_any_pose_is_what_a_build_there_measures() {
    // At the default gauge (the counts of `params` give rows twice as tall).
    let p = KnitParams {
        measure_clearance: true,
        seed: 3,
        ..Default::default()
    };
    let prepared = PreparedKnit::new(&rest(), &stockinette(), &p).unwrap();
    let bent = sheet(1.2, false, |q| q, Mat3::IDENTITY);
    let squashed = sheet(0.0, false, |q| q * Vec3::new(1.0, 0.4, 1.0), Mat3::IDENTITY);
    let mut figures = Vec::new();
    for surface in [rest(), bent, squashed] {
        let c = prepared.clearance(&surface).unwrap();
        let built = prepared.build(&surface).unwrap().stats.clearance.unwrap();
        assert_eq!(c.0.to_bits(), built.0.to_bits());
        assert_eq!(c.1.to_bits(), built.1.to_bits());
        figures.push(c);
    }
    assert!(figures[0].0 > 0.7, "{figures:?}");
    assert!(figures[2].0 < 0.5 && figures[2].1 < 0.5, "{figures:?}");
    let other = sheet(0.0, true, |q| q, Mat3::IDENTITY);
    assert!(matches!(
        prepared.clearance(&other),
        Err(KnitError::Surface(_))
    ));
}
