//! Named stitch patterns, as charts (top row first, as seen on the right side).

/// (name, chart). Charts show the front: `k` a knit V, `p` a purl bump.
pub const PRESETS: &[(&str, &str)] = &[
    ("stockinette", "k"),
    ("reverse_stockinette", "p"),
    // Knit every row, flat: every other row shows purl bumps on the front.
    ("garter", "p\nk"),
    ("rib_1x1", "kp"),
    ("rib_2x2", "kkpp"),
    // Seed (British "moss"): knit over purl, purl over knit, every row.
    ("seed", "pk\nkp"),
    // Moss (American): each 1x1 rib row worked twice before the offset.
    ("moss", "pk\npk\nkp\nkp"),
    // Basketweave: 4x4 blocks of stockinette and reverse stockinette, alternating.
    (
        "basketweave",
        "ppppkkkk\nppppkkkk\nppppkkkk\nppppkkkk\nkkkkpppp\nkkkkpppp\nkkkkpppp\nkkkkpppp",
    ),
];
