//! How densely a piece of yarn is sampled: more samples per loop on courses whose loops lean
//! across columns.
//!
//! A loop leaning `L` columns (a cable's crossed stitch) is about `1 + L / 2` times as long
//! as a straight one, and its legs run nearly along the course. At the knit's samples per
//! loop the chords between its samples grow as long as several yarn diameters; on a curved
//! surface a chord cuts inside the yarn's true path by its sagitta (0.2 diameters for a
//! 6.6-diameter chord round a 3 cm sleeve), enough to bring the legs of a cable closer than a
//! diameter where the spline itself clears (measured: a horseshoe cable on a 3 cm cylinder,
//! 0.89 diameters at 16 samples per loop, 0.96 at 32). Pieces holding leaning loops are
//! therefore sampled [`density`] times as densely, so every loop's chords stay about as long
//! as a straight loop's. Whole pieces, not single stitches, so that a piece keeps one
//! uniform parameter step and the buffers' layout stays a closed form of the piece.

use super::stitch_shape::landing;
use super::YarnPiece;
use crate::lattice::Lattice;
use crate::pattern::StitchPattern;

/// Most samples-per-loop multiple a piece gets (a loop leaning six columns).
pub const MAX_DENSITY: usize = 4;

/// The samples-per-loop multiple for loops leaning at most `lean` columns.
pub fn density(lean: usize) -> usize {
    (1 + lean / 2).min(MAX_DENSITY)
}

/// Sets each piece's [`YarnPiece::density`] from the loops it holds that lean furthest.
/// Bobbles, floats and edges keep 1.
pub fn sampling_density(pieces: &mut [YarnPiece], lattice: &Lattice, pattern: &StitchPattern) {
    let wales = lattice.wales;
    for piece in pieces {
        if piece.bobble || piece.float_color.is_some() || piece.edge.is_some() {
            continue;
        }
        let lean = (0..piece.stitches)
            .map(|j| {
                let w = (piece.first_wale + j) % wales;
                landing(lattice, pattern, piece.course, w).abs_diff(w as isize)
            })
            .max()
            .unwrap_or(0);
        piece.density = density(lean);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn longer_loops_get_more_samples() {
        assert_eq!(density(0), 1);
        assert_eq!(density(1), 1);
        assert_eq!(density(2), 2);
        assert_eq!(density(3), 2);
        assert_eq!(density(6), 4);
        assert_eq!(density(100), MAX_DENSITY);
    }
}
