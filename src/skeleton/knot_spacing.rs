//! Where the yarn's spline takes its knots from its chords ([`super::CardinalSpline::spacing`]).
//!
//! A loop that leans three columns or more (a C6 cable's, a horseshoe's) has legs three
//! stitches long and a head a third of a stitch wide. The uniform spline gives the head the
//! tangents of the legs: the head overshoots its leg tops and crosses itself, and the sinker
//! between two such loops does too. On the 12 x 10 cm sheet of `examples/interlock_survey`,
//! uniform knots left 140 such self-crossings in C6, 54 in the corpus's cable-6, 96 in
//! cable-8 and 76 in the horseshoe cable (counted as undecided crossings, since no rule
//! orders a yarn against itself).
//!
//! A course holding such a loop takes knots spaced by the fourth root of each chord, measured
//! in stitch widths: half way from uniform knots (the chord to the power 0) to centripetal
//! ones (the square root). Measured on that sheet: the fourth root leaves none of those
//! self-crossings in cable-6, cable-8 and the horseshoe (C6 keeps 8, in its bind-off, which
//! keeps uniform knots); the square root also unties them, but bows the legs so far that the
//! legs of neighbouring loops cross instead (96 crossings in cable-6, 106 in the horseshoe).
//! Courses without such a loop keep uniform knots and are drawn exactly as before: C4's loops
//! lean two columns and never curled.

use glam::{Vec2, Vec3};

use super::stitch_shape::stitch_key_points;
use super::{NormalOffsets, KEY_POINTS};
use crate::lattice::Lattice;
use crate::pattern::StitchPattern;

/// How far, in stitch widths, a loop's head must stand aside of the middle of its feet for
/// its course to take knots from its chords: C4's loops lean two columns, C6's three.
pub const FAR_LEAN: f32 = 2.5;

/// The least knot spacing, so that key points standing on one another in (u, v) (a depth
/// step) divide by no zero.
const MIN_SPACING: f32 = 1e-3;

/// Whether the loop with key points `stitch` leans [`FAR_LEAN`] or more, `metric` taking
/// (u, v) to stitch widths.
fn leans_far(stitch: &[Vec3], metric: Vec2) -> bool {
    let feet = 0.5 * (stitch[1].x + stitch[5].x);
    ((stitch[3].x - feet) * metric.x).abs() >= FAR_LEAN
}

/// Whether any loop of `course` leans [`FAR_LEAN`] or more: then every piece of the course
/// (and the fabric the edges keep clear of, [`super::edge_clearance`]) spaces its knots by its
/// chords. The whole course decides, so that a piece and the window the edges see of it are
/// drawn alike.
pub fn course_leans_far(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    metric: Vec2,
    course: usize,
) -> bool {
    (0..lattice.wales).any(|w| {
        leans_far(
            &stitch_key_points(lattice, pattern, offsets, course, w),
            metric,
        )
    })
}

/// [`course_leans_far`] for a piece of `course` with key points `kp`: a piece holding every
/// stitch of its course answers from its own key points (no second pass over the course each
/// time a pose is sampled).
pub fn piece_course_leans_far(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    metric: Vec2,
    course: usize,
    kp: &[Vec3],
) -> bool {
    if kp.len() >= lattice.wales * KEY_POINTS {
        kp.chunks_exact(KEY_POINTS).any(|s| leans_far(s, metric))
    } else {
        course_leans_far(lattice, pattern, offsets, metric, course)
    }
}

/// The knot spacing of each chord of a piece's key points `kp` (in (u, v, lambda)), for
/// [`super::CardinalSpline::spacing`]: `metric` takes (u, v) to stitch widths (lambda is not
/// measured: the crossings that matter are those of the (u, v) projection), and a closed
/// piece's last chord runs to its first point shifted by `period`.
pub fn knot_spacing(kp: &[Vec3], metric: Vec2, closed: bool, period: Vec3) -> Vec<f32> {
    let n = kp.len();
    let chords = if closed { n } else { n - 1 };
    (0..chords)
        .map(|i| {
            let next = if i + 1 < n { kp[i + 1] } else { kp[0] + period };
            let c = metric * (next - kp[i]).truncate();
            fourth_root_of_length(c.dot(c)).max(MIN_SPACING)
        })
        .collect()
}

/// The fourth root of a length given squared: three square roots, each rounded exactly by
/// IEEE, so every machine gets the same bits (`powf` may differ in its last bit).
fn fourth_root_of_length(squared_length: f32) -> f32 {
    squared_length.sqrt().sqrt().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn loop_leaning(lean: f32, x0: f32) -> [Vec3; KEY_POINTS] {
        [
            Vec3::new(x0, -0.35, 0.0),
            Vec3::new(x0 + 0.375, 0.0, 0.0),
            Vec3::new(x0 + lean + 0.125, 1.0, 0.0),
            Vec3::new(x0 + lean + 0.5, 1.35, 0.0),
            Vec3::new(x0 + lean + 0.875, 1.0, 0.0),
            Vec3::new(x0 + 0.625, 0.0, 0.0),
        ]
    }

    #[test]
    fn loops_leaning_three_columns_lean_far_and_their_chords_set_the_knots() {
        let metric = Vec2::ONE;
        assert!(!leans_far(&loop_leaning(0.0, 0.0), metric));
        assert!(!leans_far(&loop_leaning(2.0, 0.0), metric));
        assert!(leans_far(&loop_leaning(3.0, 0.0), metric));
        assert!(leans_far(&loop_leaning(-3.0, 0.0), metric));
        // With u measured at twice the stitch width, two columns are four stitch widths.
        assert!(leans_far(&loop_leaning(2.0, 0.0), Vec2::new(2.0, 1.0)));
        let mut three: Vec<Vec3> = (0..4).flat_map(|i| loop_leaning(0.0, i as f32)).collect();
        three[6..12].copy_from_slice(&loop_leaning(-3.0, 1.0));
        let sp = knot_spacing(&three, metric, false, Vec3::ZERO);
        assert_eq!(sp.len(), three.len() - 1);
        // The spacing grows with the chord, as its fourth root.
        let leg = (three[8] - three[7]).truncate().length();
        assert!((sp[7] - leg.powf(0.25)).abs() < 1e-6);
        let closed = knot_spacing(&three, metric, true, Vec3::new(4.0, 0.0, 0.0));
        assert_eq!(closed.len(), three.len());
    }
}
