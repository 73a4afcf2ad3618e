//! Culling the yarn hidden behind other yarn (issue 7, `DetailParams::cull_hidden`): only
//! triangles some view sees are built, the culled knit is a subset of the whole one, and it
//! stays deterministic, pinnable and equal between `build` and `positions_into`.

use glam::Vec3;
use knitwear::detail::{CameraView, DetailParams};
use knitwear::knit::{KnitOutput, KnitParams, PreparedKnit};
use knitwear::pattern::StitchPattern;
use knitwear::surface::{PlaneSurface, Surface, SurfacePoint, UvRect};
use knitwear::KnitError;

mod common;

use common::cameras::{look_at, perspective};

const RES: (u32, u32) = (480, 270);

/// A perspective view from `eye` towards `target` (z up), 50 degrees vertical field of view.
fn view(eye: Vec3, target: Vec3) -> CameraView {
    let look = look_at(eye, target, Vec3::Z);
    let proj = perspective(50f32.to_radians(), RES.0 as f32 / RES.1 as f32, 0.01, 100.0);
    CameraView {
        clip_from_object: proj * look,
        eye: eye.extend(1.0),
    }
}

/// A 6 x 8 cm patch in z = 0 (12 wales x 22 courses at the default gauge).
fn patch(height: f32) -> PlaneSurface {
    PlaneSurface {
        width: 0.06,
        height,
    }
}

/// Above the patch, looking down at it from the front.
fn above() -> CameraView {
    view(Vec3::new(0.03, -0.06, 0.1), Vec3::new(0.03, 0.04, 0.0))
}

/// Below the patch, looking up at its back.
fn below() -> CameraView {
    view(Vec3::new(0.03, -0.06, -0.1), Vec3::new(0.03, 0.04, 0.0))
}

fn params(views: Vec<CameraView>, cull_hidden: bool, threads: usize) -> KnitParams {
    KnitParams {
        seed: 5,
        kappa: 0.01,
        threads: Some(threads),
        detail: Some(DetailParams {
            views,
            resolution: RES,
            // Every stitch in view at full detail: the whole mesh is then the full knit.
            full_px: 0.0,
            mid_px: 0.0,
            texture_px: 0.0,
            cull_hidden,
            ..Default::default()
        }),
        ..Default::default()
    }
}

fn stockinette() -> StitchPattern {
    StitchPattern::preset("stockinette").unwrap()
}

fn prepare(p: &KnitParams) -> PreparedKnit {
    PreparedKnit::new(&patch(0.08), &stockinette(), p).unwrap()
}

/// Each triangle as its three corner positions, bit for bit.
fn corners(out: &KnitOutput) -> Vec<[u32; 9]> {
    out.triangles
        .chunks_exact(3)
        .map(|t| {
            let mut c = [0u32; 9];
            for (k, &v) in t.iter().enumerate() {
                for a in 0..3 {
                    c[3 * k + a] = out.positions[3 * v as usize + a].to_bits();
                }
            }
            c
        })
        .collect()
}

#[test]
fn only_seen_triangles_are_built_and_they_are_the_whole_knits_own() {
    let whole_knit = prepare(&params(vec![above()], false, 2));
    let whole = whole_knit.build(&patch(0.08)).unwrap();
    let culled = prepare(&params(vec![above()], true, 2));
    let out = culled.build(&patch(0.08)).unwrap();
    let (t, w) = (out.stats.triangles, whole.stats.triangles);
    assert_eq!(t + out.stats.triangles_hidden, w);
    assert_eq!(
        out.stats.triangles_full_detail,
        whole.stats.triangles_full_detail
    );
    // Close up (each stitch about 30 pixels, 16 samples a pixel) much of the yarn shows,
    // but the backs of the strands and the loops behind the fabric do not. The yarn is about
    // 2.5 pixels thick here, near the 2 below which triangles are kept wherever a renderer's
    // samples might catch them (visibility::MAY_SHOW_PX): about 84% are kept.
    assert!(
        t * 10 < w * 9 && t * 5 > w,
        "{t} of {w} triangles seen: a tenth or more of a knit hides behind itself, not all"
    );
    assert_eq!(out.triangles.len(), 3 * t);
    assert_eq!(out.positions.len(), 3 * culled.vertex_count());
    assert_eq!(out.triangles.len(), 3 * culled.triangle_count());
    // Every kept triangle is one of the whole knit's, in the whole knit's order, with the
    // same corners and colours.
    let all = corners(&whole);
    let kept = corners(&out);
    // The whole knit's shading normals, as its own per-frame path gives them and as its
    // build does (the swept tube's: unit, see geometry::bundle's tests).
    let mut whole_positions = vec![0.0; whole.positions.len()];
    let mut whole_normals = vec![0.0; whole.positions.len()];
    whole_knit
        .positions_and_shading_into(
            &patch(0.08),
            &mut whole_positions,
            Some(&mut whole_normals),
            None,
        )
        .unwrap();
    assert_eq!(whole_positions, whole.positions);
    assert_eq!(whole_normals, whole.normals);
    for (v, n) in whole_normals.chunks(3).enumerate() {
        let length = Vec3::from_slice(n).length();
        assert!((length - 1.0).abs() < 1e-5, "vertex {v}: normal {n:?}");
    }
    assert_eq!(out.normals.len(), out.positions.len());
    let mut at = 0;
    for (k, c) in kept.iter().enumerate() {
        while at < all.len() && all[at] != *c {
            at += 1;
        }
        assert!(
            at < all.len(),
            "a culled knit's triangle is not the whole knit's"
        );
        // Its corners carry the whole knit's normals and fibre directions.
        for corner in 0..3 {
            let (v, w) = (
                out.triangles[3 * k + corner] as usize,
                whole.triangles[3 * at + corner] as usize,
            );
            assert_eq!(
                out.normals[3 * v..3 * v + 3],
                whole_normals[3 * w..3 * w + 3]
            );
            assert_eq!(
                out.tangents[3 * v..3 * v + 3],
                whole.tangents[3 * w..3 * w + 3]
            );
        }
        at += 1;
    }
    let bits = culled.seen_triangles().unwrap();
    assert_eq!(bits.len(), w.div_ceil(8));
    let ones: u32 = bits.iter().map(|b| b.count_ones()).sum();
    assert_eq!(ones as usize, t);
    // Every edge and vertex is used by a kept triangle.
    let mut used = vec![false; culled.vertex_count()];
    for &v in &out.triangles {
        used[v as usize] = true;
    }
    assert!(used.iter().all(|&u| u));
    assert!(out
        .corner_edges
        .iter()
        .all(|&e| (e as usize) < out.edges.len() / 2));
}

#[test]
fn a_second_view_of_the_back_keeps_what_it_sees_too() {
    let front = prepare(&params(vec![above()], true, 2));
    let back = prepare(&params(vec![below()], true, 2));
    let both = prepare(&params(vec![above(), below()], true, 2));
    let (f, b, fb) = (
        front.stats().triangles,
        back.stats().triangles,
        both.stats().triangles,
    );
    assert!(
        fb > f.max(b) && fb <= f + b,
        "front {f}, back {b}, both {fb}"
    );
    let (fs, bs, s) = (
        front.seen_triangles().unwrap(),
        back.seen_triangles().unwrap(),
        both.seen_triangles().unwrap(),
    );
    for i in 0..s.len() {
        assert_eq!(s[i], fs[i] | bs[i], "the views' union, byte {i}");
    }
}

/// The patch turned over, half a turn about the x axis: the same (u,v) layout with its back
/// up, every coordinate exactly the patch's negated (no rounding).
struct TurnedOver(PlaneSurface);

impl TurnedOver {
    fn turn(p: SurfacePoint) -> SurfacePoint {
        let flip = |v: Vec3| Vec3::new(v.x, -v.y, -v.z);
        SurfacePoint {
            position: flip(p.position),
            normal: flip(p.normal),
        }
    }
}

impl Surface for TurnedOver {
    fn domain(&self) -> UvRect {
        self.0.domain()
    }
    fn cyclic_u(&self) -> bool {
        self.0.cyclic_u()
    }
    fn cyclic_v(&self) -> bool {
        self.0.cyclic_v()
    }
    fn eval(&self, uv: glam::Vec2) -> Option<SurfacePoint> {
        self.0.eval(uv).map(Self::turn)
    }
    fn eval_nearest(&self, uv: glam::Vec2) -> SurfacePoint {
        Self::turn(self.0.eval_nearest(uv))
    }
    fn extent(&self) -> (f32, f32) {
        self.0.extent()
    }
}

/// Above the turned-over patch (y in [-0.08, 0]), looking down at its back.
fn above_turned() -> CameraView {
    view(Vec3::new(0.03, 0.06, 0.1), Vec3::new(0.03, -0.04, 0.0))
}

/// Issue 23: a source that deforms culls its hidden yarn too. Each view finds what it sees
/// on the surface in its own pose, so a camera that sees the back of a piece once the body
/// turns it over keeps the yarn of the back; it used to be refused (the pass looked at the
/// knitted pose only, where that camera sees nothing of the patch).
#[test]
fn each_view_culls_the_yarn_hidden_in_its_own_pose() {
    use std::sync::Arc;
    let turned: Arc<dyn Surface> = Arc::new(TurnedOver(patch(0.08)));
    let posed = |views: Vec<CameraView>, poses: Vec<Arc<dyn Surface>>| {
        let mut p = params(views, true, 2);
        p.detail.as_mut().unwrap().poses = knitwear::detail::ViewPoses(poses);
        prepare(&p)
    };
    // What the view sees on the turned patch, pose given, is what a knit of the turned patch
    // itself sees, bit for bit, and the culled mesh it builds in that pose is that knit's.
    let in_pose = posed(vec![above_turned()], vec![turned.clone()]);
    let direct = PreparedKnit::new(
        &TurnedOver(patch(0.08)),
        &stockinette(),
        &params(vec![above_turned()], true, 2),
    )
    .unwrap();
    assert_eq!(in_pose.seen_triangles(), direct.seen_triangles());
    let (a, b) = (
        in_pose.build(&*turned).unwrap(),
        direct.build(&*turned).unwrap(),
    );
    assert_eq!(a.positions, b.positions);
    assert_eq!(a.triangles, b.triangles);
    let whole = a.stats.triangles + a.stats.triangles_hidden;
    assert!(
        a.stats.triangles * 10 < whole * 9 && a.stats.triangles * 5 > whole,
        "{} of {whole} seen in the turned pose",
        a.stats.triangles
    );
    // Found in the knitted pose instead (no poses), the same view keeps another set.
    let unposed = prepare(&params(vec![above_turned()], true, 2));
    assert_ne!(unposed.seen_triangles(), in_pose.seen_triangles());
    // Views in different poses keep the union of what each sees in its own; views that share
    // a pose are rasterised on one build of it.
    let own: Arc<dyn Surface> = Arc::new(patch(0.08));
    let front = prepare(&params(vec![above()], true, 2));
    let both = posed(
        vec![above(), above_turned(), above_turned()],
        vec![own, turned.clone(), turned],
    );
    let (f, t, s) = (
        front.seen_triangles().unwrap(),
        in_pose.seen_triangles().unwrap(),
        both.seen_triangles().unwrap(),
    );
    for i in 0..s.len() {
        assert_eq!(s[i], f[i] | t[i], "the poses' union, byte {i}");
    }
    assert!(both.stats().triangles > front.stats().triangles.max(in_pose.stats().triangles));
}

#[test]
fn culling_is_deterministic_on_any_thread_count_and_positions_match_build() {
    let a = prepare(&params(vec![above()], true, 1));
    let b = prepare(&params(vec![above()], true, 3));
    assert_eq!(a.seen_triangles(), b.seen_triangles());
    assert_eq!(a.stats().topology_key, b.stats().topology_key);
    let (oa, ob) = (
        a.build(&patch(0.08)).unwrap(),
        b.build(&patch(0.08)).unwrap(),
    );
    assert_eq!(oa.positions, ob.positions);
    assert_eq!(oa.colors, ob.colors);
    assert_eq!(oa.triangles, ob.triangles);
    assert_eq!(oa.edges, ob.edges);
    assert_eq!(oa.corner_edges, ob.corner_edges);
    // A second build (a fresh sweep, not the one made to look) and the positions-only path
    // give the same, in the knitted pose and in a stretched one.
    assert_eq!(b.build(&patch(0.08)).unwrap().positions, oa.positions);
    for surface in [patch(0.08), patch(0.085)] {
        let built = b.build(&surface).unwrap();
        assert_eq!(built.triangles, oa.triangles);
        let mut pos = vec![0.0; 3 * b.vertex_count()];
        b.positions_into(&surface, &mut pos).unwrap();
        assert_eq!(pos, built.positions);
        let mut nrm = vec![0.0; 3 * b.vertex_count()];
        let mut tan = vec![0.0; 3 * b.vertex_count()];
        b.positions_and_shading_into(&surface, &mut pos, Some(&mut nrm), Some(&mut tan))
            .unwrap();
        assert_eq!(nrm, built.normals);
        assert_eq!(tan, built.tangents);
    }
    assert_eq!(oa.normals, ob.normals);
}

#[test]
fn pinned_seen_triangles_rebuild_the_same_mesh_without_the_camera() {
    let first = prepare(&params(vec![above()], true, 2));
    let pinned = KnitParams {
        detail: Some(DetailParams {
            pinned: Some(first.stitch_levels().unwrap().to_vec()),
            pinned_seen: Some(first.seen_triangles().unwrap().to_vec()),
            cull_hidden: true,
            ..Default::default()
        }),
        ..params(vec![], true, 2)
    };
    let again = prepare(&pinned);
    assert_eq!(again.stats().topology_key, first.stats().topology_key);
    let (a, b) = (
        first.build(&patch(0.085)).unwrap(),
        again.build(&patch(0.085)).unwrap(),
    );
    assert_eq!(a.positions, b.positions);
    assert_eq!(a.triangles, b.triangles);
    assert_eq!(a.edges, b.edges);
}

#[test]
fn bad_hidden_culling_settings_are_errors() {
    let first = prepare(&params(vec![above()], true, 2));
    let mut bits = first.seen_triangles().unwrap().to_vec();
    bits.pop();
    let wrong_length = KnitParams {
        detail: Some(DetailParams {
            pinned: Some(first.stitch_levels().unwrap().to_vec()),
            pinned_seen: Some(bits),
            cull_hidden: true,
            ..Default::default()
        }),
        ..params(vec![], true, 2)
    };
    let no_views = KnitParams {
        detail: Some(DetailParams {
            pinned: Some(first.stitch_levels().unwrap().to_vec()),
            cull_hidden: true,
            ..Default::default()
        }),
        ..params(vec![], true, 2)
    };
    let mut bad_samples = params(vec![above()], true, 2);
    bad_samples.detail.as_mut().unwrap().hidden_supersampling = 0;
    for p in [wrong_length, no_views, bad_samples] {
        let r = PreparedKnit::new(&patch(0.08), &stockinette(), &p);
        assert!(matches!(r, Err(KnitError::Parameter(_))), "{:?}", r.err());
    }
}
