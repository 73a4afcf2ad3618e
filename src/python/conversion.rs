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

/// A Python `str` argument as Rust text. A lone surrogate (which Python strings may hold and
/// UTF-8 cannot) or a value that is not a `str` is a [`PatternError`] naming the argument,
/// not a `UnicodeEncodeError` or `TypeError` from deep inside the binding.
pub(crate) fn text_arg(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    let s = obj.cast::<pyo3::types::PyString>().map_err(|_| {
        PatternError::new_err(format!(
            "{name} must be a str, not {}",
            obj.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    s.to_str().map(str::to_owned).map_err(|_| {
        PatternError::new_err(format!(
            "{name} holds a character that is not valid Unicode (a lone surrogate such as \
             '\\udc80', often left by decoding bytes with errors='surrogateescape')"
        ))
    })
}

/// A file path argument: `str`, `bytes` or any `os.PathLike`, as Python's own `open` takes.
pub(crate) fn path_arg(obj: &Bound<'_, PyAny>) -> PyResult<std::path::PathBuf> {
    let fspath = obj
        .py()
        .import("os")
        .and_then(|os| os.call_method1("fspath", (obj,)))
        .map_err(|_| {
            PatternError::new_err(format!(
                "a pattern file path must be a str, bytes or os.PathLike, not {}",
                obj.get_type()
                    .name()
                    .map(|n| n.to_string())
                    .unwrap_or_default()
            ))
        })?;
    if let Ok(b) = fspath.cast::<pyo3::types::PyBytes>() {
        #[cfg(unix)]
        {
            use std::os::unix::ffi::OsStrExt;
            return Ok(std::ffi::OsStr::from_bytes(b.as_bytes()).into());
        }
        #[cfg(not(unix))]
        {
            return std::str::from_utf8(b.as_bytes())
                .map(std::path::PathBuf::from)
                .map_err(|_| PatternError::new_err("a bytes path must be UTF-8 here"));
        }
    }
    Ok(text_arg(&fspath, "the pattern file path")?.into())
}

/// Any Python integer argument as i128, saturated beyond that range (`#[pyo3(from_py_with =
/// int_arg)]`): the setting's own check ([`within`]) then names itself, the value and the
/// range, instead of pyo3 raising a bare `OverflowError` for -1 or 2**64 before the call.
/// A value that is not an integer is a [`ParameterError`] too.
pub(crate) fn int_arg(obj: &Bound<'_, PyAny>) -> PyResult<i128> {
    let index = obj.call_method0("__index__").map_err(|_| {
        ParameterError::new_err(format!(
            "an integer setting was given {} ({}): pass an int",
            obj.repr().map(|r| r.to_string()).unwrap_or_default(),
            obj.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    match index.extract::<i128>() {
        Ok(v) => Ok(v),
        Err(_) if index.lt(0)? => Ok(i128::MIN),
        Err(_) => Ok(i128::MAX),
    }
}

/// [`int_arg`] for an optional argument (`None` stays `None`).
pub(crate) fn opt_int_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<i128>> {
    if obj.is_none() {
        Ok(None)
    } else {
        int_arg(obj).map(Some)
    }
}

/// `value` if it lies in `min..=max`, else a [`ParameterError`] naming the setting, the value
/// and the range.
pub(crate) fn within<T>(name: &str, value: i128, min: T, max: T) -> PyResult<T>
where
    T: TryFrom<i128> + Into<i128> + Copy + std::fmt::Display,
{
    if (min.into()..=max.into()).contains(&value) {
        if let Ok(v) = T::try_from(value) {
            return Ok(v);
        }
    }
    let shown = match value {
        i128::MAX => "a number too large to hold".to_string(),
        i128::MIN => "a number too far below zero to hold".to_string(),
        v => v.to_string(),
    };
    Err(ParameterError::new_err(format!(
        "{name} must be an integer from {min} to {max}, not {shown}"
    )))
}

/// A count of at least `min`.
pub(crate) fn count_arg(name: &str, value: i128, min: usize) -> PyResult<usize> {
    within(name, value, min as u64, usize::MAX as u64).map(|v| v as usize)
}

/// A seed: any integer from 0 to 2^64 - 1.
pub(crate) fn seed_arg(value: i128) -> PyResult<u64> {
    within("seed", value, 0u64, u64::MAX)
}

/// A memory budget in bytes, `default` when not given.
pub(crate) fn budget_arg(value: Option<i128>, default: u64) -> PyResult<u64> {
    value.map_or(Ok(default), |v| within("budget_bytes", v, 0u64, u64::MAX))
}

/// A pair of integers (`(width, height)`), each as [`int_arg`].
pub(crate) fn int_pair_arg(obj: &Bound<'_, PyAny>) -> PyResult<(i128, i128)> {
    let (a, b) = obj
        .extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>()
        .map_err(|_| ParameterError::new_err("expected a pair of integers (width, height)"))?;
    Ok((int_arg(&a)?, int_arg(&b)?))
}

/// `obj` as `T`, any value that is not of that shape (a wrong type, a tuple of the wrong
/// length, an integer beyond 64 bits) a [`ParameterError`] that names the setting and the
/// shape it takes, rather than the `TypeError`, `ValueError` or `OverflowError` pyo3 raises
/// on its own.
pub(crate) fn shaped_arg<T>(obj: &Bound<'_, PyAny>, name: &str, shape: &str) -> PyResult<T>
where
    T: for<'a, 'py> FromPyObject<'a, 'py>,
{
    obj.extract::<T>().map_err(|_| {
        let given = obj.repr().map(|r| r.to_string()).unwrap_or_default();
        let given: String = given.chars().take(80).collect();
        ParameterError::new_err(format!("{name} must be {shape}, not {given}"))
    })
}

/// [`shaped_arg`] for an optional setting (`None` stays `None`).
pub(crate) fn opt_shaped_arg<T>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    shape: &str,
) -> PyResult<Option<T>>
where
    T: for<'a, 'py> FromPyObject<'a, 'py>,
{
    if obj.is_none() {
        Ok(None)
    } else {
        shaped_arg(obj, name, shape).map(Some)
    }
}

/// `gauge=(stitches, rows)` per 10 cm, for `#[pyo3(from_py_with)]`.
pub(crate) fn gauge_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<(f32, f32)>> {
    opt_shaped_arg(obj, "gauge", "(stitches, rows) per 10 cm: two numbers")
}

/// `stitch_size=(width, height)` of one stitch, for `#[pyo3(from_py_with)]`.
pub(crate) fn stitch_size_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<(f32, f32)>> {
    opt_shaped_arg(
        obj,
        "stitch_size",
        "(width, height) of a stitch: two numbers",
    )
}
