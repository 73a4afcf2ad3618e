//! The key points of one stitch in (u, v, lambda), for every kind of stitch (docs/design.md
//! section 3, "Advanced stitches").
//!
//! A loop's bottom (sinker k0, leg bottoms k1 and k5) sits in its own tile, where it was pulled
//! through the loop below. Its top (leg tops k2 and k4, head k3) sits in the tile where the
//! loop lands: the column of the stitch in the row above that is pulled through it. For a
//! plain stitch that is the tile straight above its bottom; under a cable or a decrease the
//! loop leans to another column, which is how a cable's stitches cross: the legs of loops
//! travelling opposite ways cross halfway up the row. (Knitting crosses the loops of the row
//! below the cable row on the cable needle: these are the loops that lean here, so the yarn of
//! every row still visits its stitches in needle order.)
//!
//! Where loops cross or are gathered by a decrease, the one the pattern puts in front stands
//! half a yarn diameter further out along the normal and the one behind half a diameter
//! further in, so that crossing legs and stacked heads clear each other by a diameter.

use glam::{Vec2, Vec3};

use super::key_points::{key_points, KEY_POINTS};
use super::offsets::{NormalOffsets, Shape};
use crate::lattice::{Lattice, Tile};
use crate::pattern::{Form, Stitch, StitchPattern};

/// How far a bobble stands off the fabric, in yarn diameters.
pub const BOBBLE_HEIGHT: f32 = 1.0;
/// How far a bobble's legs swell sideways at their tops, in stitch widths.
pub const BOBBLE_SPREAD: f32 = 0.15;
/// Where a yarn-over's legs end, as a fraction of the row up from the row's bottom: the hole
/// under it.
pub const YARN_OVER_LEG_BOTTOM: f32 = 0.45;
/// The same for a made stitch (m1), whose legs reach further down: a small, closed gap.
pub const MAKE_ONE_LEG_BOTTOM: f32 = 0.2;

/// The wale the loop of stitch (course, wale) lands in: where the pattern says, if the whole
/// run of loops it crosses or is gathered with ([`StitchPattern::landing_group`]) is on the
/// fabric; otherwise its own (the loop stays straight).
///
/// On an open-u surface a run cut by the edge stays straight, all of it: leaning only the
/// loops whose landing is on the fabric would land two loops on one stitch. Round a cyclic-u
/// surface whose wales are not a whole number of pattern repeats, the last, partial repeat
/// meets the first at the seam with its columns out of step: runs there stay straight too.
pub fn landing(lattice: &Lattice, pattern: &StitchPattern, course: usize, wale: usize) -> isize {
    let here = wale as isize;
    let dest = here + isize::from(pattern.stitch(course, wale).land_offset);
    let fits = if lattice.window {
        lattice.cyclic_u || (0..lattice.wales as isize).contains(&dest)
    } else {
        group_on_fabric(lattice, pattern, course, wale)
    };
    if fits {
        dest
    } else {
        here
    }
}

/// How many courses the loop of stitch (`course`, `wale`) is carried up by stitches slipped
/// over it before a stitch is pulled through it: 0 for a loop worked in the next course, 1
/// under one slipped stitch, 2 where the next row slips it again (a slip column, mosaic
/// knitting): [`Stitch::rise`] of the loop, then of each slipped stitch, says whether the
/// next row slips it (again). Capped at the last course, which carries a loop
/// no further: the bind-off above it holds it. [`StitchPattern::check_knittable`] refuses a
/// column slipped in every row of the repeat, whose loop would rise for ever.
pub fn carried_rise(
    lattice: &Lattice,
    pattern: &StitchPattern,
    course: usize,
    wale: usize,
) -> usize {
    let last = lattice.courses.saturating_sub(1);
    let (mut rise, mut at) = (0, wale);
    // Each slipped stitch's own `rise` says whether the next row slips the loop again.
    while pattern.stitch(course + rise, at).rise > 0 && course + rise < last {
        at = landing(lattice, pattern, course + rise, at).rem_euclid(lattice.wales as isize)
            as usize;
        rise += 1;
        if rise >= pattern.height() {
            break;
        }
    }
    rise
}

/// Whether the whole run of loops that the loop of stitch (course, wale) crosses or is
/// gathered with is on the fabric (see [`landing`]): a run cut by an open-u edge, or by the
/// seam of a cyclic u whose wales are not whole pattern repeats, is not. True for a loop that
/// is in no run, and on a [`Lattice::window`].
///
/// The last course of an open v still leans as its pattern says, as if the row above were
/// there: straightening it (its loops bound off) measured worse, its neighbours' offsets and
/// relief being made for leaning loops (feather and fan on the test sleeve: 0.84 diameters
/// straight, 0.90 with the course below on the straightened pattern's offsets, against 0.945
/// leaning; 0.953 leaning once the top rows kept the pattern's shape,
/// [`crate::lattice::RowHeights::node_displacements`]).
pub fn group_on_fabric(
    lattice: &Lattice,
    pattern: &StitchPattern,
    course: usize,
    wale: usize,
) -> bool {
    if lattice.window {
        return true;
    }
    let (lo, hi) = pattern.landing_group(course, wale);
    if (lo, hi) == (0, 0) {
        return true;
    }
    let wales = lattice.wales as isize;
    let whole = wales - wales % pattern.width() as isize;
    if lattice.cyclic_u && whole == wales {
        return true;
    }
    let end = if lattice.cyclic_u { whole } else { wales };
    let here = wale as isize;
    here + lo >= 0 && here + hi < end
}

/// The form stitch (course, wale) is knitted with on this fabric: the pattern's, except
/// that a yarn-over or a made stitch over a loop that nothing else pulls through is knitted
/// plain. In a whole repeat the loop under a yarn-over is gathered by the decrease beside
/// it; where an edge or a seam cuts that decrease off, the loop stays in its own column
/// ([`landing`]) under the yarn-over, which is pulled through nothing: the loop would be
/// dropped. A knitter works the stitches left after the last whole repeat plain, and so
/// does this: "K1, *yo, k2tog" on an even count ends in a knit stitch, not a yarn-over
/// over a dropped loop. The first course is left as written (the cast-on under it has no
/// loop under a yarn-over), and so is a yarn-over over a slipped stitch.
pub fn knitted_form(
    lattice: &Lattice,
    pattern: &StitchPattern,
    course: usize,
    wale: usize,
) -> Form {
    let form = pattern.stitch(course, wale).form;
    if !matches!(form, Form::YarnOver | Form::MakeOne) || course == 0 {
        return form;
    }
    let below = pattern.stitch(course - 1, wale);
    let pulled_here = !matches!(below.form, Form::Slip { .. })
        && below.rise == 0
        && landing(lattice, pattern, course - 1, wale) == wale as isize;
    if pulled_here {
        Form::Plain
    } else {
        form
    }
}

/// Whether a piece knits every row of `wale` as the pattern says: false where its edge cuts
/// a crossing or a decrease of some row in that wale ([`group_on_fabric`]). Such a wale is
/// knitted as the pattern straightened ([`StitchPattern::straightened`]), with a relief made
/// for it ([`NormalOffsets::for_stitch`]) and regular rows
/// ([`super::leaning_rows::fabric_row_heights`]).
pub fn wale_knits_whole(lattice: &Lattice, pattern: &StitchPattern, wale: usize) -> bool {
    (0..pattern.height()).all(|r| group_on_fabric(lattice, pattern, r, wale))
}

/// The tile of stitch (course, wale) for a wale that may lie past either end of a cyclic-u
/// lattice: the tile is moved by whole periods so a piece stays continuous.
pub fn tile_at(lattice: &Lattice, course: usize, wale: isize) -> Tile {
    let wales = lattice.wales as isize;
    let t = lattice.tile(course, wale.rem_euclid(wales) as usize);
    let shift = Vec2::new(
        wale.div_euclid(wales) as f32 * lattice.tile.x * wales as f32,
        0.0,
    );
    Tile {
        n0: t.n0 + shift,
        n1: t.n1 + shift,
        n2: t.n2 + shift,
        n3: t.n3 + shift,
        n4: t.n4 + shift,
    }
}

/// How many pushes a loop in `layer` stands out of the fabric (negative: behind it).
/// Gathered loops (a `k4tog`'s, all pulled through one stitch) stand a push further for each
/// layer. Crossing loops stand one push out in the first layer and half a push more in the
/// second (the front group of a centre cross, [`crate::pattern::Instruction::CentreCross`]):
/// enough to clear the group one layer in, where a full second push lifts the leg tops so
/// far that the head between them stands in front of the legs of the stitch pulled through
/// it, undoing the interlock (measured on a `2/1/2 RPC`: 24 of 2,771 interlock crossings
/// wrong at a full push, none at a half). Gathered loops keep the full push: their outer
/// loops lean at most a column or two under one stitch, and k4tog lace cleared less at a half
/// (0.145 diameters against 0.183).
fn layer_depth(layer: i8, gathered: bool) -> f32 {
    match layer {
        0 => 0.0,
        l if gathered => f32::from(l),
        l => f32::from(l.signum()) * (1.0 + 0.5 * f32::from(l.unsigned_abs() - 1)),
    }
}

/// Key points k0..k5 of stitch (`course`, `wale`) in (u, v, lambda). `wale` may run past the
/// last wale on a cyclic-u surface (a closed piece); the points are then one period on.
pub fn stitch_key_points(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    course: usize,
    wale: usize,
) -> [Vec3; KEY_POINTS] {
    let wales = lattice.wales;
    let w = wale % wales;
    let mut this = pattern.stitch(course, w);
    this.form = knitted_form(lattice, pattern, course, w);
    // A crossing or a decrease the fabric holds only part of is knitted straight: its loops
    // pass no other loop and take no corrections made for the whole of it. A wale knitted
    // straight in some row takes the relief made for the pattern straightened.
    let whole_group = group_on_fabric(lattice, pattern, course, w);
    let (offsets, relief) = offsets.for_stitch(course, w, whole_group);
    if !whole_group {
        this.land_offset = 0;
        this.land_layer = 0;
    }
    let left: Stitch = if w > 0 {
        pattern.stitch(course, w - 1)
    } else if lattice.cyclic_u {
        pattern.stitch(course, wales - 1)
    } else {
        this
    };
    let unwrap = (wale - w) as isize;
    let dest = landing(lattice, pattern, course, w);
    // Slipped stitches above carry this loop up a row each (where there is one).
    let rise = carried_rise(lattice, pattern, course, w);
    let above = pattern.stitch(course + 1 + rise, dest.rem_euclid(wales as isize) as usize);
    let own = tile_at(lattice, course, w as isize + unwrap);
    let top = tile_at(lattice, course + rise, dest + unwrap);
    let bottom_kp = key_points(&own, &offsets.loop_shape);
    let top_kp = key_points(&top, &offsets.loop_shape);
    let mut kp = [
        bottom_kp[0],
        bottom_kp[1],
        top_kp[2],
        top_kp[3],
        top_kp[4],
        bottom_kp[5],
    ];
    // A sinker between a knit and a purl column dips as any other: it passes the leg tops of
    // the loop below on its puller's far side, which a sinker straight across between the
    // columns (an earlier rule here, from the stacked model) only grazed. Measured at 24
    // samples a loop, the straight one left 1x1 rib with 27 of 648 stitch buckets
    // interlocked on the sinker side; dipping: all 648, and clearance 0.968 -> 1.000 (2x2
    // rib 0.860 -> 0.958, moss 0.687 -> 0.899, basketweave 0.640 -> 0.855).
    let mut lambdas = offsets.lambdas(this, above, left);
    match this.form {
        Form::Plain => {}
        Form::Bobble => {
            // The stitch under a bobble's ball (`super::bobbles`) stands a little proud: its
            // legs swell out sideways and forwards (BOBBLE_HEIGHT at their tops, half that at
            // their feet), while its head stays where the stitch above is pulled through.
            let h = BOBBLE_HEIGHT * offsets.diameter;
            let across = BOBBLE_SPREAD * (own.n2 - own.n3);
            kp[2] -= across;
            kp[4] += across;
            for (i, l) in lambdas.iter_mut().enumerate() {
                *l += match i {
                    1 | 5 => 0.5 * h,
                    2 | 4 => h,
                    _ => 0.0,
                };
            }
        }
        Form::Twisted => {
            // Through the back loop: the legs swap feet and cross above them, the leg the
            // yarn reaches first in front.
            kp.swap(1, 5);
            lambdas[1] += offsets.shape(Shape::Twist);
            lambdas[5] -= offsets.shape(Shape::Twist);
        }
        Form::YarnOver | Form::MakeOne => {
            // No loop below to pass through: the legs stop short, over a hole.
            let f = if this.form == Form::YarnOver {
                YARN_OVER_LEG_BOTTOM
            } else {
                MAKE_ONE_LEG_BOTTOM
            };
            let up = f * (own.n0 - own.n3);
            kp[1] += up;
            kp[5] += up;
        }
        Form::Slip { yarn_front } => {
            // No loop: the yarn floats straight past, above the heads of the row below, in
            // front of or behind the loop below that the slip carries up.
            let y = 0.55;
            for (i, p) in kp.iter_mut().enumerate() {
                let x = (2 * i + 1) as f32 / (2 * KEY_POINTS) as f32;
                *p = own.n3 + x * (own.n2 - own.n3) + y * (own.n0 - own.n3);
            }
            let side = if yarn_front { 1.0 } else { -1.0 };
            // The yarn reaches the float from the stitch before it as a sinker does: past
            // the leg tops of the loop below that stitch on the interlock's side, and only
            // then to the float's side, between that loop and the one slipped.
            let sinker = lambdas[0];
            lambdas = [side * offsets.shape(Shape::Float); KEY_POINTS];
            lambdas[0] = sinker;
        }
    }
    if this.land_layer != 0 {
        // A leaning or gathered loop passes the loops it crosses in front or behind.
        let layer = layer_depth(this.land_layer, above.sources > 1);
        let (bottom, top) = (
            offsets.shape(Shape::PushBottom),
            offsets.shape(Shape::PushTop),
        );
        // At its feet a loop is still held by the head below it: a loop behind must not be
        // pushed back through that head, so only loops in front move out there.
        lambdas[1] += layer.max(0.0) * bottom;
        lambdas[5] += layer.max(0.0) * bottom;
        lambdas[2] += layer * top;
        lambdas[4] += layer * top;
        // At its head a loop is held by the legs of the stitch pulled through it: a loop in
        // front must not be pushed forward through those legs (which would undo the
        // interlock), so only loops behind move back there, twice as far.
        lambdas[3] += 2.0 * layer.min(0.0) * offsets.shape(Shape::PushHead);
    }
    if dest != w as isize {
        // A loop leaning across columns is stretched thin: its legs would lie nearly on top of
        // each other seen from the front, so they stand one behind the other instead.
        let (bottom, top) = (
            offsets.shape(Shape::SplitBottom),
            offsets.shape(Shape::SplitTop),
        );
        lambdas[1] += bottom;
        lambdas[5] -= bottom;
        lambdas[2] += top;
        lambdas[4] -= top;
    }
    if let Some(relief) = relief {
        for (l, r) in lambdas.iter_mut().zip(relief) {
            *l += r * offsets.diameter;
        }
    }
    lattice.keep_on_fabric(&mut kp);
    std::array::from_fn(|i| Vec3::new(kp[i].x, kp[i].y, lambdas[i]))
}
