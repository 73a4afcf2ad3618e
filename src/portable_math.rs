//! Transcendental functions that give the same bits on every machine.
//!
//! `f32::sin` and friends call the platform's maths library, whose last bit differs between
//! C libraries and their versions; a farm of mixed machines would then render frames that
//! differ by an ulp here and there. The `libm` crate (rust-lang's port of musl's libm) is
//! pure Rust, so the same inputs give the same bits wherever the core runs. glam is built with
//! its `libm` feature for the same reason.

/// `(sin x, cos x)`, `x` in radians.
#[inline]
pub fn sin_cos(x: f32) -> (f32, f32) {
    (libm::sinf(x), libm::cosf(x))
}

/// The angle of `(x, y)` from the x axis, radians in `[-pi, pi]`.
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    libm::atan2f(y, x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agrees_with_the_platform_to_an_ulp_or_two() {
        for k in 0..1000 {
            let x = -10.0 + 0.02 * k as f32;
            let (s, c) = sin_cos(x);
            assert!((s - x.sin()).abs() <= 2.0 * f32::EPSILON);
            assert!((c - x.cos()).abs() <= 2.0 * f32::EPSILON);
            assert!((atan2(s, c) - s.atan2(c)).abs() <= 4.0 * f32::EPSILON);
        }
    }
}
