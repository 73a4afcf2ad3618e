//! `Pattern` and `ColorPattern`: stitch patterns (presets, charts, Knitspeak) and colour
//! charts.

use pyo3::prelude::*;

use crate::error::KnitError;
use crate::pattern::{ColorPattern, StitchPattern};

use super::*;

/// A stitch pattern: a chart of knit and purl stitches repeated over the surface.
#[pyclass(name = "Pattern", module = "knitwear", frozen)]
pub struct PyPattern {
    pub(crate) inner: StitchPattern,
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

pub(crate) fn palette_of(palette: Vec<Vec<f32>>) -> PyResult<Vec<[f32; 3]>> {
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
    pub(crate) inner: ColorPattern,
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
