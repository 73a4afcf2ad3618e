//! The six key points of a loop in (u,v) (seed 000, section 2.3, figure 4).

use glam::Vec2;

use crate::lattice::Tile;

/// Number of key points per loop.
pub const KEY_POINTS: usize = 6;

/// The key points k0..k5 of the loop in `tile`, in yarn order, in (u,v):
///
/// - k0 = n3 + 0.35 (n3 - n0): the sinker, dipping below the bottom-left corner;
/// - k1 = n3 + 0.375 (n2 - n3): left leg, bottom;
/// - k2 = n0 + 0.125 (n1 - n0): left leg, top;
/// - k3 = (n0 + n1) / 2 + 0.35 (n4 - n0): the head, reaching into the row above;
/// - k4 = n0 + 0.875 (n1 - n0): right leg, top;
/// - k5 = n3 + 0.625 (n2 - n3): right leg, bottom.
pub fn key_points(t: &Tile) -> [Vec2; KEY_POINTS] {
    [
        t.n3 + 0.35 * (t.n3 - t.n0),
        t.n3 + 0.375 * (t.n2 - t.n3),
        t.n0 + 0.125 * (t.n1 - t.n0),
        0.5 * (t.n0 + t.n1) + 0.35 * (t.n4 - t.n0),
        t.n0 + 0.875 * (t.n1 - t.n0),
        t.n3 + 0.625 * (t.n2 - t.n3),
    ]
}

/// The sinker k0 of a loop on a vertical knit/purl boundary (its left neighbour is of the other
/// kind, the stitch below of its own): it does not dip, `k0 = n3`.
///
/// Between a knit and a purl column (a rib) the yarn goes straight from the front of the fabric to
/// the back between the two needles instead of forming a sinker loop. With the paper's dip
/// of 0.35 rows, the sinker reaches down to where both legs below are crossing the surface
/// and must pass in front of one and behind the other at the same height: no choice of
/// normal offsets then clears 0.8 yarn diameters in a 1x1 rib, where the straight crossing
/// clears more than one. Where the stitch below is of the other kind too (seed stitch), the
/// legs below do not cross the surface there and the paper's dip clears best.
pub fn boundary_sinker(t: &Tile) -> Vec2 {
    t.n3
}
