//! Culling the yarn no camera view sees: the seen set of triangles, packed one bit each,
//! and the mesh subset it keeps.

use super::*;
use crate::detail::DetailParams;
use crate::error::{KnitError, Result};
use crate::geometry::MeshSubset;
use crate::parallel::run_in_pool;
use crate::surface::Surface;
use crate::visibility::{seen_triangles, VisibilityPass};

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
        let (c, out, seen) = run_in_pool(self.params.threads, || {
            let c = self.centrelines(surface);
            let out = self.bundles(&c);
            let seen = match pinned {
                Some(seen) => seen,
                None => seen_triangles(
                    &out.positions,
                    &out.triangles,
                    &d.views,
                    &VisibilityPass {
                        resolution: d.resolution,
                        supersampling: d.hidden_supersampling,
                        margin: d.frustum_margin,
                        budget_bytes: self.params.budget_bytes,
                        yarn_radius: self.radius,
                    },
                )?,
            };
            Ok::<_, KnitError>((c, out, seen))
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
        if d.pinned_seen.is_none() {
            self.first_build.keep(c, out);
        }
        Ok(())
    }

    /// With `cull_hidden`: the triangles seen, one bit per triangle of the knit before
    /// culling (see [`DetailParams::pinned_seen`]); give them back as `pinned_seen` to
    /// rebuild the same mesh in another pose or session.
    pub fn seen_triangles(&self) -> Option<&[u8]> {
        self.hidden.as_ref().map(|h| h.seen.as_slice())
    }
}
