//! The core's hot path, timed by criterion: building a prepared knit (bundles swept along the
//! centrelines into preallocated buffers, in parallel) and the per-frame positions of an
//! animated knit. `cargo bench --bench core_hot_path`.
//!
//! The whole-pipeline figures a user sees (click to mesh in Blender, the Geometry Nodes
//! peer) are `benchmarks/bench_knit.py`'s; this one isolates the Rust work, with
//! statistics, so that a change to the sweep shows up as a change here.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use knitwear::knit::{KnitParams, PreparedKnit};
use knitwear::pattern::StitchPattern;
use knitwear::surface::PlaneSurface;

/// A 50 x 50 cm sheet at the default gauge: 100 wales x 140 courses, 14,000 stitches.
fn sheet() -> PlaneSurface {
    PlaneSurface {
        width: 0.5,
        height: 0.5,
    }
}

fn hot_path(c: &mut Criterion) {
    let surface = sheet();
    let pattern = StitchPattern::preset("stockinette").unwrap();
    // Prepared once (the loop shapes are tuned and cached here): what is timed is what a
    // knit costs on every build and every frame.
    let knit = PreparedKnit::new(&surface, &pattern, &KnitParams::default()).unwrap();
    let triangles = knit.build(&surface).unwrap().triangles.len() / 3;
    let mut group = c.benchmark_group("stockinette 14k stitches");
    group.sample_size(20);
    group.throughput(Throughput::Elements(triangles as u64));
    group.bench_function("build", |b| {
        b.iter(|| black_box(knit.build(black_box(&surface)).unwrap()))
    });
    let mut positions = vec![0.0f32; 3 * knit.vertex_count()];
    group.bench_function("positions_into", |b| {
        b.iter(|| {
            knit.positions_into(black_box(&surface), &mut positions)
                .unwrap();
            black_box(&positions);
        })
    });
    group.finish();
}

criterion_group!(benches, hot_path);
criterion_main!(benches);
