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

use super::edges::Edge;
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

/// The samples-per-loop multiple of a cast-on. Its loops wrap round the legs of the first
/// course, from two diameters behind the fabric to two in front within a quarter of a
/// stitch; at one sample in sixteen a chord there ran two diameters through the depth, and
/// the edge's clearance pass ([`super::edge_clearance`]), which moves samples, could not bend
/// it round a sinker it passed (horseshoe cable's cast-on on a 3 cm cylinder came within 0.03
/// diameters of the second course; 0.065 at twice the density).
///
/// The bind-off keeps the fabric's sampling: at twice the density its spline showed a fold
/// at horseshoe cable's purl columns (the yarn from a loop's left leg top to its head came
/// within 0.012 diameters of itself), which its chords at the fabric's density cut across.
pub const CAST_ON_DENSITY: usize = 2;

/// Sets each piece's [`YarnPiece::density`] from the loops it holds that lean furthest, and
/// the cast-on's to [`CAST_ON_DENSITY`]. Bobbles, floats and the bind-off keep 1.
pub fn sampling_density(pieces: &mut [YarnPiece], lattice: &Lattice, pattern: &StitchPattern) {
    let wales = lattice.wales;
    for piece in pieces {
        if piece.edge == Some(Edge::CastOn) {
            piece.density = CAST_ON_DENSITY;
            continue;
        }
        if piece.bobble || piece.float_color.is_some() {
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
