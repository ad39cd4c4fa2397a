//! The live complex's tables and stars straight from a complex's listing, when the listing holds
//! nothing but distinct top simplices (`Complex::tops_listed` reads it as is: a complex built
//! from maximal simplices, as Rips and alpha complexes are listed).
//!
//! The stars are the inversion of the top → vertex relation ([`crate::parallel::try_invert`]):
//! on several threads when the listing is large, each vertex's entries in listing order, so the
//! arrays are the ones the serial build (`LiveComplex::try_from_complex` pushing every top in
//! listing order into its vertices' stars) makes, with any thread count.
//!
//! Cost: one pass over the listing's offsets (top counts per dimension), one copying the tops
//! into their tables, and the inversion's two passes (the parallel part): O(Σ_t |t|) work, 4
//! bytes a listed simplex and 4 a vertex (plus 4 a vertex per thread when split) of scratch.

use super::{DEAD, LiveComplex, NONE, SLOT_MASK, pack};
use crate::complex::{Complex, MAX_DIMENSION, PlainTables, RawInput};
use crate::relation::StructureKind;
use crate::structures::BuildError;
use crate::structures::common::{too_large, try_copy, try_with_capacity};

use super::stars::Stars;

const K: StructureKind = StructureKind::IaStar;

/// What the live complex is built from: its top tables, live counts and stars.
pub(super) struct Parts {
    pub(super) tops: Vec<Vec<u32>>,
    pub(super) live_tops: [usize; MAX_DIMENSION + 1],
    pub(super) star: Stars,
}

impl Parts {
    /// The live complex over these parts: `n` live vertices, generation 0, no data yet. The
    /// vertex flags are allocated fallibly.
    pub(super) fn into_live(
        self,
        n: usize,
        coord_dim: usize,
        coords: Vec<f64>,
    ) -> Result<LiveComplex, BuildError> {
        Ok(LiveComplex {
            tops: self.tops,
            live_tops: self.live_tops,
            alive: crate::structures::common::try_vec(K, true, n, "vertex flags")?,
            live_vertices: n as u32,
            star: self.star,
            coord_dim,
            coords,
            epoch: 0,
            images: Vec::new(),
            data: super::data::LiveData::default(),
            dense: Default::default(),
            kept_across: None,
        })
    }
}

/// Listing entry `i`'s packed top id (`NONE` for a listed vertex), the visit the inversion
/// makes over a range of the listing.
struct TopsOfListing<'a> {
    complex: &'a Complex,
    packed: &'a [u32],
}

impl crate::parallel::Incidences for TopsOfListing<'_> {
    fn visit(&self, range: std::ops::Range<usize>, f: &mut impl FnMut(u32, u32)) {
        for i in range {
            let raw = self.packed[i];
            if raw != NONE {
                for &v in self.complex.input_simplex(i) {
                    f(raw, v);
                }
            }
        }
    }
}

/// The parts for `complex` (whose listing is its top simplices, `!tops_listed_needs_maps()`),
/// `n` vertices. Fallible as `LiveComplex::try_from_complex`.
pub(super) fn from_listing(complex: &Complex, n: usize) -> Result<Parts, BuildError> {
    let listed = complex.input_count();
    let live_tops = count_tops(complex);
    let (tops, packed) = copy_tops(complex, &live_tops)?;
    let entries: usize = (1..=MAX_DIMENSION).map(|p| (p + 1) * live_tops[p]).sum();
    if entries > u32::MAX as usize {
        return Err(too_large(K, entries * 4, "star entries (at most 2^32)"));
    }
    let inc = TopsOfListing {
        complex,
        packed: &packed,
    };
    let (off, list) = crate::parallel::try_invert(n, listed, &inc)
        .map_err(|bytes| too_large(K, bytes, "vertex stars"))?;
    drop(packed);
    let star = Stars::from_csr(K, &off, list)?;
    Ok(Parts {
        tops,
        live_tops,
        star,
    })
}

/// Top p-simplices per dimension (p ≥ 1; the slot bound is checked by [`empty_tables`]).
fn count_tops(complex: &Complex) -> [usize; MAX_DIMENSION + 1] {
    let mut per_dim = [0usize; MAX_DIMENSION + 1];
    for i in 0..complex.input_count() {
        per_dim[complex.input_simplex(i).len() - 1] += 1;
    }
    per_dim[0] = 0;
    per_dim
}

/// Empty top tables for `per_dim[p]` top p-simplices, each reserved exactly (fallibly), or
/// [`BuildError::TooLarge`] past the 2^28 slots a dimension has.
pub(super) fn empty_tables(
    per_dim: &[usize; MAX_DIMENSION + 1],
) -> Result<Vec<Vec<u32>>, BuildError> {
    check_slots(per_dim)?;
    let mut tops: Vec<Vec<u32>> = try_with_capacity(K, MAX_DIMENSION + 1, "top arrays")?;
    for (p, &count) in per_dim.iter().enumerate() {
        tops.push(try_with_capacity(
            K,
            count.saturating_mul(p + 1),
            &format!("top {p}-simplex vertices"),
        )?);
    }
    Ok(tops)
}

/// [`BuildError::TooLarge`] when a dimension holds more tops than its 2^28 slots.
fn check_slots(per_dim: &[usize; MAX_DIMENSION + 1]) -> Result<(), BuildError> {
    match per_dim
        .iter()
        .position(|&count| count > SLOT_MASK as usize + 1)
    {
        Some(p) => Err(BuildError::TooLarge {
            kind: K,
            what: format!(
                "{} top {p}-simplices (at most 2^28 per dimension)",
                per_dim[p]
            ),
        }),
        None => Ok(()),
    }
}

/// The top tables (each top in its dimension's next slot, in listing order, with its winding)
/// and every listing entry's packed top id.
fn copy_tops(
    complex: &Complex,
    per_dim: &[usize; MAX_DIMENSION + 1],
) -> Result<(Vec<Vec<u32>>, Vec<u32>), BuildError> {
    let mut tops = empty_tables(per_dim)?;
    let mut packed = try_with_capacity(K, complex.input_count(), "listing's top ids")?;
    for i in 0..complex.input_count() {
        let s = complex.input_simplex(i);
        let p = s.len() - 1;
        if p == 0 {
            packed.push(NONE);
            continue;
        }
        packed.push(pack(p, (tops[p].len() / (p + 1)) as u32));
        tops[p].extend_from_slice(s);
    }
    Ok((tops, packed))
}

/// A reader's listing as a live complex with no complex in between, when the listing is plain:
/// a declared vertex count (1 to 2^31), no attributes, coordinates of that count, and every
/// simplex 2 to 16 distinct ids below the count, none listed twice or a face of another — so
/// each is a top and gets its slot in listing order with its winding, as
/// `LiveComplex::try_from_complex` of the normalised complex would give it. `None` for any
/// other listing (the complex's path normalises it and names what is wrong).
///
/// Cost: two passes over the listing, the stars by pushes, and the absorption check (each top
/// against the tops through its vertex of smallest star: O(Σ_t d²·k)); memory the live complex
/// itself plus 4 bytes a vertex, nothing sorted and no complex kept.
pub(super) fn from_plain_listing(raw: &RawInput) -> Option<Result<LiveComplex, BuildError>> {
    let n = raw.vertex_count? as usize;
    if n == 0 || n > DEAD as usize || !raw.attributes.is_empty() {
        return None;
    }
    let (coord_dim, coord_len) = raw
        .coords
        .as_ref()
        .map_or((0, 0), |c| (c.dim, c.data.len()));
    if coord_len != n * coord_dim {
        return None;
    }
    let mut per_dim = [0usize; MAX_DIMENSION + 1];
    for i in 0..raw.simplex_count() {
        let s = raw.simplex(i);
        if s.len() < 2 || s.len() > MAX_DIMENSION + 1 {
            return None;
        }
        for (k, &v) in s.iter().enumerate() {
            if v as usize >= n || s[..k].contains(&v) {
                return None;
            }
        }
        per_dim[s.len() - 1] += 1;
    }
    match build_plain(raw, n, &per_dim) {
        Ok(live) if live.absorbs_a_top() => None,
        built => Some(built),
    }
}

/// The tables and stars of a checked plain listing.
fn build_plain(
    raw: &RawInput,
    n: usize,
    per_dim: &[usize; MAX_DIMENSION + 1],
) -> Result<LiveComplex, BuildError> {
    let mut tops = empty_tables(per_dim)?;
    let mut uses: Vec<u32> = crate::structures::common::try_vec(K, 0, n, "vertex degrees")?;
    for i in 0..raw.simplex_count() {
        let s = raw.simplex(i);
        tops[s.len() - 1].extend_from_slice(s);
        for &v in s {
            uses[v as usize] += 1;
        }
    }
    let (coord_dim, coords) = match &raw.coords {
        Some(c) => (c.dim, try_copy(K, &c.data, "coordinates")?),
        None => (0, Vec::new()),
    };
    with_stars(tops, per_dim, uses, n, coord_dim, coords)
}

/// The live complex over filled top tables (`per_dim[p]` tops in `tops[p]`, listing order) and
/// each vertex's use count: the stars reserved exactly from the counts, then filled table by
/// table, slot by slot (the order [`build_plain`] and the streamed tables share).
fn with_stars(
    tops: Vec<Vec<u32>>,
    per_dim: &[usize; MAX_DIMENSION + 1],
    uses: Vec<u32>,
    n: usize,
    coord_dim: usize,
    coords: Vec<f64>,
) -> Result<LiveComplex, BuildError> {
    let entries: usize = uses.iter().map(|&k| k as usize).sum();
    if entries > u32::MAX as usize {
        return Err(too_large(K, entries * 4, "star entries (at most 2^32)"));
    }
    let mut star = Stars::with_degrees(K, &uses)?;
    drop(uses);
    for (p, table) in tops.iter().enumerate().skip(1) {
        for (slot, s) in table.chunks_exact(p + 1).enumerate() {
            for &v in s {
                star.push(v, pack(p, slot as u32));
            }
        }
    }
    let mut live_tops = *per_dim;
    live_tops[0] = 0;
    Parts {
        tops,
        live_tops,
        star,
    }
    .into_live(n, coord_dim, coords)
}

/// A streamed plain file's tables ([`PlainTables`]: tops and coordinates moved in, not copied)
/// as a live complex; `None` when a top repeats another or is a face of another (the file must
/// be read the general way, so that a complex absorbs it). Cost: the stars' two passes and the
/// absorption check, as [`from_plain_listing`]; memory the live complex and nothing else.
pub(super) fn from_plain_tables(t: PlainTables) -> Option<Result<LiveComplex, BuildError>> {
    let n = t.vertex_count as usize;
    if n == 0 || n > DEAD as usize || t.tops.len() > MAX_DIMENSION + 1 {
        return None;
    }
    let mut per_dim = [0usize; MAX_DIMENSION + 1];
    for (p, table) in t.tops.iter().enumerate().skip(1) {
        per_dim[p] = table.len() / (p + 1);
    }
    let mut tops = t.tops;
    tops.resize_with(MAX_DIMENSION + 1, Vec::new);
    let built = check_slots(&per_dim)
        .and_then(|()| with_stars(tops, &per_dim, t.uses, n, t.coords.dim, t.coords.data));
    match built {
        Ok(live) if live.absorbs_a_top() => None,
        built => Some(built),
    }
}

impl LiveComplex {
    /// Whether some top is listed twice or is a face of another (then the listing was not plain:
    /// a complex must absorb it). Each top against the tops through its vertex of smallest star.
    fn absorbs_a_top(&self) -> bool {
        (1..=MAX_DIMENSION).any(|p| {
            self.tops[p]
                .chunks_exact(p + 1)
                .enumerate()
                .any(|(slot, s)| {
                    let me = pack(p, slot as u32);
                    let v = *s
                        .iter()
                        .min_by_key(|&&v| self.star[v as usize].len())
                        .expect("a top has vertices");
                    self.star[v as usize].iter().any(|&other| {
                        other != me
                            && super::unpack(other).0 >= p
                            && super::subset(s, self.top_raw(other))
                    })
                })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::LiveComplex;
    use crate::complex::Complex;

    /// Random complexes of 1 to 4 dimensions over a few vertices, each as drawn (faces and
    /// repeats absorbed: the listing maps are needed) and listed again as its top simplices
    /// (the direct case), and one with a face listed besides its top.
    fn complexes() -> Vec<Complex> {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut below = |k: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % k
        };
        let mut out = Vec::new();
        for _ in 0..40 {
            let n = 3 + below(12) as u32;
            let mut rows: Vec<Vec<u32>> = Vec::new();
            for _ in 0..1 + below(20) {
                let len = 1 + below(5.min(n as u64)) as usize;
                let mut s: Vec<u32> = Vec::new();
                while s.len() < len {
                    let v = below(n as u64) as u32;
                    if !s.contains(&v) {
                        s.push(v);
                    }
                }
                rows.push(s);
            }
            let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
            let c = Complex::from_simplices(n, &refs).unwrap();
            // Listed again as its top simplices only: the direct case.
            let tops: Vec<&[u32]> = c.tops_listed().map(|(_, s)| s).collect();
            out.push(Complex::from_simplices(n, &tops).unwrap());
            out.push(c);
        }
        // Drawn: the triangle 0 1 2 and its edge 1 0 listed too (the listing maps are needed).
        out.push(Complex::from_simplices(4, &[&[0, 1, 2][..], &[1, 0], &[3]]).unwrap());
        out
    }

    /// Every random complex listed as a reader would give it: a plain listing (its top
    /// simplices, each once, with coordinates) builds the same live complex as its normalised
    /// complex; a listing with a repeat, a face beside its top or a 1-vertex simplex is not
    /// plain and is left to the complex.
    #[test]
    fn a_plain_listing_builds_what_its_complex_builds() {
        let mut plain = 0;
        for c in complexes() {
            let n = c.vertex_count();
            let mut raw = crate::complex::RawInput::new();
            raw.vertex_count = Some(n);
            raw.coords = Some(crate::complex::Coords {
                dim: 2,
                data: (0..2 * n).map(f64::from).collect(),
            });
            for i in 0..c.input_count() {
                raw.push(c.input_simplex(i), 1);
            }
            let want = LiveComplex::try_from_complex(
                &Complex::from_input(raw.clone(), None, Default::default()).unwrap(),
            )
            .unwrap();
            let tops_only = !c.tops_listed_needs_maps()
                && (0..c.input_count()).all(|i| c.input_simplex(i).len() > 1);
            match LiveComplex::from_plain_listing(&raw) {
                None => assert!(!tops_only, "a listing of tops only was not taken as plain"),
                Some(built) => {
                    let built = built.unwrap();
                    assert!(
                        tops_only,
                        "a listing with repeats or faces was taken as plain"
                    );
                    built.check_invariants().unwrap();
                    assert_eq!(built.tops, want.tops);
                    assert_eq!(built.coords, want.coords);
                    for v in 0..n as usize {
                        let (mut a, mut b) = (built.star[v].to_vec(), want.star[v].to_vec());
                        a.sort_unstable();
                        b.sort_unstable();
                        assert_eq!(a, b, "star of {v}");
                    }
                    plain += 1;
                }
            }
        }
        assert!(plain >= 30, "only {plain} plain listings");
    }

    /// Random edge-and-triangle listings written as OFF files, some with a triangle repeated or
    /// an edge of a triangle listed too: streamed into tables and built, each is the live
    /// complex the general read builds (tables, coordinates, stars entry for entry), or is left
    /// to the general read exactly when that read finds it not plain.
    #[test]
    fn a_streamed_off_file_builds_what_the_general_read_builds() {
        let mut below = crate::complex::xorshift_below(0x0ff_5eed);
        let path = std::env::temp_dir().join(format!("topoplex-live-{}.off", std::process::id()));
        let (mut streamed, mut left) = (0, 0);
        for _ in 0..300 {
            let n = 8 + below(20) as u32;
            let mut text = String::new();
            let mut rows: Vec<Vec<u32>> = Vec::new();
            for _ in 0..1 + below(12) {
                let k = 2 + below(2) as usize;
                let mut s: Vec<u32> = Vec::new();
                while s.len() < k {
                    let v = below(u64::from(n)) as u32;
                    if !s.contains(&v) {
                        s.push(v);
                    }
                }
                rows.push(s);
            }
            if below(4) == 0 {
                let again = rows[below(rows.len() as u64) as usize].clone();
                rows.push(again[..2].to_vec());
            }
            text.push_str(&format!("OFF\n{n} {} 0\n", rows.len()));
            for v in 0..n {
                text.push_str(&format!("{v} {} 0.5\n", v * v));
            }
            for s in &rows {
                let ids: Vec<String> = s.iter().map(u32::to_string).collect();
                text.push_str(&format!("{} {}\n", s.len(), ids.join(" ")));
            }
            std::fs::write(&path, &text).unwrap();
            let raw = crate::io::read_path(&path).unwrap();
            let general = LiveComplex::from_plain_listing(&raw).map(Result::unwrap);
            let tables = crate::io::plain::read_off(&path).expect("drawn plain");
            match (LiveComplex::from_plain_tables(tables), general) {
                (Some(built), Some(want)) => {
                    let built = built.unwrap();
                    built.check_invariants().unwrap();
                    assert_eq!(built.tops, want.tops, "{text}");
                    assert_eq!(built.coords, want.coords, "{text}");
                    for v in 0..n as usize {
                        assert_eq!(built.star[v], want.star[v], "star of {v}: {text}");
                    }
                    streamed += 1;
                }
                (None, None) => left += 1,
                (built, want) => panic!(
                    "streamed {}, general {}: {text}",
                    built.is_some(),
                    want.is_some()
                ),
            }
        }
        let _ = std::fs::remove_file(&path);
        assert!(
            streamed > 150 && left > 20,
            "{streamed} streamed, {left} left"
        );
    }

    #[test]
    fn the_listing_build_equals_pushing_every_top() {
        let mut direct = 0;
        for c in complexes() {
            let pushed = LiveComplex::try_from_complex_by_pushes(&c).unwrap();
            let built = LiveComplex::try_from_complex(&c).unwrap();
            built.check_invariants().unwrap();
            assert_eq!(format!("{built:?}"), format!("{pushed:?}"));
            assert_eq!(
                crate::relation::Topology::storage(&built),
                crate::relation::Topology::storage(&pushed)
            );
            direct += usize::from(!c.tops_listed_needs_maps());
        }
        assert!(
            direct >= 40,
            "only {direct} complexes took the listing build"
        );
    }
}
