//! What the four 2D structures (TS, PE, LE, DE) share: the domain check, the radial order of the
//! triangles around an edge, the connected components of a vertex's star, and the relation
//! retrieval written once against `TriTopo` (crate-internal).
//!
//! # Slots
//! Triangle `t` (ascending vertices `v0 < v1 < v2`, triangles numbered in lexicographic order) is
//! oriented `v0 → v1 → v2`. Its *slot* `3t + i` is the oriented edge from `vi` to `v(i+1 mod 3)`;
//! slot `3t + i` is also the *corner* of `vi` in `t` (the slot that starts at `vi`). PE's
//! partial-edges, LE's edge-uses and DE's directed edges of triangle `t` are its three slots.
//!
//! # Radial order around an edge {a, b}, a < b
//! With 3D coordinates (or 2D ones, taken as z = 0): counter-clockwise by the angle of each
//! triangle's third vertex around the axis a → b, i.e. right-handed about a → b, which is
//! counter-clockwise for a viewer at b looking down the edge towards a. Angles are measured from
//! the triangle whose third vertex has the smallest id, which is therefore first; equal angles
//! (degenerate triangles, or a flat 2D drawing) are ordered by third-vertex id. Without usable
//! coordinates (none, another dimension, non-finite values, a zero-length edge): ascending
//! third-vertex id, which is also ascending triangle id.

use crate::mapped::Arr;
use std::f64::consts::TAU;

use rustc_hash::FxHashSet;

use super::common::{IdSet, Scratch, try_iota, try_order, try_push, try_table, try_vec};
use super::nav::{Fast, Visit, with_scratch};
use super::{BuildError, to_u32};
use crate::complex::Coords;
use crate::complex::table::id_bits;
use crate::complex::{Complex, SimplexTable};
use crate::relation::handle::SimplexHandle;
use crate::relation::{QueryError, StructureKind};

pub(crate) const NONE: u32 = u32::MAX;

/// The top simplices of a complex of dimension ≤ 2.
pub(crate) struct Parts {
    pub n: u32,
    pub dim: usize,
    /// All triangles (each is top in a 2-complex), ascending lexicographic.
    pub tris: SimplexTable,
    /// Wire edges (top 1-simplices), ascending lexicographic.
    pub wires: SimplexTable,
    /// Isolated vertices (top 0-simplices).
    pub isolated: usize,
}

/// Splits a complex into triangles and wire edges, refusing dimension 3 and above.
pub(crate) fn parts(kind: StructureKind, complex: &Complex) -> Result<Parts, BuildError> {
    let d = complex.dimension();
    if d > 2 {
        // The lexicographically first tetrahedron is the first four vertices of some top simplex.
        let first = (3..=d)
            .flat_map(|p| complex.tops(p).iter().map(|s| s[..4].to_vec()))
            .min()
            .expect("a complex of dimension > 2 has a top simplex of dimension > 2");
        return Err(BuildError::Unsupported {
            kind,
            reason: format!(
                "tetrahedron {} (the complex has dimension {d}; {kind} encodes triangle complexes \
                 of dimension at most 2)",
                show(&first)
            ),
        });
    }
    let tris = if d == 2 {
        try_table(kind, complex.tops(2))?
    } else {
        SimplexTable::empty(3)
    };
    let wires = if d >= 1 {
        try_table(kind, complex.tops(1))?
    } else {
        SimplexTable::empty(2)
    };
    to_u32(kind, 3 * tris.len() + 2 * wires.len(), "edge uses")?;
    Ok(Parts {
        n: complex.vertex_count(),
        dim: d,
        isolated: complex.tops(0).len(),
        tris,
        wires,
    })
}

pub(crate) fn show(ids: &[u32]) -> String {
    let v: Vec<String> = ids.iter().map(|i| i.to_string()).collect();
    format!("[{}]", v.join(" "))
}

/// Ends of slot `s` of a triangle with vertices `tri` in slot order.
#[inline]
pub(crate) fn slot_ends(tri: [u32; 3], s: u32) -> (u32, u32) {
    let i = (s % 3) as usize;
    (tri[i], tri[(i + 1) % 3])
}

#[inline]
fn unordered(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

pub(crate) fn row3(t: &SimplexTable, i: u32) -> [u32; 3] {
    let r = t.get(i as usize);
    [r[0], r[1], r[2]]
}

/// The radial cycles of the triangle slots, and the triangle edges they define.
pub(crate) struct Radial {
    /// Next and previous slot around the same edge in radial order (cyclic; a slot alone on its
    /// edge is its own neighbour).
    pub next: Vec<u32>,
    pub prev: Vec<u32>,
    /// Distinct edges of the triangles, ascending lexicographic.
    pub edges: Vec<[u32; 2]>,
    /// Edge of each slot (index into `edges`).
    pub slot_edge: Vec<u32>,
    /// Radially first slot of each edge.
    pub edge_first: Vec<u32>,
}

/// Groups the slots by edge (radix sort, O(n2)) and orders each group radially.
pub(crate) fn radial(
    kind: StructureKind,
    tris: &SimplexTable,
    coords: Option<&Coords>,
) -> Result<Radial, BuildError> {
    let m = tris.len() * 3;
    let key = |s: u32| {
        let t = row3(tris, s / 3);
        let (a, b) = slot_ends(t, s);
        let (a, b) = unordered(a, b);
        (a, b, t[((s % 3 + 2) % 3) as usize])
    };
    // Sorting by the edge alone, ties by slot, gives the same order as by (edge, third vertex):
    // the triangles on edge {a, b} ascend lexicographically exactly as their third vertices do,
    // and each has one slot on the edge. Two ids leave room in the 64-bit key for the slot, so
    // the radix sort stays on its one-word path at 10^6 triangles.
    let bits = id_bits(tris.as_flat().iter().copied().max().unwrap_or(0));
    let order = try_order(kind, m, 2 * bits, |s| {
        let (a, b, _) = key(s);
        (a as u64) << bits | b as u64
    })?;
    let mut order = match order {
        Some(order) => order,
        None => {
            let mut order = try_iota(kind, m, "edge slots")?;
            order.sort_unstable_by_key(|&s| key(s));
            order
        }
    };
    let mut r = Radial {
        next: try_vec(kind, NONE, m, "radial links")?,
        prev: try_vec(kind, NONE, m, "radial links")?,
        edges: Vec::new(),
        slot_edge: try_vec(kind, NONE, m, "slot edges")?,
        edge_first: Vec::new(),
    };
    let mut g = 0;
    while g < m {
        let (a, b, _) = key(order[g]);
        let mut h = g + 1;
        while h < m && {
            let (x, y, _) = key(order[h]);
            (x, y) == (a, b)
        } {
            h += 1;
        }
        let group = &mut order[g..h];
        if let (3.., Some(c)) = (group.len(), coords) {
            sort_by_angle(group, a, b, c, |s| key(s).2);
        }
        let e = r.edges.len() as u32;
        try_push(kind, &mut r.edges, [a, b], "edges")?;
        try_push(kind, &mut r.edge_first, group[0], "edges")?;
        let k = group.len();
        for j in 0..k {
            let s = group[j] as usize;
            r.next[s] = group[(j + 1) % k];
            r.prev[s] = group[(j + k - 1) % k];
            r.slot_edge[s] = e;
        }
        g = h;
    }
    Ok(r)
}

fn point(c: &Coords, v: u32) -> Option<[f64; 3]> {
    let i = v as usize * c.dim;
    let p = match c.dim {
        3 => [c.data[i], c.data[i + 1], c.data[i + 2]],
        2 => [c.data[i], c.data[i + 1], 0.0],
        _ => return None,
    };
    p.iter().all(|x| x.is_finite()).then_some(p)
}

/// The storage of a radial structure: `integers` as counted, `arrays` (its `u32` arrays) as
/// the bytes they hold room for.
pub(crate) fn storage_of<'a>(
    integers: u64,
    arrays: impl IntoIterator<Item = &'a Arr<u32>>,
) -> crate::relation::Storage {
    crate::relation::Storage {
        integers,
        bits: 0,
        bytes: arrays.into_iter().map(|a| a.capacity() as u64 * 4).sum(),
    }
}

/// The 3-vector kit (also used by `nmia`).
pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Reorders `group` (slots on edge {a, b}, in ascending third-vertex order) counter-clockwise
/// about a → b; leaves it unchanged when the geometry cannot define angles.
fn sort_by_angle(group: &mut [u32], a: u32, b: u32, c: &Coords, third: impl Fn(u32) -> u32) {
    let (Some(pa), Some(pb)) = (point(c, a), point(c, b)) else {
        return;
    };
    let d = sub(pb, pa);
    let dd = dot(d, d);
    if dd <= 0.0 || !dd.is_finite() {
        return;
    }
    let perp = |v: u32| -> Option<[f64; 3]> {
        let w = sub(point(c, v)?, pa);
        let k = dot(w, d) / dd;
        Some([w[0] - k * d[0], w[1] - k * d[1], w[2] - k * d[2]])
    };
    let Some(u) = perp(third(group[0])) else {
        return;
    };
    if dot(u, u) <= 0.0 {
        return;
    }
    let v = cross(d, u);
    let len_d = dd.sqrt();
    let mut keyed = Vec::with_capacity(group.len());
    for (j, &s) in group.iter().enumerate() {
        let Some(w) = perp(third(s)) else {
            return;
        };
        let mut ang = if j == 0 {
            0.0
        } else {
            (dot(w, v) / len_d).atan2(dot(w, u))
        };
        if ang < 0.0 {
            ang += TAU;
        }
        // Rounding can put a triangle coplanar with the reference just below 2π.
        if ang >= TAU - 1e-12 {
            ang = 0.0;
        }
        keyed.push((ang, third(s), s));
    }
    keyed.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    for (g, k) in group.iter_mut().zip(keyed) {
        *g = k.2;
    }
}

fn find_root(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[x as usize];
        parent[x as usize] = parent[p as usize];
        x = p;
    }
    x
}

/// Corner (slot starting at `v`) of `v` in triangle `t` with vertices `tri`.
#[inline]
pub(crate) fn corner(t: u32, tri: [u32; 3], v: u32) -> u32 {
    3 * t
        + tri
            .iter()
            .position(|&x| x == v)
            .expect("vertex of the triangle") as u32
}

/// For each corner, the smallest corner of its star component (triangles at the corner's vertex
/// joined through edges at that vertex). Union-find over corners: near O(n2); on several
/// threads for many triangles (a shared union–find whose roots are the smallest corners too, so
/// the same labels), else serial.
pub(crate) fn corner_roots(
    n_tris: u32,
    tri: impl Fn(u32) -> [u32; 3] + Sync + Send,
    radial_next: impl Fn(u32) -> u32 + Sync + Send,
) -> Vec<u32> {
    let m = 3 * n_tris;
    // Corner pairs of slot s and the next slot around its edge, for each end of the edge.
    let joins = |s: u32, join: &mut dyn FnMut(u32, u32)| {
        let t = s / 3;
        let tv = tri(t);
        let (a, b) = slot_ends(tv, s);
        let s2 = radial_next(s);
        let t2 = s2 / 3;
        let tv2 = tri(t2);
        for v in [a, b] {
            join(corner(t, tv, v), corner(t2, tv2, v));
        }
    };
    if crate::parallel::splits(m as usize)
        && let Ok(uf) = crate::parallel::SharedUnionFind::try_new(m as usize)
    {
        crate::parallel::map_ranges(m as usize, |range| {
            for s in range {
                joins(s as u32, &mut |x, y| uf.union(x, y));
            }
        });
        return uf.into_roots();
    }
    let mut parent: Vec<u32> = (0..m).collect();
    for s in 0..m {
        joins(s, &mut |x, y| {
            let (x, y) = (find_root(&mut parent, x), find_root(&mut parent, y));
            parent[x.max(y) as usize] = x.min(y);
        });
    }
    for c in 0..m {
        parent[c as usize] = find_root(&mut parent, c);
    }
    parent
}

/// Whether [`vertex_components`] and [`wire_lists`] can have their memory (roots, doubling
/// lists of components and the CSR arrays: under 8 bytes a vertex, 72 a triangle, 16 a wire),
/// else `TooLarge`: their arrays are made infallibly, so the build checks first.
pub(crate) fn components_headroom(
    kind: StructureKind,
    n: u32,
    tris: usize,
    wires: usize,
) -> Result<(), BuildError> {
    let bytes = (n as usize)
        .saturating_mul(8)
        .saturating_add(tris.saturating_mul(72))
        .saturating_add(wires.saturating_mul(16));
    crate::parallel::headroom_for(tris, bytes)
        .map_err(|bytes| super::common::too_large(kind, bytes, "the star components"))
}

/// The star components of each vertex: CSR offsets over the vertices and, per component, its
/// smallest corner (ascending within a vertex). O(n2 + n0).
pub(crate) fn vertex_components(
    n: u32,
    n_tris: u32,
    tri: impl Fn(u32) -> [u32; 3] + Sync + Send,
    radial_next: impl Fn(u32) -> u32 + Sync + Send,
) -> (Vec<u32>, Vec<u32>) {
    let roots = corner_roots(n_tris, &tri, radial_next);
    let mut off = vec![0u32; n as usize + 1];
    let mut reps = Vec::new();
    let mut owner = Vec::new();
    for c in 0..3 * n_tris {
        if roots[c as usize] == c {
            let v = tri(c / 3)[(c % 3) as usize];
            off[v as usize + 1] += 1;
            reps.push(c);
            owner.push(v);
        }
    }
    for i in 0..n as usize {
        off[i + 1] += off[i];
    }
    let mut fill = off.clone();
    let mut list = vec![0u32; reps.len()];
    for (c, v) in reps.into_iter().zip(owner) {
        list[fill[v as usize] as usize] = c;
        fill[v as usize] += 1;
    }
    (off, list)
}

/// Both directions of each wire edge in CSR form: each vertex's wire neighbours, ascending.
pub(crate) fn wire_lists(n: u32, wires: &SimplexTable) -> (Vec<u32>, Vec<u32>) {
    let mut off = vec![0u32; n as usize + 1];
    for w in wires.iter() {
        off[w[0] as usize + 1] += 1;
        off[w[1] as usize + 1] += 1;
    }
    for i in 0..n as usize {
        off[i + 1] += off[i];
    }
    let mut fill = off.clone();
    let mut list = vec![0u32; 2 * wires.len()];
    // In table order, a vertex's lower neighbours (rows (w, v)) arrive ascending, all before its
    // higher ones (rows (v, w)), which also arrive ascending: each list comes out sorted.
    for w in wires.iter() {
        for (x, y) in [(w[0], w[1]), (w[1], w[0])] {
            list[fill[x as usize] as usize] = y;
            fill[x as usize] += 1;
        }
    }
    (off, list)
}

/// Finds an edge among the triangles' slots by binary search: the triangle table is sorted by
/// (v0, v1); two permutations sort it by (v0, v2) and by (v1, v2). 2·n2 integers, a locating
/// index the survey does not count (the papers address an edge by an entity of the structure;
/// the relation API addresses it by its vertices).
#[derive(Debug, Clone)]
pub(crate) struct EdgeLocator {
    by02: Arr<u32>,
    by12: Arr<u32>,
}

impl EdgeLocator {
    /// Both permutations by radix sort (ties by triangle, as a sort by (key, triangle) would
    /// give), on [`crate::parallel::threads`] threads when large: O(n2).
    /// `TooLarge` (for `kind`) when the orders cannot be had.
    pub fn build(kind: StructureKind, tris: &SimplexTable) -> Result<EdgeLocator, BuildError> {
        let n2 = tris.len();
        let bits = id_bits(tris.as_flat().iter().copied().max().unwrap_or(0));
        let by = |i: usize, j: usize| -> Result<Vec<u32>, BuildError> {
            let key = |t: u32| {
                let r = tris.get(t as usize);
                (r[i], r[j], t)
            };
            let order = try_order(kind, n2, 2 * bits, |t| {
                let (a, b, _) = key(t);
                (a as u64) << bits | b as u64
            })?;
            Ok(match order {
                Some(order) => order,
                None => {
                    let mut order = try_iota(kind, n2, "triangles")?;
                    order.sort_unstable_by_key(|&t| key(t));
                    order
                }
            })
        };
        Ok(EdgeLocator {
            by02: by(0, 2)?.into(),
            by12: by(1, 2)?.into(),
        })
    }

    /// A slot on edge {a, b} (a < b), or `None`: three binary searches, O(log n2).
    pub fn find(&self, n2: u32, tri: impl Fn(u32) -> [u32; 3], a: u32, b: u32) -> Option<u32> {
        let k = partition(n2, |t| {
            let r = tri(t);
            (r[0], r[1]) < (a, b)
        });
        if k < n2 && tri(k)[..2] == [a, b] {
            return Some(3 * k);
        }
        for (perm, i, j, slot) in [(&self.by02, 0, 2, 2), (&self.by12, 1, 2, 1)] {
            let k = partition(n2, |x| {
                let r = tri(perm[x as usize]);
                (r[i], r[j]) < (a, b)
            });
            if k < n2 {
                let t = perm[k as usize];
                let r = tri(t);
                if (r[i], r[j]) == (a, b) {
                    return Some(3 * t + slot);
                }
            }
        }
        None
    }

    pub fn heap_bytes(&self) -> usize {
        (self.by02.capacity() + self.by12.capacity()) * 4
    }

    /// Each permutation sorted and complete.
    pub fn validate(&self, n2: u32, tri: impl Fn(u32) -> [u32; 3]) -> Result<(), String> {
        for (perm, i, j) in [(&self.by02, 0, 2), (&self.by12, 1, 2)] {
            if perm.len() != n2 as usize {
                return Err("edge locator has the wrong length".into());
            }
            let mut seen = vec![false; perm.len()];
            for (k, &t) in perm.iter().enumerate() {
                if t as usize >= seen.len() || std::mem::replace(&mut seen[t as usize], true) {
                    return Err(format!("edge locator is not a permutation at {k}"));
                }
                if k > 0 {
                    let (x, y) = (tri(perm[k - 1]), tri(t));
                    if (x[i], x[j]) > (y[i], y[j]) {
                        return Err(format!("edge locator unsorted at {k}"));
                    }
                }
            }
        }
        Ok(())
    }
}

/// First index in `0..n` where `below` turns false (`below` must be monotone).
pub(crate) fn partition(n: u32, below: impl Fn(u32) -> bool) -> u32 {
    crate::complex::table::partition_point(0..n as usize, |i| below(i as u32)) as u32
}

/// Where a located edge lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[doc(hidden)]
pub enum EdgeAt {
    /// A slot on the edge (a triangle edge).
    Slot(u32),
    /// A wire edge (no triangle).
    Wire,
}

/// The next slot of a radial walk, counting its steps: a cycle longer than there are slots
/// (only a saved file's arrays altered behind their checksums make one) stops the walk with a
/// panic, which the CLI and the C ABI report as such, instead of looping and growing the answer
/// without bound.
#[inline]
fn next_in_cycle<T: TriTopo + ?Sized>(topo: &T, r: u32, steps: &mut u32) -> u32 {
    *steps += 1;
    assert!(
        *steps <= topo.n_tris().saturating_mul(3),
        "radial cycle does not close (inconsistent arrays)"
    );
    topo.radial_next(r)
}

/// The primitive operations each 2D structure provides; every relation is derived from them.
#[doc(hidden)]
pub trait TriTopo {
    fn n_tris(&self) -> u32;
    /// Vertices of triangle `t` in slot order (ascending).
    fn tri(&self, t: u32) -> [u32; 3];
    /// Next slot around the same edge in radial order (itself when alone), O(1).
    fn radial_next(&self, s: u32) -> u32;
    /// Appends every corner at `v` (one slot starting at `v` per triangle incident at `v`),
    /// each once: O(triangles at v).
    fn star_corners(&self, v: u32, out: &mut Vec<u32>);
    /// Appends the other end of every wire edge at `v`: O(wire edges at v).
    fn wire_neighbours(&self, v: u32, out: &mut Vec<u32>);
    /// The triangle with ascending vertices `t`; by default a binary search, for triangles
    /// numbered in lexicographic order: O(log triangles).
    fn find_tri(&self, t: &[u32]) -> Option<u32> {
        let n = self.n_tris();
        let k = partition(n, |f| self.tri(f)[..] < *t);
        (k < n && self.tri(k)[..] == *t).then_some(k)
    }
    /// Edge {a, b}, a < b.
    fn find_edge(&self, a: u32, b: u32) -> Option<EdgeAt>;
}

/// The corners at `v` reached from one corner per star component (`reps`), walking each radial
/// cycle around an edge at `v` once: O(triangles at v + Σ radial cycles at v) = O(triangles at v).
pub(crate) fn walk_star<T: TriTopo + ?Sized>(
    topo: &T,
    v: u32,
    reps: impl Iterator<Item = u32>,
    out: &mut Vec<u32>,
) {
    let start = out.len();
    let mut seen_tri: IdSet = IdSet::default();
    let mut seen_edge: IdSet = IdSet::default();
    for c in reps {
        if seen_tri.insert(c / 3) {
            out.push(c);
        }
    }
    let mut k = start;
    while k < out.len() {
        let c = out[k];
        k += 1;
        let t = c / 3;
        let tv = topo.tri(t);
        // The two slots of t on edges at v: the one leaving v and the one arriving at v.
        for s in [c, 3 * t + (c % 3 + 2) % 3] {
            let (x, y) = slot_ends(tv, s);
            let other = if x == v { y } else { x };
            if !seen_edge.insert(other) {
                continue;
            }
            let (mut r, mut steps) = (topo.radial_next(s), 0u32);
            while r != s {
                let t2 = r / 3;
                if seen_tri.insert(t2) {
                    out.push(corner(t2, topo.tri(t2), v));
                }
                r = next_in_cycle(topo, r, &mut steps);
            }
        }
    }
}

/// `NavBase` for a 2-complex structure with a `nav: NavIndex` field, whose fast paths are
/// [`fast_visit`] and [`fast_into`] (TS, PE, LE and DE share them); items after `;` are the
/// structure's own further methods.
macro_rules! nav_base {
    ($t:ty $(; $($extra:tt)*)?) => {
        impl super::nav::NavBase for $t {
            fn nav(&self) -> &super::nav::NavIndex {
                &self.nav
            }

            fn fast_visit(
                &self,
                h: crate::relation::handle::SimplexHandle,
                sigma: &[u32],
                q: usize,
                visit: crate::structures::nav::Visit<'_>,
            ) -> crate::structures::nav::Fast {
                super::radial::fast_visit(self, h, sigma, q, visit)
            }

            fn has_fast(&self, p: usize, q: usize) -> bool {
                super::radial::has_fast(p, q)
            }

            fn fast_into(&self, p: usize, i: u32, q: usize, ids: &mut Vec<u32>) {
                super::radial::fast_into(self, p, i, q, ids)
            }

            $($($extra)*)?
        }
    };
}
pub(crate) use nav_base;

/// The handle walks the primitives give directly (triangle `t` is dense 2-simplex `t`):
/// R_{0,0}, R_{0,2}: O(star of v); R_{1,2}: the radial cycle; R_{2,0}: O(1); R_{2,2}: the three
/// radial cycles. Other relations: `None` (the generic path). `sigma` is the checked handle `h`'s vertices.
pub(crate) fn fast_visit<T: TriTopo + ?Sized>(
    topo: &T,
    h: SimplexHandle,
    sigma: &[u32],
    q: usize,
    visit: Visit<'_>,
) -> Fast {
    match (sigma.len() - 1, q) {
        (0, 0) => with_scratch(|buf| {
            neighbours(topo, sigma[0], buf);
            buf.iter().for_each(|&x| visit(SimplexHandle::dense(0, x)));
        }),
        (0, 2) => with_scratch(|buf| {
            topo.star_corners(sigma[0], buf);
            buf.iter()
                .for_each(|&c| visit(SimplexHandle::dense(2, c / 3)));
        }),
        (1, 2) => {
            // A wire edge has no triangle (and a checked handle always finds its edge).
            if let Some(EdgeAt::Slot(s)) = topo.find_edge(sigma[0], sigma[1]) {
                with_scratch(|slots| {
                    cycle(topo, s, slots);
                    slots
                        .iter()
                        .for_each(|&r| visit(SimplexHandle::dense(2, r / 3)));
                });
            }
        }
        (2, 0) => sigma
            .iter()
            .for_each(|&x| visit(SimplexHandle::dense(0, x))),
        (2, 2) => {
            let t = h.index();
            for s in 3 * t..3 * t + 3 {
                let (mut r, mut steps) = (topo.radial_next(s), 0u32);
                while r != s {
                    visit(SimplexHandle::dense(2, r / 3));
                    r = next_in_cycle(topo, r, &mut steps);
                }
            }
        }
        _ => return None,
    }
    Some(Ok(()))
}

/// Whether [`fast_into`] answers R_{p,q}: VV (R_{0,0}), VF (R_{0,2}) and FF (R_{2,2}).
pub(crate) fn has_fast(p: usize, q: usize) -> bool {
    matches!((p, q), (0, 0) | (0, 2) | (2, 2))
}

/// [`fast_visit`]'s answers for VV, VF and FF appended to `ids` as dense indices, in the same
/// order, with no call per answer; `i` is a checked index of a p-simplex.
pub(crate) fn fast_into<T: TriTopo + ?Sized>(
    topo: &T,
    p: usize,
    i: u32,
    q: usize,
    ids: &mut Vec<u32>,
) {
    match (p, q) {
        (0, 0) => neighbours(topo, i, ids),
        (0, 2) => {
            let start = ids.len();
            topo.star_corners(i, ids);
            ids[start..].iter_mut().for_each(|c| *c /= 3);
        }
        (2, 2) => {
            for s in 3 * i..3 * i + 3 {
                let (mut r, mut steps) = (topo.radial_next(s), 0u32);
                while r != s {
                    ids.push(r / 3);
                    r = next_in_cycle(topo, r, &mut steps);
                }
            }
        }
        _ => debug_assert!(false, "no fast walk for R_{{{p},{q}}}"),
    }
}

/// Distinct vertices adjacent to `v` (through triangles or wire edges), in discovery order:
/// O(star of v).
fn neighbours<T: TriTopo + ?Sized>(topo: &T, v: u32, out: &mut Vec<u32>) {
    // The corners go to the end of `out` first and are dropped at the end: no allocation.
    let start = out.len();
    topo.star_corners(v, out);
    let k = out.len() - start;
    if k <= 32 {
        // A mesh vertex's few neighbours: deduplicated against what is already written, which
        // costs less than setting up a set.
        for i in start..start + k {
            for w in topo.tri(out[i] / 3) {
                if w != v && !out[start + k..].contains(&w) {
                    out.push(w);
                }
            }
        }
    } else {
        let mut seen: IdSet = IdSet::default();
        for i in start..start + k {
            for w in topo.tri(out[i] / 3) {
                if w != v && seen.insert(w) {
                    out.push(w);
                }
            }
        }
    }
    out.drain(start..start + k);
    // A wire neighbour shares no triangle with v.
    topo.wire_neighbours(v, out);
}

/// The slots of the radial cycle through `s`, rotated to start at the radially first one (the
/// smallest triangle id): O(k) for an edge in k triangles.
pub(crate) fn cycle<T: TriTopo + ?Sized>(topo: &T, s: u32, out: &mut Vec<u32>) {
    let start = out.len();
    let (mut r, mut steps) = (s, 0u32);
    loop {
        out.push(r);
        r = next_in_cycle(topo, r, &mut steps);
        if r == s {
            break;
        }
    }
    let first = (start..out.len()).min_by_key(|&i| out[i]).unwrap();
    out[start..].rotate_left(first - start);
}

fn push_edge(out: &mut Vec<u32>, a: u32, b: u32) {
    let (a, b) = unordered(a, b);
    out.push(a);
    out.push(b);
}

/// Whether ascending `sigma` is a simplex (vertex ids already range-checked).
pub(crate) fn contains<T: TriTopo + ?Sized>(topo: &T, sigma: &[u32]) -> bool {
    match sigma.len() {
        1 => true,
        2 => topo.find_edge(sigma[0], sigma[1]).is_some(),
        3 => topo.find_tri(sigma).is_some(),
        _ => false,
    }
}

/// R_{p,q}(σ) for ascending σ, answered from the primitives. Costs (after locating σ):
/// R_{0,q}: O(star of v); R_{1,0}: O(1); R_{1,1}: O(star of a + star of b); R_{1,2}: O(k);
/// R_{2,0}, R_{2,1}: O(1); R_{2,2}: O(Σ of the radial cycles of its three edges).
pub(crate) fn query<T: TriTopo + ?Sized>(
    topo: &T,
    sigma: &[u32],
    q: usize,
    out: &mut Vec<u32>,
) -> Result<(), QueryError> {
    let missing = || QueryError::NotInComplex {
        simplex: sigma.to_vec(),
    };
    match sigma.len() {
        1 => {
            let v = sigma[0];
            match q {
                0 => neighbours(topo, v, out),
                // Both expand in place, from the back, what the walk left at the end of `out`:
                // row i lands at or after entry i, so no entry is overwritten before it is read.
                1 => {
                    let start = out.len();
                    neighbours(topo, v, out);
                    let k = out.len() - start;
                    out.resize(start + 2 * k, 0);
                    for i in (0..k).rev() {
                        let (a, b) = unordered(v, out[start + i]);
                        out[start + 2 * i] = a;
                        out[start + 2 * i + 1] = b;
                    }
                }
                _ => {
                    let start = out.len();
                    topo.star_corners(v, out);
                    let k = out.len() - start;
                    out.resize(start + 3 * k, 0);
                    for i in (0..k).rev() {
                        let t = topo.tri(out[start + i] / 3);
                        out[start + 3 * i..start + 3 * i + 3].copy_from_slice(&t);
                    }
                }
            }
        }
        2 => {
            let (a, b) = (sigma[0], sigma[1]);
            let at = topo.find_edge(a, b).ok_or_else(missing)?;
            match q {
                0 => out.extend_from_slice(&[a, b]),
                1 => {
                    let mut nb = Scratch::<Vec<u32>>::take();
                    for (x, y) in [(a, b), (b, a)] {
                        nb.clear();
                        neighbours(topo, x, &mut nb);
                        for &w in nb.iter() {
                            if w != y {
                                push_edge(out, x, w);
                            }
                        }
                    }
                }
                _ => {
                    if let EdgeAt::Slot(s) = at {
                        let mut slots = Scratch::<Vec<u32>>::take();
                        cycle(topo, s, &mut slots);
                        for &r in slots.iter() {
                            out.extend_from_slice(&topo.tri(r / 3));
                        }
                    }
                }
            }
        }
        3 => {
            let t = topo.find_tri(sigma).ok_or_else(missing)?;
            let tv = topo.tri(t);
            match q {
                0 => out.extend_from_slice(&tv),
                1 => {
                    for i in 0..3 {
                        let (x, y) = slot_ends(tv, 3 * t + i);
                        push_edge(out, x, y);
                    }
                }
                _ => {
                    for i in 0..3 {
                        let s = 3 * t + i;
                        let (mut r, mut steps) = (topo.radial_next(s), 0u32);
                        while r != s {
                            out.extend_from_slice(&topo.tri(r / 3));
                            r = next_in_cycle(topo, r, &mut steps);
                        }
                    }
                }
            }
        }
        _ => return Err(missing()),
    }
    Ok(())
}

/// Every p-simplex in ascending lexicographic order. Edges: each vertex's higher neighbours,
/// sorted: O(Σ_v star(v) log).
pub(crate) fn simplices<T: TriTopo + ?Sized>(topo: &T, n: u32, p: usize, out: &mut Vec<u32>) {
    match p {
        0 => out.extend(0..n),
        1 => {
            let mut nb = Vec::new();
            for v in 0..n {
                nb.clear();
                neighbours(topo, v, &mut nb);
                nb.retain(|&w| w > v);
                nb.sort_unstable();
                for &w in &nb {
                    out.extend_from_slice(&[v, w]);
                }
            }
        }
        2 => {
            for t in 0..topo.n_tris() {
                out.extend_from_slice(&topo.tri(t));
            }
        }
        _ => {}
    }
}

/// Checks shared by all four: triangles strictly ascending in lexicographic order, every radial
/// cycle closes within `n2` steps and stays on one edge, and no two slots on one edge lie in
/// different cycles (each edge's triangles are counted against the cycle length).
pub(crate) fn validate_common<T: TriTopo + ?Sized>(topo: &T, n: u32) -> Result<(), String> {
    let n2 = topo.n_tris();
    let mut on_edge: rustc_hash::FxHashMap<(u32, u32), u32> = Default::default();
    for t in 0..n2 {
        let tv = topo.tri(t);
        if !(tv[0] < tv[1] && tv[1] < tv[2]) || tv[2] >= n {
            return Err(format!(
                "triangle {t} {} is not ascending in range",
                show(&tv)
            ));
        }
        if t > 0 && topo.tri(t - 1) >= tv {
            return Err(format!("triangles not in lexicographic order at {t}"));
        }
        for i in 0..3 {
            let (a, b) = slot_ends(tv, 3 * t + i);
            *on_edge.entry(unordered(a, b)).or_default() += 1;
        }
    }
    for s in 0..3 * n2 {
        let e = {
            let (a, b) = slot_ends(topo.tri(s / 3), s);
            unordered(a, b)
        };
        let mut r = s;
        let mut len = 0u32;
        loop {
            r = topo.radial_next(r);
            len += 1;
            if r >= 3 * n2 || len > n2 {
                return Err(format!("radial cycle of slot {s} does not close"));
            }
            let (a, b) = slot_ends(topo.tri(r / 3), r);
            if unordered(a, b) != e {
                return Err(format!(
                    "radial cycle of slot {s} on edge [{} {}] reaches edge [{a} {b}]",
                    e.0, e.1
                ));
            }
            if r == s {
                break;
            }
        }
        if len != on_edge[&e] {
            return Err(format!(
                "edge [{} {}] is in {} triangles but its radial cycle has {len}",
                e.0, e.1, on_edge[&e]
            ));
        }
    }
    Ok(())
}

/// Checks one stored representative per star component of every vertex (`reps(v)` as corners):
/// each at `v`, no two in one component, as many as the star has components. O(n2 + n0).
pub(crate) fn validate_components<T: TriTopo + Sync + ?Sized>(
    topo: &T,
    n: u32,
    reps: impl Fn(u32) -> Vec<u32>,
) -> Result<(), String> {
    let roots = corner_roots(topo.n_tris(), |t| topo.tri(t), |s| topo.radial_next(s));
    let (off, _) = vertex_components(n, topo.n_tris(), |t| topo.tri(t), |s| topo.radial_next(s));
    for v in 0..n {
        let stored = reps(v);
        let expect = (off[v as usize + 1] - off[v as usize]) as usize;
        if stored.len() != expect {
            return Err(format!(
                "vertex {v} stores {} star components, its star has {expect}",
                stored.len()
            ));
        }
        let mut seen = FxHashSet::default();
        for &c in &stored {
            if c >= 3 * topo.n_tris() || topo.tri(c / 3)[(c % 3) as usize] != v {
                return Err(format!("vertex {v} stores corner {c}, which is not at it"));
            }
            if !seen.insert(roots[c as usize]) {
                return Err(format!(
                    "vertex {v}: two stored corners are in one star component"
                ));
            }
        }
    }
    Ok(())
}

/// Numbers all edges (triangle edges and wire edges, disjoint sets) in lexicographic order:
/// returns the id of each triangle edge and of each wire edge. O(n1).
pub(crate) fn merge_edges(tri_edges: &[[u32; 2]], wires: &SimplexTable) -> (Vec<u32>, Vec<u32>) {
    let (mut te, mut we) = (
        Vec::with_capacity(tri_edges.len()),
        Vec::with_capacity(wires.len()),
    );
    let (mut i, mut j) = (0, 0);
    let mut id = 0u32;
    while i < tri_edges.len() || j < wires.len() {
        let take_tri =
            j == wires.len() || (i < tri_edges.len() && tri_edges[i][..] < *wires.get(j));
        if take_tri {
            te.push(id);
            i += 1;
        } else {
            we.push(id);
            j += 1;
        }
        id += 1;
    }
    (te, we)
}

crate::persist_fields!(EdgeLocator { by02, by12 });
