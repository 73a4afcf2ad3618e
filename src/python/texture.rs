//! Binding of the knitwear texture ([`crate::texture`]): `knit_texture()`, an image of the
//! stitches in the surface's (u,v) domain. Thin: the keyword settings of `Knit`, the GIL
//! released around the core, the pixels moved out as an `(H, W, 4)` float32 array.

use numpy::ndarray::Array3;
use numpy::IntoPyArray;
use pyo3::prelude::*;

use super::{
    count_arg, gauge_arg, guarded, int_arg, opt_int_arg, params_from, stitch_size_arg, AnySurface,
    InternalError, PyColorPattern, PyPattern,
};
use crate::texture::knit_texture as core_texture;

/// The knitwear texture of `pattern` on `surface`: `(height, width, 4)` float32 linear RGBA
/// over the surface's (u,v) domain (`surface.domain`), row 0 at the smallest v (Blender's
/// pixel order), transparent where no yarn is. Settings as `Knit`'s.
#[pyfunction]
#[pyo3(signature = (
    surface, pattern, *, width=1024, height=1024, courses=None, wales=None, gauge=None,
    yarn_radius=None, stitch_size=None, fluffiness=0.5, ring_segments=6, plies=1, live_loops=false,
    samples_per_loop=16, tension=0.0, kappa=0.0, seed=0, colors=None, color_image=None, color_variation=0.15,
    threads=None, budget_bytes=None, measure_clearance=false
))]
#[allow(clippy::too_many_arguments)]
fn knit_texture(
    py: Python<'_>,
    surface: &Bound<'_, PyAny>,
    pattern: &Bound<'_, PyPattern>,
    #[pyo3(from_py_with = int_arg)] width: i128,
    #[pyo3(from_py_with = int_arg)] height: i128,
    #[pyo3(from_py_with = opt_int_arg)] courses: Option<i128>,
    #[pyo3(from_py_with = opt_int_arg)] wales: Option<i128>,
    #[pyo3(from_py_with = gauge_arg)] gauge: Option<(f32, f32)>,
    yarn_radius: Option<f32>,
    #[pyo3(from_py_with = stitch_size_arg)] stitch_size: Option<(f32, f32)>,
    fluffiness: f32,
    #[pyo3(from_py_with = int_arg)] ring_segments: i128,
    #[pyo3(from_py_with = int_arg)] plies: i128,
    live_loops: bool,
    #[pyo3(from_py_with = int_arg)] samples_per_loop: i128,
    tension: f32,
    kappa: f32,
    #[pyo3(from_py_with = int_arg)] seed: i128,
    colors: Option<&Bound<'_, PyColorPattern>>,
    color_image: Option<&Bound<'_, PyAny>>,
    color_variation: f32,
    #[pyo3(from_py_with = opt_int_arg)] threads: Option<i128>,
    #[pyo3(from_py_with = opt_int_arg)] budget_bytes: Option<i128>,
    measure_clearance: bool,
) -> PyResult<Py<PyAny>> {
    let surf = AnySurface::from_py(surface)?;
    let params = params_from(
        courses,
        wales,
        gauge,
        yarn_radius,
        stitch_size,
        fluffiness,
        ring_segments,
        plies,
        live_loops,
        samples_per_loop,
        tension,
        kappa,
        seed,
        colors,
        color_image,
        color_variation,
        threads,
        budget_bytes,
        measure_clearance,
    )?;
    let (width, height) = (
        count_arg("width", width, 0)?,
        count_arg("height", height, 0)?,
    );
    let pattern = pattern.get().inner.clone();
    let img = guarded(py, move || {
        core_texture(surf.as_dyn(), &pattern, &params, width, height)
    })?;
    let a = Array3::from_shape_vec((img.height, img.width, 4), img.pixels)
        .map_err(|e| InternalError::new_err(format!("texture shape: {e}")))?;
    Ok(a.into_pyarray(py).into_any().unbind())
}

pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(knit_texture, m)?)
}
