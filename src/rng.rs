//! The project's one seed mixer: SplitMix64 (Steele, Lea and Flood 2014), the stateless hash
//! every random choice is drawn from. Pure integer arithmetic: the same 64 bits for the same
//! inputs on every machine and thread count, which is what lets a farm render any frame
//! alone.

/// SplitMix64's golden gamma (2^64 / phi): the step between successive states, and the
/// multiplier that spreads the first index of [`cell_seed`].
pub const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// A second odd multiplier (xxHash's PRIME64_2) that spreads the second index of
/// [`cell_seed`].
const SECOND_PRIME: u64 = 0xC2B2_AE3D_27D4_EB4F;

/// SplitMix64's finaliser: every input bit flips about half the output bits.
#[inline]
pub fn mix64(z: u64) -> u64 {
    let z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    let z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// SplitMix64's step: add the golden gamma, then the finaliser.
#[inline]
pub fn splitmix64(z: u64) -> u64 {
    mix64(z.wrapping_add(GOLDEN_GAMMA))
}

/// A stable 64-bit seed for cell `(a, b)` of a grid under `seed` (a stitch's course and wale,
/// a noise texel's row and column).
#[inline]
pub fn cell_seed(seed: u64, a: usize, b: usize) -> u64 {
    mix64(seed ^ (a as u64).wrapping_mul(GOLDEN_GAMMA) ^ (b as u64).wrapping_mul(SECOND_PRIME))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_matches_the_reference_sequence() {
        // The reference generator seeded with 0 (Vigna's splitmix64.c): its state advances
        // by the gamma before each output.
        let mut state = 0u64;
        let mut next = || {
            let out = splitmix64(state);
            state = state.wrapping_add(GOLDEN_GAMMA);
            out
        };
        assert_eq!(next(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(next(), 0x6E78_9E6A_A1B9_65F4);
        assert_eq!(next(), 0x06C4_5D18_8009_454F);
    }

    #[test]
    fn neighbouring_cells_differ_in_about_half_their_bits() {
        let base = cell_seed(7, 10, 10);
        for (a, b) in [(11, 10), (10, 11), (9, 10), (10, 9)] {
            let flipped = (cell_seed(7, a, b) ^ base).count_ones();
            assert!((16..=48).contains(&flipped), "({a}, {b}): {flipped} bits");
        }
        assert_ne!(cell_seed(7, 1, 2), cell_seed(7, 2, 1));
    }
}
