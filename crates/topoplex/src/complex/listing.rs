//! The simplices as listed (order and vertex order exactly as given, which saved files and
//! writers keep) and the listing ↔ top maps: the top simplex each listed simplex became
//! ([`Complex::input_top`]) and the first listing of each top simplex
//! ([`Complex::top_listing`]), which give every top simplex its input winding.
//!
//! Costs: the listing is one copy of the input ids, plus an offset (8 bytes) per listed simplex
//! unless all have the same number of vertices; the maps, 8 bytes a listing and 4 a top
//! simplex, are built on first use in O(Σ (p+1) log n_p) (one compare a listing for a listing
//! in lexicographic order), on several threads, reserved fallibly by
//! [`Complex::try_listing_maps`].

use super::table;
use super::{Complex, MAX_DIMENSION, SimplexTable};

/// The input simplices as given, and (computed on first use) which top simplex each became.
///
/// Cost: one copy of the input ids (held for the complex's life), plus an offset (8 bytes) per
/// listed simplex unless all have the same number of vertices (a mesh of one kind of cell:
/// then the offsets are a formula); the listing ↔ top maps cost 12 bytes per listed simplex
/// more, built on first use in O(Σ (p+1) log n_p) by binary search in the top tables.
#[derive(Debug, Clone, Default)]
pub(super) struct Listing {
    pub(super) ids: Vec<u32>,
    pub(super) offsets: Offsets,
    maps: std::sync::OnceLock<ListingMaps>,
    /// The listings absorbed as faces, by ascending vertex ids then listing: built on first
    /// use by [`Complex::listed_index`].
    faces: std::sync::OnceLock<Vec<(Box<[u32]>, usize)>>,
}

/// Where each listed simplex's ids start in [`Listing::ids`].
#[derive(Debug, Clone)]
pub(super) enum Offsets {
    /// `count` simplices of `arity` ids each: simplex `i` starts at `i * arity`.
    Uniform { arity: usize, count: usize },
    /// Simplex `i` is `ids[o[i]..o[i + 1]]` (`o` starts with 0).
    Varied(Vec<usize>),
}

impl Default for Offsets {
    fn default() -> Self {
        Offsets::Uniform { arity: 0, count: 0 }
    }
}

impl Offsets {
    /// The offsets of a reader or caller (`o[0] == 0`, ascending), dropped for the formula when
    /// every simplex has the same length.
    pub(super) fn from_vec(o: Vec<usize>) -> Offsets {
        let count = o.len().saturating_sub(1);
        let arity = o.get(1).copied().unwrap_or(0);
        let uniform = o.first().is_none_or(|&a| a == 0)
            && arity > 0
            && crate::parallel::map_ranges(o.len(), |r| {
                o[r.clone()].iter().zip(r).all(|(&x, i)| x == i * arity)
            })
            .into_iter()
            .all(|ok| ok);
        if uniform || count == 0 {
            Offsets::Uniform { arity, count }
        } else {
            Offsets::Varied(o)
        }
    }

    /// Number of simplices.
    fn count(&self) -> usize {
        match self {
            Offsets::Uniform { count, .. } => *count,
            Offsets::Varied(o) => o.len().saturating_sub(1),
        }
    }

    /// Where simplex `i` starts (`i == count()`: the ids' end).
    #[inline]
    fn at(&self, i: usize) -> usize {
        match self {
            Offsets::Uniform { arity, .. } => i * arity,
            Offsets::Varied(o) => o[i],
        }
    }
}

#[derive(Debug, Clone, Default)]
struct ListingMaps {
    /// Per listed simplex: its top simplex as (dimension, index), or `NONE_TOP` when absorbed
    /// as a face of another listed simplex.
    top: Vec<(u8, u32)>,
    /// Per dimension p, per top p-simplex: its first listing, `u32::MAX` for an isolated vertex
    /// that no simplex lists.
    first: Vec<Vec<u32>>,
}

const NONE_TOP: (u8, u32) = (u8::MAX, u32::MAX);

impl Complex {
    /// The listing: its ids, its simplex count and where simplex `i` starts in the ids
    /// (`0..=count`): simplex `i` as given is `ids[at(i)..at(i + 1)]` (saved files keep them so
    /// that the complex is rebuilt exactly).
    pub(crate) fn listing_arrays(&self) -> (&[u32], usize, impl Fn(usize) -> usize + '_) {
        let o = &self.listing.offsets;
        (&self.listing.ids, o.count(), move |i| o.at(i))
    }

    /// Number of simplices as listed in the input (absorbed ones included).
    pub fn input_count(&self) -> usize {
        self.listing.offsets.count()
    }

    /// Listed simplex `i` exactly as given: its vertex order is the input's winding.
    pub fn input_simplex(&self, i: usize) -> &[u32] {
        let o = &self.listing.offsets;
        &self.listing.ids[o.at(i)..o.at(i + 1)]
    }

    /// Builds the listing ↔ top maps now if their memory (8 bytes a listing, 4 a top simplex)
    /// can be had: `Err(bytes)` otherwise, where the first use would abort.
    pub(crate) fn try_listing_maps(&self) -> Result<(), usize> {
        if self.listing.maps.get().is_none() {
            let tops: usize = self.tops.iter().map(SimplexTable::len).sum();
            let starts = (self.n_vertices as usize + 1) * 4 * self.tops.len();
            crate::parallel::headroom_for(
                self.input_count(),
                self.input_count() * 8 + tops * 4 + starts,
            )?;
            // Another thread may have built them meanwhile: then ours is dropped.
            let _ = self.listing.maps.set(self.build_listing_maps()?);
        }
        Ok(())
    }

    fn listing_maps(&self) -> &ListingMaps {
        self.listing.maps.get_or_init(|| {
            self.build_listing_maps()
                .unwrap_or_else(|bytes| table::abort_for(bytes))
        })
    }

    /// The listing ↔ top maps, every array reserved fallibly (`Err(bytes)`). Each listing is
    /// searched among the top simplices that start with its smallest vertex (a few rows, not
    /// log n_p cache misses), listings on several threads. (Tables small next to the vertex
    /// count are searched whole.) Each top's first listing is the smallest listing that found
    /// it, kept by an atomic minimum on several threads: the same maps for any thread count.
    fn build_listing_maps(&self) -> Result<ListingMaps, usize> {
        let mut starts: Vec<Vec<u32>> = Vec::new();
        table::try_reserve_exact(&mut starts, self.tops.len())?;
        for t in &self.tops {
            // Starts cost O(n): worth it for tables of at least n/4 rows (a Rips complex's few
            // lower-dimensional tops over a million vertices are searched whole).
            starts.push(if t.len() < 64 || t.len() < self.n_vertices as usize / 4 {
                Vec::new()
            } else {
                self.first_vertex_starts(t)?
            });
        }
        // Listings in runs of at least `RUN` on several threads; inside a run each dimension's
        // last answer is tried first (then the row after it): a listing written in
        // lexicographic order, as Rips and alpha makers write it, then costs one compare, not
        // a search. The hint only saves work: the answer is the same without it.
        const RUN: usize = 4096;
        let find = |last: &mut [usize; MAX_DIMENSION + 1], i: usize| {
            let mut sorted = [0u32; MAX_DIMENSION + 1];
            let given = self.input_simplex(i);
            let sorted = &mut sorted[..given.len()];
            sorted.copy_from_slice(given);
            sorted.sort_unstable();
            let p = sorted.len() - 1;
            let (Some(t), Some(start)) = (self.tops.get(p), starts.get(p)) else {
                return NONE_TOP;
            };
            let near = [last[p].wrapping_add(1), last[p]];
            let found = match near
                .into_iter()
                .find(|&j| j < t.len() && t.get(j) == &*sorted)
            {
                Some(j) => Some(j),
                None => find_top(t, start, sorted),
            };
            found.map_or(NONE_TOP, |j| {
                last[p] = j;
                (p as u8, j as u32)
            })
        };
        let top = crate::parallel::try_map_collect_with(
            self.input_count(),
            RUN,
            || [usize::MAX; MAX_DIMENSION + 1],
            find,
        )?;
        drop(starts);
        let mut first: Vec<Vec<std::sync::atomic::AtomicU32>> = Vec::new();
        table::try_reserve_exact(&mut first, self.tops.len())?;
        for t in &self.tops {
            first.push(crate::parallel::try_atomics(t.len(), |_| u32::MAX)?);
        }
        if crate::parallel::splits(top.len()) {
            crate::parallel::map_ranges(top.len(), |range| {
                for i in range {
                    let (p, j) = top[i];
                    if p != u8::MAX {
                        first[p as usize][j as usize]
                            .fetch_min(i as u32, std::sync::atomic::Ordering::Relaxed);
                    }
                }
            });
        } else {
            // One thread: plain words, no atomic instruction per listing.
            for (i, &(p, j)) in top.iter().enumerate() {
                if p != u8::MAX {
                    let f = first[p as usize][j as usize].get_mut();
                    *f = (*f).min(i as u32);
                }
            }
        }
        let first = first.into_iter().map(crate::parallel::into_plain).collect();
        Ok(ListingMaps { top, first })
    }

    /// `start[v]`: the first row of `table` (sorted) whose first vertex is ≥ v, for v in
    /// `0..=n`; vertices in chunks on several threads, each chunk finding its first row by a
    /// binary search and walking on from there.
    fn first_vertex_starts(&self, table: &SimplexTable) -> Result<Vec<u32>, usize> {
        const CHUNK: usize = 4096;
        let mut start = crate::parallel::try_filled(self.n_vertices as usize + 1, 0u32)?;
        crate::parallel::fill_rows(&mut start, CHUNK, |c, part| {
            let v0 = c * CHUNK;
            let mut row =
                table::partition_point(0..table.len(), |mid| (table.get(mid)[0] as usize) < v0);
            for (v, slot) in (v0..).zip(part.iter_mut()) {
                while row < table.len() && (table.get(row)[0] as usize) < v {
                    row += 1;
                }
                *slot = row as u32;
            }
        });
        Ok(start)
    }

    /// The top simplex that listed simplex `i` is, as (dimension, index in [`Complex::tops`]);
    /// `None` when it was absorbed as a face of another listed simplex. A repeated listing maps
    /// to the same top simplex as its first listing. First call: O(Σ (p+1) log n_p).
    pub fn input_top(&self, i: usize) -> Option<(usize, u32)> {
        let (p, j) = self.listing_maps().top[i];
        (p != u8::MAX).then_some((p as usize, j))
    }

    /// The first listing of top p-simplex `i`; `None` for an isolated vertex no simplex lists.
    pub fn top_listing(&self, p: usize, i: u32) -> Option<usize> {
        let f = self.listing_maps().first[p][i as usize];
        (f != u32::MAX).then_some(f as usize)
    }

    /// The first listing of the simplex with vertices `simplex` (any order): for a top simplex
    /// its first listing ([`Complex::top_listing`]), for a face listed on its own (absorbed) its
    /// first listing; `None` when the simplex was never listed. Its attribute values are element
    /// `listed_index` of the [`super::Location::Listed`] attributes.
    ///
    /// Cost: a search in the top table of its dimension (the listing ↔ top maps built on first
    /// use), then, when the simplex is not a top, a binary search among the absorbed listings
    /// (an index of them built on first use: O(a log a) for a absorbed listings, their ids
    /// plus 24 bytes each).
    pub fn listed_index(&self, simplex: &[u32]) -> Option<usize> {
        let mut buf = [0u32; MAX_DIMENSION + 1];
        let sorted = buf.get_mut(..simplex.len())?;
        sorted.copy_from_slice(simplex);
        sorted.sort_unstable();
        let p = sorted.len().checked_sub(1)?;
        if let Some(i) = self.tops(p).find(sorted) {
            return self.top_listing(p, i);
        }
        let faces = self.listing.faces.get_or_init(|| {
            let maps = self.listing_maps();
            let mut faces: Vec<(Box<[u32]>, usize)> = (0..self.input_count())
                .filter(|&i| maps.top[i] == NONE_TOP)
                .map(|i| {
                    let mut ids: Box<[u32]> = self.input_simplex(i).into();
                    ids.sort_unstable();
                    (ids, i)
                })
                .collect();
            faces.sort_unstable();
            faces
        });
        let at = faces.partition_point(|(ids, _)| **ids < *sorted);
        faces
            .get(at)
            .filter(|(ids, _)| **ids == *sorted)
            .map(|&(_, i)| i)
    }

    /// Top p-simplex `i` with its vertices in the order of its first listing (its input
    /// winding); ascending for an isolated vertex no simplex lists.
    pub fn top_oriented(&self, p: usize, i: u32) -> &[u32] {
        match self.top_listing(p, i) {
            Some(l) => self.input_simplex(l),
            None => self.tops(p).get(i as usize),
        }
    }

    /// The top simplices in input order, each once (at its first listing), vertices in input
    /// order, as (listing index, dimension, top index, vertices). Absorbed listings and repeats
    /// are skipped; isolated vertices that no simplex lists are not yielded (every id in
    /// `0..vertex_count` is a vertex).
    pub fn tops_as_given(&self) -> impl Iterator<Item = (usize, usize, u32, &[u32])> + '_ {
        let maps = self.listing_maps();
        (0..self.input_count()).filter_map(move |i| {
            let (p, j) = maps.top[i];
            (p != u8::MAX && maps.first[p as usize][j as usize] as usize == i)
                .then(|| (i, p as usize, j, self.input_simplex(i)))
        })
    }

    /// The top simplices of dimension ≥ 1 as (dimension, vertices in input order), in input
    /// order: those of [`Complex::tops_as_given`], without their indices. When every listed
    /// simplex of two or more vertices is a distinct top simplex (as many as there are top
    /// simplices of dimension ≥ 1: nothing absorbed or repeated), they are the listing itself,
    /// and the listing ↔ top maps (12 bytes a listing) are not built. O(listing).
    pub(crate) fn tops_listed(&self) -> impl Iterator<Item = (usize, &[u32])> + '_ {
        let direct = !self.tops_listed_needs_maps();
        let listing = (0..if direct { self.input_count() } else { 0 })
            .map(|i| self.input_simplex(i))
            .filter(|s| s.len() > 1)
            .map(|s| (s.len() - 1, s));
        let mapped = (!direct)
            .then(|| {
                self.tops_as_given()
                    .filter(|t| t.1 > 0)
                    .map(|(_, p, _, s)| (p, s))
            })
            .into_iter()
            .flatten();
        listing.chain(mapped)
    }

    /// Whether [`Complex::tops_listed`] needs the listing ↔ top maps.
    pub(crate) fn tops_listed_needs_maps(&self) -> bool {
        let tops: usize = self.tops.iter().skip(1).map(SimplexTable::len).sum();
        let listed = (0..self.input_count())
            .filter(|&i| self.listing.offsets.at(i + 1) - self.listing.offsets.at(i) > 1)
            .count();
        tops != listed
    }
}

/// Row of `sorted` in top table `t`: among the rows that start with its first vertex when
/// `start` holds the first-vertex starts, else in the whole table.
fn find_top(t: &SimplexTable, start: &[u32], sorted: &[u32]) -> Option<usize> {
    if start.is_empty() {
        return t.find(sorted).map(|j| j as usize);
    }
    let v = sorted[0] as usize;
    let (lo, hi) = (start[v] as usize, start[v + 1] as usize);
    let a = table::partition_point(lo..hi, |mid| t.get(mid) < sorted);
    (a < hi && t.get(a) == sorted).then_some(a)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Listings of every kind past one run of the map search: sorted runs of tops, shuffled
    /// windings, repeats, absorbed faces, over few vertices (starts) and many (whole search).
    #[test]
    fn listing_maps_name_the_top_each_listing_became() {
        let mut rnd = crate::complex::xorshift_below(0x9e37_79b9_7f4a_7c15);
        for n in [40u32, 3000, 200_000] {
            let mut listed: Vec<Vec<u32>> = (0..9000)
                .map(|_| {
                    let mut s: Vec<u32> = (0..1 + rnd(5)).map(|_| rnd(n as u64) as u32).collect();
                    s.sort_unstable();
                    s.dedup();
                    s
                })
                .collect();
            listed.sort();
            for i in 0..listed.len() {
                match rnd(6) {
                    0 => listed[i].reverse(),
                    1 => listed.push(listed[i].clone()),
                    _ => {}
                }
            }
            let refs: Vec<&[u32]> = listed.iter().map(Vec::as_slice).collect();
            let c = Complex::from_simplices(n, &refs).unwrap();
            let mut first_seen = std::collections::HashMap::new();
            for (i, given) in listed.iter().enumerate() {
                let mut s = given.clone();
                s.sort_unstable();
                let want = c.tops(s.len() - 1).find(&s).map(|j| (s.len() - 1, j));
                assert_eq!(c.input_top(i), want, "listing {i}: {given:?}");
                let first = *first_seen.entry(s).or_insert(i);
                if let Some((p, j)) = want {
                    assert_eq!(c.top_listing(p, j), Some(first));
                }
            }
            // Built again on 2 and 3 threads, cut into small pieces (runs of listings, chunks
            // of vertex starts, ranges of the first-listing minimum): the same maps.
            let (threads, split) = (crate::parallel::threads(), crate::parallel::MIN_PARALLEL);
            crate::parallel::set_split_threshold(5);
            for t in [2, 3] {
                crate::parallel::set_threads(t);
                let maps = c.build_listing_maps().unwrap();
                assert_eq!(maps.top, c.listing_maps().top, "n = {n}, {t} threads");
                assert_eq!(maps.first, c.listing_maps().first, "n = {n}, {t} threads");
            }
            crate::parallel::set_threads(threads);
            crate::parallel::set_split_threshold(split);
        }
    }

    /// Vertex starts of sorted tables with gaps (vertices starting no row) at the chunks'
    /// edges, found on 1 to 3 threads, against a count of the rows by first vertex.
    #[test]
    fn first_vertex_starts_count_the_rows_before_each_vertex() {
        let mut rnd = crate::complex::xorshift_below(0x2545_f491_4f6c_dd1d);
        let n = 3 * 4096 + 5;
        let skip = |v: u64| (4090..4100).contains(&(v % 4096)) || v < 3 || v + 3 > n;
        let mut rows: Vec<Vec<u32>> = (0..20_000)
            .map(|_| {
                let a = rnd(n - 1);
                vec![a as u32, (a + 1 + rnd(n - 1 - a)) as u32]
            })
            .filter(|r| !skip(u64::from(r[0])))
            .collect();
        rows.sort();
        rows.dedup();
        let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
        let c = Complex::from_simplices(n as u32, &refs).unwrap();
        let table = c.tops(1);
        let mut want = vec![0u32; n as usize + 1];
        for s in table.iter() {
            want[s[0] as usize + 1] += 1;
        }
        for v in 0..n as usize {
            want[v + 1] += want[v];
        }
        let (threads, split) = (crate::parallel::threads(), crate::parallel::MIN_PARALLEL);
        crate::parallel::set_split_threshold(2);
        for t in [1, 2, 3] {
            crate::parallel::set_threads(t);
            assert_eq!(c.first_vertex_starts(table).unwrap(), want, "{t} threads");
        }
        crate::parallel::set_threads(threads);
        crate::parallel::set_split_threshold(split);
    }
}
