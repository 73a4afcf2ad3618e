//! Surfaces with planted answers: a plane, a cylinder with and without its duplicated seam, a
//! sphere with pinched poles; a UV-mapped square, cube islands, degenerate UVs. Benchmarks
//! (ignored by default) print evaluations per second:
//! `cargo test --release --test surface -- --ignored --nocapture`.

use std::f64::consts::TAU;

use glam::{Vec2, Vec3};
use knitwear::error::KnitError;
use knitwear::surface::{GridSurface, MeshSurface, Surface, SurfacePoint};

/// Deterministic uniform numbers in [0, 1) (a 64-bit LCG): tests must not depend on a seed
/// the machine picks.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn uv(&mut self) -> Vec2 {
        Vec2::new(self.next(), self.next())
    }
}

/// Row-major (rows, cols, 3) position and normal buffers of `f(u, v) -> (position, normal)`
/// sampled at `u_j = j / du`, `v_i = i / dv`.
fn sample_grid(
    rows: usize,
    cols: usize,
    du: f64,
    dv: f64,
    f: impl Fn(f64, f64) -> ([f64; 3], [f64; 3]),
) -> (Vec<f32>, Vec<f32>) {
    let (mut p, mut n) = (Vec::new(), Vec::new());
    for i in 0..rows {
        for j in 0..cols {
            let (pos, nrm) = f(j as f64 / du, i as f64 / dv);
            p.extend(pos.map(|x| x as f32));
            n.extend(nrm.map(|x| x as f32));
        }
    }
    (p, n)
}

fn plane_grid(rows: usize, cols: usize) -> GridSurface {
    let (p, n) = sample_grid(rows, cols, (cols - 1) as f64, (rows - 1) as f64, |u, v| {
        ([2.0 * u, 3.0 * v, 0.0], [0.0, 0.0, 1.0])
    });
    GridSurface::new(rows, cols, &p, &n, false, false).expect("a plane is a valid surface")
}

/// Radius-1 cylinder of height 2 around z, cyclic in u. With `seam`, the last column repeats
/// the first (as Blender's cyclic NURBS tessellation gives it).
fn cylinder(rows: usize, around: usize, seam: bool) -> GridSurface {
    let cols = if seam { around + 1 } else { around };
    let (p, n) = sample_grid(rows, cols, around as f64, (rows - 1) as f64, |u, v| {
        let (s, c) = (TAU * u).sin_cos();
        ([c, s, 2.0 * v], [c, s, 0.0])
    });
    GridSurface::new(rows, cols, &p, &n, true, false).expect("a cylinder is a valid surface")
}

fn assert_close(a: Vec3, b: Vec3, tol: f32) {
    assert!(a.distance(b) <= tol, "{a} != {b} (tolerance {tol})");
}

fn assert_unit(p: &SurfacePoint) {
    assert!(p.position.is_finite() && p.normal.is_finite(), "{p:?}");
    assert!((p.normal.length() - 1.0).abs() < 1e-5, "{p:?}");
}

fn surface_error<T>(r: Result<T, KnitError>) -> String {
    match r {
        Err(KnitError::Surface(msg)) => msg,
        Err(e) => panic!("expected a surface error, got {e:?}"),
        Ok(_) => panic!("expected a surface error, got a surface"),
    }
}

// ---------------------------------------------------------------- grid

#[test]
fn grid_plane_evaluates_exactly() {
    let g = plane_grid(5, 7);
    assert_eq!((g.rows(), g.cols()), (5, 7));
    let mut rng = Lcg(1);
    for _ in 0..10_000 {
        let uv = rng.uv();
        let p = g.eval(uv).expect("a grid covers its domain");
        assert_close(p.position, Vec3::new(2.0 * uv.x, 3.0 * uv.y, 0.0), 1e-5);
        assert_eq!(p.normal, Vec3::Z);
        assert_eq!(g.eval_nearest(uv), p);
    }
    // Samples come back exactly, corners included.
    assert_eq!(
        g.eval(Vec2::new(1.0, 1.0)).unwrap().position,
        Vec3::new(2.0, 3.0, 0.0)
    );
    assert_eq!(g.eval(Vec2::ZERO).unwrap().position, Vec3::ZERO);
    let (eu, ev) = g.extent();
    assert!(
        (eu - 2.0).abs() < 1e-5 && (ev - 3.0).abs() < 1e-5,
        "extent {:?}",
        g.extent()
    );
    assert_eq!(g.domain().size(), Vec2::ONE);
    assert!(!g.cyclic_u() && !g.cyclic_v());
}

#[test]
fn grid_clamps_outside_its_domain_and_survives_nan() {
    let g = plane_grid(3, 3);
    assert_eq!(
        g.eval(Vec2::new(-0.5, 1.5)).unwrap().position,
        Vec3::new(0.0, 3.0, 0.0)
    );
    assert_eq!(
        g.eval(Vec2::new(7.0, -3.0)).unwrap().position,
        Vec3::new(2.0, 0.0, 0.0)
    );
    for uv in [
        Vec2::NAN,
        Vec2::new(f32::INFINITY, f32::NEG_INFINITY),
        Vec2::splat(1e30),
    ] {
        assert_unit(&g.eval_nearest(uv));
    }
}

#[test]
fn grid_cylinder_wraps_with_and_without_seam_column() {
    let around = 64;
    let plain = cylinder(9, around, false);
    let seamed = cylinder(9, around, true);
    assert_eq!(plain.cols(), around);
    assert_eq!(
        seamed.cols(),
        around,
        "the duplicated seam column is dropped"
    );
    assert!(plain.cyclic_u() && !plain.cyclic_v());

    let mut rng = Lcg(2);
    for _ in 0..10_000 {
        let uv = rng.uv();
        let a = plain.eval(uv).unwrap();
        assert_eq!(a, seamed.eval(uv).unwrap());
        assert_unit(&a);
        // Wrapping: a whole turn later, or earlier, is the same point.
        for shift in [1.0, -1.0, 3.0] {
            let b = plain.eval(uv + Vec2::new(shift, 0.0)).unwrap();
            assert_close(a.position, b.position, 1e-4);
        }
        // On the polygon: between cos(pi / n) and 1 from the axis, normal radial.
        let r = a.position.truncate().length();
        assert!(r <= 1.0 + 1e-5 && r >= (std::f32::consts::PI / around as f32).cos() - 1e-5);
        assert!(a.normal.z.abs() < 1e-5 && a.normal.truncate().dot(a.position.truncate()) > 0.0);
    }
    // The wrap cell: halfway between the last column and the first is the chord's midpoint.
    let mid = plain
        .eval(Vec2::new(1.0 - 0.5 / around as f32, 0.0))
        .unwrap();
    let half = std::f32::consts::PI / around as f32;
    assert_close(
        mid.position,
        Vec3::new(half.cos() * half.cos(), -half.cos() * half.sin(), 0.0),
        1e-5,
    );

    // Extent: the polygon's perimeter (within its 2 pi (1 - sinc) of the circle) by the height.
    let polygon = 2.0 * around as f32 * half.sin();
    for g in [&plain, &seamed] {
        let (eu, ev) = g.extent();
        assert!((eu - polygon).abs() < 1e-4, "{eu} vs {polygon}");
        assert!((eu - std::f32::consts::TAU).abs() < 0.01);
        assert!((ev - 2.0).abs() < 1e-5);
    }
}

#[test]
fn grid_cyclic_in_both_directions_torus() {
    // Torus: major radius 2, minor 0.5; u round the tube's path, v round the tube.
    let (rows, cols) = (24, 48);
    let (p, n) = sample_grid(rows + 1, cols + 1, cols as f64, rows as f64, |u, v| {
        let (su, cu) = (TAU * u).sin_cos();
        let (sv, cv) = (TAU * v).sin_cos();
        let r = 2.0 + 0.5 * cv;
        ([r * cu, r * su, 0.5 * sv], [cv * cu, cv * su, sv])
    });
    let g = GridSurface::new(rows + 1, cols + 1, &p, &n, true, true).unwrap();
    assert_eq!((g.rows(), g.cols()), (rows, cols), "both seams dropped");
    let (eu, ev) = g.extent();
    // Mean over v of the circle of radius 2 + 0.5 cos(v) is 2 pi * 2 (polygon: a bit less).
    assert!((eu - 4.0 * std::f32::consts::PI).abs() < 0.05, "{eu}");
    assert!((ev - std::f32::consts::PI).abs() < 0.01, "{ev}");
    let a = g.eval(Vec2::new(0.3, 0.9)).unwrap();
    let b = g.eval(Vec2::new(1.3, -0.1)).unwrap();
    assert_close(a.position, b.position, 1e-4);
}

#[test]
fn grid_nan_is_rejected_with_its_index() {
    let (rows, cols) = (4, 5);
    let (mut p, n) = sample_grid(rows, cols, 4.0, 3.0, |u, v| ([u, v, 0.0], [0.0, 0.0, 1.0]));
    p[3 * (2 * cols + 3) + 1] = f32::NAN; // row 2, column 3, y
    let msg = surface_error(GridSurface::new(rows, cols, &p, &n, false, false));
    assert!(
        msg.contains("row 2") && msg.contains("column 3") && msg.contains("40"),
        "{msg}"
    );

    let (p, mut n) = sample_grid(rows, cols, 4.0, 3.0, |u, v| ([u, v, 0.0], [0.0, 0.0, 1.0]));
    n[5] = f32::INFINITY;
    let msg = surface_error(GridSurface::new(rows, cols, &p, &n, false, false));
    assert!(msg.contains("normal") && msg.contains("column 1"), "{msg}");
}

#[test]
fn grid_rejects_bad_shapes_and_degenerate_surfaces() {
    let (p, n) = sample_grid(3, 3, 2.0, 2.0, |u, v| ([u, v, 0.0], [0.0, 0.0, 1.0]));
    surface_error(GridSurface::new(1, 9, &p, &n, false, false));
    surface_error(GridSurface::new(0, 0, &[], &[], false, false));
    surface_error(GridSurface::new(3, 2, &p, &n, false, false));
    surface_error(GridSurface::new(3, 3, &p, &n[..6], false, false));
    surface_error(GridSurface::new(usize::MAX, 3, &p, &n, false, false));
    // Every point the same: no area.
    let same = vec![1.0f32; 27];
    let msg = surface_error(GridSurface::new(3, 3, &same, &n, false, false));
    assert!(msg.contains("no area"), "{msg}");
    // Every row a single point (a curve along v): no length along u.
    let (line, _) = sample_grid(3, 3, 2.0, 2.0, |_, v| ([0.0, v, 0.0], [0.0; 3]));
    surface_error(GridSurface::new(3, 3, &line, &n, false, false));
}

#[test]
fn grid_sphere_poles_get_finite_normals() {
    // Latitude along v from the south pole to the north pole; Blender gives zero normals
    // where the surface pinches. Longitude along u, cyclic, with a seam column.
    let (rows, around) = (17, 32);
    let (p, n) = sample_grid(
        rows,
        around + 1,
        around as f64,
        (rows - 1) as f64,
        |u, v| {
            let (st, ct) = (std::f64::consts::PI * v).sin_cos();
            let (sp, cp) = (TAU * u).sin_cos();
            let pos = [st * cp, st * sp, -ct];
            let pole = v == 0.0 || v == 1.0;
            (pos, if pole { [0.0; 3] } else { pos })
        },
    );
    let g = GridSurface::new(rows, around + 1, &p, &n, true, false).unwrap();
    for j in 0..g.cols() {
        for (i, z) in [(0, -1.0), (rows - 1, 1.0)] {
            let s = g.sample(i, j).unwrap();
            assert_unit(&s);
            // Points away from the sphere, within a grid step of the pole's true normal.
            assert!(
                s.normal.dot(Vec3::new(0.0, 0.0, z)) > (std::f32::consts::PI / 16.0).cos() - 1e-3
            );
        }
    }
    let mut rng = Lcg(3);
    for _ in 0..10_000 {
        let p = g.eval(rng.uv()).unwrap();
        assert_unit(&p);
        assert!(p.normal.dot(p.position) > 0.0, "{p:?}");
    }
}

#[test]
fn grid_collapsed_regions_get_normals_in_linear_time() {
    // A 600 x 600 cone whose upper half is pinched to its apex (every sample there at one
    // point, zero normals): repaired by growing the valid normals, not by a search per sample.
    let n = 600;
    let (p, nr) = sample_grid(n, n, n as f64, (n - 1) as f64, |u, v| {
        let r = (1.0 - 2.0 * v).max(0.0);
        let (s, c) = (TAU * u).sin_cos();
        let slope = std::f64::consts::FRAC_1_SQRT_2;
        (
            [r * c, r * s, 1.0 - r],
            if r > 0.0 {
                [c * slope, s * slope, slope]
            } else {
                [0.0; 3]
            },
        )
    });
    let g = GridSurface::new(n, n, &p, &nr, true, false).unwrap();
    for i in [n / 2, n - 1] {
        for j in [0, n / 3] {
            let s = g.sample(i, j).unwrap();
            assert_unit(&s);
            assert!(s.normal.z > 0.5, "{s:?}");
        }
    }
    // A grid whose points all lie on a line has no normal anywhere: +Z, never NaN.
    let (p, nr) = sample_grid(50, 50, 49.0, 49.0, |u, v| ([u + v, 0.0, 0.0], [0.0; 3]));
    let g = GridSurface::new(50, 50, &p, &nr, false, false).unwrap();
    assert_eq!(g.eval(Vec2::splat(0.3)).unwrap().normal, Vec3::Z);
}

#[test]
fn grid_zero_normals_come_from_finite_differences() {
    // No normals at all: derived as du x dv.
    let (p, n) = sample_grid(3, 4, 3.0, 2.0, |u, v| ([2.0 * u, 3.0 * v, 0.0], [0.0; 3]));
    let g = GridSurface::new(3, 4, &p, &n, false, false).unwrap();
    for uv in [Vec2::ZERO, Vec2::splat(0.5), Vec2::ONE] {
        assert_eq!(g.eval(uv).unwrap().normal, Vec3::Z);
    }
    // One zero normal among -Z ones: derived, then oriented like its neighbours.
    let (p, mut n) = sample_grid(3, 4, 3.0, 2.0, |u, v| {
        ([2.0 * u, 3.0 * v, 0.0], [0.0, 0.0, -1.0])
    });
    n[3 * 5..3 * 6].fill(0.0);
    let g = GridSurface::new(3, 4, &p, &n, false, false).unwrap();
    assert_eq!(g.sample(1, 1).unwrap().normal, -Vec3::Z);
    // Opposite normals in one cell cancel halfway: the nearest sample's normal instead.
    let (p, mut n) = sample_grid(2, 2, 1.0, 1.0, |u, v| ([u, v, 0.0], [0.0, 0.0, 1.0]));
    n[5] = -1.0;
    n[11] = -1.0;
    let g = GridSurface::new(2, 2, &p, &n, false, false).unwrap();
    assert_unit(&g.eval(Vec2::new(0.5, 0.5)).unwrap());
}

// ---------------------------------------------------------------- mesh

/// A unit square in z = 0 split along its diagonal into two triangles, UV = (x, y).
fn unit_square() -> MeshSurface {
    let positions = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];
    let normals = [0., 0., 1.].repeat(4);
    let triangles = [0, 1, 2, 0, 2, 3];
    let uvs = [0., 0., 1., 0., 1., 1., 0., 0., 1., 1., 0., 1.];
    MeshSurface::new(&positions, &normals, &triangles, &uvs).unwrap()
}

#[test]
fn mesh_square_interior_diagonal_and_outside() {
    let m = unit_square();
    assert_eq!(
        (m.triangle_count(), m.uv_triangle_count(), m.vertex_count()),
        (2, 2, 4)
    );
    let mut rng = Lcg(4);
    for _ in 0..10_000 {
        let uv = rng.uv();
        let p = m.eval(uv).expect("inside the square");
        assert_close(p.position, uv.extend(0.0), 1e-6);
        assert_eq!(p.normal, Vec3::Z);
    }
    // On the shared diagonal: found, and deterministically in the lower-index triangle.
    for k in 0..=100 {
        let t = k as f32 / 100.0;
        let p = m.eval(Vec2::splat(t)).expect("on the diagonal");
        assert_close(p.position, Vec3::new(t, t, 0.0), 1e-6);
        assert_eq!(m.locate(Vec2::splat(t)), Some(0));
    }
    // Corners and edges of the square.
    for uv in [
        Vec2::ZERO,
        Vec2::X,
        Vec2::ONE,
        Vec2::Y,
        Vec2::new(0.5, 0.0),
        Vec2::new(1.0, 0.3),
    ] {
        assert_close(
            m.eval(uv).expect("on the border").position,
            uv.extend(0.0),
            1e-6,
        );
    }
    for uv in [
        Vec2::new(1.5, 0.5),
        Vec2::new(-0.01, 0.5),
        Vec2::new(0.5, 1.001),
        Vec2::NAN,
    ] {
        assert_eq!(m.eval(uv), None, "{uv}");
    }
    let d = m.domain();
    assert_eq!((d.min, d.max), (Vec2::ZERO, Vec2::ONE));
    assert!(!m.cyclic_u() && !m.cyclic_v());
}

#[test]
fn mesh_eval_nearest_snaps_to_the_border() {
    let m = unit_square();
    let cases = [
        (Vec2::new(1.5, 0.5), Vec3::new(1.0, 0.5, 0.0)),
        (Vec2::new(-3.0, 0.25), Vec3::new(0.0, 0.25, 0.0)),
        (Vec2::new(0.7, -0.2), Vec3::new(0.7, 0.0, 0.0)),
        (Vec2::new(2.0, 2.0), Vec3::new(1.0, 1.0, 0.0)),
        (Vec2::new(-1e30, 0.5), Vec3::new(0.0, 0.5, 0.0)),
        (Vec2::new(0.3, 0.4), Vec3::new(0.3, 0.4, 0.0)),
    ];
    for (uv, want) in cases {
        let p = m.eval_nearest(uv);
        assert_close(p.position, want, 1e-5);
        assert_eq!(p.normal, Vec3::Z);
    }
    for uv in [
        Vec2::NAN,
        Vec2::new(f32::INFINITY, 0.5),
        Vec2::new(0.5, f32::NEG_INFINITY),
    ] {
        assert_unit(&m.eval_nearest(uv));
    }
}

#[test]
fn mesh_extent_of_a_scaled_plane() {
    // A 2 x 3 plane, 10 x 10 quads, UV in [0.5, 1] x [0, 2] (not the unit square on purpose).
    let n = 10;
    let (mut pos, mut nrm, mut tri, mut uv) = (vec![], vec![], vec![], vec![]);
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (j as f32 / n as f32, i as f32 / n as f32);
            pos.extend([2.0 * x, 3.0 * y, 0.0]);
            nrm.extend([0.0, 0.0, 1.0]);
        }
    }
    let uv_of = |k: u32| {
        let (i, j) = (k / (n + 1), k % (n + 1));
        [0.5 + 0.5 * j as f32 / n as f32, 2.0 * i as f32 / n as f32]
    };
    for i in 0..n {
        for j in 0..n {
            let k = i * (n + 1) + j;
            for t in [[k, k + 1, k + n + 2], [k, k + n + 2, k + n + 1]] {
                tri.extend(t);
                uv.extend(t.iter().flat_map(|&v| uv_of(v)));
            }
        }
    }
    let m = MeshSurface::new(&pos, &nrm, &tri, &uv).unwrap();
    let (eu, ev) = m.extent();
    assert!(
        (eu - 2.0).abs() < 1e-5 && (ev - 3.0).abs() < 1e-5,
        "{:?}",
        m.extent()
    );
    let p = m.eval(Vec2::new(0.75, 1.0)).unwrap();
    assert_close(p.position, Vec3::new(1.0, 1.5, 0.0), 1e-5);
}

/// The six faces of the cube [-1, 1]^3 as separate UV islands: face f is the square
/// [0.35 c, 0.35 c + 0.3] x [0.5 r, 0.5 r + 0.4] (c = f % 3, r = f / 3), gaps between them.
fn cube_islands() -> (MeshSurface, Vec<(Vec3, Vec3, Vec3, Vec2)>) {
    let (mut pos, mut nrm, mut tri, mut uv) = (vec![], vec![], vec![], vec![]);
    let mut faces = vec![];
    for f in 0..6u32 {
        let axis = (f / 2) as usize;
        let sign = if f % 2 == 0 { 1.0 } else { -1.0 };
        let mut normal = Vec3::ZERO;
        normal[axis] = sign;
        // Two tangents spanning the face.
        let mut t1 = Vec3::ZERO;
        let mut t2 = Vec3::ZERO;
        t1[(axis + 1) % 3] = 1.0;
        t2[(axis + 2) % 3] = 1.0;
        let corner = Vec2::new(0.35 * (f % 3) as f32, 0.5 * (f / 3) as f32);
        let size = Vec2::new(0.3, 0.4);
        let base = pos.len() as u32 / 3;
        for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            pos.extend((normal + t1 * a + t2 * b).to_array());
            nrm.extend(normal.to_array());
        }
        let uv_of = |k: u32| {
            let (a, b) = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)][k as usize];
            corner + size * Vec2::new(a, b)
        };
        for t in [[0, 1, 2], [0, 2, 3]] {
            tri.extend(t.map(|k| base + k));
            uv.extend(t.iter().flat_map(|&k| uv_of(k).to_array()));
        }
        faces.push((normal, t1, t2, corner));
    }
    (MeshSurface::new(&pos, &nrm, &tri, &uv).unwrap(), faces)
}

#[test]
fn mesh_cube_islands() {
    let (m, faces) = cube_islands();
    let size = Vec2::new(0.3, 0.4);
    let d = m.domain();
    assert_close(d.min.extend(0.0), Vec3::ZERO, 1e-6);
    assert_close(d.max.extend(0.0), Vec3::new(1.0, 0.9, 0.0), 1e-6);
    let mut rng = Lcg(5);
    for (normal, t1, t2, corner) in &faces {
        for _ in 0..1000 {
            let local = rng.uv();
            let p = m.eval(*corner + size * local).expect("inside an island");
            let want = *normal + *t1 * (2.0 * local.x - 1.0) + *t2 * (2.0 * local.y - 1.0);
            assert_close(p.position, want, 1e-5);
            assert_eq!(p.normal, *normal);
        }
    }
    // Gaps between islands have no surface; eval_nearest snaps to the nearer island's edge.
    let gap = Vec2::new(0.31, 0.2); // 0.01 right of face 0, 0.04 left of face 1
    assert_eq!(m.eval(gap), None);
    let p = m.eval_nearest(gap);
    let (normal, t1, t2, _) = faces[0];
    assert_close(p.position, normal + t1 + t2 * (2.0 * 0.5 - 1.0), 1e-5);
    assert_eq!(m.eval(Vec2::new(0.5, 0.45)), None);
    let p = m.eval_nearest(Vec2::new(0.5, 0.42)); // 0.02 above face 1, 0.08 below face 4
    let (normal, t1, t2, _) = faces[1];
    assert_close(
        p.position,
        normal + t1 * (2.0 * (0.15 / 0.3) - 1.0) + t2,
        1e-5,
    );
    // Extent: islands are each 2 units across their 0.3 x 0.4 UV, domain 1 x 0.9.
    let (eu, ev) = m.extent();
    assert!(
        (eu - 2.0 / 0.3).abs() < 1e-4 && (ev - 2.0 / 0.4 * 0.9).abs() < 1e-4,
        "{eu} {ev}"
    );
}

#[test]
fn mesh_degenerate_uv_triangles_are_ignored() {
    // Triangle 0 has zero UV area across the square's middle (and far-away positions); it
    // must neither win lookups nor widen the domain.
    let positions = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 9., 9., 9.];
    let normals = [0., 0., 1.].repeat(5);
    let triangles = [4, 4, 4, 0, 1, 2, 0, 2, 3, 1, 2, 4];
    let uvs = [
        0., 0., 2., 2., 1., 1., // collinear: zero area
        0., 0., 1., 0., 1., 1., //
        0., 0., 1., 1., 0., 1., //
        0.5, 0.5, 0.5, 0.5, 0.5, 0.5, // a point
    ];
    let m = MeshSurface::new(&positions, &normals, &triangles, &uvs).unwrap();
    assert_eq!((m.triangle_count(), m.uv_triangle_count()), (4, 2));
    assert_eq!(m.domain().max, Vec2::ONE);
    assert_eq!(m.locate(Vec2::new(0.5, 0.5)), Some(1));
    assert_close(
        m.eval(Vec2::new(0.5, 0.5)).unwrap().position,
        Vec3::new(0.5, 0.5, 0.0),
        1e-6,
    );
    assert_eq!(m.eval(Vec2::new(1.5, 1.5)), None);
    // All degenerate: an error that says what to do.
    let msg = surface_error(MeshSurface::new(
        &positions,
        &normals,
        &triangles[..3],
        &uvs[..6],
    ));
    assert!(msg.contains("UV"), "{msg}");
}

#[test]
fn mesh_zero_area_triangle_and_zero_normals_stay_finite() {
    // All three vertices at one point (zero 3D area) with zero normals: a UV area that maps
    // to a point. Plus a normal triangle whose normals cancel at its centre.
    let positions = [
        1., 2., 3., 1., 2., 3., 1., 2., 3., 0., 0., 0., 1., 0., 0., 0., 1., 0.,
    ];
    let normals = [
        0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 1., 0., 0., -1., 0., 0., 1.,
    ];
    let triangles = [0, 1, 2, 3, 4, 5];
    let uvs = [0., 0., 1., 0., 0., 1., 2., 0., 3., 0., 2., 1.];
    let m = MeshSurface::new(&positions, &normals, &triangles, &uvs).unwrap();
    let p = m.eval(Vec2::new(0.2, 0.2)).unwrap();
    assert_eq!(p.position, Vec3::new(1.0, 2.0, 3.0));
    assert_unit(&p);
    let p = m.eval(Vec2::new(2.5, 0.0)).unwrap();
    assert_unit(&p);
    assert_eq!(
        p.normal,
        Vec3::Z,
        "geometric normal, oriented like the vertex normals"
    );
}

#[test]
fn mesh_without_3d_area_is_rejected() {
    // UV area, but every vertex at one point: nothing to knit on.
    let positions = [1., 1., 1.].repeat(3);
    let normals = [0., 0., 1.].repeat(3);
    let msg = surface_error(MeshSurface::new(
        &positions,
        &normals,
        &[0, 1, 2],
        &[0., 0., 1., 0., 0., 1.],
    ));
    assert!(msg.contains("no area"), "{msg}");
}

#[test]
fn mesh_overlapping_islands_pick_the_lowest_index() {
    // Two squares with the same UVs, at z = 0 (triangles 2, 3) and z = 1 (triangles 0, 1).
    let positions = [
        0., 0., 1., 1., 0., 1., 1., 1., 1., 0., 1., 1., 0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1.,
        0.,
    ];
    let normals = [0., 0., 1.].repeat(8);
    let triangles = [0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
    let uvs = [0., 0., 1., 0., 1., 1., 0., 0., 1., 1., 0., 1.].repeat(2);
    let m = MeshSurface::new(&positions, &normals, &triangles, &uvs).unwrap();
    let mut rng = Lcg(6);
    for _ in 0..1000 {
        assert_eq!(m.eval(rng.uv()).unwrap().position.z, 1.0);
    }
}

#[test]
fn mesh_bad_input_is_rejected() {
    let positions = [0., 0., 0., 1., 0., 0., 1., 1., 0.];
    let normals = [0., 0., 1.].repeat(3);
    let uvs = [0., 0., 1., 0., 1., 1.];
    let msg = surface_error(MeshSurface::new(&positions, &normals, &[0, 1, 7], &uvs));
    assert!(
        msg.contains("vertex 7") && msg.contains("corner 2"),
        "{msg}"
    );
    let mut bad = uvs;
    bad[3] = f32::NAN;
    let msg = surface_error(MeshSurface::new(&positions, &normals, &[0, 1, 2], &bad));
    assert!(msg.contains("triangle 0 corner 1"), "{msg}");
    let mut bad = positions;
    bad[4] = f32::INFINITY;
    let msg = surface_error(MeshSurface::new(&bad, &normals, &[0, 1, 2], &uvs));
    assert!(msg.contains("vertex 1"), "{msg}");
    surface_error(MeshSurface::new(
        &positions[..8],
        &normals,
        &[0, 1, 2],
        &uvs,
    ));
    surface_error(MeshSurface::new(
        &positions,
        &normals[..6],
        &[0, 1, 2],
        &uvs,
    ));
    surface_error(MeshSurface::new(&positions, &normals, &[0, 1], &uvs));
    surface_error(MeshSurface::new(
        &positions,
        &normals,
        &[0, 1, 2],
        &uvs[..5],
    ));
    surface_error(MeshSurface::new(&[], &[], &[], &[]));
}

/// A wavy `n x n`-quad sheet with jittered UVs (a real unwrap is never a regular grid).
fn jittered_sheet(n: u32, seed: u64) -> (Vec<f32>, Vec<f32>, Vec<u32>, Vec<f32>) {
    let mut rng = Lcg(seed);
    let (mut pos, mut nrm, mut tri, mut uv) = (vec![], vec![], vec![], vec![]);
    let mut vuv = vec![];
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (j as f32 / n as f32, i as f32 / n as f32);
            pos.extend([x, y, 0.1 * (6.0 * x).sin() * (4.0 * y).cos()]);
            nrm.extend([0.0, 0.0, 1.0]);
            let inner = i > 0 && i < n && j > 0 && j < n;
            let jitter = if inner { 0.3 / n as f32 } else { 0.0 };
            vuv.push(Vec2::new(
                x + jitter * (rng.next() - 0.5),
                y + jitter * (rng.next() - 0.5),
            ));
        }
    }
    for i in 0..n {
        for j in 0..n {
            let k = i * (n + 1) + j;
            for t in [[k, k + 1, k + n + 2], [k, k + n + 2, k + n + 1]] {
                tri.extend(t);
                uv.extend(t.iter().flat_map(|&v| vuv[v as usize].to_array()));
            }
        }
    }
    (pos, nrm, tri, uv)
}

#[test]
fn mesh_index_agrees_with_brute_force() {
    let (pos, nrm, tri, uv) = jittered_sheet(30, 7);
    let m = MeshSurface::new(&pos, &nrm, &tri, &uv).unwrap();
    let corners: Vec<[Vec2; 3]> = uv
        .chunks_exact(6)
        .map(|c| {
            [
                Vec2::new(c[0], c[1]),
                Vec2::new(c[2], c[3]),
                Vec2::new(c[4], c[5]),
            ]
        })
        .collect();
    let dist_to_tri = |p: Vec2, t: &[Vec2; 3]| -> f32 {
        let inside = (0..3).all(|e| (t[(e + 1) % 3] - t[e]).perp_dot(p - t[e]) >= 0.0);
        if inside {
            return 0.0;
        }
        (0..3)
            .map(|e| {
                let (a, b) = (t[e], t[(e + 1) % 3]);
                let s = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                (a + (b - a) * s).distance(p)
            })
            .fold(f32::INFINITY, f32::min)
    };
    let mut rng = Lcg(8);
    for _ in 0..20_000 {
        // Some points outside the sheet, for eval_nearest.
        let uv = rng.uv() * 1.4 - Vec2::splat(0.2);
        let brute = corners
            .iter()
            .map(|t| dist_to_tri(uv, t))
            .fold(f32::INFINITY, f32::min);
        match m.eval(uv) {
            Some(p) => {
                assert!(
                    brute < 1e-5,
                    "{uv}: found by the index, {brute} away by brute force"
                );
                assert_unit(&p);
            }
            None => assert!(brute > 0.0, "{uv}: inside a triangle, missed by the index"),
        }
        // eval_nearest lands at the brute-force distance (positions are a UV-to-xy identity
        // up to the jitter, so compare UV distances through the located point).
        let p = m.eval_nearest(uv);
        assert_unit(&p);
        if brute > 1e-3 {
            let reach = (p.position.truncate() - uv).length();
            // The sheet's xy is its UV up to the jitter (0.15 / n): within that of brute.
            assert!(
                (reach - brute).abs() < 0.3 / 30.0,
                "{uv}: {reach} vs {brute}"
            );
        }
    }
}

/// Squared UV distance from `p` to triangle `t`, by brute force (0 inside).
fn uv_distance2(p: Vec2, t: &[Vec2; 3]) -> f32 {
    let side = |e: usize| (t[(e + 1) % 3] - t[e]).perp_dot(p - t[e]);
    let (s0, s1, s2) = (side(0), side(1), side(2));
    if (s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) || (s0 <= 0.0 && s1 <= 0.0 && s2 <= 0.0) {
        return 0.0;
    }
    (0..3)
        .map(|e| {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            let s = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            (a + (b - a) * s).distance_squared(p)
        })
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn mesh_nearest_among_scattered_islands_is_exact() {
    // 400 small triangles scattered over [0, 1]^2 (both windings, some overlapping): most of
    // the domain is holes, at every distance from the nearest island.
    let mut rng = Lcg(12);
    let (mut pos, mut nrm, mut tri, mut uv) = (vec![], vec![], vec![], vec![]);
    let mut corners = vec![];
    for k in 0..400u32 {
        let c = rng.uv();
        let t = [0, 1, 2].map(|_| c + (rng.uv() - Vec2::splat(0.5)) * 0.03);
        for p in t {
            pos.extend([p.x, p.y, 0.0]);
            nrm.extend([0.0, 0.0, 1.0]);
            uv.extend(p.to_array());
        }
        tri.extend([3 * k, 3 * k + 1, 3 * k + 2]);
        corners.push(t);
    }
    let m = MeshSurface::new(&pos, &nrm, &tri, &uv).unwrap();
    for _ in 0..20_000 {
        let q = rng.uv() * 1.3 - Vec2::splat(0.15);
        let brute = corners
            .iter()
            .map(|t| uv_distance2(q, t))
            .fold(f32::INFINITY, f32::min);
        let (at, k) = m.nearest_uv(q).unwrap();
        let got = at.distance_squared(q);
        assert!(
            (got.sqrt() - brute.sqrt()).abs() < 1e-5,
            "{q}: {} vs brute {}",
            got.sqrt(),
            brute.sqrt()
        );
        assert!(
            uv_distance2(at, &corners[k]) < 1e-10,
            "the point lies on its triangle"
        );
        // The surface is the UV map itself (z = 0): eval_nearest lands on the same point.
        assert_close(m.eval_nearest(q).position, at.extend(0.0), 1e-5);
    }
    assert_eq!(m.nearest_uv(Vec2::NAN), None);
}

// ---------------------------------------------------------------- benchmarks
