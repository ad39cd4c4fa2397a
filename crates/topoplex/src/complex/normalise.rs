//! Normalisation: reader output or arrays become a [`Complex`] ([`Complex::from_input`],
//! [`Complex::from_raw`], [`Complex::from_arrays`], [`Complex::from_simplices`]), by the steps
//! of [`Complex::build`]: every simplex checked and sorted into the rows of its dimension
//! (ranges of simplices on several threads for large inputs), repeats removed, the closure's
//! size checked against the [`Budget`] before anything of closure size is allocated, listed
//! faces of other listed simplices absorbed, unused vertices made isolated, and the listing
//! copied (module docs of [`super`]: the input rules).
//!
//! Costs: O(listed ids) to check, plus a sort of each dimension's rows; absorbing faces
//! O(Σ_σ min_{v∈σ} deg(v) · d), near linear on meshes. Memory: the sorted rows (reserved at
//! their exact size, deduplicated by blocks while that pays), the listing's copy, and a few
//! arrays per vertex; every reservation the input's size asks for is fallible
//! ([`ComplexError::OutOfMemory`]).

use std::path::Path;

use super::closure::{EXACT_COUNT_FACTOR, closure_bound, closure_count};
use super::listing::{Listing, Offsets};
use super::{
    Budget, Complex, ComplexError, Coords, InputStats, MAX_DIMENSION, MAX_IMPLIED_VERTICES, Origin,
    RawInput, SimplexTable, is_subset, sort_dedup_rows, table,
};

impl Complex {
    /// Normalises reader output that the complex may keep under `budget` (`file` names the
    /// source in errors): the simplex list becomes the listing and the coordinates the
    /// complex's, moved rather than copied, which keeps the peak memory of reading and building
    /// down (docs/bad-input.md, "Bounded resources"); the offsets are dropped when every
    /// simplex has the same length, and the line numbers once normalised.
    pub fn from_input(
        mut raw: RawInput,
        file: Option<&Path>,
        budget: Budget,
    ) -> Result<Complex, ComplexError> {
        let coords = raw.coords.take();
        let mut c = Complex::normalise_raw(&raw, file, coords, budget, false)?;
        c.listing.ids = raw.ids;
        c.listing.offsets = Offsets::from_vec(raw.offsets);
        c.set_attributes(raw.attributes)?;
        Ok(c)
    }

    /// Normalises reader output under the default [`Budget`]; `file` names the source in errors.
    pub fn from_raw(raw: &RawInput, file: Option<&Path>) -> Result<Complex, ComplexError> {
        Complex::from_raw_with(raw, file, Budget::default())
    }

    /// Normalises reader output under `budget`; `file` names the source in errors. The input
    /// size is the listed ids plus the vertices the file declares.
    pub fn from_raw_with(
        raw: &RawInput,
        file: Option<&Path>,
        budget: Budget,
    ) -> Result<Complex, ComplexError> {
        let mut c = Complex::normalise_raw(raw, file, raw.coords.clone(), budget, true)?;
        c.set_attributes(raw.attributes.clone())?;
        Ok(c)
    }

    /// [`Complex::from_raw_with`] with the coordinates given apart; the listing is left empty
    /// unless `copy_listing`.
    fn normalise_raw(
        raw: &RawInput,
        file: Option<&Path>,
        coords: Option<Coords>,
        budget: Budget,
        copy_listing: bool,
    ) -> Result<Complex, ComplexError> {
        let origin = |i: usize| Origin {
            file: file.map(Path::to_path_buf),
            line: raw.lines.get(i).copied().unwrap_or(0),
            index: i,
        };
        let n = match raw.vertex_count {
            Some(n) => n,
            None => {
                // The vertices are 0..=max id: a single large id would otherwise make a tiny
                // file demand gigabytes of isolated vertices.
                let Some((i, &max)) = (0..raw.simplex_count())
                    .flat_map(|i| raw.simplex(i).iter().map(move |v| (i, v)))
                    .max_by_key(|&(_, v)| *v)
                else {
                    return Err(ComplexError::NoVertices {
                        file: file.map(Path::to_path_buf),
                    });
                };
                if max >= MAX_IMPLIED_VERTICES {
                    return Err(ComplexError::ImpliedVertexCount {
                        origin: origin(i),
                        simplex: raw.simplex(i).to_vec(),
                        vertex: max,
                        max: MAX_IMPLIED_VERTICES,
                    });
                }
                max + 1
            }
        };
        let input_size = raw.ids.len() as u64 + raw.vertex_count.map_or(0, u64::from);
        Complex::build(
            n,
            coords,
            raw.simplex_count(),
            |i| raw.simplex(i),
            origin,
            file,
            (budget, input_size),
            if copy_listing {
                ListingSource::Arrays(&raw.ids, &raw.offsets)
            } else {
                ListingSource::None
            },
        )
    }

    /// Builds from arrays under the default [`Budget`]: simplex `i` is
    /// `ids[offsets[i]..offsets[i+1]]`.
    pub fn from_arrays(
        n_vertices: u32,
        ids: &[u32],
        offsets: &[usize],
        coords: Option<Coords>,
    ) -> Result<Complex, ComplexError> {
        Complex::from_arrays_with(n_vertices, ids, offsets, coords, Budget::default())
    }

    /// Builds from arrays under `budget`. The input size is the ids plus, when coordinates are
    /// given, the vertices (a bare vertex count, without coordinates, is not input: a caller
    /// asking for 2^32 isolated vertices must raise the budget).
    pub fn from_arrays_with(
        n_vertices: u32,
        ids: &[u32],
        offsets: &[usize],
        coords: Option<Coords>,
        budget: Budget,
    ) -> Result<Complex, ComplexError> {
        let input_size = ids.len() as u64
            + if coords.is_some() {
                u64::from(n_vertices)
            } else {
                0
            };
        let count = offsets.len().saturating_sub(1);
        Complex::build(
            n_vertices,
            coords,
            count,
            |i| &ids[offsets[i]..offsets[i + 1]],
            array_origin,
            None,
            (budget, input_size),
            ListingSource::Arrays(ids, offsets),
        )
    }

    /// Builds from one array of simplices of `arity` vertices each (simplex `i` is
    /// `ids[i * arity..(i + 1) * arity]`, as a numpy `(n, arity)` array lies in memory) under
    /// the default [`Budget`]: [`Complex::from_arrays`] without the offsets, which the listing
    /// keeps as a formula anyway (8 bytes a simplex neither made nor read). A length that is
    /// not a multiple of `arity` leaves a shorter last simplex; `arity` 0 with ids is an empty
    /// simplex (refused). Cost: that of `from_arrays`.
    pub fn from_uniform(
        n_vertices: u32,
        arity: usize,
        ids: &[u32],
        coords: Option<Coords>,
    ) -> Result<Complex, ComplexError> {
        let input_size = ids.len() as u64
            + if coords.is_some() {
                u64::from(n_vertices)
            } else {
                0
            };
        let len = ids.len();
        let count = match arity {
            0 => usize::from(len > 0),
            a => len.div_ceil(a),
        };
        Complex::build(
            n_vertices,
            coords,
            count,
            |i| &ids[(i * arity).min(len)..((i + 1) * arity).min(len)],
            array_origin,
            None,
            (Budget::default(), input_size),
            ListingSource::Uniform(ids),
        )
    }

    /// Builds from a list of simplices (tests, fixtures).
    pub fn from_simplices(n_vertices: u32, simplices: &[&[u32]]) -> Result<Complex, ComplexError> {
        Complex::build(
            n_vertices,
            None,
            simplices.len(),
            |i| simplices[i],
            array_origin,
            None,
            (Budget::UNLIMITED, 0),
            ListingSource::Each,
        )
    }

    /// Validates, sorts and absorbs. `(budget, input_size)`: the closure's upper bound is
    /// checked against `budget.limit(input_size)` before anything of closure size is allocated.
    /// The listing is copied from `listing_source` (left empty for the caller to fill when
    /// [`ListingSource::None`]).
    #[allow(clippy::too_many_arguments)]
    fn build<'a>(
        n: u32,
        coords: Option<Coords>,
        count: usize,
        simplex: impl Fn(usize) -> &'a [u32] + Sync,
        origin: impl Fn(usize) -> Origin,
        file: Option<&Path>,
        (budget, input_size): (Budget, u64),
        listing_source: ListingSource<'a>,
    ) -> Result<Complex, ComplexError> {
        let oom = |what| no_room(file, what);
        check_vertices(n, coords.as_ref(), file)?;
        // Validate and bucket by dimension; rows are sorted so duplicates become equal rows.
        // Exact sizes up front: growing by doubling would hold up to twice the ids (peak memory).
        let totals = ids_per_length(count, &simplex);
        let by_dim = sorted_rows(count, n, &simplex, &totals).map_err(|stop| match stop {
            Stop::Refused(i, why) => why.error(origin(i), simplex(i).to_vec(), n),
            Stop::NoRoom(bytes) => oom("the input simplices")(bytes),
        })?;
        let mut stats = InputStats {
            input_simplices: count,
            ..Default::default()
        };
        let tables =
            dedup_tables(by_dim, &mut stats).map_err(oom("sorting the input simplices"))?;
        check_budget(n, &tables, budget, input_size, file)?;
        let tops = absorb_faces(n, tables, &mut stats).map_err(oom("the vertex tables"))?;
        let listing = copy_listing(listing_source, count, &simplex, &totals)
            .map_err(oom("the input listing"))?;
        Ok(Complex {
            n_vertices: n,
            coords: coords.unwrap_or(Coords {
                dim: 0,
                data: Vec::new(),
            }),
            tops,
            stats,
            source: file.map(Path::to_path_buf),
            listing,
            attributes: Default::default(),
        })
    }
}

/// Where simplex `i` of arrays given through the API was given.
fn array_origin(i: usize) -> Origin {
    Origin {
        file: None,
        line: 0,
        index: i,
    }
}

/// The error for `bytes` of memory for `what` that could not be had.
fn no_room<'f>(file: Option<&'f Path>, what: &'static str) -> impl Fn(usize) -> ComplexError + 'f {
    move |bytes| ComplexError::OutOfMemory {
        file: file.map(Path::to_path_buf),
        what,
        bytes: bytes as u64,
    }
}

/// Refuses a complex of no vertex, and coordinates other than `dim` numbers a vertex.
fn check_vertices(
    n: u32,
    coords: Option<&Coords>,
    file: Option<&Path>,
) -> Result<(), ComplexError> {
    if n == 0 {
        return Err(ComplexError::NoVertices {
            file: file.map(Path::to_path_buf),
        });
    }
    if let Some(c) = coords
        && c.data.len() != c.dim * n as usize
    {
        return Err(ComplexError::Coordinates(format!(
            "{} numbers given for {n} vertices of dimension {}",
            c.data.len(),
            c.dim
        )));
    }
    Ok(())
}

/// `totals[k − 1]`: the ids of the simplices `0..count` of k vertices, for k in
/// `1..=MAX_DIMENSION + 1` (simplices of other lengths are refused by [`sorted_row`]).
fn ids_per_length<'a>(
    count: usize,
    simplex: &impl Fn(usize) -> &'a [u32],
) -> [usize; MAX_DIMENSION + 1] {
    let mut totals = [0usize; MAX_DIMENSION + 1];
    for i in 0..count {
        let len = simplex(i).len();
        if (1..=MAX_DIMENSION + 1).contains(&len) {
            totals[len - 1] += len;
        }
    }
    totals
}

/// Simplices `0..count` checked and sorted ([`sorted_row`]) into the rows of their dimension,
/// reserved for `totals` ([`ids_per_length`]): on several threads when `count` splits
/// ([`sorted_rows_in_parallel`]), else in one loop; the first refused simplex in input order.
fn sorted_rows<'a>(
    count: usize,
    n: u32,
    simplex: &(impl Fn(usize) -> &'a [u32] + Sync),
    totals: &[usize; MAX_DIMENSION + 1],
) -> Result<Vec<Rows>, Stop> {
    let highest = totals.iter().rposition(|&t| t > 0).map_or(0, |p| p + 1);
    let mut by_dim: Vec<Rows> = totals[..highest]
        .iter()
        .enumerate()
        .map(|(p, &t)| Rows::new(p + 1, t))
        .collect();
    if crate::parallel::splits(count) {
        sorted_rows_in_parallel(count, n, simplex, &mut by_dim)?;
    } else {
        let mut sorted = [0u32; MAX_DIMENSION + 1];
        for i in 0..count {
            let row =
                sorted_row(simplex(i), n, &mut sorted).map_err(|why| Stop::Refused(i, why))?;
            by_dim[row.len() - 1].push(row).map_err(Stop::NoRoom)?;
        }
    }
    Ok(by_dim)
}

/// Each dimension's rows as a sorted table without repeats; the repeats counted in `stats`.
/// `Err(bytes)` when the sort's memory cannot be had.
fn dedup_tables(by_dim: Vec<Rows>, stats: &mut InputStats) -> Result<Vec<SimplexTable>, usize> {
    let mut tables: Vec<SimplexTable> = Vec::with_capacity(by_dim.len());
    for (p, rows) in by_dim.into_iter().enumerate() {
        let (t, dups) = SimplexTable::try_from_rows(p + 1, rows.ids)?;
        stats.absorbed_duplicates += dups + rows.absorbed;
        tables.push(t);
    }
    Ok(tables)
}

/// Refuses a closure that could outgrow `budget` for an input of `input_size`: its upper
/// bound ([`closure_bound`]) above the limit, and, when the bound is not far above it
/// ([`EXACT_COUNT_FACTOR`]), its exact size ([`closure_count`]) too.
fn check_budget(
    n: u32,
    tables: &[SimplexTable],
    budget: Budget,
    input_size: u64,
    file: Option<&Path>,
) -> Result<(), ComplexError> {
    let bound = closure_bound(n, tables);
    let limit = budget.limit(input_size);
    // The bound ignores shared faces; when it is not far above the limit, count exactly.
    if bound > limit
        && (bound > limit.saturating_mul(EXACT_COUNT_FACTOR)
            || closure_count(n, tables, limit).is_none())
    {
        return Err(ComplexError::TooLarge {
            file: file.map(Path::to_path_buf),
            bound,
            limit,
            input_size,
        });
    }
    Ok(())
}

/// Where [`Complex::build`] copies the listing from.
enum ListingSource<'a> {
    /// Nowhere: the caller moves its own arrays in.
    None,
    /// Simplex by simplex, through the accessor.
    Each,
    /// Arrays in which simplex `i` is `ids[offsets[i]..offsets[i + 1]]`: the simplices are one
    /// run of `ids`, copied whole on several threads.
    Arrays(&'a [u32], &'a [usize]),
    /// One run of `ids` in simplices of one length ([`Complex::from_uniform`]), copied whole on
    /// several threads when they are (else simplex by simplex).
    Uniform(&'a [u32]),
}

/// The listing of simplices `0..count` (all checked: 1 to `MAX_DIMENSION + 1` ids each, so
/// `totals`, the ids per length, has one non-zero entry exactly when every simplex has the same
/// length, and the offsets are then a formula). Memory reserved fallibly (`Err(bytes)`).
fn copy_listing<'a>(
    source: ListingSource<'a>,
    count: usize,
    simplex: &impl Fn(usize) -> &'a [u32],
    totals: &[usize],
) -> Result<Listing, usize> {
    let mut listing = Listing::default();
    let id_count: usize = totals.iter().sum();
    let varied = totals.iter().filter(|&&t| t > 0).count() > 1;
    let mut offsets = Vec::new();
    match source {
        ListingSource::None => return Ok(listing),
        ListingSource::Arrays(ids, o) if count > 0 => {
            // Every simplex was sliced out of `ids` by the caller already, so `o[..=count]` is
            // ascending and within `ids`.
            let (base, run) = (o[0], &ids[o[0]..o[count]]);
            listing.ids = crate::parallel::try_map_collect(run.len(), |k| run[k])
                .map_err(|_| id_count * 4)?;
            if varied {
                offsets = crate::parallel::try_map_collect(count + 1, |i| o[i] - base)
                    .map_err(|_| (count + 1) * 8)?;
            }
        }
        ListingSource::Uniform(ids) if count > 0 && !varied => {
            listing.ids = crate::parallel::try_map_collect(ids.len(), |k| ids[k])
                .map_err(|_| id_count * 4)?;
        }
        _ => {
            if varied {
                table::try_reserve_exact(&mut offsets, count + 1).map_err(|_| (count + 1) * 8)?;
                offsets.push(0);
            }
            table::try_reserve_exact(&mut listing.ids, id_count).map_err(|_| id_count * 4)?;
            for i in 0..count {
                listing.ids.extend_from_slice(simplex(i));
                if varied {
                    offsets.push(listing.ids.len());
                }
            }
        }
    }
    listing.offsets = if varied {
        Offsets::Varied(offsets)
    } else {
        Offsets::Uniform {
            arity: id_count / count.max(1),
            count,
        }
    };
    Ok(listing)
}

/// Why a listed simplex is refused (the error is made with its origin by the caller).
#[derive(Debug, Clone, Copy)]
enum Invalid {
    Empty,
    TooHigh,
    OutOfRange(u32),
    Repeated(u32),
}

impl Invalid {
    /// The error for `simplex`, given at `origin`, in a complex of `n` vertices.
    #[cold]
    fn error(self, origin: Origin, simplex: Vec<u32>, n: u32) -> ComplexError {
        match self {
            Invalid::Empty => ComplexError::EmptySimplex { origin },
            Invalid::TooHigh => ComplexError::DimensionTooHigh {
                origin,
                dim: simplex.len() - 1,
                simplex,
                max: MAX_DIMENSION,
            },
            Invalid::OutOfRange(vertex) => ComplexError::VertexOutOfRange {
                origin,
                simplex,
                vertex,
                n,
            },
            Invalid::Repeated(vertex) => ComplexError::RepeatedVertex {
                origin,
                simplex,
                vertex,
            },
        }
    }
}

/// Simplex `s` checked (1 to `MAX_DIMENSION + 1` vertices, ids below `n`, none repeated) and
/// sorted into `buf`: the sorted row.
#[inline]
fn sorted_row<'b>(
    s: &'b [u32],
    n: u32,
    buf: &'b mut [u32; MAX_DIMENSION + 1],
) -> Result<&'b [u32], Invalid> {
    if s.is_empty() {
        return Err(Invalid::Empty);
    }
    if s.len() > MAX_DIMENSION + 1 {
        return Err(Invalid::TooHigh);
    }
    if s.is_sorted_by(|a, b| a < b) {
        // Ascending as given (Rips and alpha makers write rows so): no repeat, and the first
        // id out of range, if any, is at the end.
        return match s[s.len() - 1] {
            last if last < n => Ok(s),
            _ => Err(Invalid::OutOfRange(
                *s.iter().find(|&&v| v >= n).unwrap_or(&n),
            )),
        };
    }
    if let Some(&v) = s.iter().find(|&&v| v >= n) {
        return Err(Invalid::OutOfRange(v));
    }
    let row = &mut buf[..s.len()];
    row.copy_from_slice(s);
    row.sort_unstable();
    if let Some(w) = row.windows(2).find(|w| w[0] == w[1]) {
        return Err(Invalid::Repeated(w[0]));
    }
    Ok(row)
}

/// Why [`sorted_rows_in_parallel`] stopped: simplex `i` is refused, or memory ran out.
enum Stop {
    Refused(usize, Invalid),
    NoRoom(usize),
}

/// [`sorted_row`] of simplices `0..count` pushed into `by_dim` (by length) on several threads,
/// with the serial loop's result: the same rows, the first refused simplex in input order.
/// While a dimension's rows may still be deduplicated by blocks ([`Rows::push`]), windows of
/// simplices are checked and sorted in ranges on [`crate::parallel::threads`] threads into
/// buffers of the window's size (reserved fallibly), then pushed in order; from where no
/// dimension deduplicates any more (at once for most inputs, after one block for large
/// ones), the rest is written in place ([`rows_in_place`]).
fn sorted_rows_in_parallel<'a>(
    count: usize,
    n: u32,
    simplex: &(impl Fn(usize) -> &'a [u32] + Sync),
    by_dim: &mut [Rows],
) -> Result<(), Stop> {
    const WINDOW: usize = 1 << 18;
    let mut w = 0;
    while w < count {
        if by_dim.iter().all(|r| r.next_dedup == usize::MAX) {
            return rows_in_place(w..count, n, simplex, by_dim);
        }
        let window = w..(w + WINDOW).min(count);
        let parts = crate::parallel::map_ranges(window.len(), |r| {
            let r = (w + r.start)..(w + r.end);
            let ids: usize = r
                .clone()
                .map(|i| simplex(i).len().min(MAX_DIMENSION + 1))
                .sum();
            let mut rows: Vec<u32> = Vec::new();
            table::try_reserve_exact(&mut rows, ids)?;
            let mut buf = [0u32; MAX_DIMENSION + 1];
            for i in r.clone() {
                match sorted_row(simplex(i), n, &mut buf) {
                    Ok(row) => rows.extend_from_slice(row),
                    Err(why) => return Ok((rows, r, Some((i, why)))),
                }
            }
            Ok((rows, r, None))
        });
        for part in parts {
            let (rows, r, refused) = part.map_err(Stop::NoRoom)?;
            let mut at = 0;
            for i in r.start..refused.map_or(r.end, |(i, _)| i) {
                let len = simplex(i).len();
                by_dim[len - 1]
                    .push(&rows[at..at + len])
                    .map_err(Stop::NoRoom)?;
                at += len;
            }
            if let Some((i, why)) = refused {
                return Err(Stop::Refused(i, why));
            }
        }
        w = window.end;
    }
    Ok(())
}

/// The rows of simplices `range` written in place on several threads, once no dimension
/// deduplicates: each dimension's array is reserved at its exact final size (as
/// [`Rows::push`] would) and filled with zeros, every range of simplices counts its rows per
/// dimension, and then sorts its simplices into its own slice of each array.
fn rows_in_place<'a>(
    range: std::ops::Range<usize>,
    n: u32,
    simplex: &(impl Fn(usize) -> &'a [u32] + Sync),
    by_dim: &mut [Rows],
) -> Result<(), Stop> {
    let ranges: Vec<_> = crate::parallel::ranges(range.len())
        .into_iter()
        .map(|r| (range.start + r.start)..(range.start + r.end))
        .collect();
    let dims = by_dim.len();
    let counts = crate::parallel::map_chunks(ranges.len(), |k| {
        let mut c = [0usize; MAX_DIMENSION + 1];
        for i in ranges[k].clone() {
            let len = simplex(i).len();
            if (1..=dims).contains(&len) {
                c[len - 1] += len;
            }
        }
        c
    });
    let mut tails = Vec::with_capacity(dims);
    for rows in by_dim.iter_mut() {
        let base = rows.ids.len();
        table::try_reserve_exact(&mut rows.ids, rows.left).map_err(Stop::NoRoom)?;
        crate::parallel::extend_filled(&mut rows.ids, rows.left, 0);
        rows.left = 0;
        tails.push(&mut rows.ids[base..]);
    }
    let mut parts = Vec::with_capacity(ranges.len());
    for (c, r) in counts.iter().zip(&ranges) {
        let mine: Vec<&mut [u32]> = tails
            .iter_mut()
            .zip(c)
            .map(|(t, &len)| {
                let (a, b) = std::mem::take(t).split_at_mut(len);
                *t = b;
                a
            })
            .collect();
        parts.push((mine, r.clone()));
    }
    let refused: Vec<Option<(usize, Invalid)>> =
        crate::parallel::map_items(parts, |(mut slices, r)| {
            let mut at = [0usize; MAX_DIMENSION + 1];
            let mut buf = [0u32; MAX_DIMENSION + 1];
            for i in r {
                match sorted_row(simplex(i), n, &mut buf) {
                    Ok(row) => {
                        let p = row.len() - 1;
                        slices[p][at[p]..at[p] + row.len()].copy_from_slice(row);
                        at[p] += row.len();
                    }
                    Err(why) => return Some((i, why)),
                }
            }
            None
        });
    match refused.into_iter().flatten().next() {
        Some((i, why)) => Err(Stop::Refused(i, why)),
        None => Ok(()),
    }
}

/// The sorted input rows of one dimension, deduplicated as they come while that pays: a file
/// of many short lines lists the same few simplices over and over (an 8-byte `s 1 2 3` line can
/// only name vertices 0–9), and holding every copy until the final sort would cost 12 bytes a
/// line plus the sort's keys (issue 16 class 5: reading must peak under 5× the file). Each
/// block of [`Rows::BLOCK`] rows is sorted and deduplicated with what is held; once a block
/// removes less than half of the rows, the rest is reserved exactly and kept as is (unique
/// inputs pay one sort of one block).
struct Rows {
    arity: usize,
    ids: Vec<u32>,
    /// Ids still to come for this dimension.
    left: usize,
    /// Row count at which the next block is deduplicated; `usize::MAX` once that stopped.
    next_dedup: usize,
    /// Rows removed as duplicates so far.
    absorbed: usize,
}

impl Rows {
    /// Rows a block holds before it is deduplicated.
    const BLOCK: usize = 1 << 18;

    fn new(arity: usize, total_ids: usize) -> Rows {
        let rows = total_ids / arity;
        let dedup = rows > 2 * Rows::BLOCK;
        Rows {
            arity,
            // Exact reservation unless blocks may shrink it (growth by doubling would hold up
            // to twice the ids).
            ids: Vec::new(),
            left: total_ids,
            next_dedup: if dedup { Rows::BLOCK } else { usize::MAX },
            absorbed: 0,
        }
    }

    /// Appends one sorted row; `Err(bytes)` when memory runs out.
    fn push(&mut self, row: &[u32]) -> Result<(), usize> {
        if self.ids.len() == self.ids.capacity() {
            let want = if self.next_dedup == usize::MAX {
                self.left
            } else {
                (self.next_dedup * self.arity - self.ids.len()).min(self.left)
            };
            self.ids
                .try_reserve_exact(want.max(row.len()))
                .map_err(|_| want * 4)?;
        }
        self.ids.extend_from_slice(row);
        self.left -= row.len();
        if self.next_dedup != usize::MAX && self.ids.len() == self.next_dedup * self.arity {
            self.dedup();
        }
        Ok(())
    }

    /// Sorts and deduplicates what is held; sets the next block's bound, or stops.
    fn dedup(&mut self) {
        let before = self.ids.len() / self.arity;
        let ids = std::mem::take(&mut self.ids);
        self.ids = sort_dedup_rows(self.arity, ids);
        let after = self.ids.len() / self.arity;
        self.absorbed += before - after;
        // Held rows sorted plus a fresh block: continue while blocks halve at least.
        self.next_dedup = if before - after >= Rows::BLOCK / 2 {
            after + Rows::BLOCK
        } else {
            usize::MAX
        };
    }
}

/// Drops listed simplices that are faces of higher-dimensional listed ones, and adds the vertices
/// no simplex uses as top 0-simplices. A p-simplex is tested against the listed simplices of
/// higher dimension at its *hub*, its vertex with the fewest listed simplices of dimension ≥ 2:
/// O(Σ_σ min_{v∈σ} deg(v) · d) in all, near linear on meshes (the worst case is many
/// low-dimensional simplices all at one hub vertex). Only the hubs' simplices are gathered
/// (a Rips complex's few low-dimensional tops touch a small part of its stars). Testing against
/// every listed simplex, absorbed or not, gives the verdict of testing against the kept ones: a
/// face of an absorbed simplex is a face of the simplex that absorbed it. The per-vertex arrays
/// are reserved fallibly: `Err(bytes)` when they cannot be had.
fn absorb_faces(
    n: u32,
    mut tables: Vec<SimplexTable>,
    stats: &mut InputStats,
) -> Result<Vec<SimplexTable>, usize> {
    // No listed simplex at all: every vertex is isolated.
    let d = tables.len().max(1) - 1;
    let (degree, used) = degrees(n, &tables)?;
    let used = |v: u32| used[v as usize];
    let hub = |s: &[u32]| *s.iter().min_by_key(|&&v| degree[v as usize]).unwrap();
    let mut kept: Vec<SimplexTable> = vec![SimplexTable::default(); d + 1];
    // Only when some dimension 1..d has simplices to test: a pure mesh never pays for the stars.
    let test = tables
        .get(1..d)
        .is_some_and(|t| t.iter().any(|t| !t.is_empty()));
    if test {
        let stars = HubStars::new(n, &tables, &degree, hub)?;
        for p in (1..d).rev() {
            let t = &tables[p];
            let parts = crate::parallel::map_ranges(t.len(), |r| -> Result<_, usize> {
                let (mut rows, mut absorbed) = (Vec::new(), 0usize);
                for s in r.map(|i| t.get(i)) {
                    // A star lists its simplices by dimension: those above p are its tail.
                    let star = stars.at(hub(s));
                    let above = &star[star.partition_point(|&(q, _)| q as usize <= p)..];
                    let is_face = above
                        .iter()
                        .any(|&(q, j)| is_subset(s, tables[q as usize].get(j as usize)));
                    if is_face {
                        absorbed += 1;
                    } else {
                        table::try_extend(&mut rows, s)?;
                    }
                }
                Ok((rows, absorbed))
            });
            let mut rows = Vec::new();
            for part in parts {
                let (part, absorbed) = part?;
                stats.absorbed_faces += absorbed;
                if rows.is_empty() {
                    rows = part;
                } else {
                    table::try_extend(&mut rows, &part)?;
                }
            }
            // A subsequence of a sorted table is still sorted.
            kept[p] = SimplexTable::from_sorted_unique(p + 1, rows);
        }
    }
    for p in 1..=d {
        if p == d || !test {
            kept[p] = std::mem::take(&mut tables[p]);
        }
    }
    let listed_vertices = tables.first().map_or(0, SimplexTable::len);
    let listed_isolated = tables
        .first()
        .map_or(0, |t| t.iter().filter(|s| !used(s[0])).count());
    stats.absorbed_faces += listed_vertices - listed_isolated;
    let free = (0..n).filter(|&v| !used(v)).count();
    let mut isolated: Vec<u32> = Vec::new();
    isolated.try_reserve_exact(free).map_err(|_| free * 4)?;
    isolated.extend((0..n).filter(|&v| !used(v)));
    kept[0] = SimplexTable::from_sorted_unique(1, isolated);
    // A complex of only isolated vertices has d = 0.
    while kept.len() > 1 && kept.last().unwrap().is_empty() {
        kept.pop();
    }
    Ok(kept)
}

/// Per vertex, the number of listed simplices of dimension ≥ 2 at it (saturating: it only
/// picks hubs), and whether a listed simplex of dimension ≥ 1 uses it — which a kept one then
/// does too (a listed simplex is kept or a face of a kept one). Reserved fallibly.
fn degrees(n: u32, tables: &[SimplexTable]) -> Result<(Vec<u32>, Vec<bool>), usize> {
    let n = n as usize;
    let mut degree: Vec<u32> = Vec::new();
    table::try_reserve_exact(&mut degree, n)?;
    degree.resize(n, 0);
    let mut edge: Vec<bool> = Vec::new();
    table::try_reserve_exact(&mut edge, n)?;
    edge.resize(n, false);
    for (p, t) in tables.iter().enumerate().skip(1) {
        for &v in t.as_flat() {
            if p == 1 {
                edge[v as usize] = true;
            } else {
                degree[v as usize] = degree[v as usize].saturating_add(1);
            }
        }
    }
    for (e, &k) in edge.iter_mut().zip(&degree) {
        *e |= k > 0;
    }
    Ok((degree, edge))
}

/// A listed simplex as (dimension, row in its table).
type Listed = (u8, u32);

/// The listed simplices of dimension ≥ 2 at each hub of a simplex to test (CSR over the hubs,
/// in hub order of first appearance).
struct HubStars {
    /// Per vertex: its hub number, `u32::MAX` when it is no hub.
    slot: Vec<u32>,
    off: Vec<usize>,
    at: Vec<Listed>,
}

impl HubStars {
    /// The stars of the hubs (by `hub`) of the simplices of dimensions 1..d−1 that may be faces
    /// (hubs with a listed simplex of dimension ≥ 2). Reserved fallibly.
    fn new(
        n: u32,
        tables: &[SimplexTable],
        degree: &[u32],
        hub: impl Fn(&[u32]) -> u32,
    ) -> Result<HubStars, usize> {
        let d = tables.len() - 1;
        let mut slot: Vec<u32> = Vec::new();
        table::try_reserve_exact(&mut slot, n as usize)?;
        slot.resize(n as usize, u32::MAX);
        let mut off = vec![0usize];
        for t in &tables[1..d] {
            for s in t.iter() {
                let h = hub(s) as usize;
                if slot[h] == u32::MAX && degree[h] > 0 {
                    if degree[h] == u32::MAX {
                        // Only a saturated count: more listed simplices than memory holds.
                        return Err(usize::MAX);
                    }
                    let end = off[off.len() - 1] + degree[h] as usize;
                    slot[h] = (off.len() - 1) as u32;
                    table::try_push(&mut off, end)?;
                }
            }
        }
        let mut fill: Vec<usize> = Vec::new();
        table::try_reserve_exact(&mut fill, off.len())?;
        fill.extend_from_slice(&off);
        let mut at: Vec<Listed> = Vec::new();
        let len = off[off.len() - 1];
        table::try_reserve_exact(&mut at, len)?;
        at.resize(len, (0, 0));
        for (p, t) in tables.iter().enumerate().skip(2) {
            for (j, s) in t.iter().enumerate() {
                for &v in s {
                    let h = slot[v as usize];
                    if h != u32::MAX {
                        at[fill[h as usize]] = (p as u8, j as u32);
                        fill[h as usize] += 1;
                    }
                }
            }
        }
        Ok(HubStars { slot, off, at })
    }

    /// The listed simplices of dimension ≥ 2 at `v`, by dimension (empty when `v` is no hub).
    fn at(&self, v: u32) -> &[Listed] {
        match self.slot[v as usize] {
            u32::MAX => &[],
            h => &self.at[self.off[h as usize]..self.off[h as usize + 1]],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::{MAX_DIMENSION, is_subset};

    /// `from_uniform` gives the complex `from_arrays` gives with the offsets of that arity:
    /// the same tops, listing (each simplex as given) and statistics, on random rows of 1 to 4
    /// vertices (repeats, faces and bad rows included: the same error then); a short last row
    /// is a simplex of its own, arity 0 an empty simplex.
    #[test]
    fn from_uniform_equals_from_arrays_with_uniform_offsets() {
        let mut rnd = crate::complex::xorshift_below(0x0f0f_1234_5678_9abc);
        for _ in 0..300 {
            let arity = 1 + rnd(4) as usize;
            let n = 2 + rnd(8) as u32;
            let rows = rnd(9) as usize;
            let ids: Vec<u32> = (0..rows * arity)
                .map(|_| rnd(u64::from(n) + 1) as u32)
                .collect();
            let offsets: Vec<usize> = (0..=rows).map(|i| i * arity).collect();
            let want = Complex::from_arrays(n, &ids, &offsets, None);
            let got = Complex::from_uniform(n, arity, &ids, None);
            match (want, got) {
                (Ok(w), Ok(g)) => {
                    assert_eq!(w.top_counts(), g.top_counts());
                    for p in 0..=w.dimension() {
                        let (a, b) = (w.tops(p), g.tops(p));
                        assert!((0..a.len()).all(|i| a.get(i) == b.get(i)));
                    }
                    assert_eq!(w.input_count(), g.input_count());
                    for i in 0..w.input_count() {
                        assert_eq!(w.input_simplex(i), g.input_simplex(i));
                    }
                    assert_eq!(w.stats(), g.stats());
                }
                (Err(w), Err(g)) => assert_eq!(w.to_string(), g.to_string()),
                (w, g) => panic!("from_arrays {w:?} but from_uniform {g:?}"),
            }
        }
        let short = Complex::from_uniform(5, 3, &[0, 1, 2, 3, 4], None).unwrap();
        assert_eq!(short.input_count(), 2);
        assert_eq!(short.input_simplex(1), &[3, 4]);
        assert!(matches!(
            Complex::from_uniform(5, 0, &[0], None),
            Err(ComplexError::EmptySimplex { .. })
        ));
        assert_eq!(
            Complex::from_uniform(5, 0, &[], None)
                .unwrap()
                .vertex_count(),
            5
        );
    }

    /// Normalises a listing by definition: rows sorted, repeats counted, a row that is a
    /// proper subset of another counted as a face, unused vertices isolated.
    fn normalised_by_brute_force(n: u32, listed: &[Vec<u32>]) -> (Vec<Vec<Vec<u32>>>, InputStats) {
        let mut rows: Vec<Vec<u32>> = listed
            .iter()
            .map(|s| {
                let mut s = s.clone();
                s.sort_unstable();
                s
            })
            .collect();
        rows.sort();
        rows.dedup();
        let mut stats = InputStats {
            input_simplices: listed.len(),
            absorbed_duplicates: listed.len() - rows.len(),
            absorbed_faces: 0,
        };
        let mut tops: Vec<Vec<Vec<u32>>> = vec![Vec::new(); MAX_DIMENSION + 1];
        for s in &rows {
            if rows.iter().any(|t| t.len() > s.len() && is_subset(s, t)) {
                stats.absorbed_faces += 1;
            } else {
                tops[s.len() - 1].push(s.clone());
            }
        }
        let used: std::collections::HashSet<u32> = rows.iter().flatten().copied().collect();
        tops[0].extend((0..n).filter(|v| !used.contains(v)).map(|v| vec![v]));
        tops[0].sort();
        while tops.len() > 1 && tops.last().unwrap().is_empty() {
            tops.pop();
        }
        (tops, stats)
    }

    fn tops_of(c: &Complex) -> Vec<Vec<Vec<u32>>> {
        (0..=c.dimension())
            .map(|p| c.tops(p).iter().map(<[u32]>::to_vec).collect())
            .collect()
    }

    fn from_listing(n: u32, listed: &[Vec<u32>]) -> Result<Complex, ComplexError> {
        let ids: Vec<u32> = listed.concat();
        let mut offsets = vec![0];
        for s in listed {
            offsets.push(offsets.last().unwrap() + s.len());
        }
        Complex::from_arrays_with(n, &ids, &offsets, None, Budget::UNLIMITED)
    }

    /// A listing written as Rips and alpha makers write it (rows ascending, in lexicographic
    /// order per dimension: no sort needed) and the same simplices shuffled and reversed (every
    /// row and table sorted) give the tops and counts of the definition — with repeats and
    /// faces of other listed simplices, some shared and mixed in. Large listings (so the
    /// ascending check and the rows split into ranges) and small.
    #[test]
    fn ascending_listings_and_shuffled_ones_normalise_as_by_definition() {
        let mut rnd = crate::complex::xorshift_below(0x51ed_270b_2763_f3a9);
        for case in 0..120 {
            let n = 2 + rnd(if case % 3 == 0 { 400 } else { 12 }) as u32;
            let count = rnd(if case % 10 == 0 { 3000 } else { 40 }) as usize;
            let mut listed: Vec<Vec<u32>> = (0..count)
                .map(|_| {
                    let mut s: Vec<u32> = (0..1 + rnd(6)).map(|_| rnd(n as u64) as u32).collect();
                    s.sort_unstable();
                    s.dedup();
                    s
                })
                .collect();
            // Faces of listed simplices and repeats.
            for i in 0..listed.len() {
                match rnd(5) {
                    0 if listed[i].len() > 1 => {
                        let mut f = listed[i].clone();
                        f.remove(rnd(f.len() as u64) as usize);
                        listed.push(f);
                    }
                    1 => listed.push(listed[i].clone()),
                    _ => {}
                }
            }
            let want = normalised_by_brute_force(n, &listed);
            // As a maker writes it: by dimension, each in order (repeats stay next to each other).
            let mut ascending = listed.clone();
            ascending.sort_by(|a, b| (a.len(), a).cmp(&(b.len(), b)));
            if case % 2 == 0 {
                // Dimensions interleaved; each dimension still in order.
                ascending.sort_by_key(|s| s.len() % 3);
            }
            let mut shuffled = listed.clone();
            for i in (1..shuffled.len()).rev() {
                shuffled.swap(i, rnd(i as u64 + 1) as usize);
                if rnd(2) == 0 {
                    shuffled[i].reverse();
                }
            }
            for given in [&ascending, &shuffled, &listed] {
                let c = from_listing(n, given).unwrap();
                assert_eq!((tops_of(&c), c.stats()), want, "case {case}");
                let back: Vec<Vec<u32>> = (0..c.input_count())
                    .map(|i| c.input_simplex(i).to_vec())
                    .collect();
                assert_eq!(&back, given);
            }
        }
    }

    /// One bad simplex at every position of an ascending listing (so the rows before it took
    /// the ascending path): the error names it as the per-row checks do, and of two bad ones
    /// the first.
    #[test]
    fn a_bad_simplex_anywhere_in_an_ascending_listing_is_the_error() {
        let n = 9u32;
        let good: Vec<Vec<u32>> = (0..7u32).map(|v| vec![v, v + 1, v + 2]).collect();
        let bad: [(Vec<u32>, &str); 6] = [
            (
                vec![1, 4, 9],
                "uses vertex 9, but the complex has 9 vertices",
            ),
            (
                vec![3, 10, 12],
                "uses vertex 10, but the complex has 9 vertices",
            ),
            (
                vec![12, 3, 10],
                "uses vertex 12, but the complex has 9 vertices",
            ),
            (vec![2, 5, 5], "repeats vertex 5"),
            (vec![], "simplex with no vertex"),
            (
                (0..17).collect(),
                "has dimension 16, above the supported maximum 15",
            ),
        ];
        for (b, why) in &bad {
            for at in 0..=good.len() {
                let mut listed = good.clone();
                listed.insert(at, b.clone());
                let e = from_listing(n, &listed).unwrap_err().to_string();
                assert!(
                    e.starts_with(&format!("input simplex #{at}:")) && e.contains(why),
                    "{b:?} at {at}: {e}"
                );
                // A later bad simplex does not hide it.
                listed.push(vec![0, 0]);
                assert_eq!(from_listing(n, &listed).unwrap_err().to_string(), e);
            }
        }
    }
}
