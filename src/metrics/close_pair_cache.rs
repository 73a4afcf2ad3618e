//! [`close_pairs`](super::close_pairs) asked again and again of yarns that move a little
//! between calls (the contact relief's rounds, `skeleton::contact`), answered without
//! searching the whole scene each time, and bit for bit as `close_pairs` answers.
//!
//! Why it is exact: the distance between two segments moves by no more than the largest
//! displacement of either's end points plus the other's. The cache keeps, from a reference
//! state, every pair of segments (other than neighbours by index) nearer than the asked
//! distance plus a margin. Later, a pair near enough now is either among those candidates
//! (neither segment has moved half the margin since the reference) or has a segment that
//! moved further, whose neighbourhood is searched afresh. Every pair found either way goes
//! through the same test [`close_pairs`](super::close_pairs) applies (arclength exclusion,
//! double criticality, distance), computed from the lower-numbered segment as it is there,
//! and the pairs come out in the same order (`a`, then `b`).

use glam::Vec3;
use rayon::prelude::*;

use super::{measurable, ClosePair, Measurable, SegmentIndex, YarnPolyline};

/// When more than this share of the segments has moved half the margin, the reference is
/// taken again (each such segment costs a search of its own).
const REBUILD_SHARE: f32 = 0.125;

/// Close pairs of yarns that move between calls; see the module documentation.
pub struct ClosePairCache {
    /// Margin beyond the asked distance kept in the candidates, in diameters.
    margin: f32,
    /// Segment end points at the reference state (scene units).
    reference: Vec<[Vec3; 2]>,
    /// Candidate pairs `(a, b)`, `a < b`, ascending.
    candidates: Vec<(u32, u32)>,
    /// The distance and diameter the candidates were found for.
    asked: (f32, f32, f32),
    /// Points per yarn and whether it is closed, at the reference: segments are numbered by
    /// it.
    shape: Vec<(usize, bool)>,
}

impl ClosePairCache {
    /// A cache keeping pairs up to `margin` diameters beyond the distance asked.
    pub fn new(margin: f32) -> Self {
        Self {
            margin,
            reference: Vec::new(),
            candidates: Vec::new(),
            asked: (f32::NAN, f32::NAN, f32::NAN),
            shape: Vec::new(),
        }
    }

    /// What [`close_pairs`](super::close_pairs) returns for the same arguments.
    pub fn close_pairs(
        &mut self,
        yarns: &[YarnPolyline],
        diameter: f32,
        neighbour_arclength: f32,
        within: f32,
    ) -> Option<Vec<ClosePair>> {
        let Measurable { segments, radius } =
            measurable(yarns, diameter, neighbour_arclength, within)?;
        if segments == 0 {
            return Some(Vec::new());
        }
        let exclusion = f64::from(neighbour_arclength.max(0.0)) * f64::from(diameter);
        let index = SegmentIndex::new(yarns, diameter, radius, exclusion);
        let margin = self.margin * diameter;
        let asked = (diameter, neighbour_arclength, within);
        let shape: Vec<(usize, bool)> = yarns.iter().map(|y| (y.points.len(), y.closed)).collect();
        let moved = |reference: &[[Vec3; 2]]| -> Vec<u32> {
            (0..segments)
                .filter(|&i| {
                    let ([a, b], [p, q]) = (index.ends[i], reference[i]);
                    a.distance(p).max(b.distance(q)) > 0.5 * margin
                })
                .map(|i| i as u32)
                .collect()
        };
        let same = self.asked == asked && self.shape == shape && self.reference.len() == segments;
        let mut far: Vec<u32> = if same {
            moved(&self.reference)
        } else {
            (0..segments as u32).collect()
        };
        if far.len() as f32 > REBUILD_SHARE * segments as f32 {
            let wide = SegmentIndex::new(yarns, diameter, radius + margin, exclusion);
            self.candidates = (0..segments)
                .into_par_iter()
                .with_min_len(256)
                .flat_map_iter(|a| {
                    let mut found = Vec::new();
                    wide.near(a, |b| {
                        if b > a {
                            found.push((a as u32, b as u32));
                        }
                    });
                    found
                })
                .collect();
            self.reference = index.ends.clone();
            self.asked = asked;
            self.shape = shape;
            far.clear();
        }
        let pair = |a: usize, b: usize| {
            index.compare(a, b).map(|(s, t, d)| ClosePair {
                a,
                b,
                s,
                t,
                distance: d / diameter,
            })
        };
        let mut pairs: Vec<ClosePair> = self
            .candidates
            .par_iter()
            .with_min_len(1024)
            .filter_map(|&(a, b)| pair(a as usize, b as usize))
            .collect();
        if !far.is_empty() {
            let fresh: Vec<ClosePair> = far
                .par_iter()
                .flat_map_iter(|&i| {
                    let i = i as usize;
                    let mut found = Vec::new();
                    index.near(i, |j| found.push(pair(i.min(j), i.max(j))));
                    found.into_iter().flatten()
                })
                .collect();
            pairs.extend(fresh);
            pairs.sort_unstable_by_key(|p| (p.a, p.b));
            pairs.dedup_by_key(|p| (p.a, p.b));
        }
        Some(pairs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::close_pairs;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Wavy yarns side by side (one closed), moved a little each round, some points now and
    /// then a long way: the cache answers exactly as a fresh search, pair for pair and bit
    /// for bit, whether it reuses its candidates, searches round moved segments, or starts
    /// again.
    #[test]
    fn tracked_pairs_are_the_pairs_searched_afresh() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut lines: Vec<Vec<Vec3>> = (0..6)
            .map(|y| {
                (0..80)
                    .map(|i| {
                        let x = i as f32 * 0.3;
                        Vec3::new(
                            x,
                            y as f32 * 0.9 + 0.4 * (x * 1.3).sin(),
                            0.3 * (x + y as f32).cos(),
                        )
                    })
                    .collect()
            })
            .collect();
        // A ring crossing the others, on itself.
        lines.push(
            (0..60)
                .map(|i| {
                    let a = i as f32 / 60.0 * std::f32::consts::TAU;
                    Vec3::new(
                        12.0 + 3.0 * a.cos(),
                        2.5 + 3.0 * a.sin(),
                        0.2 * (3.0 * a).sin(),
                    )
                })
                .collect(),
        );
        let mut cache = ClosePairCache::new(0.5);
        // Rounds that reused the candidates alone, searched round moved segments, started again.
        let mut ways = [0; 3];
        for round in 0..40 {
            for line in &mut lines {
                for p in line.iter_mut() {
                    // Now and then a point jumps (a segment searched round afresh); every
                    // tenth round the whole scene drifts (the candidates found again).
                    let far = round % 7 == 3 && rng.random::<f32>() < 0.01;
                    let step = if far { 4.0 } else { 0.04 };
                    let r = Vec3::new(rng.random(), rng.random(), rng.random()) - 0.5;
                    *p += step * r
                        + if round % 10 == 9 {
                            Vec3::X * 0.3
                        } else {
                            Vec3::ZERO
                        };
                }
            }
            let yarns: Vec<YarnPolyline> = lines
                .iter()
                .enumerate()
                .map(|(k, l)| YarnPolyline {
                    points: l,
                    closed: k == 6,
                })
                .collect();
            let ends: Vec<[Vec3; 2]> = lines
                .iter()
                .enumerate()
                .flat_map(|(k, l)| {
                    let n = if k == 6 { l.len() } else { l.len() - 1 };
                    (0..n).map(move |i| [l[i], l[(i + 1) % l.len()]])
                })
                .collect();
            let moved = cache.reference.len() == ends.len()
                && ends
                    .iter()
                    .zip(&cache.reference)
                    .any(|(e, r)| e[0].distance(r[0]).max(e[1].distance(r[1])) > 0.25);
            let before = cache.candidates.clone();
            let tracked = cache.close_pairs(&yarns, 1.0, 3.0, 1.05).unwrap();
            ways[if cache.candidates != before {
                2
            } else if moved {
                1
            } else {
                0
            }] += 1;
            let fresh = close_pairs(&yarns, 1.0, 3.0, 1.05).unwrap();
            assert!(!fresh.is_empty());
            assert_eq!(tracked.len(), fresh.len(), "round {round}");
            for (t, f) in tracked.iter().zip(&fresh) {
                assert_eq!((t.a, t.b), (f.a, f.b), "round {round}");
                assert_eq!(
                    [t.s, t.t, t.distance].map(f32::to_bits),
                    [f.s, f.t, f.distance].map(f32::to_bits),
                    "round {round}"
                );
            }
        }
        // Every way was taken.
        assert!(ways.iter().all(|&n| n >= 3), "{ways:?}");
    }
}
