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

/// Largest pattern file read: a 256 x 1024 chart with its legend is about 270 KB.
const MAX_PATTERN_FILE_BYTES: u64 = 4 << 20;

/// The text of a pattern file, refusing a directory, a named pipe, a device that never ends
/// (`/dev/zero`) or a file too large to be a pattern before reading it all.
fn read_pattern_file(path: &std::path::Path) -> Result<String, KnitError> {
    use std::io::Read;
    let cannot = |why: String| {
        KnitError::Pattern(format!(
            "cannot read pattern file {}: {why}",
            path.display()
        ))
    };
    // Looked at before opening: opening a named pipe for reading waits for a writer, which
    // may never come.
    let kind = std::fs::metadata(path)
        .map_err(|e| cannot(e.to_string()))?
        .file_type();
    if kind.is_dir() {
        return Err(cannot("it is a folder, not a file".into()));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() || kind.is_socket() {
            return Err(cannot(
                "it is a pipe or a socket, not a file: save the pattern to a file".into(),
            ));
        }
    }
    let file = std::fs::File::open(path).map_err(|e| cannot(e.to_string()))?;
    let mut bytes = Vec::new();
    file.take(MAX_PATTERN_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| cannot(e.to_string()))?;
    if bytes.len() as u64 > MAX_PATTERN_FILE_BYTES {
        return Err(cannot(format!(
            "it is larger than the {} MiB a pattern file may be",
            MAX_PATTERN_FILE_BYTES >> 20
        )));
    }
    String::from_utf8(bytes).map_err(|e| {
        cannot(format!(
            "it is not UTF-8 text (byte {} is not valid): save it as UTF-8",
            e.utf8_error().valid_up_to()
        ))
    })
}

/// A pattern parsed without the GIL, a panic caught as every core call's is.
fn parsed(
    py: Python<'_>,
    parse: impl FnOnce() -> Result<StitchPattern, KnitError> + Send,
) -> PyResult<PyPattern> {
    guarded(py, parse).map(|inner| PyPattern { inner })
}

#[pymethods]
impl PyPattern {
    /// A named preset; see `Pattern.presets()`.
    #[staticmethod]
    fn preset(name: &Bound<'_, PyAny>) -> PyResult<Self> {
        StitchPattern::preset(&text_arg(name, "the preset name")?)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
    /// A text chart: one line per row, top row first; k (knit) and p (purl) as seen on the front.
    #[staticmethod]
    fn from_chart(py: Python<'_>, text: &Bound<'_, PyAny>) -> PyResult<Self> {
        let text = text_arg(text, "the chart text")?;
        parsed(py, move || StitchPattern::from_chart(&text))
    }
    /// Knitspeak row instructions ("Row 1 (RS): *k2, 2/2 RC, p2; rep from *."): cables,
    /// decreases, yarn-overs, slips, bobbles, repeats (see docs/stitches.md).
    #[staticmethod]
    fn from_knitspeak(py: Python<'_>, text: &Bound<'_, PyAny>) -> PyResult<Self> {
        let text = text_arg(text, "the Knitspeak text")?;
        parsed(py, move || StitchPattern::from_knitspeak(&text))
    }
    /// Knitspeak or a chart, told apart by content (Knitspeak starts with a row header).
    #[staticmethod]
    fn from_text(py: Python<'_>, text: &Bound<'_, PyAny>) -> PyResult<Self> {
        let text = text_arg(text, "the pattern text")?;
        parsed(py, move || StitchPattern::from_text(&text))
    }
    /// A pattern file (UTF-8 text, at most [`MAX_PATTERN_FILE_BYTES`]): Knitspeak or a chart,
    /// told apart by content. The path may be a str, bytes or os.PathLike. A file that cannot
    /// be read is a PatternError naming the path.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<Self> {
        let path = path_arg(path)?;
        parsed(py, move || {
            let text = read_pattern_file(&path)?;
            StitchPattern::from_text(&text).map_err(|e| match e {
                KnitError::Pattern(m) => KnitError::Pattern(format!("{}: {m}", path.display())),
                other => other,
            })
        })
    }
    /// Per chart row, bottom row first: (loops of the row below it works, stitches it makes).
    fn stitch_counts(&self) -> Vec<(usize, usize)> {
        self.inner.stitch_counts()
    }
    /// Whether `text` reads as Knitspeak (starts with a row header) rather than a chart.
    #[staticmethod]
    fn looks_like_knitspeak(text: &Bound<'_, PyAny>) -> PyResult<bool> {
        Ok(crate::pattern::looks_like_knitspeak(&text_arg(
            text,
            "the pattern text",
        )?))
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
    #[pyo3(signature = (palette, chart=None))]
    fn new(palette: Vec<Vec<f32>>, chart: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        // No chart: one colour, the palette's first.
        let chart = match chart {
            Some(c) => text_arg(c, "the colour chart")?,
            None => "0".to_owned(),
        };
        ColorPattern::new(palette_of(palette)?, &chart)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
    /// A named colour chart (see `ColorPattern.presets()`) in the given palette.
    #[staticmethod]
    fn preset(name: &Bound<'_, PyAny>, palette: Vec<Vec<f32>>) -> PyResult<Self> {
        crate::pattern::color_preset(
            &text_arg(name, "the colour preset name")?,
            palette_of(palette)?,
        )
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
    fn stripes(
        palette: Vec<Vec<f32>>,
        #[pyo3(from_py_with = int_arg)] rows_each: i128,
    ) -> PyResult<Self> {
        ColorPattern::stripes(palette_of(palette)?, count_arg("rows_each", rows_each, 0)?)
            .map(|inner| Self { inner })
            .map_err(to_py)
    }
}
