//! Binding of the settings table ([`crate::settings`]): `settings()`, every knit setting as a
//! dict, which the Blender add-on builds its properties from.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::KnitError;
use crate::settings::{Kind, Setting, KNIT_SETTINGS, PLUSH_SETTINGS};

use super::errors::to_py;

/// A number of the table as the setting's Python type; `None` for an unbounded end.
fn value<'py>(py: Python<'py>, kind: Kind, v: f64) -> PyResult<Bound<'py, PyAny>> {
    if !v.is_finite() {
        return Ok(py.None().into_bound(py));
    }
    Ok(match kind {
        Kind::Int => (v as i64).into_pyobject(py)?.into_any(),
        Kind::Float => v.into_pyobject(py)?.into_any(),
        Kind::Bool => (v != 0.0).into_pyobject(py)?.to_owned().into_any(),
    })
}

fn setting_dict<'py>(py: Python<'py>, s: &Setting) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", s.name)?;
    d.set_item("core_keyword", s.core_keyword)?;
    d.set_item("part_of", s.part_of)?;
    d.set_item("property", s.property())?;
    d.set_item("label", s.label)?;
    d.set_item("type", s.kind.python_name())?;
    let default = match s.default {
        Some(v) => value(py, s.kind, v)?,
        None => py.None().into_bound(py),
    };
    d.set_item("default", default)?;
    d.set_item("addon_default", value(py, s.kind, s.addon_value())?)?;
    d.set_item("addon_why", s.addon_why)?;
    d.set_item("min", value(py, s.kind, s.min)?)?;
    d.set_item("max", value(py, s.kind, s.max)?)?;
    d.set_item("unit", s.unit)?;
    d.set_item("doc", s.doc)?;
    Ok(d)
}

/// Every setting of a knit (`kind="knit"`) or a plush (`kind="plush"`), in display order:
/// a dict each with `name`, `core_keyword` (the keyword of `Knit` or `plush`, or None where
/// the setting is part of a tuple keyword, `part_of`), `property` (the Blender property),
/// `label`, `type` ("int", "float", "bool"), `default` (the core's; None where the core works
/// it out), `addon_default` and `addon_why`, `min` and `max` (None: unbounded), `unit` and
/// `doc`.
#[pyfunction]
#[pyo3(signature = (kind="knit"))]
fn settings<'py>(py: Python<'py>, kind: &str) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let table = match kind {
        "knit" => KNIT_SETTINGS,
        "plush" => PLUSH_SETTINGS,
        _ => {
            return Err(to_py(KnitError::Parameter(format!(
                "settings are of a \"knit\" or a \"plush\", not {kind:?}"
            ))))
        }
    };
    table.iter().map(|s| setting_dict(py, s)).collect()
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(settings, m)?)
}
