//! Text charts of knit and purl stitches.

use super::{Stitch, StitchPattern};
use crate::error::{KnitError, Result};

/// Symbols for a knit stitch (what shows on the front: a V).
pub const KNIT_SYMBOLS: &[char] = &['k', 'K', '|', 'v', 'V'];
/// Symbols for a purl stitch (a bump on the front; charts draw it as a dot or a dash).
pub const PURL_SYMBOLS: &[char] = &['p', 'P', '-', '.', '•', '·', 'o', 'O'];

/// Parses a chart: one line per row, **top row first** as the chart is drawn on paper (the
/// last line is row 1, the first row knitted), one symbol per stitch as it shows on the right
/// side, columns left to right. Spaces and tabs between symbols are ignored, as are empty lines
/// and lines starting with `#`. Knit: `k K | v V`; purl: `p P - . • · o O`.
///
/// Errors name the row (counted from the bottom, as knitters number rows), the column and the
/// symbol.
pub fn parse_chart(text: &str) -> Result<StitchPattern> {
    let lines: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect();
    if lines.is_empty() {
        return Err(KnitError::Pattern(
            "the chart is empty: write one line per row, e.g. \"kkpp\"".into(),
        ));
    }
    let n = lines.len();
    let mut rows = Vec::with_capacity(n);
    for (i, line) in lines.iter().enumerate().rev() {
        let row_number = n - i;
        let mut row = Vec::with_capacity(line.len());
        for (col, ch) in line
            .chars()
            .filter(|c| !matches!(c, ' ' | '\t'))
            .enumerate()
        {
            let stitch = if KNIT_SYMBOLS.contains(&ch) {
                Stitch::KNIT
            } else if PURL_SYMBOLS.contains(&ch) {
                Stitch::PURL
            } else {
                return Err(KnitError::Pattern(format!(
                    "row {row_number}, column {}: unknown symbol {ch:?}; use k (knit) or p (purl)",
                    col + 1
                )));
            };
            row.push(stitch);
        }
        rows.push(row);
    }
    StitchPattern::from_rows("custom", rows)
}
