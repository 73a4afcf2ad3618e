//! Every setting a user gives a knit, declared once: its name, kind, default, range, unit,
//! label and one line of doc.
//!
//! The table is the one source the other layers read:
//! - the core's defaults ([`crate::knit::KnitParams::default`],
//!   [`crate::detail::DetailParams::default`]) and its range checks ([`Setting::check`]);
//! - the Python module's `knitwear.settings()`, from which the Blender add-on builds its
//!   properties (label, tooltip, default, range);
//! - the manual's settings reference, `docs/settings.md` (`scripts/settings_table.py` writes it).
//!
//! The pyo3 signatures and the `.pyi` stub must spell their defaults as literals; a test
//! (`tests/python/core/test_settings.py`) fails when they disagree with this table, and
//! another (`tests/python/blender/test_settings_source.py`) when the add-on's properties do.
//!
//! Where the add-on's default differs from the core's, the difference is declared here
//! ([`Setting::addon_default`] and [`Setting::addon_why`]): the core's defaults are what a
//! script gets (a regular, complete knit); the add-on's what a click in a scene with a
//! camera should give.

use crate::error::{KnitError, Result};

/// What a setting holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Int,
    Float,
    Bool,
}

impl Kind {
    /// The Python type's name, as `knitwear.settings()` reports it.
    pub fn python_name(self) -> &'static str {
        match self {
            Kind::Int => "int",
            Kind::Float => "float",
            Kind::Bool => "bool",
        }
    }
}

/// One setting. Ranges are inclusive, in the setting's unit; an unbounded end is infinite.
/// Booleans have the range 0..=1 and a default of 0 or 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setting {
    /// The keyword of `knitwear.Knit` (and the add-on's property name, unless
    /// `addon_name` says otherwise). `None` in `core_keyword` where the core takes it inside
    /// another keyword (the gauge's stitches and rows are `gauge=(s, r)`).
    pub name: &'static str,
    /// The core's keyword, where it is not `name` (or `None` where it is part of a tuple).
    pub core_keyword: Option<&'static str>,
    /// The tuple keyword it is part of, where `core_keyword` is `None`, as the core spells
    /// it (`gauge=(stitches, rows)`).
    pub part_of: Option<&'static str>,
    /// The Blender property's name, where it is not `name`.
    pub addon_name: Option<&'static str>,
    /// The label the add-on shows.
    pub label: &'static str,
    pub kind: Kind,
    /// The core's default; `None`: worked out from other settings (the counts from the
    /// gauge, the yarn radius from the stitch width).
    pub default: Option<f64>,
    /// The add-on's default, where it differs from the core's (and why, in `addon_why`).
    pub addon_default: Option<f64>,
    pub addon_why: &'static str,
    /// Smallest and largest value the core accepts.
    pub min: f64,
    pub max: f64,
    /// Unit of the value ("" for a pure number).
    pub unit: &'static str,
    /// One line of doc: the add-on's tooltip, the settings reference's description.
    pub doc: &'static str,
}

impl Setting {
    /// The default the add-on gives the property: its own where declared, else the core's
    /// (a setting the core works out has an add-on default).
    pub const fn addon_value(&self) -> f64 {
        match (self.addon_default, self.default) {
            (Some(v), _) => v,
            (None, Some(v)) => v,
            (None, None) => 0.0,
        }
    }

    /// The Blender property's name.
    pub const fn property(&self) -> &'static str {
        match self.addon_name {
            Some(n) => n,
            None => self.name,
        }
    }

    /// The core's default as an `f32` (a setting with a default).
    pub const fn default_f32(&self) -> f32 {
        match self.default {
            Some(v) => v as f32,
            None => 0.0,
        }
    }

    /// The core's default as a count (a setting with a default).
    pub const fn default_usize(&self) -> usize {
        match self.default {
            Some(v) => v as usize,
            None => 0,
        }
    }

    /// `value` if it is finite and within the range, else a [`KnitError::Parameter`] that
    /// names the setting and its range.
    pub fn check<T: Into<f64> + Copy>(&self, value: T) -> Result<()> {
        let v: f64 = value.into();
        if v.is_finite() && v >= self.min && v <= self.max {
            return Ok(());
        }
        let range = match (self.min > f64::MIN, self.max.is_finite()) {
            (true, true) => format!("{}..={}", self.min, self.max),
            (true, false) if self.min > 0.0 && self.min < 1e-30 => "positive".to_string(),
            (true, false) => format!("at least {}", self.min),
            _ => format!("at most {}", self.max),
        };
        let range = if range == "positive" {
            "positive".to_string()
        } else {
            format!("in {range}")
        };
        // A part of a tuple keyword is named by the keyword the caller wrote (`gauge`).
        let who = match self.part_of {
            Some(p) => p.split('=').next().unwrap_or(p),
            None => self.name,
        };
        Err(KnitError::Parameter(format!(
            "{who} must be {range}{}, not {v}",
            if self.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", self.unit)
            }
        )))
    }

    /// A count (`usize`) checked against the range.
    pub fn check_count(&self, value: usize) -> Result<()> {
        self.check(value as f64)
    }
}

/// The smallest positive `f32`: the lower end of a range that only excludes zero.
const POSITIVE: f64 = f32::MIN_POSITIVE as f64;

const fn float(
    name: &'static str,
    label: &'static str,
    default: f64,
    range: (f64, f64),
) -> Setting {
    Setting {
        name,
        core_keyword: Some(name),
        part_of: None,
        addon_name: None,
        label,
        kind: Kind::Float,
        default: Some(default),
        addon_default: None,
        addon_why: "",
        min: range.0,
        max: range.1,
        unit: "",
        doc: "",
    }
}

const fn int(name: &'static str, label: &'static str, default: f64, range: (f64, f64)) -> Setting {
    Setting {
        kind: Kind::Int,
        ..float(name, label, default, range)
    }
}

const fn boolean(name: &'static str, label: &'static str, default: bool) -> Setting {
    Setting {
        kind: Kind::Bool,
        ..float(name, label, if default { 1.0 } else { 0.0 }, (0.0, 1.0))
    }
}

/// Stitches per 10 cm along a course (the gauge; 0.1 scene units).
pub const GAUGE_STITCHES: Setting = Setting {
    core_keyword: None,
    part_of: Some("gauge=(stitches, rows)"),
    unit: "stitches per 10 cm",
    doc: "Gauge: stitches per 10 cm measured along a course (scene units are metres times \
          the scene's unit scale)",
    // A worsted-weight yarn on 4.5 mm needles.
    ..float(
        "gauge_stitches",
        "Stitches / 10 cm",
        20.0,
        (POSITIVE, f64::INFINITY),
    )
};

/// Rows per 10 cm along a wale.
pub const GAUGE_ROWS: Setting = Setting {
    core_keyword: None,
    part_of: Some("gauge=(stitches, rows)"),
    unit: "rows per 10 cm",
    doc: "Gauge: rows (courses) per 10 cm measured along a wale",
    ..float(
        "gauge_rows",
        "Rows / 10 cm",
        28.0,
        (POSITIVE, f64::INFINITY),
    )
};

/// Rows of stitches (along v); the core works them out from the gauge unless given.
pub const COURSES: Setting = Setting {
    default: None,
    addon_default: Some(30.0),
    addon_why: "used only when Size is Counts; the core takes the count from the gauge \
                unless one is given",
    unit: "stitches",
    doc: "Number of courses (rows of stitches) over the whole surface",
    ..int("courses", "Courses", 0.0, (1.0, 1_000_000.0))
};

/// Columns of stitches (along u).
pub const WALES: Setting = Setting {
    name: "wales",
    core_keyword: Some("wales"),
    label: "Wales",
    doc: "Number of wales (columns of stitches) over the whole surface",
    ..COURSES
};

/// Yarn radius; the core works it out from the stitch width unless given.
pub const YARN_RADIUS: Setting = Setting {
    default: None,
    addon_default: Some(0.0),
    addon_why: "0 stands for the core's automatic radius (a Blender property cannot be None); \
                the core takes None for it and refuses 0",
    unit: "scene units",
    doc: "Radius of the yarn in scene units; 0 = automatic, an eighth of the stitch width (the \
          thickness the core's loop shapes are tuned for)",
    ..float("yarn_radius", "Yarn Radius", 0.0, (0.0, f64::INFINITY))
};

pub const FLUFFINESS: Setting = Setting {
    unit: "yarn radii",
    doc: "How far stray fibres stand out of the yarn, as a fraction of its radius (0 = \
          smooth tube)",
    ..float("fluffiness", "Fluffiness", 0.5, (0.0, 4.0))
};

pub const RING_SEGMENTS: Setting = Setting {
    unit: "vertices",
    doc: "Vertices around the yarn's cross-section (more = rounder, heavier)",
    ..int("ring_segments", "Ring Segments", 6.0, (3.0, 64.0))
};

/// Plies twisted round each other; the upper end is [`crate::geometry::plies::MAX_PLIES`].
pub const PLIES: Setting = Setting {
    unit: "plies",
    doc: "Strands twisted round each other in the yarn: grooves that turn along it (1 = a \
          round strand)",
    ..int("plies", "Plies", 1.0, (1.0, 8.0))
};

/// Whether the first and last courses keep their loops live ([`crate::skeleton::edges`]).
pub const LIVE_LOOPS: Setting = Setting {
    doc: "Leave the loops of the first and last courses live, as on the needles, instead of \
          finishing the fabric with a cast-on and a bind-off edge (surfaces open along v)",
    ..boolean("live_loops", "Live Loops", false)
};

pub const SAMPLES_PER_LOOP: Setting = Setting {
    unit: "rings per stitch",
    doc: "Rings along the yarn per stitch loop (more = smoother curves, heavier)",
    ..int("samples_per_loop", "Samples per Loop", 16.0, (6.0, 256.0))
};

pub const TENSION: Setting = Setting {
    doc: "Tension of the cardinal spline through each loop's key points (0 = Catmull-Rom, \
          round loops; towards 1 = straighter segments)",
    ..float("tension", "Spline Tension", 0.0, (0.0, 0.99))
};

/// The recursive perturbation's kappa; its upper end is where no tile can fold
/// ([`crate::lattice::KAPPA_MAX`] explains the bound).
pub const KAPPA: Setting = Setting {
    addon_default: Some(0.005),
    addon_why: "a click should look hand-knitted; a script gets the regular lattice, which \
                tests and comparisons need",
    doc: "How far stitches stray from a perfect grid, as hand knitting does: the kappa of \
          the recursive perturbation (0 = machine-regular; at most 0.02, where no stitch can \
          fold over)",
    ..float("kappa", "Irregularity", 0.0, (0.0, 0.02))
};

pub const SEED: Setting = Setting {
    doc: "Random seed of the stitch irregularity and fibres; the same seed gives the same \
          knit on every machine",
    ..int("seed", "Seed", 0.0, (0.0, f64::INFINITY))
};

pub const COLOR_VARIATION: Setting = Setting {
    doc: "Random per-fibre brightness variation that gives yarn its fibrous look (fraction \
          of the colour)",
    ..float("color_variation", "Variation", 0.15, (0.0, 1.0))
};

/// Stitches at least this many pixels across are built at full quality.
pub const DETAIL_FULL_PX: Setting = Setting {
    core_keyword: None,
    part_of: Some("detail_px=(full, mid, texture)"),
    unit: "pixels",
    doc: "Stitches at least this many pixels across in the render get the full quality set \
          in Yarn",
    ..float("detail_full_px", "Full Above", 12.0, (0.0, f64::INFINITY))
};

pub const DETAIL_MID_PX: Setting = Setting {
    core_keyword: None,
    part_of: Some("detail_px=(full, mid, texture)"),
    unit: "pixels",
    doc: "Stitches at least this many pixels across (and below Full Above) get half the \
          samples and five sixths of the ring segments",
    ..float("detail_mid_px", "Reduced Above", 5.0, (0.0, f64::INFINITY))
};

pub const DETAIL_TEXTURE_PX: Setting = Setting {
    core_keyword: None,
    part_of: Some("detail_px=(full, mid, texture)"),
    unit: "pixels",
    doc: "Stitches smaller than this many pixels are not built: the source surface wears \
          the knitwear texture there. Between this and Reduced Above, stitches are plain \
          tubes of 3 segments",
    ..float(
        "detail_texture_px",
        "Texture Below",
        1.0,
        (0.0, f64::INFINITY),
    )
};

pub const FRUSTUM_MARGIN: Setting = Setting {
    unit: "half-frames",
    doc: "Stitches this far outside the camera's frame (a fraction of the frame's half-size) \
          are still built; the camera is followed over the scene's frame range (negative: \
          stitches outside the frame are built too)",
    ..float(
        "frustum_margin",
        "Frame Margin",
        0.1,
        (f64::NEG_INFINITY, 100.0),
    )
};

pub const CULL_BACK_FACES: Setting = Setting {
    addon_default: Some(1.0),
    addon_why: "the add-on turns it on only for sources it finds closed; a script knows \
                its own surface",
    doc: "On a closed surface, do not build the stitches that face away from the camera in \
          every frame (the front hides them)",
    ..boolean("cull_back_faces", "Cull Back", false)
};

pub const CULL_HIDDEN: Setting = Setting {
    addon_default: Some(1.0),
    addon_why: "the add-on knits for the scene's camera; a script may look from anywhere",
    doc: "Do not build the yarn that other yarn hides from the camera in every sampled \
          frame (most of a knit's triangles: the back of each strand, the loops behind the \
          fabric). A moving camera is followed over the frame range, and a source that \
          animates is seen in each sampled frame's pose",
    ..boolean("cull_hidden", "Cull Hidden Yarn", false)
};

pub const HIDDEN_SUPERSAMPLING: Setting = Setting {
    addon_name: Some("cull_hidden_samples"),
    addon_default: Some(2.0),
    addon_why: "an anti-aliased render spreads its own samples, and yarn under 2 pixels thick \
                is kept wherever they might catch it: 2 per pixel side leaves 9.1x fewer \
                triangles than full detail, within 0.004 SSIM of keeping the hidden yarn",
    unit: "samples per pixel side",
    doc: "Samples per pixel side at which Cull Hidden Yarn looks for the yarn the camera \
          sees (2: 4 samples a pixel; odd counts include the pixel centres a one-sample \
          render looks at). More keeps the slivers between nearer strands, at more \
          triangles and time",
    ..int(
        "hidden_supersampling",
        "Visibility Samples",
        4.0,
        (1.0, 16.0),
    )
};

pub const CULL_HIDDEN_MIN_TRIANGLES: Setting = Setting {
    addon_default: Some(2_000_000.0),
    addon_why: "the hidden-yarn pass costs more than it saves below that: on the demo swatch \
                at 1080p it took 0.27 s to drop 70k of 220k triangles that cost 0.02 s to \
                build, and at 10k stitches 0.9 s to drop 0.94M of 1.9M; above it the \
                triangles it drops are memory and render time the scene keeps paying",
    unit: "triangles",
    doc: "Cull Hidden Yarn runs only where the knit has at least this many triangles at \
          full detail, the yarn thick enough in the image for hidden yarn to be found (it \
          keeps thinner yarn anyway); otherwise the knit is built whole, which is quicker \
          than finding its hidden yarn (0: always)",
    ..int(
        "cull_hidden_min_triangles",
        "Cull From",
        0.0,
        (0.0, 2_000_000_000.0),
    )
};

/// Every knit setting, in the order the add-on and `docs/settings.md` show them.
pub const KNIT_SETTINGS: &[Setting] = &[
    GAUGE_STITCHES,
    GAUGE_ROWS,
    COURSES,
    WALES,
    YARN_RADIUS,
    FLUFFINESS,
    RING_SEGMENTS,
    PLIES,
    LIVE_LOOPS,
    SAMPLES_PER_LOOP,
    TENSION,
    KAPPA,
    SEED,
    COLOR_VARIATION,
    DETAIL_FULL_PX,
    DETAIL_MID_PX,
    DETAIL_TEXTURE_PX,
    FRUSTUM_MARGIN,
    CULL_BACK_FACES,
    CULL_HIDDEN,
    HIDDEN_SUPERSAMPLING,
    CULL_HIDDEN_MIN_TRIANGLES,
];

/// Wales per 10 cm of a plush (the gauge's first number; the paper's fabric has about 48).
pub const PLUSH_GAUGE_WALES: Setting = Setting {
    part_of: Some("gauge=(wales, courses)"),
    label: "Wales / 10 cm",
    unit: "wales per 10 cm",
    doc: "Stitches along a course per 10 cm (the paper's fabric: about 48)",
    default: Some(48.0),
    ..GAUGE_STITCHES
};

/// Courses per 10 cm of a plush.
pub const PLUSH_GAUGE_COURSES: Setting = Setting {
    part_of: Some("gauge=(wales, courses)"),
    label: "Courses / 10 cm",
    unit: "courses per 10 cm",
    doc: "Courses (rows) per 10 cm along a wale",
    default: Some(64.0),
    ..GAUGE_ROWS
};

pub const PLUSH_COURSES: Setting = Setting {
    addon_default: Some(96.0),
    doc: "Courses over the whole surface (along v)",
    ..COURSES
};

pub const PLUSH_WALES: Setting = Setting {
    addon_default: Some(64.0),
    doc: "Wales over the whole surface (along u)",
    ..WALES
};

pub const PILES_PER_STITCH: Setting = Setting {
    unit: "piles",
    doc: "Piles grown from each stitch, on a near-square sub-grid (4: 2x2)",
    ..int("piles_per_stitch", "Piles per Stitch", 1.0, (1.0, 64.0))
};

/// A pile's length; the core makes it 2.5 stitch widths unless given.
pub const PILE_LENGTH: Setting = Setting {
    default: None,
    addon_default: Some(0.0),
    addon_why: "0 stands for the core's automatic length (a Blender property cannot be None)",
    unit: "scene units",
    doc: "Length of a pile; 0 = automatic (2.5 stitch widths)",
    ..float("pile_length", "Pile Length", 0.0, (0.0, f64::INFINITY))
};

/// Half the width of a slice; the core makes it 0.6 pile spacings unless given.
pub const PILE_RADIUS: Setting = Setting {
    default: None,
    addon_default: Some(0.0),
    addon_why: "0 stands for the core's automatic radius (a Blender property cannot be None)",
    unit: "scene units",
    doc: "Half width of a slice; 0 = automatic (0.6 pile spacings)",
    ..float("pile_radius", "Pile Radius", 0.0, (0.0, f64::INFINITY))
};

pub const SLICES: Setting = Setting {
    unit: "quads per pile",
    doc: "Quads per pile",
    ..int("slices", "Slices", 8.0, (1.0, 64.0))
};

/// The angle of the pile's nominal direction from the surface normal.
pub const LEAN_ANGLE: Setting = Setting {
    core_keyword: None,
    part_of: Some("lean=(angle, azimuth)"),
    unit: "radians",
    doc: "Angle of the pile's nominal direction from the surface normal",
    ..float(
        "lean_angle",
        "Lean",
        // The f32 constant, so the core's default is the same bits it always was.
        std::f32::consts::FRAC_PI_6 as f64,
        (0.0, 89.0 * std::f64::consts::PI / 180.0),
    )
};

/// The azimuth of the lean in the fabric plane.
pub const LEAN_DIRECTION: Setting = Setting {
    core_keyword: None,
    part_of: Some("lean=(angle, azimuth)"),
    unit: "radians",
    doc: "Azimuth of the lean in the fabric plane, from the course (u) towards the wale (v)",
    ..float(
        "lean_direction",
        "Lean Direction",
        -std::f32::consts::FRAC_PI_2 as f64,
        (-std::f64::consts::TAU, std::f64::consts::TAU),
    )
};

/// The largest deviation of a pile from its nominal direction: below 45 degrees, the
/// paper's bound ([`crate::pile::fractal_noise::THETA_MAX_LIMIT`]).
pub const THETA_MAX: Setting = Setting {
    unit: "radians",
    doc: "Largest deviation of a pile from the nominal direction (theta_max, below 45 \
          degrees)",
    ..float(
        "theta_max",
        "Noise Angle",
        (20.0 * std::f32::consts::PI / 180.0) as f64,
        (0.0, std::f64::consts::FRAC_PI_4 - 1e-6),
    )
};

pub const PLUSH_SEED: Setting = Setting {
    doc: "Random seed of the noise: same seed, same plush",
    ..SEED
};

pub const PRESS_STRENGTH: Setting = Setting {
    doc: "How far a fully pressed pile bends (0..1)",
    ..float("press_strength", "Press Strength", 0.9, (0.0, 1.0))
};

/// Every plush setting with a number, in the order the add-on shows them.
pub const PLUSH_SETTINGS: &[Setting] = &[
    PLUSH_GAUGE_WALES,
    PLUSH_GAUGE_COURSES,
    PLUSH_COURSES,
    PLUSH_WALES,
    PILES_PER_STITCH,
    PILE_LENGTH,
    PILE_RADIUS,
    SLICES,
    LEAN_ANGLE,
    LEAN_DIRECTION,
    THETA_MAX,
    PLUSH_SEED,
    PRESS_STRENGTH,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_setting_is_whole_and_its_defaults_in_range() {
        for table in [KNIT_SETTINGS, PLUSH_SETTINGS] {
            check_table(table);
        }
    }

    fn check_table(table: &[Setting]) {
        let mut names: Vec<&str> = table.iter().map(Setting::property).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), table.len(), "a name twice");
        for s in table {
            assert!(!s.doc.is_empty() && !s.label.is_empty(), "{}", s.name);
            assert!(s.min <= s.max, "{}", s.name);
            if let Some(d) = s.default {
                s.check(d).unwrap();
            }
            if s.addon_default.is_some() {
                assert!(!s.addon_why.is_empty(), "{}: a difference says why", s.name);
            }
            s.check(s.addon_value())
                .unwrap_or_else(|e| panic!("{}: add-on default out of range: {e}", s.name));
            if s.kind != Kind::Float {
                assert_eq!(s.addon_value().fract(), 0.0, "{}", s.name);
            }
        }
    }

    /// The plush's angles are the f32 constants the core always used, bit for bit.
    #[test]
    fn the_plush_angles_keep_their_bits() {
        use std::f32::consts::{FRAC_PI_2, FRAC_PI_6, PI};
        assert_eq!(LEAN_ANGLE.default_f32().to_bits(), FRAC_PI_6.to_bits());
        assert_eq!(
            LEAN_DIRECTION.default_f32().to_bits(),
            (-FRAC_PI_2).to_bits()
        );
        assert_eq!(
            THETA_MAX.default_f32().to_bits(),
            (20.0f32 * PI / 180.0).to_bits()
        );
    }

    #[test]
    fn a_value_out_of_range_names_the_setting_and_its_range() {
        let e = RING_SEGMENTS.check(2.0).unwrap_err().to_string();
        assert!(
            e.contains("ring_segments must be in 3..=64 vertices, not 2"),
            "{e}"
        );
        let e = GAUGE_ROWS.check(0.0).unwrap_err().to_string();
        assert!(e.contains("gauge must be positive rows per 10 cm"), "{e}");
        assert!(FLUFFINESS.check(f32::NAN).is_err());
        assert!(SEED.check(1e30).is_ok());
    }
}
