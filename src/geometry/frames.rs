//! Frames along a yarn centreline, for placing the rings of the swept yarn.

use glam::Vec3;

/// The frame at centreline sample `i`: unit tangent `t`, and two unit vectors `(a, b)`
/// spanning the ring plane, right-handed (`t x a = b`).
///
/// `a` is the surface normal under the sample made perpendicular to the tangent. Tying the
/// frame to the surface, rather than transporting it along the yarn, makes each ring a pure
/// function of its neighbourhood: no twist accumulates along a course, rings can be built in
/// any order, and a deforming surface turns the rings with it. Where the tangent runs along
/// the normal (never in a regular skeleton), any perpendicular is used.
pub fn ring_frame(points: &[Vec3], normals: &[Vec3], i: usize, closed: bool) -> (Vec3, Vec3, Vec3) {
    let n = points.len();
    let prev = if i > 0 {
        points[i - 1]
    } else if closed {
        points[n - 1]
    } else {
        points[i]
    };
    let next = if i + 1 < n {
        points[i + 1]
    } else if closed {
        points[0]
    } else {
        points[i]
    };
    frame_from_tangent(next - prev, normals[i])
}

/// The ring frame for a tangent direction `tangent` (any length) and the surface normal
/// `nrm` under the sample: see [`ring_frame`], which this is with the tangent taken from the
/// neighbouring samples. A yarn built in spans at different densities (camera-driven detail)
/// gives the rings where two spans meet the tangent of the full-density centreline, so both
/// spans put that ring in the same plane.
pub fn frame_from_tangent(tangent: Vec3, nrm: Vec3) -> (Vec3, Vec3, Vec3) {
    let t = tangent.try_normalize().unwrap_or(Vec3::X);
    let a = (nrm - nrm.dot(t) * t)
        .try_normalize()
        .unwrap_or_else(|| t.any_orthonormal_vector());
    let b = t.cross(a);
    (t, a, b)
}
