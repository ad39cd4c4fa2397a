//! Handles and navigation (issue 13): every handle operation of every structure equals the
//! vertex-id relation API and the brute-force oracle, on fixtures, random non-manifold complexes
//! up to dimension 6 and the real data; fans and edge clusters are checked against brute force.

use crate::common;

use common::nav::{
    check_around_edges, check_fans, oracle_boundary, oracle_manifold, rows_of, sorted,
};

use std::collections::BTreeSet;

use proptest::prelude::*;
use topoplex::handle::HandleForm;
use topoplex::oracle::Oracle;
use topoplex::{
    Complex, Fans, Navigate, Order, QueryError, SimplexHandle, TopId, Topology, VertexId, fixtures,
};

fn nav(s: &dyn Topology) -> &dyn Navigate {
    s.as_navigate().expect("every structure navigates")
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
/// (TS, PE, LE, DE answer VV, VF and FF in their own loop), and refuses an index out of range;
/// so is `related_handles_batch` over every simplex, dimensions mixed.
fn check_batches(n: &dyn Navigate) -> Result<(), String> {
    let d = n.dimension();
    let kind = n.kind();
    let mut buf = Vec::new();
    let every: Vec<SimplexHandle> = (0..=d)
        .rev()
        .flat_map(|p| (0..n.count(p) as u32).map(move |i| (p, i)))
        .map(|(p, i)| n.handle(p, i).unwrap())
        .collect();
    for q in 0..=d {
        for order in [Order::Natural, Order::Lexicographic] {
            let (mut got, mut ends) = (Vec::new(), Vec::new());
            n.related_handles_batch(&every, q, order, &mut got, &mut ends)
                .map_err(|e| format!("{kind}: handle batch R_{{*,{q}}}: {e}"))?;
            let (mut want, mut want_ends) = (Vec::new(), Vec::new());
            for &h in &every {
                n.related(h, q, order, &mut buf).unwrap();
                want.extend_from_slice(&buf);
                want_ends.push(want.len());
            }
            if (&got, &ends) != (&want, &want_ends) {
                return Err(format!(
                    "{kind}: handle batch R_{{*,{q}}} ({order:?}) differs from per handle"
                ));
            }
        }
    }
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
            check_views_and_degrees(n, p, q)?;
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

/// For R_{p,q}: `related_ids` (both orders), the lent `relation_view` and `degree_batch` agree
/// with `related` handle by handle; the view is the same on a second call (kept), and
/// `degree_batch` refuses an index out of range.
fn check_views_and_degrees(n: &dyn Navigate, p: usize, q: usize) -> Result<(), String> {
    let kind = n.kind();
    let all: Vec<u32> = (0..n.count(p) as u32).collect();
    let view = n
        .relation_view(p, q)
        .map_err(|e| format!("{kind}: view R_{{{p},{q}}}: {e}"))?
        .ok_or_else(|| format!("{kind}: no view"))?;
    let mut degrees = vec![0u32; all.len()];
    n.degree_batch(p, &all, q, &mut degrees)
        .map_err(|e| format!("{kind}: degree_batch R_{{{p},{q}}}: {e}"))?;
    if view.len() != all.len() {
        return Err(format!(
            "{kind}: view R_{{{p},{q}}} has {} rows",
            view.len()
        ));
    }
    let (mut buf, mut ids) = (Vec::new(), Vec::new());
    for &i in &all {
        let h = n.handle(p, i).unwrap();
        for order in [Order::Natural, Order::Lexicographic] {
            n.related(h, q, order, &mut buf).unwrap();
            let want: Vec<u32> = buf.iter().map(|h| h.index()).collect();
            ids.clear();
            ids.push(7); // appended after what is there
            n.related_ids(h, q, order, &mut ids).unwrap();
            if ids[1..] != want[..] {
                return Err(format!(
                    "{kind}: related_ids R_{{{p},{q}}}({h}) {ids:?}, related {want:?}"
                ));
            }
            if order == Order::Natural && view.get(i as usize) != &want[..] {
                return Err(format!(
                    "{kind}: view R_{{{p},{q}}}({h}) {:?}, related {want:?}",
                    view.get(i as usize)
                ));
            }
        }
        if degrees[i as usize] as usize != buf.len() {
            return Err(format!(
                "{kind}: degree_batch R_{{{p},{q}}}({h}) {}, related has {}",
                degrees[i as usize],
                buf.len()
            ));
        }
    }
    let again = n.relation_view(p, q).unwrap().unwrap();
    if again.ids().as_ptr() != view.ids().as_ptr() || again != view {
        return Err(format!(
            "{kind}: view R_{{{p},{q}}} rebuilt on the second call"
        ));
    }
    if n.degree_batch(p, &[n.count(p) as u32], q, &mut [0]).is_ok() {
        return Err(format!(
            "{kind}: degree_batch R_{{{p},{q}}} took an index out of range"
        ));
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
    for s in common::buildable(c, what) {
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
    for s in common::buildable(&c, "a wound open fan") {
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
    fn every_handle_operation_matches_the_oracle_on_random_complexes(c in common::random_complex(6, 8, 7)) {
        check_all(&c, "random", true);
    }

    #[test]
    fn fans_match_brute_force_on_random_surfaces(c in common::random_complex(2, 10, 14)) {
        check_all(&c, "random 2-complex", false);
    }

    #[test]
    fn edge_clusters_match_brute_force_on_random_3_complexes(c in common::random_complex(3, 8, 10)) {
        check_all(&c, "random 3-complex", false);
    }
}

/// Real data: every structure's handles against the vertex-id API on a sample of simplices of
/// each dimension (every 97th), and fans / edge clusters on the small files.
#[test]
fn real_data_handles_agree_with_the_relation_api() {
    for (path, c) in common::shared_complexes() {
        let what = path.display().to_string();
        for s in common::buildable(&c, &what) {
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
