//! Finding an object index among a data dictionary's sorted keys (OD-01, OD-16) in a number of steps that
//! does not grow with the dictionary when its indices are spread evenly (issue 41 item 4): an interpolated
//! guess (one multiply by a constant the compiler computes from the keys), checked, and the binary search
//! when it misses. A dictionary of 1,000 VARs at 2000h..23E7h finds every key on the guess; a lumpy one
//! (RECORD members repeat their index, gaps between ranges) pays the check on top of the binary search.

/// The scale of the interpolated guess for `keys`: `(len - 1) / (last - first)` in 16.16 fixed point (0 for
/// fewer than two distinct keys, where the guess is always the first position).
///
/// ```
/// use canopen_core::od::data::search::scale;
/// assert_eq!(scale(&[0x2000, 0x2001, 0x2002]), 1 << 16);
/// assert_eq!(scale(&[0x2000, 0x2000]), 0);
/// ```
pub const fn scale(keys: &[u16]) -> u32 {
    let n = keys.len();
    if n < 2 || keys[n - 1] <= keys[0] {
        return 0;
    }
    (((n - 1) as u32) << 16) / (keys[n - 1] - keys[0]) as u32
}

/// Whether no key repeats in `keys` (sorted): then a guess that holds the index is its first row, with no
/// look at the row before (a dictionary without RECORDs; computed at compile time).
///
/// ```
/// use canopen_core::od::data::search::unique;
/// assert!(unique(&[0x2000, 0x2001, 0x6000]));
/// assert!(!unique(&[0x2000, 0x2001, 0x2001]));
/// ```
pub const fn unique(keys: &[u16]) -> bool {
    let mut i = 1;
    while i < keys.len() {
        if keys[i] == keys[i - 1] {
            return false;
        }
        i += 1;
    }
    true
}

/// The first position in `keys` (sorted, repeats allowed) whose key is not below `index`, as
/// `keys.partition_point(|&k| k < index)`, with `scale` from [`scale`] and `unique` from [`unique`] of the
/// same keys: the interpolated guess when it holds `index` and is its first row (checked, so any guess is
/// safe), else the binary search.
///
/// ```
/// use canopen_core::od::data::search::{locate, scale, unique};
/// let keys = [0x1000, 0x2000, 0x2000, 0x2001, 0x6000];
/// for index in [0u16, 0x1000, 0x1FFF, 0x2000, 0x2001, 0x2002, 0x6000, 0xFFFF] {
///     assert_eq!(locate(&keys, scale(&keys), unique(&keys), index), keys.partition_point(|&k| k < index));
/// }
/// ```
#[inline]
pub fn locate(keys: &[u16], scale: u32, unique: bool, index: u16) -> usize {
    let Some(&first) = keys.first() else {
        return 0;
    };
    // Below the first key the distance wraps and the product may too: whatever the guess, it only stands
    // when the check below confirms it.
    let guess = (u32::from(index.wrapping_sub(first)).wrapping_mul(scale) >> 16) as usize;
    if let Some(&k) = keys.get(guess) {
        let first_of_its_key = unique || guess == 0 || keys.get(guess - 1).is_some_and(|&p| p < index);
        if k == index && first_of_its_key {
            return guess;
        }
    }
    keys.partition_point(|&k| k < index)
}

/// Where the rows of object `k` of a dictionary with a key per object are, from
/// [`OdData::FIRST_ROWS`](super::OdData::FIRST_ROWS) (`low`) and
/// [`OdData::FIRST_ROW_WRAPS`](super::OdData::FIRST_ROW_WRAPS) (`wraps`): object `k` starts at row `k + e`,
/// where `e`, the rows before it beyond one per object, is `low[k]` plus 256 for each entry of `wraps` up to
/// `k` (the objects where `e` passed a multiple of 256); it has `1 + (low[k + 1] - low[k]) mod 256` rows
/// (an object has at most 255). One byte per object instead of two; `None` past the table.
///
/// ```
/// use canopen_core::od::data::search::rows_of;
/// // Objects of 1, 200, 100, 1 and 1 rows start at rows 0, 1, 201, 301 and 302: e = 0, 0, 199, 298, 298,
/// // and the rows end at 303: e = 298 there too.
/// let (low, wraps) = ([0u8, 0, 199, 42, 42, 42], [3u16]);
/// let rows: Vec<_> = (0..6).map(|k| rows_of(&low, &wraps, k)).collect();
/// assert_eq!(rows, [Some((0, 1)), Some((1, 201)), Some((201, 301)), Some((301, 302)), Some((302, 303)), None]);
/// ```
#[inline]
pub fn rows_of(low: &[u8], wraps: &[u16], k: usize) -> Option<(usize, usize)> {
    let (&here, &next) = (low.get(k)?, low.get(k + 1)?);
    let first = k + usize::from(here) + 256 * wraps.partition_point(|&w| usize::from(w) <= k);
    Some((first, first + 1 + usize::from(next.wrapping_sub(here))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    extern crate std;
    use std::vec;
    use std::vec::Vec;

    proptest! {
        /// [`rows_of`] gives back the rows of every object, whatever their sizes (1 to 254 rows: an
        /// ARRAY or VAR is one, a RECORD up to 254 members), encoded as the derive does.
        #[test]
        fn rows_of_gives_every_object_its_rows(sizes in proptest::collection::vec(prop_oneof![3 => 1usize..4, 1 => 1usize..=254], 0..400)) {
            let mut starts = vec![0usize];
            for s in &sizes {
                starts.push(starts.last().unwrap() + s);
            }
            let mut low = Vec::new();
            let mut wraps = Vec::new();
            for (k, &start) in starts.iter().enumerate() {
                let e = start - k;
                while wraps.len() < e / 256 {
                    wraps.push(k as u16);
                }
                low.push((e % 256) as u8);
            }
            for (k, pair) in starts.windows(2).enumerate() {
                prop_assert_eq!(rows_of(&low, &wraps, k), Some((pair[0], pair[1])));
            }
            prop_assert_eq!(rows_of(&low, &wraps, sizes.len()), None);
        }

        /// The same answer as a binary search, for any sorted keys (repeats, gaps) and any index.
        #[test]
        fn locate_is_partition_point(mut keys in proptest::collection::vec(any::<u16>(), 0..300), index in any::<u16>(), near in 0usize..300) {
            keys.sort_unstable();
            let (s, u) = (scale(&keys), unique(&keys));
            prop_assert_eq!(locate(&keys, s, u, index), keys.partition_point(|&k| k < index));
            // And for the keys themselves and their neighbours (the interesting cases).
            if let Some(&k) = keys.get(near % keys.len().max(1)) {
                for i in [k.wrapping_sub(1), k, k.wrapping_add(1)] {
                    prop_assert_eq!(locate(&keys, s, u, i), keys.partition_point(|&x| x < i));
                }
            }
        }
    }

    /// Evenly spread keys: the first guess is the answer.
    #[test]
    fn dense_keys_are_found_on_the_first_guess() {
        let mut keys = [0u16; 1000];
        for (k, i) in keys.iter_mut().zip(0x2000..) {
            *k = i;
        }
        let s = scale(&keys);
        for (pos, &k) in keys.iter().enumerate() {
            assert_eq!(((u32::from(k - keys[0]) * s) >> 16) as usize, pos);
            assert_eq!(locate(&keys, s, true, k), pos);
        }
    }
}
