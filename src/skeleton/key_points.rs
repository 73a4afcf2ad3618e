//! The six key points of a loop in (u,v) ([Zhong 2001], section 2.3, figure 4).

use glam::Vec2;

use crate::lattice::Tile;

/// Number of key points per loop.
pub const KEY_POINTS: usize = 6;

/// Where a loop's key points stand in its tile, as fractions of the tile (the paper's
/// figure 4 gives one such shape, [`LoopShape::PAPER`]). The clearance tuning
/// ([`super::tuning`]) chooses them per pattern and yarn with the normal offsets: a thick
/// yarn needs its leg bottoms further from the leg tops of the loop below than the paper's
/// thin one. Every field keeps the loop's topology: the legs stay inside the tile, the
/// sinker below its bottom edge and the head above its top edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopShape {
    /// How far the sinker dips below the tile, in rows (at most [`crate::lattice::ROW_OVERHANG`]).
    pub sinker_dip: f32,
    /// Where the left leg's bottom stands from the tile's left edge, in stitch widths (the
    /// right leg mirrors it).
    pub leg_bottom: f32,
    /// The same for the left leg's top.
    pub leg_top: f32,
    /// How far the head reaches into the row above, in rows (at most
    /// [`crate::lattice::ROW_OVERHANG`]).
    pub head_reach: f32,
}

impl LoopShape {
    /// Seed 000's figure 4.
    pub const PAPER: LoopShape = LoopShape {
        sinker_dip: 0.35,
        leg_bottom: 0.375,
        leg_top: 0.125,
        head_reach: 0.35,
    };
    /// Number of fields, for a search over them.
    pub const FIELDS: usize = 4;
    /// Bounds of each field (in the order of [`Self::to_array`]).
    pub const BOUNDS: [(f32, f32); Self::FIELDS] =
        [(0.15, 0.35), (0.25, 0.45), (0.0, 0.25), (0.15, 0.35)];

    pub fn to_array(self) -> [f32; Self::FIELDS] {
        [
            self.sinker_dip,
            self.leg_bottom,
            self.leg_top,
            self.head_reach,
        ]
    }

    pub fn from_array(a: [f32; Self::FIELDS]) -> Self {
        Self {
            sinker_dip: a[0],
            leg_bottom: a[1],
            leg_top: a[2],
            head_reach: a[3],
        }
    }
}

impl Default for LoopShape {
    fn default() -> Self {
        Self::PAPER
    }
}

/// The key points k0..k5 of the loop in `tile`, in yarn order, in (u,v), for loop shape `s`
/// (the paper's numbers in brackets):
///
/// - k0 = n3 + dip (n3 - n0): the sinker, dipping below the bottom-left corner (0.35);
/// - k1 = n3 + bottom (n2 - n3): left leg, bottom (0.375);
/// - k2 = n0 + top (n1 - n0): left leg, top (0.125);
/// - k3 = (n0 + n1) / 2 + reach (n4 - n0): the head, reaching into the row above (0.35);
/// - k4 = n0 + (1 - top) (n1 - n0): right leg, top;
/// - k5 = n3 + (1 - bottom) (n2 - n3): right leg, bottom.
pub fn key_points(t: &Tile, s: &LoopShape) -> [Vec2; KEY_POINTS] {
    [
        t.n3 + s.sinker_dip * (t.n3 - t.n0),
        t.n3 + s.leg_bottom * (t.n2 - t.n3),
        t.n0 + s.leg_top * (t.n1 - t.n0),
        0.5 * (t.n0 + t.n1) + s.head_reach * (t.n4 - t.n0),
        t.n0 + (1.0 - s.leg_top) * (t.n1 - t.n0),
        t.n3 + (1.0 - s.leg_bottom) * (t.n2 - t.n3),
    ]
}
