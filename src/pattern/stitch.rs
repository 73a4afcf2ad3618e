//! One cell of a stitch chart: a stitch as it shows on the right side, with where its loop
//! came from in the row below and where its own head goes in the row above.

/// Which way a loop was pulled through the loop below, as seen from the right side (front).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Face {
    /// Pulled from back to front: the legs show as a V on the front and the head of the loop
    /// below lies behind them.
    Knit,
    /// Pulled from front to back: the head of the loop below shows as a bump on the front.
    Purl,
}

/// How a stitch's own loop is formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Form {
    /// An ordinary loop (also every crossed stitch and every decrease).
    Plain,
    /// Worked through the back loop (`k tbl`, `p tbl`): the legs cross at the base.
    Twisted,
    /// A yarn-over: a loop with no loop below it, leaving a hole.
    YarnOver,
    /// A made stitch (`m1l`, `m1r`): a loop picked up from the bar between two stitches, with
    /// no loop below it but twisted shut (no hole).
    MakeOne,
    /// Slipped: this row's yarn does not form a loop here but floats past it, in front of the
    /// fabric (`yarn_front`, "wyif" on the right side) or behind it; the loop below is carried
    /// up a row (a row more for each row that slips it again).
    Slip { yarn_front: bool },
    /// A bobble: a knit stitch topped by a small knot of extra loops standing off the fabric.
    Bobble,
}

/// A chart cell. Columns count left to right as seen on the right side; offsets are in
/// columns and wrap round the chart's width (the chart repeats across the fabric).
///
/// Invariants (kept by [`super::StitchPattern`]): every loop of the row below lands in
/// exactly one stitch of this row (the one whose sources include it), except under a slipped
/// stitch, where it is carried up; a yarn-over and a made stitch have no sources.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Stitch {
    pub face: Face,
    pub form: Form,
    /// The loops of the row below this stitch is pulled through: columns
    /// `col + source_offset .. col + source_offset + sources` of the row below.
    pub source_offset: i8,
    /// How many loops it is pulled through: 1 for most stitches, 2 or 3 for decreases, 0 for
    /// a yarn-over or a made stitch.
    pub sources: u8,
    /// Where this stitch's own loop ends up in the row above: the column offset of the stitch
    /// pulled through it (non-zero under a cable or a decrease, whose loops lean).
    pub land_offset: i8,
    /// Which way this loop passes the loops it crosses on its way there: +1 in front, -1
    /// behind, 0 when it crosses none. Among loops gathered by one decrease, the order of
    /// their layers is the order front to back.
    pub land_layer: i8,
    /// 1 where the stitch above slips this loop (or, on a slipped stitch, where the next row
    /// slips the loop it carries again), else 0. A loop's whole rise follows these flags up
    /// the column (`skeleton::stitch_shape::carried_rise`).
    pub rise: u8,
}

impl Stitch {
    /// A knit stitch over the loop straight below.
    pub const KNIT: Stitch = Stitch::plain(Face::Knit);
    /// A purl stitch over the loop straight below.
    pub const PURL: Stitch = Stitch::plain(Face::Purl);

    /// An ordinary stitch of `face` pulled through the loop straight below, its own loop
    /// caught straight above.
    pub const fn plain(face: Face) -> Self {
        Self {
            face,
            form: Form::Plain,
            source_offset: 0,
            sources: 1,
            land_offset: 0,
            land_layer: 0,
            rise: 0,
        }
    }

    /// +1 for knit, -1 for purl: the side (along the surface normal) on which this stitch's
    /// legs pass the head of the loop below.
    pub fn side(self) -> f32 {
        match self.face {
            Face::Knit => 1.0,
            Face::Purl => -1.0,
        }
    }

    /// Whether this is an ordinary knit or purl stitch with nothing crossing it.
    pub fn is_plain(self) -> bool {
        self == Stitch::plain(self.face)
    }

    /// The chart symbol of a plain knit (`k`) or purl (`p`) stitch; other stitches have the
    /// symbols of [`super::chart`]'s legend.
    pub fn symbol(self) -> char {
        match self.face {
            Face::Knit => 'k',
            Face::Purl => 'p',
        }
    }
}
