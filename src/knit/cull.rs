//! Culling the yarn no camera view sees: the seen set of triangles, packed one bit each,
//! and the mesh subset it keeps.

use super::*;
use crate::detail::DetailParams;
use crate::error::{KnitError, Result};
use crate::geometry::MeshSubset;
use crate::parallel::run_in_pool;
use crate::surface::Surface;
use crate::visibility::{seen_triangles, VisibilityPass};
use std::sync::Arc;

/// Packs one flag per triangle into bits, triangle `i` at bit `i % 8` of byte `i / 8`.
pub(super) fn pack_bits(flags: &[bool]) -> Vec<u8> {
    flags
        .chunks(8)
        .map(|c| {
            c.iter()
                .enumerate()
                .fold(0u8, |b, (i, &f)| b | (u8::from(f) << i))
        })
        .collect()
}

pub(super) fn unpack_bits(bits: &[u8], n: usize) -> Result<Vec<bool>> {
    if bits.len() != n.div_ceil(8) {
        return Err(KnitError::Parameter(format!(
            "the pinned seen triangles are {} bytes; this knit has {n} triangles before \
             culling ({} bytes): they are from another knit",
            bits.len(),
            n.div_ceil(8)
        )));
    }
    Ok((0..n).map(|i| bits[i / 8] >> (i % 8) & 1 == 1).collect())
}

impl PreparedKnit {
    /// Finds the triangles `d`'s views see on `surface` (or takes its pinned ones), so every
    /// build keeps only those. The whole build made to look is kept for the first
    /// [`build`](Self::build) of the same surface.
    pub(super) fn cull_hidden(&mut self, surface: &dyn Surface, d: &DetailParams) -> Result<()> {
        let whole = self.total.triangles as usize;
        let pinned = d
            .pinned_seen
            .as_ref()
            .map(|bits| unpack_bits(bits, whole))
            .transpose()?;
        let pass = VisibilityPass {
            resolution: d.resolution,
            supersampling: d.hidden_supersampling,
            margin: d.frustum_margin,
            budget_bytes: self.params.budget_bytes,
            yarn_radius: self.radius,
        };
        let (own, out, seen) = run_in_pool(self.params.threads, || match pinned {
            Some(seen) => {
                let c = self.centrelines(surface);
                let out = self.bundles(&c);
                Ok::<_, KnitError>((Some(c), out, seen))
            }
            None if d.poses.is_empty() => {
                let c = self.centrelines(surface);
                let out = self.bundles(&c);
                let seen = seen_triangles(&out.positions, &out.triangles, &d.views, &pass)?;
                Ok((Some(c), out, seen))
            }
            None => {
                let (out, seen) = self.seen_in_poses(d, &pass)?;
                Ok((None, out, seen))
            }
        })??;
        // Nothing half made is kept for the first build.
        crate::cancel::check()?;
        let subset = MeshSubset::new(
            &seen,
            &out.triangles,
            &out.corner_edges,
            self.total.vertices as usize,
            self.total.edges as usize,
        );
        let bits = pack_bits(&seen);
        self.stats.vertices = subset.vertex_count();
        self.stats.triangles = subset.triangle_count();
        self.stats.triangles_hidden = whole - subset.triangle_count();
        self.stats.topology_key = bits.chunks(8).fold(self.stats.topology_key, |h, c| {
            let mut word = [0u8; 8];
            word[..c.len()].copy_from_slice(c);
            crate::geometry::stitch_seed(h, u64::from_le_bytes(word) as usize, 0x5345_454e)
        });
        self.hidden = Some(HiddenCulled { subset, seen: bits });
        if let (Some(c), None) = (own, &d.pinned_seen) {
            self.first_build.keep(c, out);
        }
        Ok(())
    }

    /// The triangles each view sees on the surface in that view's pose (`d.poses`, not
    /// empty), united, and the last pose's build (its topology is every pose's). Views that
    /// share a pose (by identity) are rasterised over one build of it; the poses are built
    /// one at a time in view order, so memory holds one build, and the union does not depend
    /// on the order or the thread count.
    fn seen_in_poses(
        &self,
        d: &DetailParams,
        pass: &VisibilityPass,
    ) -> Result<(KnitOutput, Vec<bool>)> {
        let mut seen = vec![false; self.total.triangles as usize];
        let mut last = None;
        let mut done = vec![false; d.views.len()];
        for i in 0..d.views.len() {
            if done[i] {
                continue;
            }
            crate::cancel::check()?;
            let pose = &d.poses.0[i];
            let views: Vec<_> = (i..d.views.len())
                .filter(|&j| std::ptr::addr_eq(Arc::as_ptr(&d.poses.0[j]), Arc::as_ptr(pose)))
                .inspect(|&j| done[j] = true)
                .map(|j| d.views[j])
                .collect();
            // The previous pose's build goes before this one is made: one at a time.
            drop(last.take());
            let out = self.bundles(&self.centrelines(&**pose));
            let in_pose = seen_triangles(&out.positions, &out.triangles, &views, pass)?;
            for (s, v) in seen.iter_mut().zip(in_pose) {
                *s |= v;
            }
            last = Some(out);
        }
        let out = last.ok_or_else(|| {
            KnitError::Parameter("culling hidden yarn needs at least one camera view".into())
        })?;
        Ok((out, seen))
    }

    /// With `cull_hidden`: the triangles seen, one bit per triangle of the knit before
    /// culling (see [`DetailParams::pinned_seen`]); give them back as `pinned_seen` to
    /// rebuild the same mesh in another pose or session.
    pub fn seen_triangles(&self) -> Option<&[u8]> {
        self.hidden.as_ref().map(|h| h.seen.as_slice())
    }
}
