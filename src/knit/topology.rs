//! The knit's skeleton as measured: its centrelines in (u,v) and the crossing order of its
//! courses (the interlock).

use glam::Vec3;
use rayon::prelude::*;

use super::*;
use crate::error::Result;
use crate::surface::Surface;

impl PreparedKnit {
    /// Every yarn piece's centreline in (u, v, lambda) (lambda: normal offset, scene units),
    /// sampled exactly where [`build`](Self::build) samples it, before it is mapped onto the
    /// surface. Runs in the caller's rayon pool.
    pub fn uv_centrelines(&self, surface: &dyn Surface) -> Result<Vec<UvYarn>> {
        self.check_layout(surface)?;
        let wales = self.skeleton.lattice().wales;
        Ok(self
            .pieces
            .par_iter()
            .zip(&self.samples)
            .map(|(pc, &n)| {
                let mut points = vec![Vec3::ZERO; n];
                let mut owner = vec![0u32; n];
                let spl = self.skeleton.sampling().samples_per_loop;
                self.skeleton
                    .sample_uv(surface, &self.pattern, pc, spl, &mut points, &mut owner);
                let stitches = owner
                    .iter()
                    .map(|&o| (pc.course, (pc.first_wale + o as usize) % wales))
                    .collect();
                UvYarn {
                    points,
                    stitches,
                    closed: pc.closed,
                    bobble: pc.bobble,
                    period_u: self.skeleton.lattice().tile.x * wales as f32,
                }
            })
            .collect())
    }

    /// The interlock-topology metric of this knit on `surface` (see
    /// [`crate::skeleton::crossings::crossing_order`]), measured on the skeleton's spline at
    /// [`TOPOLOGY_SAMPLES`] samples a loop at least (as the tuning and the contact relief
    /// see it), not on the output's possibly coarser polyline: where a head and a sinker run
    /// side by side, a coarse chord grazes across the other yarn's projection and back, and
    /// which of two such grazing "crossings" exist depends on the sampling, not the knit.
    pub fn crossing_order(
        &self,
        surface: &dyn Surface,
    ) -> Result<crate::skeleton::crossings::CrossingOrder> {
        self.check_layout(surface)?;
        let samples_per_loop = self
            .skeleton
            .sampling()
            .samples_per_loop
            .max(TOPOLOGY_SAMPLES);
        let lines: Vec<Vec<Vec3>> = self
            .pieces
            .par_iter()
            .map(|pc| {
                let n = pc.sample_count(samples_per_loop);
                let mut points = vec![Vec3::ZERO; n];
                let mut owner = vec![0u32; n];
                self.skeleton.sample_uv(
                    surface,
                    &self.pattern,
                    pc,
                    samples_per_loop,
                    &mut points,
                    &mut owner,
                );
                points
            })
            .collect();
        Ok(self
            .skeleton
            .crossing_order(&self.pattern, &self.pieces, &lines, samples_per_loop))
    }
}
