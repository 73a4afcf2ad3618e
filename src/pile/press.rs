//! The press map: where something pressed the fabric (a palm, [Zhang plush] figure 7), the pile is
//! bent over towards the fabric plane.
//!
//! A press map is a greyscale image of weights in `[0, 1]` over the surface's (u,v): pixel
//! `(x, y)` covers `u in [x/W, (x+1)/W)`, `v in [y/H, (y+1)/H)` (row 0 at v = 0, Blender's
//! pixel order, so an image painted over a UV map lines up), sampled bilinearly between pixel
//! centres and clamped at the borders (a palm print does not repeat).
//!
//! Bending, in the fabric frame (x along the course, y along the wale, z the normal): with
//! `s = weight * strength`, the pile direction `d` becomes `normalize((1 - s) d + s p)` where
//! `p = (cos e cos a, cos e sin a, sin e)` is the pressed direction: azimuth `a` in the fabric
//! plane and a small elevation `e` ([`PRESS_ELEVATION`]) above it, so fully pressed pile lies almost flat
//! without sinking into the fabric.

use glam::{Vec2, Vec3};

use crate::error::{KnitError, Result};
use crate::portable_math::sin_cos;

/// Elevation above the fabric plane of fully pressed pile: 0.12 rad (about 7 degrees).
pub const PRESS_ELEVATION: f32 = 0.12;

/// Weights in `[0, 1]` over (u,v), row-major, row 0 at v = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct PressMap {
    pub width: usize,
    pub height: usize,
    pub weights: Vec<f32>,
}

impl PressMap {
    /// Checks the size and that every weight is finite and in `[0, 1]`.
    pub fn new(width: usize, height: usize, weights: Vec<f32>) -> Result<Self> {
        if width == 0 || height == 0 {
            return Err(KnitError::Parameter(format!(
                "a press map must be at least 1 x 1 pixels, not {width} x {height}"
            )));
        }
        if weights.len() != width.saturating_mul(height) {
            return Err(KnitError::Parameter(format!(
                "a {width} x {height} press map needs {} weights, not {}",
                width.saturating_mul(height),
                weights.len()
            )));
        }
        if let Some(w) = weights
            .iter()
            .find(|w| !(w.is_finite() && (0.0..=1.0).contains(*w)))
        {
            return Err(KnitError::Parameter(format!(
                "press weights must be in 0..=1, found {w}"
            )));
        }
        Ok(Self {
            width,
            height,
            weights,
        })
    }

    /// Bilinear weight at (u,v), clamped at the borders.
    pub fn sample(&self, uv: Vec2) -> f32 {
        let x = (uv.x * self.width as f32 - 0.5).clamp(0.0, (self.width - 1) as f32);
        let y = (uv.y * self.height as f32 - 0.5).clamp(0.0, (self.height - 1) as f32);
        if !(x.is_finite() && y.is_finite()) {
            return 0.0;
        }
        let (x0, y0) = (x.floor() as usize, y.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (fx, fy) = (x - x0 as f32, y - y0 as f32);
        let px = |xi: usize, yi: usize| self.weights[yi * self.width + xi];
        let bottom = px(x0, y0) + (px(x1, y0) - px(x0, y0)) * fx;
        let top = px(x0, y1) + (px(x1, y1) - px(x0, y1)) * fx;
        bottom + (top - bottom) * fy
    }
}

/// The direction fully pressed pile takes, in the fabric frame: azimuth `azimuth` (radians
/// from the course direction x towards the wale direction y), [`PRESS_ELEVATION`] above the
/// fabric plane.
pub fn pressed_direction(azimuth: f32) -> Vec3 {
    let (se, ce) = sin_cos(PRESS_ELEVATION);
    let (sa, ca) = sin_cos(azimuth);
    Vec3::new(ce * ca, ce * sa, se)
}

/// Bends the unit fabric-frame direction `d` by `amount` in `[0, 1]` towards `pressed`.
#[inline]
pub fn bend(d: Vec3, pressed: Vec3, amount: f32) -> Vec3 {
    if amount <= 0.0 {
        return d;
    }
    (d * (1.0 - amount) + pressed * amount)
        .try_normalize()
        .unwrap_or(pressed)
}
