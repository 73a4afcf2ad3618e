//! Test surfaces sampled from a function of (u, v) in [0, 1]^2.

use glam::Vec3;
use knitwear::surface::GridSurface;

/// Positions and normals of `f` on a `rows x cols` grid, row-major (u along a row). With
/// `cyclic_u` the columns stop one step short of u = 1, which the seam closes.
pub fn grid_buffers(
    rows: usize,
    cols: usize,
    cyclic_u: bool,
    f: impl Fn(f32, f32) -> (Vec3, Vec3),
) -> (Vec<f32>, Vec<f32>) {
    let (mut p, mut n) = (Vec::new(), Vec::new());
    for i in 0..rows {
        for j in 0..cols {
            let u = if cyclic_u {
                j as f32 / cols as f32
            } else {
                j as f32 / (cols - 1) as f32
            };
            let (a, b) = f(u, i as f32 / (rows - 1) as f32);
            p.extend(a.to_array());
            n.extend(b.to_array());
        }
    }
    (p, n)
}

/// The grid surface of `f` ([`grid_buffers`]), open in v.
pub fn grid(
    rows: usize,
    cols: usize,
    cyclic_u: bool,
    f: impl Fn(f32, f32) -> (Vec3, Vec3),
) -> GridSurface {
    let (p, n) = grid_buffers(rows, cols, cyclic_u, f);
    GridSurface::new(rows, cols, &p, &n, cyclic_u, false).unwrap()
}
