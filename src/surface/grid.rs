//! PLACEHOLDER until the real grid surface lands.
use super::{Surface, SurfacePoint, UvRect};
use crate::error::{KnitError, Result};
use glam::{Vec2, Vec3};

#[derive(Debug, Clone)]
pub struct GridSurface {
    rows: usize,
    cols: usize,
    p: Vec<Vec3>,
    n: Vec<Vec3>,
    cu: bool,
    cv: bool,
}

impl GridSurface {
    pub fn new(
        rows: usize,
        cols: usize,
        positions: &[f32],
        normals: &[f32],
        cyclic_u: bool,
        cyclic_v: bool,
    ) -> Result<Self> {
        if rows < 2
            || cols < 2
            || positions.len() != rows * cols * 3
            || normals.len() != positions.len()
        {
            return Err(KnitError::Surface("bad grid".into()));
        }
        if positions.iter().chain(normals).any(|x| !x.is_finite()) {
            return Err(KnitError::Surface("non-finite".into()));
        }
        let p = positions
            .chunks(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect();
        let n = normals
            .chunks(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]).normalize_or(Vec3::Z))
            .collect();
        Ok(Self {
            rows,
            cols,
            p,
            n,
            cu: cyclic_u,
            cv: cyclic_v,
        })
    }
    fn idx(&self, i: isize, j: isize) -> usize {
        let i = if self.cv {
            i.rem_euclid(self.rows as isize)
        } else {
            i.clamp(0, self.rows as isize - 1)
        };
        let j = if self.cu {
            j.rem_euclid(self.cols as isize)
        } else {
            j.clamp(0, self.cols as isize - 1)
        };
        i as usize * self.cols + j as usize
    }
}

impl Surface for GridSurface {
    fn domain(&self) -> UvRect {
        UvRect {
            min: Vec2::ZERO,
            max: Vec2::ONE,
        }
    }
    fn cyclic_u(&self) -> bool {
        self.cu
    }
    fn cyclic_v(&self) -> bool {
        self.cv
    }
    fn eval(&self, uv: Vec2) -> Option<SurfacePoint> {
        Some(self.eval_nearest(uv))
    }
    fn eval_nearest(&self, uv: Vec2) -> SurfacePoint {
        let su = if self.cu {
            self.cols as f32
        } else {
            (self.cols - 1) as f32
        };
        let sv = if self.cv {
            self.rows as f32
        } else {
            (self.rows - 1) as f32
        };
        let x = if self.cu {
            uv.x * su
        } else {
            (uv.x * su).clamp(0.0, su)
        };
        let y = if self.cv {
            uv.y * sv
        } else {
            (uv.y * sv).clamp(0.0, sv)
        };
        let (j, i) = (x.floor(), y.floor());
        let (fx, fy) = (x - j, y - i);
        let (i, j) = (i as isize, j as isize);
        let lerp = |a: &Vec<Vec3>| {
            let a00 = a[self.idx(i, j)];
            let a01 = a[self.idx(i, j + 1)];
            let a10 = a[self.idx(i + 1, j)];
            let a11 = a[self.idx(i + 1, j + 1)];
            (a00 * (1.0 - fx) + a01 * fx) * (1.0 - fy) + (a10 * (1.0 - fx) + a11 * fx) * fy
        };
        SurfacePoint {
            position: lerp(&self.p),
            normal: lerp(&self.n).normalize_or(Vec3::Z),
        }
    }
    fn extent(&self) -> (f32, f32) {
        let mut lu = 0.0;
        for i in 0..self.rows {
            for j in 0..self.cols - 1 {
                lu += (self.p[i * self.cols + j + 1] - self.p[i * self.cols + j]).length();
            }
        }
        let mut lv = 0.0;
        for i in 0..self.rows - 1 {
            for j in 0..self.cols {
                lv += (self.p[(i + 1) * self.cols + j] - self.p[i * self.cols + j]).length();
            }
        }
        (lu / self.rows as f32, lv / self.cols as f32)
    }
}
