//! PLACEHOLDER until the real mesh surface lands.
use super::{Surface, SurfacePoint, UvRect};
use crate::error::{KnitError, Result};
use glam::{Vec2, Vec3};

#[derive(Debug, Clone)]
pub struct MeshSurface {
    p: Vec<Vec3>,
    n: Vec<Vec3>,
    t: Vec<[u32; 3]>,
    uv: Vec<[Vec2; 3]>,
    dom: UvRect,
}

impl MeshSurface {
    pub fn new(positions: &[f32], normals: &[f32], triangles: &[u32], uvs: &[f32]) -> Result<Self> {
        let nv = positions.len() / 3;
        if triangles.iter().any(|&i| i as usize >= nv)
            || uvs.len() != triangles.len() * 2
            || triangles.is_empty()
        {
            return Err(KnitError::Surface("bad mesh".into()));
        }
        if positions
            .iter()
            .chain(normals)
            .chain(uvs)
            .any(|x| !x.is_finite())
        {
            return Err(KnitError::Surface("non-finite".into()));
        }
        let p: Vec<Vec3> = positions
            .chunks(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect();
        let n = normals
            .chunks(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]).normalize_or(Vec3::Z))
            .collect();
        let t: Vec<[u32; 3]> = triangles.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
        let uv: Vec<[Vec2; 3]> = uvs
            .chunks(6)
            .map(|c| {
                [
                    Vec2::new(c[0], c[1]),
                    Vec2::new(c[2], c[3]),
                    Vec2::new(c[4], c[5]),
                ]
            })
            .collect();
        let mut mn = Vec2::splat(f32::MAX);
        let mut mx = Vec2::splat(f32::MIN);
        for q in &uv {
            for x in q {
                mn = mn.min(*x);
                mx = mx.max(*x);
            }
        }
        Ok(Self {
            p,
            n,
            t,
            uv,
            dom: UvRect { min: mn, max: mx },
        })
    }
}

impl Surface for MeshSurface {
    fn domain(&self) -> UvRect {
        self.dom
    }
    fn cyclic_u(&self) -> bool {
        false
    }
    fn cyclic_v(&self) -> bool {
        false
    }
    fn eval(&self, q: Vec2) -> Option<SurfacePoint> {
        for (k, [a, b, c]) in self.uv.iter().enumerate() {
            let v0 = *b - *a;
            let v1 = *c - *a;
            let v2 = q - *a;
            let d = v0.perp_dot(v1);
            if d.abs() < 1e-12 {
                continue;
            }
            let l1 = v2.perp_dot(v1) / d;
            let l2 = v0.perp_dot(v2) / d;
            let l0 = 1.0 - l1 - l2;
            if l0 >= -1e-5 && l1 >= -1e-5 && l2 >= -1e-5 {
                let t = self.t[k];
                let pos = self.p[t[0] as usize] * l0
                    + self.p[t[1] as usize] * l1
                    + self.p[t[2] as usize] * l2;
                let nor = self.n[t[0] as usize] * l0
                    + self.n[t[1] as usize] * l1
                    + self.n[t[2] as usize] * l2;
                return Some(SurfacePoint {
                    position: pos,
                    normal: nor.normalize_or(Vec3::Z),
                });
            }
        }
        None
    }
    fn eval_nearest(&self, q: Vec2) -> SurfacePoint {
        self.eval(q).unwrap_or(SurfacePoint {
            position: self.p[self.t[0][0] as usize],
            normal: Vec3::Z,
        })
    }
    fn extent(&self) -> (f32, f32) {
        (1.0, 1.0)
    }
}
