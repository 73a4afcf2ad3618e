//! What a knit returns: flat buffers in the dtypes Blender's `foreach_set` takes, and the
//! figures about them.

use glam::Vec3;

use super::*;

/// Figures about a knit.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KnitStats {
    pub courses: usize,
    pub wales: usize,
    /// Stitches built.
    pub stitches: usize,
    /// Stitches not built because part of them had no surface (outside every UV island).
    pub stitches_skipped: usize,
    /// Of `stitches_skipped`, those whose centre is on the surface: fabric lost where a UV
    /// island ends part-way through a stitch. The rest lie in empty UV space.
    pub stitches_lost: usize,
    /// Built stitches whose normal offsets were clamped because the surface curves more
    /// tightly there than the offsets reach (a thin tube, a sharp crease; see
    /// [`crate::skeleton::curvature`]). Counted per build (the pose decides it), so 0 in
    /// [`PreparedKnit::stats`].
    pub stitches_clamped: usize,
    pub vertices: usize,
    pub triangles: usize,
    pub yarn_pieces: usize,
    /// Whether the fabric closes round along u and along v: knitted in the round (a closed
    /// NURBS surface, or a mesh whose UV seam closes it: [`crate::surface::MeshSurface`]).
    pub in_the_round: (bool, bool),
    /// Stitch width and height measured on the surface (scene units).
    pub stitch_width: f32,
    pub stitch_height: f32,
    /// How far the stitches' sizes on the surface spread round their mean (the UV map's
    /// stretch), measured when the stitch size is not pinned; `None` where it is.
    pub stitch_spread: Option<crate::tight_stitches::StitchSpread>,
    /// Clearance of the tuned offsets on a flat patch, in yarn diameters.
    pub flat_clearance: f32,
    /// Clearance of this result (min, 1st percentile) in diameters, if measured.
    pub clearance: Option<(f32, f32)>,
    /// The interlock of this result, if measured (with the clearance): crossings between a
    /// course and the loops it is pulled through, and how many of them have the yarn the
    /// pattern says in front ([`crate::skeleton::crossings`]). Equal numbers: every course
    /// interlocks with the one below, stitch by stitch.
    pub interlock: Option<(usize, usize)>,
    /// Loops that nothing is pulled through and stitches pulled through no loop, if measured
    /// (with the interlock): 0 and 0 where the fabric is finished with a cast-on and a
    /// bind-off ([`crate::skeleton::crossings::CrossingOrder::free_loops`]).
    pub free_loops: Option<(usize, usize)>,
    /// Seconds spent in the core.
    pub seconds: f64,
    /// A key of the mesh topology (triangles, edges, their order): equal keys mean identical
    /// `triangles`, `edges` and `corner_edges` buffers, so a consumer holding a mesh with this
    /// key need only rewrite positions and colours. It depends on the yarn pieces' lengths,
    /// whether they are closed, and the ring segments; never on positions or random choices
    /// (each triangle owns its apex vertex, so the random apex picks move vertices only).
    pub topology_key: u64,
    /// Stitches at each [`Level`] (full, mid, far, texture, culled), of the `stitches` that
    /// have a surface. Without camera-driven detail all are full.
    pub levels: [usize; 5],
    /// Triangles the same knit has with every stitch at full quality (equal to `triangles`
    /// without camera-driven detail).
    pub triangles_full_detail: usize,
    /// Triangles culled as hidden behind other yarn from every view (`cull_hidden`; 0
    /// without). `triangles` are those left.
    pub triangles_hidden: usize,
    /// With `cull_hidden`, whether the hidden-yarn pass ran (or pinned seen triangles
    /// applied): false where the knit has fewer full-quality triangles than
    /// [`crate::detail::DetailParams::cull_hidden_min_triangles`]. `None` without
    /// `cull_hidden`.
    pub hidden_pass: Option<bool>,
    /// Seconds the hidden-yarn pass took (building the whole knit to look at included); 0
    /// where it did not run.
    pub hidden_pass_seconds: f64,
}

/// A knit, in flat buffers.
#[derive(Debug, Clone, Default)]
pub struct KnitOutput {
    /// `(V, 3)` vertex positions, scene units, the surface's object space.
    pub positions: Vec<f32>,
    /// `(V, 4)` linear RGBA.
    pub colors: Vec<f32>,
    /// `(T, 3)` vertex indices.
    pub triangles: Vec<i32>,
    /// `(3T,)` edge from corner k to corner k+1 of each triangle.
    pub corner_edges: Vec<i32>,
    /// `(E, 2)` vertex indices.
    pub edges: Vec<i32>,
    /// `(P, 3)` yarn centreline samples.
    pub centerline: Vec<f32>,
    /// `(Y + 1,)`: yarn piece `i` is samples `offsets[i]..offsets[i + 1]`.
    pub yarn_offsets: Vec<i64>,
    /// `(Y,)` the course of each yarn piece.
    pub yarn_course: Vec<i32>,
    /// `(Y,)` whether each yarn piece is closed (a whole course round a cyclic-u surface).
    pub yarn_closed: Vec<bool>,
    /// `(V, 3)` unit shading normals: the swept tube's, out from the yarn's centreline at
    /// each vertex (see [`crate::geometry::build_bundle`]), for a renderer to shade with in
    /// place of the normals the fibre triangles give. A knit with its hidden yarn culled
    /// has the whole knit's at the vertices it keeps.
    pub normals: Vec<f32>,
    /// `(V, 3)` unit fibre directions: tangents of the swept tube along the yarn, slanted
    /// round it with the plies' twist, perpendicular to `normals` (see
    /// [`crate::geometry::build_bundle`]), for a material's anisotropic highlight. Culled
    /// like `normals`.
    pub tangents: Vec<f32>,
    pub yarn_radius: f32,
    pub stats: KnitStats,
}

/// One yarn piece's centreline in (u, v, lambda): see [`PreparedKnit::uv_centrelines`].
#[derive(Debug, Clone)]
pub struct UvYarn {
    /// Samples in (u, v, lambda); u may run past the domain on a cyclic-u surface.
    pub points: Vec<Vec3>,
    /// (course, wale) of the stitch each sample belongs to.
    pub stitches: Vec<(usize, usize)>,
    /// A whole course round a cyclic-u surface: the last sample joins the first moved by
    /// `period_u` along u.
    pub closed: bool,
    /// The ball of a bobble (see [`crate::skeleton::bobbles`]), not a course's yarn.
    pub bobble: bool,
    /// The domain's width in u (the period of a cyclic u).
    pub period_u: f32,
}

/// Clearance (min, p01) of a finished knit, in yarn diameters.
pub fn measure(out: &KnitOutput) -> (f32, f32) {
    let pieces: Vec<(usize, usize, bool)> = out
        .yarn_offsets
        .windows(2)
        .zip(&out.yarn_closed)
        .map(|(w, &closed)| (w[0] as usize, w[1] as usize, closed))
        .collect();
    crate::metrics::yarn_clearance(vec3_slice(&out.centerline), &pieces, out.yarn_radius)
}
