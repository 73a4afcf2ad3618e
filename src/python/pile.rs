//! Bindings of the plush core ([`crate::pile`]): `plush()`, `PlushField` (follow a camera
//! cheaply), `PlushResult`, `PlushView` and `fractal_noise()`. Thin: argument conversion,
//! the GIL released around the core, NumPy arrays moved out.

use std::sync::Arc;

use glam::Vec3;
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{
    budget_arg, count_arg, flat, gauge_arg, guarded, int_arg, opt_int_arg, opt_shaped_arg, rows,
    seed_arg, to_py, AnySurface, InternalError, ParameterError, PyColorPattern, PyGridSurface,
    PyMeshSurface, SurfaceError,
};
use crate::pattern::ColorImage;
use crate::pile::fractal_noise::{fractal_noise as core_noise, NoiseParams};
use crate::pile::{
    plush as core_plush, Nominal, PileBuffers, PileColors, PileField, PileParams, PileStats,
    PressMap, View,
};

/// A float32 C-contiguous array with `ndim` dimensions, copied out with its shape; errors
/// (ParameterError) name the argument.
fn f32_array(obj: &Bound<'_, PyAny>, name: &str, ndim: usize) -> PyResult<(Vec<usize>, Vec<f32>)> {
    let arr = obj.cast::<PyArrayDyn<f32>>().map_err(|_| {
        ParameterError::new_err(format!(
            "{name} must be a numpy float32 array (use numpy.asarray(x, dtype=numpy.float32))"
        ))
    })?;
    let ro = arr.readonly();
    let dims = ro.shape().to_vec();
    if dims.len() != ndim {
        return Err(ParameterError::new_err(format!(
            "{name} must have {ndim} dimensions, not shape {dims:?}"
        )));
    }
    let not_c = || ParameterError::new_err(format!("{name} must be C-contiguous"));
    if !ro.is_c_contiguous() {
        return Err(not_c());
    }
    Ok((dims, ro.as_slice().map_err(|_| not_c())?.to_vec()))
}

fn vec3(name: &str, v: Option<Vec<f32>>) -> PyResult<Option<Vec3>> {
    match v {
        None => Ok(None),
        Some(c) if c.len() == 3 => Ok(Some(Vec3::new(c[0], c[1], c[2]))),
        Some(c) => Err(ParameterError::new_err(format!(
            "{name} must be 3 numbers (x, y, z), not {} of them",
            c.len()
        ))),
    }
}

/// `eye` (perspective) or `view_dir` (orthographic), or neither (seen along each normal).
fn lean_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<Vec<f32>>> {
    opt_shaped_arg(
        obj,
        "lean",
        "(angle, azimuth) in radians or a direction (x, y, z)",
    )
}

fn eye_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<Vec<f32>>> {
    opt_shaped_arg(obj, "eye", "a position (x, y, z)")
}

fn view_dir_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<Vec<f32>>> {
    opt_shaped_arg(obj, "view_dir", "a direction (x, y, z)")
}

fn noise_scales_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<Vec<i64>>> {
    opt_shaped_arg(
        obj,
        "noise_scales",
        "a sequence of integers such as (1, 2, 4, 8)",
    )
}

fn scales_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<Vec<i64>>> {
    opt_shaped_arg(obj, "scales", "a sequence of integers such as (1, 2, 4, 8)")
}

fn noise_size_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<(i64, i64)>> {
    opt_shaped_arg(obj, "noise_size", "(width, height): two integers")
}

/// `eye` (perspective) or `view_dir` (orthographic), or neither (seen along each normal).
fn view_of(eye: Option<Vec<f32>>, view_dir: Option<Vec<f32>>) -> PyResult<View> {
    match (vec3("eye", eye)?, vec3("view_dir", view_dir)?) {
        (Some(_), Some(_)) => Err(ParameterError::new_err(
            "give eye (a perspective camera) or view_dir (an orthographic one), not both",
        )),
        (Some(eye), None) => Ok(View::Perspective { eye }),
        (None, Some(direction)) => Ok(View::Orthographic { direction }),
        (None, None) => Ok(View::AlongNormal),
    }
}

fn usize_arg(name: &str, v: impl Into<i128>, min: usize) -> PyResult<usize> {
    count_arg(name, v.into(), min)
}

fn stats_dict<'py>(py: Python<'py>, s: &PileStats) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("courses", s.courses)?;
    d.set_item("wales", s.wales)?;
    d.set_item("piles", s.piles)?;
    d.set_item("piles_skipped", s.piles_skipped)?;
    d.set_item("horizontal", s.horizontal)?;
    d.set_item("vertical", s.vertical)?;
    d.set_item("slices", s.slices)?;
    d.set_item("vertices", s.vertices)?;
    d.set_item("triangles", s.triangles)?;
    d.set_item("pile_length", s.pile_length)?;
    d.set_item("pile_radius", s.pile_radius)?;
    d.set_item("stitch_width", s.stitch_width)?;
    d.set_item("stitch_height", s.stitch_height)?;
    d.set_item("noise_width", s.noise_width)?;
    d.set_item("noise_height", s.noise_height)?;
    d.set_item("topology_key", s.topology_key)?;
    d.set_item("seconds", s.seconds)?;
    Ok(d)
}

/// A plush's pile field: roots, frames, directions and colours sampled once. Builds the
/// buffers for any view without sampling the surface again.
#[pyclass(name = "PlushField", module = "knitwear", frozen)]
pub struct PyPlushField {
    inner: Arc<PileField>,
}

/// The view-dependent buffers of a plush for one view; topology, UVs and colours are the
/// `PlushResult`'s.
#[pyclass(name = "PlushView", module = "knitwear", frozen)]
pub struct PyPlushView {
    #[pyo3(get)]
    vertices: Py<PyAny>,
    #[pyo3(get)]
    mask: Py<PyAny>,
    #[pyo3(get)]
    horizontal: Py<PyAny>,
    #[pyo3(get)]
    stats: Py<PyDict>,
}

/// A plush: NumPy arrays ready for Blender's `foreach_set`, and the field to re-view it.
#[pyclass(name = "PlushResult", module = "knitwear", frozen)]
pub struct PyPlushResult {
    #[pyo3(get)]
    vertices: Py<PyAny>,
    #[pyo3(get)]
    triangles: Py<PyAny>,
    #[pyo3(get)]
    edges: Py<PyAny>,
    #[pyo3(get)]
    corner_edges: Py<PyAny>,
    #[pyo3(get)]
    colors: Py<PyAny>,
    #[pyo3(get)]
    uvs: Py<PyAny>,
    #[pyo3(get)]
    mask: Py<PyAny>,
    #[pyo3(get)]
    horizontal: Py<PyAny>,
    #[pyo3(get)]
    stats: Py<PyDict>,
    #[pyo3(get)]
    field: Py<PyPlushField>,
}

#[pymethods]
impl PyPlushResult {
    fn __repr__(&self, py: Python<'_>) -> String {
        let s = self.stats.bind(py).repr().map(|r| r.to_string());
        format!("PlushResult({})", s.unwrap_or_default())
    }
}

fn to_result(py: Python<'_>, field: Py<PyPlushField>, b: PileBuffers) -> PyResult<PyPlushResult> {
    let stats = stats_dict(py, &b.stats)?.unbind();
    Ok(PyPlushResult {
        vertices: rows(py, b.positions, 3)?,
        triangles: rows(py, b.triangles, 3)?,
        edges: rows(py, b.edges, 2)?,
        corner_edges: flat(py, b.corner_edges),
        colors: rows(py, b.colors, 4)?,
        uvs: rows(py, b.uvs, 2)?,
        mask: flat(py, b.mask),
        horizontal: flat(py, b.horizontal),
        stats,
        field,
    })
}

fn noise_array(py: Python<'_>, h: usize, w: usize, v: Vec<f32>) -> PyResult<Py<PyAny>> {
    let a = Array3::from_shape_vec((h, w, 3), v)
        .map_err(|e| InternalError::new_err(format!("noise shape: {e}")))?;
    Ok(a.into_pyarray(py).into_any().unbind())
}

#[pymethods]
impl PyPlushField {
    /// Positions, mask and slice choice for a new view (eye: perspective camera position,
    /// view_dir: orthographic view direction, both in the surface's object space; neither:
    /// each pile seen along its normal). Cheap: no surface sampling, no noise.
    #[pyo3(signature = (*, eye=None, view_dir=None, threads=None))]
    fn view(
        &self,
        py: Python<'_>,
        #[pyo3(from_py_with = eye_arg)] eye: Option<Vec<f32>>,
        #[pyo3(from_py_with = view_dir_arg)] view_dir: Option<Vec<f32>>,
        #[pyo3(from_py_with = opt_int_arg)] threads: Option<i128>,
    ) -> PyResult<PyPlushView> {
        let view = view_of(eye, view_dir)?;
        let threads = threads.map(|t| usize_arg("threads", t, 1)).transpose()?;
        let field = self.inner.clone();
        let v = guarded(py, move || field.view(&view, threads))?;
        let stats = PyDict::new(py);
        stats.set_item("horizontal", v.horizontal_count)?;
        stats.set_item("vertical", v.vertical_count)?;
        stats.set_item("seconds", v.seconds)?;
        Ok(PyPlushView {
            vertices: rows(py, v.positions, 3)?,
            mask: flat(py, v.mask),
            horizontal: flat(py, v.horizontal),
            stats: stats.unbind(),
        })
    }

    /// Every buffer for a view, as `plush()` returns them (the field is this one).
    #[pyo3(signature = (*, eye=None, view_dir=None, threads=None, budget_bytes=None))]
    fn build(
        slf: &Bound<'_, Self>,
        #[pyo3(from_py_with = eye_arg)] eye: Option<Vec<f32>>,
        #[pyo3(from_py_with = view_dir_arg)] view_dir: Option<Vec<f32>>,
        #[pyo3(from_py_with = opt_int_arg)] threads: Option<i128>,
        #[pyo3(from_py_with = opt_int_arg)] budget_bytes: Option<i128>,
    ) -> PyResult<PyPlushResult> {
        let py = slf.py();
        let view = view_of(eye, view_dir)?;
        let threads = threads.map(|t| usize_arg("threads", t, 1)).transpose()?;
        let budget = budget_arg(budget_bytes, crate::budget::DEFAULT_BUDGET_BYTES)?;
        let field = slf.get().inner.clone();
        let b = guarded(py, move || field.build(&view, threads, budget))?;
        to_result(py, slf.clone().unbind(), b)
    }

    #[getter]
    fn piles(&self) -> usize {
        self.inner.piles.len()
    }
    #[getter]
    fn slices(&self) -> usize {
        self.inner.slices
    }
    #[getter]
    fn pile_length(&self) -> f32 {
        self.inner.pile_length
    }
    #[getter]
    fn pile_radius(&self) -> f32 {
        self.inner.pile_radius
    }
    /// Statistics of the field (view counts 0).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        stats_dict(py, &self.inner.stats)
    }
    /// `(P, 3)` float32 pile roots, object space.
    #[getter]
    fn roots(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v = self.inner.piles.iter().flat_map(|p| p.root.to_array());
        rows(py, v.collect(), 3)
    }
    /// `(P, 3)` float32 unit pile directions, object space.
    #[getter]
    fn directions(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v = self.inner.piles.iter().flat_map(|p| p.t.to_array());
        rows(py, v.collect(), 3)
    }
    /// `(P, 3)` float32 unit surface normals at the roots.
    #[getter]
    fn normals(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v = self.inner.piles.iter().flat_map(|p| p.normal.to_array());
        rows(py, v.collect(), 3)
    }
    /// `(P,)` float32 each pile's threshold in `[0, 1)` across the band where slices change kind:
    /// horizontal when `2 r |cos a| >= (1 + blend) l sin a`.
    #[getter]
    fn blends(&self, py: Python<'_>) -> Py<PyAny> {
        flat(py, self.inner.piles.iter().map(|p| p.blend).collect())
    }
    /// `(P, 2)` float32 (u,v) of the roots.
    #[getter]
    fn root_uvs(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v = self.inner.root_uvs.iter().flat_map(|p| p.to_array());
        rows(py, v.collect(), 2)
    }
    /// `(H, W, 3)` float32 fractal noise in the noise frame (z = nominal pile direction).
    #[getter]
    fn noise(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let n = &self.inner.noise;
        noise_array(py, n.height, n.width, n.to_flat())
    }
    /// `(H, W, 3)` float32 noise image in `[0, 1]`: `(v + 1) / 2`, as the paper draws it.
    #[getter]
    fn noise_rgb(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let n = &self.inner.noise;
        noise_array(py, n.height, n.width, n.to_rgb())
    }
    fn __repr__(&self) -> String {
        format!(
            "PlushField({} piles x {} slices)",
            self.inner.piles.len(),
            self.inner.slices
        )
    }
}

fn colors_of(
    obj: Option<&Bound<'_, PyAny>>,
    image: Option<&Bound<'_, PyAny>>,
) -> PyResult<PileColors> {
    if let Some(img) = image {
        if obj.is_some() {
            return Err(ParameterError::new_err(
                "give colors or color_image, not both",
            ));
        }
        let (dims, data) = f32_array(img, "color_image", 3)?;
        return ColorImage::new(dims[1], dims[0], dims[2], data)
            .map(PileColors::Image)
            .map_err(to_py);
    }
    let Some(obj) = obj else {
        return Ok(PileColors::Solid(crate::pile::DEFAULT_PILE_COLOR));
    };
    if let Ok(cp) = obj.cast::<PyColorPattern>() {
        return Ok(PileColors::Pattern(cp.get().inner.clone()));
    }
    if obj.cast::<PyArrayDyn<f32>>().is_ok() {
        let arr = obj.cast::<PyArrayDyn<f32>>()?;
        let ndim = arr.readonly().shape().len();
        let (dims, data) = f32_array(obj, "colors", ndim)?;
        if !matches!(dims.as_slice(), [_, 3] | [_, _, 3]) {
            return Err(ParameterError::new_err(format!(
                "per-stitch colors must have shape (courses, wales, 3) or (courses * wales, 3), \
                 not {dims:?}"
            )));
        }
        let cs = data.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        return Ok(PileColors::PerStitch(cs));
    }
    match obj.extract::<Vec<f32>>() {
        Ok(c) if c.len() == 3 || c.len() == 4 => Ok(PileColors::Solid([c[0], c[1], c[2]])),
        _ => Err(ParameterError::new_err(
            "colors must be (r, g, b), a knitwear.ColorPattern, or a float32 array of \
             per-stitch colours (courses, wales, 3)",
        )),
    }
}

/// Grows warp-knit plush over `surface`. See docs/settings.md for every argument.
#[pyfunction]
#[pyo3(signature = (
    surface, *, courses=None, wales=None, gauge=None, piles_per_stitch=1, pile_length=None,
    pile_radius=None, slices=8, lean=None, theta_max=None, noise_scales=None, noise_size=None,
    seed=0, eye=None, view_dir=None, colors=None, color_image=None, press=None,
    press_strength=None, press_direction=None, threads=None, budget_bytes=None
))]
#[allow(clippy::too_many_arguments)]
fn plush(
    py: Python<'_>,
    surface: &Bound<'_, PyAny>,
    #[pyo3(from_py_with = opt_int_arg)] courses: Option<i128>,
    #[pyo3(from_py_with = opt_int_arg)] wales: Option<i128>,
    #[pyo3(from_py_with = gauge_arg)] gauge: Option<(f32, f32)>,
    #[pyo3(from_py_with = int_arg)] piles_per_stitch: i128,
    pile_length: Option<f32>,
    pile_radius: Option<f32>,
    #[pyo3(from_py_with = int_arg)] slices: i128,
    #[pyo3(from_py_with = lean_arg)] lean: Option<Vec<f32>>,
    theta_max: Option<f32>,
    #[pyo3(from_py_with = noise_scales_arg)] noise_scales: Option<Vec<i64>>,
    #[pyo3(from_py_with = noise_size_arg)] noise_size: Option<(i64, i64)>,
    #[pyo3(from_py_with = int_arg)] seed: i128,
    #[pyo3(from_py_with = eye_arg)] eye: Option<Vec<f32>>,
    #[pyo3(from_py_with = view_dir_arg)] view_dir: Option<Vec<f32>>,
    colors: Option<&Bound<'_, PyAny>>,
    color_image: Option<&Bound<'_, PyAny>>,
    press: Option<&Bound<'_, PyAny>>,
    press_strength: Option<f32>,
    press_direction: Option<f32>,
    #[pyo3(from_py_with = opt_int_arg)] threads: Option<i128>,
    #[pyo3(from_py_with = opt_int_arg)] budget_bytes: Option<i128>,
) -> PyResult<PyPlushResult> {
    let surf = if let Ok(g) = surface.cast::<PyGridSurface>() {
        AnySurface::Grid(g.get().inner.clone())
    } else if let Ok(m) = surface.cast::<PyMeshSurface>() {
        AnySurface::Mesh(m.get().inner.clone())
    } else {
        return Err(SurfaceError::new_err(format!(
            "surface must be a knitwear.GridSurface or knitwear.MeshSurface, not {}",
            surface.get_type()
        )));
    };
    let view = view_of(eye, view_dir)?;
    let defaults = PileParams::default();
    let nominal = match lean.as_deref() {
        None => defaults.nominal,
        Some([angle, azimuth]) => Nominal::Lean {
            angle: *angle,
            azimuth: *azimuth,
        },
        Some([x, y, z]) => Nominal::Direction(Vec3::new(*x, *y, *z)),
        Some(other) => {
            return Err(ParameterError::new_err(format!(
                "lean must be (angle, direction) in radians or a direction (x, y, z) in the \
                 fabric frame, not {} numbers",
                other.len()
            )))
        }
    };
    let press = match press {
        None => None,
        Some(obj) => {
            let (dims, w) = f32_array(obj, "press", 2)?;
            Some(PressMap::new(dims[1], dims[0], w).map_err(to_py)?)
        }
    };
    let count = |name: &str, v: Option<i128>| v.map(|n| usize_arg(name, n, 1)).transpose();
    let params = PileParams {
        courses: count("courses", courses)?,
        wales: count("wales", wales)?,
        gauge,
        piles_per_stitch: usize_arg("piles_per_stitch", piles_per_stitch, 1)?,
        pile_length,
        pile_radius,
        slices: usize_arg("slices", slices, 1)?,
        nominal,
        theta_max: theta_max.unwrap_or(defaults.theta_max),
        noise_scales: match noise_scales {
            None => defaults.noise_scales.clone(),
            Some(ks) => ks
                .into_iter()
                .map(|k| usize_arg("each noise scale", k, 1))
                .collect::<PyResult<_>>()?,
        },
        noise_size: match noise_size {
            None => None,
            Some((w, h)) => Some((
                usize_arg("noise width", w, 1)?,
                usize_arg("noise height", h, 1)?,
            )),
        },
        seed: seed_arg(seed)?,
        colors: colors_of(colors, color_image)?,
        press,
        press_strength: press_strength.unwrap_or(defaults.press_strength),
        press_azimuth: press_direction,
        threads: count("threads", threads)?,
        budget_bytes: budget_arg(budget_bytes, defaults.budget_bytes)?,
    };
    let out = guarded(py, move || match &surf {
        AnySurface::Grid(g) => core_plush(g.as_ref(), &params, &view),
        AnySurface::Mesh(m) => core_plush(m.as_ref(), &params, &view),
    })?;
    let field = Py::new(
        py,
        PyPlushField {
            inner: Arc::new(out.field),
        },
    )?;
    to_result(py, field, out.buffers)
}

/// The fractal noise of pile directions: `(height, width, 3)` float32 unit vectors in the
/// noise frame (z = nominal direction), or with `rgb=True` the paper's image `(v + 1) / 2`.
/// `scales=(1,)` gives the base noise.
#[pyfunction]
#[pyo3(signature = (size, *, theta_max=None, scales=None, seed=0, rgb=false, threads=None))]
fn fractal_noise(
    py: Python<'_>,
    size: &Bound<'_, PyAny>,
    theta_max: Option<f32>,
    #[pyo3(from_py_with = scales_arg)] scales: Option<Vec<i64>>,
    #[pyo3(from_py_with = int_arg)] seed: i128,
    rgb: bool,
    #[pyo3(from_py_with = opt_int_arg)] threads: Option<i128>,
) -> PyResult<Py<PyAny>> {
    let (w, h) = match size.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>() {
        Ok((w, h)) => (int_arg(&w)?, int_arg(&h)?),
        Err(_) => {
            let n = int_arg(size)
                .map_err(|_| ParameterError::new_err("size must be an int or (width, height)"))?;
            (n, n)
        }
    };
    let mut p = NoiseParams::new(
        usize_arg("width", w, 1)?,
        usize_arg("height", h, 1)?,
        seed_arg(seed)?,
    );
    if let Some(t) = theta_max {
        p.theta_max = t;
    }
    if let Some(ks) = scales {
        p.scales = ks
            .into_iter()
            .map(|k| usize_arg("each scale", k, 1))
            .collect::<PyResult<_>>()?;
    }
    let threads = threads.map(|t| usize_arg("threads", t, 1)).transpose()?;
    let (width, height) = (p.width, p.height);
    let data = guarded(py, move || {
        p.validate()?;
        let noise = crate::parallel::run_in_pool(threads, || core_noise(&p))??;
        Ok(if rgb { noise.to_rgb() } else { noise.to_flat() })
    })?;
    noise_array(py, height, width, data)
}

/// Adds the plush classes and functions to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyPlushField>()?;
    m.add_class::<PyPlushResult>()?;
    m.add_class::<PyPlushView>()?;
    m.add_function(wrap_pyfunction!(plush, m)?)?;
    m.add_function(wrap_pyfunction!(fractal_noise, m)?)?;
    Ok(())
}
