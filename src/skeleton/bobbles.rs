//! Bobbles: the knot of extra loops a bobble (`MB`) works into one stitch, standing off the
//! front of the fabric.
//!
//! Making a bobble works several loops into one stitch, turns and works them back and forth a
//! few times, then gathers them: a small ball of yarn on the front. The stitch itself is drawn
//! as a knit stitch standing a little proud ([`super::stitch_shape`]); the ball is an extra
//! piece of yarn per bobble, a helix of [`TURNS`] turns round the stitch's centre, each turn a
//! yarn diameter further out and a little narrower (a dome), so the turns clear each other and
//! the ball reads from the front as a ring of yarn and from the side as a bump.

use glam::Vec3;

use super::stitch_shape::tile_at;
use super::{YarnPiece, KEY_POINTS};
use crate::lattice::Lattice;
use crate::pattern::{Form, StitchPattern};

/// Turns of yarn in a bobble's ball.
pub const TURNS: usize = 4;
/// Radius of the ball's first turn, as a fraction of the stitch width; the turns further out
/// close in to half that, a dome.
pub const RADIUS: f32 = 0.6;
/// How far in front of the surface the first turn runs, in yarn diameters; each further turn is
/// one diameter further out.
pub const FIRST_TURN: f32 = 2.25;

/// One open piece per built bobble stitch of the fabric, in course then wale order.
pub fn bobble_pieces(lattice: &Lattice, built: &[bool], pattern: &StitchPattern) -> Vec<YarnPiece> {
    let wales = lattice.wales;
    let mut pieces = Vec::new();
    for course in 0..lattice.courses {
        for wale in 0..wales {
            if built[course * wales + wale] && pattern.stitch(course, wale).form == Form::Bobble {
                pieces.push(YarnPiece {
                    course,
                    first_wale: wale,
                    // Six key points a turn, counted as one "stitch" each for sampling.
                    stitches: TURNS,
                    closed: false,
                    float_color: None,
                    float_layer: 0,
                    bobble: true,
                    density: 1,
                    edge: None,
                });
            }
        }
    }
    pieces
}

/// Clearance of the ball's first turn in front of the yarn under it, in yarn diameters.
pub const OVER_STITCH: f32 = 1.25;

/// Key points of a bobble's ball in (u, v, lambda): [`TURNS`] turns of six points. The first
/// turn runs [`FIRST_TURN`] diameters in front of the surface, or [`OVER_STITCH`] in front of
/// `under` (the largest offset of the yarn under the ball, scene units) where that is
/// further out.
pub fn bobble_key_points(
    lattice: &Lattice,
    piece: &YarnPiece,
    diameter: f32,
    under: f32,
) -> Vec<Vec3> {
    let first = (FIRST_TURN * diameter).max(under + OVER_STITCH * diameter);
    let t = tile_at(lattice, piece.course, piece.first_wale as isize);
    let across = t.n2 - t.n3;
    let up = t.n0 - t.n3;
    // Round in the fabric: a row is about 0.7 of a stitch width at the gauges knitters use.
    let (rx, ry) = (RADIUS, RADIUS / 0.7);
    let centre = t.n3 + 0.5 * across + 0.6 * up;
    (0..TURNS * KEY_POINTS)
        .map(|j| {
            let a = std::f32::consts::TAU * j as f32 / KEY_POINTS as f32;
            let shrink = 1.0 - 0.5 * j as f32 / (TURNS * KEY_POINTS) as f32;
            let p = centre + shrink * (rx * a.cos() * across + ry * a.sin() * up);
            let lambda = first + j as f32 / KEY_POINTS as f32 * diameter;
            Vec3::new(p.x, p.y, lambda)
        })
        .collect()
}
