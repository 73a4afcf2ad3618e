//! The perturbed stitch lattice ([Zhong 2001] section 2.4, docs/design.md section 4): kappa 0
//! is the regular lattice, tiles never fold, the field is local, periodic, deterministic and
//! independent of the thread count.

use glam::Vec2;
use knitwear::error::KnitError;
use knitwear::lattice::perturbation::{node_random, LOCALITY_RADIUS, MAX_LEVELS};
use knitwear::lattice::{Lattice, Perturbation, KAPPA_MAX};
use knitwear::parallel::run_in_pool;
use knitwear::surface::UvRect;

const CYCLIC: [(bool, bool); 4] = [(false, false), (true, false), (false, true), (true, true)];

fn domain() -> UvRect {
    UvRect {
        min: Vec2::new(-0.3, 0.2),
        max: Vec2::new(1.1, 1.7),
    }
}

/// A small deterministic generator for test parameters (SplitMix64).
struct Gen(u64);

impl Gen {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn bits(l: &Lattice) -> Vec<[u32; 2]> {
    let mut out = Vec::new();
    for r in 0..l.courses + 2 {
        for c in 0..l.wales + 1 {
            let p = l.node(r, c);
            out.push([p.x.to_bits(), p.y.to_bits()]);
        }
    }
    out
}

/// Node positions in tile units, `(rows, cols, positions)`, from a lattice.
fn tile_units(l: &Lattice) -> (usize, usize, Vec<[f64; 2]>) {
    let o = l.node(0, 0).as_dvec2();
    let t = l.tile.as_dvec2();
    let mut p = Vec::new();
    for r in 0..l.courses + 2 {
        for c in 0..l.wales + 1 {
            let q = (l.node(r, c).as_dvec2() - o) / t;
            p.push([q.x, q.y]);
        }
    }
    (l.courses + 2, l.wales + 1, p)
}

/// Node positions in tile units straight from a field (no f32 rounding of positions).
fn field_units(f: &Perturbation, courses: usize, wales: usize) -> (usize, usize, Vec<[f64; 2]>) {
    let mut p = Vec::new();
    for r in 0..courses + 2 {
        for c in 0..wales + 1 {
            let d = f.displacement(r, c);
            p.push([c as f64 + d[0], r as f64 + d[1]]);
        }
    }
    (courses + 2, wales + 1, p)
}

/// Smallest corner cross product and smallest area over all quads, normalised by the regular
/// tile (1 x 1).
fn min_cross_and_area(rows: usize, cols: usize, p: &[[f64; 2]]) -> (f64, f64) {
    let at = |r: usize, c: usize| p[r * cols + c];
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let (mut min_cross, mut min_area) = (f64::INFINITY, f64::INFINITY);
    for r in 0..rows - 1 {
        for c in 0..cols - 1 {
            // Counter-clockwise in (u,v): bottom-left, bottom-right, top-right, top-left.
            let q = [at(r, c), at(r, c + 1), at(r + 1, c + 1), at(r + 1, c)];
            for k in 0..4 {
                let x = cross(q[k], q[(k + 1) % 4], q[(k + 3) % 4]);
                min_cross = min_cross.min(x);
            }
            let area = 0.5 * cross(q[0], q[2], q[3]) + 0.5 * cross(q[0], q[1], q[2]);
            min_area = min_area.min(area);
        }
    }
    (min_cross, min_area)
}

#[test]
fn kappa_zero_is_the_regular_lattice_bit_for_bit() {
    for (courses, wales) in [(1, 1), (1, 17), (3, 2), (37, 53), (64, 16)] {
        for (cu, cv) in CYCLIC {
            let regular = Lattice::regular(domain(), courses, wales, cu, cv);
            for seed in [0, 1, u64::MAX] {
                for kappa in [0.0f32, -0.0] {
                    let p =
                        Lattice::perturbed(domain(), courses, wales, cu, cv, kappa, seed).unwrap();
                    assert_eq!(bits(&p), bits(&regular));
                    assert_eq!(p.tile, regular.tile);
                    for r in 0..courses {
                        for c in 0..wales {
                            assert_eq!(
                                p.tile_center(r, c).to_array().map(f32::to_bits),
                                regular.tile_center(r, c).to_array().map(f32::to_bits)
                            );
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn tile_center_is_the_mean_of_the_corners() {
    let l = Lattice::perturbed(domain(), 20, 30, false, true, KAPPA_MAX, 3).unwrap();
    let regular = Lattice::regular(domain(), 20, 30, false, true);
    let mut moved = 0;
    for r in 0..20 {
        for c in 0..30 {
            let t = l.tile(r, c);
            let mean = (t.n0 + t.n1 + t.n2 + t.n3) / 4.0;
            assert!((l.tile_center(r, c) - mean).abs().max_element() < 1e-6);
            if (l.tile_center(r, c) - regular.tile_center(r, c)).length() > 1e-4 {
                moved += 1;
            }
        }
    }
    assert!(moved > 500, "only {moved} of 600 centres moved");
}

#[test]
fn tiles_never_fold_over_seeds_kappas_sizes_and_cyclic_sides() {
    let sizes = [
        (1, 1),
        (1, 17),
        (17, 1),
        (3, 2),
        (2, 3),
        (16, 16),
        (31, 33),
        (37, 53),
        (5, 70),
    ];
    let mut g = Gen(0x5EED);
    let mut worst = f64::INFINITY;
    let mut checked = 0usize;
    for (courses, wales) in sizes {
        for (cu, cv) in CYCLIC {
            let mut kappas = vec![0.001f32, 0.01, KAPPA_MAX];
            kappas.extend((0..4).map(|_| (g.unit() * f64::from(KAPPA_MAX)) as f32));
            for kappa in kappas {
                for _ in 0..12 {
                    let seed = g.next();
                    // Through the field, exactly.
                    let f = Perturbation::new(courses, wales, cu, cv, kappa, seed).unwrap();
                    let (rows, cols, p) = field_units(&f, courses, wales);
                    let (cross, area) = min_cross_and_area(rows, cols, &p);
                    let bound = 1.0 - 40.0 * f64::from(kappa);
                    assert!(
                        cross > 0.0 && area >= bound - 1e-9,
                        "{courses}x{wales} cyclic ({cu},{cv}) kappa {kappa} seed {seed}: \
                         cross {cross} area {area}"
                    );
                    // Through the lattice in (u,v), scaled to tile units.
                    let l =
                        Lattice::perturbed(domain(), courses, wales, cu, cv, kappa, seed).unwrap();
                    let (rows, cols, p) = tile_units(&l);
                    let (cross, area) = min_cross_and_area(rows, cols, &p);
                    assert!(
                        cross > 0.0 && area >= bound - 1e-4,
                        "lattice {courses}x{wales} ({cu},{cv}) kappa {kappa} seed {seed}"
                    );
                    if kappa == KAPPA_MAX {
                        worst = worst.min(area);
                    }
                    checked += 1;
                }
            }
        }
    }
    println!(
        "{checked} random lattices: smallest normalised tile area at kappa = KAPPA_MAX \
         ({KAPPA_MAX}): {worst:.4} (guaranteed >= {:.2})",
        1.0 - 40.0 * KAPPA_MAX
    );
}

/// Adversarial values: every level-grid value at +-1 (the extreme of its range) in sign
/// patterns built from parities of the grid indices, plus random +-1 signs.
#[test]
fn planted_worst_case_keeps_every_tile() {
    let pattern = |code: u32, l: usize, i: usize, j: usize, k: usize| -> f64 {
        let bitk = |b: u32| (code >> (6 * k as u32 + b)) & 1 == 1;
        let mut s = 0usize;
        for (b, term) in [i, j, i / 2, j / 2, l].into_iter().enumerate() {
            if bitk(b as u32) {
                s += term;
            }
        }
        let sign = if bitk(5) { -1.0 } else { 1.0 };
        if s % 2 == 0 {
            sign
        } else {
            -sign
        }
    };
    let mut worst = (f64::INFINITY, String::new());
    let mut tried = 0;
    for (courses, wales, cu, cv) in [
        (40, 40, false, false),
        (33, 47, true, false),
        (24, 24, true, true),
    ] {
        let mut codes: Vec<u32> = (0..1u32 << 12).step_by(3).collect();
        codes.extend([0, (1 << 12) - 1]);
        for code in codes {
            let f = Perturbation::with_values(courses, wales, cu, cv, KAPPA_MAX, &|l, i, j, k| {
                pattern(code, l, i, j, k)
            })
            .unwrap();
            let (rows, cols, p) = field_units(&f, courses, wales);
            let (cross, area) = min_cross_and_area(rows, cols, &p);
            assert!(cross > 0.0, "pattern {code:#x} folds a tile");
            if area < worst.0 {
                worst = (area, format!("pattern {code:#x}, {courses}x{wales}"));
            }
            tried += 1;
        }
        for seed in 0..200u64 {
            let f = Perturbation::with_values(courses, wales, cu, cv, KAPPA_MAX, &|l, i, j, k| {
                node_random(seed, l, i, j, k).signum()
            })
            .unwrap();
            let (rows, cols, p) = field_units(&f, courses, wales);
            let (cross, area) = min_cross_and_area(rows, cols, &p);
            assert!(cross > 0.0, "random signs {seed} fold a tile");
            if area < worst.0 {
                worst = (area, format!("random signs {seed}, {courses}x{wales}"));
            }
            tried += 1;
        }
    }
    let bound = 1.0 - 40.0 * f64::from(KAPPA_MAX);
    println!(
        "planted worst case over {tried} extreme fields at kappa {KAPPA_MAX}: smallest \
         normalised tile area {:.4} ({}); guaranteed >= {bound:.2}",
        worst.0, worst.1
    );
    assert!(worst.0 >= bound - 1e-9);
}

#[test]
fn growing_at_the_far_edge_leaves_the_rest_unchanged() {
    let same = |a: &Perturbation, b: &Perturbation, r: usize, c: usize| {
        let (x, y) = (a.displacement(r, c), b.displacement(r, c));
        x.map(f64::to_bits) == y.map(f64::to_bits)
    };
    // Rows: courses 60 -> 120, and rows 0..=20 in particular.
    for cu in [false, true] {
        let a = Perturbation::new(60, 30, cu, false, KAPPA_MAX, 11).unwrap();
        let b = Perturbation::new(120, 30, cu, false, KAPPA_MAX, 11).unwrap();
        for r in 0..=(61 - LOCALITY_RADIUS) {
            for c in 0..=30 {
                assert!(
                    same(&a, &b, r, c),
                    "row {r} col {c} changed (cyclic u {cu})"
                );
            }
        }
        let mut differ = 0;
        for r in 40..=61 {
            for c in 0..=30 {
                differ += usize::from(!same(&a, &b, r, c));
            }
        }
        assert!(differ > 0, "the rows near the old edge should change");
    }
    // Columns: wales 50 -> 90.
    for cv in [false, true] {
        let a = Perturbation::new(25, 50, false, cv, KAPPA_MAX, 12).unwrap();
        let b = Perturbation::new(25, 90, false, cv, KAPPA_MAX, 12).unwrap();
        for r in 0..=26 {
            for c in 0..=(50 - LOCALITY_RADIUS) {
                assert!(
                    same(&a, &b, r, c),
                    "row {r} col {c} changed (cyclic v {cv})"
                );
            }
        }
    }
    // The general statement, over random sizes: nodes at least LOCALITY_RADIUS tiles from the
    // old far edge keep their displacement.
    let mut g = Gen(77);
    for _ in 0..40 {
        let courses = 1 + (g.next() % 90) as usize;
        let wales = 1 + (g.next() % 90) as usize;
        let more_c = courses + 1 + (g.next() % 50) as usize;
        let more_w = wales + 1 + (g.next() % 50) as usize;
        let seed = g.next();
        let a = Perturbation::new(courses, wales, false, false, 0.013, seed).unwrap();
        let b = Perturbation::new(more_c, more_w, false, false, 0.013, seed).unwrap();
        for r in 0..=courses + 1 {
            for c in 0..=wales {
                if r + LOCALITY_RADIUS <= courses + 1 && c + LOCALITY_RADIUS <= wales {
                    assert!(same(&a, &b, r, c), "{courses}x{wales} -> {more_c}x{more_w}");
                }
            }
        }
    }
    // Through the lattice: the displacement in tiles of the low rows is the same.
    let tall = |courses: usize| {
        let tile_v = 0.01f32;
        let d = UvRect {
            min: Vec2::ZERO,
            max: Vec2::new(0.3, tile_v * (courses as f32 + 0.7)),
        };
        let l = Lattice::perturbed(d, courses, 30, false, false, KAPPA_MAX, 5).unwrap();
        let r = Lattice::regular(d, courses, 30, false, false);
        (0..=20)
            .flat_map(|row| (0..=30).map(move |c| (row, c)))
            .map(|(row, c)| (l.node(row, c) - r.node(row, c)) / l.tile)
            .collect::<Vec<_>>()
    };
    for (x, y) in tall(60).iter().zip(tall(120)) {
        assert!((*x - y).abs().max_element() < 1e-4);
    }
}

#[test]
fn cyclic_sides_are_periodic() {
    for (courses, wales) in [(10, 1), (9, 23), (30, 40), (17, 100)] {
        for cv in [false, true] {
            let f = Perturbation::new(courses, wales, true, cv, KAPPA_MAX, 9).unwrap();
            let l = Lattice::perturbed(domain(), courses, wales, true, cv, KAPPA_MAX, 9).unwrap();
            let width = domain().size().x;
            for r in 0..courses + 2 {
                let (a, b) = (f.displacement(r, wales), f.displacement(r, 0));
                assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
                let seam = l.node(r, wales) - l.node(r, 0);
                assert!((seam - Vec2::new(width, 0.0)).abs().max_element() < 1e-5);
            }
        }
        let f = Perturbation::new(courses, wales, false, true, KAPPA_MAX, 9).unwrap();
        let l = Lattice::perturbed(domain(), courses, wales, false, true, KAPPA_MAX, 9).unwrap();
        for c in 0..=wales {
            for (r, r0) in [(courses, 0), (courses + 1, 1)] {
                let (a, b) = (f.displacement(r, c), f.displacement(r0, c));
                assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
                let seam = l.node(r, c) - l.node(r0, c);
                assert!(
                    (seam - Vec2::new(0.0, domain().size().y))
                        .abs()
                        .max_element()
                        < 1e-5
                );
            }
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(96))]

    /// For any size, cyclic sides, irregularity and seed: a side that is not cyclic keeps its
    /// boundary coordinate exactly (the perturbation slides nodes along it, never off it),
    /// and rows 0..=courses stay within the domain (row courses + 1 is only the top course's
    /// northern neighbour, outside the domain even when regular).
    #[test]
    fn non_cyclic_sides_keep_their_boundary_coordinate(
        courses in 1usize..60,
        wales in 1usize..60,
        cu: bool,
        cv: bool,
        kappa in 0.0f32..=KAPPA_MAX,
        seed: u64,
    ) {
        let l = Lattice::perturbed(domain(), courses, wales, cu, cv, kappa, seed).unwrap();
        let r = Lattice::regular(domain(), courses, wales, cu, cv);
        if !cu {
            for row in 0..courses + 2 {
                proptest::prop_assert_eq!(l.node(row, 0).x, domain().min.x);
                proptest::prop_assert_eq!(l.node(row, 0).x, r.node(row, 0).x);
                proptest::prop_assert_eq!(l.node(row, wales).x, r.node(row, wales).x);
            }
        }
        if !cv {
            for c in 0..=wales {
                proptest::prop_assert_eq!(l.node(0, c).y, r.node(0, c).y);
                proptest::prop_assert_eq!(l.node(courses + 1, c).y, r.node(courses + 1, c).y);
            }
        }
        for row in 0..=courses {
            for c in 0..=wales {
                let p = l.node(row, c);
                if !cu {
                    proptest::prop_assert!(p.x >= domain().min.x && p.x <= domain().max.x + 1e-6);
                }
                if !cv {
                    proptest::prop_assert!(p.y >= domain().min.y && p.y <= domain().max.y + 1e-6);
                }
            }
        }
    }
}

/// Key points extrapolate beyond the tile (the sinker 0.35 of a row below it, the head 0.35
/// into the row above), so on a non-cyclic v the first course's sinkers and the last course's
/// heads can leave the domain by a little: at most 0.35 and 0.65 of the change `12 kappa` of
/// a row's height. Across u they stay inside.
#[test]
fn key_points_stay_within_a_small_margin_of_the_domain() {
    let kappa = KAPPA_MAX;
    let mut worst = [0.0f64; 2];
    for (courses, wales) in [(1, 1), (3, 2), (20, 20), (37, 53)] {
        for seed in 0..40 {
            let l =
                Lattice::perturbed(domain(), courses, wales, false, false, kappa, seed).unwrap();
            let (lo, hi) = (domain().min.as_dvec2(), domain().max.as_dvec2());
            let t = l.tile.as_dvec2();
            for r in 0..courses {
                for c in 0..wales {
                    for k in knitwear::skeleton::key_points(
                        &l.tile(r, c),
                        &knitwear::skeleton::LoopShape::PAPER,
                    ) {
                        let k = k.as_dvec2();
                        let out = ((lo - k).max(k - hi) / t).max(glam::DVec2::ZERO);
                        worst[0] = worst[0].max(out.x);
                        worst[1] = worst[1].max(out.y);
                    }
                }
            }
        }
    }
    println!(
        "key points outside the domain at kappa {kappa}: {:.4} tiles across u, {:.4} across v \
         (bound {:.4})",
        worst[0],
        worst[1],
        0.65 * 12.0 * f64::from(kappa)
    );
    assert!(worst[0] < 1e-4);
    assert!(worst[1] <= 0.65 * 12.0 * f64::from(kappa) + 1e-4);
}

#[test]
fn same_seed_same_bits_other_seed_other_lattice() {
    for (cu, cv) in CYCLIC {
        let a = Lattice::perturbed(domain(), 37, 53, cu, cv, 0.01, 42).unwrap();
        let b = Lattice::perturbed(domain(), 37, 53, cu, cv, 0.01, 42).unwrap();
        let c = Lattice::perturbed(domain(), 37, 53, cu, cv, 0.01, 43).unwrap();
        assert_eq!(bits(&a), bits(&b));
        let differ = bits(&a)
            .iter()
            .zip(bits(&c))
            .filter(|(x, y)| **x != *y)
            .count();
        assert!(differ > 37 * 53 / 2, "only {differ} nodes differ");
    }
}

#[test]
fn thread_count_does_not_change_a_bit() {
    let build = |n: usize| {
        run_in_pool(Some(n), || {
            CYCLIC
                .iter()
                .map(|&(cu, cv)| {
                    bits(&Lattice::perturbed(domain(), 131, 97, cu, cv, KAPPA_MAX, 1234).unwrap())
                })
                .collect::<Vec<_>>()
        })
        .unwrap()
    };
    let one = build(1);
    assert_eq!(one, build(2));
    assert_eq!(one, build(8));
}

#[test]
fn out_of_range_kappa_is_a_parameter_error() {
    for kappa in [
        KAPPA_MAX * 1.001,
        0.5,
        -0.001,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
    ] {
        let err = Lattice::perturbed(domain(), 10, 10, false, false, kappa, 0).unwrap_err();
        assert!(
            matches!(err, KnitError::Parameter(_)),
            "kappa {kappa}: {err:?}"
        );
        assert!(matches!(
            Perturbation::new(10, 10, false, false, kappa, 0),
            Err(KnitError::Parameter(_))
        ));
    }
    assert!(Lattice::perturbed(domain(), 10, 10, false, false, KAPPA_MAX, 0).is_ok());
}

#[test]
fn mean_is_near_zero_and_spread_grows_with_kappa() {
    let (courses, wales) = (200, 200);
    let mut last_rms = 0.0;
    for kappa in [0.005f32, 0.01, 0.02] {
        let (mut sum, mut sq, mut n, mut max) = ([0.0f64; 2], 0.0f64, 0usize, 0.0f64);
        for seed in 0..4 {
            let f = Perturbation::new(courses, wales, false, false, kappa, seed).unwrap();
            assert_eq!(f.level_count(), MAX_LEVELS);
            for r in 0..courses + 2 {
                for c in 0..=wales {
                    let d = f.displacement(r, c);
                    sum[0] += d[0];
                    sum[1] += d[1];
                    sq += d[0] * d[0] + d[1] * d[1];
                    max = max.max(d[0].abs()).max(d[1].abs());
                    n += 1;
                }
            }
        }
        let mean = [sum[0] / n as f64, sum[1] / n as f64];
        let rms = (sq / n as f64).sqrt();
        println!(
            "kappa {kappa}: RMS displacement {rms:.4} tiles, mean ({:.4}, {:.4}), max |component| \
             {max:.4}",
            mean[0], mean[1]
        );
        assert!(mean[0].abs() < 0.2 * rms && mean[1].abs() < 0.2 * rms);
        assert!(rms > 1.5 * last_rms);
        last_rms = rms;
    }
}
