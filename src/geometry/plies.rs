//! Plies: the yarn's cross-section as `p` strands twisted round each other.
//!
//! Real yarn is several plies twisted together, and the twist shows as helical grooves along
//! the strand. The bundle keeps its one ring of points per sample (so its topology, budget,
//! detail levels and culling are those of a single tube); each ring point is moved in or out
//! to the outline of `p` circles packed round the centreline, and that outline turns along
//! the yarn. A point's radius, as a fraction of the yarn radius, is
//!
//! `1 - GROOVE_DEPTH * (1 - outline(angle - twist))`,
//!
//! where `outline` is the distance from the centre to the far side of the nearest ply (the
//! plies touch each other and the yarn's radius: ply radius `s / (1 + s)` with
//! `s = sin(pi / p)`), and the twist turns `TURNS_PER_LOOP` times per stitch loop of yarn,
//! counted in the piece's full-density samples so that a span of a coarser level, a
//! positions-only build of an animated frame and a whole build all twist alike.
//!
//! One ply (the default) is the plain tube, untouched to the bit.

use std::f32::consts::{PI, TAU};

/// Turns of the plies per stitch loop of yarn. A loop is about 16 yarn diameters long at the
/// default yarn, so a turn every 4 diameters: a helix angle of about 25 degrees at the plies'
/// centres, as in a worsted yarn.
pub const TURNS_PER_LOOP: f32 = 4.0;

/// How much of the space between the plies' outlines shows as a groove (1: the full outline
/// of touching circles, which for two plies pinches the strand to a line; 0: a round tube).
/// Fibres fill part of it in real yarn.
pub const GROOVE_DEPTH: f32 = 0.5;

/// The most plies a yarn has.
pub const MAX_PLIES: usize = crate::settings::PLIES.max as usize;

/// The twist of the plies at full-density sample `sample` of a piece sampled at
/// `samples_per_loop` per stitch, radians.
pub fn twist(sample: usize, samples_per_loop: usize) -> f32 {
    let turns = TURNS_PER_LOOP * sample as f32 / samples_per_loop.max(1) as f32;
    TAU * turns.fract()
}

/// How fast the plies turn round the yarn where `samples` full-density samples span
/// `length` scene units of centreline, radians per scene unit (0 where the span has no
/// length). A point at radius `rho` from the centreline follows a helix whose slope round the
/// yarn, per unit along it, is `rho` times this: the fibres' slant (see
/// [`crate::geometry::build_bundle`]'s tangents).
pub fn twist_rate(samples: usize, length: f32, samples_per_loop: usize) -> f32 {
    if length <= 0.0 || !length.is_finite() {
        return 0.0;
    }
    TAU * TURNS_PER_LOOP * samples as f32 / samples_per_loop.max(1) as f32 / length
}

/// The radius, as a fraction of the yarn radius, of a `plies`-ply yarn in the direction
/// `angle` (radians round the ring from the ring frame's first axis) where the plies have
/// turned by `twist`. Exactly 1 for one ply.
pub fn ply_radius(plies: usize, angle: f32, twist: f32) -> f32 {
    if plies <= 1 {
        return 1.0;
    }
    let p = plies as f32;
    let s = crate::portable_math::sin_cos(PI / p).0;
    let (ply, centre) = (s / (1.0 + s), 1.0 / (1.0 + s));
    // The angle from the nearest ply's centre, in [-pi/p, pi/p].
    let sector = TAU / p;
    let a = (angle - twist).rem_euclid(sector);
    let delta = if a > 0.5 * sector { a - sector } else { a };
    let (sin_d, cos_d) = crate::portable_math::sin_cos(delta);
    let across = centre * sin_d;
    let outline = centre * cos_d + (ply * ply - across * across).max(0.0).sqrt();
    1.0 - GROOVE_DEPTH * (1.0 - outline)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_ply_is_the_round_tube() {
        for k in 0..12 {
            assert_eq!(ply_radius(1, k as f32, 0.3 * k as f32), 1.0);
        }
    }

    #[test]
    fn plies_reach_the_yarn_radius_over_their_centres_and_groove_between() {
        for p in 2..=MAX_PLIES {
            let sector = TAU / p as f32;
            for k in 0..p {
                let over = ply_radius(p, k as f32 * sector + 0.7, 0.7);
                assert!((over - 1.0).abs() < 1e-5, "{p} plies: {over}");
                let groove = ply_radius(p, (k as f32 + 0.5) * sector + 0.7, 0.7);
                assert!(
                    (1.0 - GROOVE_DEPTH..0.99).contains(&groove),
                    "{p}: {groove}"
                );
            }
        }
    }

    #[test]
    fn the_twist_turns_along_the_yarn_and_repeats_every_turn() {
        let spl = 16;
        assert_eq!(twist(0, spl), 0.0);
        // A quarter of a loop is one turn at 4 turns a loop.
        assert!(twist(spl / 4, spl).abs() < 1e-6);
        assert!((twist(spl / 8, spl) - PI).abs() < 1e-5);
    }
}
