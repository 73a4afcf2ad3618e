//! Every setting of a knit ([`KnitParams`]), its defaults (from [`crate::settings`]) and
//! their validation.

use crate::budget::{self};
use crate::detail::DetailParams;
use crate::error::{KnitError, Result};
use crate::pattern::ColorPattern;

/// Gauge used when neither counts nor a gauge are given: 20 stitches and 28 rows per 10 cm
/// (a worsted-weight yarn on 4.5 mm needles; [`crate::settings::GAUGE_STITCHES`]).
pub const DEFAULT_GAUGE: (f32, f32) = (
    crate::settings::GAUGE_STITCHES.default_f32(),
    crate::settings::GAUGE_ROWS.default_f32(),
);

/// Default yarn radius as a fraction of the stitch width: a diameter of a quarter of a
/// stitch, 1.25 mm at the default gauge of 20 stitches per 10 cm (a worsted yarn as it lies
/// in the fabric, pressed flatter than in the ball). Stockinette's loops hide 89% of the
/// fabric with it and clear a diameter (docs/design.md section 3.3); a fifth of a stitch,
/// the default before, hid 75%.
pub const DEFAULT_RADIUS_PER_STITCH_WIDTH: f32 = 0.125;

/// Samples a loop at which [`super::PreparedKnit::crossing_order`] measures the skeleton's topology
/// (at least): the tuning's and the contact relief's.
pub const TOPOLOGY_SAMPLES: usize = 24;

/// Default yarn colour (linear RGB): a warm oatmeal wool.
pub const DEFAULT_YARN_COLOR: [f32; 3] = [0.55, 0.42, 0.30];

pub use crate::gauge::MAX_STITCHES_PER_DIRECTION;

/// Re-exported: a knit's `color_image` setting.
pub use crate::pattern::ColorImage;

/// Every setting of a knit. Lengths in scene units.
#[derive(Debug, Clone)]
pub struct KnitParams {
    /// Rows of stitches (along v). `None`: from the gauge.
    pub courses: Option<usize>,
    /// Columns of stitches (along u). `None`: from the gauge.
    pub wales: Option<usize>,
    /// Stitches and rows per 10 cm (0.1 scene units), measured on the surface. Used for the
    /// counts not given. Default: [`DEFAULT_GAUGE`].
    pub gauge: Option<(f32, f32)>,
    /// Yarn radius. Default: [`DEFAULT_RADIUS_PER_STITCH_WIDTH`] of the mean stitch width
    /// measured on the surface, or of `stitch_size`'s width where that is given (the gauge's
    /// width where a count in the round was rounded to whole pattern repeats).
    pub yarn_radius: Option<f32>,
    /// Stitch width and height (scene units) that the normal offsets (and the rows of leaning
    /// loops) are tuned for. Default: measured on the surface, the tighter stitches' size
    /// ([`crate::tight_stitches`]: the mean stitch where all are alike). An animated knit pins
    /// the values measured at its rest pose, so a stretched frame moves the yarn but never
    /// re-tunes it (which would change every loop's shape from one frame to the next).
    pub stitch_size: Option<(f32, f32)>,
    /// Apex push as a fraction of the radius, 0..=4. Default: 0.5.
    pub fluffiness: f32,
    /// Points per yarn ring, 3..=64. Default: 6.
    pub ring_segments: usize,
    /// Plies twisted round each other ([`crate::geometry::plies`]), 1..=8. Default: 1.
    pub plies: usize,
    /// Leave the first and last courses' loops live: no cast-on or bind-off
    /// ([`crate::skeleton::edges`]). Default: false.
    pub live_loops: bool,
    /// Centreline samples per stitch, 6..=256. Default: 16.
    pub samples_per_loop: usize,
    /// Cardinal spline tension, 0..1 (0: Catmull-Rom). Default: 0.
    pub tension: f32,
    /// Irregularity of stitch positions: the recursive perturbation's kappa ([Zhong 2001],
    /// section 2.4), 0 (a regular lattice) to [`crate::lattice::KAPPA_MAX`]. Default: 0.
    pub kappa: f32,
    pub seed: u64,
    /// Colours per stitch from a palette chart. Default: one yarn colour.
    pub colors: Option<ColorPattern>,
    /// Colours per stitch from an image (wins over `colors`).
    pub color_image: Option<ColorImage>,
    /// Random brightness variation of vertex colours, 0..=1. Default: 0.15.
    pub color_variation: f32,
    /// Threads of the private pool. Default: all cores.
    pub threads: Option<usize>,
    /// Refuse outputs larger than this many bytes. Default: [`budget::DEFAULT_BUDGET_BYTES`].
    pub budget_bytes: u64,
    /// Also measure the clearance of the result (costs about as much as the knit itself).
    pub measure_clearance: bool,
    /// Camera-driven level of detail and culling ([`crate::detail`]). Default: `None`, every
    /// stitch at full quality.
    pub detail: Option<DetailParams>,
}

impl Default for KnitParams {
    /// The defaults of [`crate::settings`].
    fn default() -> Self {
        use crate::settings as s;
        Self {
            courses: None,
            wales: None,
            gauge: None,
            yarn_radius: None,
            stitch_size: None,
            fluffiness: s::FLUFFINESS.default_f32(),
            ring_segments: s::RING_SEGMENTS.default_usize(),
            plies: s::PLIES.default_usize(),
            live_loops: s::LIVE_LOOPS.default == Some(1.0),
            samples_per_loop: s::SAMPLES_PER_LOOP.default_usize(),
            tension: s::TENSION.default_f32(),
            kappa: s::KAPPA.default_f32(),
            seed: 0,
            colors: None,
            color_image: None,
            color_variation: s::COLOR_VARIATION.default_f32(),
            threads: None,
            budget_bytes: budget::DEFAULT_BUDGET_BYTES,
            measure_clearance: false,
            detail: None,
        }
    }
}

pub(super) fn validate(p: &KnitParams) -> Result<()> {
    use crate::settings as s;
    s::FLUFFINESS.check(p.fluffiness)?;
    s::RING_SEGMENTS.check_count(p.ring_segments)?;
    s::PLIES.check_count(p.plies)?;
    s::SAMPLES_PER_LOOP.check_count(p.samples_per_loop)?;
    s::TENSION.check(p.tension)?;
    s::COLOR_VARIATION.check(p.color_variation)?;
    s::KAPPA.check(p.kappa)?;
    if let Some(d) = &p.detail {
        d.validate()?;
    }
    for (setting, n) in [(s::COURSES, p.courses), (s::WALES, p.wales)] {
        if let Some(n) = n {
            setting.check_count(n)?;
        }
    }
    if let Some((stitches, rows)) = p.gauge {
        s::GAUGE_STITCHES.check(stitches)?;
        s::GAUGE_ROWS.check(rows)?;
    }
    if let Some((w, h)) = p.stitch_size {
        if !(w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0) {
            return Err(KnitError::Parameter(format!(
                "stitch size must be a positive width and height, not ({w}, {h})"
            )));
        }
    }
    if let Some(r) = p.yarn_radius {
        if !(r.is_finite() && r > 0.0) {
            return Err(KnitError::Parameter(format!(
                "yarn_radius must be positive (or None: an eighth of the stitch width), not {r}"
            )));
        }
    }
    Ok(())
}
