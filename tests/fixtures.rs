//! Where methods fail, and what the user gets instead (issue 4): a fixture suite of the surfaces
//! and requests that break knit-on-surface methods, each built from code, each with a defined
//! outcome. Either the knit succeeds with every position finite and stats that add up (what it
//! degraded is counted in `stats`), or it fails with the expected [`KnitError`] variant whose
//! message names the problem. Never a panic, a hang or a NaN.
//!
//! `cargo test --test fixtures -- --nocapture` prints each fixture's outcome and clearance.

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};
use knitwear::knit::{knit, measure, KnitOutput, KnitParams};
use knitwear::pattern::StitchPattern;
use knitwear::surface::{GridSurface, MeshSurface, Surface};
use knitwear::KnitError;

mod common;
use common::surfaces::{grid, grid_buffers};

// ---------------------------------------------------------------------------------------------
// Builders

/// Mesh buffers: positions, normals, triangles, per-corner UVs.
#[derive(Default, Clone)]
struct Mesh {
    p: Vec<f32>,
    n: Vec<f32>,
    t: Vec<u32>,
    uv: Vec<f32>,
}

impl Mesh {
    fn vertex(&mut self, p: Vec3, n: Vec3) -> u32 {
        self.p.extend(p.to_array());
        self.n.extend(n.to_array());
        (self.p.len() / 3 - 1) as u32
    }

    fn triangle(&mut self, v: [u32; 3], uv: [Vec2; 3]) {
        self.t.extend(v);
        for q in uv {
            self.uv.extend(q.to_array());
        }
    }

    /// A quad `a b c d` (counter-clockwise) with UVs `ta tb tc td`, as two triangles.
    fn quad(&mut self, v: [u32; 4], uv: [Vec2; 4]) {
        self.triangle([v[0], v[1], v[2]], [uv[0], uv[1], uv[2]]);
        self.triangle([v[0], v[2], v[3]], [uv[0], uv[2], uv[3]]);
    }

    /// A `k x k` quad grid over `f(u, v) -> (position, normal)`, with UVs `uv_of(u, v)`.
    fn sheet(
        k: usize,
        f: impl Fn(f32, f32) -> (Vec3, Vec3),
        uv_of: impl Fn(f32, f32) -> Vec2,
    ) -> Mesh {
        let mut m = Mesh::default();
        let mut ids = Vec::new();
        let mut uvs = Vec::new();
        for i in 0..=k {
            for j in 0..=k {
                let (u, v) = (j as f32 / k as f32, i as f32 / k as f32);
                let (p, n) = f(u, v);
                ids.push(m.vertex(p, n));
                uvs.push(uv_of(u, v));
            }
        }
        let at = |i: usize, j: usize| i * (k + 1) + j;
        for i in 0..k {
            for j in 0..k {
                let c = [at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)];
                m.quad(c.map(|x| ids[x]), c.map(|x| uvs[x]));
            }
        }
        m
    }

    fn surface(&self) -> Result<MeshSurface, KnitError> {
        MeshSurface::new(&self.p, &self.n, &self.t, &self.uv)
    }
}

/// A flat 10 x 10 cm sheet in z = 0 with normal +Z and UVs = (x, y) / 10 cm.
fn flat_sheet(k: usize) -> Mesh {
    Mesh::sheet(
        k,
        |u, v| (Vec3::new(0.1 * u, 0.1 * v, 0.0), Vec3::Z),
        Vec2::new,
    )
}

/// Clearance kept by stockinette at these fixtures' coarse sampling (8 samples a loop), in
/// diameters: the interlocked loops' polyline cuts their corners (0.52 on the seamed tube).
const COARSE_FLOOR: f32 = 0.4;

fn params() -> KnitParams {
    KnitParams {
        ring_segments: 4,
        samples_per_loop: 8,
        threads: Some(2),
        ..Default::default()
    }
}

fn stockinette() -> StitchPattern {
    StitchPattern::preset("stockinette").unwrap()
}

// ---------------------------------------------------------------------------------------------
// Outcomes

/// Knits and checks the invariants of a successful knit: every buffer finite, stitch counts
/// that add up, the buffers sized from the stats. Returns the output and its clearance
/// (min, p01) in yarn diameters, printed with `name`.
fn knit_ok(name: &str, surface: &dyn Surface, p: &KnitParams) -> (KnitOutput, (f32, f32)) {
    let out = match knit(surface, &stockinette(), p) {
        Ok(out) => out,
        Err(e) => panic!("{name}: expected a knit, got the error {e}"),
    };
    let s = &out.stats;
    assert_eq!(
        s.stitches + s.stitches_skipped,
        s.courses * s.wales,
        "{name}: {s:?}"
    );
    assert_eq!(out.positions.len(), 3 * s.vertices, "{name}");
    assert_eq!(out.triangles.len(), 3 * s.triangles, "{name}");
    let bad = |buf: &[f32]| buf.iter().position(|x| !x.is_finite());
    assert_eq!(
        bad(&out.positions),
        None,
        "{name}: a position is not finite"
    );
    assert_eq!(bad(&out.colors), None, "{name}: a colour is not finite");
    assert_eq!(
        bad(&out.centerline),
        None,
        "{name}: a centreline point is not finite"
    );
    let nv = s.vertices as i32;
    assert!(
        out.triangles.iter().all(|&i| (0..nv).contains(&i)),
        "{name}: a triangle index is out of range"
    );
    assert!(
        out.yarn_radius.is_finite() && out.yarn_radius > 0.0,
        "{name}"
    );
    let c = measure(&out);
    assert!(
        !c.0.is_nan() && !c.1.is_nan(),
        "{name}: clearance not measurable"
    );
    println!(
        "{name:<34} ok: {} x {} = {} stitches built, {} skipped, {} clamped; clearance \
         min {:.2} p01 {:.2} diameters",
        s.courses, s.wales, s.stitches, s.stitches_skipped, s.stitches_clamped, c.0, c.1
    );
    (out, c)
}

/// The message of `r`'s error, which must be `variant` and contain every one of `words`.
fn expect_err<T: std::fmt::Debug>(
    name: &str,
    r: Result<T, KnitError>,
    variant: fn(&KnitError) -> bool,
    words: &[&str],
) -> String {
    match r {
        Err(e) if variant(&e) => {
            let msg = e.to_string();
            for w in words {
                assert!(msg.contains(w), "{name}: {msg:?} does not name {w:?}");
            }
            println!("{name:<34} error: {msg}");
            msg
        }
        other => panic!("{name}: expected a different outcome, got {other:?}"),
    }
}

fn is_surface(e: &KnitError) -> bool {
    matches!(e, KnitError::Surface(_))
}
fn is_parameter(e: &KnitError) -> bool {
    matches!(e, KnitError::Parameter(_))
}
fn is_budget(e: &KnitError) -> bool {
    matches!(e, KnitError::Budget(_))
}

// ---------------------------------------------------------------------------------------------
// 1. Poles and apexes

/// Blender's NURBS sphere: cyclic in u, pinched to a point at v = 0 and v = 1, where Blender
/// reports zero normals.
#[test]
fn nurbs_sphere_poles() {
    let (p, mut n) = grid_buffers(33, 32, true, |u, v| {
        let (a, lat) = (TAU * u, (v - 0.5) * PI);
        let d = Vec3::new(lat.cos() * a.cos(), lat.cos() * a.sin(), lat.sin());
        (0.05 * d, d)
    });
    // Zero normals on the pole rows, and the pole positions exactly equal.
    let (p, cols) = (
        p.chunks_exact(3)
            .enumerate()
            .flat_map(|(k, q)| match k / 32 {
                0 => [0.0, 0.0, -0.05],
                32 => [0.0, 0.0, 0.05],
                _ => [q[0], q[1], q[2]],
            })
            .collect::<Vec<f32>>(),
        32,
    );
    for k in (0..cols).chain(32 * cols..33 * cols) {
        n[3 * k..3 * k + 3].copy_from_slice(&[0.0; 3]);
    }
    let sphere = GridSurface::new(33, cols, &p, &n, true, false).unwrap();
    let (out, _) = knit_ok("nurbs sphere (poles)", &sphere, &params());
    // Every stitch is built: a grid has surface everywhere, poles included.
    assert_eq!(out.stats.stitches_skipped, 0);
    // The yarn stays near the sphere (no stitch flung off at a pole).
    let r = 0.05;
    let far = out
        .centerline
        .chunks_exact(3)
        .map(|q| (Vec3::from_slice(q).length() - r).abs())
        .fold(0.0f32, f32::max);
    assert!(far < 3.0 * out.yarn_radius * 2.0, "{far}");
}

/// Blender's UV sphere: one vertex at each pole, a fan of triangles round it whose pole
/// corners sit at the middle of each segment's UV column.
fn uv_sphere(segments: usize, rings: usize, radius: f32) -> Mesh {
    let mut m = Mesh::default();
    let dir = |a: f32, lat: f32| Vec3::new(lat.cos() * a.cos(), lat.cos() * a.sin(), lat.sin());
    let south = m.vertex(Vec3::new(0.0, 0.0, -radius), -Vec3::Z);
    let north = m.vertex(Vec3::new(0.0, 0.0, radius), Vec3::Z);
    // Ring vertices (rings - 1 rings), shared round the seam as Blender shares them.
    let mut ring = Vec::new();
    for r in 1..rings {
        let lat = -PI / 2.0 + PI * r as f32 / rings as f32;
        let ids: Vec<u32> = (0..segments)
            .map(|s| {
                let d = dir(TAU * s as f32 / segments as f32, lat);
                m.vertex(radius * d, d)
            })
            .collect();
        ring.push(ids);
    }
    let uv = |s: f32, r: f32| Vec2::new(s / segments as f32, r / rings as f32);
    for s in 0..segments {
        let s1 = (s + 1) % segments;
        let (sf, sf1) = (s as f32, s as f32 + 1.0);
        m.triangle(
            [south, ring[0][s1], ring[0][s]],
            [uv(sf + 0.5, 0.0), uv(sf1, 1.0), uv(sf, 1.0)],
        );
        for r in 1..rings - 1 {
            let (a, b) = (&ring[r - 1], &ring[r]);
            let (rf, rf1) = (r as f32, r as f32 + 1.0);
            m.quad(
                [a[s], a[s1], b[s1], b[s]],
                [uv(sf, rf), uv(sf1, rf), uv(sf1, rf1), uv(sf, rf1)],
            );
        }
        let top = &ring[rings - 2];
        let rl = (rings - 1) as f32;
        m.triangle(
            [top[s], top[s1], north],
            [uv(sf, rl), uv(sf1, rl), uv(sf + 0.5, rings as f32)],
        );
    }
    m
}

/// The pole fans leave gaps between their triangles in UV, which are no gaps in 3D: they
/// are closed (`surface::pole_fans`), and the courses run round the poles whole. Left open,
/// 212 stitches of this sphere's 1,848 had no surface under them and the courses round the
/// poles broke into single stitches, each finished as a little ring. What is still skipped
/// lies where the UV map's seam cuts the last teeth in half, beside its sides.
#[test]
fn uv_sphere_poles() {
    let (segments, rings) = (32, 16);
    let mesh = uv_sphere(segments, rings, 0.05);
    let sphere = mesh.surface().unwrap();
    // A point in the gap between two teeth lies on the edge they share, between the pole
    // and their ring vertex (3D): here half-way down the gap's middle line.
    let north = Vec3::new(0.0, 0.0, 0.05);
    let gap = Vec2::new(1.0 / segments as f32, 1.0 - 0.5 / rings as f32);
    let at = sphere
        .eval(gap)
        .expect("a point between two teeth is on the surface");
    let lat = PI / 2.0 - PI / rings as f32;
    let ring = 0.05
        * Vec3::new(
            lat.cos() * (TAU / segments as f32).cos(),
            lat.cos() * (TAU / segments as f32).sin(),
            lat.sin(),
        );
    let along = (at.position - north).cross(ring - north).length();
    assert!(along < 1e-6, "{:?} is off the edge by {along}", at.position);
    // The map closes round its seam, and so does the gap between the first tooth and the
    // last, in two halves (one at each side of the map): no stitch is lost at the poles and
    // every course runs whole round the sphere.
    assert!(sphere.cyclic_u() && !sphere.cyclic_v());
    let (out, _) = knit_ok("uv sphere (pole fans)", &sphere, &params());
    assert_eq!(out.stats.stitches_skipped, 0);
    assert!(out.yarn_closed.iter().all(|&closed| closed));
}

/// A cone, 5 cm round at the base, pinched to an apex at v = 1 (the normals there are the
/// cone's, different round the apex).
#[test]
fn cone_apex() {
    let (h, r) = (0.06f32, 0.03f32);
    let slope = Vec2::new(h, r).normalize();
    let cone = grid(24, 48, true, |u, v| {
        let a = TAU * u;
        (
            Vec3::new((1.0 - v) * r * a.cos(), (1.0 - v) * r * a.sin(), v * h),
            Vec3::new(slope.x * a.cos(), slope.x * a.sin(), slope.y),
        )
    });
    let (out, _) = knit_ok("cone apex", &cone, &params());
    assert_eq!(out.stats.stitches_skipped, 0);
}

// ---------------------------------------------------------------------------------------------
// 2. Seams and islands

/// A 4 cm cube with Blender's six-island cross layout in a 4 x 3 UV grid (half of the UV
/// bounding box has no island).
fn cube_cross() -> Mesh {
    let mut m = Mesh::default();
    let s = 0.04f32;
    // (normal, u axis, v axis) of each face; UV cell of each face in the cross.
    let faces = [
        (Vec3::NEG_Y, Vec3::X, Vec3::Z, (1, 1)),
        (Vec3::X, Vec3::Y, Vec3::Z, (2, 1)),
        (Vec3::Y, Vec3::NEG_X, Vec3::Z, (3, 1)),
        (Vec3::NEG_X, Vec3::NEG_Y, Vec3::Z, (0, 1)),
        (Vec3::Z, Vec3::X, Vec3::Y, (1, 2)),
        (Vec3::NEG_Z, Vec3::X, Vec3::NEG_Y, (1, 0)),
    ];
    for (n, a, b, (cu, cv)) in faces {
        let centre = 0.5 * s * n;
        let corner = |x: f32, y: f32| centre + s * (x - 0.5) * a + s * (y - 0.5) * b;
        let v = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
            .map(|(x, y)| m.vertex(corner(x, y), n));
        let uv = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
            .map(|(x, y)| Vec2::new((cu as f32 + x) / 4.0, (cv as f32 + y) / 3.0));
        m.quad(v, uv);
    }
    m
}

#[test]
fn cube_six_islands() {
    let cube = cube_cross().surface().unwrap();
    let (out, _) = knit_ok("cube, six UV islands", &cube, &params());
    let s = &out.stats;
    // Six of the twelve cells of the cross layout are islands: about half the stitches are
    // outside them (fewer: stitches straddling two adjacent islands are built).
    let fraction = s.stitches_skipped as f32 / (s.courses * s.wales) as f32;
    assert!((0.4..0.75).contains(&fraction), "{s:?}");
    // One yarn piece per run of built stitches: each course crosses one run of islands
    // (with live loops: no cast-on or bind-off where an island ends along v).
    let live = KnitParams {
        live_loops: true,
        ..params()
    };
    let (live_out, _) = knit_ok("cube, six UV islands, live loops", &cube, &live);
    assert_eq!(
        live_out.stats.yarn_pieces, s.courses,
        "{:?}",
        live_out.stats
    );
    // Finished, every island's lower and upper ends get theirs.
    assert!(s.yarn_pieces > s.courses, "{s:?}");
    // The cube's edges between neighbouring islands are creases: clamped there, not elsewhere.
    assert!(
        s.stitches_clamped > 0 && s.stitches_clamped < s.stitches / 4,
        "{s:?}"
    );
}

/// A 10 x 10 cm sheet whose right half is mirrored onto the left half's UVs (a symmetry
/// modifier's mirrored UVs): both halves cover the same (u,v); the lowest triangle wins.
#[test]
fn mirrored_half_uv() {
    let m = Mesh::sheet(
        16,
        |u, v| (Vec3::new(0.1 * u, 0.1 * v, 0.0), Vec3::Z),
        |u, v| Vec2::new(0.5 - (u - 0.5).abs(), v),
    );
    let (out, _) = knit_ok("mirrored half UV", &m.surface().unwrap(), &params());
    assert_eq!(out.stats.stitches_skipped, 0);
    // The extent is measured over the UV map's (u,v) domain, which is half the sheet.
    assert!((out.stats.stitch_width * out.stats.wales as f32 - 0.05).abs() < 1e-3);
}

/// Two separate 5 cm squares sharing one UV square (overlapping islands).
#[test]
fn overlapping_uvs() {
    let mut m = flat_sheet(4);
    let other = Mesh::sheet(
        4,
        |u, v| (Vec3::new(0.3 + 0.1 * u, 0.1 * v, 0.02), Vec3::Z),
        Vec2::new,
    );
    let base = (m.p.len() / 3) as u32;
    m.p.extend(&other.p);
    m.n.extend(&other.n);
    m.t.extend(other.t.iter().map(|i| i + base));
    m.uv.extend(&other.uv);
    let (out, _) = knit_ok("overlapping UVs", &m.surface().unwrap(), &params());
    assert_eq!(out.stats.stitches_skipped, 0);
    // Only the first square is knitted.
    assert!(out.centerline.chunks_exact(3).all(|q| q[0] < 0.2));
}

/// A tube cut open along a UV seam (the seam vertices doubled, UVs from 0 to 1 round it) is
/// knitted in the round: every course, the cast-on and the bind-off close on themselves
/// across the seam, as they would on a tube knitted on circular needles (before, the tube
/// was knitted flat, with yarn ends and a gap of about a stitch column along the seam).
#[test]
fn uv_seam_on_a_tube() {
    let m = Mesh::sheet(
        24,
        |u, v| {
            let a = TAU * u;
            let d = Vec3::new(a.cos(), a.sin(), 0.0);
            (0.02 * d + Vec3::new(0.0, 0.0, 0.06 * v), d)
        },
        Vec2::new,
    );
    let tube = m.surface().unwrap();
    assert!(tube.cyclic_u() && !tube.cyclic_v());
    let (out, c) = knit_ok("tube with a UV seam", &tube, &params());
    assert_eq!(out.stats.stitches_skipped, 0);
    assert!(c.0 > COARSE_FLOOR, "{c:?}");
    assert_eq!(out.yarn_closed.len(), out.stats.courses + 2);
    assert!(
        out.yarn_closed.iter().all(|&closed| closed),
        "{:?}",
        out.yarn_closed
    );
    // The same sheet unrolled flat (its two sides 6 cm apart) stays a flat piece.
    let flat = Mesh::sheet(
        24,
        |u, v| (Vec3::new(0.12 * u, 0.06 * v, 0.0), Vec3::Z),
        Vec2::new,
    );
    let (out, _) = knit_ok("sheet", &flat.surface().unwrap(), &params());
    assert!(out.yarn_closed.iter().all(|&closed| !closed));
}

// ---------------------------------------------------------------------------------------------
// 3. Degenerate triangles and doubled vertices

#[test]
fn degenerate_uv_triangles() {
    // A sheet whose middle column of quads has UVs collapsed: zero UV area in one triangle of
    // each quad (all corners at one point) and collinear UVs in the other.
    let mut m = flat_sheet(10);
    for q in 0..m.t.len() / 6 {
        if q % 10 == 5 {
            let (a, b) = (12 * q, 12 * q + 6);
            let first = [m.uv[a], m.uv[a + 1]];
            for k in 0..3 {
                m.uv[a + 2 * k..a + 2 * k + 2].copy_from_slice(&first);
            }
            let (u0, v0) = (m.uv[b], m.uv[b + 1]);
            m.uv[b + 2..b + 6].copy_from_slice(&[u0 + 0.05, v0, u0 + 0.1, v0]);
        }
    }
    let surface = m.surface().unwrap();
    assert_eq!(surface.uv_triangle_count(), 200 - 20);
    let (out, _) = knit_ok("degenerate UV triangles", &surface, &params());
    // The collapsed column is a gap in the UV map: the stitches over it are skipped.
    assert!(out.stats.stitches_skipped > 0, "{:?}", out.stats);

    // A mesh whose every UV triangle is degenerate is refused, naming the fix.
    let mut flat = flat_sheet(2);
    for x in flat.uv.chunks_exact_mut(2) {
        x[1] = 0.5;
    }
    expect_err(
        "only collinear UVs",
        flat.surface(),
        is_surface,
        &["UV area", "Unwrap"],
    );
}

#[test]
fn zero_area_3d_faces_and_doubled_vertices() {
    // The middle row of vertices is moved onto the row below: one row of quads has no 3D
    // area (but its UVs do).
    let k = 10;
    let m = Mesh::sheet(
        k,
        |u, v| {
            let v = if (v * k as f32 - 5.0).abs() < 0.1 {
                0.4
            } else {
                v
            };
            (Vec3::new(0.1 * u, 0.1 * v, 0.0), Vec3::Z)
        },
        Vec2::new,
    );
    knit_ok("zero-area 3D faces", &m.surface().unwrap(), &params());

    // Every vertex doubled: each triangle has its own three vertices, and each is there twice
    // (a mesh never merged by distance), with the duplicates unused.
    let flat = flat_sheet(8);
    let mut d = Mesh::default();
    for (t, corners) in flat.t.chunks_exact(3).enumerate() {
        let v = [0, 1, 2].map(|c| {
            let i = corners[c] as usize;
            let (p, n) = (
                Vec3::from_slice(&flat.p[3 * i..]),
                Vec3::from_slice(&flat.n[3 * i..]),
            );
            d.vertex(p, n);
            d.vertex(p, n)
        });
        let uv = [0, 1, 2].map(|c| Vec2::from_slice(&flat.uv[6 * t + 2 * c..]));
        d.triangle(v, uv);
    }
    let (out, c) = knit_ok("doubled vertices", &d.surface().unwrap(), &params());
    let (reference, rc) = knit_ok(
        "(the same sheet, merged)",
        &flat.surface().unwrap(),
        &params(),
    );
    let untimed = |o: &KnitOutput| knitwear::knit::KnitStats {
        seconds: 0.0,
        ..o.stats.clone()
    };
    assert_eq!(untimed(&out), untimed(&reference));
    assert_eq!(out.positions, reference.positions);
    assert_eq!(c, rc);
}

// ---------------------------------------------------------------------------------------------
// 4. Normals and topology

#[test]
fn flipped_and_inconsistent_normals() {
    // All normals flipped: the fabric mirrors to the other side, as well cleared.
    let up = flat_sheet(8);
    let mut down = up.clone();
    for x in down.n.iter_mut() {
        *x = -*x;
    }
    let (_, c_up) = knit_ok("normals up", &up.surface().unwrap(), &params());
    let (_, c_down) = knit_ok("normals flipped", &down.surface().unwrap(), &params());
    assert!((c_up.0 - c_down.0).abs() < 0.05, "{c_up:?} {c_down:?}");

    // Inconsistent: every other vertex's normal flipped (a mesh with mixed winding whose
    // normals were recalculated badly). Interpolated normals cancel inside triangles; the
    // triangle's own geometric normal takes over there.
    let mut mixed = up.clone();
    for (k, x) in mixed.n.chunks_exact_mut(3).enumerate() {
        if k % 2 == 1 {
            x[2] = -x[2];
        }
    }
    knit_ok("normals inconsistent", &mixed.surface().unwrap(), &params());

    // A grid with flipped normals on every other row.
    let g = grid(20, 20, false, |u, v| {
        let flip = if (v * 19.0).round() as i32 % 2 == 0 {
            1.0
        } else {
            -1.0
        };
        (Vec3::new(0.1 * u, 0.1 * v, 0.0), flip * Vec3::Z)
    });
    knit_ok("grid, normals flip every row", &g, &params());
}

#[test]
fn non_manifold_edge() {
    // Three 5 cm fins sharing one edge (the z axis), unwrapped side by side in UV.
    let mut m = Mesh::default();
    let (a, b) = (
        m.vertex(Vec3::ZERO, Vec3::X),
        m.vertex(Vec3::new(0.0, 0.0, 0.05), Vec3::X),
    );
    for f in 0..3 {
        let ang = TAU * f as f32 / 3.0;
        let out = Vec3::new(ang.cos(), ang.sin(), 0.0);
        let n = Vec3::new(-ang.sin(), ang.cos(), 0.0);
        let c = m.vertex(0.05 * out + Vec3::new(0.0, 0.0, 0.05), n);
        let d = m.vertex(0.05 * out, n);
        let u0 = f as f32 / 3.0;
        let u1 = u0 + 1.0 / 3.0;
        m.quad(
            [a, d, c, b],
            [
                Vec2::new(u0, 0.0),
                Vec2::new(u1, 0.0),
                Vec2::new(u1, 1.0),
                Vec2::new(u0, 1.0),
            ],
        );
    }
    knit_ok(
        "non-manifold edge (three fins)",
        &m.surface().unwrap(),
        &params(),
    );
}

// ---------------------------------------------------------------------------------------------
// 5. Anisotropic stretch

#[test]
fn uvs_stretched_100_to_1() {
    // A 1 m x 1 cm strip mapped onto the unit UV square: a UV step along u is 100 times longer
    // on the surface than one along v. Counts from the gauge follow the surface, not the UVs.
    let strip = Mesh::sheet(
        20,
        |u, v| (Vec3::new(1.0 * u, 0.01 * v, 0.0), Vec3::Z),
        Vec2::new,
    );
    let surface = strip.surface().unwrap();
    let (out, c) = knit_ok("UV stretch 100:1 (gauge)", &surface, &params());
    assert_eq!((out.stats.wales, out.stats.courses), (200, 3));
    assert!(c.0 > COARSE_FLOOR, "{c:?}");
    let g = grid(4, 200, false, |u, v| {
        (Vec3::new(1.0 * u, 0.01 * v, 0.0), Vec3::Z)
    });
    knit_ok("UV stretch 100:1 (grid)", &g, &params());

    // Forcing square counts on it asks for stitches 100 times wider than tall: the yarn a
    // stitch that wide needs cannot fit in a row that short.
    let p = KnitParams {
        courses: Some(20),
        wales: Some(20),
        ..params()
    };
    expect_err(
        "UV stretch 100:1 (forced counts)",
        knit(&surface, &stockinette(), &p),
        is_parameter,
        &["thicker than a stitch"],
    );
}

// ---------------------------------------------------------------------------------------------
// 6. Curvature tighter than the normal offsets

/// Smallest distance of a centreline point from the z axis.
fn min_axis_distance(out: &KnitOutput) -> f32 {
    out.centerline
        .chunks_exact(3)
        .map(|q| Vec2::new(q[0], q[1]).length())
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn thin_cylinder_clamps_offsets() {
    // A 1 mm cylinder knitted with 2 stitches round it and a yarn 1.2 mm thick: the tuned
    // offsets (up to a diameter either side) would push the yarn through the axis and out the
    // other side. They are clamped to half the local curvature radius.
    let r = 0.001f32;
    let thin = grid(40, 48, true, |u, v| {
        let a = TAU * u;
        let d = Vec3::new(a.cos(), a.sin(), 0.0);
        (r * d + Vec3::new(0.0, 0.0, 0.04 * v), d)
    });
    let p = KnitParams {
        courses: Some(16),
        wales: Some(2),
        yarn_radius: Some(0.0006),
        ..params()
    };
    let (out, c) = knit_ok("thin cylinder (r = 1 mm)", &thin, &p);
    // Every stitch: the fabric's 32 and the 2 + 2 of its cast-on and bind-off.
    assert_eq!(out.stats.stitches_clamped, 32 + 4, "{:?}", out.stats);
    // Known answer: the yarn stays outside half the radius (a little less where the spline
    // overshoots between key points).
    let inner = min_axis_distance(&out);
    println!(
        "    thin cylinder: nearest yarn point {:.3} mm from the axis",
        inner * 1e3
    );
    assert!(inner > 0.35 * r, "{inner}");
    assert!(c.0.is_finite());

    // The same knit on a thick cylinder is not clamped at all.
    let thick = grid(40, 96, true, |u, v| {
        let a = TAU * u;
        let d = Vec3::new(a.cos(), a.sin(), 0.0);
        (0.03 * d + Vec3::new(0.0, 0.0, 0.08 * v), d)
    });
    let (out, _) = knit_ok("thick cylinder (r = 3 cm)", &thick, &params());
    assert_eq!(out.stats.stitches_clamped, 0);
}

#[test]
fn sharp_crease_clamps_offsets() {
    // A sheet folded sharply along v = 0.5 into a V whose sides are 30 degrees apart (the
    // normal turns by 150 degrees), sampled finely: normals turn within one grid cell, far
    // tighter than a stitch.
    let half = 75f32.to_radians();
    let crease = grid(81, 40, false, |u, v| {
        let s = v - 0.5;
        let side = if s < 0.0 { -1.0 } else { 1.0 };
        let dir = Vec3::new(0.0, half.cos() * side, half.sin());
        let n = Vec3::new(0.0, -half.sin() * side, half.cos());
        let n = if s.abs() < 1e-6 { Vec3::Z } else { n };
        (Vec3::new(0.1 * u, 0.0, 0.0) + 0.1 * s.abs() * dir, n)
    });
    let (out, c) = knit_ok("sharp crease (30 degree V)", &crease, &params());
    assert!(out.stats.stitches_clamped > 0, "{:?}", out.stats);
    assert!(out.stats.stitches_clamped < out.stats.stitches / 2);
    println!("    sharp crease: clearance min {:.2} diameters", c.0);
}

// ---------------------------------------------------------------------------------------------
// 7. Non-finite coordinates

#[test]
fn nan_and_infinite_coordinates_are_named() {
    let (mut p, n) = grid_buffers(4, 5, false, |u, v| (Vec3::new(u, v, 0.0), Vec3::Z));
    p[3 * (2 * 5 + 3) + 1] = f32::NAN;
    expect_err(
        "grid, NaN position",
        GridSurface::new(4, 5, &p, &n, false, false),
        is_surface,
        &["position", "row 2, column 3", "NaN"],
    );
    let (p, mut n) = grid_buffers(4, 5, false, |u, v| (Vec3::new(u, v, 0.0), Vec3::Z));
    n[0] = f32::INFINITY;
    expect_err(
        "grid, infinite normal",
        GridSurface::new(4, 5, &p, &n, false, false),
        is_surface,
        &["normal", "row 0, column 0", "inf"],
    );
    // Finite but huge: lengths overflow f32.
    let (p, n) = grid_buffers(4, 5, false, |u, v| {
        (Vec3::new(3e38 * (2.0 * u - 1.0), v, 0.0), Vec3::Z)
    });
    expect_err(
        "grid, coordinates near f32::MAX",
        GridSurface::new(4, 5, &p, &n, false, false),
        is_surface,
        &["too large"],
    );

    let mut m = flat_sheet(2);
    m.p[3 * 4 + 2] = f32::NEG_INFINITY;
    expect_err(
        "mesh, infinite position",
        m.surface(),
        is_surface,
        &["position of vertex 4", "-inf"],
    );
    // Blender stores an infinite coordinate as the largest float: refused as too large.
    let mut m = flat_sheet(2);
    m.p[3 * 4] = f32::MAX;
    expect_err(
        "mesh, position 3.4e38 (Blender's inf)",
        m.surface(),
        is_surface,
        &["position of vertex 4", "3.4028235e38", "too large"],
    );
    let mut m = flat_sheet(2);
    m.uv[6 * 3 + 2] = f32::NAN; // triangle 3, corner 1, u
    expect_err(
        "mesh, NaN UV",
        m.surface(),
        is_surface,
        &["UV of triangle 3 corner 1", "NaN"],
    );
}

// ---------------------------------------------------------------------------------------------
// 8. Absurd requests

#[test]
fn absurd_requests() {
    let sheet = flat_sheet(4).surface().unwrap();
    let run = |p: KnitParams| knit(&sheet, &stockinette(), &p);
    expect_err(
        "10^9 stitches",
        run(KnitParams {
            courses: Some(1_000_000),
            wales: Some(1_000),
            ..params()
        }),
        is_budget,
        &["1000000000 stitches", "GiB"],
    );
    expect_err(
        "10^12 stitches from a gauge",
        run(KnitParams {
            gauge: Some((1e7, 1e7)),
            ..params()
        }),
        is_budget,
        &["gauge", "coarser gauge"],
    );
    for gauge in [
        (0.0, 28.0),
        (20.0, -28.0),
        (f32::NAN, 28.0),
        (f32::INFINITY, 28.0),
    ] {
        expect_err(
            &format!("gauge {gauge:?}"),
            run(KnitParams {
                gauge: Some(gauge),
                ..params()
            }),
            is_parameter,
            &["gauge must be positive"],
        );
    }
    for count in [0, 2_000_000] {
        expect_err(
            &format!("{count} courses"),
            run(KnitParams {
                courses: Some(count),
                ..params()
            }),
            is_parameter,
            &["courses must be in"],
        );
    }
    expect_err(
        "yarn thicker than a stitch",
        run(KnitParams {
            yarn_radius: Some(0.01),
            ..params()
        }),
        is_parameter,
        &["thicker than a stitch"],
    );
    for r in [0.0, -1.0, f32::NAN] {
        expect_err(
            &format!("yarn radius {r}"),
            run(KnitParams {
                yarn_radius: Some(r),
                ..params()
            }),
            is_parameter,
            &["yarn_radius must be positive"],
        );
    }
    for kappa in [-0.1, 0.5, f32::NAN] {
        expect_err(
            &format!("kappa {kappa}"),
            run(KnitParams { kappa, ..params() }),
            is_parameter,
            &["kappa"],
        );
    }
    expect_err(
        "stitch size (0, 1)",
        run(KnitParams {
            stitch_size: Some((0.0, 1.0)),
            ..params()
        }),
        is_parameter,
        &["stitch size"],
    );
    // A gauge so coarse the whole sheet is one stitch is not absurd: one stitch it is.
    let (out, _) = knit_ok(
        "gauge 0.001 (one stitch)",
        &sheet,
        &KnitParams {
            gauge: Some((0.001, 0.001)),
            ..params()
        },
    );
    assert_eq!(out.stats.stitches, 1);
}
