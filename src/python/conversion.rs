//! NumPy buffers in and out: shape and dtype checks with messages that name the argument,
//! and vectors handed to NumPy without a copy.

use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use super::*;

/// A float32 C-contiguous array of the expected trailing shape, copied out as a Vec (the
/// inputs are small next to the output). Errors name the argument.
pub(crate) fn f32_buffer(
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
pub(crate) fn index_buffer(obj: &Bound<'_, PyAny>) -> PyResult<Vec<u32>> {
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

pub(crate) fn rows<T: numpy::Element>(
    py: Python<'_>,
    v: Vec<T>,
    cols: usize,
) -> PyResult<Py<PyAny>> {
    let n = v.len() / cols;
    let a = Array2::from_shape_vec((n, cols), v)
        .map_err(|e| InternalError::new_err(format!("output shape: {e}")))?;
    Ok(a.into_pyarray(py).into_any().unbind())
}

pub(crate) fn flat<T: numpy::Element>(py: Python<'_>, v: Vec<T>) -> Py<PyAny> {
    Array1::from_vec(v).into_pyarray(py).into_any().unbind()
}
