//! The live complex (`topoplex::live`): fixtures with exact answers, and random edit sequences
//! on random non-manifold complexes checked after every step against a set-of-simplices model,
//! a rebuild from scratch, the oracle, and a brute-force link condition.

use crate::common;

use std::collections::{BTreeMap, BTreeSet};

use proptest::prelude::*;
use topoplex::live::link::OMEGA;
use topoplex::live::{ContractMode, LiveComplex, Refusal, UndoRecord, VertexId};
use topoplex::oracle::{Oracle, check_structure};
use topoplex::testing::follows_edit;
use topoplex::{Complex, Fans, Navigate, Order, QueryError, SimplexHandle, Topology};

use common::nav::{check_around_edges, check_fans, oracle_boundary, oracle_manifold, rows_of};

/// The closure of a complex as plain sets: the reference semantics of every edit.
#[derive(Debug, Clone)]
struct Model {
    verts: BTreeSet<u32>,
    /// Every simplex of dimension ≥ 1, ascending ids.
    simplices: BTreeSet<Vec<u32>>,
}

fn sorted(s: &[u32]) -> Vec<u32> {
    let mut v = s.to_vec();
    v.sort_unstable();
    v
}

impl Model {
    fn of(live: &LiveComplex) -> Model {
        let mut m = Model {
            verts: live.vertices().map(|v| v.0).collect(),
            simplices: BTreeSet::new(),
        };
        for (_, t) in live.tops() {
            m.add(t);
        }
        m
    }

    fn add(&mut self, s: &[u32]) {
        let s = sorted(s);
        for mask in 1u32..1 << s.len() {
            if mask.count_ones() >= 2 {
                let f: Vec<u32> = (0..s.len())
                    .filter(|i| mask >> i & 1 == 1)
                    .map(|i| s[i])
                    .collect();
                self.simplices.insert(f);
            }
        }
    }

    fn contains(&self, s: &[u32]) -> bool {
        if s.len() == 1 {
            self.verts.contains(&s[0])
        } else {
            self.simplices.contains(&sorted(s))
        }
    }

    /// Top simplices of dimension ≥ 1.
    fn tops(&self) -> Vec<Vec<u32>> {
        self.simplices
            .iter()
            .filter(|s| {
                !self
                    .simplices
                    .iter()
                    .any(|t| t.len() == s.len() + 1 && s.iter().all(|v| t.contains(v)))
            })
            .cloned()
            .collect()
    }

    fn is_top(&self, s: &[u32]) -> bool {
        if s.len() == 1 {
            return self.verts.contains(&s[0]) && !self.simplices.iter().any(|t| t.contains(&s[0]));
        }
        self.tops().contains(&sorted(s))
    }

    fn remove_top(&mut self, s: &[u32]) {
        if s.len() == 1 {
            self.verts.remove(&s[0]);
            return;
        }
        let s = sorted(s);
        let rest: Vec<Vec<u32>> = self.tops().into_iter().filter(|t| *t != s).collect();
        self.simplices.clear();
        for t in rest {
            self.add(&t);
        }
    }

    fn contract(&mut self, a: u32, b: u32) {
        let old = std::mem::take(&mut self.simplices);
        for s in old {
            let mut img: Vec<u32> = s.iter().map(|&v| if v == b { a } else { v }).collect();
            img.sort_unstable();
            img.dedup();
            if img.len() >= 2 {
                self.simplices.insert(img);
            }
        }
        self.verts.remove(&b);
    }

    /// Lk(σ) without the empty simplex.
    fn link(&self, sigma: &[u32]) -> BTreeSet<Vec<u32>> {
        self.simplices
            .iter()
            .filter(|t| sigma.iter().all(|v| t.contains(v)) && t.len() > sigma.len())
            .map(|t| t.iter().copied().filter(|v| !sigma.contains(v)).collect())
            .collect()
    }

    /// The complex coned over its boundary (simplices with exactly one proper coface) from
    /// the vertex `OMEGA`.
    fn coned(&self) -> Model {
        let all: Vec<Vec<u32>> = self
            .verts
            .iter()
            .map(|&v| vec![v])
            .chain(self.simplices.iter().cloned())
            .collect();
        let mut k = self.clone();
        k.verts.insert(OMEGA);
        for f in &all {
            let cofaces = self
                .simplices
                .iter()
                .filter(|t| t.len() > f.len() && f.iter().all(|v| t.contains(v)))
                .count();
            if cofaces == 1 {
                let mut cone = f.clone();
                cone.push(OMEGA);
                k.add(&cone);
            }
        }
        k
    }

    /// Brute-force link condition: `None` when it holds, else the lowest dimension failing
    /// (`Some(usize::MAX)` for a non-edge).
    fn link_failure(&self, a: u32, b: u32) -> Option<usize> {
        if !self.contains(&[a, b]) {
            return Some(usize::MAX);
        }
        let (la, lb, lab) = (self.link(&[a]), self.link(&[b]), self.link(&[a, b]));
        la.intersection(&lb)
            .filter(|t| !lab.contains(*t))
            .map(|t| t.len() - 1)
            .min()
    }
}

/// Every p-simplex of the live complex equals the model's, for every p.
fn assert_matches_model(live: &LiveComplex, m: &Model) {
    live.validate().unwrap();
    let mut out = Vec::new();
    live.simplices(0, &mut out);
    assert_eq!(out, m.verts.iter().copied().collect::<Vec<_>>());
    for p in 1..=7 {
        out.clear();
        live.simplices(p, &mut out);
        let want: Vec<u32> = m
            .simplices
            .iter()
            .filter(|s| s.len() == p + 1)
            .flatten()
            .copied()
            .collect();
        assert_eq!(out, want, "{p}-simplices");
    }
    assert_rings_match_the_model(live, m);
}

/// `LiveComplex::rings` against the model's tops: each live vertex's row holds every vertex
/// sharing a top with it, once, beside the number of tops holding that edge; a removed vertex's
/// row is empty; `top_dims` names the tops' dimensions.
fn assert_rings_match_the_model(live: &LiveComplex, m: &Model) {
    let rings = live.rings().unwrap();
    let tops = m.tops();
    assert_eq!(rings.offsets.len(), live.vertex_slots() as usize + 1);
    assert_eq!(rings.neighbours.len(), rings.held.len());
    assert_eq!(
        rings.offsets.last().copied(),
        Some(rings.neighbours.len() as u32)
    );
    let dims = tops.iter().fold(0u16, |d, t| d | 1 << (t.len() - 1));
    assert_eq!(rings.top_dims, dims);
    for v in 0..live.vertex_slots() {
        let mut want: BTreeMap<u32, u32> = BTreeMap::new();
        if m.verts.contains(&v) {
            for t in tops.iter().filter(|t| t.contains(&v)) {
                for &w in t.iter().filter(|&&w| w != v) {
                    *want.entry(w).or_default() += 1;
                }
            }
        }
        let mut got: Vec<(u32, u32)> = rings
            .ring(v)
            .iter()
            .copied()
            .zip(rings.edge_tops(v).iter().copied())
            .collect();
        got.sort_unstable();
        assert_eq!(
            got,
            want.into_iter().collect::<Vec<_>>(),
            "ring of vertex {v}"
        );
    }
    assert!(rings.ring(live.vertex_slots()).is_empty());
}

/// A compacted copy answers every relation like the oracle on its own `to_complex()`, and a
/// rebuild from that complex has the same top simplices with the same winding.
fn assert_matches_oracle_and_rebuild(live: &LiveComplex) {
    let mut dense = live.clone();
    dense.compact();
    dense.validate().unwrap();
    let c = live.to_complex();
    check_structure(&dense, &c).unwrap();
    let rebuilt = LiveComplex::from_complex(&c);
    rebuilt.validate().unwrap();
    let oriented = |l: &LiveComplex| {
        let mut v: Vec<Vec<u32>> = l.tops().map(|(_, s)| s.to_vec()).collect();
        v.sort_by_key(|s| sorted(s));
        v
    };
    assert_eq!(oriented(&dense), oriented(&rebuilt));
    assert_eq!(dense.live_vertex_count(), rebuilt.live_vertex_count());
    for v in dense.vertices() {
        assert_eq!(dense.coords(v).unwrap(), rebuilt.coords(v).unwrap());
    }
}

/// Slots, vertices and coordinates all equal (what split ∘ contract must give back).
fn assert_same_state(x: &LiveComplex, y: &LiveComplex) {
    let tops = |l: &LiveComplex| l.tops().map(|(t, s)| (t, s.to_vec())).collect::<Vec<_>>();
    assert_eq!(tops(x), tops(y));
    assert_eq!(
        x.vertices().collect::<Vec<_>>(),
        y.vertices().collect::<Vec<_>>()
    );
    for v in x.vertices() {
        assert_eq!(x.coords(v).unwrap(), y.coords(v).unwrap());
        let mut sx: Vec<_> = x.vertex_star(v).unwrap().collect::<Vec<_>>();
        let mut sy: Vec<_> = y.vertex_star(v).unwrap().collect::<Vec<_>>();
        sx.sort_by_key(|t| (t.dim(), t.slot()));
        sy.sort_by_key(|t| (t.dim(), t.slot()));
        assert_eq!(sx, sy);
    }
}

fn with_coords(n: u32, list: &[Vec<u32>]) -> Complex {
    let mut ids = Vec::new();
    let mut offsets = vec![0];
    for s in list {
        ids.extend_from_slice(s);
        offsets.push(ids.len());
    }
    let data = (0..n).flat_map(|v| [v as f64, (v * v) as f64]).collect();
    Complex::from_arrays(
        n,
        &ids,
        &offsets,
        Some(topoplex::io::Coords { dim: 2, data }),
    )
    .unwrap()
}

/// The topology-preserving contraction of vertex `b` into `a`, `a` keeping its position.
fn preserving(live: &mut LiveComplex, a: u32, b: u32) -> Result<UndoRecord, Refusal> {
    live.contract(
        VertexId(a),
        VertexId(b),
        ContractMode::PreserveTopology,
        None,
    )
}

/// A [`common::random_input`] complex with [`with_coords`]'s coordinates (its strategy,
/// shrinking as it does).
fn placed(
    max_dim: usize,
    max_vertices: u32,
    max_simplices: usize,
) -> impl Strategy<Value = Complex> {
    common::random_input(max_dim, max_vertices, max_simplices)
        .prop_map(|(n, list)| with_coords(n, &list))
}

/// Up to four edits for [`shrink_and_check`]: (contract or remove, which, which).
fn shrinks() -> impl Strategy<Value = Vec<(bool, prop::sample::Index, prop::sample::Index)>> {
    proptest::collection::vec(
        (
            any::<bool>(),
            any::<prop::sample::Index>(),
            any::<prop::sample::Index>(),
        ),
        0..5,
    )
}

/// ```text
///   0           3        a bowtie: triangles 012 and 234 pinched at 2,
///   | \       / |        plus the wire edge 4-5 and the isolated vertex 6
///   |   2 --- ? |        (no edge 2-? : the two triangles share only vertex 2)
///   | /       \ |
///   1           4 --- 5      6
/// ```
fn bowtie() -> LiveComplex {
    LiveComplex::from_complex(&with_coords(7, &[vec![0, 1, 2], vec![2, 3, 4], vec![4, 5]]))
}

#[test]
fn bowtie_contraction_in_a_triangle_keeps_the_pinch_and_the_winding() {
    let mut live = bowtie();
    live.validate().unwrap();
    // Lk(0) = {1, 2, 12}, Lk(1) = {0, 2, 02}, Lk(01) = {2}: holds.
    live.link_condition(VertexId(0), VertexId(1)).unwrap();
    let undo = live
        .contract(
            VertexId(0),
            VertexId(1),
            ContractMode::PreserveTopology,
            Some(&[0.5, 0.5]),
        )
        .unwrap();
    live.validate().unwrap();
    let tops: Vec<Vec<u32>> = live.tops().map(|(_, s)| s.to_vec()).collect();
    assert_eq!(tops, vec![vec![4, 5], vec![0, 2], vec![2, 3, 4]]);
    assert_eq!(live.coords(VertexId(0)).unwrap(), &[0.5, 0.5]);
    assert!(!live.is_live(VertexId(1)));
    let before = bowtie();
    live.split(&undo).unwrap();
    assert_same_state(&live, &before);
}

/// ```text
///   0 ----- 1 ----- 4      triangles 0 1 2, 1 3 2 and 2 3 4 (input winding):
///    \     / \     /       contracting 3 into 1 drops 1 3 2 (through both) and
///     \   /   \   /        moves 2 3 4 to 2 1 4 in its own slot, keeping its id
///       2 ----- 3
/// ```
#[test]
fn strip_contraction_moves_a_top_in_place_and_keeps_its_id() {
    let c = with_coords(5, &[vec![0, 1, 2], vec![1, 3, 2], vec![2, 3, 4]]);
    let mut live = LiveComplex::from_complex(&c);
    let before = live.clone();
    let moved = live.tops().find(|(_, s)| s == &[2, 3, 4]).unwrap().0;
    let undo = preserving(&mut live, 1, 3).unwrap();
    live.validate().unwrap();
    assert_eq!(live.top_vertices(moved).unwrap(), &[2, 1, 4]);
    assert!(undo.inserted_tops().any(|t| t == moved));
    let tops: Vec<Vec<u32>> = live.tops().map(|(_, s)| s.to_vec()).collect();
    assert_eq!(tops, vec![vec![0, 1, 2], vec![2, 1, 4]]);
    let mut removed: Vec<Vec<u32>> = undo.removed_tops().map(<[u32]>::to_vec).collect();
    removed.sort();
    assert_eq!(removed, vec![vec![1, 3, 2], vec![2, 3, 4]]);
    live.split(&undo).unwrap();
    live.validate().unwrap();
    assert_same_state(&live, &before);
    assert_eq!(live.top_vertices(moved).unwrap(), &[2, 3, 4]);
}

/// The strip above: handles named through triangle 1 3 2 (slot 1) outlive it. Contracting 3
/// into 1 retires it (its image 1 2 lies in 0 1 2): the handle of edge 2 3 names the image 1 2,
/// those of 1 3 and 1 2 3 (through both ends) are refused; the split brings them back. Removing
/// 0 1 2 keeps edge 1 2 (in 1 3 2) but not 0 1; `compact` makes every handle stale.
#[test]
fn strip_face_handles_outlive_their_removed_top_while_the_face_lives() {
    let c = with_coords(5, &[vec![0, 1, 2], vec![1, 3, 2], vec![2, 3, 4]]);
    let mut live = LiveComplex::from_complex(&c);
    let h = |live: &LiveComplex, s: &[u32]| live.locate(s).unwrap();
    let (e12, e23, e13, e01) = (
        h(&live, &[1, 2]),
        h(&live, &[2, 3]),
        h(&live, &[1, 3]),
        h(&live, &[0, 1]),
    );
    let t123 = h(&live, &[1, 2, 3]);
    let names = |live: &LiveComplex, x: SimplexHandle| live.vertices_of(x).map(|v| v.to_vec());
    let stale = |live: &LiveComplex, x: SimplexHandle| {
        matches!(live.vertices_of(x), Err(QueryError::StaleHandle { .. }))
            && matches!(live.degree(x, 0), Err(QueryError::StaleHandle { .. }))
    };
    let undo = preserving(&mut live, 1, 3).unwrap();
    live.validate().unwrap();
    assert_eq!(names(&live, e23), Ok(vec![1, 2]));
    assert_eq!(names(&live, e12), Ok(vec![1, 2]));
    assert!(stale(&live, e13) && stale(&live, t123));
    // Navigation through the retired slot answers as through the located handle.
    let mut via_old = Vec::new();
    let mut via_new = Vec::new();
    for q in 0..=2 {
        live.related(e23, q, Order::Natural, &mut via_old).unwrap();
        live.related(h(&live, &[1, 2]), q, Order::Natural, &mut via_new)
            .unwrap();
        assert_eq!(via_old, via_new);
    }
    assert_eq!(live.top_id(e23), live.top_id(h(&live, &[1, 2])));
    live.split(&undo).unwrap();
    assert_eq!(names(&live, e23), Ok(vec![2, 3]));
    assert_eq!(names(&live, e13), Ok(vec![1, 3]));
    assert_eq!(names(&live, t123), Ok(vec![1, 2, 3]));
    live.remove_top(&[2, 1, 0]).unwrap();
    live.validate().unwrap();
    assert_eq!(names(&live, e12), Ok(vec![1, 2]));
    assert_eq!(live.degree(e12, 2), Ok(1));
    assert!(stale(&live, e01));
    assert_eq!(names(&live, h(&live, &[0])), Ok(vec![0]));
    live.compact();
    for x in [e12, e23, e13, e01, t123] {
        assert!(matches!(
            live.vertices_of(x),
            Err(QueryError::StaleGeneration { .. })
        ));
    }
}

#[test]
fn bowtie_contraction_across_the_pinch_is_refused_unless_free() {
    let mut live = bowtie();
    // 0 and 3 are not adjacent.
    assert_eq!(
        preserving(&mut live, 0, 3),
        Err(Refusal::NotAnEdge { a: 0, b: 3 })
    );
    // Edge 2-3: Lk(2) ∋ 4, Lk(3) ∋ 4, Lk(23) = {4}: holds. Edge 2-4 likewise. But contracting
    // 1 into 3 after ... keep it simple: free mode unifies 0 and 3, gluing the two triangles
    // at the edge 0-2 ~ 3-2.
    let undo = live
        .contract(VertexId(0), VertexId(3), ContractMode::Free, None)
        .unwrap();
    live.validate().unwrap();
    let mut tops: Vec<Vec<u32>> = live.tops().map(|(_, s)| sorted(s)).collect();
    tops.sort();
    assert_eq!(tops, vec![vec![0, 1, 2], vec![0, 2, 4], vec![4, 5]]);
    live.split(&undo).unwrap();
    assert_same_state(&live, &bowtie());
}

/// ```text
///   2 ----- 3      the boundary of a triangle 0 1 2 plus triangle 1 2 3:
///   | \     |      contracting edge 1-2 would pinch the empty triangle 0 1 2
///   |   \   |      into an edge: Lk(1) ∩ Lk(2) ∋ 0 but 0 ∉ Lk(12) = {3}.
///   0 --- 1 |
///         \ |
/// ```
#[test]
fn hollow_triangle_edge_fails_the_link_condition_in_dimension_0() {
    let c = Complex::from_simplices(4, &[&[0, 1], &[0, 2], &[1, 2, 3]]).unwrap();
    let mut live = LiveComplex::from_complex(&c);
    let refusal = preserving(&mut live, 1, 2).unwrap_err();
    assert_eq!(
        refusal,
        Refusal::LinkCondition {
            a: 1,
            b: 2,
            dim: 0,
            simplex: vec![0]
        }
    );
    assert_eq!(live.to_complex().top_counts(), vec![0, 2, 1]);
}

#[test]
fn bad_requests_are_refused_and_change_nothing() {
    let mut live = bowtie();
    let before = live.clone();
    assert!(matches!(
        live.insert_top(&[0, 1]),
        Err(Refusal::AlreadyPresent { .. })
    ));
    assert!(matches!(
        live.insert_top(&[0, 0, 3]),
        Err(Refusal::InvalidSimplex { .. })
    ));
    assert!(matches!(
        live.insert_top(&[0, 9]),
        Err(Refusal::UnknownVertex { vertex: 9, .. })
    ));
    assert!(matches!(
        live.insert_top(&[]),
        Err(Refusal::InvalidSimplex { .. })
    ));
    assert!(matches!(
        live.remove_top(&[0, 1]),
        Err(Refusal::NotTop { .. })
    ));
    assert!(matches!(
        live.remove_top(&[0, 3]),
        Err(Refusal::NotInComplex { .. })
    ));
    assert!(matches!(live.remove_top(&[2]), Err(Refusal::NotTop { .. })));
    assert!(matches!(
        live.contract(VertexId(0), VertexId(0), ContractMode::Free, None),
        Err(Refusal::InvalidSimplex { .. })
    ));
    assert!(matches!(
        live.contract(VertexId(0), VertexId(1), ContractMode::Free, Some(&[1.0])),
        Err(Refusal::CoordinateDimension { given: 1, dim: 2 })
    ));
    assert!(matches!(
        live.set_coords(VertexId(0), &[1.0, 2.0, 3.0]),
        Err(Refusal::CoordinateDimension { .. })
    ));
    assert_same_state(&live, &before);
    // Stale handles and undo records after compact().
    let undo = preserving(&mut live, 4, 5).unwrap();
    let t = live.tops().next().unwrap().0;
    let maps = live.compact();
    assert_eq!(maps.vertices, vec![0, 1, 2, 3, 4, u32::MAX, 5]);
    assert!(matches!(live.split(&undo), Err(Refusal::StaleHandle(_))));
    assert!(matches!(
        live.remove_top_id(t),
        Err(Refusal::StaleHandle(_))
    ));
    assert!(matches!(live.top_vertices(t), Err(Refusal::StaleHandle(_))));
    live.validate().unwrap();
}

#[test]
fn insert_absorbs_faces_and_remove_keeps_vertices() {
    let mut live = bowtie();
    // Triangle 4 5 6 makes the wire edge 4-5 and the isolated vertex 6 its faces.
    live.insert_top(&[6, 4, 5]).unwrap();
    live.validate().unwrap();
    assert_eq!(live.top_count(1), 0);
    assert_eq!(live.top_count(0), 0);
    live.remove_top(&[4, 5, 6]).unwrap();
    live.validate().unwrap();
    // Its edges go, its vertices stay: 5 and 6 are isolated, 4 is still in triangle 2 3 4.
    assert_eq!(live.top_count(0), 2);
    assert_eq!(live.count(1), 6);
    live.remove_top(&[6]).unwrap();
    assert!(!live.is_live(VertexId(6)));
    live.validate().unwrap();
}

#[derive(Debug, Clone)]
enum Op {
    Insert(Vec<u32>),
    Remove(prop::sample::Index, Vec<u32>),
    Contract(prop::sample::Index, prop::sample::Index, u8),
    Split,
}

fn op() -> impl Strategy<Value = Op> {
    let simplex = proptest::collection::vec(0u32..10, 1..=7);
    prop_oneof![
        2 => simplex.clone().prop_map(Op::Insert),
        2 => (any::<prop::sample::Index>(), simplex).prop_map(|(i, s)| Op::Remove(i, s)),
        4 => (any::<prop::sample::Index>(), any::<prop::sample::Index>(), 0u8..3)
            .prop_map(|(a, b, mode)| Op::Contract(a, b, mode)),
        2 => Just(Op::Split),
    ]
}

/// Applies one op to `live` and to the model, checking the outcome agrees. Returns the pair
/// (a, b) of a contraction of b into a (`true`) or of the split undoing one (`false`): the
/// edits that move tops in place.
fn step(
    live: &mut LiveComplex,
    m: &mut Model,
    undos: &mut Vec<(topoplex::live::UndoRecord, Model, LiveComplex)>,
    op: &Op,
) -> Option<(u32, u32, bool)> {
    let verts: Vec<u32> = m.verts.iter().copied().collect();
    match op {
        Op::Insert(s) => {
            let distinct = sorted(s).windows(2).all(|w| w[0] != w[1]);
            let known = s.iter().all(|v| m.verts.contains(v));
            match live.insert_top(s) {
                Ok(_) => {
                    assert!(distinct && known && !m.contains(s) && s.len() > 1);
                    m.add(s);
                    undos.clear();
                }
                Err(Refusal::AlreadyPresent { .. }) => assert!(m.contains(s)),
                Err(Refusal::InvalidSimplex { .. }) => assert!(!distinct),
                Err(Refusal::UnknownVertex { .. }) => assert!(!known),
                Err(e) => panic!("insert {s:?}: {e}"),
            }
        }
        Op::Remove(i, s) => {
            // Half the time a real top simplex (or isolated vertex), else the random one.
            let mut tops = m.tops();
            tops.extend(verts.iter().filter(|&&v| m.is_top(&[v])).map(|&v| vec![v]));
            let s = if !tops.is_empty() && s.len() % 2 == 0 {
                tops[i.index(tops.len())].clone()
            } else {
                s.clone()
            };
            match live.remove_top(&s) {
                Ok(()) => {
                    assert!(m.is_top(&s), "removed non-top {s:?}");
                    m.remove_top(&s);
                    undos.clear();
                }
                Err(Refusal::NotTop { .. }) => assert!(m.contains(&s) && !m.is_top(&s)),
                Err(Refusal::NotInComplex { .. }) => assert!(!m.contains(&s)),
                Err(Refusal::InvalidSimplex { .. }) => {
                    assert!(sorted(&s).windows(2).any(|w| w[0] == w[1]) || m.verts.len() == 1)
                }
                Err(Refusal::UnknownVertex { .. }) => {
                    assert!(s.iter().any(|v| !m.verts.contains(v)))
                }
                Err(e) => panic!("remove {s:?}: {e}"),
            }
        }
        Op::Contract(i, j, mode) => {
            let (a, b) = (verts[i.index(verts.len())], verts[j.index(verts.len())]);
            let brute_plain = m.link_failure(a, b);
            let brute_coned = m.coned().link_failure(a, b);
            if a != b {
                let got = live.link_condition_with_boundary(VertexId(a), VertexId(b));
                // The plain condition is checked first (its failure implies the coned one's).
                match (&got, brute_plain.or(brute_coned)) {
                    (Ok(()), None) => {}
                    (Err(Refusal::NotAnEdge { .. }), Some(usize::MAX)) => {}
                    (Err(Refusal::LinkCondition { dim, .. }), Some(d)) => assert_eq!(*dim, d),
                    other => panic!("coned link condition of {a} {b}: {other:?}"),
                }
            }
            let brute = if *mode == 2 {
                brute_coned.or(brute_plain)
            } else {
                brute_plain
            };
            let free = &(*mode == 1);
            let checked = live.link_condition(VertexId(a), VertexId(b));
            if a != b {
                match (&checked, brute_plain) {
                    (Ok(()), None) => {}
                    (Err(Refusal::NotAnEdge { .. }), Some(usize::MAX)) => {}
                    (Err(Refusal::LinkCondition { dim, simplex, .. }), Some(d)) => {
                        assert_eq!(*dim, d);
                        let (la, lb, lab) = (m.link(&[a]), m.link(&[b]), m.link(&[a, b]));
                        assert!(
                            la.contains(simplex) && lb.contains(simplex) && !lab.contains(simplex)
                        );
                    }
                    other => panic!("link condition of {a} {b}: {other:?}"),
                }
            }
            let mode = match mode {
                0 => ContractMode::PreserveTopology,
                1 => ContractMode::Free,
                _ => ContractMode::PreserveManifold,
            };
            let before = live.clone();
            match live.contract(VertexId(a), VertexId(b), mode, None) {
                Ok(undo) => {
                    assert!(a != b && (*free || brute.is_none()));
                    undos.push((undo, m.clone(), before));
                    m.contract(a, b);
                    return Some((a, b, true));
                }
                Err(e) => {
                    assert!(a == b || (!*free && brute.is_some()), "{e}");
                    assert_same_state(live, &before);
                }
            }
        }
        Op::Split => {
            if let Some((undo, old_m, old_live)) = undos.pop() {
                live.split(&undo).unwrap();
                assert_same_state(live, &old_live);
                *m = old_m;
                return Some((undo.a.0, undo.b.0, false));
            }
        }
    }
    None
}

/// Every handle operation of `live`, tombstones and all, equals the oracle on its rebuild
/// (`to_complex()`: live vertices renumbered densely, an order-keeping map); answers are
/// canonical (each equals the located handle of its vertices) and come lexicographic. Fans and
/// edge clusters equal a compacted copy's, which are checked against brute force.
fn assert_handles_match_the_oracle(live: &LiveComplex) {
    let c = live.to_complex();
    let o = Oracle::new(&c);
    let slots: Vec<u32> = live.vertices().map(|v| v.0).collect();
    let to_slots = |r: &[u32]| -> Vec<u32> { r.iter().map(|&v| slots[v as usize]).collect() };
    let to_dense = |r: &[u32]| -> Vec<u32> {
        r.iter()
            .map(|v| slots.binary_search(v).unwrap() as u32)
            .collect()
    };
    let n: &dyn Navigate = live.as_navigate().unwrap();
    let d = o.dimension();
    assert_eq!(n.dimension(), d);
    let mut buf = Vec::new();
    for p in 0..=d {
        for row in &o.levels[p] {
            let mut given = to_slots(row);
            given.reverse();
            let h = n.locate(&given).unwrap();
            assert_eq!((h.dim(), h.generation()), (p, Navigate::generation(live)));
            assert_eq!(to_dense(&n.vertices_of(h).unwrap()), *row);
            let top = n.top_id(h).unwrap();
            assert_eq!(top.is_some(), o.tops[p].contains(row), "top_id of {row:?}");
            if let Some(t) = top {
                assert_eq!(n.top(t), Ok(h));
                let mut w = n.top_as_given(t).unwrap().to_vec();
                w.sort_unstable();
                assert_eq!(to_dense(&w), *row);
            }
            for q in 0..=d {
                for order in [Order::Natural, Order::Lexicographic] {
                    n.related(h, q, order, &mut buf).unwrap();
                    let got: Vec<Vec<u32>> = rows_of(n, &buf).iter().map(|r| to_dense(r)).collect();
                    assert_eq!(got, o.relation(row, q), "R_{{{p},{q}}}({row:?})");
                }
                assert_eq!(n.degree(h, q), Ok(buf.len()));
                for &x in &buf {
                    assert_eq!(n.locate(&n.vertices_of(x).unwrap()), Ok(x), "canonical");
                }
            }
            n.star(h, Order::Lexicographic, &mut buf).unwrap();
            let star: Vec<Vec<u32>> = rows_of(n, &buf).iter().map(|r| to_dense(r)).collect();
            let want: Vec<Vec<u32>> = (p + 1..=d).flat_map(|q| o.relation(row, q)).collect();
            assert_eq!(star, want, "star of {row:?}");
            n.link(h, Order::Natural, &mut buf).unwrap();
            let link: Vec<Vec<u32>> = rows_of(n, &buf).iter().map(|r| to_dense(r)).collect();
            let mut want: Vec<Vec<u32>> = want
                .iter()
                .map(|t| t.iter().copied().filter(|x| !row.contains(x)).collect())
                .collect();
            want.sort_by_key(|r| r.len());
            assert_eq!(link, want, "link of {row:?}");
            assert_eq!(n.is_boundary(h), Ok(oracle_boundary(&o, row)));
            assert_eq!(n.is_manifold(h), Ok(oracle_manifold(&o, row)));
        }
    }
    let tops: usize = o.tops.iter().map(Vec::len).sum();
    assert_eq!(n.top_total() as usize, tops);
    assert_batches_match_the_oracle(live, &o, &to_dense);
    assert_dense_indices_match_the_oracle(live, &o, &slots);
    assert_cyclic_order_matches_a_compacted_copy(live, &c);
}

/// The index half of the handle API on the live complex equals the oracle's lexicographic ranks
/// (vertices: their slots): `handle(p, i)` names the oracle's i-th p-simplex and `index_of`
/// takes it back; `related_ids` and `related_batch` answer the oracle's relation as ranks,
/// `degree_batch` its sizes, and every relation view its rows (a removed vertex's row empty).
fn assert_dense_indices_match_the_oracle(live: &LiveComplex, o: &Oracle, slots: &[u32]) {
    let n: &dyn Navigate = live;
    let d = o.dimension();
    let rank = |row: &[u32]| oracle_rank(o, slots, row);
    let to_slots = |r: &[u32]| -> Vec<u32> { r.iter().map(|&v| slots[v as usize]).collect() };
    // Indices of dimension p: slots for vertices (removed ones included), ranks above.
    let indices = |p: usize| -> Vec<u32> {
        if p == 0 {
            (0..live.vertex_slots()).collect()
        } else {
            (0..o.levels[p].len() as u32).collect()
        }
    };
    let mut ids = Vec::new();
    for p in 0..=d {
        for (i, row) in o.levels[p].iter().enumerate() {
            let given = to_slots(row);
            let i = if p == 0 { given[0] } else { i as u32 };
            let h = n.handle(p, i).unwrap();
            assert_eq!(*n.vertices_of(h).unwrap(), given[..], "handle({p}, {i})");
            assert_eq!(n.locate(&given), Ok(h), "handle({p}, {i}) is canonical");
            assert_eq!(n.index_of(h), Ok(i));
            // A dense handle made from the index (as the C++ ranges make them) names it too.
            let dh = SimplexHandle::dense(p, i).with_generation(Navigate::generation(live));
            assert_eq!(*n.vertices_of(dh).unwrap(), given[..]);
            for q in 0..=d {
                ids.clear();
                n.related_ids(h, q, Order::Natural, &mut ids).unwrap();
                let want: Vec<u32> = o
                    .relation(row, q)
                    .iter()
                    .map(|r| rank(&to_slots(r)))
                    .collect();
                assert_eq!(ids, want, "related_ids R_{{{p},{q}}}({given:?})");
            }
        }
        let count = o.levels[p].len() as u32;
        // The count read from the built table (O(1)) is the oracle's too.
        assert_eq!(
            n.count(p),
            count as usize,
            "count({p}) with its table built"
        );
        assert!(matches!(
            n.handle(p, if p == 0 { live.vertex_slots() } else { count }),
            Err(QueryError::InvalidHandle { .. })
        ));
        let all = indices(p);
        let live_ones: Vec<u32> = all
            .iter()
            .copied()
            .filter(|&i| p > 0 || live.is_live(VertexId(i)))
            .collect();
        for q in 0..=d {
            let view = n.relation_view(p, q).unwrap().unwrap();
            assert_eq!(view.len(), all.len());
            let (mut batch, mut ends) = (Vec::new(), Vec::new());
            n.related_batch(
                p,
                &live_ones,
                q,
                Order::Lexicographic,
                &mut batch,
                &mut ends,
            )
            .unwrap();
            let mut degrees = vec![0u32; live_ones.len()];
            n.degree_batch(p, &live_ones, q, &mut degrees).unwrap();
            let mut start = 0;
            for (k, &i) in live_ones.iter().enumerate() {
                ids.clear();
                n.related_ids(n.handle(p, i).unwrap(), q, Order::Natural, &mut ids)
                    .unwrap();
                assert_eq!(view.get(i as usize), &ids[..], "view R_{{{p},{q}}} of {i}");
                assert_eq!(
                    &batch[start..ends[k]],
                    &ids[..],
                    "batch R_{{{p},{q}}} of {i}"
                );
                assert_eq!(degrees[k] as usize, ids.len());
                start = ends[k];
            }
            for &i in all.iter().filter(|i| !live_ones.contains(i)) {
                assert!(view.get(i as usize).is_empty(), "removed vertex {i}");
                assert!(matches!(
                    n.degree_batch(p, &[i], q, &mut [0]),
                    Err(QueryError::StaleHandle { .. })
                ));
            }
        }
    }
    assert!(n.handle_bytes() > 0, "tables and views are counted");
}

/// `related_handles_batch` over every simplex at once (all dimensions mixed, in an order that is
/// not by dimension) answers each like the oracle, in both orders.
fn assert_batches_match_the_oracle(
    live: &LiveComplex,
    o: &Oracle,
    to_dense: &dyn Fn(&[u32]) -> Vec<u32>,
) {
    let mut all = every_handle(live);
    all.reverse();
    let hs: Vec<SimplexHandle> = all.iter().map(|(h, _)| *h).collect();
    let (mut out, mut ends) = (Vec::new(), Vec::new());
    for q in 0..=o.dimension() {
        for order in [Order::Natural, Order::Lexicographic] {
            out.clear();
            ends.clear();
            live.related_handles_batch(&hs, q, order, &mut out, &mut ends)
                .unwrap();
            assert_eq!(ends.len(), hs.len());
            let mut start = 0;
            for ((_, row), &end) in all.iter().zip(&ends) {
                let got: Vec<Vec<u32>> = rows_of(live, &out[start..end])
                    .iter()
                    .map(|r| to_dense(r))
                    .collect();
                assert_eq!(got, o.relation(&to_dense(row), q), "batch R_q={q}({row:?})");
                start = end;
            }
        }
    }
}

fn assert_cyclic_order_matches_a_compacted_copy(live: &LiveComplex, c: &Complex) {
    let mut dense = live.clone();
    dense.compact();
    let d = c.dimension();
    if d == 2 {
        check_fans(&dense, c).unwrap();
    }
    if d == 3 {
        check_around_edges(&dense, c).unwrap();
    }
    let (mut fa, mut fb) = (Fans::default(), Fans::default());
    let same = |fa: &Fans, fb: &Fans| {
        let rows = |l: &LiveComplex, f: &Fans| {
            let live_ids: Vec<u32> = l.vertices().map(|v| v.0).collect();
            rows_of(l, &f.items)
                .into_iter()
                .map(|r| {
                    r.iter()
                        .map(|v| live_ids.binary_search(v).unwrap())
                        .collect::<Vec<_>>()
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(rows(live, fa), rows(&dense, fb));
        assert_eq!(
            (&fa.offsets, &fa.closed, &fa.oriented),
            (&fb.offsets, &fb.closed, &fb.oriented)
        );
    };
    for (k, v) in live.vertices().enumerate() {
        let r = live.fans_around(live.vertex(v).unwrap(), &mut fa);
        let s = dense.fans_around(dense.vertex(VertexId(k as u32)).unwrap(), &mut fb);
        assert_eq!(r.is_ok(), s.is_ok());
        if r.is_ok() {
            same(&fa, &fb);
        }
    }
    if d == 3 {
        for e in live.edges() {
            let h = live.locate(&e).unwrap();
            let ids: Vec<u32> = live.vertices().map(|v| v.0).collect();
            let de: Vec<u32> = e
                .iter()
                .map(|v| ids.binary_search(v).unwrap() as u32)
                .collect();
            for q in [2, 3] {
                live.around_edge(h, q, &mut fa).unwrap();
                dense
                    .around_edge(dense.locate(&de).unwrap(), q, &mut fb)
                    .unwrap();
                same(&fa, &fb);
            }
        }
    }
}

/// An old handle `h` that names `v` answers every relation as the located handle of `v` does.
fn navigates_as_located(live: &LiveComplex, h: SimplexHandle, v: &[u32]) {
    let now = live.locate(v).unwrap();
    assert_eq!(live.top_id(h), live.top_id(now), "top_id of {h}");
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for q in 0..=live.dimension() {
        live.related(h, q, Order::Natural, &mut x).unwrap();
        live.related(now, q, Order::Natural, &mut y).unwrap();
        assert_eq!(x, y, "R_q={q} of {h} (names {v:?})");
    }
}

/// Handles of every simplex, with their vertices.
fn every_handle(live: &LiveComplex) -> Vec<(SimplexHandle, Vec<u32>)> {
    let mut out = Vec::new();
    for p in 0..=live.dimension() {
        let mut rows = Vec::new();
        live.simplices(p, &mut rows);
        for r in rows.chunks_exact(p + 1) {
            out.push((live.locate(r).unwrap(), r.to_vec()));
        }
    }
    out
}

/// Contractions (link-checked or free) and removals only, so that a surface stays a 2-complex
/// and a tetrahedral complex a 3-complex: fans and edge clusters after every edit.
fn shrink_and_check(c: &Complex, ops: &[(bool, prop::sample::Index, prop::sample::Index)]) {
    let mut live = LiveComplex::from_complex(c);
    for (free, i, j) in ops {
        let vs: Vec<VertexId> = live.vertices().collect();
        let (a, b) = (vs[i.index(vs.len())], vs[j.index(vs.len())]);
        if *free && a != b {
            live.contract(a, b, ContractMode::Free, None).unwrap();
        } else if !*free {
            let top: Option<Vec<u32>> = live.tops().nth(i.index(8)).map(|(_, s)| s.to_vec());
            if let Some(s) = top {
                live.remove_top(&s).unwrap();
            }
        }
        assert_handles_match_the_oracle(&live);
        assert_writes_its_listing(&live);
    }
}

/// What the live complex writes is what its listing writes, byte for byte: for OFF of edges and
/// triangles that is the writer straight from the tables (vertex gaps renumbered as the listing
/// does), for anything else the listing itself.
fn assert_writes_its_listing(live: &LiveComplex) {
    let dir = std::env::temp_dir();
    let tag = format!("{}-{:?}", std::process::id(), std::thread::current().id());
    let tag: String = tag.chars().filter(char::is_ascii_alphanumeric).collect();
    for ext in ["off", "simplices"] {
        let (a, b) = (
            dir.join(format!("live-{tag}.{ext}")),
            dir.join(format!("listing-{tag}.{ext}")),
        );
        let got = live.write(&a, None).map(|()| std::fs::read(&a).unwrap());
        let want = topoplex::io::write::write_raw(&live.to_listing(), &b, None)
            .map(|()| std::fs::read(&b).unwrap());
        assert_eq!(got.map_err(|e| e.kind), want.map_err(|e| e.kind), "{ext}");
        let _ = (std::fs::remove_file(&a), std::fs::remove_file(&b));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]
    #[test]
    fn fans_match_brute_force_after_edits_of_random_surfaces(
        c in placed(2, 10, 14),
        ops in shrinks(),
    ) {
        shrink_and_check(&c, &ops);
    }

    #[test]
    fn edge_clusters_match_brute_force_after_edits_of_random_3_complexes(
        c in placed(3, 8, 10),
        ops in shrinks(),
    ) {
        shrink_and_check(&c, &ops);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, ..ProptestConfig::default() })]
    #[test]
    fn handles_match_the_oracle_after_every_edit_and_never_name_another_simplex(
        c in placed(6, 8, 7),
        ops in proptest::collection::vec(op(), 1..10),
    ) {
        let mut live = LiveComplex::from_complex(&c);
        let mut m = Model::of(&live);
        let mut undos = Vec::new();
        assert_handles_match_the_oracle(&live);
        // Every handle given out so far, with the simplex it last named.
        let mut known: BTreeMap<SimplexHandle, Vec<u32>> = every_handle(&live).into_iter().collect();
        for op in &ops {
            let edit = step(&mut live, &mut m, &mut undos, op);
            assert_handles_match_the_oracle(&live);
            // Every earlier handle names the simplex it named, or that simplex's image under
            // this edit (a contraction of b into a, or the split undoing one), and navigates as
            // the located handle does; or it is refused because that simplex is gone.
            for (&h, last) in known.iter_mut() {
                match live.vertices_of(h) {
                    Ok(v) => {
                        prop_assert!(*v == last[..] || follows_edit(last, &v, edit), "{h}: {last:?} -> {v:?}");
                        navigates_as_located(&live, h, &v);
                        *last = v.to_vec();
                    }
                    Err(QueryError::StaleHandle { .. }) => {
                        prop_assert!(!m.contains(last), "{h} refused, but {last:?} is there");
                        prop_assert!(live.degree(h, 0).is_err());
                    }
                    Err(e) => panic!("{h}: {e}"),
                }
            }
            for (h, v) in every_handle(&live) {
                known.entry(h).or_insert(v);
            }
        }
        let before = every_handle(&live);
        live.compact();
        for (h, _) in before.into_iter().chain(known) {
            let stale = matches!(live.vertices_of(h), Err(QueryError::StaleGeneration { .. }));
            prop_assert!(stale);
            prop_assert!(live.degree(h, 0).is_err());
        }
        assert_handles_match_the_oracle(&live);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]
    #[test]
    fn random_edit_sequences_match_the_model_the_oracle_and_a_rebuild(
        c in placed(6, 9, 8),
        ops in proptest::collection::vec(op(), 1..14),
    ) {
        let mut live = LiveComplex::from_complex(&c);
        let mut m = Model::of(&live);
        assert_matches_model(&live, &m);
        let mut undos = Vec::new();
        for (k, op) in ops.iter().enumerate() {
            step(&mut live, &mut m, &mut undos, op);
            assert_matches_model(&live, &m);
            if k % 3 == 2 || k + 1 == ops.len() {
                assert_matches_oracle_and_rebuild(&live);
                assert_writes_its_listing(&live);
            }
            // Splits that still apply undo everything back to the start.
        }
        while let Some((undo, old_m, old_live)) = undos.pop() {
            live.split(&undo).unwrap();
            assert_same_state(&live, &old_live);
            assert_matches_model(&live, &old_m);
        }
    }

    #[test]
    fn freshly_built_live_complexes_match_the_oracle(c in common::random_complex(6, 9, 8)) {
        let live = LiveComplex::from_complex(&c);
        prop_assert_eq!(live.validate(), Ok(()));
        prop_assert_eq!(check_structure(&live, &c), Ok(()));
    }
}

/// The README's C++ example, through the C ABI it wraps: a non-manifold edge and a hollow
/// triangle; each status the example relies on.
#[test]
fn readme_example_contracts_edges_on_a_non_manifold_mesh_through_the_c_abi() {
    use topoplex_ffi::*;
    let tops: [&[u32]; 5] = [&[1, 2, 3], &[1, 2, 4], &[1, 2, 5], &[0, 1], &[0, 2]];
    let c = common::c_complex(6, &tops, None);
    let (mut l, mut u) = (std::ptr::null_mut(), std::ptr::null_mut());
    let mut count = 0usize;
    // SAFETY: handles from this library, freed once.
    unsafe {
        assert_eq!(tpx_live_from_complex(c, &mut l), TpxStatus::Ok);
        // Contractions without a new position.
        let contract = move |a, b, mode, u: *mut *mut TpxUndo| {
            tpx_live_contract(l, a, b, mode, std::ptr::null(), 0, u)
        };
        assert_eq!(
            tpx_live_link_condition(l, 1, 2),
            TpxStatus::LinkConditionFails
        );
        assert_eq!(
            contract(1, 2, TPX_CONTRACT_PRESERVE_TOPOLOGY, &mut u),
            TpxStatus::LinkConditionFails
        );
        assert!(u.is_null());
        assert_eq!(
            contract(1, 3, TPX_CONTRACT_PRESERVE_TOPOLOGY, &mut u),
            TpxStatus::Ok
        );
        assert_eq!(tpx_live_top_count(l, 2, &mut count), TpxStatus::Ok);
        assert_eq!(count, 2);
        assert_eq!(tpx_live_split(l, u), TpxStatus::Ok);
        assert_eq!(tpx_live_split(l, u), TpxStatus::StaleUndo);
        assert_eq!(tpx_live_top_count(l, 2, &mut count), TpxStatus::Ok);
        assert_eq!(count, 3);
        assert_eq!(
            contract(0, 3, TPX_CONTRACT_PRESERVE_TOPOLOGY, std::ptr::null_mut()),
            TpxStatus::NotAnEdge
        );
        assert_eq!(
            contract(0, 3, TPX_CONTRACT_FREE, std::ptr::null_mut()),
            TpxStatus::Ok
        );
        assert_eq!(tpx_live_top_count(l, 2, &mut count), TpxStatus::Ok);
        assert_eq!(count, 3);
        assert_eq!(tpx_live_top_count(l, 1, &mut count), TpxStatus::Ok);
        assert_eq!(count, 0);
        assert_eq!(
            tpx_live_insert_top(l, [0u32, 1].as_ptr(), 2),
            TpxStatus::SimplexAlreadyPresent
        );
        assert_eq!(
            tpx_live_remove_top(l, [0u32, 1].as_ptr(), 2),
            TpxStatus::NotATopSimplex
        );
        assert_eq!(
            tpx_live_remove_top(l, [3u32, 1].as_ptr(), 2),
            TpxStatus::DeadVertex
        );
        assert_eq!(
            tpx_live_insert_top(l, [4u32, 4].as_ptr(), 2),
            TpxStatus::InvalidSimplex
        );
        let mut map = [0u32; 6];
        assert_eq!(
            tpx_live_compact(l, map.as_mut_ptr(), 6, &mut count),
            TpxStatus::Ok
        );
        assert_eq!(map, [0, 1, 2, u32::MAX, 3, 4]);
        assert_eq!(tpx_live_split(l, u), TpxStatus::StaleUndo);
        assert_eq!(tpx_live_validate(l), TpxStatus::Ok);
        tpx_undo_free(u);
        tpx_live_free(l);
        tpx_complex_free(c);
    }
}

/// The live complex's view as a structure (`tpx_live_structure`).
fn c_view(l: *const topoplex_ffi::TpxLive) -> *const topoplex_ffi::TpxStructure {
    let mut s = std::ptr::null();
    // SAFETY: `l` is a live handle; `s` a writable pointer.
    assert_eq!(
        unsafe { topoplex_ffi::tpx_live_structure(l, &mut s) },
        topoplex_ffi::TpxStatus::Ok
    );
    s
}

/// The vertices of a C handle of the live complex, with the status.
fn c_vertices(
    l: *const topoplex_ffi::TpxLive,
    h: &topoplex_ffi::TpxSimplex,
) -> (topoplex_ffi::TpxStatus, Vec<u32>) {
    let mut buf = [0u32; 16];
    let mut len = 0usize;
    // SAFETY: a valid structure pointer, a 16-id buffer.
    let st =
        unsafe { topoplex_ffi::tpx_simplex_vertices(c_view(l), h, buf.as_mut_ptr(), 16, &mut len) };
    (st, buf[..len].to_vec())
}

/// C handles of every simplex of the live complex, located through the C ABI.
fn c_handles(
    l: *const topoplex_ffi::TpxLive,
    rust: &LiveComplex,
) -> Vec<(topoplex_ffi::TpxSimplex, Vec<u32>)> {
    use topoplex_ffi::*;
    every_handle(rust)
        .into_iter()
        .map(|(_, row)| {
            let mut h = TpxSimplex::default();
            // SAFETY: a valid structure pointer and a simplex of row.len() ids.
            let st = unsafe { tpx_locate(c_view(l), row.as_ptr(), row.len(), &mut h) };
            assert_eq!(st, TpxStatus::Ok);
            (h, row)
        })
        .collect()
}

/// The dense index of a simplex of `live` (ids are slots) by brute force: a vertex's slot, else
/// the rank of its row among the oracle's q-simplices of the rebuilt complex (whose vertex
/// renumbering keeps order, so ranks are the same).
fn oracle_rank(o: &Oracle, slots: &[u32], row: &[u32]) -> u32 {
    if row.len() == 1 {
        return row[0];
    }
    let dense: Vec<u32> = row
        .iter()
        .map(|v| slots.binary_search(v).unwrap() as u32)
        .collect();
    o.levels[row.len() - 1].binary_search(&dense).unwrap() as u32
}

/// Every navigation function of the C ABI on the live complex's view answers what the Rust
/// API answers (as vertex rows), and the index-writing ones answer the oracle's ranks.
fn c_navigation_matches(l: *const topoplex_ffi::TpxLive, rust: &LiveComplex) {
    use topoplex_ffi::*;
    let s = c_view(l);
    let d = rust.dimension();
    let o = Oracle::new(&rust.to_complex());
    let slots: Vec<u32> = rust.vertices().map(|v| v.0).collect();
    let ranks = |rows: Vec<Vec<u32>>| -> Vec<u32> {
        rows.iter().map(|r| oracle_rank(&o, &slots, r)).collect()
    };
    let rows = |hs: &[TpxSimplex]| -> Vec<Vec<u32>> {
        hs.iter()
            .map(|h| {
                let (st, r) = c_vertices(l, h);
                assert_eq!(st, TpxStatus::Ok);
                r
            })
            .collect()
    };
    let mut buf = vec![TpxSimplex::default(); 4096];
    let mut rbuf = Vec::new();
    for (h, row) in c_handles(l, rust) {
        let rh = rust.locate(&row).unwrap();
        assert_eq!(c_vertices(l, &h), (TpxStatus::Ok, row.clone()));
        for q in 0..=d {
            let mut len = 0usize;
            // SAFETY: valid pointers; buffers of the stated lengths.
            unsafe {
                let st = tpx_related_handles(
                    s,
                    &h,
                    q as u32,
                    TPX_ORDER_NATURAL,
                    buf.as_mut_ptr(),
                    buf.len(),
                    &mut len,
                );
                assert_eq!(st, TpxStatus::Ok);
                rust.related(rh, q, Order::Natural, &mut rbuf).unwrap();
                assert_eq!(rows(&buf[..len]), rows_of(rust, &rbuf));
                let mut deg = 0usize;
                assert_eq!(tpx_degree(s, &h, q as u32, &mut deg), TpxStatus::Ok);
                assert_eq!(deg, len);
                let mut ids = [0u32; 64];
                let st = tpx_related(
                    s,
                    &h,
                    q as u32,
                    TPX_ORDER_NATURAL,
                    ids.as_mut_ptr(),
                    64,
                    &mut len,
                );
                assert_eq!(st, TpxStatus::Ok);
                assert_eq!(ids[..len], ranks(rows_of(rust, &rbuf))[..], "ids R_q={q}");
            }
        }
        for link in [0, 1] {
            let mut len = 0usize;
            // SAFETY: as above.
            let st = unsafe {
                tpx_star(
                    s,
                    &h,
                    link,
                    TPX_ORDER_LEXICOGRAPHIC,
                    buf.as_mut_ptr(),
                    buf.len(),
                    &mut len,
                )
            };
            assert_eq!(st, TpxStatus::Ok);
            if link == 0 {
                rust.star(rh, Order::Lexicographic, &mut rbuf).unwrap();
            } else {
                rust.link(rh, Order::Lexicographic, &mut rbuf).unwrap();
            }
            assert_eq!(rows(&buf[..len]), rows_of(rust, &rbuf));
        }
        for (what, want) in [(0, rust.is_boundary(rh)), (1, rust.is_manifold(rh))] {
            let mut r = 0u32;
            // SAFETY: as above.
            assert_eq!(
                unsafe { tpx_simplex_test(s, &h, what, &mut r) },
                TpxStatus::Ok
            );
            assert_eq!(r == 1, want.unwrap());
        }
        let q = match (row.len(), d) {
            (1, 2) => 0,
            (2, 3) => 3,
            _ => continue,
        };
        let mut fans = Fans::default();
        if q == 0 {
            rust.fans_around(rh, &mut fans).unwrap();
        } else {
            rust.around_edge(rh, 3, &mut fans).unwrap();
        }
        let (mut offsets, mut flags) = (vec![0u32; 65], vec![0u32; 64]);
        let (mut ni, mut ng) = (0usize, 0usize);
        // SAFETY: as above.
        unsafe {
            let st = tpx_cyclic_handles(
                s,
                &h,
                q,
                buf.as_mut_ptr(),
                buf.len(),
                offsets.as_mut_ptr(),
                flags.as_mut_ptr(),
                64,
                &mut ni,
                &mut ng,
            );
            assert_eq!(st, TpxStatus::Ok);
            assert_eq!(rows(&buf[..ni]), rows_of(rust, &fans.items));
            assert_eq!(&offsets[..=ng], &fans.offsets[..]);
            let mut items = [0u32; 64];
            let st = tpx_cyclic(
                s,
                &h,
                q,
                items.as_mut_ptr(),
                64,
                offsets.as_mut_ptr(),
                flags.as_mut_ptr(),
                64,
                &mut ni,
                &mut ng,
            );
            assert_eq!(st, TpxStatus::Ok);
            assert_eq!(items[..ni], ranks(rows_of(rust, &fans.items))[..]);
        }
    }
    c_batches_match(l, rust);
}

/// `tpx_related_handles_batch` over every simplex (dimensions mixed) equals the Rust API's
/// per-handle answers; a too-small buffer writes nothing and says the size; a handle of another
/// structure is refused with its position; `tpx_related_batch` of a vertex answers ranks.
fn c_batches_match(l: *const topoplex_ffi::TpxLive, rust: &LiveComplex) {
    use topoplex_ffi::*;
    let s = c_view(l);
    let (hs, rows): (Vec<TpxSimplex>, Vec<Vec<u32>>) = c_handles(l, rust).into_iter().rev().unzip();
    let mut buf = vec![TpxSimplex::default(); 8192];
    let mut offsets = vec![u32::MAX; hs.len() + 1];
    let mut rbuf = Vec::new();
    for q in 0..=rust.dimension() as u32 {
        let mut len = 0usize;
        // SAFETY: valid pointers; buffers of the stated lengths.
        let st = unsafe {
            tpx_related_handles_batch(
                s,
                hs.as_ptr(),
                hs.len(),
                q,
                TPX_ORDER_LEXICOGRAPHIC,
                offsets.as_mut_ptr(),
                buf.as_mut_ptr(),
                buf.len(),
                &mut len,
            )
        };
        assert_eq!(st, TpxStatus::Ok);
        assert_eq!((offsets[0], offsets[hs.len()] as usize), (0, len));
        for (k, row) in rows.iter().enumerate() {
            let got: Vec<Vec<u32>> = buf[offsets[k] as usize..offsets[k + 1] as usize]
                .iter()
                .map(|h| c_vertices(l, h).1)
                .collect();
            let rh = rust.locate(row).unwrap();
            rust.related(rh, q as usize, Order::Lexicographic, &mut rbuf)
                .unwrap();
            assert_eq!(got, rows_of(rust, &rbuf), "batch R_q={q}({row:?})");
        }
        if len > 0 {
            let before = offsets.clone();
            let mut need = 0usize;
            // SAFETY: as above, with a buffer one handle short.
            let st = unsafe {
                tpx_related_handles_batch(
                    s,
                    hs.as_ptr(),
                    hs.len(),
                    q,
                    TPX_ORDER_NATURAL,
                    offsets.as_mut_ptr(),
                    buf.as_mut_ptr(),
                    len - 1,
                    &mut need,
                )
            };
            assert_eq!((st, need), (TpxStatus::BufferTooSmall, len));
            assert_eq!(offsets, before, "offsets written on an error");
        }
        let mut ids = [0u32; 256];
        let mut one = [0u32; 2];
        // SAFETY: as above; one vertex index.
        let st = unsafe {
            tpx_related_batch(
                s,
                0,
                [rows[rows.len() - 1][0]].as_ptr(),
                1,
                q,
                TPX_ORDER_NATURAL,
                one.as_mut_ptr(),
                ids.as_mut_ptr(),
                ids.len(),
                &mut len,
            )
        };
        assert_eq!(st, TpxStatus::Ok);
        let v = rows[rows.len() - 1][0];
        let rh = rust.vertex(VertexId(v)).unwrap();
        rust.related(rh, q as usize, Order::Natural, &mut rbuf)
            .unwrap();
        let o = Oracle::new(&rust.to_complex());
        let slots: Vec<u32> = rust.vertices().map(|v| v.0).collect();
        let want: Vec<u32> = rows_of(rust, &rbuf)
            .iter()
            .map(|r| oracle_rank(&o, &slots, r))
            .collect();
        assert_eq!((&ids[..len], one[1] as usize), (&want[..], len));
    }
    let mut foreign = hs.clone();
    foreign[hs.len() / 2].owner ^= 0x5a5a;
    let mut len = 0usize;
    // SAFETY: as above.
    let st = unsafe {
        tpx_related_handles_batch(
            s,
            foreign.as_ptr(),
            foreign.len(),
            0,
            TPX_ORDER_NATURAL,
            offsets.as_mut_ptr(),
            buf.as_mut_ptr(),
            buf.len(),
            &mut len,
        )
    };
    assert_eq!(st, TpxStatus::ForeignHandle);
    // SAFETY: the message of this thread's last error, a NUL-terminated string.
    let msg = unsafe { std::ffi::CStr::from_ptr(tpx_last_error_message()) };
    assert!(
        msg.to_str()
            .unwrap()
            .contains(&format!("batch entry {}", hs.len() / 2)),
        "{msg:?}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
    /// The C ABI and the Rust API agree on the outcome of every edit of a random sequence, and
    /// the C side's frozen copy equals the Rust side's.
    #[test]
    fn c_abi_edits_agree_with_the_rust_api(
        (n, list) in common::random_input(4, 8, 6),
        ops in proptest::collection::vec((0u8..5, 0u32..9, 0u32..9, 0u32..9, 1usize..4), 1..16),
    ) {
        use topoplex_ffi::*;
        let c = common::complex_of(n, &list);
        let mut rust = LiveComplex::from_complex(&c);
        let ids: Vec<u32> = list.iter().flatten().copied().collect();
        let mut offsets = vec![0usize];
        for s in &list {
            offsets.push(offsets.last().unwrap() + s.len());
        }
        let (mut tc, mut l) = (std::ptr::null_mut(), std::ptr::null_mut());
        let mut undos = Vec::new();
        // SAFETY: arrays of the stated lengths; handles from this library, freed once.
        unsafe {
            prop_assert_eq!(tpx_complex_from_arrays(n, ids.as_ptr(), offsets.as_ptr(), list.len(), std::ptr::null(), 0, &mut tc), TpxStatus::Ok);
            prop_assert_eq!(tpx_live_from_complex(tc, &mut l), TpxStatus::Ok);
            tpx_complex_free(tc);
            let mut before = c_handles(l, &rust);
            for (kind, a, b, x, len) in ops {
                let sigma = [a, b, x][..len].to_vec();
                let mut edit = None;
                let (st, ok) = match kind {
                    0 => (tpx_live_insert_top(l, sigma.as_ptr(), len), rust.insert_top(&sigma).is_ok()),
                    1 => (tpx_live_remove_top(l, sigma.as_ptr(), len), rust.remove_top(&sigma).is_ok()),
                    2 | 3 => {
                        let (mode, m) = if kind == 2 { (TPX_CONTRACT_PRESERVE_TOPOLOGY, ContractMode::PreserveTopology) } else { (TPX_CONTRACT_FREE, ContractMode::Free) };
                        let mut u = std::ptr::null_mut();
                        let st = tpx_live_contract(l, a, b, mode, std::ptr::null(), 0, &mut u);
                        let r = rust.contract(VertexId(a), VertexId(b), m, None);
                        let ok = r.is_ok();
                        if let Ok(rec) = r { undos.push((u, rec)); edit = Some((a, b, true)); }
                        (st, ok)
                    }
                    _ => match undos.pop() {
                        Some((u, rec)) => {
                            let st = tpx_live_split(l, u);
                            tpx_undo_free(u);
                            edit = Some((rec.a.0, rec.b.0, false));
                            (st, rust.split(&rec).is_ok())
                        }
                        None => continue,
                    },
                };
                prop_assert_eq!(st == TpxStatus::Ok, ok, "status {:?}", st);
                prop_assert_eq!(tpx_live_validate(l), TpxStatus::Ok);
                // Every earlier handle names the simplex it last named or its image under this
                // edit, or is refused because that simplex is gone.
                for (h, row) in before.iter_mut() {
                    let (st, got) = c_vertices(l, h);
                    match st {
                        TpxStatus::Ok => {
                            prop_assert!(got == *row || follows_edit(row, &got, edit), "{:?} -> {:?}", row, got);
                            *row = got;
                        }
                        TpxStatus::StaleHandle => prop_assert!(!rust.contains(row), "{:?} refused", row),
                        _ => prop_assert!(false, "{:?}", st),
                    }
                }
                for (h, row) in c_handles(l, &rust) {
                    if !before.iter().any(|(k, _)| *k == h) {
                        before.push((h, row));
                    }
                }
                c_navigation_matches(l, &rust);
            }
            let old = before;
            let mut map = vec![0u32; rust.vertex_slots() as usize];
            let mut len = 0usize;
            prop_assert_eq!(tpx_live_compact(l, map.as_mut_ptr(), map.len(), &mut len), TpxStatus::Ok);
            rust.compact();
            for (h, _) in &old {
                prop_assert_eq!(c_vertices(l, h).0, TpxStatus::StaleGeneration);
            }
            c_navigation_matches(l, &rust);
            let mut frozen = std::ptr::null_mut();
            prop_assert_eq!(tpx_live_to_complex(l, &mut frozen), TpxStatus::Ok);
            let mut ig = std::ptr::null_mut();
            prop_assert_eq!(tpx_structure_build(frozen, TPX_KIND_IG, &mut ig), TpxStatus::Ok);
            let want = rust.to_complex();
            let mut nv = 0u32;
            prop_assert_eq!(tpx_complex_vertex_count(frozen, &mut nv), TpxStatus::Ok);
            prop_assert_eq!(nv, want.vertex_count());
            for p in 0..=want.dimension() {
                let mut k = 0usize;
                prop_assert_eq!(tpx_complex_top_count(frozen, p as u32, &mut k), TpxStatus::Ok);
                prop_assert_eq!(k, want.tops(p).len());
            }
            for (u, _) in undos { tpx_undo_free(u); }
            tpx_structure_free(ig);
            tpx_complex_free(frozen);
            tpx_live_free(l);
        }
    }
}

/// ```text
///   0 ---- 1 ---- 2      a strip of four triangles (a disk); edge 1-4 joins the two
///   |    / |    / |      boundary vertices 1 and 4 through the interior; coned over the
///   |  /   |  /   |      boundary, ω ∈ Lk(1) ∩ Lk(4) but ω ∉ Lk(14) (1-4 is interior)
///   3 ---- 4 ---- 5
/// ```
/// Triangles 0 1 3, 1 3 4, 1 2 4, 2 4 5: Lk(1) ∩ Lk(4) = {2, 3} = Lk(14), so contracting 1-4
/// keeps the homotopy type, but it pinches the disk at the merged vertex: refused by
/// `PreserveManifold` with ω in dimension 0.
#[test]
fn strip_interior_edge_between_boundary_vertices_is_refused_by_preserve_manifold() {
    let c = Complex::from_simplices(6, &[&[0, 1, 3], &[1, 3, 4], &[1, 2, 4], &[2, 4, 5]]).unwrap();
    let mut live = LiveComplex::from_complex(&c);
    live.link_condition(VertexId(1), VertexId(4)).unwrap();
    assert_eq!(
        live.contract(
            VertexId(1),
            VertexId(4),
            ContractMode::PreserveManifold,
            None
        ),
        Err(Refusal::LinkCondition {
            a: 1,
            b: 4,
            dim: 0,
            simplex: vec![OMEGA]
        })
    );
    // A boundary edge (0-1) passes both, and the result is still a disk.
    live.contract(
        VertexId(0),
        VertexId(1),
        ContractMode::PreserveManifold,
        None,
    )
    .unwrap();
    live.validate().unwrap();
    assert_eq!(live.top_count(2), 3);
}

/// χ = Σ (−1)^p n_p.
fn euler(live: &LiveComplex) -> i64 {
    (0..=live.dimension())
        .map(|p| if p % 2 == 0 { 1 } else { -1 } * live.count(p) as i64)
        .sum()
}

/// Connected components (over edges; isolated vertices count).
fn components(live: &LiveComplex) -> usize {
    let n = live.vertex_slots() as usize;
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], x: usize) -> usize {
        let mut x = x;
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for [a, b] in live.edges() {
        let (ra, rb) = (find(&mut parent, a as usize), find(&mut parent, b as usize));
        parent[ra] = rb;
    }
    live.vertices()
        .filter(|v| find(&mut parent, v.index()) == v.index())
        .count()
}

/// Real data (../shared/data, skipped when absent): up to 1500 link-checked contractions per
/// file keep χ and the component count; the result is valid, answers like an IG built from its
/// frozen copy, and with `PreserveManifold` every (d−1)-simplex of a pure mesh stays in at
/// most two d-simplices.
#[test]
fn real_data_contractions_keep_euler_characteristic_and_components() {
    let Some(dir) = common::shared_data() else {
        eprintln!("../shared/data is absent: skipping");
        return;
    };
    let files = [
        ("nonmanifold/fan3.obj", ContractMode::PreserveTopology),
        (
            "nonmanifold/hourglass_ico.obj",
            ContractMode::PreserveTopology,
        ),
        ("nonmanifold/moebius.obj", ContractMode::PreserveManifold),
        (
            "nonmanifold/triple_vierbein.obj",
            ContractMode::PreserveTopology,
        ),
        ("nonmanifold/truck.obj", ContractMode::PreserveTopology),
        (
            "mixed/gmsh_baffles_wire.mesh",
            ContractMode::PreserveTopology,
        ),
        (
            "tetrahedral/octopus-low.mesh",
            ContractMode::PreserveManifold,
        ),
        ("surfaces/elephant.off", ContractMode::PreserveManifold),
    ];
    for (name, mode) in files {
        let path = dir.join(name);
        let Ok(c) = Complex::from_path(&path) else {
            eprintln!("{name}: does not load, skipped");
            continue;
        };
        let mut live = LiveComplex::from_complex(&c);
        let (chi, comps) = (euler(&live), components(&live));
        let edges = live.edges();
        let step = (edges.len() / 1500).max(1);
        let mut done = 0;
        for &[a, b] in edges.iter().step_by(step) {
            if live.is_live(VertexId(a)) && live.is_live(VertexId(b)) {
                done += live.contract(VertexId(a), VertexId(b), mode, None).is_ok() as usize;
            }
        }
        live.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(done > 0, "{name}: no contraction passed");
        assert_eq!(
            euler(&live),
            chi,
            "{name}: χ changed after {done} contractions"
        );
        assert_eq!(components(&live), comps, "{name}: components changed");
        if mode == ContractMode::PreserveManifold {
            let d = live.dimension();
            let mut facets = Vec::new();
            live.simplices(d - 1, &mut facets);
            let mut out = Vec::new();
            for f in facets.chunks_exact(d) {
                live.relation(f, d, &mut out).unwrap();
                assert!(
                    out.len() <= 2 * (d + 1),
                    "{name}: {f:?} in more than two {d}-simplices"
                );
            }
        }
        let mut dense = live.clone();
        dense.compact();
        let ig = topoplex::build(topoplex::StructureKind::Ig, &live.to_complex()).unwrap();
        topoplex::oracle::compare_structures(&dense, ig.as_ref())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        eprintln!("{name}: {done} contractions, χ = {chi}, {comps} components kept");
    }
}

/// Every `tpx_live_*` export refuses NULL handles and out-pointers with NULL_ARGUMENT, and the
/// frees accept NULL.
#[test]
fn c_abi_live_functions_refuse_null() {
    use std::ptr::{null, null_mut};
    use topoplex_ffi::*;
    let mut u = 0u32;
    let mut z = 0usize;
    // SAFETY: every pointer is NULL or valid; NULL handles must be refused, not read.
    unsafe {
        tpx_live_free(null_mut());
        tpx_undo_free(null_mut());
        assert_eq!(
            tpx_live_from_complex(null(), null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_live_vertex_slots(null(), &mut u),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_live_vertex_count(null(), &mut u),
            TpxStatus::NullArgument
        );
        assert_eq!(tpx_live_dimension(null(), &mut u), TpxStatus::NullArgument);
        assert_eq!(
            tpx_live_top_count(null(), 1, &mut z),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_live_insert_top(null_mut(), [0u32, 1].as_ptr(), 2),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_live_remove_top(null_mut(), [0u32, 1].as_ptr(), 2),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_live_link_condition(null(), 0, 1),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_live_contract(null_mut(), 0, 1, 0, null(), 0, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(tpx_live_split(null_mut(), null()), TpxStatus::NullArgument);
        assert_eq!(
            tpx_live_compact(null_mut(), null_mut(), 0, &mut z),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_live_to_complex(null(), null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(tpx_live_validate(null()), TpxStatus::NullArgument);
        // A live handle with NULL out-pointers.
        let (mut c, mut l) = (null_mut(), null_mut());
        let ids = [0u32, 1];
        let offsets = [0usize, 2];
        assert_eq!(
            tpx_complex_from_arrays(2, ids.as_ptr(), offsets.as_ptr(), 1, null(), 0, &mut c),
            TpxStatus::Ok
        );
        assert_eq!(tpx_live_from_complex(c, &mut l), TpxStatus::Ok);
        assert_eq!(
            tpx_live_vertex_slots(l, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(tpx_live_insert_top(l, null(), 2), TpxStatus::NullArgument);
        assert_eq!(
            tpx_live_contract(l, 0, 1, 7, null(), 0, null_mut()),
            TpxStatus::InvalidArgument
        );
        assert_eq!(tpx_live_validate(l), TpxStatus::Ok);
        tpx_live_free(l);
        tpx_complex_free(c);
    }
}

/// One step of the coordinate property test.
#[derive(Debug, Clone)]
enum CoordOp {
    /// Set one live vertex's coordinates.
    Set(prop::sample::Index, f64, f64),
    /// Set every slot's coordinates from a seed.
    SetAll(f64),
    /// Free contraction of b into a, with a new position for a or not.
    Contract(prop::sample::Index, prop::sample::Index, Option<(f64, f64)>),
    /// Undo the last contraction still undoable.
    Split,
    Compact,
    /// A refused setting: NaN / infinity, wrong length, a removed vertex.
    Refused(prop::sample::Index, u8),
}

fn coord_op() -> impl Strategy<Value = CoordOp> {
    let x = -1e6f64..1e6;
    prop_oneof![
        3 => (any::<prop::sample::Index>(), x.clone(), x.clone()).prop_map(|(i, a, b)| CoordOp::Set(i, a, b)),
        1 => x.clone().prop_map(CoordOp::SetAll),
        3 => (any::<prop::sample::Index>(), any::<prop::sample::Index>(), proptest::option::of((x.clone(), x)))
            .prop_map(|(a, b, p)| CoordOp::Contract(a, b, p)),
        2 => Just(CoordOp::Split),
        1 => Just(CoordOp::Compact),
        2 => (any::<prop::sample::Index>(), 0u8..5).prop_map(|(i, k)| CoordOp::Refused(i, k)),
    ]
}

/// The live complex's coordinates equal `want` (per slot, `None` for a removed vertex): one at
/// a time, as the lent whole array, and through `to_complex`.
fn assert_coords(live: &LiveComplex, want: &[Option<[f64; 2]>]) {
    assert_eq!(live.vertex_slots() as usize, want.len());
    let all = live.all_coords();
    assert_eq!(all.len(), 2 * want.len());
    let mut dense = Vec::new();
    for (v, w) in want.iter().enumerate() {
        assert_eq!(live.is_live(VertexId(v as u32)), w.is_some(), "vertex {v}");
        if let Some(w) = w {
            assert_eq!(
                live.coords(VertexId(v as u32)).unwrap(),
                &w[..],
                "vertex {v}"
            );
            assert_eq!(&all[2 * v..2 * v + 2], &w[..]);
            dense.extend_from_slice(w);
        }
    }
    assert_eq!(live.to_complex().coords().unwrap().data, dense);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]
    /// Coordinates set one vertex at a time and as a whole array follow free contractions (a
    /// keeps or takes the given position, b goes), splits (a and b get back what they had
    /// before the contraction), compaction (renumbered with the vertices); refused settings
    /// change nothing; setting coordinates keeps the dense tables (not an edit of the
    /// topology); and the navigation still equals the oracle after all of it.
    #[test]
    fn coordinates_set_per_vertex_and_whole_follow_edits_and_navigation_matches_the_oracle(
        c in placed(6, 8, 7),
        ops in proptest::collection::vec(coord_op(), 1..12),
    ) {
        let mut live = LiveComplex::from_complex(&c);
        let n = c.vertex_count();
        let mut want: Vec<Option<[f64; 2]>> =
            (0..n).map(|v| Some([v as f64, (v * v) as f64])).collect();
        // Undo records with the coordinates of a and b before their contraction.
        let mut undos: Vec<(topoplex::live::UndoRecord, [f64; 2], [f64; 2])> = Vec::new();
        assert_coords(&live, &want);
        for op in &ops {
            let alive: Vec<u32> = live.vertices().map(|v| v.0).collect();
            match op {
                CoordOp::Set(i, x, y) => {
                    let v = alive[i.index(alive.len())];
                    live.relation_view(0, 0).unwrap();
                    let ring = live.rings().unwrap().neighbours.as_ptr();
                    let bytes = Navigate::handle_bytes(&live);
                    live.set_coords(VertexId(v), &[*x, *y]).unwrap();
                    want[v as usize] = Some([*x, *y]);
                    prop_assert_eq!(Navigate::handle_bytes(&live), bytes);
                    // The rings are kept, not rebuilt.
                    prop_assert_eq!(live.rings().unwrap().neighbours.as_ptr(), ring);
                }
                CoordOp::SetAll(seed) => {
                    let data: Vec<f64> = (0..2 * want.len()).map(|k| seed + k as f64).collect();
                    live.set_all_coords(&data).unwrap();
                    for (v, w) in want.iter_mut().enumerate() {
                        if w.is_some() {
                            *w = Some([data[2 * v], data[2 * v + 1]]);
                        }
                    }
                }
                CoordOp::Contract(i, j, pos) => {
                    let (a, b) = (alive[i.index(alive.len())], alive[j.index(alive.len())]);
                    if a == b {
                        continue;
                    }
                    let (wa, wb) = (want[a as usize].unwrap(), want[b as usize].unwrap());
                    let p = pos.map(|(x, y)| [x, y]);
                    let undo = live
                        .contract(VertexId(a), VertexId(b), ContractMode::Free, p.as_ref().map(|p| &p[..]))
                        .unwrap();
                    undos.push((undo, wa, wb));
                    want[b as usize] = None;
                    if let Some(p) = p {
                        want[a as usize] = Some(p);
                    }
                }
                CoordOp::Split => {
                    if let Some((undo, wa, wb)) = undos.pop() {
                        let before = live.clone();
                        match live.split(&undo) {
                            Ok(()) => {
                                want[undo.a.index()] = Some(wa);
                                want[undo.b.index()] = Some(wb);
                            }
                            Err(Refusal::StaleHandle(_)) => assert_same_state(&live, &before),
                            Err(e) => panic!("split: {e}"),
                        }
                    }
                }
                CoordOp::Compact => {
                    let maps = live.compact();
                    let mut next = vec![None; live.vertex_slots() as usize];
                    for (old, &new) in maps.vertices.iter().enumerate() {
                        if new != u32::MAX {
                            next[new as usize] = want[old];
                        }
                    }
                    want = next;
                    undos.clear();
                }
                CoordOp::Refused(i, kind) => {
                    let v = alive[i.index(alive.len())];
                    let before = live.clone();
                    let dead = (0..live.vertex_slots()).find(|&u| !live.is_live(VertexId(u)));
                    let r = match kind {
                        0 => live.set_coords(VertexId(v), &[f64::NAN, 0.0]),
                        1 => live.set_coords(VertexId(v), &[0.0]),
                        2 => {
                            let mut data = vec![0.0; 2 * want.len()];
                            let k = i.index(data.len());
                            data[k] = f64::INFINITY;
                            live.set_all_coords(&data)
                        }
                        3 => live.set_all_coords(&vec![0.0; 2 * want.len() + 1]),
                        _ => live.set_coords(VertexId(dead.unwrap_or(live.vertex_slots())), &[0.0, 0.0]),
                    };
                    match (kind, r) {
                        (0 | 2, Err(Refusal::NonFiniteCoordinate { .. })) => {}
                        (1 | 3, Err(Refusal::CoordinateDimension { .. })) => {}
                        (4, Err(Refusal::UnknownVertex { .. })) => {}
                        (k, other) => panic!("refusal {k}: {other:?}"),
                    }
                    assert_same_state(&live, &before);
                }
            }
            assert_coords(&live, &want);
        }
        assert_handles_match_the_oracle(&live);
    }
}

/// Moving a vertex of a contraction's a after the contraction: the split puts back a's
/// position from before it (the undo record holds it), and keeps a third vertex's new one.
#[test]
fn split_restores_the_contracted_pair_positions_and_keeps_other_moves() {
    let mut live = bowtie();
    let undo = live
        .contract(
            VertexId(0),
            VertexId(1),
            ContractMode::PreserveTopology,
            Some(&[9.0, 9.0]),
        )
        .unwrap();
    live.set_coords(VertexId(0), &[7.0, 7.0]).unwrap();
    live.set_coords(VertexId(3), &[5.0, 5.0]).unwrap();
    assert!(matches!(
        live.set_coords(VertexId(1), &[1.0, 1.0]),
        Err(Refusal::UnknownVertex { vertex: 1, .. })
    ));
    live.split(&undo).unwrap();
    assert_eq!(live.coords(VertexId(0)).unwrap(), &[0.0, 0.0]);
    assert_eq!(live.coords(VertexId(1)).unwrap(), &[1.0, 1.0]);
    assert_eq!(live.coords(VertexId(3)).unwrap(), &[5.0, 5.0]);
    let err = live.set_all_coords(&[0.0; 14 - 1]).unwrap_err();
    assert_eq!(err, Refusal::CoordinateDimension { given: 13, dim: 14 });
    let mut data = [0.0; 14];
    data[7] = f64::NEG_INFINITY;
    assert_eq!(
        live.set_all_coords(&data).unwrap_err().to_string(),
        "coordinate 1 of vertex 3 is -inf, not a finite number"
    );
    assert_eq!(live.coords(VertexId(3)).unwrap(), &[5.0, 5.0]);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The link condition, plain and on the complex coned over its boundary, against the
    /// brute-force model on complexes where vertex 0 has a large star (a cone over 64 to 150
    /// random triangles and edges on 120 vertices, beside random small simplices), so that the
    /// test on an edge at 0 reads St(0) only where the common vertices are: every edge at 0,
    /// both ways, gets the model's answer (and a named simplex in both links, not in Lk(ab)).
    #[test]
    fn link_condition_around_a_large_star_matches_the_model(
        base in prop::collection::vec(prop::collection::btree_set(1u32..120, 2..=3), 64..150),
        others in prop::collection::vec(prop::collection::btree_set(1u32..120, 2..=4), 0..20),
    ) {
        let mut simplices: Vec<Vec<u32>> = base
            .iter()
            .map(|f| std::iter::once(0).chain(f.iter().copied()).collect())
            .collect();
        simplices.extend(others.into_iter().map(|t| t.into_iter().collect::<Vec<u32>>()));
        let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
        let Ok(c) = Complex::from_simplices(120, &refs) else {
            return Ok(());
        };
        let live = LiveComplex::from_complex(&c);
        let m = Model::of(&live);
        let coned = m.coned();
        for b in 1..120 {
            for (x, y) in [(0, b), (b, 0)] {
                let plain = m.link_failure(x, y);
                match (live.link_condition(VertexId(x), VertexId(y)), plain) {
                    (Ok(()), None) => {}
                    (Err(Refusal::NotAnEdge { .. }), Some(usize::MAX)) => {}
                    (Err(Refusal::LinkCondition { dim, simplex, .. }), Some(d)) => {
                        prop_assert_eq!(dim, d);
                        let (la, lb, lab) = (m.link(&[x]), m.link(&[y]), m.link(&[x, y]));
                        prop_assert!(
                            la.contains(&simplex) && lb.contains(&simplex) && !lab.contains(&simplex)
                        );
                    }
                    other => panic!("link condition of {x} {y}: {other:?}"),
                }
                let with_boundary = plain.or(coned.link_failure(x, y));
                match (live.link_condition_with_boundary(VertexId(x), VertexId(y)), with_boundary) {
                    (Ok(()), None) => {}
                    (Err(Refusal::NotAnEdge { .. }), Some(usize::MAX)) => {}
                    (Err(Refusal::LinkCondition { dim, .. }), Some(d)) => prop_assert_eq!(dim, d),
                    other => panic!("coned link condition of {x} {y}: {other:?}"),
                }
            }
        }
    }
}
