//! Flat, sorted tables of p-simplices: the one representation of "a set of simplices" shared by
//! the complex model, the oracle and the incidence-based structures.

/// The p-simplices of some set, each as `arity = p + 1` ascending vertex ids, concatenated, in
/// ascending lexicographic order, without duplicates. Simplex `i` of the table is its `i`-th
/// entry, so the table itself is the dense numbering of those simplices.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SimplexTable {
    arity: usize,
    ids: Vec<u32>,
}

impl SimplexTable {
    /// An empty table of vertices, usable in statics.
    pub const EMPTY: SimplexTable = SimplexTable {
        arity: 1,
        ids: Vec::new(),
    };

    /// Wraps rows the caller knows are ascending and distinct (checked in debug builds).
    pub fn from_sorted_unique(arity: usize, ids: Vec<u32>) -> Self {
        let t = SimplexTable { arity, ids };
        debug_assert!((1..t.len()).all(|i| t.get(i - 1) < t.get(i)));
        t
    }

    pub fn empty(arity: usize) -> Self {
        SimplexTable {
            arity,
            ids: Vec::new(),
        }
    }

    /// Sorts and deduplicates `ids` (rows of `arity` already-ascending vertex ids) into a table;
    /// returns it with the number of duplicate rows removed. O(n log n) comparisons.
    pub fn from_rows(arity: usize, ids: Vec<u32>) -> (Self, usize) {
        assert!(arity > 0 && ids.len().is_multiple_of(arity));
        let rows = ids.len() / arity;
        let ids = sort_dedup_rows(arity, ids);
        let table = SimplexTable { arity, ids };
        let dups = rows - table.len();
        (table, dups)
    }

    /// The vertices `0..n` as a table of 0-simplices.
    pub fn vertices(n: u32) -> Self {
        SimplexTable {
            arity: 1,
            ids: (0..n).collect(),
        }
    }

    pub fn arity(&self) -> usize {
        self.arity
    }

    pub fn len(&self) -> usize {
        self.ids.len().checked_div(self.arity).unwrap_or(0)
    }

    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    pub fn get(&self, i: usize) -> &[u32] {
        &self.ids[i * self.arity..(i + 1) * self.arity]
    }

    /// All rows concatenated.
    pub fn as_flat(&self) -> &[u32] {
        &self.ids
    }

    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.ids.chunks_exact(self.arity.max(1))
    }

    /// Index of `simplex` (ascending ids) in the table: O(arity · log len).
    pub fn find(&self, simplex: &[u32]) -> Option<u32> {
        if simplex.len() != self.arity {
            return None;
        }
        let (mut lo, mut hi) = (0usize, self.len());
        while lo < hi {
            let mid = (lo + hi) / 2;
            match self.get(mid).cmp(simplex) {
                std::cmp::Ordering::Less => lo = mid + 1,
                std::cmp::Ordering::Greater => hi = mid,
                std::cmp::Ordering::Equal => return Some(mid as u32),
            }
        }
        None
    }

    pub fn heap_bytes(&self) -> usize {
        self.ids.capacity() * 4
    }
}

/// Sorts rows of `arity` u32s lexicographically and drops repeated rows. Rows of up to four ids
/// are packed into one integer key, which sorts several times faster than comparing slices.
pub fn sort_dedup_rows(arity: usize, ids: Vec<u32>) -> Vec<u32> {
    fn packed<K: Ord + Copy>(
        arity: usize,
        ids: &[u32],
        pack: impl Fn(&[u32]) -> K,
        unpack: impl Fn(K, &mut Vec<u32>),
    ) -> Vec<u32> {
        let mut keys: Vec<K> = ids.chunks_exact(arity).map(pack).collect();
        keys.sort_unstable();
        keys.dedup();
        let mut out = Vec::with_capacity(keys.len() * arity);
        for k in keys {
            unpack(k, &mut out);
        }
        out
    }
    match arity {
        1 => {
            let mut ids = ids;
            ids.sort_unstable();
            ids.dedup();
            ids
        }
        2 => packed(
            2,
            &ids,
            |r| ((r[0] as u64) << 32) | r[1] as u64,
            |k, out| out.extend_from_slice(&[(k >> 32) as u32, k as u32]),
        ),
        3 | 4 => packed(
            arity,
            &ids,
            |r| r.iter().fold(0u128, |acc, &v| (acc << 32) | v as u128),
            |k, out| {
                for i in (0..arity).rev() {
                    out.push((k >> (32 * i)) as u32);
                }
            },
        ),
        _ => {
            let rows = ids.len() / arity;
            let mut order: Vec<u32> = (0..rows as u32).collect();
            let row = |i: u32| &ids[i as usize * arity..(i as usize + 1) * arity];
            order.sort_unstable_by(|&a, &b| row(a).cmp(row(b)));
            order.dedup_by(|a, b| row(*a) == row(*b));
            let mut out = Vec::with_capacity(order.len() * arity);
            for i in order {
                out.extend_from_slice(row(i));
            }
            out
        }
    }
}

/// Appends to `out` the facets of `simplex` (ascending ids): facet `i` omits vertex `i`, so the
/// facets come in descending lexicographic order.
pub fn push_facets(simplex: &[u32], out: &mut Vec<u32>) {
    for skip in 0..simplex.len() {
        for (j, &v) in simplex.iter().enumerate() {
            if j != skip {
                out.push(v);
            }
        }
    }
}

/// Whether ascending `small` is a subset of ascending `big`: O(|big|).
pub fn is_subset(small: &[u32], big: &[u32]) -> bool {
    let mut it = big.iter();
    small.iter().all(|s| it.any(|b| b == s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_sort_as_vectors_of_numbers() {
        for arity in 1..=6 {
            // `0 9 10` before `0 10 11`: numeric, not textual, order.
            let mut rows = vec![
                vec![0u32, 10, 11, 12, 13, 14],
                vec![0, 9, 10, 11, 12, 13],
                vec![0, 10, 11, 12, 13, 14],
            ];
            for r in &mut rows {
                r.truncate(arity);
            }
            let flat: Vec<u32> = rows.concat();
            let (t, dups) = SimplexTable::from_rows(arity, flat);
            let mut expect = rows.clone();
            expect.sort();
            expect.dedup();
            assert_eq!(t.iter().map(|r| r.to_vec()).collect::<Vec<_>>(), expect);
            assert_eq!(dups, rows.len() - expect.len());
            for (i, r) in expect.iter().enumerate() {
                assert_eq!(t.find(r), Some(i as u32));
            }
            assert_eq!(t.find(&vec![7; arity]), None);
        }
    }

    #[test]
    fn facets_and_subsets() {
        let mut f = Vec::new();
        push_facets(&[1, 4, 7], &mut f);
        assert_eq!(f, vec![4, 7, 1, 7, 1, 4]);
        assert!(is_subset(&[1, 7], &[1, 4, 7]));
        assert!(!is_subset(&[1, 5], &[1, 4, 7]));
        assert!(is_subset(&[], &[1]));
    }
}
