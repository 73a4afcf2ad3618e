//! Building a prepared knit for a surface in any pose: the centrelines, the bundles swept
//! along them, and the positions alone for an animated knit.

use std::sync::Mutex;
use std::time::Instant;

use glam::Vec3;
use rayon::prelude::*;

use super::*;
use crate::detail::Level;
use crate::error::{KnitError, Result};
use crate::geometry::{
    build_bundle, bundle_profile, piece_streams, stitch_seed, sweep_bundle, BundleCounts,
    BundleProfile, BundleSettings, EndTangents, FullDensityDraws, PieceBuffers, TopologyBuffers,
};
use crate::output_buffer;
use crate::parallel::{run_in_pool, split_lengths};
use crate::surface::Surface;

/// What one span's bundle is built from (see [`crate::geometry::build_bundle`]).
struct SpanInputs<'a> {
    points: &'a [Vec3],
    normals: &'a [Vec3],
    owner: &'a dyn Fn(usize) -> (usize, usize),
    color_of: &'a dyn Fn(usize, usize) -> [f32; 3],
    closed: bool,
    ends: EndTangents,
    settings: &'a BundleSettings,
    draws: Option<&'a FullDensityDraws<'a>>,
}

/// A whole build and the centrelines it was swept along (cloning a knit does not clone it).
#[derive(Default)]
pub(super) struct FirstBuild(Mutex<Option<(Centrelines, KnitOutput)>>);

impl Clone for FirstBuild {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for FirstBuild {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("FirstBuild")
    }
}

impl FirstBuild {
    /// Keeps `out`, swept along `c`, for the first build of the same centrelines.
    pub(super) fn keep(&self, c: Centrelines, out: KnitOutput) {
        if let Ok(mut slot) = self.0.lock() {
            *slot = Some((c, out));
        }
    }

    /// The kept build, if it was swept along exactly `c` (bit for bit: then it is what a new
    /// sweep would make).
    pub(super) fn take_if_same(&self, c: &Centrelines) -> Option<KnitOutput> {
        let mut slot = self.0.lock().ok()?;
        let same = slot.as_ref().is_some_and(|(kept, _)| kept.same_as(c));
        if same {
            slot.take().map(|(_, out)| out)
        } else {
            None
        }
    }
}

/// Sampled centrelines of all pieces, concatenated.
pub(super) struct Centrelines {
    points: Vec<Vec3>,
    normals: Vec<Vec3>,
    owner: Vec<u32>,
    /// Stitches whose offsets were clamped for curvature.
    clamped: usize,
}

impl Centrelines {
    /// The sample points of every piece, concatenated in piece order (scene units).
    pub(super) fn points(&self) -> &[Vec3] {
        &self.points
    }

    /// Bit for bit the same samples (so the same sweep).
    pub(super) fn same_as(&self, other: &Centrelines) -> bool {
        let same = |a: &[Vec3], b: &[Vec3]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(p, q)| p.to_array().map(f32::to_bits) == q.to_array().map(f32::to_bits))
        };
        self.owner == other.owner
            && same(&self.points, &other.points)
            && same(&self.normals, &other.normals)
    }
}

pub(super) fn vec3_slice(v: &[f32]) -> &[Vec3] {
    // Vec3 is three packed f32 (glam's non-SIMD Vec3), so a flat f32 buffer of 3N values is
    // N Vec3s.
    let n = v.len() / 3;
    // SAFETY: Vec3 is #[repr(C)] { x, y, z: f32 }, size 12, align 4, like [f32; 3].
    unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<Vec3>(), n) }
}

impl PreparedKnit {
    pub(super) fn check_layout(&self, surface: &dyn Surface) -> Result<()> {
        let cyclic = (surface.cyclic_u(), surface.cyclic_v());
        if surface.domain() != self.domain || cyclic != self.cyclic {
            return Err(KnitError::Surface(format!(
                "the surface's (u,v) layout changed since it was knitted (domain {:?} -> \
                 {:?}, cyclic {:?} -> {:?}): knit it again",
                self.domain,
                surface.domain(),
                self.cyclic,
                cyclic
            )));
        }
        Ok(())
    }

    /// The whole output for `surface` (the prepared one, or it deformed).
    pub fn build(&self, surface: &dyn Surface) -> Result<KnitOutput> {
        let start = Instant::now();
        self.check_layout(surface)?;
        let mut out = run_in_pool(self.params.threads, || self.build_in_pool(surface))??;
        crate::cancel::check()?;
        out.yarn_radius = self.radius;
        out.stats = KnitStats {
            seconds: start.elapsed().as_secs_f64(),
            stitches_clamped: out.stats.stitches_clamped,
            ..self.stats.clone()
        };
        if self.params.measure_clearance {
            out.stats.clearance = Some(measure(&out));
            let order = self.crossing_order(surface)?;
            out.stats.interlock = Some((order.interlock_decided, order.interlock_agree));
            out.stats.free_loops = Some((order.free_loops, order.free_feet));
        }
        Ok(out)
    }

    /// Only the vertex positions for `surface` (the prepared one, or it deformed), into
    /// `positions` (`3 * vertex_count()` floats): the same values [`build`](Self::build)
    /// writes, without allocating the rest. The per-frame path of an animated knit.
    pub fn positions_into(&self, surface: &dyn Surface, positions: &mut [f32]) -> Result<()> {
        self.positions_and_shading_into(surface, positions, None, None)
    }

    /// [`positions_into`](Self::positions_into), and with `normals` and `tangents` (each
    /// `3 * vertex_count()` floats) the shading normals and fibre directions
    /// [`build`](Self::build) gives for that pose (the swept tube's: see
    /// [`crate::geometry::build_bundle`]), in the same pass.
    pub fn positions_and_shading_into(
        &self,
        surface: &dyn Surface,
        positions: &mut [f32],
        normals: Option<&mut [f32]>,
        tangents: Option<&mut [f32]>,
    ) -> Result<()> {
        self.check_layout(surface)?;
        let nv = self.vertex_count();
        let check = |name: &str, len: usize| {
            if len == 3 * nv {
                return Ok(());
            }
            Err(KnitError::Parameter(format!(
                "the {name} buffer holds {len} floats; this knit needs {} ({nv} vertices x 3)",
                3 * nv
            )))
        };
        check("positions", positions.len())?;
        if let Some(n) = &normals {
            check("normals", n.len())?;
        }
        if let Some(t) = &tangents {
            check("tangents", t.len())?;
        }
        run_in_pool(self.params.threads, || {
            let centrelines = self.centrelines(surface);
            match &self.hidden {
                None => self.whole_positions(&centrelines, positions, normals, tangents),
                Some(h) => {
                    let nv = 3 * self.total.vertices as usize;
                    let mut whole = output_buffer::zeroed(nv);
                    let mut whole_normals = normals.as_ref().map(|_| output_buffer::zeroed(nv));
                    let mut whole_tangents = tangents.as_ref().map(|_| output_buffer::zeroed(nv));
                    self.whole_positions(
                        &centrelines,
                        &mut whole,
                        whole_normals.as_deref_mut(),
                        whole_tangents.as_deref_mut(),
                    );
                    h.subset.gather_vectors(&whole, positions);
                    if let (Some(normals), Some(whole)) = (normals, whole_normals) {
                        h.subset.gather_vectors(&whole, normals);
                    }
                    if let (Some(tangents), Some(whole)) = (tangents, whole_tangents) {
                        h.subset.gather_vectors(&whole, tangents);
                    }
                }
            }
        })?;
        // A stopped call leaves the buffers half written: say so rather than return them.
        crate::cancel::check()
    }

    /// Every span's vertex positions (and, where given, normals and tangents), before any
    /// culling of hidden yarn.
    pub(super) fn whole_positions(
        &self,
        centrelines: &Centrelines,
        positions: &mut [f32],
        normals: Option<&mut [f32]>,
        tangents: Option<&mut [f32]>,
    ) {
        let lengths = self.span_lengths(3);
        let pos = split_lengths(positions, &lengths);
        fn per_span<'a>(
            buf: Option<&'a mut [f32]>,
            lengths: &[usize],
        ) -> Vec<Option<&'a mut [f32]>> {
            match buf {
                Some(b) => split_lengths(b, lengths).into_iter().map(Some).collect(),
                None => lengths.iter().map(|_| None).collect(),
            }
        }
        let nrm = per_span(normals, &lengths);
        let tan = per_span(tangents, &lengths);
        // The draws are the same on every frame: made on the first, swept on every one.
        let profiles = self.span_profiles.get_or_init(|| {
            (0..self.spans.len())
                .into_par_iter()
                .map(|k| self.span_profile(k, centrelines))
                .collect()
        });
        pos.into_par_iter().zip(nrm).zip(tan).enumerate().for_each(
            |(k, ((positions, normals), tangents))| {
                if crate::cancel::requested() {
                    return;
                }
                let mut bufs = PieceBuffers::positions_only(positions);
                bufs.normals = normals;
                bufs.tangents = tangents;
                self.bundle_span(k, centrelines, Some(&profiles[k]), &mut bufs);
            },
        );
    }

    /// Floats per span in a per-vertex buffer of `width` floats per vertex.
    fn span_lengths(&self, width: usize) -> Vec<usize> {
        self.counts.iter().map(|c| width * c.vertices).collect()
    }

    /// Samples every piece's centreline (points, surface normals, owning stitch), in parallel.
    pub(super) fn centrelines(&self, surface: &dyn Surface) -> Centrelines {
        let n = self.total.samples as usize;
        let mut c = Centrelines {
            points: vec![Vec3::ZERO; n],
            normals: vec![Vec3::ZERO; n],
            owner: vec![0u32; n],
            clamped: 0,
        };
        {
            let pts = split_lengths(&mut c.points, &self.samples);
            let nrm = split_lengths(&mut c.normals, &self.samples);
            let own = split_lengths(&mut c.owner, &self.samples);
            c.clamped = self
                .pieces
                .par_iter()
                .zip(pts)
                .zip(nrm)
                .zip(own)
                .map(|(((pc, a), b), o)| {
                    if crate::cancel::requested() {
                        return 0;
                    }
                    self.skeleton.sample(surface, &self.pattern, pc, a, b, o)
                })
                .sum();
        }
        c
    }

    /// Sweeps span `k`'s bundle into `bufs` (whatever parts of the output they hold), its
    /// draws made afresh (`profile` `None`) or taken from [`Self::span_profile`].
    pub(super) fn bundle_span(
        &self,
        k: usize,
        cl: &Centrelines,
        profile: Option<&BundleProfile>,
        bufs: &mut PieceBuffers,
    ) {
        self.with_span(k, cl, |s| match profile {
            None => build_bundle(
                s.points, s.normals, s.owner, s.color_of, s.closed, s.ends, s.settings, s.draws,
                bufs,
            ),
            Some(profile) => sweep_bundle(
                s.points, s.normals, s.closed, s.ends, s.settings, s.draws, profile, bufs,
            ),
        })
    }

    /// Span `k`'s draws ([`BundleProfile`]): what its frames share, wherever the surface
    /// moves.
    pub(super) fn span_profile(&self, k: usize, cl: &Centrelines) -> BundleProfile {
        self.with_span(k, cl, |s| {
            bundle_profile(
                s.points.len(),
                s.closed,
                s.owner,
                s.color_of,
                s.settings,
                s.draws,
                None,
            )
        })
    }

    /// Calls `f` with what span `k`'s bundle is built from.
    fn with_span<R>(&self, k: usize, cl: &Centrelines, f: impl FnOnce(SpanInputs) -> R) -> R {
        let sp = self.spans[k];
        let pc = self.pieces[sp.piece];
        let n = self.samples[sp.piece];
        let base = self.piece_start[sp.piece];
        let points = &cl.points[base..base + n];
        let normals = &cl.normals[base..base + n];
        let owner = &cl.owner[base..base + n];
        let wales = self.skeleton.lattice().wales;
        // A float of stranded colourwork is its own colour, not the stitches' it passes.
        let float = pc.float_color.and_then(|i| {
            let palette = self.params.colors.as_ref()?.palette();
            palette.get(usize::from(i)).copied()
        });
        let color_of =
            |course: usize, wale: usize| float.unwrap_or_else(|| self.stitch_color(course, wale));
        let settings = &self.level_bundle[sp.level as usize];
        let whole = sp.first == 0 && sp.rings == n && (sp.closed || sp.last + 1 == n);
        if whole {
            // Every sample: the piece's own slices, exactly as without detail.
            let owner_of = |i: usize| (pc.course, (pc.first_wale + owner[i] as usize) % wales);
            return f(SpanInputs {
                points,
                normals,
                owner: &owner_of,
                color_of: &color_of,
                closed: sp.closed,
                ends: EndTangents::default(),
                settings,
                draws: None,
            });
        }
        let idx: Vec<usize> = (0..sp.rings).map(|i| sp.sample(i, n)).collect();
        let pts: Vec<Vec3> = idx.iter().map(|&i| points[i]).collect();
        let nrm: Vec<Vec3> = idx.iter().map(|&i| normals[i]).collect();
        let own: Vec<u32> = idx.iter().map(|&i| owner[i]).collect();
        let owner_of = |i: usize| (pc.course, (pc.first_wale + own[i] as usize) % wales);
        // Where the span meets another one, its end ring takes the full-density tangent so
        // both spans put the shared ring in the same plane.
        let tangent_at = |i: usize| -> Option<Vec3> {
            let inner = i > 0 && i + 1 < n;
            if pc.closed || inner {
                Some(points[(i + 1) % n] - points[(i + n - 1) % n])
            } else {
                None
            }
        };
        let ends = if sp.closed {
            EndTangents::default()
        } else {
            EndTangents {
                first: tangent_at(idx[0]),
                last: tangent_at(idx[sp.rings - 1]),
            }
        };
        // The draws of the whole piece at full detail, so this span keeps a subset of its
        // fibres (see `geometry::bundle`).
        let seed = self.level_bundle[Level::Full as usize].seed;
        let streams = piece_streams(n, |i| {
            stitch_seed(seed, pc.course, (pc.first_wale + owner[i] as usize) % wales)
        });
        let draws = FullDensityDraws {
            samples: &idx,
            streams: &streams,
            ring_segments: self.level_bundle[Level::Full as usize].ring_segments,
        };
        f(SpanInputs {
            points: &pts,
            normals: &nrm,
            owner: &owner_of,
            color_of: &color_of,
            closed: sp.closed,
            ends,
            settings,
            draws: Some(&draws),
        })
    }

    pub(super) fn build_in_pool(&self, surface: &dyn Surface) -> Result<KnitOutput> {
        let centrelines = self.centrelines(surface);
        crate::cancel::check()?;
        let mut out = match self.first_build.take_if_same(&centrelines) {
            Some(out) => out,
            None => self.bundles(&centrelines),
        };
        if let Some(h) = &self.hidden {
            let mut normals = output_buffer::zeroed(3 * h.subset.vertex_count());
            h.subset.gather_vectors(&out.normals, &mut normals);
            out.normals = normals;
            let mut tangents = output_buffer::zeroed(3 * h.subset.vertex_count());
            h.subset.gather_vectors(&out.tangents, &mut tangents);
            out.tangents = tangents;
            let b = h.subset.apply(
                &out.positions,
                &out.colors,
                &out.triangles,
                &out.corner_edges,
                &out.edges,
            );
            out.positions = b.positions;
            out.colors = b.colors;
            out.triangles = b.triangles;
            out.corner_edges = b.corner_edges;
            out.edges = b.edges;
        }
        out.stats.stitches_clamped = centrelines.clamped;
        Ok(out)
    }

    /// The whole output swept along `centrelines`, before any culling of hidden yarn.
    pub(super) fn bundles(&self, centrelines: &Centrelines) -> KnitOutput {
        let nv = self.total.vertices as usize;
        let nt = self.total.triangles as usize;
        let ne = self.total.edges as usize;
        let mut out = KnitOutput {
            positions: output_buffer::zeroed(3 * nv),
            normals: output_buffer::zeroed(3 * nv),
            tangents: output_buffer::zeroed(3 * nv),
            colors: output_buffer::zeroed(4 * nv),
            triangles: output_buffer::zeroed(3 * nt),
            corner_edges: output_buffer::zeroed(3 * nt),
            edges: output_buffer::zeroed(2 * ne),
            ..Default::default()
        };
        let (mut vbase, mut ebase) = (
            Vec::with_capacity(self.pieces.len()),
            Vec::with_capacity(self.pieces.len()),
        );
        let (mut v, mut e) = (0usize, 0usize);
        for c in &self.counts {
            vbase.push(v);
            ebase.push(e);
            v += c.vertices;
            e += c.edges;
        }
        let lengths = |f: &dyn Fn(&BundleCounts) -> usize| -> Vec<usize> {
            self.counts.iter().map(f).collect()
        };
        let pos = split_lengths(&mut out.positions, &lengths(&|c| 3 * c.vertices));
        let nrm = split_lengths(&mut out.normals, &lengths(&|c| 3 * c.vertices));
        let tan = split_lengths(&mut out.tangents, &lengths(&|c| 3 * c.vertices));
        let col = split_lengths(&mut out.colors, &lengths(&|c| 4 * c.vertices));
        let tri = split_lengths(&mut out.triangles, &lengths(&|c| 3 * c.triangles));
        let ced = split_lengths(&mut out.corner_edges, &lengths(&|c| 3 * c.triangles));
        let edg = split_lengths(&mut out.edges, &lengths(&|c| 2 * c.edges));
        pos.into_par_iter()
            .zip(nrm)
            .zip(tan)
            .zip(col)
            .zip(tri)
            .zip(ced)
            .zip(edg)
            .enumerate()
            .for_each(
                |(
                    i,
                    (
                        (((((positions, normals), tangents), colors), corner_verts), corner_edges),
                        edge_verts,
                    ),
                )| {
                    if crate::cancel::requested() {
                        return;
                    }
                    let mut bufs = PieceBuffers {
                        vertex_base: vbase[i],
                        edge_base: ebase[i],
                        positions,
                        colors: Some(colors),
                        normals: Some(normals),
                        tangents: Some(tangents),
                        topology: Some(TopologyBuffers {
                            corner_verts,
                            corner_edges,
                            edge_verts,
                        }),
                    };
                    self.bundle_span(i, centrelines, None, &mut bufs);
                },
            );

        out.centerline = centrelines
            .points
            .iter()
            .flat_map(|q| q.to_array())
            .collect();
        out.yarn_offsets = std::iter::once(0i64)
            .chain(self.samples.iter().scan(0i64, |acc, &n| {
                *acc += n as i64;
                Some(*acc)
            }))
            .collect();
        out.yarn_course = self.pieces.iter().map(|pc| pc.course as i32).collect();
        out.yarn_closed = self.pieces.iter().map(|pc| pc.closed).collect();
        out
    }
}
