//! Cubic cardinal splines through key points ([Zhong 2001], section 2.3).
//!
//! Key point `i` sits at parameter `t = i`. With uniform knots the tangent at key point `i`
//! is `(1 - tension) (p[i+1] - p[i-1]) / 2`; tension 0 is the Catmull-Rom spline, tension 1
//! the polyline. Cardinal splines are affine-invariant, so a spline built in (u, v, lambda)
//! space maps to the same curve under any affine map of the domain.
//!
//! Where the caller spaces the knots ([`CardinalSpline::spacing`], see
//! [`super::knot_spacing`]), a segment is the Catmull-Rom segment of those knots (Barry and
//! Goldman's recursion written as Hermite tangents, as in [Yuksel 2011]), each tangent
//! scaled by `1 - tension` and the segment still mapped onto `[i, i + 1]`: the curve keeps
//! its key points, its sampling and a continuous tangent direction.

use glam::Vec3;

/// A cardinal spline through `points`; `closed` wraps the last point to the first, shifted
/// by `period` for each wrap (a course round a cyclic-u surface comes back to its start one
/// domain width further on in u).
#[derive(Debug, Clone, Copy)]
pub struct CardinalSpline<'a> {
    pub points: &'a [Vec3],
    pub closed: bool,
    pub tension: f32,
    /// Added to a point each time the index wraps past the end (closed splines only).
    pub period: Vec3,
    /// Knot spacing of each chord, `spacing[i]` from key point `i` to `i + 1` (for a closed
    /// spline the last one closes it), all positive; `None`: uniform. A segment whose three
    /// chords are spaced alike is the uniform one exactly.
    pub spacing: Option<&'a [f32]>,
}

impl CardinalSpline<'_> {
    /// The largest parameter value: `n - 1` for an open spline, `n` (back at the start) for a
    /// closed one.
    pub fn t_max(&self) -> f32 {
        let n = self.points.len();
        if self.closed {
            n as f32
        } else {
            n.saturating_sub(1) as f32
        }
    }

    fn point(&self, i: isize) -> Vec3 {
        let n = self.points.len() as isize;
        if self.closed {
            self.points[i.rem_euclid(n) as usize] + i.div_euclid(n) as f32 * self.period
        } else if i < 0 {
            // Reflect the first segment so the end tangent follows the yarn.
            2.0 * self.points[0] - self.points[1.min(n - 1) as usize]
        } else if i >= n {
            2.0 * self.points[(n - 1) as usize] - self.points[(n - 2).max(0) as usize]
        } else {
            self.points[i as usize]
        }
    }

    /// The knot spacings of the chords before, of and after segment `i`. An open spline's
    /// reflected end chords take the spacing of the chord they reflect.
    fn knots(&self, spacing: &[f32], i: isize) -> (f32, f32, f32) {
        let n = self.points.len() as isize;
        let chord = |j: isize| {
            let j = if self.closed {
                j.rem_euclid(n)
            } else {
                j.clamp(0, n - 2)
            };
            spacing[j as usize]
        };
        (chord(i - 1), chord(i), chord(i + 1))
    }

    /// The point at parameter `t` (clamped to `[0, t_max]`). Passes through key point `i` at
    /// `t = i` exactly.
    pub fn eval(&self, t: f32) -> Vec3 {
        let n = self.points.len();
        if n == 0 {
            return Vec3::ZERO;
        }
        if n == 1 {
            return self.points[0];
        }
        let t = t.clamp(0.0, self.t_max());
        let mut i = t.floor() as isize;
        let last_segment = if self.closed {
            n as isize - 1
        } else {
            n as isize - 2
        };
        if i > last_segment {
            i = last_segment;
        }
        let s = t - i as f32;
        let p0 = self.point(i - 1);
        let p1 = self.point(i);
        let p2 = self.point(i + 1);
        let p3 = self.point(i + 2);
        let (m1, m2) = match self.spacing.map(|sp| self.knots(sp, i)) {
            Some((d0, d1, d2)) if d0 != d1 || d1 != d2 => {
                // The non-uniform Catmull-Rom tangents, scaled to the segment's unit span.
                let k = 1.0 - self.tension;
                let m1 = k * d1 * ((p1 - p0) / d0 - (p2 - p0) / (d0 + d1) + (p2 - p1) / d1);
                let m2 = k * d1 * ((p2 - p1) / d1 - (p3 - p1) / (d1 + d2) + (p3 - p2) / d2);
                (m1, m2)
            }
            _ => {
                let k = 0.5 * (1.0 - self.tension);
                (k * (p2 - p0), k * (p3 - p1))
            }
        };
        let s2 = s * s;
        let s3 = s2 * s;
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h10 = s3 - 2.0 * s2 + s;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h11 = s3 - s2;
        h00 * p1 + h10 * m1 + h01 * p2 + h11 * m2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_through_key_points_open_and_closed() {
        let pts: Vec<Vec3> = (0..7)
            .map(|i| Vec3::new(i as f32, (i as f32 * 1.3).sin(), (i * i) as f32 * 0.1))
            .collect();
        for closed in [false, true] {
            for tension in [0.0, 0.3, 0.9] {
                let s = CardinalSpline {
                    points: &pts,
                    closed,
                    tension,
                    period: Vec3::ZERO,
                    spacing: None,
                };
                for (i, p) in pts.iter().enumerate() {
                    assert!(
                        (s.eval(i as f32) - *p).length() < 1e-5,
                        "closed={closed} i={i}"
                    );
                }
            }
        }
        let s = CardinalSpline {
            points: &pts,
            closed: true,
            tension: 0.0,
            period: Vec3::ZERO,
            spacing: None,
        };
        assert!((s.eval(7.0) - pts[0]).length() < 1e-5);
        // With a period, a closed spline ends at its start one period further on.
        let period = Vec3::new(10.0, 0.0, 0.0);
        let s = CardinalSpline {
            points: &pts,
            closed: true,
            tension: 0.0,
            period,
            spacing: None,
        };
        assert!((s.eval(7.0) - (pts[0] + period)).length() < 1e-5);
        assert!((6.0..10.0).contains(&s.eval(6.5).x));
    }

    #[test]
    fn tension_one_is_the_polyline() {
        let pts = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0)];
        let s = CardinalSpline {
            points: &pts,
            closed: false,
            tension: 1.0,
            period: Vec3::ZERO,
            spacing: None,
        };
        assert!((s.eval(0.5) - Vec3::new(0.5, 0.0, 0.0)).length() < 1e-6);
        assert!((s.eval(1.5) - Vec3::new(1.0, 0.5, 0.0)).length() < 1e-6);
    }
}
