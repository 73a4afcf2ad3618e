//! What a contact relief makes ([`super::contact`]): corrections to the key points' normal
//! offsets, in yarn diameters, per pattern cell ([`ContactRelief`]) or per pattern row and
//! wale of a piece ([`EdgeRelief`]). Data only, so that the offsets that carry a relief
//! ([`super::NormalOffsets`]) need not know how it is made.

use super::KEY_POINTS;

/// Normal-offset corrections per pattern cell and key point, in yarn diameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactRelief {
    pub(super) height: usize,
    pub(super) width: usize,
    /// Row-major, `height * width` cells.
    pub(super) lambdas: Vec<[f32; KEY_POINTS]>,
}

impl ContactRelief {
    /// The corrections of stitch (`course`, `wale`) of a fabric knitted with the pattern.
    pub fn at(&self, course: usize, wale: usize) -> [f32; KEY_POINTS] {
        self.lambdas[(course % self.height) * self.width + wale % self.width]
    }

    /// The corrections of the chart started `shift` columns further right
    /// ([`crate::pattern::StitchPattern::columns_rotated`]): column `c` of the result is
    /// column `(c + shift) % width` of this one.
    pub fn columns_rotated(&self, shift: usize) -> Self {
        let w = self.width;
        let lambdas = (0..self.height * w)
            .map(|i| self.lambdas[(i / w) * w + (i % w + shift) % w])
            .collect();
        Self {
            height: self.height,
            width: w,
            lambdas,
        }
    }

    /// The largest correction, in diameters.
    pub fn largest(&self) -> f32 {
        self.lambdas
            .iter()
            .flatten()
            .fold(0.0f32, |m, x| m.max(x.abs()))
    }
}

/// Corrections made for one piece of fabric near the wales it knits straight (where an edge
/// cuts a crossing or a decrease: [`super::StraightWales`]), per pattern row and wale, in
/// yarn diameters: there, wales knitted straight meet wales knitted as the pattern says,
/// and neither the pattern's relief nor the straightened pattern's was made for that.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeRelief {
    pub(super) rows: usize,
    /// Per wale of the piece: its first cell in `lambdas`, or `NO_CELL`.
    pub(super) first_cell: Vec<u32>,
    /// `rows` cells per wale that has any.
    pub(super) lambdas: Vec<[f32; KEY_POINTS]>,
}

/// `first_cell` of a wale without corrections.
pub(super) const NO_CELL: u32 = u32::MAX;

impl EdgeRelief {
    /// The corrections of stitch (`course`, `wale`), if made for its wale.
    pub fn at(&self, course: usize, wale: usize) -> Option<[f32; KEY_POINTS]> {
        let first = *self.first_cell.get(wale)?;
        (first != NO_CELL).then(|| self.lambdas[first as usize + course % self.rows])
    }
}
