//! What a knitter does at one point of a row: an instruction consumes some loops of the row
//! below (stitches-in) and makes some stitches (stitches-out).
//!
//! Each instruction is described as it is worked from the right side; [`Instruction::worked`]
//! gives its stitches and loops in right-side chart order (left to right as seen from the
//! front). A wrong-side row mirrors them (see [`super::rows`]).

use super::stitch::{Face, Form};

/// One knitting instruction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Instruction {
    Knit,
    Purl,
    /// `k tbl`
    KnitTbl,
    /// `p tbl`
    PurlTbl,
    /// `sl1 wyib` / `sl1 wyif`: slipped purlwise with the yarn in back or in front.
    Slip {
        yarn_front: bool,
    },
    /// `yo`
    YarnOver,
    /// `m1l`
    MakeOneLeft,
    /// `m1r`
    MakeOneRight,
    /// `k2tog`: right-leaning; the left loop lies on top.
    K2tog,
    /// `ssk`: left-leaning; the right loop lies on top.
    Ssk,
    /// `p2tog`
    P2tog,
    /// `ssp`
    Ssp,
    /// `k3tog`: right-leaning double decrease.
    K3tog,
    /// `sssk`: left-leaning double decrease.
    Sssk,
    /// `p3tog`: [`Self::K3tog`] purled.
    P3tog,
    /// `sssp`: [`Self::Sssk`] purled.
    Sssp,
    /// `k2tog tbl`: two loops knitted together through their back loops, which leans left
    /// like [`Self::Ssk`] (the right loop on top), the stitch twisted.
    K2togTbl,
    /// `p2tog tbl`: [`Self::K2togTbl`] purled.
    P2togTbl,
    /// `k3tog tbl`: three loops knitted together through their back loops, which leans left
    /// like [`Self::Sssk`] (the right loop on top), the stitch twisted.
    K3togTbl,
    /// `p3tog tbl`: [`Self::K3togTbl`] purled.
    P3togTbl,
    /// `cddp` (`sl2-p1-p2sso`): [`Self::Cdd`] purled.
    Cddp,
    /// `k4tog`: right-leaning triple decrease, the loops stacked left over right.
    K4tog,
    /// `p4tog`: [`Self::K4tog`] purled.
    P4tog,
    /// `k5tog`: right-leaning quadruple decrease, the loops stacked left over right.
    K5tog,
    /// `p5tog`: [`Self::K5tog`] purled.
    P5tog,
    /// `sl1-k2tog-psso` (`sk2p`): left-leaning double decrease, the slipped (right) loop on top.
    Sk2p,
    /// `cdd` (`sl2-k1-p2sso`, `s2kp`): centred double decrease, the centre loop on top.
    Cdd,
    /// `MB`: make a bobble.
    Bobble,
    /// A cable or twist `m/n RC`, `m/n LC`, `m/n RPC`, `m/n LPC` (`1/1 RT` is `1/1 RC`, `C4B`
    /// is `2/2 RC`, `C4F` is `2/2 LC`): `m` stitches travel in front of `n`, to the right
    /// (`left == false`) or to the left. `purl_back`: the `n` stitches that pass behind are
    /// purled (the `P` of `RPC`).
    Cross {
        m: u8,
        n: u8,
        left: bool,
        purl_back: bool,
    },
    /// A cross around a centre, `m/c/n RC`, `m/c/n LC`, `m/c/n RPC`, `m/c/n LPC` (`1/1/1 RT`
    /// is `1/1/1 RC`): the `m` stitches travel in front of the `c` centre stitches and the `n`
    /// stitches, to the right (`left == false`) or to the left; the `n` stitches travel the
    /// other way behind the `m` but in front of the centre, which is held on its own cable
    /// needle in back and worked in between. `purl_centre`: the centre stitches are purled (the
    /// `P` of `RPC`). Each of `m + c` and `c + n` is at most [`MAX_CROSS_SIDE`], so no loop
    /// travels further than in a plain cross.
    CentreCross {
        m: u8,
        c: u8,
        n: u8,
        left: bool,
        purl_centre: bool,
    },
}

/// A stitch made by an instruction, in right-side order within the instruction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MadeStitch {
    pub face: Face,
    pub form: Form,
    /// First loop (index into the instruction's loops-in, right-side order) pulled through.
    pub first_source: usize,
    /// Loops pulled through (0 for a yarn-over or a made stitch).
    pub sources: usize,
}

/// Where a loop of the row below goes: which made stitch (index within the instruction) is
/// pulled through it, and on which side it passes the loops it crosses (+1 front, -1 back).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LoopFate {
    pub made_by: usize,
    pub layer: i8,
}

/// An instruction's effect, right-side order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Worked {
    pub made: Vec<MadeStitch>,
    pub loops: Vec<LoopFate>,
}

/// Largest stitch count on either side of a cross.
pub const MAX_CROSS_SIDE: u8 = 6;

impl Instruction {
    /// Loops of the row below it works.
    pub fn stitches_in(self) -> usize {
        match self {
            Self::YarnOver | Self::MakeOneLeft | Self::MakeOneRight => 0,
            Self::K2tog | Self::Ssk | Self::P2tog | Self::Ssp | Self::K2togTbl | Self::P2togTbl => {
                2
            }
            Self::K3tog
            | Self::Sssk
            | Self::P3tog
            | Self::Sssp
            | Self::K3togTbl
            | Self::P3togTbl
            | Self::Sk2p
            | Self::Cdd
            | Self::Cddp => 3,
            Self::K4tog | Self::P4tog => 4,
            Self::K5tog | Self::P5tog => 5,
            Self::Cross { m, n, .. } => usize::from(m) + usize::from(n),
            Self::CentreCross { m, c, n, .. } => usize::from(m) + usize::from(c) + usize::from(n),
            _ => 1,
        }
    }

    /// Stitches it makes.
    pub fn stitches_out(self) -> usize {
        match self {
            Self::Cross { m, n, .. } => usize::from(m) + usize::from(n),
            Self::CentreCross { m, c, n, .. } => usize::from(m) + usize::from(c) + usize::from(n),
            _ => 1,
        }
    }

    /// The Knitspeak name, as stitch-maps writes it.
    pub fn name(self) -> String {
        match self {
            Self::Knit => "k".into(),
            Self::Purl => "p".into(),
            Self::KnitTbl => "k tbl".into(),
            Self::PurlTbl => "p tbl".into(),
            Self::Slip { yarn_front: false } => "sl1 wyib".into(),
            Self::Slip { yarn_front: true } => "sl1 wyif".into(),
            Self::YarnOver => "yo".into(),
            Self::MakeOneLeft => "m1l".into(),
            Self::MakeOneRight => "m1r".into(),
            Self::K2tog => "k2tog".into(),
            Self::Ssk => "ssk".into(),
            Self::P2tog => "p2tog".into(),
            Self::Ssp => "ssp".into(),
            Self::K3tog => "k3tog".into(),
            Self::Sssk => "sssk".into(),
            Self::P3tog => "p3tog".into(),
            Self::Sssp => "sssp".into(),
            Self::K2togTbl => "k2tog tbl".into(),
            Self::P2togTbl => "p2tog tbl".into(),
            Self::K3togTbl => "k3tog tbl".into(),
            Self::P3togTbl => "p3tog tbl".into(),
            Self::Cddp => "cddp".into(),
            Self::K4tog => "k4tog".into(),
            Self::P4tog => "p4tog".into(),
            Self::K5tog => "k5tog".into(),
            Self::P5tog => "p5tog".into(),
            Self::Sk2p => "sl1-k2tog-psso".into(),
            Self::Cdd => "cdd".into(),
            Self::Bobble => "MB".into(),
            Self::Cross {
                m,
                n,
                left,
                purl_back,
            } => format!(
                "{m}/{n} {}{}C",
                if left { "L" } else { "R" },
                if purl_back { "P" } else { "" }
            ),
            Self::CentreCross {
                m,
                c,
                n,
                left,
                purl_centre,
            } => format!(
                "{m}/{c}/{n} {}{}C",
                if left { "L" } else { "R" },
                if purl_centre { "P" } else { "" }
            ),
        }
    }

    /// What it does, in right-side order (left to right as seen from the front).
    pub fn worked(self) -> Worked {
        let one = |face, form| Worked {
            made: vec![MadeStitch {
                face,
                form,
                first_source: 0,
                sources: 1,
            }],
            loops: vec![LoopFate {
                made_by: 0,
                layer: 0,
            }],
        };
        let new_loop = |form| Worked {
            made: vec![MadeStitch {
                face: Face::Knit,
                form,
                first_source: 0,
                sources: 0,
            }],
            loops: vec![],
        };
        // A decrease: one stitch through all loops, `layers` front-to-back order per loop.
        let gather_as = |face, form, layers: &[i8]| Worked {
            made: vec![MadeStitch {
                face,
                form,
                first_source: 0,
                sources: layers.len(),
            }],
            loops: layers
                .iter()
                .map(|&layer| LoopFate { made_by: 0, layer })
                .collect(),
        };
        let gather = |face, layers: &[i8]| gather_as(face, Form::Plain, layers);
        match self {
            Self::Knit => one(Face::Knit, Form::Plain),
            Self::Purl => one(Face::Purl, Form::Plain),
            Self::KnitTbl => one(Face::Knit, Form::Twisted),
            Self::PurlTbl => one(Face::Purl, Form::Twisted),
            Self::Slip { yarn_front } => one(Face::Knit, Form::Slip { yarn_front }),
            Self::Bobble => one(Face::Knit, Form::Bobble),
            Self::YarnOver => new_loop(Form::YarnOver),
            Self::MakeOneLeft | Self::MakeOneRight => new_loop(Form::MakeOne),
            // Right-leaning: the left loop on top.
            Self::K2tog => gather(Face::Knit, &[1, -1]),
            Self::P2tog => gather(Face::Purl, &[1, -1]),
            Self::K3tog => gather(Face::Knit, &[1, 0, -1]),
            Self::P3tog => gather(Face::Purl, &[1, 0, -1]),
            // More loops stack further: the outer ones pass those they cross twice as far.
            Self::K4tog => gather(Face::Knit, &[2, 1, -1, -2]),
            Self::P4tog => gather(Face::Purl, &[2, 1, -1, -2]),
            Self::K5tog => gather(Face::Knit, &[2, 1, 0, -1, -2]),
            Self::P5tog => gather(Face::Purl, &[2, 1, 0, -1, -2]),
            // Left-leaning: the right loop on top.
            Self::Ssk => gather(Face::Knit, &[-1, 1]),
            Self::Ssp => gather(Face::Purl, &[-1, 1]),
            Self::Sssk => gather(Face::Knit, &[-1, 0, 1]),
            Self::Sssp => gather(Face::Purl, &[-1, 0, 1]),
            Self::K2togTbl => gather_as(Face::Knit, Form::Twisted, &[-1, 1]),
            Self::P2togTbl => gather_as(Face::Purl, Form::Twisted, &[-1, 1]),
            Self::K3togTbl => gather_as(Face::Knit, Form::Twisted, &[-1, 0, 1]),
            Self::P3togTbl => gather_as(Face::Purl, Form::Twisted, &[-1, 0, 1]),
            // The slipped right loop passed over the k2tog of the other two.
            Self::Sk2p => gather(Face::Knit, &[0, -1, 1]),
            // The centre loop on top of the two passed over it.
            Self::Cdd => gather(Face::Knit, &[0, 1, -1]),
            Self::Cddp => gather(Face::Purl, &[0, 1, -1]),
            Self::Cross {
                m,
                n,
                left,
                purl_back,
            } => cross(
                Groups {
                    front: usize::from(m),
                    centre: 0,
                    back: usize::from(n),
                },
                left,
                purl_back,
            ),
            Self::CentreCross {
                m,
                c,
                n,
                left,
                purl_centre,
            } => cross(
                Groups {
                    front: usize::from(m),
                    centre: usize::from(c),
                    back: usize::from(n),
                },
                left,
                purl_centre,
            ),
        }
    }
}

/// The stitch groups of a cross, in the order a knitter names them: `front` travels in front
/// of the others, `back` the other way behind it, `centre` (0 in a plain cross) between them.
struct Groups {
    front: usize,
    centre: usize,
    back: usize,
}

/// `m/n RC` (`left == false`): slip `n` to a cable needle held in back, knit `m`, then the `n`
/// from the cable needle; the `m` loops travel right, in front. `m/n LC`: slip `m` held in
/// front, work `n`, knit the `m`; the `m` loops travel left, in front. The row is worked right
/// to left, so the loops worked first land furthest right.
///
/// With a centre (`m/c/n RC`): slip `n` to a first cable needle and `c` to a second, both held
/// in back, knit `m`, work the `c`, knit the `n`; `m/c/n LC`: slip `m` held in front and `c`
/// held in back, knit `n`, work the `c`, knit the `m`. The centre loops stay between the
/// groups and pass behind both, the `n` loops pass behind the `m` in front of the centre: the
/// layers are +2 (front), +1 (back group) and -1 (centre), so every two groups that cross have
/// distinct layers, the higher in front. Without a centre they are +1 and -1.
///
/// `purl`: the stitches held furthest back (the back group of a plain cross, the centre of a
/// centre cross) are purled.
fn cross(g: Groups, left: bool, purl: bool) -> Worked {
    let Groups {
        front: m,
        centre: c,
        back: n,
    } = g;
    let total = m + c + n;
    let mut made = vec![
        MadeStitch {
            face: Face::Knit,
            form: Form::Plain,
            first_source: 0,
            sources: 1,
        };
        total
    ];
    let mut loops = vec![
        LoopFate {
            made_by: 0,
            layer: 0
        };
        total
    ];
    let (front, back, centre) = if c == 0 { (1, -1, 0) } else { (2, 1, -1) };
    let purled = if c == 0 { back } else { centre };
    let mut link = |from: usize, to: usize, layer: i8| {
        made[to].first_source = from;
        made[to].face = if purl && layer == purled {
            Face::Purl
        } else {
            Face::Knit
        };
        loops[from] = LoopFate { made_by: to, layer };
    };
    if left {
        // Loops n+c..n+c+m (front) land at 0..m; the centre n..n+c lands at m..m+c; loops
        // 0..n (back) land at m+c..m+c+n.
        for i in 0..m {
            link(n + c + i, i, front);
        }
        for k in 0..c {
            link(n + k, m + k, centre);
        }
        for j in 0..n {
            link(j, m + c + j, back);
        }
    } else {
        // Loops 0..m (front) land at n+c..n+c+m; the centre m..m+c at n..n+c; loops
        // m+c..m+c+n (back) at 0..n.
        for i in 0..m {
            link(i, n + c + i, front);
        }
        for k in 0..c {
            link(m + k, n + k, centre);
        }
        for j in 0..n {
            link(m + c + j, j, back);
        }
    }
    Worked { made, loops }
}
