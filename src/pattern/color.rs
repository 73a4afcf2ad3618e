//! Colour patterns: a palette and a chart of palette indices, repeated over the fabric.

use crate::error::{KnitError, Result};

/// A colour pattern. Colours are linear RGB in 0..1 (Blender's scene-linear). Row 0 of the
/// index chart is the bottom row. Invariant: every index is `< palette.len()`, the chart is
/// `width x height` with both at least 1.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorPattern {
    palette: Vec<[f32; 3]>,
    width: usize,
    height: usize,
    indices: Vec<u8>,
}

impl ColorPattern {
    /// A palette and a chart of indices: one line per row, top row first, one character per
    /// stitch: `0`-`9` then `a`-`z` (so up to 36 colours). Spaces are ignored.
    pub fn new(palette: Vec<[f32; 3]>, chart: &str) -> Result<Self> {
        if palette.is_empty() {
            return Err(KnitError::Pattern("the colour palette is empty".into()));
        }
        if palette.len() > 36 {
            return Err(KnitError::Pattern(format!(
                "the colour palette has {} colours; at most 36 can be charted (0-9, a-z)",
                palette.len()
            )));
        }
        if let Some((i, _)) = palette
            .iter()
            .enumerate()
            .find(|(_, c)| c.iter().any(|x| !x.is_finite() || *x < 0.0))
        {
            return Err(KnitError::Pattern(format!(
                "colour {i} of the palette is not a finite, non-negative RGB value"
            )));
        }
        let lines: Vec<&str> = chart
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with('#'))
            .collect();
        if lines.is_empty() {
            return Err(KnitError::Pattern("the colour chart is empty".into()));
        }
        let n = lines.len();
        let mut width = 0;
        let mut indices = Vec::new();
        for (i, line) in lines.iter().enumerate().rev() {
            let row_number = n - i;
            let row: Vec<char> = line.chars().filter(|c| !c.is_whitespace()).collect();
            if width == 0 {
                width = row.len();
            } else if row.len() != width {
                return Err(KnitError::Pattern(format!(
                    "colour chart row {row_number} has {} stitches but row 1 has {width}",
                    row.len()
                )));
            }
            for (col, ch) in row.iter().enumerate() {
                let idx = ch.to_digit(36).filter(|&d| (d as usize) < palette.len());
                match idx {
                    Some(d) => indices.push(d as u8),
                    None => {
                        return Err(KnitError::Pattern(format!(
                            "colour chart row {row_number}, column {}: {ch:?} is not a colour of \
                             the palette (0..{})",
                            col + 1,
                            palette.len() - 1
                        )))
                    }
                }
            }
        }
        Ok(Self {
            palette,
            width,
            height: n,
            indices,
        })
    }

    /// One colour for the whole fabric.
    pub fn solid(color: [f32; 3]) -> Result<Self> {
        Self::new(vec![color], "0")
    }

    /// Horizontal stripes: each palette colour in turn for `rows_each` courses.
    pub fn stripes(palette: Vec<[f32; 3]>, rows_each: usize) -> Result<Self> {
        if rows_each == 0 || rows_each > 10_000 {
            return Err(KnitError::Pattern(format!(
                "stripe height must be 1..10000 rows, not {rows_each}"
            )));
        }
        let n = palette.len().min(36);
        let chart: String = (0..n)
            .rev()
            .flat_map(|i| {
                std::iter::repeat_n(
                    format!("{}\n", char::from_digit(i as u32, 36).unwrap_or('0')),
                    rows_each,
                )
            })
            .collect();
        Self::new(palette, &chart)
    }

    /// The colour of the stitch at (course, wale), the chart repeated in both directions.
    pub fn color(&self, course: usize, wale: usize) -> [f32; 3] {
        self.palette[self.index(course, wale) as usize]
    }

    /// The palette index of stitch (course, wale).
    pub fn index(&self, course: usize, wale: usize) -> u8 {
        self.indices[(course % self.height) * self.width + wale % self.width]
    }

    pub fn palette(&self) -> &[[f32; 3]] {
        &self.palette
    }

    /// Stitches in one repeat of the chart across a row.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Rows in one repeat of the chart.
    pub fn height(&self) -> usize {
        self.height
    }
}
