//! Camera-driven level of detail and culling (issue 7): levels follow the projected stitch
//! size, spans of different levels share their boundary rings (no cracks), culling drops what
//! no view sees, and everything stays deterministic and equal between `build` and
//! `positions_into`.

use glam::{Mat4, Vec3, Vec4};
use knitwear::detail::{CameraView, DetailParams, Level};
use knitwear::knit::{knit, KnitParams, PreparedKnit};
use knitwear::pattern::StitchPattern;
use knitwear::surface::{GridSurface, PlaneSurface, Surface};
use knitwear::KnitError;

mod common;

use common::cameras::{look_at, perspective};

const RES: (u32, u32) = (1920, 1080);

/// OpenGL orthographic projection of the box `[l, r] x [b, t] x [-far, -near]`.
fn orthographic(l: f32, r: f32, b: f32, t: f32, near: f32, far: f32) -> Mat4 {
    Mat4::from_cols(
        Vec4::new(2.0 / (r - l), 0.0, 0.0, 0.0),
        Vec4::new(0.0, 2.0 / (t - b), 0.0, 0.0),
        Vec4::new(0.0, 0.0, -2.0 / (far - near), 0.0),
        Vec4::new(
            -(r + l) / (r - l),
            -(t + b) / (t - b),
            -(far + near) / (far - near),
            1.0,
        ),
    )
}

/// A 10 x 60 cm strip in z = 0 (20 wales x 168 courses at the default gauge).
fn strip() -> PlaneSurface {
    PlaneSurface {
        width: 0.1,
        height: 0.6,
    }
}

/// A perspective view from `eye` towards `target`, 50 degrees vertical field of view.
fn view(eye: Vec3, target: Vec3) -> CameraView {
    let aspect = RES.0 as f32 / RES.1 as f32;
    let proj = perspective(50f32.to_radians(), aspect, 0.01, 100.0);
    CameraView {
        clip_from_object: proj * look_at(eye, target, Vec3::Z),
        eye: eye.extend(1.0),
    }
}

/// Low over the strip's near end, looking along it: it recedes into the distance.
fn receding() -> CameraView {
    view(Vec3::new(0.05, -0.08, 0.06), Vec3::new(0.05, 0.25, 0.0))
}

/// Detail for `views` at thresholds of 24 / 10 / 2 pixels (coarser than the defaults), so
/// this strip at this resolution gets every built level.
fn detail(views: Vec<CameraView>) -> DetailParams {
    DetailParams {
        views,
        resolution: RES,
        full_px: 24.0,
        mid_px: 10.0,
        texture_px: 2.0,
        ..Default::default()
    }
}

fn params(detail: Option<DetailParams>) -> KnitParams {
    KnitParams {
        seed: 3,
        kappa: 0.01,
        detail,
        ..Default::default()
    }
}

fn stockinette() -> StitchPattern {
    StitchPattern::preset("stockinette").unwrap()
}

#[test]
fn without_a_camera_every_stitch_is_full() {
    let out = knit(&strip(), &stockinette(), &params(None)).unwrap();
    let s = &out.stats;
    assert_eq!(s.levels, [s.stitches, 0, 0, 0, 0]);
    assert_eq!(s.triangles_full_detail, s.triangles);
}

#[test]
fn a_receding_strip_gets_every_built_level_and_fewer_triangles() {
    let full = knit(&strip(), &stockinette(), &params(None)).unwrap();
    let out = knit(
        &strip(),
        &stockinette(),
        &params(Some(detail(vec![receding()]))),
    )
    .unwrap();
    let s = &out.stats;
    println!(
        "levels {:?}, triangles {} of {}",
        s.levels, s.triangles, s.triangles_full_detail
    );
    assert_eq!(s.levels.iter().sum::<usize>(), s.stitches);
    assert!(
        s.levels[0] > 0 && s.levels[1] > 0 && s.levels[2] > 0,
        "{:?}",
        s.levels
    );
    assert_eq!(s.triangles_full_detail, full.stats.triangles);
    assert!(s.triangles < full.stats.triangles);
    assert!(out.positions.iter().all(|x| x.is_finite()));
    // The centreline is the full-detail one: the same spline, sampled the same way.
    assert_eq!(out.centerline, full.centerline);
    // Every index is in range and every triangle's edges are its own.
    let nv = out.positions.len() / 3;
    assert!(out.triangles.iter().all(|&v| (v as usize) < nv));
    for (t, tri) in out.triangles.chunks_exact(3).enumerate() {
        for k in 0..3 {
            let e = out.corner_edges[3 * t + k] as usize;
            let (a, b) = (out.edges[2 * e], out.edges[2 * e + 1]);
            let (p, q) = (tri[k], tri[(k + 1) % 3]);
            assert!(
                (a, b) == (p, q) || (a, b) == (q, p),
                "triangle {t} corner {k}"
            );
        }
    }
    // Levels only get coarser along the strip, away from the camera.
    let prepared = PreparedKnit::new(
        &strip(),
        &stockinette(),
        &params(Some(detail(vec![receding()]))),
    )
    .unwrap();
    let levels = prepared.stitch_levels().unwrap();
    let wales = s.wales;
    for course in 1..s.courses {
        let mid = course * wales + wales / 2;
        assert!(levels[mid] >= levels[mid - wales], "course {course}");
    }
}

/// Where two spans of one piece meet, the last ring of the first and the first ring of the
/// second are rings round the same centreline sample, in the same plane: the yarn has no gap.
#[test]
fn spans_meet_on_one_centreline_point_in_one_plane() {
    let p = params(Some(detail(vec![receding()])));
    let prepared = PreparedKnit::new(&strip(), &stockinette(), &p).unwrap();
    let out = prepared.build(&strip()).unwrap();
    let pts: Vec<Vec3> = out
        .centerline
        .chunks_exact(3)
        .map(Vec3::from_slice)
        .collect();
    let spans = prepared.spans();
    let mut vbase = Vec::new();
    let mut v = 0;
    for sp in spans {
        vbase.push(v);
        let m = prepared.ring_segments(sp.level);
        v += sp.rings * m + if sp.closed { sp.rings } else { sp.rings - 1 } * 2 * m;
    }
    assert_eq!(v, out.positions.len() / 3);
    let ring = |k: usize, r: usize| -> Vec<Vec3> {
        let m = prepared.ring_segments(spans[k].level);
        (0..m)
            .map(|j| {
                let i = vbase[k] + r * m + j;
                Vec3::from_slice(&out.positions[3 * i..3 * i + 3])
            })
            .collect()
    };
    let plane_normal =
        |ring: &[Vec3], c: Vec3| -> Vec3 { (ring[0] - c).cross(ring[1] - c).normalize() };
    let mut joins = 0;
    for k in 1..spans.len() {
        let (a, b) = (spans[k - 1], spans[k]);
        if a.piece != b.piece {
            continue;
        }
        joins += 1;
        assert_eq!(a.last, b.first);
        let start = out.yarn_offsets[a.piece] as usize;
        let centre = pts[start + b.first];
        let (ra, rb) = (ring(k - 1, a.rings - 1), ring(k, 0));
        // Each ring at its level's radius: the yarn's at full detail, wider at coarser levels
        // (they keep the knit's cover), so a level change is a step, never a gap.
        for (r, level) in [(&ra, a.level), (&rb, b.level)] {
            let want = prepared.ring_radius(level);
            assert!(want >= out.yarn_radius);
            for q in r.iter() {
                let d = (*q - centre).length();
                assert!(
                    (d - want).abs() < 1e-5,
                    "ring point {d} from the centre, not {want}"
                );
            }
        }
        let (na, nb) = (plane_normal(&ra, centre), plane_normal(&rb, centre));
        assert!(
            na.dot(nb).abs() > 0.9999,
            "ring planes differ: {na} vs {nb}"
        );
    }
    assert!(joins >= 20, "only {joins} level changes along courses");
}

#[test]
fn detail_is_deterministic_on_any_thread_count_and_positions_match_build() {
    let mk = |threads| KnitParams {
        threads: Some(threads),
        ..params(Some(detail(vec![receding()])))
    };
    let a = PreparedKnit::new(&strip(), &stockinette(), &mk(1)).unwrap();
    let b = PreparedKnit::new(&strip(), &stockinette(), &mk(2)).unwrap();
    let (oa, ob) = (a.build(&strip()).unwrap(), b.build(&strip()).unwrap());
    assert_eq!(oa.positions, ob.positions);
    assert_eq!(oa.colors, ob.colors);
    assert_eq!(oa.triangles, ob.triangles);
    assert_eq!(oa.stats.topology_key, ob.stats.topology_key);
    let mut pos = vec![0.0; 3 * b.vertex_count()];
    b.positions_into(&strip(), &mut pos).unwrap();
    assert_eq!(pos, oa.positions);
    // A later frame sweeps the draws the first one kept, coarser levels' spans included.
    let stretched = PlaneSurface {
        height: 0.66,
        ..strip()
    };
    b.positions_into(&stretched, &mut pos).unwrap();
    assert_eq!(pos, b.build(&stretched).unwrap().positions);
    assert_ne!(pos, oa.positions);
}

#[test]
fn small_stitches_are_left_to_the_texture() {
    let d = DetailParams {
        texture_px: 9.0,
        ..detail(vec![receding()])
    };
    let out = knit(&strip(), &stockinette(), &params(Some(d))).unwrap();
    let s = &out.stats;
    assert!(s.levels[Level::Texture as usize] > 0, "{:?}", s.levels);
    // Texture stitches get no yarn: the built pieces hold only the others.
    let built = s.levels[0] + s.levels[1] + s.levels[2];
    let samples = out.centerline.len() / 3;
    assert!(
        samples < 17 * built + s.courses,
        "{samples} samples for {built} stitches"
    );
}

#[test]
fn stitches_outside_the_frame_are_culled_unless_the_margin_covers_them() {
    // Looking straight down at the strip's first 10 cm: the rest is outside the frame.
    let down = view(Vec3::new(0.05, 0.05, 0.12), Vec3::new(0.05, 0.05, 0.0));
    let down = CameraView {
        clip_from_object: perspective(50f32.to_radians(), 16.0 / 9.0, 0.01, 10.0)
            * look_at(
                Vec3::new(0.05, 0.05, 0.12),
                Vec3::new(0.05, 0.05, 0.0),
                Vec3::Y,
            ),
        ..down
    };
    let tight = knit(&strip(), &stockinette(), &params(Some(detail(vec![down])))).unwrap();
    let culled = tight.stats.levels[Level::Culled as usize];
    assert!(
        culled > tight.stats.stitches / 2,
        "{:?}",
        tight.stats.levels
    );
    let wide = DetailParams {
        frustum_margin: 20.0,
        ..detail(vec![down])
    };
    let wide = knit(&strip(), &stockinette(), &params(Some(wide))).unwrap();
    assert_eq!(wide.stats.levels[Level::Culled as usize], 0);
    // A second view that sees the far end: a stitch is culled only if no view sees it.
    let far_end = view(Vec3::new(0.05, 0.45, 0.12), Vec3::new(0.05, 0.5, 0.0));
    let both = knit(
        &strip(),
        &stockinette(),
        &params(Some(detail(vec![down, far_end]))),
    )
    .unwrap();
    assert!(both.stats.levels[Level::Culled as usize] < culled);
}

/// A surface moved by `offset`: the same (u,v) layout in another pose.
struct Moved<S> {
    inner: S,
    offset: Vec3,
}

impl<S: Surface> Surface for Moved<S> {
    fn domain(&self) -> knitwear::surface::UvRect {
        self.inner.domain()
    }
    fn cyclic_u(&self) -> bool {
        self.inner.cyclic_u()
    }
    fn cyclic_v(&self) -> bool {
        self.inner.cyclic_v()
    }
    fn eval(&self, uv: glam::Vec2) -> Option<knitwear::surface::SurfacePoint> {
        self.inner
            .eval(uv)
            .map(|p| knitwear::surface::SurfacePoint {
                position: p.position + self.offset,
                ..p
            })
    }
    fn eval_nearest(&self, uv: glam::Vec2) -> knitwear::surface::SurfacePoint {
        let p = self.inner.eval_nearest(uv);
        knitwear::surface::SurfacePoint {
            position: p.position + self.offset,
            ..p
        }
    }
    fn extent(&self) -> (f32, f32) {
        self.inner.extent()
    }
}

/// Each view measures the stitches on its own pose of the surface: a still camera over the
/// strip's near end sees its far end once the strip has slid 50 cm under it, and only that.
#[test]
fn each_view_sees_the_surface_in_its_own_pose() {
    let down = CameraView {
        clip_from_object: perspective(50f32.to_radians(), 16.0 / 9.0, 0.01, 10.0)
            * look_at(
                Vec3::new(0.05, 0.05, 0.12),
                Vec3::new(0.05, 0.05, 0.0),
                Vec3::Y,
            ),
        eye: Vec3::new(0.05, 0.05, 0.12).extend(1.0),
    };
    let levels = |poses: Vec<std::sync::Arc<dyn Surface>>| {
        let d = DetailParams {
            poses: knitwear::detail::ViewPoses(poses),
            ..detail(vec![down])
        };
        let prepared = PreparedKnit::new(&strip(), &stockinette(), &params(Some(d))).unwrap();
        let levels = prepared.stitch_levels().unwrap().to_vec();
        let courses = levels.len() / 20;
        let culled = |rows: std::ops::Range<usize>| {
            levels[rows.start * 20..rows.end * 20]
                .iter()
                .all(|&l| l == Level::Culled)
        };
        (
            culled(0..courses / 10),
            culled(courses - courses / 10..courses),
        )
    };
    // The strip where it is: its near end seen, its far end not.
    assert_eq!(levels(Vec::new()), (false, true));
    let here: std::sync::Arc<dyn Surface> = std::sync::Arc::new(strip());
    assert_eq!(levels(vec![here]), (false, true));
    // Slid 50 cm towards -y: the far end under the camera, the near end out of the frame.
    let slid: std::sync::Arc<dyn Surface> = std::sync::Arc::new(Moved {
        inner: strip(),
        offset: Vec3::new(0.0, -0.5, 0.0),
    });
    assert_eq!(levels(vec![slid.clone()]), (true, false));
    // A pose per view: one pose for two views is refused, as is another (u,v) layout.
    let two = DetailParams {
        poses: knitwear::detail::ViewPoses(vec![slid]),
        ..detail(vec![down, down])
    };
    let err = PreparedKnit::new(&strip(), &stockinette(), &params(Some(two))).unwrap_err();
    assert!(
        matches!(err, KnitError::Parameter(ref m) if m.contains("one pose per view")),
        "{err}"
    );
    let wider: std::sync::Arc<dyn Surface> = std::sync::Arc::new(
        GridSurface::new(
            2,
            2,
            &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0],
            &[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0],
            true,
            false,
        )
        .unwrap(),
    );
    let other = DetailParams {
        poses: knitwear::detail::ViewPoses(vec![wider]),
        ..detail(vec![down])
    };
    let err = PreparedKnit::new(&strip(), &stockinette(), &params(Some(other))).unwrap_err();
    assert!(
        matches!(err, KnitError::Parameter(ref m) if m.contains("layout")),
        "{err}"
    );
}

/// A closed tube seen from the side: with back-face culling its far side is not built.
#[test]
fn back_faces_of_a_closed_surface_are_culled_when_asked() {
    let (rows, cols, r) = (24, 48, 0.05f32);
    let (mut p, mut n) = (Vec::new(), Vec::new());
    for i in 0..rows {
        for j in 0..cols {
            let a = std::f32::consts::TAU * j as f32 / cols as f32;
            let dir = Vec3::new(a.cos(), a.sin(), 0.0);
            p.extend((r * dir + Vec3::Z * (0.1 * i as f32 / (rows - 1) as f32)).to_array());
            n.extend(dir.to_array());
        }
    }
    let tube = GridSurface::new(rows, cols, &p, &n, true, false).unwrap();
    let side = view(Vec3::new(0.4, 0.0, 0.05), Vec3::new(0.0, 0.0, 0.05));
    let keep = knit(&tube, &stockinette(), &params(Some(detail(vec![side])))).unwrap();
    assert_eq!(keep.stats.levels[Level::Culled as usize], 0);
    let cull = DetailParams {
        cull_back_faces: true,
        ..detail(vec![side])
    };
    let cull = knit(&tube, &stockinette(), &params(Some(cull))).unwrap();
    let frac = cull.stats.levels[Level::Culled as usize] as f32 / cull.stats.stitches as f32;
    // The eye is 8 radii away: it sees a bit less than half the tube; the slack keeps a
    // little of the back near the silhouette.
    assert!((0.35..0.55).contains(&frac), "culled fraction {frac}");
    assert!(cull.stats.triangles < keep.stats.triangles);
    // An orthographic view from +x: eye is a direction.
    let ortho = CameraView {
        clip_from_object: orthographic(-0.1, 0.1, -0.06, 0.06, 0.01, 10.0)
            * look_at(
                Vec3::new(1.0, 0.0, 0.05),
                Vec3::new(0.0, 0.0, 0.05),
                Vec3::Z,
            ),
        eye: Vec4::new(1.0, 0.0, 0.0, 0.0),
    };
    let ortho = DetailParams {
        cull_back_faces: true,
        ..detail(vec![ortho])
    };
    let o = knit(&tube, &stockinette(), &params(Some(ortho))).unwrap();
    let frac = o.stats.levels[Level::Culled as usize] as f32 / o.stats.stitches as f32;
    assert!(
        (0.35..0.5).contains(&frac),
        "orthographic culled fraction {frac}"
    );
}

#[test]
fn bad_detail_settings_are_errors() {
    let cases = [
        detail(vec![]),
        DetailParams {
            full_px: 4.0,
            mid_px: 8.0,
            ..detail(vec![receding()])
        },
        DetailParams {
            resolution: (0, 100),
            ..detail(vec![receding()])
        },
        detail(vec![CameraView {
            clip_from_object: Mat4::from_cols_array(&[f32::NAN; 16]),
            eye: Vec4::W,
        }]),
    ];
    for d in cases {
        match knit(&strip(), &stockinette(), &params(Some(d.clone()))) {
            Err(KnitError::Parameter(msg)) => println!("{msg}"),
            other => panic!("{d:?} gave {:?}", other.map(|o| o.stats)),
        }
    }
    let _ = strip().domain();
}

/// Pinned levels rebuild the same knit without the camera (an animated knit's frames).
#[test]
fn pinned_levels_rebuild_the_same_topology_without_the_camera() {
    let p = params(Some(detail(vec![receding()])));
    let first = PreparedKnit::new(&strip(), &stockinette(), &p).unwrap();
    let pinned = DetailParams {
        pinned: Some(first.stitch_levels().unwrap().to_vec()),
        ..DetailParams::default()
    };
    let again = PreparedKnit::new(&strip(), &stockinette(), &params(Some(pinned))).unwrap();
    assert_eq!(again.stats().topology_key, first.stats().topology_key);
    let (a, b) = (
        first.build(&strip()).unwrap(),
        again.build(&strip()).unwrap(),
    );
    assert_eq!(a.positions, b.positions);
    assert_eq!(a.triangles, b.triangles);
    let wrong = DetailParams {
        pinned: Some(vec![Level::Full; 7]),
        ..DetailParams::default()
    };
    assert!(matches!(
        PreparedKnit::new(&strip(), &stockinette(), &params(Some(wrong))),
        Err(KnitError::Parameter(_))
    ));
}
