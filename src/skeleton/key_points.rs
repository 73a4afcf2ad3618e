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
