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

/// `acos x` in radians, for `x` in `[-1, 1]` (clamped), to within 1e-6 radians (Abramowitz
/// and Stegun 4.4.46: a polynomial and one square root). For weights, where a few times
/// `libm::acosf`'s speed matters more than its last bits (the smooth normals of every vertex,
/// every frame).
#[inline]
pub fn acos_fast(x: f32) -> f32 {
    const A: [f32; 8] = [
        std::f32::consts::FRAC_PI_2,
        -0.214_598_8,
        0.088_978_99,
        -0.050_174_304,
        0.030_891_88,
        -0.017_088_126,
        0.006_670_09,
        -0.001_262_491_1,
    ];
    let a = x.abs().min(1.0);
    let mut p = A[7];
    for &c in A[..7].iter().rev() {
        p = p * a + c;
    }
    let r = (1.0 - a).sqrt() * p;
    if x < 0.0 {
        std::f32::consts::PI - r
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn acos_fast_is_within_a_micro_radian() {
        for k in 0..=20_000 {
            let x = -1.0 + k as f32 / 10_000.0;
            let want = f64::from(x).acos();
            let got = f64::from(acos_fast(x));
            assert!((got - want).abs() < 1e-6, "acos({x}) = {want}, not {got}");
        }
        assert_eq!(acos_fast(2.0), acos_fast(1.0));
    }

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
