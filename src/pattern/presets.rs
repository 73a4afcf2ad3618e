//! Named stitch patterns knitters recognise, written as knitters write them: in Knitspeak
//! (read by [`super::parse_knitspeak`]) or as a chart (top row first, as seen on the right
//! side, read by [`super::parse_chart`]). Every one balances its stitch count row by row and
//! is at most 24 stitches wide and 24 rows high (`tests/knitspeak.rs` checks both).
//!
//! The first eight are the original knit/purl charts, kept cell for cell (the add-on and the
//! clearance tables name them).

use super::ColorPattern;
use crate::error::{KnitError, Result};

/// (name, Knitspeak or chart text), in display order.
pub const PRESETS: &[(&str, &str)] = &[
    ("stockinette", "k"),
    ("reverse_stockinette", "p"),
    // Knit every row, flat: every other row shows purl bumps on the front.
    ("garter", "p\nk"),
    ("rib_1x1", "kp"),
    ("rib_2x2", "kkpp"),
    // Seed (British "moss"): knit over purl, purl over knit, every row.
    ("seed", "pk\nkp"),
    // Moss (American, "double moss"): each 1x1 rib row worked twice before the offset.
    ("moss", "pk\npk\nkp\nkp"),
    // Basketweave: 4x4 blocks of stockinette and reverse stockinette, alternating.
    (
        "basketweave",
        "ppppkkkk\nppppkkkk\nppppkkkk\nppppkkkk\nkkkkpppp\nkkkkpppp\nkkkkpppp\nkkkkpppp",
    ),
    (
        "twisted_rib",
        "Row 1 (RS): *K1 tbl, p1; rep from *.\n\
         Row 2: *K1, p1 tbl; rep from *.",
    ),
    // A 4-stitch cable crossed every 6th row on a reverse stockinette ground.
    (
        "cable_c4",
        "Rows 1 and 5 (RS): P2, *k4, p2; rep from *.\n\
         Rows 2, 4, and 6: K2, *p4, k2; rep from *.\n\
         Row 3: P2, *C4B, p2; rep from *.",
    ),
    (
        "cable_c6",
        "Rows 1, 5, and 7 (RS): P2, *k6, p2; rep from *.\n\
         Rows 2, 4, 6, and 8: K2, *p6, k2; rep from *.\n\
         Row 3: P2, *C6B, p2; rep from *.",
    ),
    // A 16-stitch panel: a 3/3 right cross beside a 3/3 left cross.
    (
        "horseshoe_cable",
        "Rows 1, 5, and 7 (RS): P2, k12, p2.\n\
         Rows 2, 4, 6, and 8: K2, p12, k2.\n\
         Row 3: P2, 3/3 RC, 3/3 LC, p2.",
    ),
    // Pairs of 2/2 crosses that meet and part: a honeycomb of knit cells.
    (
        "honeycomb_cable",
        "Row 1 (RS): *2/2 RC, 2/2 LC; rep from *.\n\
         All WS rows: Purl.\n\
         Rows 3 and 7: Knit.\n\
         Row 5: *2/2 LC, 2/2 RC; rep from *.",
    ),
    // 1/1 right twists on a 2x2 rib: a cable look without a cable needle.
    (
        "mock_cable_rib",
        "Row 1 (RS): P2, *k2, p2; rep from *.\n\
         Rows 2 and 4: K2, *p2, k2; rep from *.\n\
         Row 3: P2, *1/1 RT, p2; rep from *.",
    ),
    // Little left twists every other row, between purls.
    (
        "twisted_cable_rib",
        "Row 1 (RS): *P1, 1/1 LT, p1; rep from *.\n\
         Row 2: *K1, p2, k1; rep from *.",
    ),
    // Diamond brocade: purl diamonds on stockinette (chart, as seen on the right side).
    (
        "diamond",
        "kkpkpkkk\nkpkkkpkk\npkkkkkpk\nkkkkkkkp\npkkkkkpk\nkpkkkpkk\nkkpkpkkk\nkkkpkkkk",
    ),
    // Purl zigzags on stockinette (chart).
    ("chevron", "kkkppkkk\nkkpkkpkk\nkpkkkkpk\npkkkkkkp"),
    // Old shale: three decreases each side of six yarn-overs, an 18-stitch scallop.
    (
        "feather_and_fan",
        "Row 1 (RS): Knit.\n\
         Row 2: Purl.\n\
         Row 3: *[K2tog] 3 times, [yo, k1] 6 times, [k2tog] 3 times; rep from *.\n\
         Row 4: Knit.",
    ),
    (
        "eyelet_rows",
        "Rows 1 and 3 (RS): Knit.\n\
         Rows 2, 4, and 6: Purl.\n\
         Row 5: K1, *yo, k2tog; rep from *.",
    ),
    // An 8-stitch lace diamond: yarn-overs part and meet again, paired k2tog and ssk.
    (
        "lace_diamond",
        "Row 1 (RS): *K2, k2tog, yo, k1, yo, ssk, k1; rep from *.\n\
         Row 3: *K1, k2tog, yo, k3, yo, ssk; rep from *.\n\
         Row 5: *K1, yo, ssk, k3, k2tog, yo; rep from *.\n\
         Row 7: *K2, yo, ssk, k1, k2tog, yo, k1; rep from *.\n\
         All WS rows: Purl.",
    ),
    // Bobbles on stockinette, staggered every 4 rows.
    (
        "bobbles",
        "Rows 1 and 5 (RS): Knit.\n\
         All WS rows: Purl.\n\
         Row 3: K2, *MB, k5; rep from * to last 3 sts, MB, k2.\n\
         Row 7: K5, *MB, k5; rep from *.",
    ),
    // Linen stitch: slipped stitches with the yarn carried across the front in little bars.
    (
        "linen_stitch",
        "Row 1 (RS): *K1, sl1 wyif; rep from *.\n\
         Row 2: *P1, sl1 wyib; rep from *.",
    ),
    // The stitch part of Fair Isle: stockinette in the round (the colours are a colour chart,
    // `FAIR_ISLE_BAND`).
    ("fair_isle", "Rnd 1: Knit."),
];

/// A Fair Isle band for [`super::ColorPattern::new`] with a palette of two colours (0 the
/// background, 1 the pattern): a peerie band of diamonds and dots, 8 stitches by 8 rows.
pub const FAIR_ISLE_BAND: &str = "00000000\n\
                                  01000100\n\
                                  00101000\n\
                                  10010001\n\
                                  00101000\n\
                                  01000100\n\
                                  00000000\n\
                                  11111111";

/// Named colour charts for [`super::ColorPattern`]: (name, chart of palette indices).
pub const COLOR_PRESETS: &[(&str, &str)] = &[("fair_isle_band", FAIR_ISLE_BAND)];

/// A named colour chart in `palette` (which must have a colour for every index it uses).
pub fn color_preset(name: &str, palette: Vec<[f32; 3]>) -> Result<ColorPattern> {
    let key = super::normalise_name(name);
    let Some((_, chart)) = COLOR_PRESETS
        .iter()
        .find(|(n, _)| super::normalise_name(n) == key)
    else {
        let names: Vec<&str> = COLOR_PRESETS.iter().map(|(n, _)| *n).collect();
        return Err(KnitError::Pattern(format!(
            "unknown colour preset {name:?}; colour presets are: {}",
            names.join(", ")
        )));
    };
    ColorPattern::new(palette, chart)
}
