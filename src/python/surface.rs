//! `GridSurface` and `MeshSurface`: the sampled surfaces a knit or a plush is built on.

use std::sync::Arc;

use pyo3::prelude::*;

use crate::surface::{GridSurface, MeshSurface, Surface};

use super::*;

/// Positions and normals sampled on a regular (u,v) grid (a NURBS surface).
#[pyclass(name = "GridSurface", module = "knitwear", frozen)]
pub struct PyGridSurface {
    pub(crate) inner: Arc<GridSurface>,
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
    pub(crate) inner: Arc<MeshSurface>,
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

    /// Whether the UV map closes round along u and along v (a tube's seam): `(u, v)`. A
    /// closed direction is knitted in the round.
    #[getter]
    fn cyclic(&self) -> (bool, bool) {
        (self.inner.cyclic_u(), self.inner.cyclic_v())
    }
}

pub(crate) enum AnySurface {
    Grid(Arc<GridSurface>),
    Mesh(Arc<MeshSurface>),
}

impl AnySurface {
    pub(crate) fn from_py(surface: &Bound<'_, PyAny>) -> PyResult<Self> {
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

    /// The surface, shared.
    pub(crate) fn shared(&self) -> Arc<dyn Surface> {
        match self {
            AnySurface::Grid(g) => g.clone(),
            AnySurface::Mesh(m) => m.clone(),
        }
    }

    pub(crate) fn as_dyn(&self) -> &dyn Surface {
        match self {
            AnySurface::Grid(g) => g.as_ref(),
            AnySurface::Mesh(m) => m.as_ref(),
        }
    }
}
