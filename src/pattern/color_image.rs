//! Colours per stitch from an image: the colour pattern a knit or a plush takes where a chart
//! would be too coarse (a photo, a logo).

use glam::{Vec2, Vec3};

use crate::error::{KnitError, Result};

/// An image sampled per stitch at the tile centre: `(u, v)` maps to pixel
/// `(u * width, v * height)`, repeated; row 0 is the bottom row (Blender's pixel order).
#[derive(Debug, Clone, PartialEq)]
pub struct ColorImage {
    pub width: usize,
    pub height: usize,
    /// 3 (RGB) or 4 (RGBA, alpha ignored).
    pub channels: usize,
    /// `height * width * channels` linear values.
    pub pixels: Vec<f32>,
}

impl ColorImage {
    pub fn new(width: usize, height: usize, channels: usize, pixels: Vec<f32>) -> Result<Self> {
        if width == 0 || height == 0 || !(3..=4).contains(&channels) {
            return Err(KnitError::Parameter(format!(
                "a colour image must be (height, width, 3 or 4) with both sizes at least 1, \
                 not ({height}, {width}, {channels})"
            )));
        }
        if pixels.len() != width * height * channels {
            return Err(KnitError::Parameter(
                "colour image buffer has the wrong length".into(),
            ));
        }
        if pixels.iter().any(|p| !p.is_finite()) {
            return Err(KnitError::Parameter(
                "the colour image has NaN or infinite pixels".into(),
            ));
        }
        Ok(Self {
            width,
            height,
            channels,
            pixels,
        })
    }

    /// Bilinear sample at (u,v), repeating.
    pub fn sample(&self, uv: Vec2) -> [f32; 3] {
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let px = |xi: i64, yi: i64| {
            let xi = xi.rem_euclid(self.width as i64) as usize;
            let yi = yi.rem_euclid(self.height as i64) as usize;
            let o = (yi * self.width + xi) * self.channels;
            Vec3::new(self.pixels[o], self.pixels[o + 1], self.pixels[o + 2])
        };
        let (x0, y0) = (x0 as i64, y0 as i64);
        let c = (px(x0, y0) * (1.0 - fx) + px(x0 + 1, y0) * fx) * (1.0 - fy)
            + (px(x0, y0 + 1) * (1.0 - fx) + px(x0 + 1, y0 + 1) * fx) * fy;
        c.max(Vec3::ZERO).to_array()
    }
}
