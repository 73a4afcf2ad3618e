//! Geometry of the stitch vocabulary: crossed, decreased, yarn-over, twisted and slipped
//! stitches clear each other on a flat sheet, a cylinder and a sphere.

use std::f32::consts::TAU;

use glam::Vec3;
use knitwear::knit::{knit, KnitParams};
use knitwear::pattern::{Instruction as I, StitchPattern, WrittenRow};
use knitwear::surface::{GridSurface, PlaneSurface};

fn grid(rows: usize, cols: usize, cyclic_u: bool, f: impl Fn(f32, f32) -> (Vec3, Vec3)) -> GridSurface {
    let (mut p, mut n) = (Vec::new(), Vec::new());
    for i in 0..rows {
        for j in 0..cols {
            let u = if cyclic_u { j as f32 / cols as f32 } else { j as f32 / (cols - 1) as f32 };
            let (a, b) = f(u, i as f32 / (rows - 1) as f32);
            p.extend(a.to_array());
            n.extend(b.to_array());
        }
    }
    GridSurface::new(rows, cols, &p, &n, cyclic_u, false).unwrap()
}

fn rows(spec: &[(bool, Vec<I>)]) -> StitchPattern {
    let rows: Vec<WrittenRow> = spec
        .iter()
        .enumerate()
        .map(|(i, (rs, ins))| WrittenRow { number: i + 1, right_side: *rs, instructions: ins.clone() })
        .collect();
    StitchPattern::from_written_rows("test", &rows).unwrap()
}

fn rep(ins: &[I], n: usize) -> Vec<I> {
    ins.iter().copied().cycle().take(ins.len() * n).collect()
}

fn patterns() -> Vec<(&'static str, StitchPattern)> {
    let rc = I::Cross { m: 2, n: 2, left: false, purl_back: false };
    let lc = I::Cross { m: 2, n: 2, left: true, purl_back: false };
    let k = I::Knit;
    let p = I::Purl;
    vec![
        ("cable", rows(&[
            (true, vec![p, p, k, k, k, k, p, p]),
            (false, vec![k, k, p, p, p, p, k, k]),
            (true, vec![p, p, rc, p, p]),
            (false, vec![k, k, p, p, p, p, k, k]),
        ])),
        ("cable_lc", rows(&[
            (true, vec![k, k, k, k, p, p]),
            (false, vec![k, k, p, p, p, p]),
            (true, vec![lc, p, p]),
            (false, vec![k, k, p, p, p, p]),
        ])),
        ("eyelet", rows(&[
            (true, vec![k, k, k, k]),
            (false, vec![p, p, p, p]),
            (true, rep(&[I::YarnOver, I::K2tog], 2)),
            (false, vec![p, p, p, p]),
        ])),
        ("twisted_rib", rows(&[
            (true, vec![I::KnitTbl, p]),
            (false, vec![k, I::PurlTbl]),
        ])),
        ("slip", rows(&[
            (true, vec![k, I::Slip { yarn_front: false }, k, k]),
            (false, vec![p, p, p, p]),
        ])),
        ("feather_and_fan", rows(&[
            (true, rep(&[k], 18)),
            (false, rep(&[p], 18)),
            (true, [rep(&[I::K2tog], 3), rep(&[I::YarnOver, k], 6), rep(&[I::K2tog], 3)].concat()),
            (false, rep(&[k], 18)),
        ])),
        ("cdd", rows(&[
            (true, vec![k, I::YarnOver, I::Cdd, I::YarnOver]),
            (false, vec![p, p, p, p]),
        ])),
    ]
}

