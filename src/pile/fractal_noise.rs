//! Fractal noise of pile directions ([Zhang plush], section 1, figure 3 and formula (1); our
//! reading is docs/design.md section 6).
//!
//! - **Base noise**: per texel, `theta ~ U(0, theta_max)` (how far the pile strays from its
//!   nominal direction, `theta_max < 45 deg`) and `phi ~ U(0, 2 pi)` (which way), giving the
//!   unit vector `v = (sin theta cos phi, sin theta sin phi, cos theta)` in the *noise frame*,
//!   whose z axis is the pile's nominal direction.
//! - **Sampled noise with coefficient k**: keep every k-th texel of the base noise in both
//!   directions and fill the others by bilinear interpolation of the four surrounding kept
//!   texels with the smoothstep weight `s(t) = 3t^2 - 2t^3` (first along x, then along y, as
//!   the paper's figure 2). `k = 1` is the base noise itself.
//! - **Fractal noise**, formula (1) in our reading: `P = sum_i k_i P_i / sum_i k_i` (coarser
//!   samplings weigh more and set the overall shape, finer ones add detail), renormalised to
//!   unit length.
//!
//! The texture is tileable: kept texels wrap round the right and top borders (a last cell
//! shorter than `k` when `k` does not divide the size interpolates towards texel 0), so a
//! cylinder or torus shows no seam. Every texel of the fractal noise is a normalised positive
//! combination of base vectors, all inside the cone of half-angle `theta_max` round z; that
//! cone is convex (`theta_max < 90 deg`), so the fractal noise stays within `theta_max` too.
//!
//! Randomness is keyed by texel: texel (x, y) draws its two angles from a ChaCha8 generator
//! seeded by `(seed, x, y)` alone, so the noise does not depend on threads or on the order the
//! texels are visited, and a texel keeps its angles when the texture grows.

use std::f32::consts::{FRAC_PI_4, TAU};

use glam::{Vec2, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::error::{KnitError, Result};
use crate::portable_math::sin_cos;

/// The paper's sampling coefficients: k = 1, 2, 4, 8.
pub const DEFAULT_SCALES: [usize; 4] = [1, 2, 4, 8];
/// Default largest deviation from the nominal direction: 20 degrees (0.349 rad). The paper
/// only says "usually below 45 degrees"; 20 reads as natural variation, not as a mess.
pub const DEFAULT_THETA_MAX: f32 = crate::settings::THETA_MAX.default_f32();
/// `theta_max` must stay below this (45 degrees, the paper's bound), exclusive.
pub const THETA_MAX_LIMIT: f32 = FRAC_PI_4;
/// Largest sampling coefficient.
pub const MAX_SCALE: usize = 4096;
/// Most sampling coefficients in one mix.
pub const MAX_SCALES: usize = 16;
/// Largest noise texture side, in texels.
pub const MAX_NOISE_SIDE: usize = 1 << 15;

/// Mixed into the seed so the noise draws differ from other users of `(seed, i, j)`.
const NOISE_SALT: u64 = 0x6E6F_6973_655F_7069; // "noise_pi"

/// Settings of a fractal noise texture.
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseParams {
    /// Texels along x (the surface's u, along a course). At least 1.
    pub width: usize,
    /// Texels along y (the surface's v, along a wale). At least 1.
    pub height: usize,
    /// Radians, `0 <= theta_max < pi/4`. Default: [`DEFAULT_THETA_MAX`].
    pub theta_max: f32,
    /// Sampling coefficients `k_i`, each `1..=MAX_SCALE`, at most [`MAX_SCALES`] of them.
    /// Default: [`DEFAULT_SCALES`]. `[1]` gives the base noise.
    pub scales: Vec<usize>,
    pub seed: u64,
}

impl NoiseParams {
    /// A `width x height` texture with the default angle bound and scales.
    pub fn new(width: usize, height: usize, seed: u64) -> Self {
        Self {
            width,
            height,
            theta_max: DEFAULT_THETA_MAX,
            scales: DEFAULT_SCALES.to_vec(),
            seed,
        }
    }

    /// Refuses out-of-range settings (never panics on user input).
    pub fn validate(&self) -> Result<()> {
        for (name, n) in [("width", self.width), ("height", self.height)] {
            if !(1..=MAX_NOISE_SIDE).contains(&n) {
                return Err(KnitError::Parameter(format!(
                    "noise {name} must be 1..={MAX_NOISE_SIDE} texels, not {n}"
                )));
            }
        }
        if !(self.theta_max.is_finite()
            && self.theta_max >= 0.0
            && self.theta_max < THETA_MAX_LIMIT)
        {
            return Err(KnitError::Parameter(format!(
                "theta_max must be at least 0 and below pi/4 (45 degrees), in radians, not {}",
                self.theta_max
            )));
        }
        if self.scales.is_empty() || self.scales.len() > MAX_SCALES {
            return Err(KnitError::Parameter(format!(
                "noise scales must list 1..={MAX_SCALES} sampling coefficients, not {}",
                self.scales.len()
            )));
        }
        if let Some(k) = self.scales.iter().find(|k| !(1..=MAX_SCALE).contains(*k)) {
            return Err(KnitError::Parameter(format!(
                "each noise scale (sampling coefficient k) must be 1..={MAX_SCALE}, not {k}"
            )));
        }
        Ok(())
    }
}

/// A texture of unit vectors, row-major, row 0 at the bottom (v minimum, Blender's pixel
/// order), `vectors[y * width + x]`.
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseField {
    pub width: usize,
    pub height: usize,
    pub vectors: Vec<Vec3>,
}

impl NoiseField {
    /// The vector of texel (x, y).
    #[inline]
    pub fn at(&self, x: usize, y: usize) -> Vec3 {
        self.vectors[y * self.width + x]
    }

    /// The texel holding normalised coordinates `st` in `[0,1]^2` (nearest texel: texel
    /// `(x, y)` covers `[x/W, (x+1)/W) x [y/H, (y+1)/H)`); outside, repeated.
    pub fn lookup(&self, st: Vec2) -> Vec3 {
        let x = ((st.x * self.width as f32).floor() as i64).rem_euclid(self.width as i64);
        let y = ((st.y * self.height as f32).floor() as i64).rem_euclid(self.height as i64);
        self.at(x as usize, y as usize)
    }

    /// `(H, W, 3)` f32 components, for NumPy.
    pub fn to_flat(&self) -> Vec<f32> {
        self.vectors.iter().flat_map(|v| v.to_array()).collect()
    }

    /// The paper's noise image: `R = (x + 1) / 2`, `G = (y + 1) / 2`, `B = (z + 1) / 2`,
    /// `(H, W, 3)` f32 in `[0, 1]` (row 0 at the bottom).
    pub fn to_rgb(&self) -> Vec<f32> {
        self.vectors
            .iter()
            .flat_map(|v| ((*v + Vec3::ONE) * 0.5).to_array())
            .collect()
    }

    /// [`to_rgb`](Self::to_rgb) as 8-bit values (the paper's `x 255`), rounded.
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.to_rgb()
            .into_iter()
            .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
            .collect()
    }
}

/// The project's seed hash (splitmix64 finaliser of the seed and two indices), salted for the
/// noise. Same inputs, same 64 bits, on every machine.
pub fn texel_seed(seed: u64, x: usize, y: usize) -> u64 {
    crate::rng::cell_seed(seed ^ NOISE_SALT, y, x)
}

/// The base noise's angles `(theta, phi)` of texel (x, y), radians.
pub fn base_angles(seed: u64, x: usize, y: usize, theta_max: f32) -> (f32, f32) {
    let mut rng = ChaCha8Rng::seed_from_u64(texel_seed(seed, x, y));
    let theta = theta_max * rng.random::<f32>();
    let phi = TAU * rng.random::<f32>();
    (theta, phi)
}

/// `(sin theta cos phi, sin theta sin phi, cos theta)`.
#[inline]
pub fn from_angles(theta: f32, phi: f32) -> Vec3 {
    let (st, ct) = sin_cos(theta);
    let (sp, cp) = sin_cos(phi);
    Vec3::new(st * cp, st * sp, ct)
}

/// The base noise: one random unit vector per texel (runs on the current rayon pool).
pub fn base_noise(p: &NoiseParams) -> Result<NoiseField> {
    p.validate()?;
    let (w, h) = (p.width, p.height);
    let mut vectors = vec![Vec3::ZERO; w * h];
    vectors.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, v) in row.iter_mut().enumerate() {
            let (theta, phi) = base_angles(p.seed, x, y, p.theta_max);
            *v = from_angles(theta, phi);
        }
    });
    Ok(NoiseField {
        width: w,
        height: h,
        vectors,
    })
}

/// Perlin's smoothstep weight `3t^2 - 2t^3`.
#[inline]
pub fn smoothstep(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

/// Along one axis of `n` texels with coefficient `k`: the kept texels below and above `i`
/// (wrapping to 0 past the end) and the position of `i` between them in `[0, 1)`.
#[inline]
fn cell(i: usize, k: usize, n: usize) -> (usize, usize, f32) {
    let i0 = i / k * k;
    let (i1, len) = if i0 + k < n { (i0 + k, k) } else { (0, n - i0) };
    (i0, i1, (i - i0) as f32 / len as f32)
}

/// Sampled noise with coefficient `k` at texel (x, y): the smoothstep-bilinear interpolation
/// of the four kept texels around it (not renormalised).
#[inline]
pub fn sampled_at(base: &NoiseField, k: usize, x: usize, y: usize) -> Vec3 {
    if k == 1 {
        return base.at(x, y);
    }
    let (x0, x1, tx) = cell(x, k, base.width);
    let (y0, y1, ty) = cell(y, k, base.height);
    let (sx, sy) = (smoothstep(tx), smoothstep(ty));
    let bottom = base.at(x0, y0).lerp(base.at(x1, y0), sx);
    let top = base.at(x0, y1).lerp(base.at(x1, y1), sx);
    bottom.lerp(top, sy)
}

/// The fractal mix of `base` (formula (1)), renormalised: the fractal noise.
pub fn mix(base: &NoiseField, scales: &[usize]) -> NoiseField {
    let (w, h) = (base.width, base.height);
    let total: f32 = scales.iter().map(|&k| k as f32).sum();
    let mut vectors = vec![Vec3::ZERO; w * h];
    vectors.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let mut acc = Vec3::ZERO;
            for &k in scales {
                acc += k as f32 * sampled_at(base, k, x, y);
            }
            *out = (acc / total).try_normalize().unwrap_or(Vec3::Z);
        }
    });
    NoiseField {
        width: w,
        height: h,
        vectors,
    }
}

/// The fractal noise of `p`, in the noise frame (z = nominal pile direction). Runs on the
/// current rayon pool; the result does not depend on its size.
pub fn fractal_noise(p: &NoiseParams) -> Result<NoiseField> {
    let base = base_noise(p)?;
    if p.scales == [1] {
        return Ok(base);
    }
    Ok(mix(&base, &p.scales))
}

/// Formula (2) in our reading: the rotation that takes z to the unit vector `t` (the shortest
/// arc), applied to `v`. Frames: `v` in the noise frame (z' = t), the result in the fabric
/// frame (x along the course, y along the wale, z the normal). Needs `t.z > -1`; piles never
/// point into the fabric, so `t.z >= 0` here.
#[inline]
pub fn rotate_z_to(t: Vec3, v: Vec3) -> Vec3 {
    let c = 1.0 / (1.0 + t.z);
    let (a, b) = (t.x, t.y);
    Vec3::new(
        (1.0 - a * a * c) * v.x - a * b * c * v.y + a * v.z,
        -a * b * c * v.x + (1.0 - b * b * c) * v.y + b * v.z,
        -a * v.x - b * v.y + t.z * v.z,
    )
}
