//! An exact flat rectangle, `s(u,v) = (u * width, v * height, 0)` over `[0,1]^2`. Used to tune
//! normal offsets on a flat patch with the stitch size of the real surface, and in tests.

use glam::{Vec2, Vec3};

use super::{Surface, SurfacePoint, UvRect};

/// A flat `width x height` rectangle in the z = 0 plane, normal +z, in scene units.
#[derive(Debug, Clone, Copy)]
pub struct PlaneSurface {
    pub width: f32,
    pub height: f32,
}

impl Surface for PlaneSurface {
    fn domain(&self) -> UvRect {
        UvRect {
            min: Vec2::ZERO,
            max: Vec2::ONE,
        }
    }
    fn cyclic_u(&self) -> bool {
        false
    }
    fn cyclic_v(&self) -> bool {
        false
    }
    fn eval(&self, uv: Vec2) -> Option<SurfacePoint> {
        Some(self.eval_nearest(uv))
    }
    fn eval_nearest(&self, uv: Vec2) -> SurfacePoint {
        SurfacePoint {
            position: Vec3::new(uv.x * self.width, uv.y * self.height, 0.0),
            normal: Vec3::Z,
        }
    }
    fn extent(&self) -> (f32, f32) {
        (self.width, self.height)
    }
}
