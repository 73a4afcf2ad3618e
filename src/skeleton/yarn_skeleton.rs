//! The skeleton's one front door: [`YarnSkeleton::new`] binds a pattern to a lattice (loop
//! shapes tuned and relieved for the stitch proportions and yarn, the rows of leaning loops
//! made as tall as they need, wales whose edge cuts a crossing knitted straight), and its
//! methods are all the pipeline asks of the skeleton afterwards: which stitches have a
//! surface, the pieces of yarn, their centrelines on a surface in any pose or in (u,v), and
//! the crossing order of the courses. The modules behind it (tuning, relief, leaning rows,
//! stitch shapes, bobbles, floats, crossings) are the skeleton's own business.
//!
//! Units: stitch sizes and the yarn diameter in scene units; centrelines in the surface's
//! object space (or (u, v, lambda) with lambda in scene units).

use glam::Vec3;

use super::crossings::{crossing_order, CrossingOrder};
use super::{
    bobbles, built_stitches, edges, floats, leaning_rows, sample_piece, sample_piece_uv,
    sampling_density, stitch_shape, tuning, yarn_pieces, NormalOffsets, SplineSampling, YarnPiece,
};
use crate::lattice::Lattice;
use crate::pattern::{ColorPattern, StitchPattern};
use crate::surface::Surface;

/// A knit's skeleton: its lattice (rows of leaning loops shaped), the key points' normal
/// offsets, and how the centrelines are sampled.
#[derive(Debug, Clone)]
pub struct YarnSkeleton {
    lattice: Lattice,
    offsets: NormalOffsets,
    sampling: SplineSampling,
    /// The minimum clearance of the tuned loops on a flat patch, in yarn diameters.
    flat_clearance: f32,
    /// Whether the first and last courses along an open v keep their loops live, with no
    /// cast-on or bind-off ([`super::edges`]).
    live_loops: bool,
}

impl YarnSkeleton {
    /// The skeleton of `pattern` on the stitch lattice `base`, for stitches of `stitch_size`
    /// (width, height) knitted with yarn of `diameter` (scene units), sampled as `sampling`
    /// says. The loop shapes are tuned once per pattern, proportions and yarn, and cached.
    pub fn new(
        base: Lattice,
        pattern: &StitchPattern,
        stitch_size: (f32, f32),
        diameter: f32,
        sampling: SplineSampling,
    ) -> Self {
        let (width, height) = stitch_size;
        let tension = sampling.tension;
        let (offsets, flat_clearance, per_lean) =
            tuning::tuned_offsets(pattern, width, height, diameter, tension);
        // Wales whose edge cuts a crossing or a decrease are knitted straight, with a relief
        // made for the pattern straightened.
        let straight_wales: Vec<bool> = if pattern.has_crossings() {
            (0..base.wales)
                .map(|w| !stitch_shape::wale_knits_whole(&base, pattern, w))
                .collect()
        } else {
            Vec::new()
        };
        let offsets = if !straight_wales.contains(&true) {
            offsets
        } else if base.cyclic_u {
            // Round a seam (explicit counts that are not whole repeats): no edge corrections,
            // which a flat strip cannot make across the seam.
            let straight = tuning::straight_offsets(pattern, width, height, diameter, tension);
            offsets.with_straight(straight, straight_wales)
        } else {
            tuning::offsets_with_straight_wales(
                pattern,
                width,
                height,
                diameter,
                tension,
                straight_wales,
            )
        };
        let (width_d, height_d) = tuning::proportions(width, height, diameter);
        let lattice = leaning_rows::shaped(
            base,
            pattern,
            width_d,
            height_d,
            per_lean,
            leaning_rows::Ramp::ByBlock,
        );
        Self {
            lattice,
            offsets,
            sampling,
            flat_clearance,
            live_loops: false,
        }
    }

    /// This skeleton with the first and last courses' loops left live (`true`: no cast-on
    /// or bind-off) or finished (`false`, the default).
    pub fn with_live_loops(self, live_loops: bool) -> Self {
        Self { live_loops, ..self }
    }

    /// The most samples-per-loop multiple any piece of `pattern` can get (loops that lean
    /// further are sampled more densely).
    pub fn densest_sampling(pattern: &StitchPattern) -> usize {
        let lean = (0..pattern.height())
            .flat_map(|r| (0..pattern.width()).map(move |w| (r, w)))
            .map(|(r, w)| pattern.stitch(r, w).land_offset.unsigned_abs() as usize)
            .max()
            .unwrap_or(0);
        sampling_density::density(lean)
    }

    /// The lattice the loops sit on (rows of leaning loops shaped).
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// The key points' normal offsets.
    pub fn offsets(&self) -> &NormalOffsets {
        &self.offsets
    }

    /// How the centrelines are sampled.
    pub fn sampling(&self) -> &SplineSampling {
        &self.sampling
    }

    /// The minimum clearance of the tuned loops on a flat patch, in yarn diameters.
    pub fn flat_clearance(&self) -> f32 {
        self.flat_clearance
    }

    /// Which stitches (row-major) have a surface under every key point. Runs in the
    /// caller's rayon pool.
    pub fn built_stitches(&self, surface: &dyn Surface) -> Vec<bool> {
        built_stitches(surface, &self.lattice)
    }

    /// Of the stitches not `built`, those that were fabric ([`super::lost_stitches`]). Runs
    /// in the caller's rayon pool.
    pub fn lost_stitches(&self, surface: &dyn Surface, built: &[bool]) -> usize {
        super::lost_stitches(surface, &self.lattice, built)
    }

    /// The pieces of yarn over the stitches `built` (row-major) of a fabric whose stitches
    /// on the surface are `fabric` (`built` may leave some of them out: those a detail level
    /// does not build): each course's, sampled as densely as its loops need, then the balls
    /// of the pattern's bobbles, for a palette colour chart (`colors`) the floats of stranded
    /// colourwork, and the cast-on and bind-off where the fabric ends along v (unless its
    /// loops are left live).
    pub fn pieces(
        &self,
        built: &[bool],
        fabric: &[bool],
        pattern: &StitchPattern,
        colors: Option<&ColorPattern>,
    ) -> Vec<YarnPiece> {
        let mut pieces = yarn_pieces(&self.lattice, built);
        pieces.extend(bobbles::bobble_pieces(&self.lattice, built, pattern));
        if let Some(colors) = colors {
            pieces.extend(floats::float_pieces(&self.lattice, built, colors));
        }
        if !self.live_loops {
            pieces.extend(edges::edge_pieces(&self.lattice, fabric, built));
        }
        sampling_density(&mut pieces, &self.lattice, pattern);
        pieces
    }

    /// One piece's centreline on `surface` (see [`sample_piece`]): points, the surface
    /// normal under each and each sample's stitch; returns the stitches whose offsets were
    /// clamped where the surface curves tightly.
    pub fn sample(
        &self,
        surface: &dyn Surface,
        pattern: &StitchPattern,
        piece: &YarnPiece,
        points: &mut [Vec3],
        normals: &mut [Vec3],
        stitch_of_sample: &mut [u32],
    ) -> usize {
        sample_piece(
            surface,
            &self.lattice,
            pattern,
            &self.offsets,
            &self.sampling,
            piece,
            points,
            normals,
            stitch_of_sample,
        )
    }

    /// One piece's centreline in (u, v, lambda) (see [`sample_piece_uv`]), sampled at
    /// `samples_per_loop` (the skeleton's own, or finer to measure it).
    pub fn sample_uv(
        &self,
        surface: &dyn Surface,
        pattern: &StitchPattern,
        piece: &YarnPiece,
        samples_per_loop: usize,
        uvl: &mut [Vec3],
        stitch_of_sample: &mut [u32],
    ) -> usize {
        let sampling = SplineSampling {
            samples_per_loop,
            ..self.sampling
        };
        sample_piece_uv(
            surface,
            &self.lattice,
            pattern,
            &self.offsets,
            &sampling,
            piece,
            uvl,
            stitch_of_sample,
        )
    }

    /// The crossing order of `pieces` whose centrelines in (u, v, lambda) are `lines`,
    /// sampled at `samples_per_loop` ([`crossing_order`]): the interlock, measured.
    pub fn crossing_order(
        &self,
        pattern: &StitchPattern,
        pieces: &[YarnPiece],
        lines: &[Vec<Vec3>],
        samples_per_loop: usize,
    ) -> CrossingOrder {
        crossing_order(&self.lattice, pattern, pieces, lines, samples_per_loop)
    }
}
