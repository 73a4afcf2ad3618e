//! `Knit` and `KnitResult`: a knit bound to its surface, its keyword settings, and the
//! buffers it returns.

use std::sync::Arc;

use numpy::{PyArrayDyn, PyArrayMethods, PyReadwriteArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::knit::{ColorImage, KnitOutput, KnitParams, PreparedKnit};

use super::*;

/// The result of a knit: NumPy arrays ready for Blender's `foreach_set`.
#[pyclass(name = "KnitResult", module = "knitwear", frozen)]
pub struct PyKnitResult {
    #[pyo3(get)]
    pub(crate) vertices: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) triangles: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) edges: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) corner_edges: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) colors: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) centerline_points: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) course_offsets: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) yarn_course: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) yarn_closed: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) yarn_radius: f32,
    /// `(V, 3)` unit shading normals: the swept tube's, out from the yarn's centreline (a
    /// knit that culls its hidden yarn: the whole knit's, at the vertices it keeps).
    #[pyo3(get)]
    pub(crate) normals: Py<PyAny>,
    /// `(V, 3)` unit fibre directions: along the yarn, slanted round it with the plies'
    /// twist, perpendicular to `normals` (for a material's anisotropic highlight).
    #[pyo3(get)]
    pub(crate) tangents: Py<PyAny>,
    #[pyo3(get)]
    pub(crate) stats: Py<PyDict>,
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

pub(crate) fn to_result(py: Python<'_>, out: KnitOutput) -> PyResult<PyKnitResult> {
    let s = &out.stats;
    let stats = PyDict::new(py);
    stats.set_item("courses", s.courses)?;
    stats.set_item("wales", s.wales)?;
    stats.set_item("stitches", s.stitches)?;
    stats.set_item("stitches_skipped", s.stitches_skipped)?;
    stats.set_item("stitches_lost", s.stitches_lost)?;
    stats.set_item("stitches_clamped", s.stitches_clamped)?;
    stats.set_item("vertices", s.vertices)?;
    stats.set_item("triangles", s.triangles)?;
    stats.set_item("yarn_pieces", s.yarn_pieces)?;
    stats.set_item("in_the_round", s.in_the_round)?;
    stats.set_item("stitch_width", s.stitch_width)?;
    stats.set_item("stitch_height", s.stitch_height)?;
    let spread = match s.stitch_spread {
        None => None,
        Some(sp) => {
            let d = PyDict::new(py);
            d.set_item("width", sp.width)?;
            d.set_item("height", sp.height)?;
            d.set_item("stretched", sp.stretched)?;
            Some(d)
        }
    };
    stats.set_item("stitch_spread", spread)?;
    stats.set_item("flat_clearance", s.flat_clearance)?;
    stats.set_item("clearance_min", s.clearance.map(|c| c.0))?;
    stats.set_item("clearance_p01", s.clearance.map(|c| c.1))?;
    stats.set_item("interlock", s.interlock)?;
    stats.set_item("free_loops", s.free_loops)?;
    stats.set_item("seconds", s.seconds)?;
    stats.set_item("topology_key", s.topology_key)?;
    let levels = PyDict::new(py);
    for level in crate::detail::Level::ALL {
        levels.set_item(level.name(), s.levels[level as usize])?;
    }
    stats.set_item("levels", levels)?;
    stats.set_item("triangles_full_detail", s.triangles_full_detail)?;
    stats.set_item("triangles_hidden", s.triangles_hidden)?;
    stats.set_item("hidden_pass", s.hidden_pass)?;
    stats.set_item("hidden_pass_seconds", s.hidden_pass_seconds)?;
    let yarn_radius = out.yarn_radius;
    Ok(PyKnitResult {
        normals: rows(py, out.normals, 3)?,
        tangents: rows(py, out.tangents, 3)?,
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

/// Whether a knit of `courses x wales` stitches of `pattern` fits the memory budget, as `Knit`
/// checks it first: the output's upper bound in bytes, or `BudgetError`. Cheap (no surface):
/// for a caller that must sample a surface densely for that many stitches, to refuse an
/// absurd count before it samples.
#[pyfunction]
#[pyo3(signature = (pattern, courses, wales, *, ring_segments=6, samples_per_loop=16, budget_bytes=None))]
pub(crate) fn check_budget(
    pattern: &Bound<'_, PyPattern>,
    #[pyo3(from_py_with = int_arg)] courses: i128,
    #[pyo3(from_py_with = int_arg)] wales: i128,
    #[pyo3(from_py_with = int_arg)] ring_segments: i128,
    #[pyo3(from_py_with = int_arg)] samples_per_loop: i128,
    #[pyo3(from_py_with = opt_int_arg)] budget_bytes: Option<i128>,
) -> PyResult<u64> {
    let defaults = KnitParams::default();
    let params = KnitParams {
        ring_segments: count_arg("ring_segments", ring_segments, 0)?,
        samples_per_loop: count_arg("samples_per_loop", samples_per_loop, 0)?,
        budget_bytes: budget_arg(budget_bytes, defaults.budget_bytes)?,
        ..defaults
    };
    let courses = count_arg("courses", courses, 1)?;
    let wales = count_arg("wales", wales, 1)?;
    crate::knit::check_budget(&pattern.get().inner, courses, wales, &params).map_err(to_py)
}

/// The keyword settings of `Knit` (and so of `knitwear.knit`), checked and turned into core
/// params.
#[allow(clippy::too_many_arguments)]
pub(crate) fn params_from(
    courses: Option<i128>,
    wales: Option<i128>,
    gauge: Option<(f32, f32)>,
    yarn_radius: Option<f32>,
    stitch_size: Option<(f32, f32)>,
    fluffiness: f32,
    ring_segments: i128,
    plies: i128,
    live_loops: bool,
    samples_per_loop: i128,
    tension: f32,
    kappa: f32,
    seed: i128,
    colors: Option<&Bound<'_, PyColorPattern>>,
    color_image: Option<&Bound<'_, PyAny>>,
    color_variation: f32,
    threads: Option<i128>,
    budget_bytes: Option<i128>,
    measure_clearance: bool,
) -> PyResult<KnitParams> {
    let count = |name: &str, v: Option<i128>| v.map(|n| count_arg(name, n, 1)).transpose();
    // The core checks each setting's own range; here only what a usize cannot hold.
    let positive = |name: &str, v: i128| count_arg(name, v, 0);
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
        plies: positive("plies", plies)?,
        live_loops,
        samples_per_loop: positive("samples_per_loop", samples_per_loop)?,
        tension,
        kappa,
        seed: seed_arg(seed)?,
        colors: colors.map(|c| c.get().inner.clone()),
        color_image: image,
        color_variation,
        threads: match threads {
            None => None,
            Some(t) => Some(positive("threads", t)?),
        },
        budget_bytes: budget_arg(budget_bytes, crate::budget::DEFAULT_BUDGET_BYTES)?,
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
    pub(crate) inner: Arc<PreparedKnit>,
}

#[pymethods]
impl PyKnit {
    #[new]
    #[pyo3(signature = (
        surface, pattern, *, courses=None, wales=None, gauge=None, yarn_radius=None,
        stitch_size=None, fluffiness=0.5, ring_segments=6, plies=1, live_loops=false, samples_per_loop=16,
        tension=0.0,
        kappa=0.0, seed=0, colors=None, color_image=None, color_variation=0.15, threads=None,
        budget_bytes=None, measure_clearance=false, camera=None, stitch_levels=None, detail_px=None,
        mid_quality=None, far_quality=None, frustum_margin=0.1, cull_back_faces=false,
        cull_hidden=false, hidden_supersampling=4, cull_hidden_min_triangles=0,
        seen_triangles=None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        surface: &Bound<'_, PyAny>,
        pattern: &Bound<'_, PyPattern>,
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
        camera: Option<&Bound<'_, detail::PyCamera>>,
        stitch_levels: Option<&Bound<'_, PyAny>>,
        #[pyo3(from_py_with = detail::detail_px_arg)] detail_px: Option<(f32, f32, f32)>,
        #[pyo3(from_py_with = detail::mid_quality_arg)] mid_quality: Option<(i64, i64, bool)>,
        #[pyo3(from_py_with = detail::far_quality_arg)] far_quality: Option<(i64, i64, bool)>,
        frustum_margin: f32,
        cull_back_faces: bool,
        cull_hidden: bool,
        #[pyo3(from_py_with = int_arg)] hidden_supersampling: i128,
        #[pyo3(from_py_with = int_arg)] cull_hidden_min_triangles: i128,
        #[pyo3(from_py_with = detail::seen_triangles_arg)] seen_triangles: Option<Vec<u8>>,
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
            cull_hidden_min_triangles,
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

    /// `(min, p01)` centreline clearance in yarn diameters of the knit's yarn on `surface`
    /// (the knitted one, or it deformed): what `build(surface)` measures with
    /// `measure_clearance`, without building the mesh. At 1 neighbouring yarns touch.
    fn clearance(&self, py: Python<'_>, surface: &Bound<'_, PyAny>) -> PyResult<(f32, f32)> {
        let surf = AnySurface::from_py(surface)?;
        let knit = self.inner.clone();
        guarded(py, move || knit.clearance(surf.as_dyn()))
    }

    /// Vertex positions only, `(V, 3)` float32, for `surface` in a new pose: bit-identical
    /// to `build(surface).vertices`. With `out` (a writable C-contiguous float32 `(V, 3)`
    /// array) they are written there and `out` is returned: no allocation per frame. With
    /// `normals_out` and `tangents_out` (other such arrays) the knit's shading normals and
    /// fibre directions are written there too, in the same pass (see `KnitResult.normals`
    /// and `KnitResult.tangents`).
    #[pyo3(signature = (surface, out=None, normals_out=None, tangents_out=None))]
    fn positions(
        &self,
        py: Python<'_>,
        surface: &Bound<'_, PyAny>,
        out: Option<&Bound<'_, PyAny>>,
        normals_out: Option<&Bound<'_, PyAny>>,
        tangents_out: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Py<PyAny>> {
        let surf = AnySurface::from_py(surface)?;
        let knit = self.inner.clone();
        let nv = knit.vertex_count();
        let mut normals = normals_out
            .map(|n| writable_rows(n, nv, "normals_out"))
            .transpose()?;
        let normals_slice = match normals.as_mut() {
            Some(rw) => Some(contiguous(rw, "normals_out")?),
            None => None,
        };
        let mut tangents = tangents_out
            .map(|t| writable_rows(t, nv, "tangents_out"))
            .transpose()?;
        let tangents_slice = match tangents.as_mut() {
            Some(rw) => Some(contiguous(rw, "tangents_out")?),
            None => None,
        };
        match out {
            None => {
                let mut buf = crate::output_buffer::zeroed::<f32>(3 * nv);
                let buf = guarded(py, move || {
                    knit.positions_and_shading_into(
                        surf.as_dyn(),
                        &mut buf,
                        normals_slice,
                        tangents_slice,
                    )
                    .map(|_| buf)
                })?;
                rows(py, buf, 3)
            }
            Some(obj) => {
                let mut rw = writable_rows(obj, nv, "out")?;
                let slice = contiguous(&mut rw, "out")?;
                guarded(py, move || {
                    knit.positions_and_shading_into(
                        surf.as_dyn(),
                        slice,
                        normals_slice,
                        tangents_slice,
                    )
                })?;
                Ok(obj.clone().unbind())
            }
        }
    }

    /// `(V, 3)` float32 unit shading normals for `surface` in a new pose (the swept tube's,
    /// out from the yarn's centreline), bit-identical to `build(surface).normals`. With
    /// `out`, written there. `positions(surface, out, normals_out)` gives both in one pass.
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
        let mut positions = crate::output_buffer::zeroed::<f32>(3 * nv);
        match out {
            None => {
                let mut normals = crate::output_buffer::zeroed::<f32>(3 * nv);
                let normals = guarded(py, move || {
                    knit.positions_and_shading_into(
                        surf.as_dyn(),
                        &mut positions,
                        Some(&mut normals),
                        None,
                    )
                    .map(|_| normals)
                })?;
                rows(py, normals, 3)
            }
            Some(obj) => {
                let mut rw = writable_rows(obj, nv, "out")?;
                let slice = contiguous(&mut rw, "out")?;
                guarded(py, move || {
                    knit.positions_and_shading_into(
                        surf.as_dyn(),
                        &mut positions,
                        Some(slice),
                        None,
                    )
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

    /// Triangles of every build.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.inner.triangle_count()
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

/// `obj` as a writable float32 `(nv, 3)` array, borrowed for writing; errors name `what`.
fn writable_rows<'py>(
    obj: &Bound<'py, PyAny>,
    nv: usize,
    what: &str,
) -> PyResult<PyReadwriteArrayDyn<'py, f32>> {
    let arr = obj.cast::<PyArrayDyn<f32>>().map_err(|_| {
        ParameterError::new_err(format!(
            "{what} must be a float32 numpy array of shape (V, 3)"
        ))
    })?;
    if arr.shape() != [nv, 3] {
        return Err(ParameterError::new_err(format!(
            "{what} must have shape ({nv}, 3), not {:?}",
            arr.shape()
        )));
    }
    if !arr.is_c_contiguous() {
        return Err(ParameterError::new_err(format!(
            "{what} must be C-contiguous"
        )));
    }
    arr.try_readwrite().map_err(|_| {
        ParameterError::new_err(format!(
            "{what} must be writable and not borrowed elsewhere (nor be another output)"
        ))
    })
}

/// The borrowed array's floats.
fn contiguous<'a>(rw: &'a mut PyReadwriteArrayDyn<'_, f32>, what: &str) -> PyResult<&'a mut [f32]> {
    rw.as_slice_mut()
        .map_err(|_| ParameterError::new_err(format!("{what} must be C-contiguous")))
}
