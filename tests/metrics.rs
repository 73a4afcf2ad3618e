//! Clearance with planted answers, against a brute-force reference, and bit-identical for
//! any thread count. The benchmark (ignored by default) prints segments per second:
//! `cargo test --release --test metrics -- --ignored --nocapture`.

use glam::{DVec3, Vec3};
use knitwear::metrics::{
    clearance, close_pairs, closest_parameters, segment_clearances, segment_distance_squared,
    Clearance, YarnPolyline, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
};

const CAP: f32 = 4.0;

/// Points from `a` to `b` every `step` (both ends included).
fn line(a: Vec3, b: Vec3, step: f32) -> Vec<Vec3> {
    let n = (a.distance(b) / step).round().max(1.0) as usize;
    (0..=n).map(|k| a.lerp(b, k as f32 / n as f32)).collect()
}

fn open(points: &[Vec3]) -> YarnPolyline<'_> {
    YarnPolyline {
        points,
        closed: false,
    }
}

fn assert_near(got: f32, want: f32) {
    assert!((got - want).abs() < 1e-5, "got {got}, want {want}");
}

#[test]
fn two_parallel_yarns_three_apart() {
    let a = line(Vec3::ZERO, Vec3::new(20.0, 0.0, 0.0), 0.5);
    let b = line(Vec3::new(0.0, 3.0, 0.0), Vec3::new(20.0, 3.0, 0.0), 0.5);
    let c = clearance(
        &[open(&a), open(&b)],
        1.0,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        CAP,
    );
    assert_eq!(c.segments, 80);
    assert_near(c.min, 3.0);
    assert_near(c.p01, 3.0);
    // In diameters: the same scene with a yarn half as thick is twice as clear.
    let c = clearance(
        &[open(&a), open(&b)],
        0.5,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        8.0,
    );
    assert_near(c.min, 6.0);
    // Beyond the cap: reported as the cap.
    let c = clearance(
        &[open(&a), open(&b)],
        1.0,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        2.0,
    );
    assert_eq!((c.min, c.p01), (2.0, 2.0));
}

#[test]
fn a_single_straight_yarn_is_clear_up_to_the_cap() {
    let a = line(Vec3::ZERO, Vec3::new(30.0, 0.0, 0.0), 0.25);
    // Two points of a straight yarn are never locally closest to each other: walking
    // towards each other along the yarn always brings them nearer. Nothing is measured.
    let c = clearance(&[open(&a)], 1.0, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS, CAP);
    assert_eq!(
        c,
        Clearance {
            min: CAP,
            p01: CAP,
            segments: 120
        }
    );
    let c = clearance(&[open(&a)], 1.0, 0.0, CAP);
    assert_eq!(c.min, CAP);
    // A gently bending yarn (radius 20 diameters) likewise.
    let arc: Vec<Vec3> = (0..200)
        .map(|k| {
            let t = k as f32 * 0.01;
            Vec3::new(20.0 * t.sin(), 20.0 * (1.0 - t.cos()), 0.0)
        })
        .collect();
    assert_eq!(
        clearance(
            &[open(&arc)],
            1.0,
            DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
            CAP
        )
        .min,
        CAP
    );
}

/// A flat-bottomed U: legs from y = 10 down to 0 at x = 0 and x = 2.5, joined along y = 0;
/// points every 0.5.
fn u_shape() -> Vec<Vec3> {
    let mut pts = line(Vec3::new(0.0, 10.0, 0.0), Vec3::ZERO, 0.5);
    pts.extend(&line(Vec3::ZERO, Vec3::new(2.5, 0.0, 0.0), 0.5)[1..]);
    pts.extend(&line(Vec3::new(2.5, 0.0, 0.0), Vec3::new(2.5, 10.0, 0.0), 0.5)[1..]);
    pts
}

#[test]
fn u_shaped_yarn_legs() {
    let u = u_shape();
    // The legs are 2.5 + 2y apart along the yarn at height y: beyond the exclusion of 2
    // diameters everywhere, they face each other 2.5 apart. Across a square corner, points
    // are never locally closest (walking towards the corner brings them nearer), so the
    // corner's sqrt(2)-apart pair at 2 along the yarn does not count.
    let c = clearance(&[open(&u)], 1.0, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS, CAP);
    assert_near(c.min, 2.5);
    assert_near(c.p01, 2.5);
    let c = clearance(&[open(&u)], 1.0, 4.0, CAP);
    assert_near(c.min, 2.5);
    // Thicker yarn: 2.5 scene units are 1.25 diameters; the legs are still more than 2
    // diameters apart along the yarn.
    let c = clearance(&[open(&u)], 2.0, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS, CAP);
    assert_near(c.min, 1.25);
    // Exclusion beyond the whole yarn: nothing is compared.
    let c = clearance(&[open(&u)], 1.0, 100.0, CAP);
    assert_eq!(c.min, CAP);
    let c = clearance(&[open(&u)], 1.0, f32::INFINITY, CAP);
    assert_eq!(c.min, CAP);
}

#[test]
fn a_hairpin_pinched_tighter_than_its_yarn_is_caught() {
    // Legs 0.5 apart joined by a half circle of radius 0.25 (0.79 of yarn): pairs near the
    // bend are neighbours, but higher up the legs face each other 0.5 apart.
    let mut pts = line(Vec3::new(0.0, 10.0, 0.0), Vec3::ZERO, 0.25);
    pts.extend((1..16).map(|k| {
        let a = std::f32::consts::PI * k as f32 / 16.0;
        Vec3::new(0.25 - 0.25 * a.cos(), -0.25 * a.sin(), 0.0)
    }));
    pts.extend(line(
        Vec3::new(0.5, 0.0, 0.0),
        Vec3::new(0.5, 10.0, 0.0),
        0.25,
    ));
    let c = clearance(
        &[open(&pts)],
        1.0,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        CAP,
    );
    assert_near(c.min, 0.5);
}

#[test]
fn crossing_perpendicular_segments() {
    let a = [Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0)];
    let b = [Vec3::new(0.0, -1.0, 0.5), Vec3::new(0.0, 1.0, 0.5)];
    let c = clearance(
        &[open(&a), open(&b)],
        1.0,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        CAP,
    );
    assert_eq!(c.segments, 2);
    assert_near(c.min, 0.5);
    assert_near(c.p01, 0.5);
    // Finely sampled, and crossing away from any sample point.
    let a = line(Vec3::new(-5.0, 0.3, 0.0), Vec3::new(5.0, 0.3, 0.0), 0.7);
    let b = line(Vec3::new(0.1, -5.0, 0.5), Vec3::new(0.1, 5.0, 0.5), 0.7);
    let c = clearance(
        &[open(&a), open(&b)],
        1.0,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        CAP,
    );
    assert_near(c.min, 0.5);
}

#[test]
fn segment_distance_cases() {
    let d = |p1: [f32; 3], q1: [f32; 3], p2: [f32; 3], q2: [f32; 3]| {
        segment_distance_squared(p1.into(), q1.into(), p2.into(), q2.into()).sqrt()
    };
    // Parallel and overlapping, parallel and disjoint along their line, collinear.
    assert_near(
        d([0., 0., 0.], [4., 0., 0.], [1., 2., 0.], [3., 2., 0.]),
        2.0,
    );
    assert_near(
        d([0., 0., 0.], [1., 0., 0.], [4., 0., 0.], [5., 0., 0.]),
        3.0,
    );
    assert_near(
        d([0., 0., 0.], [1., 0., 0.], [3., 4., 0.], [6., 4., 0.]),
        (4.0f32 + 16.0).sqrt(),
    );
    assert_near(
        d([0., 0., 0.], [1., 0., 0.], [2., 0., 0.], [1.5, 0., 0.]),
        0.5,
    );
    // Antiparallel.
    assert_near(
        d([0., 0., 0.], [4., 0., 0.], [3., 1., 0.], [1., 1., 0.]),
        1.0,
    );
    // Points (zero-length segments).
    assert_near(
        d([1., 1., 1.], [1., 1., 1.], [1., 1., 3.], [1., 1., 3.]),
        2.0,
    );
    assert_near(
        d([0., 0., 0.], [0., 0., 0.], [-1., 1., 0.], [1., 1., 0.]),
        1.0,
    );
    assert_near(
        d([-1., 1., 0.], [1., 1., 0.], [0., 0., 0.], [0., 0., 0.]),
        1.0,
    );
    // Skew, closest points inside both; and closest at an endpoint of one.
    assert_near(
        d([-1., 0., 0.], [1., 0., 0.], [0., -1., 1.], [0., 1., 1.]),
        1.0,
    );
    assert_near(
        d([-1., 0., 0.], [1., 0., 0.], [2., -1., 1.], [2., 1., 1.]),
        2f32.sqrt(),
    );
    // Far from the origin: still exact to f32 resolution of the small vectors.
    let o = 1000.0;
    assert!(
        (d(
            [o, o, o],
            [o + 1., o, o],
            [o, o + 0.001, o],
            [o + 1., o + 0.001, o]
        ) - 0.001)
            .abs()
            < 1e-4
    );
}

#[test]
fn closed_yarns_wrap_their_neighbours() {
    // A circle of radius 3: closed, the segments either side of the first point are
    // neighbours; treated as open (with the closing segment given explicitly), they would
    // be 0 apart.
    let n = 120;
    let circle: Vec<Vec3> = (0..n)
        .map(|k| {
            let a = std::f32::consts::TAU * k as f32 / n as f32;
            Vec3::new(3.0 * a.cos(), 3.0 * a.sin(), 0.0)
        })
        .collect();
    let ring = [YarnPolyline {
        points: &circle,
        closed: true,
    }];
    let c = clearance(&ring, 1.0, 2.0, CAP);
    assert_eq!(
        c,
        Clearance {
            min: CAP,
            p01: CAP,
            segments: n
        }
    );
    // The only doubly critical pairs of a circle are opposite points: a diameter apart (for
    // the 120-gon, opposite sides: 6 cos(pi / 120)).
    let c = clearance(&ring, 1.0, 2.0, 8.0);
    let across = 6.0 * (std::f32::consts::PI / n as f32).cos();
    assert_near(c.min, across);
    assert_near(c.p01, across);
    let mut closed_by_hand = circle.clone();
    closed_by_hand.push(circle[0]);
    let c_open = clearance(&[open(&closed_by_hand)], 1.0, 2.0, CAP);
    assert_eq!(
        c_open.min, 0.0,
        "an open yarn's ends are not neighbours of each other"
    );
    // A closed yarn of two points is one segment.
    let two = [Vec3::ZERO, Vec3::X];
    let c = clearance(
        &[YarnPolyline {
            points: &two,
            closed: true,
        }],
        1.0,
        2.0,
        CAP,
    );
    assert_eq!(
        c,
        Clearance {
            min: CAP,
            p01: CAP,
            segments: 1
        }
    );
}

#[test]
fn empty_and_unmeasurable_inputs() {
    assert_eq!(
        clearance(&[], 1.0, 2.0, CAP),
        Clearance {
            min: CAP,
            p01: CAP,
            segments: 0
        }
    );
    let one = [Vec3::ONE];
    assert_eq!(
        clearance(&[open(&one), open(&[])], 1.0, 2.0, CAP).segments,
        0
    );
    let a = line(Vec3::ZERO, Vec3::X * 5.0, 0.5);
    for (d, e, cap) in [
        (0.0, 2.0, CAP),
        (-1.0, 2.0, CAP),
        (f32::NAN, 2.0, CAP),
        (1.0, f32::NAN, CAP),
        (1.0, 2.0, 0.0),
        (1.0, 2.0, f32::INFINITY),
    ] {
        let c = clearance(&[open(&a)], d, e, cap);
        assert!(
            c.min.is_nan() && c.p01.is_nan() && c.segments == 10,
            "{d} {e} {cap}: {c:?}"
        );
    }
    let mut bad = a.clone();
    bad[3].y = f32::INFINITY;
    assert!(clearance(&[open(&bad)], 1.0, 2.0, CAP).min.is_nan());
    // Duplicate points (zero-length segments) and a yarn folded back on itself.
    let folded = [
        Vec3::ZERO,
        Vec3::ZERO,
        Vec3::X * 3.0,
        Vec3::X * 3.0,
        Vec3::ZERO,
        Vec3::ZERO,
    ];
    let c = clearance(&[open(&folded)], 1.0, 2.0, CAP);
    assert_eq!(c.min, 0.0);
    // Every point the same.
    let same = [Vec3::ONE; 10];
    let c = clearance(&[open(&same), open(&same)], 1.0, 2.0, CAP);
    assert_eq!(c.min, 0.0);
}

/// Deterministic numbers in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn vec(&mut self) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) - Vec3::splat(0.5)
    }
}

/// Random walks: `yarns` yarns of `points` points, steps of random length up to `step`.
fn random_walks(yarns: usize, points: usize, step: f32, seed: u64) -> Vec<Vec<Vec3>> {
    let mut rng = Lcg(seed);
    (0..yarns)
        .map(|_| {
            let mut p = rng.vec() * 40.0;
            (0..points)
                .map(|_| {
                    p += rng.vec() * 2.0 * step;
                    p
                })
                .collect()
        })
        .collect()
}

/// The point at arc length `sigma` along a polyline with cumulative lengths `arc`
/// (wrapping when closed, clamped when open), in f64.
fn point_at(points: &[Vec3], arc: &[f64], closed: bool, sigma: f64) -> DVec3 {
    let total = *arc.last().unwrap();
    let sigma = if closed {
        sigma.rem_euclid(total)
    } else {
        sigma.clamp(0.0, total)
    };
    let k = arc.partition_point(|&a| a <= sigma).clamp(1, arc.len() - 1) - 1;
    let (a, b) = (
        points[k % points.len()].as_dvec3(),
        points[(k + 1) % points.len()].as_dvec3(),
    );
    let len = arc[k + 1] - arc[k];
    if len > 0.0 {
        a.lerp(b, ((sigma - arc[k]) / len).clamp(0.0, 1.0))
    } else {
        a
    }
}

/// The O(n^2) reference, written independently of the index: every pair, with the
/// same-yarn rule checked by walking a short step along the yarn from each closest point.
fn brute_force(yarns: &[YarnPolyline], diameter: f32, exclusion: f32, cap: f32) -> Vec<f32> {
    struct Seg {
        a: Vec3,
        b: Vec3,
        yarn: usize,
        k: usize,
        s0: f64,
        s1: f64,
    }
    let mut segs = vec![];
    let mut info = vec![];
    for (y, yarn) in yarns.iter().enumerate() {
        let p = yarn.points;
        let n = match (p.len(), yarn.closed) {
            (0 | 1, _) => 0,
            (n, false) => n - 1,
            (2, true) => 1,
            (n, true) => n,
        };
        let mut arc = vec![0.0f64];
        for k in 0..n {
            let (a, b) = (p[k], p[(k + 1) % p.len()]);
            let s = *arc.last().unwrap();
            let len = f64::from(a.distance(b));
            segs.push(Seg {
                a,
                b,
                yarn: y,
                k,
                s0: s,
                s1: s + len,
            });
            arc.push(s + len);
        }
        info.push((yarn.closed && n > 1, n, arc));
    }
    let ex = f64::from(exclusion) * f64::from(diameter);
    let per: Vec<f32> = segs
        .iter()
        .map(|s| {
            let mut best = cap * diameter;
            for t in &segs {
                let (u, v) = closest_parameters(s.a, s.b, t.a, t.b);
                let d = segment_distance_squared(s.a, s.b, t.a, t.b).sqrt();
                if s.yarn == t.yarn {
                    let (a, b) = if s.k <= t.k { (s, t) } else { (t, s) };
                    let (closed, n, arc) = &info[s.yarn];
                    if b.k - a.k <= 1 || (*closed && a.k == 0 && b.k == n - 1) {
                        continue;
                    }
                    let len = arc.last().unwrap();
                    let mut gap = b.s0 - a.s1;
                    if *closed {
                        gap = gap.min(len - b.s1 + a.s0);
                    }
                    if gap < ex {
                        continue;
                    }
                    let points = yarns[s.yarn].points;
                    let c = f64::from(s.a.distance(s.b)) * f64::from(u) + s.s0;
                    let q = f64::from(t.a.distance(t.b)) * f64::from(v) + t.s0;
                    let (pc, pq) = (
                        point_at(points, arc, *closed, c),
                        point_at(points, arc, *closed, q),
                    );
                    let dist = pc.distance(pq);
                    // Doubly critical: for each point, walking one way along the yarn must
                    // not bring the pair nearer while walking the other way takes it
                    // further (flat within a 1e-3 slope counts as critical; an open yarn's
                    // end counts as walking further).
                    let step = 1e-7;
                    let total = *arc.last().unwrap();
                    let slope = |x: f64, y: f64, at_end: bool| -> i8 {
                        if at_end {
                            return 2;
                        }
                        let moved = point_at(points, arc, *closed, x)
                            .distance(point_at(points, arc, *closed, y));
                        let change = (moved - dist) / step;
                        if change > 1e-3 {
                            1
                        } else if change < -1e-3 {
                            -1
                        } else {
                            0
                        }
                    };
                    let ok = |fwd: i8, bwd: i8| {
                        fwd == 0 || bwd == 0 || (fwd > 0 && bwd > 0) || (fwd == -1 && bwd == -1)
                    };
                    let open_end = |x: f64| !*closed && (x < 0.0 || x > total);
                    let crit_c = ok(
                        slope(c + step, q, open_end(c + step)),
                        slope(c - step, q, open_end(c - step)),
                    );
                    let crit_q = ok(
                        slope(c, q + step, open_end(q + step)),
                        slope(c, q - step, open_end(q - step)),
                    );
                    if !(crit_c && crit_q) {
                        continue;
                    }
                }
                best = best.min(d);
            }
            (best / diameter).min(cap)
        })
        .collect();
    per
}

/// min and p01 (nearest rank) of per-segment values.
fn summary(per: &[f32], cap: f32) -> (f32, f32) {
    let mut sorted = per.to_vec();
    sorted.sort_by(f32::total_cmp);
    let min = sorted.first().copied().unwrap_or(cap);
    (
        min,
        sorted
            .get(sorted.len().div_ceil(100).max(1) - 1)
            .copied()
            .unwrap_or(cap),
    )
}

#[test]
fn agrees_with_brute_force() {
    for (seed, count, step, diameter, exclusion, cap, closed) in [
        (1, 8, 0.3, 1.0, 2.0, 4.0, false),
        (2, 8, 0.3, 0.5, 2.0, 3.0, true),
        (3, 8, 2.5, 1.0, 2.0, 4.0, false), // segments longer than cells
        (4, 8, 0.05, 0.2, 5.0, 10.0, true),
        (5, 8, 0.5, 3.0, 0.0, 1.0, false),
        (6, 1, 0.4, 1.0, 2.0, 4.0, false), // one yarn against itself only
        (7, 1, 0.4, 1.0, 2.0, 4.0, true),
    ] {
        let walks = random_walks(count, 480 / count, step, seed);
        let yarns: Vec<YarnPolyline> = walks
            .iter()
            .map(|p| YarnPolyline { points: p, closed })
            .collect();
        let fast = segment_clearances(&yarns, diameter, exclusion, cap).unwrap();
        let slow = brute_force(&yarns, diameter, exclusion, cap);
        assert_eq!(fast, slow, "seed {seed}");
        let c = clearance(&yarns, diameter, exclusion, cap);
        assert_eq!((c.min, c.p01), summary(&slow, cap));
        assert_eq!(c.segments, slow.len());
        // The test is worth something only if values spread between 0 and the cap.
        let capped = slow.iter().filter(|&&d| d == cap).count();
        assert!(
            capped > 0 && capped < slow.len() / 2,
            "seed {seed}: {capped} of {} capped",
            slow.len()
        );
    }
}

/// A sparse scene (one yarn ten thousand diameters from the rest) is indexed by a hash of
/// the cells that hold anything rather than a dense grid: it answers as brute force does too.
#[test]
fn a_sparse_scene_agrees_with_brute_force() {
    for (seed, closed) in [(21, false), (22, true)] {
        let mut walks = random_walks(8, 60, 0.3, seed);
        let far = Vec3::new(1.0e4, -2.0e4, 1.5e4);
        let last = walks.len() - 1;
        for p in &mut walks[last] {
            *p += far;
        }
        let yarns: Vec<YarnPolyline> = walks
            .iter()
            .map(|p| YarnPolyline { points: p, closed })
            .collect();
        let fast = segment_clearances(&yarns, 1.0, 2.0, 4.0).unwrap();
        let slow = brute_force(&yarns, 1.0, 2.0, 4.0);
        assert_eq!(fast, slow, "seed {seed}");
        let capped = slow.iter().filter(|&&d| d == 4.0).count();
        assert!(
            capped > 0 && capped < slow.len() / 2,
            "seed {seed}: {capped} of {} capped",
            slow.len()
        );
    }
}

/// `close_pairs` lists exactly the pairs `clearance` compares: each segment's nearest listed
/// partner is its clearance wherever that is under the radius, and it has none otherwise.
#[test]
fn close_pairs_are_the_pairs_clearance_measures() {
    for (seed, closed, within) in [(11, false, 1.5), (12, true, 2.5), (13, false, 0.8)] {
        let walks = random_walks(6, 80, 0.3, seed);
        let yarns: Vec<YarnPolyline> = walks
            .iter()
            .map(|p| YarnPolyline { points: p, closed })
            .collect();
        let per = segment_clearances(&yarns, 1.0, 2.0, within).unwrap();
        let pairs = close_pairs(&yarns, 1.0, 2.0, within).unwrap();
        let mut nearest = vec![within; per.len()];
        for p in &pairs {
            assert!(p.a < p.b && p.distance < within, "{p:?}");
            assert!(
                (0.0..=1.0).contains(&p.s) && (0.0..=1.0).contains(&p.t),
                "{p:?}"
            );
            nearest[p.a] = nearest[p.a].min(p.distance);
            nearest[p.b] = nearest[p.b].min(p.distance);
        }
        // The same pairs; a distance found from the other segment's side may round apart in
        // the last bit.
        for (k, (got, want)) in nearest.iter().zip(&per).enumerate() {
            assert!(
                (got - want).abs() <= 1e-5 * want.max(1.0),
                "seed {seed}, segment {k}: nearest listed {got}, clearance {want}"
            );
        }
        assert!(
            !pairs.is_empty() && per.contains(&within),
            "seed {seed}: the radius should split the segments"
        );
    }
    assert!(close_pairs(&[], 1.0, 2.0, f32::NAN).is_none());
}

/// `courses` wavy courses of `per_course` segments, about one diameter apart, weaving in z
/// like knitted rows do (not a real knit: a dense stand-in of the same scale).
fn knit_like(courses: usize, per_course: usize) -> Vec<Vec<Vec3>> {
    (0..courses)
        .map(|c| {
            let phase = c as f32 * 0.7;
            (0..=per_course)
                .map(|k| {
                    let x = k as f32 * 0.3;
                    Vec3::new(
                        x,
                        c as f32 * 1.1 + 0.3 * (2.0 * x + phase).sin(),
                        0.4 * (1.5 * x + phase).sin(),
                    )
                })
                .collect()
        })
        .collect()
}

#[test]
fn bit_identical_for_any_thread_count() {
    let lines = knit_like(60, 400);
    let yarns: Vec<YarnPolyline> = lines.iter().map(|p| open(p)).collect();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| clearance(&yarns, 1.0, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS, CAP))
    };
    let one = run(1);
    let four = run(4);
    assert_eq!(one.min.to_bits(), four.min.to_bits());
    assert_eq!(one.p01.to_bits(), four.p01.to_bits());
    assert_eq!(one.segments, four.segments);
    assert!(one.min > 0.0 && one.min < CAP, "{one:?}");
}
