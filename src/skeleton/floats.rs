//! Stranded colourwork (Fair Isle): the floats at the back.
//!
//! In stranded knitting every colour of a row travels along the whole row; a colour that is not
//! knitted for a few stitches is carried loosely behind them, a float. Our skeleton makes one
//! yarn per course and colours each stitch, which is what the front shows; the floats are
//! extra pieces of yarn behind the fabric, one per run of stitches a colour skips between two
//! stitches knitted in it. They run straight along the middle of the row, [`FLOAT_BACK`] yarn
//! diameters behind the surface, clear of the back of the fabric (the offsets keep it within a
//! diameter of the surface).
//!
//! Only a palette colour chart makes floats (an image gives every stitch its own colour).

use glam::Vec3;

use super::stitch_shape::tile_at;
use super::{YarnPiece, KEY_POINTS};
use crate::lattice::Lattice;
use crate::pattern::ColorPattern;

/// How far behind the surface a float runs, in yarn diameters.
pub const FLOAT_BACK: f32 = 2.25;
/// How much further back each further colour of a row floats, in diameters: floats of
/// different colours meet end to end where one colour takes over from another, so each
/// colour keeps its own layer (as the strands do in the hand, one above the other).
pub const FLOAT_STEP: f32 = 1.0;

/// The floats of every course of a fabric whose built stitches are `built` (row-major), in
/// course order, then colour order, then left to right. Each is an open piece over the
/// stitches it skips, `float_color` its palette index.
pub fn float_pieces(lattice: &Lattice, built: &[bool], colors: &ColorPattern) -> Vec<YarnPiece> {
    let wales = lattice.wales;
    let mut pieces = Vec::new();
    for course in 0..lattice.courses {
        let index = |w: usize| colors.index(course, w);
        let row = &built[course * wales..(course + 1) * wales];
        let mut used: Vec<u8> = (0..wales).filter(|&w| row[w]).map(index).collect();
        used.sort_unstable();
        used.dedup();
        if used.len() < 2 {
            continue;
        }
        for (rank, &c) in used.iter().enumerate() {
            let mut last: Option<usize> = None;
            for (w, &is_built) in row.iter().enumerate() {
                if !is_built {
                    last = None;
                    continue;
                }
                if index(w) != c {
                    continue;
                }
                if let Some(l) = last {
                    if w > l + 1 {
                        pieces.push(YarnPiece {
                            course,
                            first_wale: l + 1,
                            stitches: w - l - 1,
                            closed: false,
                            float_color: Some(c),
                            float_layer: rank as u8,
                            bobble: false,
                            density: 1,
                            edge: None,
                        });
                    }
                }
                last = Some(w);
            }
        }
    }
    pieces
}

/// Key points of a float in (u, v, lambda): six per stitch it skips, evenly along the middle
/// of the row, `FLOAT_BACK` diameters behind the surface.
pub fn float_key_points(lattice: &Lattice, piece: &YarnPiece, diameter: f32) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(piece.stitches * KEY_POINTS);
    for j in 0..piece.stitches {
        let t = tile_at(lattice, piece.course, (piece.first_wale + j) as isize);
        for k in 0..KEY_POINTS {
            let x = (k as f32 + 0.5) / KEY_POINTS as f32;
            let p = t.n3 + x * (t.n2 - t.n3) + 0.5 * (t.n0 - t.n3);
            let depth = FLOAT_BACK + FLOAT_STEP * f32::from(piece.float_layer);
            out.push(Vec3::new(p.x, p.y, -depth * diameter));
        }
    }
    out
}
