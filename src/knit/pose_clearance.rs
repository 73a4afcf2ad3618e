//! The clearance of a bound knit in any pose of its surface, for checking that yarn never
//! passes through yarn as the surface moves (issue 23): the centrelines only, measured as
//! every knit's are, without sweeping the bundles.

use super::*;
use crate::parallel::run_in_pool;

impl PreparedKnit {
    /// `(min, p01)` centreline clearance in yarn diameters (docs/design.md section 7) of this
    /// knit's yarn on `surface` (the knitted surface in any pose): bit for bit what
    /// [`build`](Self::build)`(surface)` reports with
    /// [`KnitParams::measure_clearance`], at about half its cost. Every built stitch's yarn
    /// counts, the hidden yarn culled from the mesh too: a loop no camera sees can still be
    /// pushed through another. Errors: the surface's (u,v) layout is not the knit's;
    /// cancelled.
    pub fn clearance(&self, surface: &dyn Surface) -> Result<(f32, f32)> {
        self.check_layout(surface)?;
        run_in_pool(self.params.threads, || {
            let c = self.centrelines(surface);
            crate::cancel::check()?;
            let pieces: Vec<(usize, usize, bool)> = self
                .pieces
                .iter()
                .zip(&self.samples)
                .scan(0, |at, (pc, &n)| {
                    *at += n;
                    Some((*at - n, *at, pc.closed))
                })
                .collect();
            Ok(crate::metrics::yarn_clearance(
                c.points(),
                &pieces,
                self.radius,
            ))
        })?
    }
}
