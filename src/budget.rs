//! Output-size estimates and the memory budget: checked before anything big is allocated, so
//! an absurd request fails at once with a message naming the size.

use crate::error::{KnitError, Result};

/// Default budget for one knit's output buffers: 4 GiB.
pub const DEFAULT_BUDGET_BYTES: u64 = 4 << 30;

/// Largest index a Blender mesh (int32 indices) can hold.
pub const MAX_MESH_ELEMENTS: u64 = i32::MAX as u64;

/// Bytes per output element: vertex = position (12) + colour (16); triangle = corner
/// vertices (12) + corner edges (12); edge = 8; centreline sample = position, normal (24) +
/// owner (4).
const BYTES_PER_VERTEX: u64 = 28;
const BYTES_PER_TRIANGLE: u64 = 24;
const BYTES_PER_EDGE: u64 = 8;
const BYTES_PER_SAMPLE: u64 = 28;

/// Element counts of a whole knit.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct OutputSize {
    pub vertices: u64,
    pub triangles: u64,
    pub edges: u64,
    pub samples: u64,
}

impl OutputSize {
    pub fn bytes(&self) -> u64 {
        self.vertices
            .saturating_mul(BYTES_PER_VERTEX)
            .saturating_add(self.triangles.saturating_mul(BYTES_PER_TRIANGLE))
            .saturating_add(self.edges.saturating_mul(BYTES_PER_EDGE))
            .saturating_add(self.samples.saturating_mul(BYTES_PER_SAMPLE))
    }

    /// Upper bound for `stitches` stitches sampled `samples_per_loop` times with rings of `m`.
    pub fn upper_bound(stitches: u64, samples_per_loop: u64, m: u64) -> Self {
        let samples = stitches
            .saturating_mul(samples_per_loop)
            .saturating_add(stitches);
        let triangles = samples.saturating_mul(2 * m);
        Self {
            vertices: samples.saturating_mul(m).saturating_add(triangles),
            triangles,
            edges: samples
                .saturating_mul(m)
                .saturating_add(triangles.saturating_mul(2)),
            samples,
        }
    }
}

fn human(bytes: u64) -> String {
    let gib = bytes as f64 / (1u64 << 30) as f64;
    if gib >= 1.0 {
        format!("{gib:.1} GiB")
    } else {
        format!("{:.0} MiB", bytes as f64 / (1u64 << 20) as f64)
    }
}

/// Refuses sizes over the budget or beyond what a Blender mesh can index.
pub fn check(size: &OutputSize, budget_bytes: u64, stitches: u64) -> Result<()> {
    let bytes = size.bytes();
    if bytes > budget_bytes {
        return Err(KnitError::Budget(format!(
            "{stitches} stitches would need about {} of geometry ({} triangles), over the \
             budget of {}: use fewer stitches (a coarser gauge), fewer ring segments or samples \
             per loop, or raise the budget",
            human(bytes),
            size.triangles,
            human(budget_bytes)
        )));
    }
    if size.triangles.saturating_mul(3) > MAX_MESH_ELEMENTS || size.vertices > MAX_MESH_ELEMENTS {
        return Err(KnitError::Budget(format!(
            "{stitches} stitches would need {} triangles, more than a Blender mesh can index",
            size.triangles
        )));
    }
    Ok(())
}
