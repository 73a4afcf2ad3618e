//! The knitwear texture: planted answers (the yarn colour where the yarn is, stripes in the
//! rows they were knitted in), coverage, the perturbation showing, determinism and errors.

use knitwear::knit::KnitParams;
use knitwear::pattern::{ColorPattern, StitchPattern};
use knitwear::surface::PlaneSurface;
use knitwear::texture::{knit_texture, TextureImage, MAX_TEXTURE_SIZE};
use knitwear::KnitError;

/// 10 x 10 cm, flat.
const PLANE: PlaneSurface = PlaneSurface {
    width: 0.1,
    height: 0.1,
};

fn params(courses: usize, wales: usize) -> KnitParams {
    KnitParams {
        courses: Some(courses),
        wales: Some(wales),
        color_variation: 0.0,
        ..Default::default()
    }
}

fn stockinette() -> StitchPattern {
    StitchPattern::preset("stockinette").unwrap()
}

fn covered(img: &TextureImage) -> impl Iterator<Item = [f32; 4]> + '_ {
    img.pixels
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .filter(|p| p[3] > 0.0)
}

#[test]
fn a_single_colour_knit_is_that_colour_where_the_yarn_is() {
    let color = [0.6, 0.2, 0.1];
    let p = KnitParams {
        colors: Some(ColorPattern::solid(color).unwrap()),
        ..params(12, 12)
    };
    let img = knit_texture(&PLANE, &stockinette(), &p, 256, 256).unwrap();
    assert_eq!(img.pixels.len(), 256 * 256 * 4);
    let mut brightest = 0.0f32;
    for px in covered(&img) {
        // Shading only scales the colour: every covered pixel has its hue.
        let f = px[0] / color[0];
        for k in 0..3 {
            assert!(
                (px[k] - f * color[k]).abs() < 1e-5,
                "pixel {px:?} is not a shade of {color:?}"
            );
        }
        assert!(f > 0.2 && f <= 1.0 + 1e-5, "brightness {f}");
        brightest = brightest.max(f);
    }
    // The front of the yarn, at its centre line, is the colour itself.
    assert!(brightest > 0.97, "brightest {brightest}");
    // Transparent black where no yarn is.
    for px in img.pixels.chunks_exact(4).filter(|p| p[3] == 0.0) {
        assert_eq!(px, [0.0; 4]);
    }
}

#[test]
fn yarn_covers_a_plausible_fraction_of_the_fabric() {
    let img = knit_texture(&PLANE, &stockinette(), &params(16, 16), 512, 512).unwrap();
    let coverage: f32 = img.pixels.chunks_exact(4).map(|p| p[3]).sum::<f32>() / (512.0 * 512.0);
    // A yarn a quarter of a stitch thick, two legs and a loop per stitch: most, not all.
    assert!(
        (0.35..0.95).contains(&coverage),
        "yarn covers {coverage} of the image"
    );
}

#[test]
fn thicker_yarn_covers_more() {
    let cover = |radius: f32| {
        let p = KnitParams {
            yarn_radius: Some(radius),
            ..params(10, 10)
        };
        let img = knit_texture(&PLANE, &stockinette(), &p, 256, 256).unwrap();
        img.pixels.chunks_exact(4).map(|p| p[3]).sum::<f32>()
    };
    assert!(cover(0.0015) > 1.2 * cover(0.0008));
}

#[test]
fn stripes_appear_in_the_rows_they_were_knitted_in() {
    let (red, blue) = ([0.8, 0.05, 0.05], [0.05, 0.05, 0.8]);
    // 12 courses: the bottom 6 red, the top 6 blue.
    let p = KnitParams {
        colors: Some(ColorPattern::stripes(vec![red, blue], 6).unwrap()),
        ..params(12, 12)
    };
    let img = knit_texture(&PLANE, &stockinette(), &p, 240, 240).unwrap();
    let count = |rows: std::ops::Range<usize>| {
        let (mut r, mut b) = (0, 0);
        for y in rows {
            for x in 0..img.width {
                let px = img.pixel(x, y);
                if px[3] > 0.5 {
                    if px[0] > px[2] {
                        r += 1;
                    } else {
                        b += 1;
                    }
                }
            }
        }
        (r, b)
    };
    // Row 0 is the bottom of the domain (smallest v).
    let (r, b) = count(10..90);
    assert!(r > 1000 && b == 0, "bottom: {r} red, {b} blue");
    let (r, b) = count(150..230);
    assert!(b > 1000 && r == 0, "top: {r} red, {b} blue");
}

#[test]
fn kappa_moves_the_stitches_in_the_image() {
    let regular = knit_texture(&PLANE, &stockinette(), &params(12, 12), 128, 128).unwrap();
    let p = KnitParams {
        kappa: 0.02,
        seed: 5,
        ..params(12, 12)
    };
    let perturbed = knit_texture(&PLANE, &stockinette(), &p, 128, 128).unwrap();
    let differ = regular
        .pixels
        .iter()
        .zip(&perturbed.pixels)
        .filter(|(a, b)| a != b)
        .count();
    assert!(differ > regular.pixels.len() / 20, "{differ} values differ");
    let q = KnitParams { seed: 6, ..p };
    let other_seed = knit_texture(&PLANE, &stockinette(), &q, 128, 128).unwrap();
    assert_ne!(perturbed.pixels, other_seed.pixels);
}

#[test]
fn the_same_seed_gives_the_same_bits_on_any_thread_count() {
    let base = KnitParams {
        kappa: 0.015,
        seed: 11,
        color_variation: 0.3,
        colors: Some(ColorPattern::stripes(vec![[0.7, 0.6, 0.2], [0.1, 0.3, 0.6]], 3).unwrap()),
        ..params(20, 24)
    };
    let pattern = StitchPattern::preset("seed").unwrap();
    let images: Vec<_> = [1, 2, 8]
        .iter()
        .map(|&t| {
            let p = KnitParams {
                threads: Some(t),
                ..base.clone()
            };
            knit_texture(&PLANE, &pattern, &p, 300, 200).unwrap()
        })
        .collect();
    for img in &images[1..] {
        assert!(img
            .pixels
            .iter()
            .zip(&images[0].pixels)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
    }
    assert_eq!(images[0].width, 300);
    assert_eq!(images[0].height, 200);
}

#[test]
fn bad_sizes_and_budgets_are_refused() {
    let p = params(4, 4);
    for (w, h) in [
        (0, 16),
        (16, 0),
        (MAX_TEXTURE_SIZE + 1, 16),
        (16, MAX_TEXTURE_SIZE + 1),
    ] {
        assert!(matches!(
            knit_texture(&PLANE, &stockinette(), &p, w, h),
            Err(KnitError::Parameter(_))
        ));
    }
    let tight = KnitParams {
        budget_bytes: 1 << 20,
        ..p.clone()
    };
    assert!(matches!(
        knit_texture(&PLANE, &stockinette(), &tight, 1024, 1024),
        Err(KnitError::Budget(_))
    ));
    // The knit's own settings are checked as for a 3D knit.
    let bad = KnitParams {
        fluffiness: -1.0,
        ..p
    };
    assert!(matches!(
        knit_texture(&PLANE, &stockinette(), &bad, 16, 16),
        Err(KnitError::Parameter(_))
    ));
}
