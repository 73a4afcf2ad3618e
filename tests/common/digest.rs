//! A fingerprint of a knit's every output buffer, bit for bit.

use knitwear::knit::KnitOutput;

/// FNV-1a (64-bit) over the little-endian bytes of every buffer a knit returns: positions,
/// colours, centreline, normals and tangents (as float bits), then triangles, corner edges, edges,
/// yarn courses and yarn offsets. Equal digests: identical outputs, to the last bit.
pub fn digest(out: &KnitOutput) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    for buf in [
        &out.positions,
        &out.colors,
        &out.centerline,
        &out.normals,
        &out.tangents,
    ] {
        for x in buf.iter() {
            eat(&x.to_bits().to_le_bytes());
        }
    }
    for buf in [
        &out.triangles,
        &out.corner_edges,
        &out.edges,
        &out.yarn_course,
    ] {
        for x in buf.iter() {
            eat(&x.to_le_bytes());
        }
    }
    for x in &out.yarn_offsets {
        eat(&x.to_le_bytes());
    }
    h
}
