//! Brute-force reference answers, straight from the definitions. For tests, fuzzing and
//! cross-checks only: every query scans whole dimension tables (O(n) per query).

use std::collections::BTreeSet;

use crate::complex::{Complex, is_subset};

/// Every simplex of a complex, found by enumerating all vertex subsets of every top simplex.
pub struct Oracle {
    /// `levels[p]`: the p-simplices, ascending lexicographic.
    pub levels: Vec<Vec<Vec<u32>>>,
    /// `tops[p]`: the top p-simplices (not a proper face of another simplex).
    pub tops: Vec<Vec<Vec<u32>>>,
}

impl Oracle {
    /// Enumerates the closure of `complex` (every face of every top simplex).
    pub fn new(complex: &Complex) -> Oracle {
        let d = complex.dimension();
        let mut sets: Vec<BTreeSet<Vec<u32>>> = vec![BTreeSet::new(); d + 1];
        for v in 0..complex.vertex_count() {
            sets[0].insert(vec![v]);
        }
        for p in 0..=d {
            for top in complex.tops(p).iter() {
                for mask in 1u32..(1u32 << top.len()) {
                    let face: Vec<u32> = (0..top.len())
                        .filter(|i| mask >> i & 1 == 1)
                        .map(|i| top[i])
                        .collect();
                    sets[face.len() - 1].insert(face);
                }
            }
        }
        let levels: Vec<Vec<Vec<u32>>> =
            sets.into_iter().map(|s| s.into_iter().collect()).collect();
        // A simplex is top when it is not a facet of a simplex one dimension up.
        let tops = (0..=d)
            .map(|p| {
                let mut facets: BTreeSet<Vec<u32>> = BTreeSet::new();
                for t in levels.get(p + 1).into_iter().flatten() {
                    for skip in 0..t.len() {
                        facets.insert(
                            t.iter()
                                .enumerate()
                                .filter(|&(i, _)| i != skip)
                                .map(|(_, &v)| v)
                                .collect(),
                        );
                    }
                }
                levels[p]
                    .iter()
                    .filter(|s| !facets.contains(*s))
                    .cloned()
                    .collect()
            })
            .collect();
        Oracle { levels, tops }
    }

    /// Dimension d of the complex.
    pub fn dimension(&self) -> usize {
        self.levels.len() - 1
    }

    /// Whether `s` (ascending ids) is a simplex of the complex.
    pub fn contains(&self, s: &[u32]) -> bool {
        !s.is_empty()
            && s.len() <= self.levels.len()
            && self.levels[s.len() - 1].binary_search(&s.to_vec()).is_ok()
    }

    /// The g-clusters of the restricted star of σ (SIG paper §2, as settled by its Algorithm 1):
    /// the top g-simplices properly containing σ, two in one cluster when linked by a chain of
    /// top g-simplices, consecutive ones sharing a (g−1)-face that properly contains σ. Each
    /// cluster ascending, clusters ascending; empty unless p < g ≤ d.
    pub fn clusters(&self, sigma: &[u32], g: usize) -> Vec<Vec<Vec<u32>>> {
        let p = sigma.len() - 1;
        if g <= p || g > self.dimension() {
            return Vec::new();
        }
        let tops: Vec<&Vec<u32>> = self.tops[g]
            .iter()
            .filter(|t| is_subset(sigma, t))
            .collect();
        let linked = |a: &[u32], b: &[u32]| {
            let shared: Vec<u32> = a.iter().copied().filter(|v| b.contains(v)).collect();
            shared.len() == g && shared.len() > sigma.len() && is_subset(sigma, &shared)
        };
        let mut label = vec![usize::MAX; tops.len()];
        let mut clusters = Vec::new();
        for start in 0..tops.len() {
            if label[start] != usize::MAX {
                continue;
            }
            let c = clusters.len();
            label[start] = c;
            let mut members = vec![start];
            let mut k = 0;
            while k < members.len() {
                let m = members[k];
                for o in 0..tops.len() {
                    if label[o] == usize::MAX && linked(tops[m], tops[o]) {
                        label[o] = c;
                        members.push(o);
                    }
                }
                k += 1;
            }
            let mut cl: Vec<Vec<u32>> = members.iter().map(|&m| tops[m].clone()).collect();
            cl.sort();
            clusters.push(cl);
        }
        clusters.sort();
        clusters
    }

    /// R_{p,q}(σ) for σ ascending and in the complex, ascending lexicographic.
    pub fn relation(&self, sigma: &[u32], q: usize) -> Vec<Vec<u32>> {
        let p = sigma.len() - 1;
        let mut out: Vec<Vec<u32>> = if q < p {
            self.levels[q]
                .iter()
                .filter(|t| is_subset(t, sigma))
                .cloned()
                .collect()
        } else if q > p {
            self.levels[q]
                .iter()
                .filter(|t| is_subset(sigma, t))
                .cloned()
                .collect()
        } else if p == 0 {
            self.levels
                .get(1)
                .map(|edges| {
                    edges
                        .iter()
                        .filter(|e| e.contains(&sigma[0]))
                        .map(|e| vec![if e[0] == sigma[0] { e[1] } else { e[0] }])
                        .collect()
                })
                .unwrap_or_default()
        } else {
            self.levels[p]
                .iter()
                .filter(|t| {
                    t.as_slice() != sigma && t.iter().filter(|v| sigma.contains(v)).count() == p
                })
                .cloned()
                .collect()
        };
        out.sort();
        out
    }
}

fn rows(flat: &[u32], arity: usize) -> Vec<Vec<u32>> {
    let mut v: Vec<Vec<u32>> = flat.chunks_exact(arity).map(<[u32]>::to_vec).collect();
    v.sort();
    v
}

/// Checks `topo` against the oracle: counts, top counts, enumeration, and R_{p,q} for every
/// simplex and every `p, q <= d`, plus a refusal for a vertex set that is not a simplex. The error
/// names the first disagreement.
pub fn check_structure(
    topo: &dyn crate::relation::Topology,
    complex: &Complex,
) -> Result<(), String> {
    let oracle = Oracle::new(complex);
    let d = oracle.dimension();
    let name = topo.kind();
    if topo.dimension() != d {
        return Err(format!(
            "{name}: dimension {} instead of {d}",
            topo.dimension()
        ));
    }
    let mut out = Vec::new();
    for p in 0..=d {
        if topo.count(p) != oracle.levels[p].len() {
            return Err(format!(
                "{name}: n_{p} = {} instead of {}",
                topo.count(p),
                oracle.levels[p].len()
            ));
        }
        if topo.top_count(p) != oracle.tops[p].len() {
            return Err(format!(
                "{name}: {} top {p}-simplices instead of {}",
                topo.top_count(p),
                oracle.tops[p].len()
            ));
        }
        out.clear();
        topo.simplices(p, &mut out);
        let listed: Vec<Vec<u32>> = out.chunks_exact(p + 1).map(<[u32]>::to_vec).collect();
        if listed != oracle.levels[p] {
            return Err(format!(
                "{name}: enumeration of {p}-simplices differs (or is not in lexicographic order)"
            ));
        }
        for sigma in &oracle.levels[p] {
            if !topo.contains(sigma) {
                return Err(format!("{name}: does not contain {sigma:?}"));
            }
            for q in 0..=d {
                topo.relation(sigma, q, &mut out)
                    .map_err(|e| format!("{name}: R_{{{p},{q}}}({sigma:?}): {e}"))?;
                let got = rows(&out, q + 1);
                if got.windows(2).any(|w| w[0] == w[1]) {
                    return Err(format!(
                        "{name}: R_{{{p},{q}}}({sigma:?}) lists a simplex twice: {got:?}"
                    ));
                }
                let want = oracle.relation(sigma, q);
                if got != want {
                    return Err(format!(
                        "{name}: R_{{{p},{q}}}({sigma:?}) = {got:?}, oracle says {want:?}"
                    ));
                }
            }
        }
    }
    // A vertex set that is not a simplex must be refused, not answered.
    if let Some(missing) = first_non_simplex(&oracle, complex.vertex_count()) {
        match topo.relation(&missing, 0, &mut out) {
            Err(crate::relation::QueryError::NotInComplex { .. }) => {}
            other => {
                return Err(format!(
                    "{name}: query on non-simplex {missing:?} gave {other:?}"
                ));
            }
        }
    }
    Ok(())
}

/// The lexicographically first edge or triangle over the vertices that is not in the complex.
fn first_non_simplex(oracle: &Oracle, n: u32) -> Option<Vec<u32>> {
    let n = n.min(12);
    for a in 0..n {
        for b in a + 1..n {
            if !oracle.contains(&[a, b]) {
                return Some(vec![a, b]);
            }
            for c in b + 1..n {
                if !oracle.contains(&[a, b, c]) {
                    return Some(vec![a, b, c]);
                }
            }
        }
    }
    None
}

/// Checks that two structures give the same answer to every R_{p,q} on every simplex (for real
/// data, where the oracle's scans are too slow; the reference is itself oracle-tested).
pub fn compare_structures(
    a: &dyn crate::relation::Topology,
    b: &dyn crate::relation::Topology,
) -> Result<(), String> {
    let d = a.dimension();
    if b.dimension() != d {
        return Err(format!(
            "dimension: {} {} vs {} {}",
            a.kind(),
            d,
            b.kind(),
            b.dimension()
        ));
    }
    let (mut sa, mut sb, mut ra, mut rb) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for p in 0..=d {
        sa.clear();
        sb.clear();
        a.simplices(p, &mut sa);
        b.simplices(p, &mut sb);
        if sa != sb || a.count(p) != b.count(p) || a.top_count(p) != b.top_count(p) {
            return Err(format!(
                "{p}-simplices differ between {} and {}",
                a.kind(),
                b.kind()
            ));
        }
        for sigma in sa.chunks_exact(p + 1) {
            for q in 0..=d {
                a.relation(sigma, q, &mut ra)
                    .map_err(|e| format!("{}: {e}", a.kind()))?;
                b.relation(sigma, q, &mut rb)
                    .map_err(|e| format!("{}: {e}", b.kind()))?;
                crate::relation::sort_rows(&mut ra, q + 1);
                let n = rb.len();
                crate::relation::sort_rows(&mut rb, q + 1);
                if ra != rb || n != rb.len() {
                    return Err(format!(
                        "R_{{{p},{q}}}({sigma:?}): {} gives {:?}, {} gives {:?}",
                        a.kind(),
                        rows(&ra, q + 1),
                        b.kind(),
                        rows(&rb, q + 1)
                    ));
                }
            }
        }
    }
    Ok(())
}
