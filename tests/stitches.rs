//! Geometry of the stitch vocabulary: crossed, decreased, yarn-over, twisted and slipped
//! stitches clear each other on a flat sheet, a cylinder and a sphere.

use std::f32::consts::TAU;

use glam::Vec3;
use knitwear::knit::{KnitParams, PreparedKnit};
use knitwear::pattern::{Instruction as I, StitchPattern, WrittenRow};
use knitwear::skeleton::crossings::CrossingOrder;
use knitwear::surface::{GridSurface, PlaneSurface, Surface};

mod common;
use common::surfaces::grid;

fn rows(spec: &[(bool, Vec<I>)]) -> StitchPattern {
    let rows: Vec<WrittenRow> = spec
        .iter()
        .enumerate()
        .map(|(i, (rs, ins))| WrittenRow {
            number: i + 1,
            right_side: *rs,
            instructions: ins.clone(),
        })
        .collect();
    StitchPattern::from_written_rows("test", &rows).unwrap()
}

/// Key points of stitch (course, wale) of `pattern` on a regular lattice of unit tiles, 8
/// courses by 8 wales or the pattern's width if wider.
fn key_points_of(pattern: &StitchPattern, course: usize, wale: usize) -> [Vec3; 6] {
    use knitwear::lattice::Lattice;
    use knitwear::skeleton::{stitch_key_points, NormalOffsets};
    use knitwear::surface::UvRect;
    let wales = pattern.width().max(8);
    let domain = UvRect {
        min: glam::Vec2::ZERO,
        max: glam::Vec2::new(wales as f32, 8.0 + 2.0 * knitwear::lattice::ROW_OVERHANG),
    };
    let lattice = Lattice::regular(domain, 8, wales, false, false);
    let offsets = NormalOffsets::uniform(0.1);
    stitch_key_points(&lattice, pattern, &offsets, course, wale)
}

#[test]
fn cable_loops_lean_to_where_they_are_picked_up_and_cross_in_front_or_behind() {
    let (k, p) = (I::Knit, I::Purl);
    let rc = I::Cross {
        m: 2,
        n: 2,
        left: false,
        purl_back: false,
    };
    let cable = rows(&[
        (true, vec![k, k, k, k, p, p]),
        (false, vec![k, k, p, p, p, p]),
        (true, vec![rc, p, p]),
        (false, vec![k, k, p, p, p, p]),
    ]);
    // Row 3 is worked right to left: the cable over columns 2 to 5. Row 2 (course 1) holds
    // the loops it crosses: loops 2 and 3 travel right in front to columns 4 and 5, loops 4
    // and 5 left behind to 2 and 3.
    for (wale, dest) in [(2, 4.0), (3, 5.0), (4, 2.0), (5, 3.0)] {
        let kp = key_points_of(&cable, 1, wale);
        let straight = key_points_of(&cable, 0, wale);
        // Feet in their own column, head in the column it lands in.
        assert!(
            (kp[1].x - straight[1].x).abs() < 1e-5,
            "wale {wale}: {kp:?}"
        );
        assert!((kp[3].x - (dest + 0.5)).abs() < 1e-5, "wale {wale}: {kp:?}");
    }
    // The loops travelling right pass in front of those travelling left, legs and heads.
    for (front, back) in [(2, 4), (3, 5)] {
        let (f, b) = (
            key_points_of(&cable, 1, front),
            key_points_of(&cable, 1, back),
        );
        for i in 2..5 {
            assert!(f[i].z > b[i].z, "{f:?} in front of {b:?}");
        }
    }
}

/// "*ssk, yo" on an odd count of stitches: the last repeat's ssk falls off the sheet, and the
/// loop under its yarn-over, gathered by nothing, would be dropped (before this rule a
/// yarn-over stood over it, and at the add-on's irregularity its sinker crossed that loop's
/// head on the wrong side: 5 of 3,130 interlock crossings). A knitter works the stitch left
/// over plain; so does the skeleton, and every loop is held.
#[test]
fn a_yarn_over_whose_decrease_the_edge_cuts_off_is_knitted_plain() {
    use knitwear::lattice::Lattice;
    use knitwear::pattern::Form;
    use knitwear::skeleton::stitch_shape::knitted_form;
    use knitwear::surface::UvRect;
    let pattern = StitchPattern::from_knitspeak(
        "Row 1 (RS): Knit.\nRow 2: Purl.\nRow 3: *ssk, yo; rep from *.\nRow 4: Purl.",
    )
    .unwrap();
    let lattice_of = |wales: usize, cyclic: bool| {
        let domain = UvRect {
            min: glam::Vec2::ZERO,
            max: glam::Vec2::new(wales as f32, 12.0 + 2.0 * knitwear::lattice::ROW_OVERHANG),
        };
        Lattice::regular(domain, 12, wales, cyclic, false)
    };
    // Row 3 (course 2): yarn-overs in the even columns, the ssk right of each gathering the
    // loop under it; on 23 wales the last column's ssk would be column 23.
    let lattice = lattice_of(23, false);
    assert_eq!(pattern.stitch(2, 22).form, Form::YarnOver);
    assert_eq!(knitted_form(&lattice, &pattern, 2, 22), Form::Plain);
    for w in (0..22).step_by(2) {
        assert_eq!(
            knitted_form(&lattice, &pattern, 2, w),
            Form::YarnOver,
            "column {w}"
        );
    }
    // Round a tube of whole repeats every yarn-over stays one.
    assert_eq!(
        knitted_form(&lattice_of(24, true), &pattern, 2, 22),
        Form::YarnOver
    );
    // The knit: at the add-on's irregularity, every loop held and every crossing right.
    let sheet = PlaneSurface {
        width: 0.115,
        height: 0.12,
    };
    for live_loops in [true, false] {
        let p = KnitParams {
            threads: Some(2),
            kappa: ADDON_KAPPA,
            live_loops,
            ..KnitParams::default()
        };
        let knit = PreparedKnit::new(&sheet, &pattern, &p).unwrap();
        let order = knit.crossing_order(&sheet).unwrap();
        assert_eq!(order.interlock_agree, order.interlock_decided, "{order:?}");
        assert_eq!(order.agree, order.decided, "{order:?}");
        // With live loops only the top course's loops and the first course's feet are free.
        let free = if live_loops { 23 } else { 0 };
        assert_eq!(
            (order.free_loops, order.free_feet),
            (free, free),
            "{order:?}"
        );
    }
}

#[test]
fn a_yarn_over_stops_short_over_a_hole_and_a_decrease_gathers_two_heads() {
    let (k, p) = (I::Knit, I::Purl);
    let eyelet = rows(&[
        (true, vec![k, k, k, k]),
        (false, vec![p, p, p, p]),
        (true, vec![I::YarnOver, I::K2tog, I::YarnOver, I::K2tog]),
        (false, vec![p, p, p, p]),
    ]);
    // Row 3 (course 2) is worked right to left: a yo in column 1, a k2tog in column 0.
    let yo = key_points_of(&eyelet, 2, 1);
    let knit = key_points_of(&eyelet, 0, 0);
    assert!(
        yo[1].y > knit[1].y + 0.4 && yo[5].y > knit[5].y + 0.4,
        "{yo:?} vs {knit:?}"
    );
    // Both loops of row 2 (course 1) land in column 0, one in front of the other.
    let (a, b) = (key_points_of(&eyelet, 1, 0), key_points_of(&eyelet, 1, 1));
    assert!(
        (a[3].x - 0.5).abs() < 1e-5 && (b[3].x - 0.5).abs() < 1e-5,
        "{a:?} {b:?}"
    );
    assert!(a[3].z > b[3].z, "k2tog: the left loop on top: {a:?} {b:?}");
}

fn cylinder() -> GridSurface {
    // Radius 3 cm, 8 cm tall, knitted in the round (cyclic u).
    grid(16, 96, true, |u, v| {
        let a = TAU * u;
        (
            Vec3::new(0.03 * a.cos(), 0.03 * a.sin(), 0.08 * v),
            Vec3::new(a.cos(), a.sin(), 0.0),
        )
    })
}

fn sphere_band() -> GridSurface {
    // Radius 5 cm between latitudes -50 and +50 degrees.
    grid(80, 128, true, |u, v| {
        let a = TAU * u;
        let lat = (v - 0.5) * (100.0f32).to_radians();
        let n = Vec3::new(lat.cos() * a.cos(), lat.cos() * a.sin(), lat.sin());
        (0.05 * n, n)
    })
}

fn measured(surface: &dyn Surface, pattern: &StitchPattern) -> (f32, CrossingOrder) {
    measured_at(surface, pattern, KnitParams::default().kappa)
}

/// [`measured`] with irregularity `kappa`.
fn measured_at(surface: &dyn Surface, pattern: &StitchPattern, kappa: f32) -> (f32, CrossingOrder) {
    // Default settings: the default gauge (20 stitches, 28 rows per 10 cm) and yarn.
    let p = KnitParams {
        threads: Some(2),
        measure_clearance: true,
        kappa,
        ..KnitParams::default()
    };
    let knit = PreparedKnit::new(surface, pattern, &p).unwrap();
    let out = knit.build(surface).unwrap();
    (
        out.stats.clearance.unwrap().0,
        knit.crossing_order(surface).unwrap(),
    )
}

/// The clearance every preset keeps, in yarn diameters, with every course interlocked
/// (docs/design.md section 3). The earlier floor of 0.95 was reached by flipping sinkers and leg
/// tops to the wrong side of the fabric (courses stacked like roof shingles); inside the
/// interlock the tuned key-point offsets and loop shapes reach less, and this floor records
/// what they keep so that it cannot fall further. Raising it to 0.95 is the open work of
/// "Knitted, not stacked" (relaxed loop shapes).
const CLEARANCE_TARGET: f32 = CLEARANCE_FLOOR;

/// The least clearance any preset keeps on any of the test surfaces (see
/// [`CLEARANCE_TARGET`]).
const CLEARANCE_FLOOR: f32 = 0.05;

/// Plain knit/purl textures (no crossing, decrease or yarn-over) keep more.
const PLAIN_CLEARANCE_FLOOR: f32 = 0.3;

/// Slipped-stitch textures without crossings (linen stitch) keep less than plain ones at
/// their cast-on: its loop under a slipped stitch rises to the second course, its head
/// beside the first course's leg tops where the first course's yarn also carries the float in
/// front. With the quarter-stitch yarn linen's fabric keeps 0.44 diameters and its cast-on
/// 0.258 on the sheet and 0.231 on the sphere (0.37 with the thinner yarn of before); the
/// floor records it so that it cannot fall further.
const SLIP_CLEARANCE_FLOOR: f32 = 0.2;

/// Every preset on a flat sheet, a cylinder and a sphere at default settings: every course
/// interlocks with the one below at every crossing (docs/design.md section 3), the crossings each
/// stitch's own rule decides are the right way round, and the independent check of section 7
/// holds: in nearly every stitch-wide bucket of a course's crossings with the course below,
/// the upper course is in front at about half of them. Clearance keeps its floor.
#[test]
fn every_preset_crosses_as_its_pattern_says() {
    let plane = PlaneSurface {
        width: 0.12,
        height: 0.1,
    };
    let cyl = cylinder();
    let sphere = sphere_band();
    let mut failures = Vec::new();
    for name in StitchPattern::presets() {
        let pattern = StitchPattern::preset(name).unwrap();
        let (flat, order_flat) = measured(&plane, &pattern);
        let (round, order_round) = measured(&cyl, &pattern);
        let (ball, order_ball) = measured(&sphere, &pattern);
        println!(
            "{name:20} clearance flat {flat:.3} cylinder {round:.3} sphere {ball:.3}; interlock \
             {}/{}, {}/{}, {}/{}; half-front buckets {}/{}",
            order_flat.interlock_agree,
            order_flat.interlock_decided,
            order_round.interlock_agree,
            order_round.interlock_decided,
            order_ball.interlock_agree,
            order_ball.interlock_decided,
            order_flat.buckets_half_front,
            order_flat.buckets,
        );
        let floor = if pattern.has_crossings() {
            CLEARANCE_TARGET
        } else if has_slips(&pattern) {
            SLIP_CLEARANCE_FLOOR
        } else {
            PLAIN_CLEARANCE_FLOOR
        };
        for (surface, c) in [("sheet", flat), ("cylinder", round), ("sphere", ball)] {
            if c < floor {
                failures.push(format!(
                    "{name} on the {surface}: clearance {c:.3} < {floor}"
                ));
            }
        }
        for (surface, order) in [
            ("sheet", &order_flat),
            ("cylinder", &order_round),
            ("sphere", &order_ball),
        ] {
            if order.interlock_decided == 0 {
                failures.push(format!("{name} on the {surface}: no interlock crossings"));
            }
            if order.agree != order.decided || order.interlock_agree != order.interlock_decided {
                failures.push(format!(
                    "{name} on the {surface}: {:?}",
                    order.first_disagreement
                ));
            }
            // A stacked course has the upper course in front at all of a bucket's crossings.
            // docs/design.md section 7 makes the claim for knit/purl mixes: a yarn-over holds no
            // loop below it, and the loops gathered beside it pass its column on their
            // pullers' face side only, so lace keeps it in fewer buckets (lace diamond
            // measured 0.88 on all three surfaces).
            let (part, of) = if has_yarn_overs(&pattern) {
                (17, 20)
            } else {
                (9, 10)
            };
            if of * order.buckets_half_front < part * order.buckets {
                failures.push(format!(
                    "{name} on the {surface}: {} of {} buckets half in front",
                    order.buckets_half_front, order.buckets
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Whether any stitch of `pattern` is slipped.
fn has_slips(pattern: &StitchPattern) -> bool {
    use knitwear::pattern::Form;
    (0..pattern.height()).any(|c| {
        (0..pattern.width()).any(|w| matches!(pattern.stitch(c, w).form, Form::Slip { .. }))
    })
}

/// Whether any stitch of `pattern` is a yarn-over or a made stitch (no loop below it).
fn has_yarn_overs(pattern: &StitchPattern) -> bool {
    use knitwear::pattern::Form;
    (0..pattern.height()).any(|c| {
        (0..pattern.width())
            .any(|w| matches!(pattern.stitch(c, w).form, Form::YarnOver | Form::MakeOne))
    })
}

/// A course laid wholly over the one below (the roof shingle this project once knitted) is
/// caught by the interlock measure at half its crossings, and by the bucket check in every
/// bucket: the measure only the right structure passes.
#[test]
fn a_stacked_course_fails_the_interlock() {
    use knitwear::lattice::Lattice;
    use knitwear::skeleton::crossings::crossing_order;
    use knitwear::skeleton::{sample_piece_uv, yarn_pieces, NormalOffsets, SplineSampling};
    use knitwear::surface::UvRect;
    let pattern = StitchPattern::preset("stockinette").unwrap();
    let (courses, wales) = (8, 8);
    let domain = UvRect {
        min: glam::Vec2::ZERO,
        max: glam::Vec2::new(1.0, 1.0),
    };
    let lattice = Lattice::regular(domain, courses, wales, false, false);
    let pieces = yarn_pieces(&lattice, &vec![true; courses * wales]);
    let sampling = SplineSampling {
        samples_per_loop: 24,
        tension: 0.0,
        aspect: 1.0,
    };
    let lines = |offsets: &NormalOffsets| -> Vec<Vec<Vec3>> {
        pieces
            .iter()
            .map(|p| {
                let n = p.sample_count(24);
                let mut uvl = vec![Vec3::ZERO; n];
                let mut own = vec![0u32; n];
                sample_piece_uv(
                    &PlaneSurface {
                        width: 1.0,
                        height: 1.0,
                    },
                    &lattice,
                    &pattern,
                    offsets,
                    &sampling,
                    p,
                    &mut uvl,
                    &mut own,
                );
                uvl
            })
            .collect()
    };
    // The interlock's signs: legs in front, head and sinker behind.
    let right = NormalOffsets::uniform(0.5);
    let order = crossing_order(&lattice, &pattern, &pieces, &lines(&right), 24);
    assert!(order.interlock_decided > 0, "{order:?}");
    assert_eq!(order.interlock_agree, order.interlock_decided, "{order:?}");
    assert_eq!(order.buckets_half_front, order.buckets, "{order:?}");
    // The stacked knit: sinker and leg tops flipped (what the clearance tuning once chose).
    let mut stacked = NormalOffsets::uniform(0.5);
    stacked.x[0] = -0.5;
    stacked.x[2] = -0.5;
    stacked.x[4] = -0.5;
    let order = crossing_order(&lattice, &pattern, &pieces, &lines(&stacked), 24);
    let fraction = order.interlock();
    assert!((0.4..0.6).contains(&fraction), "{order:?}");
    assert_eq!(order.buckets_half_front, 0, "{order:?}");
}

/// The add-on's default irregularity (kappa 0.005, `blender_addon/properties.py`): the
/// perturbation of hand knitting narrows some stitches and skews others, and every preset
/// still clears the target on the three surfaces (the tuning's margins: `TIGHT_QUANTILE`,
/// the relief's `TARGET`, the tuning's `ENOUGH`).
#[test]
fn every_preset_clears_with_the_add_ons_irregularity() {
    let plane = PlaneSurface {
        width: 0.12,
        height: 0.1,
    };
    let (cyl, sphere) = (cylinder(), sphere_band());
    let mut failures = Vec::new();
    for name in StitchPattern::presets() {
        let pattern = StitchPattern::preset(name).unwrap();
        let surfaces: [(&str, &dyn Surface); 3] =
            [("sheet", &plane), ("cylinder", &cyl), ("sphere", &sphere)];
        let mut line = format!("{name:20} kappa 0.005:");
        for (surface, s) in surfaces {
            let (c, _) = measured_at(s, &pattern, ADDON_KAPPA);
            line += &format!(" {surface} {c:.3}");
            if c < CLEARANCE_TARGET {
                failures.push(format!("{name} on the {surface}: clearance {c:.3}"));
            }
        }
        println!("{line}");
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The add-on's default Irregularity.
const ADDON_KAPPA: f32 = 0.005;

/// Flat pieces whose width cuts the repeat of a cable, a decrease or a lace (the wales past
/// the last whole repeat are knitted straight) clear the target too, on sheets of other
/// sizes than the one above: 24 x 34 and 25 x 35 stitches at the default gauge. Before the
/// edge corrections, feather and fan measured 0.934 on the first and the horseshoe and
/// honeycomb cables 0.946 and 0.929 on the second.
#[test]
fn pieces_that_cut_a_repeat_clear_the_target() {
    let sheets = [(0.12, 0.12), (0.125, 0.125)];
    let mut failures = Vec::new();
    let mut cut = 0;
    for name in StitchPattern::presets() {
        let pattern = StitchPattern::preset(name).unwrap();
        if !pattern.has_crossings() {
            continue;
        }
        for (width, height) in sheets {
            let plane = PlaneSurface { width, height };
            let wales = (width / 0.005_f32).round() as usize;
            if wales % pattern.width() == 0 {
                continue;
            }
            cut += 1;
            let (c, order) = measured(&plane, &pattern);
            println!("{name:20} {width} x {height} m: clearance {c:.3}");
            if c < CLEARANCE_TARGET {
                failures.push(format!("{name} on {width} x {height}: clearance {c:.3}"));
            }
            if order.agree != order.decided {
                failures.push(format!("{name} on {width} x {height}: {order:?}"));
            }
        }
    }
    assert!(cut >= 10, "only {cut} pieces cut a repeat");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Stranded colourwork: a colour skipped between two of its stitches floats behind them.
#[test]
fn fair_isle_floats_run_behind_the_fabric_in_their_own_colour() {
    use knitwear::pattern::ColorPattern;
    let palette = vec![[0.8, 0.1, 0.1], [0.9, 0.9, 0.8]];
    // Row 1: three red, one cream; row 2: all cream (no floats).
    let colors = ColorPattern::new(palette, "1111\n0001").unwrap();
    let plane = PlaneSurface {
        width: 0.08,
        height: 0.05,
    };
    let stockinette = StitchPattern::preset("stockinette").unwrap();
    let p = KnitParams {
        courses: Some(8),
        wales: Some(16),
        threads: Some(2),
        measure_clearance: true,
        colors: Some(colors),
        ..KnitParams::default()
    };
    let knit = PreparedKnit::new(&plane, &stockinette, &p).unwrap();
    let out = knit.build(&plane).unwrap();
    // 4 two-colour courses x (cream floats over 3 red stitches between cream ones: 3 per
    // course, and red floats over the 1 cream stitch between red ones: 3 per course), and
    // the cast-on and the bind-off.
    assert_eq!(out.stats.yarn_pieces, 8 + 4 * 6 + 2, "{:?}", out.stats);
    // Floats are behind the surface (z < 0 on the plane), in the colour they carry.
    let courses = &out.yarn_course;
    assert_eq!(courses.len(), out.stats.yarn_pieces);
    let (min, _) = out.stats.clearance.unwrap();
    assert!(min >= PLAIN_CLEARANCE_FLOOR, "clearance {min}");
    let order = knit.crossing_order(&plane).unwrap();
    assert!(
        order.decided > 0 && order.agree == order.decided,
        "{order:?}"
    );
    let behind = out
        .positions
        .chunks(3)
        .filter(|v| v[2] < -2.0 * knit.yarn_radius())
        .count();
    assert!(behind > 0, "no yarn runs behind the fabric");
}

/// Knitted in the round from the gauge, a pattern goes round a whole number of times (as a
/// knitter casts on a multiple of the repeat), so the seam cuts no cable; counts given
/// explicitly are kept as given.
#[test]
fn in_the_round_the_gauge_gives_whole_repeats() {
    let cyl = cylinder(); // 18.85 cm round: 37.7 stitches at 20 per 10 cm
    for (name, wales) in [("stockinette", 38), ("cable_c6", 40), ("cable_c4", 36)] {
        let pattern = StitchPattern::preset(name).unwrap();
        let knit = PreparedKnit::new(&cyl, &pattern, &KnitParams::default()).unwrap();
        assert_eq!(knit.stats().wales, wales, "{name}");
        assert_eq!(knit.stats().wales % pattern.width(), 0, "{name}");
    }
    let c6 = StitchPattern::preset("cable_c6").unwrap();
    let given = KnitParams {
        wales: Some(38),
        ..KnitParams::default()
    };
    assert_eq!(
        PreparedKnit::new(&cyl, &c6, &given).unwrap().stats().wales,
        38
    );
    // Flat, the count is the gauge's: the edges need no whole repeats.
    let plane = PlaneSurface {
        width: 0.19,
        height: 0.08,
    };
    let flat = PreparedKnit::new(&plane, &c6, &KnitParams::default()).unwrap();
    assert_eq!(flat.stats().wales, 38);
}

/// A repeat larger than the tuning's plain stand-in takes over
/// (`knitwear::skeleton::tuning::MAX_TUNED_CELLS`) whose loops lean is tuned whole: a 4/4
/// cable in a 12 x 24 repeat tuned on a plain window (every loop straight) knitted 8 of its
/// 2,815 interlock crossings the wrong way round, at 0.006 diameters of clearance.
#[test]
fn a_cable_in_a_repeat_beyond_the_plain_stand_in_is_tuned_whole_and_interlocks() {
    use knitwear::skeleton::tuning::MAX_TUNED_CELLS;
    let pattern = StitchPattern::from_knitspeak(
        "Rows 1, 3, 5, 7, 9, 11, 15, 17, 19, 21, and 23 (RS): P2, k8, p2.\n\
         Rows 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, and 24: K2, p8, k2.\n\
         Row 13: P2, 4/4 RC, p2.",
    )
    .unwrap();
    assert!(pattern.width() * pattern.height() > MAX_TUNED_CELLS);
    assert!(!pattern.is_plain_loops());
    let (clearance, order) = knitted_as_written_on_a_sheet(&pattern);
    assert_eq!(order.free_loops, 0);
    assert!(clearance >= 0.25, "{clearance}");
}

/// A 4/4 cable in a 16-row repeat on 24 wales, knitted to 54 and to 60 courses of a 12 x 20 cm
/// sheet: sizes whose stitch proportions tune differently from the 12 x 10 cm sheet's. There a
/// cable loop's head once stood in front of the leg pulled through it (24 of 5,798 crossings
/// wrong), and later two loops of the 60-course bind-off were left free (before commit
/// 5c1c7cc). Every crossing is the right way round at both, with no loop or foot left free.
#[test]
fn a_4_4_cable_interlocks_at_the_sizes_where_a_head_once_stood_in_front() {
    let pattern = StitchPattern::from_knitspeak(
        "Rows 1, 3, 5, 7, 9, 11, and 15 (RS): P2, k8, p2.\n\
         Rows 2, 4, 6, 8, 10, 12, 14, and 16: K2, p8, k2.\n\
         Row 13: P2, 4/4 RC, p2.",
    )
    .unwrap();
    let plane = PlaneSurface {
        width: 0.12,
        height: 0.2,
    };
    for courses in [54, 60] {
        let p = KnitParams {
            threads: Some(2),
            courses: Some(courses),
            wales: Some(24),
            ..KnitParams::default()
        };
        let order = PreparedKnit::new(&plane, &pattern, &p)
            .unwrap()
            .crossing_order(&plane)
            .unwrap();
        println!("{courses} courses: {order:?}");
        assert_eq!(
            order.agree, order.decided,
            "{courses} courses: {:?}",
            order.first_disagreement
        );
        assert_eq!(order.interlock_agree, order.interlock_decided);
        assert!(order.interlock_decided > 5000, "{courses} courses");
        assert_eq!(
            (order.free_loops, order.free_feet),
            (0, 0),
            "{courses} courses"
        );
    }
}

/// Loops leaning three columns or more (3/3 and 4/4 cables, the horseshoe's 3/3 pair) cross
/// no yarn of their own course but as the cable says: their heads do not curl round
/// themselves, nor do the sinkers between them, nor do neighbouring legs cross. With uniform
/// spline knots their heads crossed themselves 54, 96 and 76 times on this sheet
/// (`skeleton::knot_spacing`).
#[test]
fn loops_leaning_three_columns_or_more_neither_curl_nor_cross_their_neighbours() {
    let cables = [
        (
            "3/3 LC",
            "Rows 1, 3, and 7 (RS): P2, *k6, p2; rep from *.\n\
             Rows 2, 4, 6, and 8: K2, *p6, k2; rep from *.\n\
             Row 5: P2, *3/3 LC, p2; rep from *.",
        ),
        (
            "4/4 RC",
            "Rows 1, 3, 7, and 9 (RS): P2, *k8, p2; rep from *.\n\
             Rows 2, 4, 6, 8, and 10: K2, *p8, k2; rep from *.\n\
             Row 5: P2, *4/4 RC, p2; rep from *.",
        ),
        (
            "horseshoe",
            "Rows 1 and 5 (RS): P2, k12, p2.\n\
             Rows 2, 4, 6, and 8: K2, p12, k2.\n\
             Row 3: P2, 3/3 RC, 3/3 LC, p2.\n\
             Row 7: P2, k12, p2.",
        ),
    ];
    for (name, text) in cables {
        let pattern = StitchPattern::from_knitspeak(text).unwrap();
        let (_, order) = knitted_as_written_on_a_sheet(&pattern);
        assert_eq!(order.undecided, 0, "{name}");
        assert_eq!((order.free_loops, order.free_feet), (0, 0), "{name}");
    }
}

/// The C6 preset on the 12 x 10 cm sheet ends two rows above a crossing (28 courses of an
/// 8-row repeat): its cable columns are half a row over at the top, the purl columns beside
/// them not at all. Ramped out alike, the purl columns' top stood half a row lower than the
/// cables', in the one tile beside each cable, and the bind-off over that step curled over
/// itself: 8 crossings of the chain with itself and a clearance of 0.181 diameters. A column
/// no loop leans across now keeps regular rows up to the top (`RowHeights::leaning`): 0 and
/// 0.450.
#[test]
fn a_cable_sheet_ending_inside_its_repeat_binds_off_without_curling() {
    let pattern = StitchPattern::preset("cable_c6").unwrap();
    let (clearance, order) = knitted_as_written_on_a_sheet(&pattern);
    assert_eq!(order.undecided, 0);
    assert_eq!((order.free_loops, order.free_feet), (0, 0));
    assert!(clearance > 0.4, "{clearance}");
}

/// `pattern` knitted on a 12 x 10 cm sheet at default settings, with every crossing the
/// right way round and more than 2,000 interlock crossings; its clearance and crossings.
fn knitted_as_written_on_a_sheet(pattern: &StitchPattern) -> (f32, CrossingOrder) {
    let plane = PlaneSurface {
        width: 0.12,
        height: 0.1,
    };
    let (clearance, order) = measured(&plane, pattern);
    println!("clearance {clearance:.3}, {order:?}");
    assert_eq!(order.agree, order.decided, "{:?}", order.first_disagreement);
    assert_eq!(order.interlock_agree, order.interlock_decided);
    assert!(order.interlock_decided > 2000);
    (clearance, order)
}

/// A cross around a centre (`1/1/1 LPC`, `2/1/2 RPC`): the front group lands across the
/// centre and passes in front of everything, the other side group passes behind it but in
/// front of the centre, which stays in its columns behind both, purled. Knitted, every course
/// interlocks and every loop crosses as the pattern says.
#[test]
fn a_centre_cross_passes_its_groups_in_front_of_the_centre_and_interlocks() {
    let pattern = StitchPattern::from_knitspeak(
        "Row 1 (RS): *P2, 1/1/1 LPC, p2, 2/1/2 RPC; rep from *.\n\
         Rows 2 and 4 (WS): *P2, k1, p2, k2, p1, k1, p1, k2; rep from *.\n\
         Row 3: *P2, k1, p1, k1, p2, k2, p1, k2; rep from *.",
    )
    .unwrap();
    // Right-side columns, left to right: the 2/1/2 RPC over 0..=4, p2, the 1/1/1 LPC over
    // 7..=9, p2. Course 3 (row 4) holds the loops row 1 of the next repeat crosses.
    let lands = |wale: usize| {
        let s = pattern.stitch(3, wale);
        (s.land_offset, s.land_layer)
    };
    // 2/1/2 RPC: loops 0 and 1 travel right in front, 3 and 4 left behind them, the centre
    // stays, behind both; 1/1/1 LPC: loop 9 travels left in front, 7 right behind it.
    for (wale, want) in [
        (0, (3, 2)),
        (1, (3, 2)),
        (2, (0, -1)),
        (3, (-3, 1)),
        (4, (-3, 1)),
        (9, (-2, 2)),
        (8, (0, -1)),
        (7, (2, 1)),
    ] {
        assert_eq!(lands(wale), want, "wale {wale}");
    }
    for wale in [2, 8] {
        assert_eq!(pattern.stitch(0, wale).face, knitwear::pattern::Face::Purl);
    }
    // The shape: the front group's leg tops stand in front of the back group's, and those in
    // front of the centre's.
    for (front, middle, centre) in [(0, 3, 2), (9, 7, 8)] {
        let f = key_points_of(&pattern, 3, front);
        let m = key_points_of(&pattern, 3, middle);
        let c = key_points_of(&pattern, 3, centre);
        assert!(f[2].z > m[2].z && m[2].z > c[2].z, "{f:?} {m:?} {c:?}");
    }
    let (clearance, order) = knitted_as_written_on_a_sheet(&pattern);
    assert_eq!((order.free_loops, order.free_feet), (0, 0));
    assert!(clearance >= CLEARANCE_FLOOR, "{clearance}");
}
