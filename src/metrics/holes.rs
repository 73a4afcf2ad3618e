//! The holes of a fabric seen square-on (docs/design.md section 7): the connected regions
//! of pixels that no yarn covers in a [`super::cover_mask`], with their areas. A yarn-over
//! leaves a hole clearly larger than the gaps between ordinary stitches; this is what that
//! is measured with.
//!
//! Pixels are joined to the four beside them (not the diagonals: two yarns crossing at a
//! corner close a gap). Regions are labelled in row-major order of their first pixel, so the
//! labels depend on the mask alone.

/// The uncovered regions of a mask.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Holes {
    /// Per pixel (row-major, as the mask), the region it belongs to; [`Holes::COVERED`] for
    /// a covered pixel.
    pub labels: Vec<u32>,
    /// Per region, its area in pixels.
    pub areas: Vec<usize>,
    /// Per region, whether it touches the mask's border (the window cuts it: its area is a
    /// lower bound).
    pub open: Vec<bool>,
}

impl Holes {
    /// The label of a covered pixel.
    pub const COVERED: u32 = u32::MAX;

    /// The region at pixel (`column`, `row`), if it is uncovered.
    pub fn at(&self, resolution: usize, column: usize, row: usize) -> Option<usize> {
        if column >= resolution {
            return None;
        }
        let label = *self.labels.get(row * resolution + column)?;
        (label != Self::COVERED).then_some(label as usize)
    }
}

/// The uncovered regions of `mask` (`resolution` x `resolution`, row-major, true where
/// covered).
///
/// # Panics
/// If `mask` is not `resolution` squared long.
pub fn holes(mask: &[bool], resolution: usize) -> Holes {
    assert_eq!(mask.len(), resolution * resolution, "a square mask");
    let mut labels = vec![Holes::COVERED; mask.len()];
    let (mut areas, mut open) = (Vec::new(), Vec::new());
    let mut stack = Vec::new();
    for start in 0..mask.len() {
        if mask[start] || labels[start] != Holes::COVERED {
            continue;
        }
        let label = areas.len() as u32;
        let (mut area, mut touches) = (0usize, false);
        labels[start] = label;
        stack.push(start);
        while let Some(i) = stack.pop() {
            area += 1;
            let (row, column) = (i / resolution, i % resolution);
            touches |= row == 0 || column == 0 || row + 1 == resolution || column + 1 == resolution;
            let beside = [
                (column > 0).then(|| i - 1),
                (column + 1 < resolution).then(|| i + 1),
                (row > 0).then(|| i - resolution),
                (row + 1 < resolution).then(|| i + resolution),
            ];
            for j in beside.into_iter().flatten() {
                if !mask[j] && labels[j] == Holes::COVERED {
                    labels[j] = label;
                    stack.push(j);
                }
            }
        }
        areas.push(area);
        open.push(touches);
    }
    Holes {
        labels,
        areas,
        open,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_are_found_with_their_areas_and_whether_the_border_cuts_them() {
        // A 6 x 6 mask: a ring of yarn round a 2 x 2 hole, the rest open to the border.
        let mut mask = vec![false; 36];
        for i in 1..5 {
            for j in 1..5 {
                mask[i * 6 + j] = !(2..4).contains(&i) || !(2..4).contains(&j);
            }
        }
        let h = holes(&mask, 6);
        assert_eq!(h.areas.len(), 2);
        let inner = h.at(6, 2, 2).unwrap();
        assert_eq!((h.areas[inner], h.open[inner]), (4, false));
        let outer = h.at(6, 0, 0).unwrap();
        assert_eq!((h.areas[outer], h.open[outer]), (36 - 16, true));
        assert_eq!(h.at(6, 1, 1), None);
        // Diagonal neighbours do not join: a gap closed at a corner stays two.
        let diagonal = [false, true, true, false];
        assert_eq!(holes(&diagonal, 2).areas, vec![1, 1]);
    }
}
