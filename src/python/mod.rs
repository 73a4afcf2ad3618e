//! The pyo3 binding layer, and the only pyo3 code: NumPy buffers in, core calls with the GIL
//! released and panics caught, NumPy buffers out (moved, not copied), and one exhaustive
//! mapping from [`KnitError`] to the Python exception hierarchy.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Arc;

use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyDict;

mod detail;
mod pile;
mod settings;
mod texture;

use crate::error::KnitError;
use crate::knit::{ColorImage, KnitOutput, KnitParams, PreparedKnit};
use crate::metrics::{clearance, YarnPolyline, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS};
use crate::pattern::{ColorPattern, StitchPattern};
use crate::surface::{GridSurface, MeshSurface, Surface};

create_exception!(
    knitwear,
    PyKnitError,
    PyException,
    "Base class of every error a user can cause."
);
create_exception!(
    knitwear,
    SurfaceError,
    PyKnitError,
    "The surface cannot be knitted."
);
create_exception!(
    knitwear,
    PatternError,
    PyKnitError,
    "A pattern that does not parse."
);
create_exception!(
    knitwear,
    ParameterError,
    PyKnitError,
    "A setting out of range."
);
create_exception!(
    knitwear,
    BudgetError,
    PyKnitError,
    "The output would exceed the budget."
);
create_exception!(
    knitwear,
    InternalError,
    PyKnitError,
    "A bug in knitwear; please report it."
);

/// The one mapping from core errors to Python exceptions.
fn to_py(e: KnitError) -> PyErr {
    let msg = e.to_string();
    match e {
        KnitError::Surface(_) => SurfaceError::new_err(msg),
        KnitError::Pattern(_) => PatternError::new_err(msg),
        KnitError::Parameter(_) => ParameterError::new_err(msg),
        KnitError::Budget(_) => BudgetError::new_err(msg),
        KnitError::Internal(_) => InternalError::new_err(msg),
    }
}

/// Runs core work without the GIL, turning a panic into a [`KnitError::Internal`].
fn guarded<T: Send>(
    py: Python<'_>,
    f: impl FnOnce() -> Result<T, KnitError> + Send,
) -> PyResult<T> {
    py.detach(|| match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(KnitError::Internal(what))
        }
    })
    .map_err(to_py)
}

/// A float32 C-contiguous array of the expected trailing shape, copied out as a Vec (the
/// inputs are small next to the output). Errors name the argument.
fn f32_buffer(
    obj: &Bound<'_, PyAny>,
    name: &str,
    shape: &[Option<usize>],
) -> PyResult<(Vec<usize>, Vec<f32>)> {
    let arr = obj.cast::<PyArrayDyn<f32>>().map_err(|_| {
        let dtype = obj
            .getattr("dtype")
            .map(|d| d.to_string())
            .unwrap_or_else(|_| obj.get_type().to_string());
        SurfaceError::new_err(format!(
            "{name} must be a numpy float32 array, not {dtype} (use numpy.asarray(x, dtype=numpy.float32))"
        ))
    })?;
    let dims = arr.shape().to_vec();
    let ok = dims.len() == shape.len()
        && dims
            .iter()
            .zip(shape)
            .all(|(d, s)| s.is_none_or(|s| *d == s));
    if !ok {
        let want: Vec<String> = shape
            .iter()
            .map(|s| s.map_or("N".to_string(), |v| v.to_string()))
            .collect();
        return Err(SurfaceError::new_err(format!(
            "{name} must have shape ({}), not {dims:?}",
            want.join(", ")
        )));
    }
    let ro = arr.readonly();
    // as_slice also accepts Fortran order, which would silently scramble the samples.
    let c_order = if ro.is_c_contiguous() {
        Ok(())
    } else {
        Err(())
    };
    let data = c_order
        .and_then(|_| ro.as_slice().map_err(|_| ()))
        .map_err(|_| {
            SurfaceError::new_err(format!(
                "{name} must be C-contiguous (use numpy.ascontiguousarray)"
            ))
        })?;
    Ok((dims, data.to_vec()))
}

/// Triangle indices: int32, uint32 or int64, C-contiguous, shape (M, 3), non-negative.
fn index_buffer(obj: &Bound<'_, PyAny>) -> PyResult<Vec<u32>> {
    let bad_shape = |dims: &[usize]| {
        SurfaceError::new_err(format!("triangles must have shape (M, 3), not {dims:?}"))
    };
    let contiguous =
        || SurfaceError::new_err("triangles must be C-contiguous (use numpy.ascontiguousarray)");
    if let Ok(a) = obj.cast::<PyArrayDyn<u32>>() {
        let ro = a.readonly();
        if ro.shape().len() != 2 || ro.shape()[1] != 3 {
            return Err(bad_shape(ro.shape()));
        }
        if !ro.is_c_contiguous() {
            return Err(contiguous());
        }
        return Ok(ro.as_slice().map_err(|_| contiguous())?.to_vec());
    }
    let signed: Vec<i64> = if let Ok(a) = obj.cast::<PyArrayDyn<i32>>() {
        let ro = a.readonly();
        if ro.shape().len() != 2 || ro.shape()[1] != 3 {
            return Err(bad_shape(ro.shape()));
        }
        if !ro.is_c_contiguous() {
            return Err(contiguous());
        }
        ro.as_slice()
            .map_err(|_| contiguous())?
            .iter()
            .map(|&i| i as i64)
            .collect()
    } else if let Ok(a) = obj.cast::<PyArrayDyn<i64>>() {
        let ro = a.readonly();
        if ro.shape().len() != 2 || ro.shape()[1] != 3 {
            return Err(bad_shape(ro.shape()));
        }
        if !ro.is_c_contiguous() {
            return Err(contiguous());
        }
        ro.as_slice().map_err(|_| contiguous())?.to_vec()
    } else {
        return Err(SurfaceError::new_err(
            "triangles must be a numpy int32, uint32 or int64 array of shape (M, 3)",
        ));
    };
    signed
        .into_iter()
        .map(|i| {
            u32::try_from(i)
                .map_err(|_| SurfaceError::new_err(format!("triangle index {i} is out of range")))
        })
        .collect()
}

/// Positions and normals sampled on a regular (u,v) grid (a NURBS surface).
#[pyclass(name = "GridSurface", module = "knitwear", frozen)]
pub struct PyGridSurface {
    inner: Arc<GridSurface>,
}

#[pymethods]
impl PyGridSurface {
    #[new]
    #[pyo3(signature = (positions, normals, cyclic_u=false, cyclic_v=false))]
    fn new(
        positions: &Bound<'_, PyAny>,
        normals: &Bound<'_, PyAny>,
        cyclic_u: bool,
        cyclic_v: bool,
    ) -> PyResult<Self> {
        let (dims, p) = f32_buffer(positions, "positions", &[None, None, Some(3)])?;
        let (ndims, n) = f32_buffer(normals, "normals", &[None, None, Some(3)])?;
        if dims != ndims {
            return Err(SurfaceError::new_err(format!(
                "normals {ndims:?} must have the shape of positions {dims:?}"
            )));
        }
        let py = positions.py();
        let inner = guarded(py, move || {
            GridSurface::new(dims[0], dims[1], &p, &n, cyclic_u, cyclic_v)
        })?;
        Ok(Self {
            inner: Arc::new(inner),
        })
    }

    /// Mean length along u (a course) and along v (a wale), scene units.
    #[getter]
    fn extent(&self) -> (f32, f32) {
        self.inner.extent()
    }
}

/// A triangle mesh with per-corner UVs.
#[pyclass(name = "MeshSurface", module = "knitwear", frozen)]
pub struct PyMeshSurface {
    inner: Arc<MeshSurface>,
}

#[pymethods]
impl PyMeshSurface {
    #[new]
    fn new(
        positions: &Bound<'_, PyAny>,
        normals: &Bound<'_, PyAny>,
        triangles: &Bound<'_, PyAny>,
        uvs: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let (pd, p) = f32_buffer(positions, "positions", &[None, Some(3)])?;
        let (nd, n) = f32_buffer(normals, "normals", &[None, Some(3)])?;
        if pd != nd {
            return Err(SurfaceError::new_err(format!(
                "normals {nd:?} must have the shape of positions {pd:?}"
            )));
        }
        let t = index_buffer(triangles)?;
        let (ud, uv) = f32_buffer(uvs, "uvs", &[None, Some(3), Some(2)])?;
        if ud[0] * 3 != t.len() {
            return Err(SurfaceError::new_err(format!(
                "uvs has {} triangles but triangles has {}",
                ud[0],
                t.len() / 3
            )));
        }
        let inner = guarded(positions.py(), move || MeshSurface::new(&p, &n, &t, &uv))?;
        Ok(Self {
            inner: Arc::new(inner),
        })
    }

    #[getter]
    fn extent(&self) -> (f32, f32) {
        self.inner.extent()
    }

    /// The (u,v) rectangle the stitches are laid over: the UV map's bounding box,
    /// `((u_min, v_min), (u_max, v_max))`.
    #[getter]
    fn domain(&self) -> ((f32, f32), (f32, f32)) {
        let d = self.inner.domain();
        (d.min.into(), d.max.into())
    }
}

/// A stitch pattern: a chart of knit and purl stitches repeated over the surface.
#[pyclass(name = "Pattern", module = "knitwear", frozen)]
pub struct PyPattern {
    inner: StitchPattern,
}

#[pymethods]
impl PyPattern {
    /// A named preset; see `Pattern.presets()`.
    #[staticmethod]
    fn preset(name: &str) -> PyResult<Self> {
        StitchPattern::preset(name)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
    /// A text chart: one line per row, top row first; k (knit) and p (purl) as seen on the front.
    #[staticmethod]
    fn from_chart(text: &str) -> PyResult<Self> {
        StitchPattern::from_chart(text)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
    /// Knitspeak row instructions ("Row 1 (RS): *k2, 2/2 RC, p2; rep from *."): cables,
    /// decreases, yarn-overs, slips, bobbles, repeats (see the README).
    #[staticmethod]
    fn from_knitspeak(text: &str) -> PyResult<Self> {
        StitchPattern::from_knitspeak(text)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
    /// Knitspeak or a chart, told apart by content (Knitspeak starts with a row header).
    #[staticmethod]
    fn from_text(text: &str) -> PyResult<Self> {
        StitchPattern::from_text(text)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
    /// A pattern file (UTF-8 text): Knitspeak or a chart, told apart by content. A file that
    /// cannot be read is a PatternError naming the path.
    #[staticmethod]
    fn from_file(path: std::path::PathBuf) -> PyResult<Self> {
        let text = std::fs::read_to_string(&path).map_err(|e| {
            PatternError::new_err(format!("cannot read pattern file {}: {e}", path.display()))
        })?;
        StitchPattern::from_text(&text)
            .map(|inner| Self { inner })
            .map_err(|e| match e {
                KnitError::Pattern(m) => {
                    to_py(KnitError::Pattern(format!("{}: {m}", path.display())))
                }
                other => to_py(other),
            })
    }
    /// Per chart row, bottom row first: (loops of the row below it works, stitches it makes).
    fn stitch_counts(&self) -> Vec<(usize, usize)> {
        self.inner.stitch_counts()
    }
    /// Whether `text` reads as Knitspeak (starts with a row header) rather than a chart.
    #[staticmethod]
    fn looks_like_knitspeak(text: &str) -> bool {
        crate::pattern::looks_like_knitspeak(text)
    }
    #[staticmethod]
    fn presets() -> Vec<&'static str> {
        StitchPattern::presets()
    }
    #[getter]
    fn name(&self) -> &str {
        self.inner.name()
    }
    #[getter]
    fn width(&self) -> usize {
        self.inner.width()
    }
    #[getter]
    fn height(&self) -> usize {
        self.inner.height()
    }
    fn chart(&self) -> String {
        self.inner.chart()
    }
    fn __repr__(&self) -> String {
        format!(
            "Pattern({:?}, {}x{})",
            self.inner.name(),
            self.inner.width(),
            self.inner.height()
        )
    }
}

fn palette_of(palette: Vec<Vec<f32>>) -> PyResult<Vec<[f32; 3]>> {
    palette
        .into_iter()
        .enumerate()
        .map(|(i, c)| match c.as_slice() {
            [r, g, b] | [r, g, b, _] => Ok([*r, *g, *b]),
            _ => Err(PatternError::new_err(format!(
                "palette colour {i} must be (r, g, b)"
            ))),
        })
        .collect()
}

/// A palette (linear RGB 0..1) and a chart of palette indices repeated over the surface.
#[pyclass(name = "ColorPattern", module = "knitwear", frozen)]
pub struct PyColorPattern {
    inner: ColorPattern,
}

#[pymethods]
impl PyColorPattern {
    #[new]
    #[pyo3(signature = (palette, chart="0"))]
    fn new(palette: Vec<Vec<f32>>, chart: &str) -> PyResult<Self> {
        ColorPattern::new(palette_of(palette)?, chart)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
    /// A named colour chart (see `ColorPattern.presets()`) in the given palette.
    #[staticmethod]
    fn preset(name: &str, palette: Vec<Vec<f32>>) -> PyResult<Self> {
        crate::pattern::color_preset(name, palette_of(palette)?)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
    /// The names of the colour chart presets.
    #[staticmethod]
    fn presets() -> Vec<&'static str> {
        crate::pattern::COLOR_PRESETS
            .iter()
            .map(|(n, _)| *n)
            .collect()
    }
    /// Horizontal stripes: each colour in turn for `rows_each` courses.
    #[staticmethod]
    #[pyo3(signature = (palette, rows_each=2))]
    fn stripes(palette: Vec<Vec<f32>>, rows_each: usize) -> PyResult<Self> {
        ColorPattern::stripes(palette_of(palette)?, rows_each)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
}

/// The result of a knit: NumPy arrays ready for Blender's `foreach_set`.
#[pyclass(name = "KnitResult", module = "knitwear", frozen)]
pub struct PyKnitResult {
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
    centerline_points: Py<PyAny>,
    #[pyo3(get)]
    course_offsets: Py<PyAny>,
    #[pyo3(get)]
    yarn_course: Py<PyAny>,
    #[pyo3(get)]
    yarn_closed: Py<PyAny>,
    #[pyo3(get)]
    yarn_radius: f32,
    /// `(V, 3)` vertex normals of a knit that culls its hidden yarn (the whole knit's smooth
    /// normals), else None.
    #[pyo3(get)]
    normals: Option<Py<PyAny>>,
    #[pyo3(get)]
    stats: Py<PyDict>,
}

#[pymethods]
impl PyKnitResult {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "KnitResult({})",
            self.stats
                .bind(py)
                .repr()
                .map(|r| r.to_string())
                .unwrap_or_default()
        )
    }
}

fn rows<T: numpy::Element>(py: Python<'_>, v: Vec<T>, cols: usize) -> PyResult<Py<PyAny>> {
    let n = v.len() / cols;
    let a = Array2::from_shape_vec((n, cols), v)
        .map_err(|e| InternalError::new_err(format!("output shape: {e}")))?;
    Ok(a.into_pyarray(py).into_any().unbind())
}

fn flat<T: numpy::Element>(py: Python<'_>, v: Vec<T>) -> Py<PyAny> {
    Array1::from_vec(v).into_pyarray(py).into_any().unbind()
}

fn to_result(py: Python<'_>, out: KnitOutput) -> PyResult<PyKnitResult> {
    let s = &out.stats;
    let stats = PyDict::new(py);
    stats.set_item("courses", s.courses)?;
    stats.set_item("wales", s.wales)?;
    stats.set_item("stitches", s.stitches)?;
    stats.set_item("stitches_skipped", s.stitches_skipped)?;
    stats.set_item("stitches_clamped", s.stitches_clamped)?;
    stats.set_item("vertices", s.vertices)?;
    stats.set_item("triangles", s.triangles)?;
    stats.set_item("yarn_pieces", s.yarn_pieces)?;
    stats.set_item("stitch_width", s.stitch_width)?;
    stats.set_item("stitch_height", s.stitch_height)?;
    stats.set_item("flat_clearance", s.flat_clearance)?;
    stats.set_item("clearance_min", s.clearance.map(|c| c.0))?;
    stats.set_item("clearance_p01", s.clearance.map(|c| c.1))?;
    stats.set_item("interlock", s.interlock)?;
    stats.set_item("seconds", s.seconds)?;
    stats.set_item("topology_key", s.topology_key)?;
    let levels = PyDict::new(py);
    for level in crate::detail::Level::ALL {
        levels.set_item(level.name(), s.levels[level as usize])?;
    }
    stats.set_item("levels", levels)?;
    stats.set_item("triangles_full_detail", s.triangles_full_detail)?;
    stats.set_item("triangles_hidden", s.triangles_hidden)?;
    let yarn_radius = out.yarn_radius;
    let normals = if out.normals.is_empty() {
        None
    } else {
        Some(rows(py, out.normals, 3)?)
    };
    Ok(PyKnitResult {
        normals,
        vertices: rows(py, out.positions, 3)?,
        triangles: rows(py, out.triangles, 3)?,
        edges: rows(py, out.edges, 2)?,
        corner_edges: flat(py, out.corner_edges),
        colors: rows(py, out.colors, 4)?,
        centerline_points: rows(py, out.centerline, 3)?,
        course_offsets: flat(py, out.yarn_offsets),
        yarn_course: flat(py, out.yarn_course),
        yarn_closed: flat(py, out.yarn_closed),
        yarn_radius,
        stats: stats.unbind(),
    })
}

enum AnySurface {
    Grid(Arc<GridSurface>),
    Mesh(Arc<MeshSurface>),
}

impl AnySurface {
    fn from_py(surface: &Bound<'_, PyAny>) -> PyResult<Self> {
        if let Ok(g) = surface.cast::<PyGridSurface>() {
            Ok(AnySurface::Grid(g.get().inner.clone()))
        } else if let Ok(m) = surface.cast::<PyMeshSurface>() {
            Ok(AnySurface::Mesh(m.get().inner.clone()))
        } else {
            Err(SurfaceError::new_err(format!(
                "surface must be a knitwear.GridSurface or knitwear.MeshSurface, not {}",
                surface.get_type()
            )))
        }
    }

    fn as_dyn(&self) -> &dyn Surface {
        match self {
            AnySurface::Grid(g) => g.as_ref(),
            AnySurface::Mesh(m) => m.as_ref(),
        }
    }
}

/// The keyword settings of `Knit` (and so of `knitwear.knit`), checked and turned into core
/// params.
#[allow(clippy::too_many_arguments)]
fn params_from(
    courses: Option<i64>,
    wales: Option<i64>,
    gauge: Option<(f32, f32)>,
    yarn_radius: Option<f32>,
    stitch_size: Option<(f32, f32)>,
    fluffiness: f32,
    ring_segments: i64,
    samples_per_loop: i64,
    tension: f32,
    kappa: f32,
    seed: u64,
    colors: Option<&Bound<'_, PyColorPattern>>,
    color_image: Option<&Bound<'_, PyAny>>,
    color_variation: f32,
    threads: Option<i64>,
    budget_bytes: Option<u64>,
    measure_clearance: bool,
) -> PyResult<KnitParams> {
    let count = |name: &str, v: Option<i64>| -> PyResult<Option<usize>> {
        match v {
            None => Ok(None),
            Some(n) if n >= 1 => Ok(Some(usize::try_from(n).unwrap_or(usize::MAX))),
            Some(n) => Err(ParameterError::new_err(format!(
                "{name} must be at least 1, not {n}"
            ))),
        }
    };
    let positive = |name: &str, v: i64| -> PyResult<usize> {
        usize::try_from(v)
            .map_err(|_| ParameterError::new_err(format!("{name} must not be negative, not {v}")))
    };
    let image = match color_image {
        None => None,
        Some(obj) => {
            let arr = obj.cast::<PyArrayDyn<f32>>().map_err(|_| {
                ParameterError::new_err(
                    "color_image must be a float32 array (height, width, 3 or 4)",
                )
            })?;
            let ro = arr.readonly();
            let dims = ro.shape().to_vec();
            if dims.len() != 3 {
                return Err(ParameterError::new_err(format!(
                    "color_image must have shape (height, width, 3 or 4), not {dims:?}"
                )));
            }
            let not_c = || ParameterError::new_err("color_image must be C-contiguous");
            if !ro.is_c_contiguous() {
                return Err(not_c());
            }
            let data = ro.as_slice().map_err(|_| not_c())?.to_vec();
            Some(ColorImage::new(dims[1], dims[0], dims[2], data).map_err(to_py)?)
        }
    };
    let params = KnitParams {
        courses: count("courses", courses)?,
        wales: count("wales", wales)?,
        gauge,
        yarn_radius,
        fluffiness,
        ring_segments: positive("ring_segments", ring_segments)?,
        samples_per_loop: positive("samples_per_loop", samples_per_loop)?,
        tension,
        kappa,
        seed,
        colors: colors.map(|c| c.get().inner.clone()),
        color_image: image,
        color_variation,
        threads: match threads {
            None => None,
            Some(t) => Some(positive("threads", t)?),
        },
        budget_bytes: budget_bytes.unwrap_or(crate::budget::DEFAULT_BUDGET_BYTES),
        measure_clearance,
        stitch_size,
        detail: None,
    };
    Ok(params)
}

/// A knit bound to its surface's (u,v) layout: counts, yarn radius, stitch size, offsets,
/// lattice and buffer layout fixed once, so that `build` and `positions` give the same
/// topology for the surface in any pose (an animated, deformed source).
#[pyclass(name = "Knit", module = "knitwear", frozen)]
pub struct PyKnit {
    inner: Arc<PreparedKnit>,
}

#[pymethods]
impl PyKnit {
    #[new]
    #[pyo3(signature = (
        surface, pattern, *, courses=None, wales=None, gauge=None, yarn_radius=None,
        stitch_size=None, fluffiness=0.5, ring_segments=6, samples_per_loop=16, tension=0.0,
        kappa=0.0, seed=0, colors=None, color_image=None, color_variation=0.15, threads=None,
        budget_bytes=None, measure_clearance=false, camera=None, stitch_levels=None, detail_px=None,
        mid_quality=None, far_quality=None, frustum_margin=0.1, cull_back_faces=false,
        cull_hidden=false, hidden_supersampling=4, seen_triangles=None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        surface: &Bound<'_, PyAny>,
        pattern: &Bound<'_, PyPattern>,
        courses: Option<i64>,
        wales: Option<i64>,
        gauge: Option<(f32, f32)>,
        yarn_radius: Option<f32>,
        stitch_size: Option<(f32, f32)>,
        fluffiness: f32,
        ring_segments: i64,
        samples_per_loop: i64,
        tension: f32,
        kappa: f32,
        seed: u64,
        colors: Option<&Bound<'_, PyColorPattern>>,
        color_image: Option<&Bound<'_, PyAny>>,
        color_variation: f32,
        threads: Option<i64>,
        budget_bytes: Option<u64>,
        measure_clearance: bool,
        camera: Option<&Bound<'_, detail::PyCamera>>,
        stitch_levels: Option<&Bound<'_, PyAny>>,
        detail_px: Option<(f32, f32, f32)>,
        mid_quality: Option<(i64, i64, bool)>,
        far_quality: Option<(i64, i64, bool)>,
        frustum_margin: f32,
        cull_back_faces: bool,
        cull_hidden: bool,
        hidden_supersampling: u32,
        seen_triangles: Option<Vec<u8>>,
    ) -> PyResult<Self> {
        let surf = AnySurface::from_py(surface)?;
        let mut params = params_from(
            courses,
            wales,
            gauge,
            yarn_radius,
            stitch_size,
            fluffiness,
            ring_segments,
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
        params.detail = detail::detail_from(
            camera,
            stitch_levels,
            detail_px,
            mid_quality,
            far_quality,
            frustum_margin,
            cull_back_faces,
            cull_hidden,
            hidden_supersampling,
            seen_triangles,
        )?;
        let pattern = pattern.get().inner.clone();
        let inner = guarded(py, move || {
            PreparedKnit::new(surf.as_dyn(), &pattern, &params)
        })?;
        Ok(Self {
            inner: Arc::new(inner),
        })
    }

    /// The whole result for `surface` (the one knitted, or it deformed).
    fn build(&self, py: Python<'_>, surface: &Bound<'_, PyAny>) -> PyResult<PyKnitResult> {
        let surf = AnySurface::from_py(surface)?;
        let knit = self.inner.clone();
        let out = guarded(py, move || knit.build(surf.as_dyn()))?;
        to_result(py, out)
    }

    /// The interlock-topology metric on `surface`: `(decided, agree, undecided)` crossings,
    /// where `agree` of the `decided` ones have in front the yarn the pattern says.
    fn crossing_order(
        &self,
        py: Python<'_>,
        surface: &Bound<'_, PyAny>,
    ) -> PyResult<(usize, usize, usize)> {
        let surf = AnySurface::from_py(surface)?;
        let knit = self.inner.clone();
        let c = guarded(py, move || knit.crossing_order(surf.as_dyn()))?;
        Ok((c.decided, c.agree, c.undecided))
    }

    /// Vertex positions only, `(V, 3)` float32, for `surface` in a new pose: bit-identical
    /// to `build(surface).vertices`. With `out` (a writable C-contiguous float32 `(V, 3)`
    /// array) they are written there and `out` is returned: no allocation per frame.
    #[pyo3(signature = (surface, out=None))]
    fn positions(
        &self,
        py: Python<'_>,
        surface: &Bound<'_, PyAny>,
        out: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Py<PyAny>> {
        let surf = AnySurface::from_py(surface)?;
        let knit = self.inner.clone();
        let nv = knit.vertex_count();
        match out {
            None => {
                let mut buf = crate::output_buffer::zeroed::<f32>(3 * nv);
                let buf = guarded(py, move || {
                    knit.positions_into(surf.as_dyn(), &mut buf).map(|_| buf)
                })?;
                rows(py, buf, 3)
            }
            Some(obj) => {
                let arr = obj.cast::<PyArrayDyn<f32>>().map_err(|_| {
                    ParameterError::new_err("out must be a float32 numpy array of shape (V, 3)")
                })?;
                if arr.shape() != [nv, 3] {
                    return Err(ParameterError::new_err(format!(
                        "out must have shape ({nv}, 3), not {:?}",
                        arr.shape()
                    )));
                }
                let mut rw = arr.try_readwrite().map_err(|_| {
                    ParameterError::new_err("out must be writable and not borrowed elsewhere")
                })?;
                let slice = rw
                    .as_slice_mut()
                    .map_err(|_| ParameterError::new_err("out must be C-contiguous"))?;
                if !arr.is_c_contiguous() {
                    return Err(ParameterError::new_err("out must be C-contiguous"));
                }
                guarded(py, move || knit.positions_into(surf.as_dyn(), slice))?;
                Ok(obj.clone().unbind())
            }
        }
    }

    /// `(V, 3)` float32 vertex normals for `surface` in a new pose, bit-identical to
    /// `build(surface).normals`, of a knit that culls its hidden yarn (a `ParameterError` for
    /// another: its mesh's own normals are right). With `out`, written there.
    #[pyo3(signature = (surface, out=None))]
    fn normals(
        &self,
        py: Python<'_>,
        surface: &Bound<'_, PyAny>,
        out: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Py<PyAny>> {
        let surf = AnySurface::from_py(surface)?;
        let knit = self.inner.clone();
        let nv = knit.vertex_count();
        let mut normals = crate::output_buffer::zeroed::<f32>(3 * nv);
        let normals = guarded(py, move || {
            let mut positions = crate::output_buffer::zeroed::<f32>(3 * nv);
            knit.positions_and_normals_into(surf.as_dyn(), &mut positions, Some(&mut normals))
                .map(|_| normals)
        })?;
        match out {
            None => rows(py, normals, 3),
            Some(obj) => {
                let np = py.import("numpy")?;
                let src = rows(py, normals, 3)?;
                np.call_method1("copyto", (obj, src)).map_err(|e| {
                    ParameterError::new_err(format!("out must be a float32 array ({nv}, 3): {e}"))
                })?;
                Ok(obj.clone().unbind())
            }
        }
    }

    /// Vertices of every build.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.vertex_count()
    }

    /// The yarn radius, scene units.
    #[getter]
    fn yarn_radius(&self) -> f32 {
        self.inner.yarn_radius()
    }

    /// `(courses, wales)`.
    #[getter]
    fn counts(&self) -> (usize, usize) {
        let s = self.inner.stats();
        (s.courses, s.wales)
    }

    /// `(width, height)` of a stitch that the loop shapes are tuned for, scene units.
    #[getter]
    fn stitch_size(&self) -> (f32, f32) {
        let s = self.inner.stats();
        (s.stitch_width, s.stitch_height)
    }

    /// Equal keys mean identical triangles, edges and corner edges (see `KnitResult.stats`).
    #[getter]
    fn topology_key(&self) -> u64 {
        self.inner.stats().topology_key
    }

    /// With `cull_hidden`: the triangles seen, as `bytes`, one bit per triangle of the knit
    /// before culling (triangle `i` at bit `i % 8` of byte `i / 8`). Pass them back as
    /// `seen_triangles` (with `stitch_levels`) to rebuild the same mesh without the camera.
    /// None without.
    #[getter]
    fn seen_triangles<'py>(&self, py: Python<'py>) -> Option<Bound<'py, pyo3::types::PyBytes>> {
        self.inner
            .seen_triangles()
            .map(|b| pyo3::types::PyBytes::new(py, b))
    }

    /// With a camera: `(courses, wales)` uint8, each stitch's level (0 full, 1 mid, 2 far,
    /// 3 texture, 4 culled or no surface under it). None without a camera.
    #[getter]
    fn stitch_levels(&self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        let Some(levels) = self.inner.stitch_levels() else {
            return Ok(None);
        };
        let wales = self.inner.stats().wales;
        let v: Vec<u8> = levels.iter().map(|l| *l as u8).collect();
        rows(py, v, wales).map(Some)
    }
}

/// A knit result's centreline: its points (scene units), each yarn piece's range of points
/// and whether it is closed, and the yarn radius.
type Centreline = (Vec<glam::Vec3>, Vec<(usize, usize, bool)>, f32);

/// See [`Centreline`].
fn result_centreline(py: Python<'_>, result: &Bound<'_, PyKnitResult>) -> PyResult<Centreline> {
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

/// Clearance of a knit result: `(min, p01)` in yarn diameters (DESIGN.md section 7).
#[pyfunction]
fn measure_clearance(py: Python<'_>, result: &Bound<'_, PyKnitResult>) -> PyResult<(f32, f32)> {
    let (v, ranges, radius) = result_centreline(py, result)?;
    guarded(py, move || {
        let yarns: Vec<YarnPolyline> = ranges
            .iter()
            .map(|&(a, b, c)| YarnPolyline {
                points: &v[a..b],
                closed: c,
            })
            .collect();
        let c = clearance(
            &yarns,
            2.0 * radius,
            DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
            3.0,
        );
        Ok((c.min, c.p01))
    })
}

/// Optical cover of a knit result (DESIGN.md section 7): the fraction of the rectangle
/// `bounds = (x_min, y_min, x_max, y_max)` (object space) hidden by the yarn's tubes (no
/// fluff) in an orthographic view along z, sampled on `resolution` x `resolution` pixels.
#[pyfunction]
#[pyo3(signature = (result, bounds, resolution=800))]
fn measure_cover(
    py: Python<'_>,
    result: &Bound<'_, PyKnitResult>,
    bounds: (f32, f32, f32, f32),
    resolution: usize,
) -> PyResult<f64> {
    let (v, ranges, radius) = result_centreline(py, result)?;
    if !(1..=8192).contains(&resolution) {
        return Err(to_py(KnitError::Parameter(format!(
            "resolution must be in 1..=8192, not {resolution}"
        ))));
    }
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

/// Raises InternalError from a deliberate panic in the core: proves that no Rust panic
/// crosses into Python. For tests.
#[pyfunction]
fn _force_internal_error(py: Python<'_>) -> PyResult<()> {
    guarded(py, || -> Result<(), KnitError> {
        panic!("forced internal error (test hook)")
    })
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("KnitError", py.get_type::<PyKnitError>())?;
    m.add("SurfaceError", py.get_type::<SurfaceError>())?;
    m.add("PatternError", py.get_type::<PatternError>())?;
    m.add("ParameterError", py.get_type::<ParameterError>())?;
    m.add("BudgetError", py.get_type::<BudgetError>())?;
    m.add("InternalError", py.get_type::<InternalError>())?;
    m.add_class::<PyGridSurface>()?;
    m.add_class::<PyMeshSurface>()?;
    m.add_class::<PyPattern>()?;
    m.add_class::<PyColorPattern>()?;
    m.add_class::<PyKnitResult>()?;
    m.add_class::<PyKnit>()?;
    m.add_function(wrap_pyfunction!(measure_clearance, m)?)?;
    m.add_function(wrap_pyfunction!(measure_cover, m)?)?;
    m.add_function(wrap_pyfunction!(_force_internal_error, m)?)?;
    pile::register(m)?;
    texture::register(m)?;
    settings::register(m)?;
    detail::register(m)?;
    Ok(())
}
