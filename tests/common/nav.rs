//! Brute-force checks of handle navigation shared by the handle tests of the nine structures
//! (tests/it/handles.rs) and of the live complex (tests/it/live.rs).

use std::collections::BTreeSet;

use topoplex::oracle::Oracle;
use topoplex::{Complex, Fans, Navigate, SimplexHandle, VertexId};

pub fn rows_of(n: &dyn Navigate, hs: &[SimplexHandle]) -> Vec<Vec<u32>> {
    hs.iter()
        .map(|&h| n.vertices_of(h).unwrap().to_vec())
        .collect()
}

pub fn sorted(mut v: Vec<Vec<u32>>) -> Vec<Vec<u32>> {
    v.sort();
    v
}

/// Brute-force "on the boundary": σ or a simplex of its star is a non-top simplex with exactly
/// one coface one dimension up.
pub fn oracle_boundary(o: &Oracle, s: &[u32]) -> bool {
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
pub fn oracle_manifold(o: &Oracle, s: &[u32]) -> bool {
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

/// Fans around every vertex of a 2-complex: a partition of the star into the components joined
/// through edges with exactly two triangles, each a chain in order, closed and oriented flags
/// right, oriented fans counter-clockwise by the winding.
pub fn check_fans(n: &dyn Navigate, c: &Complex) -> Result<(), String> {
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
pub fn check_around_edges(n: &dyn Navigate, c: &Complex) -> Result<(), String> {
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
