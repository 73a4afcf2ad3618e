//! The cast-on and the bind-off (src/skeleton/edges.rs, issue "Knitted, not stacked" item 4):
//! at an open end no loop hangs free, and the fabric between the edges is knitted exactly as
//! with live loops.

use std::f32::consts::TAU;

use glam::Vec3;
use knitwear::knit::{KnitOutput, KnitParams, PreparedKnit};
use knitwear::pattern::StitchPattern;
use knitwear::skeleton::crossings::CrossingOrder;
use knitwear::surface::{PlaneSurface, Surface};

mod common;
use common::surfaces::grid;

/// Presets with every kind of stitch the edges meet: knit and purl faces and their
/// boundaries, slipped stitches on the first row, yarn-overs and decreases, cables, bobbles.
const PRESETS: &[&str] = &[
    "stockinette",
    "garter",
    "rib_1x1",
    "seed",
    "linen_stitch",
    "cable_c4",
    "lace_diamond",
    "eyelet_rows",
    "bobbles",
];

fn knit(
    surface: &dyn Surface,
    pattern: &StitchPattern,
    live_loops: bool,
) -> (PreparedKnit, KnitOutput, CrossingOrder) {
    let p = KnitParams {
        threads: Some(2),
        live_loops,
        ..KnitParams::default()
    };
    let knit = PreparedKnit::new(surface, pattern, &p).unwrap();
    let out = knit.build(surface).unwrap();
    let order = knit.crossing_order(surface).unwrap();
    (knit, out, order)
}

/// A tube knitted in the round, open at both ends: radius 3 cm, 8 cm tall.
fn tube() -> knitwear::surface::GridSurface {
    grid(16, 96, true, |u, v| {
        let a = TAU * u;
        (
            Vec3::new(0.03 * a.cos(), 0.03 * a.sin(), 0.08 * v),
            Vec3::new(a.cos(), a.sin(), 0.0),
        )
    })
}

/// Finished, every loop is held (each interlock crossing of the cast-on, the bind-off and
/// the bind-off's chain agreeing with its rule) and every stitch is pulled through a loop;
/// with live loops, the last course's loops and the first course's feet hang free, so the
/// measure is one a wrong edge fails.
#[test]
fn finished_edges_hold_every_loop_and_live_loops_hang_free() {
    let sheet = PlaneSurface {
        width: 0.06,
        height: 0.05,
    };
    let tube = tube();
    let surfaces: [(&str, &dyn Surface); 2] = [("sheet", &sheet), ("tube", &tube)];
    let mut failures = Vec::new();
    for name in PRESETS {
        let pattern = StitchPattern::preset(name).unwrap();
        for (surface_name, surface) in surfaces {
            let (prepared, _, finished) = knit(surface, &pattern, false);
            let (_, _, live) = knit(surface, &pattern, true);
            let wales = prepared.lattice().wales;
            println!(
                "{name:14} {surface_name:5}: finished: free loops {}/{}, free feet {}/{}, \
                 interlock {}/{}; live: free loops {}/{}, free feet {}/{}",
                finished.free_loops,
                finished.loops,
                finished.free_feet,
                finished.feet,
                finished.interlock_agree,
                finished.interlock_decided,
                live.free_loops,
                live.loops,
                live.free_feet,
                live.feet,
            );
            if finished.free_loops != 0 || finished.free_feet != 0 {
                failures.push(format!("{name} on the {surface_name}: {finished:?}"));
            }
            if finished.agree != finished.decided
                || finished.interlock_agree != finished.interlock_decided
            {
                failures.push(format!(
                    "{name} on the {surface_name}: {:?}",
                    finished.first_disagreement
                ));
            }
            // Live: the top loop of every column (the last course's, or under a slipped
            // stitch the loop it carries up from the course below) and the first course's
            // feet (a yarn-over has none) are free, and nothing else.
            if live.free_loops != wales || live.free_feet == 0 || live.free_feet > wales {
                failures.push(format!(
                    "{name} on the {surface_name}, live loops: {} free loops (want {wales}), {} \
                     free feet",
                    live.free_loops, live.free_feet
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The edges are extra yarn only: every piece of the fabric is sampled to the same bits as
/// with live loops, so the edges take nothing from the fabric's clearance or interlock.
#[test]
fn the_fabric_between_the_edges_is_knitted_as_with_live_loops() {
    let sheet = PlaneSurface {
        width: 0.05,
        height: 0.04,
    };
    for name in ["stockinette", "cable_c4"] {
        let pattern = StitchPattern::preset(name).unwrap();
        let (_, finished, _) = knit(&sheet, &pattern, false);
        let (_, live, _) = knit(&sheet, &pattern, true);
        let pieces = live.yarn_closed.len();
        assert_eq!(
            finished.yarn_closed.len(),
            pieces + 2,
            "{name}: one cast-on and one bind-off"
        );
        let end = live.yarn_offsets[pieces] as usize * 3;
        assert_eq!(
            finished.centerline[..end],
            live.centerline[..end],
            "{name}: the fabric's centrelines"
        );
        assert_eq!(finished.yarn_offsets[..=pieces], live.yarn_offsets[..]);
        assert!(finished.centerline.len() > end);
    }
}

/// The edges stay within about two thirds of a row of the fabric's first and last courses,
/// hanging at most three quarters of a row past the surface's border (the bind-off sits on
/// the last course's heads, which reach a third of a row into the row above), and follow
/// the sheet's plane.
#[test]
fn the_edges_hug_the_border() {
    let sheet = PlaneSurface {
        width: 0.06,
        height: 0.05,
    };
    let pattern = StitchPattern::preset("stockinette").unwrap();
    let (_, out, _) = knit(&sheet, &pattern, false);
    let row = out.stats.stitch_height;
    let pieces = out.yarn_closed.len();
    for (i, want_bottom) in [(pieces - 2, true), (pieces - 1, false)] {
        let (a, b) = (
            out.yarn_offsets[i] as usize,
            out.yarn_offsets[i + 1] as usize,
        );
        let points: Vec<Vec3> = out.centerline[3 * a..3 * b]
            .chunks(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect();
        let (lo, hi) = points.iter().fold((f32::MAX, f32::MIN), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
        let border = if want_bottom { 0.0 } else { 0.05 };
        let (near, far) = if want_bottom { (hi, lo) } else { (lo, hi) };
        assert!(
            (far - border).abs() < 0.75 * row,
            "piece {i}: reaches {far} past the border {border} (row {row})"
        );
        assert!(
            (near - border).abs() < 1.5 * row,
            "piece {i}: {near} is more than a row and a half inside the border"
        );
        let thickness = points.iter().fold(0.0f32, |m, p| m.max(p.z.abs()));
        assert!(
            thickness < 3.0 * 2.0 * out.yarn_radius,
            "off the plane: {thickness}"
        );
    }
}

/// Between their key points the edges' yarn and the fabric's can both be on their way from
/// one side to the other where they cross, and the stitch irregularity slides such a
/// crossing to where their depths meet: feather and fan's bind-off came within 0.025
/// diameters of its gathered loops on a 12 cm sheet at the add-on's irregularity. Kept clear
/// (src/skeleton/edge_clearance.rs), the finished knit's closest pair is the fabric's own,
/// with every crossing still the right way round and no loop free.
#[test]
fn the_edges_come_no_closer_than_the_fabric_itself() {
    let sheet = PlaneSurface {
        width: 0.12,
        height: 0.12,
    };
    let pattern = StitchPattern::preset("feather_and_fan").unwrap();
    let clearance = |live_loops: bool| {
        let p = KnitParams {
            threads: Some(2),
            kappa: 0.005,
            measure_clearance: true,
            live_loops,
            ..KnitParams::default()
        };
        let knit = PreparedKnit::new(&sheet, &pattern, &p).unwrap();
        let out = knit.build(&sheet).unwrap();
        let order = knit.crossing_order(&sheet).unwrap();
        (out.stats.clearance.unwrap().0, order)
    };
    let (fabric, _) = clearance(true);
    let (finished, order) = clearance(false);
    println!("feather and fan, 12 cm at kappa 0.005: fabric {fabric:.3}, finished {finished:.3}");
    assert!(finished >= 0.99 * fabric, "{finished} < {fabric}");
    assert_eq!(order.interlock_agree, order.interlock_decided, "{order:?}");
    assert_eq!((order.free_loops, order.free_feet), (0, 0), "{order:?}");
}

/// A bind-off holds every loop whichever row of the pattern the fabric ends on. Under a
/// cable's crossing row the last course's loops lean, and the tuned row heights make that
/// course short at some node columns and tall at others. The corpus's six-stitch left cable
/// (`tests/data/corpus/cable-6.ks`, a 3/3 LC on row 5 of 8) bound off on row 4, 28 courses
/// up a 12 cm sheet, left the chain loop beside each cable unheld (3 loops): its
/// neighbour's head lay over above the short loop's leg instead of across it. Every course
/// count of one repeat of rows, each at the default gauge's stitch size (so all share one
/// tuning), and the 3/3 cable preset (a C6B on row 3) likewise.
#[test]
fn a_bind_off_holds_every_loop_on_any_row_of_a_cable() {
    let corpus = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/corpus/cable-6.ks"
    ))
    .unwrap();
    let patterns = [
        ("cable-6.ks", StitchPattern::from_text(&corpus).unwrap(), 24),
        ("cable_c6", StitchPattern::preset("cable_c6").unwrap(), 16),
    ];
    let mut failures = Vec::new();
    for (name, pattern, wales) in patterns {
        let rows = pattern.height();
        for courses in 3 * rows..4 * rows {
            let sheet = PlaneSurface {
                width: wales as f32 * 0.005,
                height: courses as f32 * 0.1 / 28.0,
            };
            let p = KnitParams {
                threads: Some(2),
                courses: Some(courses),
                wales: Some(wales),
                ..KnitParams::default()
            };
            let knit = PreparedKnit::new(&sheet, &pattern, &p).unwrap();
            let order = knit.crossing_order(&sheet).unwrap();
            println!(
                "{name:10} {courses:2} courses: free loops {}/{}, free feet {}/{}, chain and \
                 crossings {}/{}",
                order.free_loops,
                order.loops,
                order.free_feet,
                order.feet,
                order.agree,
                order.decided
            );
            if (order.free_loops, order.free_feet) != (0, 0) || order.agree != order.decided {
                failures.push(format!("{name}, {courses} courses: {order:?}"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// A 4/4 cable's crossing row is three rows tall over its node columns, with regular rows
/// beside it. Bound off on that row, the chain loop over the cable's last tall column stood
/// three rows tall and the next one a row: the tall loop's head, brought down to its short
/// neighbour's height, passed above that neighbour's leg top, and nothing held the tall loop
/// (2 free loops of 719 on a 24-wale sheet of 28 courses, and of 1,103 at 44). The next loop's
/// left leg now stands as tall as the loop before it.
#[test]
fn a_bind_off_over_a_wide_cables_tall_row_holds_every_loop() {
    let pattern = StitchPattern::from_knitspeak(
        "Rows 1, 3, 5, 7, 9, 11, and 15 (RS): P2, k8, p2.\n\
         Rows 2, 4, 6, 8, 10, 12, 14, and 16: K2, p8, k2.\n\
         Row 13: P2, 4/4 RC, p2.",
    )
    .unwrap();
    let mut failures = Vec::new();
    // Both end on row 12, the (wrong-side) row under the cable row: its loops lean.
    for courses in [28, 44] {
        let sheet = PlaneSurface {
            width: 24.0 * 0.005,
            height: courses as f32 * 0.1 / 28.0,
        };
        let p = KnitParams {
            threads: Some(2),
            courses: Some(courses),
            wales: Some(24),
            ..KnitParams::default()
        };
        let knit = PreparedKnit::new(&sheet, &pattern, &p).unwrap();
        let order = knit.crossing_order(&sheet).unwrap();
        println!(
            "{courses} courses: free loops {}/{}, crossings {}/{}",
            order.free_loops, order.loops, order.agree, order.decided
        );
        if (order.free_loops, order.free_feet) != (0, 0) || order.agree != order.decided {
            failures.push(format!("{courses} courses: {order:?}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
