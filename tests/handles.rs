//! Handles and navigation (issue 13): every handle operation of every structure equals the
//! vertex-id relation API and the brute-force oracle, on fixtures, random non-manifold complexes
//! up to dimension 6 and the real data; fans and edge clusters are checked against brute force.

mod common;

use std::collections::BTreeSet;

use proptest::prelude::*;
use topoplex::handle::HandleForm;
use topoplex::oracle::Oracle;
use topoplex::structures::{BuildError, build};
use topoplex::{
    Complex, Fans, Navigate, Order, QueryError, SimplexHandle, StructureKind, TopId, Topology,
    VertexId, fixtures,
};

fn buildable(c: &Complex) -> Vec<Box<dyn Topology>> {
    let mut out = Vec::new();
    for kind in StructureKind::ALL {
        match build(kind, c) {
            Ok(s) => {
                s.validate()
                    .unwrap_or_else(|e| panic!("{kind}: validate: {e}"));
                out.push(s);
            }
            Err(BuildError::Unsupported { .. }) => {}
            Err(e) => panic!("{kind}: {e}"),
        }
    }
    out
}

fn nav(s: &dyn Topology) -> &dyn Navigate {
    s.as_navigate().expect("every structure navigates")
}

fn rows_of(n: &dyn Navigate, hs: &[SimplexHandle]) -> Vec<Vec<u32>> {
    hs.iter()
        .map(|&h| n.vertices_of(h).unwrap().to_vec())
        .collect()
}

fn sorted(mut v: Vec<Vec<u32>>) -> Vec<Vec<u32>> {
    v.sort();
    v
}

/// Brute-force "on the boundary": σ or a simplex of its star is a non-top simplex with exactly
/// one coface one dimension up.
fn oracle_boundary(o: &Oracle, s: &[u32]) -> bool {
    let d = o.dimension();
    let mut star = vec![s.to_vec()];
    for q in s.len()..=d {
        star.extend(o.relation(s, q));
    }
    star.iter().any(|t| {
        let p = t.len() - 1;
        p < d && !o.tops[p].contains(t) && o.relation(t, p + 1).len() == 1
    })
}

/// Brute-force "manifold": the link's top part is pure and a connected pseudo-manifold (BFS).
fn oracle_manifold(o: &Oracle, s: &[u32]) -> bool {
    let d = o.dimension();
    let mut link: Vec<Vec<u32>> = Vec::new();
    for q in s.len() - 1..=d {
        for t in o.relation(s, q) {
            if o.tops[q].contains(&t) && t.len() > s.len() {
                link.push(t.into_iter().filter(|x| !s.contains(x)).collect());
            }
        }
    }
    if link.is_empty() {
        return true;
    }
    let k = link[0].len();
    if link.iter().any(|r| r.len() != k) {
        return false;
    }
    if k == 1 {
        return link.len() <= 2;
    }
    let shares = |a: &Vec<u32>, b: &Vec<u32>| a.iter().filter(|x| b.contains(x)).count() == k - 1;
    for a in &link {
        for skip in 0..k {
            let f: Vec<u32> = (0..k).filter(|&i| i != skip).map(|i| a[i]).collect();
            let n = link
                .iter()
                .filter(|b| f.iter().all(|x| b.contains(x)))
                .count();
            if n > 2 {
                return false;
            }
        }
    }
    let mut seen = vec![false; link.len()];
    let mut stack = vec![0];
    seen[0] = true;
    while let Some(i) = stack.pop() {
        for j in 0..link.len() {
            if !seen[j] && shares(&link[i], &link[j]) {
                seen[j] = true;
                stack.push(j);
            }
        }
    }
    seen.iter().all(|&x| x)
}

/// Every handle operation of `s` against the oracle and the vertex-id relation API.
fn check_handles(s: &dyn Topology, c: &Complex, deep: bool) -> Result<(), String> {
    let n = nav(s);
    let o = Oracle::new(c);
    let d = s.dimension();
    let kind = s.kind();
    let mut buf = Vec::new();
    let mut rel = Vec::new();
    for p in 0..=d {
        let mut all = Vec::new();
        s.simplices(p, &mut all);
        for (i, row) in all.chunks_exact(p + 1).enumerate() {
            let h = n
                .handle(p, i as u32)
                .map_err(|e| format!("{kind}: handle: {e}"))?;
            let v = n.vertices_of(h).unwrap();
            if &*v != row {
                return Err(format!("{kind}: {h}: vertices {v:?}, expected {row:?}"));
            }
            let mut rev = row.to_vec();
            rev.reverse();
            if n.locate(&rev) != Ok(h) {
                return Err(format!(
                    "{kind}: locate {rev:?} gave {:?}, not {h}",
                    n.locate(&rev)
                ));
            }
            let is_top = o.tops[p].contains(&row.to_vec());
            if n.top_id(h).unwrap().is_some() != is_top {
                return Err(format!("{kind}: {h} {row:?}: top_id wrong (top: {is_top})"));
            }
            for q in 0..=d {
                n.related(h, q, Order::Natural, &mut buf).unwrap();
                let got = rows_of(n, &buf);
                s.relation(row, q, &mut rel).unwrap();
                let api: Vec<Vec<u32>> = rel.chunks_exact(q + 1).map(<[u32]>::to_vec).collect();
                if sorted(got.clone()) != sorted(api.clone()) {
                    return Err(format!(
                        "{kind}: R_{{{p},{q}}}({row:?}) by handle {got:?}, by ids {api:?}"
                    ));
                }
                if sorted(got.clone()) != sorted(o.relation(row, q)) {
                    return Err(format!(
                        "{kind}: R_{{{p},{q}}}({row:?}) differs from the oracle"
                    ));
                }
                if n.degree(h, q).unwrap() != got.len() {
                    return Err(format!("{kind}: degree({row:?}, {q})"));
                }
                n.related(h, q, Order::Lexicographic, &mut buf).unwrap();
                if rows_of(n, &buf) != sorted(got) {
                    return Err(format!("{kind}: lexicographic R_{{{p},{q}}}({row:?})"));
                }
            }
            if deep {
                check_star_and_link(n, &o, h, row)?;
            }
        }
    }
    check_batches(n)?;
    check_tops(n, c)
}

/// `related_batch` over every p-simplex is the per-handle answers concatenated, in both orders
/// (TS, PE, LE, DE answer VV, VF and FF in their own loop), and refuses an index out of range.
fn check_batches(n: &dyn Navigate) -> Result<(), String> {
    let d = n.dimension();
    let kind = n.kind();
    let mut buf = Vec::new();
    for p in 0..=d {
        let all: Vec<u32> = (0..n.count(p) as u32).collect();
        for q in 0..=d {
            for order in [Order::Natural, Order::Lexicographic] {
                let (mut ids, mut ends) = (Vec::new(), Vec::new());
                n.related_batch(p, &all, q, order, &mut ids, &mut ends)
                    .map_err(|e| format!("{kind}: batch R_{{{p},{q}}}: {e}"))?;
                let (mut want, mut want_ends) = (Vec::new(), Vec::new());
                for &i in &all {
                    n.related(n.handle(p, i).unwrap(), q, order, &mut buf)
                        .unwrap();
                    want.extend(buf.iter().map(|h| h.index()));
                    want_ends.push(want.len());
                }
                if (&ids, &ends) != (&want, &want_ends) {
                    return Err(format!(
                        "{kind}: batch R_{{{p},{q}}} ({order:?}) {ids:?} {ends:?}, per handle {want:?} {want_ends:?}"
                    ));
                }
            }
            let past = [n.count(p) as u32];
            let (mut ids, mut ends) = (Vec::new(), Vec::new());
            if n.related_batch(p, &past, q, Order::Natural, &mut ids, &mut ends)
                .is_ok()
            {
                return Err(format!(
                    "{kind}: batch R_{{{p},{q}}} took index {}",
                    past[0]
                ));
            }
        }
    }
    Ok(())
}

fn check_star_and_link(
    n: &dyn Navigate,
    o: &Oracle,
    h: SimplexHandle,
    row: &[u32],
) -> Result<(), String> {
    let kind = n.kind();
    let mut buf = Vec::new();
    n.star(h, Order::Lexicographic, &mut buf).unwrap();
    let star = rows_of(n, &buf);
    let mut expect = Vec::new();
    for q in row.len()..=o.dimension() {
        expect.extend(sorted(o.relation(row, q)));
    }
    if star != expect {
        return Err(format!(
            "{kind}: star({row:?}) {star:?}, expected {expect:?}"
        ));
    }
    n.link(h, Order::Natural, &mut buf).unwrap();
    let link: BTreeSet<Vec<u32>> = rows_of(n, &buf).into_iter().collect();
    let want: BTreeSet<Vec<u32>> = expect
        .iter()
        .map(|t| t.iter().copied().filter(|x| !row.contains(x)).collect())
        .collect();
    if link != want || buf.len() != want.len() {
        return Err(format!("{kind}: link({row:?})"));
    }
    if n.is_boundary(h).unwrap() != oracle_boundary(o, row) {
        return Err(format!("{kind}: is_boundary({row:?})"));
    }
    if n.is_manifold(h).unwrap() != oracle_manifold(o, row) {
        return Err(format!("{kind}: is_manifold({row:?})"));
    }
    Ok(())
}

/// TopIds number the complex's top simplices dimension ascending, lexicographic within; each
/// comes back as given (winding) and normalised.
fn check_tops(n: &dyn Navigate, c: &Complex) -> Result<(), String> {
    let kind = n.kind();
    let mut t = 0u32;
    for p in 0..=c.dimension() {
        for (i, row) in c.tops(p).iter().enumerate() {
            let h = n
                .top(TopId(t))
                .map_err(|e| format!("{kind}: top {t}: {e}"))?;
            if &*n.vertices_of(h).unwrap() != row || n.top_id(h).unwrap() != Some(TopId(t)) {
                return Err(format!("{kind}: top {t} is not {row:?}"));
            }
            if &*n.top_as_given(TopId(t)).unwrap() != c.top_oriented(p, i as u32) {
                return Err(format!("{kind}: top {t} not as given"));
            }
            t += 1;
        }
    }
    if n.top_total() != t || n.top(TopId(t)).is_ok() {
        return Err(format!("{kind}: top_total {} != {t}", n.top_total()));
    }
    Ok(())
}

/// Fans around every vertex of a 2-complex: a partition of the star into the components joined
/// through edges with exactly two triangles, each a chain in order, closed and oriented flags
/// right, oriented fans counter-clockwise by the winding.
fn check_fans(n: &dyn Navigate, c: &Complex) -> Result<(), String> {
    let kind = n.kind();
    let o = Oracle::new(c);
    let mut fans = Fans::default();
    for v in 0..c.vertex_count() {
        let h = n.vertex(VertexId(v)).unwrap();
        n.fans_around(h, &mut fans)
            .map_err(|e| format!("{kind}: {e}"))?;
        let tris = o.relation(&[v], 2);
        let got: BTreeSet<Vec<u32>> = rows_of(n, &fans.items).into_iter().collect();
        if got.len() != tris.len() || fans.items.len() != tris.len() {
            return Err(format!("{kind}: fans at {v} do not cover its star once"));
        }
        // Edges at v with exactly two triangles join them.
        let two = |a: &[u32], b: &[u32]| {
            let common: Vec<u32> = a.iter().copied().filter(|x| b.contains(x)).collect();
            common.len() == 2
                && tris
                    .iter()
                    .filter(|t| common.iter().all(|x| t.contains(x)))
                    .count()
                    == 2
        };
        let mut group_of = vec![usize::MAX; tris.len()];
        for k in 0..fans.len() {
            let g = rows_of(n, fans.group(k));
            for w in g.windows(2) {
                if !two(&w[0], &w[1]) {
                    return Err(format!("{kind}: fan at {v}: {:?} then {:?}", w[0], w[1]));
                }
            }
            let closes = g.len() >= 3 && two(&g[0], &g[g.len() - 1]);
            if closes != fans.closed[k] {
                return Err(format!("{kind}: fan at {v}: closed flag"));
            }
            for t in &g {
                group_of[tris.iter().position(|x| x == t).unwrap()] = k;
            }
            let wound = |order: &[SimplexHandle]| {
                let side = |t: SimplexHandle| {
                    let w = n.top_as_given(n.top_id(t).unwrap().unwrap()).unwrap();
                    let at = w.iter().position(|&x| x == v).unwrap();
                    (w[(at + 1) % 3], w[(at + 2) % 3])
                };
                let m = order.len();
                let steps = if fans.closed[k] { m } else { m - 1 };
                (0..steps).all(|i| side(order[i]).1 == side(order[(i + 1) % m]).0)
            };
            let grp = fans.group(k).to_vec();
            let mut rev = grp.clone();
            rev.reverse();
            if fans.oriented[k] != wound(&grp) || (!fans.oriented[k] && wound(&rev)) {
                return Err(format!(
                    "{kind}: fan at {v}: orientation {:?}",
                    fans.oriented[k]
                ));
            }
        }
        // Components: triangles joined through two-triangle edges are in one fan.
        for i in 0..tris.len() {
            for j in 0..tris.len() {
                if i != j && two(&tris[i], &tris[j]) && group_of[i] != group_of[j] {
                    return Err(format!(
                        "{kind}: fan at {v} split {:?} {:?}",
                        tris[i], tris[j]
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Clusters around every edge of a 3-complex: tetrahedra joined through triangles in exactly two
/// of them, consecutive ones sharing a triangle at the edge; for q = 2 every triangle once.
fn check_around_edges(n: &dyn Navigate, c: &Complex) -> Result<(), String> {
    let kind = n.kind();
    let o = Oracle::new(c);
    let mut fans = Fans::default();
    for e in o.levels[1].clone() {
        let h = n.locate(&e).unwrap();
        n.around_edge(h, 3, &mut fans)
            .map_err(|x| format!("{kind}: {x}"))?;
        let tets = o.relation(&e, 3);
        if sorted(rows_of(n, &fans.items)) != tets {
            return Err(format!("{kind}: tetrahedra around {e:?}"));
        }
        for k in 0..fans.len() {
            let g = rows_of(n, fans.group(k));
            for w in g.windows(2) {
                let shared = w[0].iter().filter(|x| w[1].contains(x)).count();
                if shared != 3 {
                    return Err(format!("{kind}: around {e:?}: {:?} then {:?}", w[0], w[1]));
                }
            }
        }
        // Triangles: each group a sweep through one cluster (consecutive triangles bound a
        // common tetrahedron); a triangle where clusters meet is in each of their sweeps.
        n.around_edge(h, 2, &mut fans)
            .map_err(|x| format!("{kind}: {x}"))?;
        let distinct: BTreeSet<Vec<u32>> = rows_of(n, &fans.items).into_iter().collect();
        if distinct.into_iter().collect::<Vec<_>>() != o.relation(&e, 2) {
            return Err(format!(
                "{kind}: triangles around {e:?}: {:?}",
                rows_of(n, &fans.items)
            ));
        }
        for k in 0..fans.len() {
            let g = rows_of(n, fans.group(k));
            for w in g.windows(2) {
                let mut u: Vec<u32> = w[0].iter().chain(&w[1]).copied().collect();
                u.sort();
                u.dedup();
                if !o.levels[3].contains(&u) {
                    return Err(format!("{kind}: around {e:?}: {:?} then {:?}", w[0], w[1]));
                }
            }
        }
    }
    Ok(())
}

fn check_bad_handles(n: &dyn Navigate) {
    let d = n.dimension();
    let past = SimplexHandle::dense(d, n.count(d) as u32);
    assert!(matches!(
        n.vertices_of(past),
        Err(QueryError::InvalidHandle { .. })
    ));
    assert!(matches!(
        n.degree(SimplexHandle::NONE, 0),
        Err(QueryError::InvalidHandle { .. })
    ));
    assert!(matches!(
        n.handle(d + 1, 0),
        Err(QueryError::InvalidHandle { .. })
    ));
    let face = SimplexHandle::top_face(TopId(0), 1);
    assert_eq!(face.form(), HandleForm::TopFace);
    assert!(matches!(
        n.check(face),
        Err(QueryError::InvalidHandle { .. })
    ));
    let v = n.vertex(VertexId(0)).unwrap();
    assert!(matches!(
        n.visit(v, d + 1, &mut |_| {}),
        Err(QueryError::DimensionOutOfRange { .. })
    ));
    if d >= 1 {
        assert!(matches!(
            n.around_edge(v, 2, &mut Fans::default()),
            Err(QueryError::WrongHandleKind { .. })
        ));
    }
}

fn check_all(c: &Complex, what: &str, deep: bool) {
    for s in buildable(c) {
        check_handles(s.as_ref(), c, deep).unwrap_or_else(|e| panic!("{what}: {e}"));
        let n = nav(s.as_ref());
        check_bad_handles(n);
        if c.dimension() == 2 {
            check_fans(n, c).unwrap_or_else(|e| panic!("{what}: {e}"));
        }
        if c.dimension() == 3 {
            check_around_edges(n, c).unwrap_or_else(|e| panic!("{what}: {e}"));
        }
    }
}

#[test]
fn every_handle_operation_matches_the_oracle_on_every_fixture() {
    for (name, c) in fixtures::all() {
        check_all(&c, name, true);
    }
}

/// ```text
///        3
///       / \
///      / B \          A = (0 1 2), B = (0 2 3) given as (2 3 0), C = (0 4 1) given as (4 1 0):
///     0 --- 2         one fan around 0, open, counter-clockwise by the winding: C, A, B.
///     |\ A /
///     | \ /
///     4--1
/// ```
#[test]
fn a_wound_open_fan_comes_counter_clockwise() {
    let c = Complex::from_simplices(5, &[&[0, 1, 2], &[2, 3, 0], &[4, 1, 0]]).unwrap();
    for s in buildable(&c) {
        let n = nav(s.as_ref());
        let mut fans = Fans::default();
        n.fans_around(n.vertex(VertexId(0)).unwrap(), &mut fans)
            .unwrap();
        assert_eq!(
            rows_of(n, &fans.items),
            [vec![0, 1, 4], vec![0, 1, 2], vec![0, 2, 3]]
        );
        assert_eq!(
            (fans.closed.as_slice(), fans.oriented.as_slice()),
            (&[false][..], &[true][..])
        );
        let t = n.top_id(fans.items[0]).unwrap().unwrap();
        assert_eq!(&*n.top_as_given(t).unwrap(), &[4, 1, 0]);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
    #[test]
    fn every_handle_operation_matches_the_oracle_on_random_complexes((n, list) in common::random_input(6, 8, 7)) {
        check_all(&common::complex_of(n, &list), "random", true);
    }

    #[test]
    fn fans_match_brute_force_on_random_surfaces((n, list) in common::random_input(2, 10, 14)) {
        check_all(&common::complex_of(n, &list), "random 2-complex", false);
    }

    #[test]
    fn edge_clusters_match_brute_force_on_random_3_complexes((n, list) in common::random_input(3, 8, 10)) {
        check_all(&common::complex_of(n, &list), "random 3-complex", false);
    }
}

/// Real data: every structure's handles against the vertex-id API on a sample of simplices of
/// each dimension (every 97th), and fans / edge clusters on the small files.
#[test]
fn real_data_handles_agree_with_the_relation_api() {
    for path in common::shared_files() {
        let Ok(c) = Complex::from_path(&path) else {
            continue;
        };
        let what = path.display().to_string();
        for s in buildable(&c) {
            let n = nav(s.as_ref());
            let (mut buf, mut rel, mut all) = (Vec::new(), Vec::new(), Vec::new());
            for p in 0..=s.dimension() {
                all.clear();
                s.simplices(p, &mut all);
                for row in all.chunks_exact(p + 1).step_by(97) {
                    let h = n
                        .locate(row)
                        .unwrap_or_else(|e| panic!("{what}: {}: {e}", s.kind()));
                    for q in 0..=s.dimension() {
                        n.related(h, q, Order::Natural, &mut buf).unwrap();
                        s.relation(row, q, &mut rel).unwrap();
                        let api = sorted(rel.chunks_exact(q + 1).map(<[u32]>::to_vec).collect());
                        assert_eq!(sorted(rows_of(n, &buf)), api, "{what}: {}", s.kind());
                    }
                }
            }
            check_tops(n, &c).unwrap_or_else(|e| panic!("{what}: {e}"));
            if c.vertex_count() < 3000 && c.dimension() == 2 {
                check_fans(n, &c).unwrap_or_else(|e| panic!("{what}: {e}"));
            }
        }
    }
}
