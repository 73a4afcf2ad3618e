//! Normal offsets (the lambdas of [Zhong 2001], section 2.3): how far each key point stands off
//! the surface, along the surface normal, in scene units.
//!
//! The paper leaves the signs and magnitudes open ("chosen so that the loop is knitted into the
//! skeleton according to the stitch pattern and there is no intersection"). Our model gives
//! each key point a sign from the stitch whose crossing it takes part in, and one magnitude per
//! kind of key point, tuned for clearance by [`super::tuning`]:
//!
//! - leg bottoms k1, k5 pass the head of the loop below on the side of their own stitch
//!   (front for knit, back for purl): `+a * side(self)`;
//! - the head k3 passes the legs of the loop above on the other side: `-c * side(above)`;
//! - leg tops k2, k4 pass the sinker of the row above on the side of the stitch above:
//!   `+b * side(above)`;
//! - the sinker k0 passes the leg tops of the row below on the other side of its own stitch,
//!   and halfway between where the stitch to its left differs (a knit/purl boundary, where the
//!   yarn goes from front to back): `-e * (side(self) + side(left)) / 2`.
//!
//! With every magnitude at most one and a half yarn diameters the fabric is at most four
//! diameters thick.

use std::sync::Arc;

use super::relief::{ContactRelief, EdgeRelief};
use super::{LoopShape, KEY_POINTS};
use crate::pattern::Stitch;

/// Signed normal-offset coefficients of the six key points, in scene units, each in
/// `[-1.5, 1.5]` diameters. `lambda_i = x[i] * sign_i`, where `sign_i` is the crossing side of
/// key point `i` given by the model above (so for knit-only fabric `x` is the lambdas
/// themselves, and a purl stitch mirrors them).
#[derive(Debug, Clone, PartialEq)]
pub struct NormalOffsets {
    /// k0..k5, then the sinker's extra offset where the stitch to its left is of the other
    /// kind (a knit/purl boundary, where the yarn changes sides).
    pub x: [f32; COEFFICIENTS],
    /// The yarn diameter the coefficients are measured against (1 while tuning, in diameters;
    /// scene units once [`scaled`](Self::scaled)). Crossed loops, stacked decreases and floats
    /// stand off by fractions of it (see [`super::stitch_shape`]).
    pub diameter: f32,
    /// The shapes of the stitches beyond knit and purl, in diameters (see [`Shape`]).
    pub shape: [f32; SHAPE_COEFFICIENTS],
    /// Per-stitch corrections where yarns would touch ([`super::contact`]), in diameters;
    /// `None`: none needed.
    pub relief: Option<Arc<ContactRelief>>,
    /// The wales a piece knits straight because its edge cuts a crossing or a decrease there
    /// ([`super::stitch_shape::wale_knits_whole`]), and their offsets. `None`: the piece has
    /// no such wale (and a tuning patch never has).
    pub straight: Option<Arc<StraightWales>>,
    /// Where the key points stand in their tiles, tuned with the offsets.
    pub loop_shape: LoopShape,
}

/// The wales of a piece knitted straight, and the offsets they take: the pattern's
/// coefficients, with a relief made for the pattern with every loop straight
/// ([`crate::pattern::StitchPattern::straightened`], [`super::tuning::straight_offsets`]).
/// The pattern's own relief is made for loops that lean there.
#[derive(Debug, Clone, PartialEq)]
pub struct StraightWales {
    /// Their offsets, in the same units as the offsets holding them.
    pub offsets: NormalOffsets,
    /// Per wale of the piece: whether it is knitted straight.
    pub wales: Vec<bool>,
    /// Corrections made for the piece itself near those wales, where wales knitted straight
    /// meet wales knitted as the pattern says ([`super::contact::relieve_edges`]): they
    /// replace both reliefs there. `None`: not made (a piece in the round).
    pub edge: Option<Arc<EdgeRelief>>,
}

/// The coefficients of [`NormalOffsets::shape`], each in yarn diameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(usize)]
pub enum Shape {
    /// Normal offset of a crossing or gathered loop in front at its leg bottoms (k1, k5) (a
    /// loop behind stays put there, held by the head below it).
    PushBottom,
    /// The same at its leg tops (k2, k4).
    PushTop,
    /// The same at its head (k3).
    PushHead,
    /// Half the normal separation of the two legs of a leaning loop at their bottoms (the left
    /// leg in front): a loop stretched across columns would otherwise lie on itself.
    SplitBottom,
    /// The same at their tops.
    SplitTop,
    /// Half the normal separation of the crossed legs of a twisted stitch (`k tbl`).
    Twist,
    /// How far the float past a slipped stitch stands off the fabric.
    Float,
}

/// Number of [`Shape`] coefficients.
pub const SHAPE_COEFFICIENTS: usize = 7;

/// Where the tuning of the shape coefficients starts.
pub const DEFAULT_SHAPE: [f32; SHAPE_COEFFICIENTS] = [0.5, 0.5, 0.5, 0.2, 0.2, 0.75, 1.5];

/// Number of tuned coefficients.
pub const COEFFICIENTS: usize = 7;

impl NormalOffsets {
    /// The model's naive choice: every key point `x` off the surface on its crossing side.
    pub fn uniform(x: f32) -> Self {
        Self {
            x: [x; COEFFICIENTS],
            diameter: 1.0,
            shape: DEFAULT_SHAPE,
            relief: None,
            straight: None,
            loop_shape: LoopShape::PAPER,
        }
    }

    /// These offsets with contact relief.
    pub fn with_relief(self, relief: ContactRelief) -> Self {
        Self {
            relief: Some(Arc::new(relief)),
            ..self
        }
    }

    /// These offsets, with `offsets` for the wales a piece knits straight (`wales[w]`).
    pub fn with_straight(self, offsets: NormalOffsets, wales: Vec<bool>) -> Self {
        Self {
            straight: Some(Arc::new(StraightWales {
                offsets,
                wales,
                edge: None,
            })),
            ..self
        }
    }

    /// These offsets with `edge` corrections near the wales knitted straight (a no-op
    /// without [`Self::straight`]).
    pub fn with_edge_relief(self, edge: EdgeRelief) -> Self {
        let straight = self.straight.as_ref().map(|s| {
            Arc::new(StraightWales {
                edge: Some(Arc::new(edge)),
                ..(**s).clone()
            })
        });
        Self { straight, ..self }
    }

    /// The offsets of stitch (`course`, `wale`) of a piece and its relief corrections (in
    /// diameters): near wales knitted straight, the piece's own edge corrections; in such a
    /// wale, the straightened pattern's offsets and relief; elsewhere these, relieved where
    /// `whole_group` (the loop's whole crossing is on the piece).
    pub fn for_stitch(
        &self,
        course: usize,
        wale: usize,
        whole_group: bool,
    ) -> (&NormalOffsets, Option<[f32; KEY_POINTS]>) {
        if let Some(s) = &self.straight {
            let straight = s.wales.get(wale).copied().unwrap_or(false);
            let base = if straight { &s.offsets } else { self };
            if let Some(r) = s.edge.as_ref().and_then(|e| e.at(course, wale)) {
                return (base, Some(r));
            }
            if straight {
                return (base, base.relief.as_ref().map(|r| r.at(course, wale)));
            }
        }
        let relief = self.relief.as_ref().filter(|_| whole_group);
        (self, relief.map(|r| r.at(course, wale)))
    }

    /// Rescaled from diameters to scene units (`k`: the yarn diameter).
    pub fn scaled(self, k: f32) -> Self {
        Self {
            x: self.x.map(|v| v * k),
            diameter: self.diameter * k,
            shape: self.shape,
            loop_shape: self.loop_shape,
            relief: self.relief,
            straight: self.straight.map(|s| {
                Arc::new(StraightWales {
                    offsets: s.offsets.clone().scaled(k),
                    wales: s.wales.clone(),
                    edge: s.edge.clone(),
                })
            }),
        }
    }

    /// A shape coefficient in scene units.
    pub fn shape(&self, which: Shape) -> f32 {
        self.shape[which as usize] * self.diameter
    }

    /// The signed offsets lambda_0..lambda_5 of a loop, given its stitch, the stitch above it
    /// (same wale, next course) and the stitch to its left (same course, previous wale).
    pub fn lambdas(&self, this: Stitch, above: Stitch, left: Stitch) -> [f32; 6] {
        let s = this.side();
        let up = above.side();
        let sinker_side = -0.5 * (s + left.side());
        let boundary_side = 0.5 * (s - left.side());
        let sign = [sinker_side, s, up, -up, up, s];
        let mut l: [f32; 6] = std::array::from_fn(|i| self.x[i] * sign[i]);
        l[0] += self.x[6] * boundary_side;
        l
    }
}
