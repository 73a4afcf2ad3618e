//! `measure_clearance` and `measure_cover`: the accuracy figures of a knit result.

use pyo3::prelude::*;

use crate::error::KnitError;

use super::*;

/// A knit result's centreline: its points (scene units), each yarn piece's range of points
/// and whether it is closed, and the yarn radius.
pub(crate) type Centreline = (Vec<glam::Vec3>, Vec<(usize, usize, bool)>, f32);

/// See [`Centreline`].
pub(crate) fn result_centreline(
    py: Python<'_>,
    result: &Bound<'_, PyKnitResult>,
) -> PyResult<Centreline> {
    let r = result.get();
    let (_, pts) = f32_buffer(
        r.centerline_points.bind(py),
        "centerline_points",
        &[None, Some(3)],
    )?;
    let offsets: Vec<i64> = r.course_offsets.bind(py).extract()?;
    let closed: Vec<bool> = r.yarn_closed.bind(py).extract()?;
    let v: Vec<glam::Vec3> = pts
        .chunks_exact(3)
        .map(|c| glam::Vec3::new(c[0], c[1], c[2]))
        .collect();
    let n = v.len();
    let ranges = offsets
        .windows(2)
        .zip(&closed)
        .map(|(w, &c)| {
            let (a, b) = (w[0].clamp(0, n as i64), w[1].clamp(0, n as i64));
            (a as usize, b.max(a) as usize, c)
        })
        .collect();
    Ok((v, ranges, r.yarn_radius))
}

/// Clearance of a knit result: `(min, p01)` in yarn diameters (docs/design.md section 7).
#[pyfunction]
pub(crate) fn measure_clearance(
    py: Python<'_>,
    result: &Bound<'_, PyKnitResult>,
) -> PyResult<(f32, f32)> {
    let (v, ranges, radius) = result_centreline(py, result)?;
    guarded(py, move || {
        Ok(crate::metrics::yarn_clearance(&v, &ranges, radius))
    })
}

/// Optical cover of a knit result (docs/design.md section 7): the fraction of the rectangle
fn bounds_arg(obj: &Bound<'_, PyAny>) -> PyResult<(f32, f32, f32, f32)> {
    shaped_arg(obj, "bounds", "(x_min, y_min, x_max, y_max): four numbers")
}

/// `bounds = (x_min, y_min, x_max, y_max)` (object space) hidden by the yarn's tubes (no
/// fluff) in an orthographic view along z, sampled on `resolution` x `resolution` pixels.
#[pyfunction]
#[pyo3(signature = (result, bounds, resolution=800))]
pub(crate) fn measure_cover(
    py: Python<'_>,
    result: &Bound<'_, PyKnitResult>,
    #[pyo3(from_py_with = bounds_arg)] bounds: (f32, f32, f32, f32),
    #[pyo3(from_py_with = int_arg)] resolution: i128,
) -> PyResult<f64> {
    let (v, ranges, radius) = result_centreline(py, result)?;
    let resolution = within("resolution", resolution, 1u32, 8192)? as usize;
    let (min, max) = (
        glam::Vec2::new(bounds.0, bounds.1),
        glam::Vec2::new(bounds.2, bounds.3),
    );
    if !(min.is_finite() && max.is_finite() && max.x > min.x && max.y > min.y) {
        return Err(to_py(KnitError::Parameter(format!(
            "bounds must be a finite rectangle (x_min, y_min, x_max, y_max), not {bounds:?}"
        ))));
    }
    guarded(py, move || {
        let yarns: Vec<(&[glam::Vec3], bool)> =
            ranges.iter().map(|&(a, b, c)| (&v[a..b], c)).collect();
        Ok(crate::metrics::cover(&yarns, radius, min, max, resolution))
    })
}
