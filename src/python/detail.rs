//! Binding of camera-driven detail ([`crate::detail`]): `knitwear.Camera` (one or more views
//! of the surface and a resolution) and the detail keywords of `Knit`. Thin: shapes and
//! values are checked here only as far as turning them into core types needs; the core
//! validates the rest.

use glam::{Mat4, Vec4};
use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use super::ParameterError;
use crate::detail::{CameraView, DetailParams, Level, LevelQuality, ViewPoses};

/// Camera views of a surface, for camera-driven detail: each view's clip-from-object matrix
/// (`projection @ view @ world_from_object`, OpenGL clip conventions, row-major as numpy
/// and Blender write matrices) and eye (`(x, y, z, 1)` position for a perspective camera,
/// `(dx, dy, dz, 0)` unit direction towards an orthographic one), in the surface's object
/// space; and the render resolution in pixels. Several views (an animated camera's frames)
/// model each stitch for the view that sees it largest. `poses`: the surface as each view
/// sees it (a deforming source sampled at each view's frame), one per view; without them
/// every view sees the knit's own surface.
#[pyclass(name = "Camera", module = "knitwear", frozen)]
pub struct PyCamera {
    pub(super) views: Vec<CameraView>,
    pub(super) poses: ViewPoses,
    pub(super) resolution: (u32, u32),
}

/// `obj` as a C-contiguous float32 array of `numpy.ascontiguousarray(obj, "float32")`,
/// flattened, with its shape.
fn floats(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<(Vec<usize>, Vec<f32>)> {
    let np = obj.py().import("numpy")?;
    let arr = np
        .call_method1("ascontiguousarray", (obj, "float32"))
        .map_err(|e| ParameterError::new_err(format!("{name} must be numbers: {e}")))?;
    let arr = arr
        .cast::<PyArrayDyn<f32>>()
        .map_err(|_| ParameterError::new_err(format!("{name} must be a float array")))?;
    let ro = arr.readonly();
    let shape = ro.shape().to_vec();
    let data = ro
        .as_slice()
        .map_err(|_| ParameterError::new_err(format!("{name} must be contiguous")))?
        .to_vec();
    Ok((shape, data))
}

#[pymethods]
impl PyCamera {
    #[new]
    #[pyo3(signature = (matrices, eyes, resolution, poses=None))]
    fn new(
        matrices: &Bound<'_, PyAny>,
        eyes: &Bound<'_, PyAny>,
        #[pyo3(from_py_with = super::int_pair_arg)] resolution: (i128, i128),
        poses: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        // The core checks the range; here only what a u32 can hold.
        let resolution = (
            super::within("camera resolution width", resolution.0, 0u32, u32::MAX)?,
            super::within("camera resolution height", resolution.1, 0u32, u32::MAX)?,
        );
        let (ms, m) = floats(matrices, "matrices")?;
        let (es, e) = floats(eyes, "eyes")?;
        let views = match (ms.as_slice(), es.as_slice()) {
            ([4, 4], [4]) => 1,
            ([f, 4, 4], [g, 4]) if f == g && *f > 0 => *f,
            _ => {
                return Err(ParameterError::new_err(format!(
                    "a camera takes matrices (4, 4) and eyes (4,), or (F, 4, 4) and (F, 4) \
                     for F views; got {ms:?} and {es:?}"
                )))
            }
        };
        let views = (0..views)
            .map(|i| {
                let rows: [f32; 16] = m[16 * i..16 * i + 16].try_into().expect("16 floats");
                CameraView {
                    // numpy is row-major, glam column-major.
                    clip_from_object: Mat4::from_cols_array(&rows).transpose(),
                    eye: Vec4::from_slice(&e[4 * i..4 * i + 4]),
                }
            })
            .collect::<Vec<_>>();
        let poses = match poses {
            None => ViewPoses::default(),
            Some(list) => {
                let poses = list
                    .try_iter()
                    .map_err(|_| {
                        ParameterError::new_err(
                            "poses must be a sequence of surfaces, one per camera view",
                        )
                    })?
                    .map(|s| super::surface::AnySurface::from_py(&s?).map(|s| s.shared()))
                    .collect::<PyResult<Vec<_>>>()?;
                if poses.len() != views.len() {
                    return Err(ParameterError::new_err(format!(
                        "a camera of {} view(s) takes one pose per view, not {}",
                        views.len(),
                        poses.len()
                    )));
                }
                ViewPoses(poses)
            }
        };
        Ok(Self {
            views,
            poses,
            resolution,
        })
    }

    /// Whether each view sees a pose of its own.
    #[getter]
    fn posed(&self) -> bool {
        !self.poses.is_empty()
    }

    /// Number of views.
    #[getter]
    fn views(&self) -> usize {
        self.views.len()
    }

    /// `(width, height)` in pixels.
    #[getter]
    fn resolution(&self) -> (u32, u32) {
        self.resolution
    }

    fn __repr__(&self) -> String {
        format!(
            "Camera({} view(s){}, {} x {})",
            self.views.len(),
            if self.poses.is_empty() {
                ""
            } else {
                " with poses"
            },
            self.resolution.0,
            self.resolution.1
        )
    }
}

fn quality(name: &str, q: Option<(i64, i64, bool)>) -> PyResult<Option<LevelQuality>> {
    q.map(|(s, m, fluff)| {
        let s = usize::try_from(s).map_err(|_| {
            ParameterError::new_err(format!("{name} samples per loop must not be negative"))
        })?;
        let m = usize::try_from(m).map_err(|_| {
            ParameterError::new_err(format!("{name} ring segments must not be negative"))
        })?;
        Ok(LevelQuality {
            samples_per_loop: s,
            ring_segments: m,
            fluff,
        })
    })
    .transpose()
}

/// Pinned levels from an integer array of any shape (flattened row-major).
fn pinned_levels(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Level>> {
    let (_, v) = floats(obj, "stitch_levels")?;
    v.into_iter()
        .map(|x| {
            if x.fract() != 0.0 || !(0.0..=255.0).contains(&x) {
                return Err(ParameterError::new_err(format!(
                    "stitch levels are integers 0 (full) to 4 (culled), not {x}"
                )));
            }
            Level::try_from(x as u8).map_err(super::to_py)
        })
        .collect()
}

pub(super) fn detail_px_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<(f32, f32, f32)>> {
    super::opt_shaped_arg(
        obj,
        "detail_px",
        "(full, mid, texture) pixels: three numbers",
    )
}

pub(super) fn mid_quality_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<(i64, i64, bool)>> {
    super::opt_shaped_arg(
        obj,
        "mid_quality",
        "(samples_per_loop, ring_segments, fluff): two integers and a bool",
    )
}

pub(super) fn far_quality_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<(i64, i64, bool)>> {
    super::opt_shaped_arg(
        obj,
        "far_quality",
        "(samples_per_loop, ring_segments, fluff): two integers and a bool",
    )
}

pub(super) fn seen_triangles_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<Vec<u8>>> {
    super::opt_shaped_arg(
        obj,
        "seen_triangles",
        "bytes (KnitResult.seen_triangles of an earlier knit)",
    )
}

/// The core's detail settings from `Knit`'s keywords; `None` without a camera or pinned
/// levels.
#[allow(clippy::too_many_arguments)]
pub(super) fn detail_from(
    camera: Option<&Bound<'_, PyCamera>>,
    stitch_levels: Option<&Bound<'_, PyAny>>,
    detail_px: Option<(f32, f32, f32)>,
    mid_quality: Option<(i64, i64, bool)>,
    far_quality: Option<(i64, i64, bool)>,
    frustum_margin: f32,
    cull_back_faces: bool,
    cull_hidden: bool,
    hidden_supersampling: i128,
    cull_hidden_min_triangles: i128,
    seen_triangles: Option<Vec<u8>>,
) -> PyResult<Option<DetailParams>> {
    let pinned = stitch_levels.map(pinned_levels).transpose()?;
    let (views, poses, resolution) = match (camera, &pinned) {
        (None, None) if cull_hidden || seen_triangles.is_some() => {
            return Err(ParameterError::new_err(
                "culling hidden yarn needs a camera (or the pinned stitch_levels and \
                 seen_triangles of an earlier knit)",
            ))
        }
        (Some(_), Some(_)) => {
            return Err(ParameterError::new_err(
                "give a camera or pinned stitch_levels, not both",
            ))
        }
        (Some(c), None) => (
            c.get().views.clone(),
            c.get().poses.clone(),
            c.get().resolution,
        ),
        (None, _) => (Vec::new(), ViewPoses::default(), (1, 1)),
    };
    let defaults = DetailParams::default();
    let (full_px, mid_px, texture_px) =
        detail_px.unwrap_or((defaults.full_px, defaults.mid_px, defaults.texture_px));
    let no_view = views.is_empty() && pinned.is_none();
    let params = DetailParams {
        views,
        poses,
        resolution,
        pinned,
        full_px,
        mid_px,
        texture_px,
        mid: quality("mid_quality", mid_quality)?,
        far: quality("far_quality", far_quality)?,
        frustum_margin,
        cull_back_faces,
        cull_hidden: cull_hidden || seen_triangles.is_some(),
        hidden_supersampling: super::within(
            "hidden_supersampling",
            hidden_supersampling,
            0u32,
            u32::MAX,
        )?,
        cull_hidden_min_triangles: super::within(
            "cull_hidden_min_triangles",
            cull_hidden_min_triangles,
            0u64,
            u64::MAX,
        )?,
        pinned_seen: seen_triangles,
    };
    if no_view {
        // Without a camera every stitch is full detail and these settings are unused, but a
        // value out of range is still the caller's mistake to hear about.
        params.validate_settings().map_err(super::errors::to_py)?;
        return Ok(None);
    }
    Ok(Some(params))
}

pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyCamera>()
}
