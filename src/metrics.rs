//! PLACEHOLDER (brute force) until the spatial-hash version lands.
use glam::Vec3;
use rayon::prelude::*;

pub const DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS: f32 = 2.0;

pub struct YarnPolyline<'a> {
    pub points: &'a [Vec3],
    pub closed: bool,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearance {
    pub min: f32,
    pub p01: f32,
    pub segments: usize,
}

fn seg_dist(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> f32 {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let a = d1.dot(d1);
    let e = d2.dot(d2);
    let f = d2.dot(r);
    let (s, t);
    if a <= 1e-12 && e <= 1e-12 {
        return r.length();
    }
    if a <= 1e-12 {
        s = 0.0;
        t = (f / e).clamp(0.0, 1.0);
    } else {
        let c = d1.dot(r);
        if e <= 1e-12 {
            t = 0.0;
            s = (-c / a).clamp(0.0, 1.0);
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let mut s0 = if denom > 1e-12 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t0 = (b * s0 + f) / e;
            if t0 < 0.0 {
                t0 = 0.0;
                s0 = (-c / a).clamp(0.0, 1.0);
            } else if t0 > 1.0 {
                t0 = 1.0;
                s0 = ((b - c) / a).clamp(0.0, 1.0);
            }
            s = s0;
            t = t0;
        }
    }
    ((p1 + d1 * s) - (p2 + d2 * t)).length()
}

pub fn clearance(
    yarns: &[YarnPolyline],
    diameter: f32,
    neighbour_arclength: f32,
    cap: f32,
) -> Clearance {
    let mut segs = Vec::new();
    for (yi, y) in yarns.iter().enumerate() {
        let n = y.points.len();
        let mut s = 0.0f32;
        let m = if y.closed { n } else { n.saturating_sub(1) };
        for i in 0..m {
            let a = y.points[i];
            let b = y.points[(i + 1) % n];
            segs.push((yi, a, b, s));
            s += (b - a).length();
        }
    }
    let excl = neighbour_arclength * diameter;
    let per: Vec<f32> = segs
        .par_iter()
        .map(|&(yi, a, b, s)| {
            let mut best = cap * diameter;
            for &(yj, c, d, t) in &segs {
                if yi == yj && ((s - t).abs() - (b - a).length().max((d - c).length())) < excl {
                    continue;
                }
                best = best.min(seg_dist(a, b, c, d));
            }
            best / diameter
        })
        .collect();
    let mut sorted = per.clone();
    sorted.sort_by(f32::total_cmp);
    let min = sorted.first().copied().unwrap_or(cap);
    let p01 = sorted.get(sorted.len() / 100).copied().unwrap_or(cap);
    Clearance {
        min,
        p01,
        segments: segs.len(),
    }
}
