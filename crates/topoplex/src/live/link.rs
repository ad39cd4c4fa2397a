//! The link condition Lk(a) ∩ Lk(b) = Lk(ab) for an edge {a, b} (Dey, Edelsbrunner, Guha,
//! Nekhayev 1999), checked in every dimension at once.
//!
//! Lk(ab) ⊆ Lk(a) ∩ Lk(b) always holds, so only the other inclusion is checked. With
//! F_a = {t \ {a} : t ∈ St*(a), b ∉ t}, F_b likewise, and F_ab = {t \ {a, b} : t ∈ St*(a), b ∈ t},
//! Lk(a) ∩ Lk(b) is the closure of {x ∩ y : x ∈ F_a, y ∈ F_b} (faces of a top through both a and
//! b are in Lk(ab) anyway), and Lk(ab) the closure of F_ab. So the condition holds iff every
//! non-empty x ∩ y is inside some z ∈ F_ab. The vertices that can occur in x ∩ y are the common
//! ones C = V(F_a) ∩ V(F_b), found with per-vertex stamps (one pass over each star, no sort);
//! with |C| ≤ 64 each set becomes one word and each test two word operations:
//! O(d·(k_a + k_b) + |F_a|·|F_b|·|F_ab|) after duplicate and non-maximal words are dropped.
//! Past 64 common vertices, sorted id lists do the same work. The stamps are per-thread scratch
//! of 8 bytes per vertex (not part of the structure's storage), so the test takes `&self` and
//! allocates nothing once warm.
//!
//! On failure the reported simplex is a lowest-dimensional one of Lk(a) ∩ Lk(b) outside Lk(ab).
//!
//! The test on the complex coned over its boundary (`link_condition_with_boundary`) runs on the
//! same words: ω takes one more bit, and each boundary facet f through a or b (a facet of a top
//! of the star that no other top of that star holds — found by sorting order-free hashes of the
//! star's facets, O(d·k·log(d·k)) per star, `LiveComplex::star_boundary`) adds the word of
//! f \ {a, b} with ω's bit to F_a, F_b or F_ab.
//!
//! Before any of this, when one star has 64 tops or more and over 4× the other's, a
//! 0-dimensional violation (a vertex w joined to a and to b with no top
//! holding a, b and w) is looked for from the smaller star alone: each vertex of St(b) outside
//! the tops through a and b is tested for an edge to a by scanning the smaller of St(w), St(a)
//! (O(d·k_b + Σ_w d·min(k_w, k_a))). Most refusals are found there, so a vertex with a huge
//! star (simplify gathers thousands of tops into one) does not make every refusal scan it
//! (between stars of like size the whole test reads them once instead of twice); the
//! edge test {a, b} itself scans the smaller star. It runs after the plain test on the
//! same masks, so it too allocates nothing once warm (past 64 common vertices it falls back to
//! the lists).
//!
//! When St(a) is large (64 tops or more) and over 4 times St(b), the word test reads St(a) only
//! where the common vertices are (`skewed_violation`): C from St(b), F_a's words and St(a)'s
//! boundary facets from the common vertices' stars, at O(d·k_b + Σ_{w ∈ V(St b)}
//! d·min(k_w, k_a) + d²·Σ_{w ∈ C} k_w·k_min) instead of O(d·k_a·log(d·k_a)); the one case it
//! cannot decide (whether St(a) has a boundary facet away from C, when that matters) runs the
//! whole test. The answers are the whole test's, simplex for simplex.

use std::cell::RefCell;

use super::{LiveComplex, Refusal, VertexId, subset};

impl LiveComplex {
    /// Whether {a, b} is an edge satisfying the link condition. `Err(NotAnEdge)` for a non-edge,
    /// `Err(LinkCondition { dim, simplex })` naming a lowest-dimensional simplex of
    /// Lk(a) ∩ Lk(b) not in Lk(ab). Read-only; allocates nothing after a thread's first calls
    /// (per-thread scratch). Cost: module doc of [`crate::live::link`].
    pub fn link_condition(&self, a: VertexId, b: VertexId) -> Result<(), Refusal> {
        self.checked_link(a, b, false)
    }

    /// Both link tests: the edge checked, then the first violation looked for with this
    /// thread's scratch (`coned`: on the complex coned over its boundary, after the plain test).
    fn checked_link(&self, a: VertexId, b: VertexId, coned: bool) -> Result<(), Refusal> {
        self.check_vertex(a.0)?;
        self.check_vertex(b.0)?;
        let (a, b) = (a.0, b.0);
        if a == b || !self.joined(a, b) {
            return Err(Refusal::NotAnEdge { a, b });
        }
        let found = SCRATCH.with(|s| match s.try_borrow_mut() {
            Ok(mut s) => self.first_violation(a, b, coned, &mut s),
            Err(_) => self.first_violation(a, b, coned, &mut Scratch::default()),
        });
        match found {
            None => Ok(()),
            Some(simplex) => Err(Refusal::LinkCondition {
                a,
                b,
                dim: simplex.len() - 1,
                simplex,
            }),
        }
    }

    /// Whether some top holds both a and b: the smaller of the two stars scanned.
    fn joined(&self, a: u32, b: u32) -> bool {
        let (small, other) = if self.star[a as usize].len() <= self.star[b as usize].len() {
            (a, b)
        } else {
            (b, a)
        };
        self.star[small as usize]
            .iter()
            .any(|&r| self.top_raw(r).contains(&other))
    }

    /// A vertex w ∈ Lk(a) ∩ Lk(b) outside Lk(ab), looked for from the smaller star only: the
    /// vertices of the tops of St(b) (b the smaller) that no top through a and b holds, each
    /// tested for an edge to a by [`LiveComplex::joined`] (the smaller of St(w), St(a)). Costs
    /// O(d·k_b + Σ_w d·min(k_w, k_a)), not O(d·k_a): a vertex with a huge star (simplify's
    /// contractions gather thousands of tops into one vertex) does not make every refusal
    /// scan it. A 0-dimensional violation is a lowest-dimensional one, so it is the answer
    /// when it exists; `None` says only that there is none of dimension 0.
    fn vertex_violation(&self, a: u32, b: u32, s: &mut Scratch) -> Option<u32> {
        let (a, b) = if self.star[b as usize].len() <= self.star[a as usize].len() {
            (a, b)
        } else {
            (b, a)
        };
        let (tried, in_ab) = s.fresh_stamps(self.star.len());
        let star_b = || self.star[b as usize].iter().map(|&r| self.top_raw(r));
        for t in star_b().filter(|t| t.contains(&a)) {
            for &v in t {
                s.stamp[v as usize] = in_ab;
            }
        }
        for t in star_b().filter(|t| !t.contains(&a)) {
            for &w in t {
                let st = &mut s.stamp[w as usize];
                if w == b || *st == in_ab || *st == tried {
                    continue;
                }
                *st = tried;
                if self.joined(a, w) {
                    return Some(w);
                }
            }
        }
        None
    }

    /// The common vertices C, then the word or list test (module doc); with `coned`, when the
    /// plain test passes, the same test again with the boundary facets' cones added. When one
    /// star is far larger than the other, a 0-dimensional violation is looked for first from
    /// the smaller star ([`LiveComplex::vertex_violation`]).
    fn first_violation(&self, a: u32, b: u32, coned: bool, s: &mut Scratch) -> Option<Vec<u32>> {
        // The shortcut pays only when one star is far larger (it spares reading it); between
        // stars of like size it would read them again before the whole test on every edge
        // that passes (a mesh's usual contraction: 2x the check's time).
        let (ka, kb) = (self.star[a as usize].len(), self.star[b as usize].len());
        let skewed = ka.max(kb) >= BIG_STAR && ka.max(kb) > STAR_SKEW * ka.min(kb);
        if skewed && let Some(w) = self.vertex_violation(a, b, s) {
            return Some(vec![w]);
        }
        self.full_violation(a, b, coned, s)
    }

    /// [`LiveComplex::first_violation`] without the 0-dimensional shortcut: from the smaller
    /// star ([`LiveComplex::skewed_violation`]) when St(a) is large and St(b) much smaller and
    /// that decides, else [`LiveComplex::whole_violation`].
    fn full_violation(&self, a: u32, b: u32, coned: bool, s: &mut Scratch) -> Option<Vec<u32>> {
        let (ka, kb) = (self.star[a as usize].len(), self.star[b as usize].len());
        if ka >= BIG_STAR
            && ka > STAR_SKEW * kb
            && let Some(found) = self.skewed_violation(a, b, coned, ka, s)
        {
            return found;
        }
        self.whole_violation(a, b, coned, s)
    }

    /// The word test with St(a) read only where it matters: the common vertices C found from
    /// St(b) (each vertex of St(b) tested for an edge to a by [`LiveComplex::joined`]); F_a's
    /// words from the tops of St(a) through a common vertex (found in the common vertices'
    /// stars: a top of St(a) with no common vertex gives the empty word, which changes
    /// nothing); F_ab's from St(b). Coned, the boundary facets of St(a) are found the same
    /// way: a facet f ∋ a holding a common vertex w is open when no other top of St(w) holds
    /// it (every top holding f holds w), one through b when no other top of St(b) holds it. A
    /// boundary facet of St(a) with no common vertex (nor b) gives the word {ω} alone, which
    /// this cannot see without scanning St(a); it changes the answer only when no word of F_a
    /// holds ω, a word of F_b does and none of F_ab does (x ∩ y = {ω} uncovered), and then
    /// `None` sends the caller to the whole test. Otherwise the answer is the whole test's:
    /// the families are the same sets of words once [`maximal`] has kept their maximal ones.
    /// Cost: O(d·k_b + Σ_{w ∈ V(St b)} d·min(k_w, k_a) + d²·Σ_{w ∈ C} k_w·k_min), with k_min
    /// the smallest star among a facet's common vertices; `None` also when |C| > 64 or the
    /// common vertices' stars add up to `most` tops or more (the caller passes St(a)'s size).
    fn skewed_violation(
        &self,
        a: u32,
        b: u32,
        coned: bool,
        most: usize,
        s: &mut Scratch,
    ) -> Option<Option<Vec<u32>>> {
        let found = self.skewed_common(a, b, most, s)?;
        if found + usize::from(coned) > 64 {
            return None; // words of more than 64 bits: the whole test (by lists) decides
        }
        if !s.cone(coned) {
            return Some(None);
        }
        self.skewed_families(a, b, found, s);
        let plain = s.first_violation();
        if plain.is_some() || !coned {
            return Some(plain);
        }
        let omega = 1u64 << s.index_omega;
        self.skewed_cones(a, b, found, omega, s);
        let holds_omega = |words: &[u64]| words.iter().any(|&m| m & omega != 0);
        if !holds_omega(&s.ma) && holds_omega(&s.mb) && !holds_omega(&s.mz) {
            // Whether St(a) has a boundary facet away from C decides: the whole test.
            return None;
        }
        Some(s.first_violation())
    }

    /// Step 1 of [`LiveComplex::skewed_violation`]: the common vertices C into `s.common`, in
    /// order of first appearance in St(b)'s tops (as `common_vertices` numbers them), each
    /// vertex of St(b) tried once through the stamps. Returns |C|, or `None` (the whole test
    /// decides) when C's stars add up to `most` tops or more.
    fn skewed_common(&self, a: u32, b: u32, most: usize, s: &mut Scratch) -> Option<usize> {
        let (tried, common) = s.fresh_stamps(self.star.len());
        s.common.clear();
        let mut weight = 0;
        for &r in self.star[b as usize].iter() {
            for &v in self.top_raw(r) {
                let st = s.stamp[v as usize];
                if v == a || v == b || st == tried || st == common {
                    continue;
                }
                if self.joined(a, v) {
                    s.stamp[v as usize] = common;
                    s.index[v as usize] = s.common.len() as u32;
                    s.common.push(v);
                    weight += self.star[v as usize].len();
                } else {
                    s.stamp[v as usize] = tried;
                }
            }
        }
        (weight < most).then_some(s.common.len())
    }

    /// Step 2: the plain families as masks over C: F_ab and F_b from
    /// St(b) (tops with and without a), F_a from the stars of the `found` common vertices
    /// (tops through a but not b).
    fn skewed_families(&self, a: u32, b: u32, found: usize, s: &mut Scratch) {
        s.ma.clear();
        s.mb.clear();
        s.mz.clear();
        for &r in self.star[b as usize].iter() {
            let t = self.top_raw(r);
            let m = s.mask(t);
            if t.contains(&a) {
                s.mz.push(m);
            } else {
                s.mb.push(m);
            }
        }
        for i in 0..found {
            for r in self.tops_at_a_only(s.common[i], a, b) {
                let m = s.mask(self.top_raw(r));
                s.ma.push(m);
            }
        }
    }

    /// Step 3, coned: the cones over the boundary facets at b (as `boundary_cones`) and at a
    /// (those through b, from St(b), then those through a common vertex), added to the
    /// families.
    fn skewed_cones(&self, a: u32, b: u32, found: usize, omega: u64, s: &mut Scratch) {
        self.cones_at_b(a, b, omega, s);
        for &r in self.star[b as usize].iter() {
            let t = self.top_raw(r);
            if t.contains(&a) {
                self.cones_at_a(r, a, b, omega, s);
            }
        }
        for i in 0..found {
            for r in self.tops_at_a_only(s.common[i], a, b) {
                self.cones_at_a(r, a, b, omega, s);
            }
        }
    }

    /// The tops of St(w) through a but not b (St(a)'s tops away from b, found from a common
    /// vertex w).
    fn tops_at_a_only(&self, w: u32, a: u32, b: u32) -> impl Iterator<Item = u32> + '_ {
        self.star[w as usize].iter().copied().filter(move |&r| {
            let t = self.top_raw(r);
            t.contains(&a) && !t.contains(&b)
        })
    }

    /// The cones over the open facets f ∋ a of top `r` ∈ St(a) that hold b or a common vertex
    /// (others are {ω} alone, see [`LiveComplex::skewed_violation`]), as words pushed as
    /// [`LiveComplex::boundary_cones`] pushes them: to F_ab when f holds b, else to F_a.
    fn cones_at_a(&self, r: u32, a: u32, b: u32, omega: u64, s: &mut Scratch) {
        let t = self.top_raw(r);
        let m = s.mask(t);
        let through_b = t.contains(&b);
        for (j, &x) in t.iter().enumerate() {
            if x == a {
                continue;
            }
            let word = s.without(m, x);
            let holds_b = through_b && x != b;
            // Every top holding f holds the vertex whose star is searched.
            let witness = if holds_b {
                Some(b)
            } else {
                t.iter()
                    .enumerate()
                    .filter(|&(k, &v)| k != j && s.stamp[v as usize] == s.epoch)
                    .map(|(_, &v)| v)
                    .min_by_key(|&v| self.star[v as usize].len())
            };
            let Some(w) = witness else {
                continue;
            };
            let shared = self.star[w as usize].iter().any(|&o| {
                let u = self.top_raw(o);
                o != r
                    && u.len() + 1 >= t.len()
                    && t.iter().enumerate().all(|(k, v)| k == j || u.contains(v))
            });
            if !shared {
                if holds_b {
                    s.mz.push(word | omega);
                } else {
                    s.ma.push(word | omega);
                }
            }
        }
    }

    /// [`LiveComplex::full_violation`] reading both stars whole.
    fn whole_violation(&self, a: u32, b: u32, coned: bool, s: &mut Scratch) -> Option<Vec<u32>> {
        let fa = || self.star[a as usize].iter().map(|&r| self.top_raw(r));
        let fb = || self.star[b as usize].iter().map(|&r| self.top_raw(r));
        common_vertices(fa(), fb(), a, b, self.star.len(), s);
        if !s.cone(coned) {
            return None;
        }
        if s.common.len() > 64 {
            if coned {
                s.common.pop();
            }
            s.common.sort_unstable();
            let fa: Vec<&[u32]> = fa().filter(|t| !t.contains(&b)).collect();
            let fab: Vec<&[u32]> = fa_through(self, a, b).collect();
            let fb: Vec<&[u32]> = fb().filter(|t| !t.contains(&a)).collect();
            let plain = lists::first_violation(&s.common, &fa, &fb, &fab);
            if plain.is_some() || !coned {
                return plain;
            }
            return self.coned_by_lists(a, b);
        }
        s.ma.clear();
        s.mb.clear();
        s.mz.clear();
        for t in fa() {
            let m = s.mask(t);
            if t.contains(&b) {
                s.mz.push(m);
            } else {
                s.ma.push(m);
            }
        }
        for t in fb().filter(|t| !t.contains(&a)) {
            let m = s.mask(t);
            s.mb.push(m);
        }
        let plain = s.first_violation();
        if plain.is_some() || !coned {
            return plain;
        }
        self.boundary_cones(a, b, s);
        s.first_violation()
    }

    /// The cones ω ∗ (f \ {a, b}) over the boundary facets f at a and at b, as words added to
    /// the families: at a, to F_ab when b ∈ f, else to F_a; at b, to F_b when a ∉ f.
    fn boundary_cones(&self, a: u32, b: u32, s: &mut Scratch) {
        let omega = 1u64 << s.index_omega;
        self.facet_cones(a, omega, s, |s, t, x, w| {
            if x != b && t.contains(&b) {
                s.mz.push(w);
            } else {
                s.ma.push(w);
            }
        });
        self.cones_at_b(a, b, omega, s);
    }

    /// The cones ω ∗ (f \ {b}) over the boundary facets f at b that do not hold a, as words
    /// added to F_b.
    fn cones_at_b(&self, a: u32, b: u32, omega: u64, s: &mut Scratch) {
        self.facet_cones(b, omega, s, |s, t, x, w| {
            // f = t \ {x} must not hold a.
            if x == a || !t.contains(&a) {
                s.mb.push(w);
            }
        });
    }

    /// For each boundary facet f = t \ {x} at v (t a top of St(v); the facets of
    /// [`LiveComplex::star_boundary`]), `add(s, t, x, word)` with the word of the cone ω ∗ f.
    fn facet_cones(
        &self,
        v: u32,
        omega: u64,
        s: &mut Scratch,
        add: impl Fn(&mut Scratch, &[u32], u32, u64),
    ) {
        let mut open = std::mem::take(&mut s.open);
        self.star_boundary(v, &mut s.facets, &mut open);
        for (&r, &open) in self.star[v as usize].iter().zip(&open) {
            let t = self.top_raw(r);
            let m = s.mask(t);
            for (j, &x) in t.iter().enumerate() {
                if open >> j & 1 == 1 {
                    let w = s.without(m, x) | omega;
                    add(s, t, x, w);
                }
            }
        }
        s.open = open;
    }

    /// For every top of St(v), in star order, into `open`: the positions j whose facet
    /// t \ {t[j]} (j not v's position) is on the boundary, held by no other top of St(v)
    /// (every top holding it holds v), as bits.
    ///
    /// Each facet through v gets an order-free hash of its vertex set (the sum of a mix of its
    /// ids: the top's sum minus the left-out vertex's, O(d) a top); sorting the hashes brings
    /// equal facets together, and only facets of equal hash are compared, so a star of k tops
    /// of dimension d costs O(d·k·log(d·k) + d²·(facet pairs of equal hash)) rather than the
    /// O(d²·k²) of comparing every pair of tops. A facet can also lie in a larger top of a
    /// mixed-dimensional star without being its facet: only there are the smaller tops'
    /// facets compared with each larger top. `facets` is scratch; nothing is allocated once
    /// warm.
    fn star_boundary(&self, v: u32, facets: &mut Vec<(u64, usize)>, open: &mut Vec<u32>) {
        let star = &self.star[v as usize];
        open.clear();
        facets.clear();
        if self.triangle_fan_boundary(v, open) {
            return;
        }
        open.clear();
        let (mut shortest, mut longest) = (usize::MAX, 0);
        for (i, &r) in star.iter().enumerate() {
            let t = self.top_raw(r);
            shortest = shortest.min(t.len());
            longest = longest.max(t.len());
            let own = t.iter().position(|&x| x == v).map_or(0, |j| 1 << j);
            open.push(((1u32 << t.len()) - 1) & !own);
            let sum = t.iter().fold(0u64, |h, &x| h.wrapping_add(mix(x)));
            let size = (t.len() as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            for (j, &x) in t.iter().enumerate() {
                if x != v {
                    facets.push((sum.wrapping_sub(mix(x)).wrapping_add(size), i << 4 | j));
                }
            }
        }
        facets.sort_unstable();
        let facet_of = |e: usize| (self.top_raw(star[e >> 4]), e & 15);
        let mut start = 0;
        while start < facets.len() {
            let key = facets[start].0;
            let end = start + facets[start..].iter().take_while(|f| f.0 == key).count();
            for p in start..end {
                for q in p + 1..end {
                    let (e, f) = (facets[p].1, facets[q].1);
                    let ((t, j), (u, l)) = (facet_of(e), facet_of(f));
                    // Same size (the hash holds it), so t \ {t[j]} ⊆ u \ {u[l]} is equality.
                    let same = t.len() == u.len()
                        && t.iter()
                            .enumerate()
                            .all(|(k, x)| k == j || (u.contains(x) && *x != u[l]));
                    if same {
                        open[e >> 4] &= !(1 << j);
                        open[f >> 4] &= !(1 << l);
                    }
                }
            }
            start = end;
        }
        if shortest == longest {
            return;
        }
        // Mixed dimensions: a facet of a smaller top inside a larger top.
        for (i, &r) in star.iter().enumerate() {
            let t = self.top_raw(r);
            if t.len() == longest || open[i] == 0 {
                continue;
            }
            for &o in star.iter() {
                let other = self.top_raw(o);
                if other.len() <= t.len() {
                    continue;
                }
                if let Some(j) = facet_inside(t, other) {
                    open[i] &= !(1 << j);
                }
            }
        }
    }

    /// [`LiveComplex::star_boundary`] for a star of at most [`SMALL_FAN`] triangles and nothing
    /// else (a surface's vertex): the facet through v opposite a triangle's vertex y is the
    /// edge vx, shared exactly when another triangle of the star has x among its two other
    /// vertices, so pairs of triangles compare their two link vertices (O(k²), no hashing, no
    /// sort). Returns false, having written some of `open`, when the star is not such a fan.
    fn triangle_fan_boundary(&self, v: u32, open: &mut Vec<u32>) -> bool {
        let star = &self.star[v as usize];
        if star.len() > SMALL_FAN {
            return false;
        }
        // Per triangle its two other vertices x, y and their positions.
        let mut link = [[0u32; 2]; SMALL_FAN];
        let mut at = [[0u8; 2]; SMALL_FAN];
        for (i, &r) in star.iter().enumerate() {
            if super::unpack(r).0 != 2 {
                return false;
            }
            let t = self.top_raw(r);
            let own = t.iter().position(|&x| x == v).expect("v is in its star");
            let (i1, i2) = ((own + 1) % 3, (own + 2) % 3);
            link[i] = [t[i1], t[i2]];
            at[i] = [i1 as u8, i2 as u8];
            open.push(1 << i1 | 1 << i2);
        }
        // Edge v·link[i][s] is the facet opposite link[i][1 - s], at bit at[i][1 - s].
        for i in 0..star.len() {
            for j in i + 1..star.len() {
                for s in 0..2 {
                    for u in 0..2 {
                        if link[i][s] == link[j][u] {
                            open[i] &= !(1 << at[i][1 - s]);
                            open[j] &= !(1 << at[j][1 - u]);
                        }
                    }
                }
            }
        }
        true
    }

    /// The positions j of top `raw` ∈ St(v) whose facet t \ {t[j]} (j not v's position) is on
    /// the boundary: held by no other top of St(v) (every top holding it holds v). As bits.
    /// Every pair of tops compared, O(d²·k) a top: the oracle [`LiveComplex::star_boundary`]
    /// is tested against.
    #[cfg(test)]
    fn boundary_positions(&self, v: u32, raw: u32) -> u32 {
        let t = self.top_raw(raw);
        let mut shared = 0u32;
        for &o in self.star[v as usize].iter() {
            if o == raw {
                continue;
            }
            let other = self.top_raw(o);
            if other.len() + 1 < t.len() {
                continue;
            }
            if let Some(j) = facet_inside(t, other) {
                shared |= 1 << j;
            }
        }
        let all = (1u32 << t.len()) - 1;
        let own = t.iter().position(|&x| x == v).map_or(0, |j| 1 << j);
        all & !shared & !own
    }
}

/// Up to this many triangles a vertex's star is a fan whose boundary edges are found by
/// comparing pairs ([`LiveComplex::triangle_fan_boundary`]).
const SMALL_FAN: usize = 24;

/// From this many tops in St(a), and more than [`STAR_SKEW`] times St(b)'s, the link test
/// reads St(a) only where the common vertices are ([`LiveComplex::skewed_violation`]).
const BIG_STAR: usize = 64;

/// See [`BIG_STAR`].
const STAR_SKEW: usize = 4;

/// The position j such that the facet of `t` without its j-th vertex lies in `other`, if one
/// does: that vertex is then the only one of `t` missing from `other`. O(|t|·|other|).
fn facet_inside(t: &[u32], other: &[u32]) -> Option<usize> {
    let mut missing = t.iter().enumerate().filter(|(_, x)| !other.contains(x));
    match (missing.next(), missing.next()) {
        (Some((j, _)), None) => Some(j),
        _ => None,
    }
}

/// A 64-bit mix of a vertex id (SplitMix64's finaliser), summed into order-free facet hashes.
#[inline]
fn mix(x: u32) -> u64 {
    let mut z = u64::from(x).wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The tops of St(a) through b.
fn fa_through<'a>(l: &'a LiveComplex, a: u32, b: u32) -> impl Iterator<Item = &'a [u32]> + 'a {
    l.star[a as usize]
        .iter()
        .map(move |&r| l.top_raw(r))
        .filter(move |t| t.contains(&b))
}

/// Per-thread buffers of the link test, so that a check allocates nothing once warm.
#[derive(Default)]
struct Scratch {
    /// Per vertex: `epoch - 1` when in a top of St(a), `epoch` when common too.
    stamp: Vec<u32>,
    /// Per common vertex: its bit.
    index: Vec<u32>,
    epoch: u32,
    common: Vec<u32>,
    /// The bit of ω (the cone vertex) in the coned test.
    index_omega: u32,
    ma: Vec<u64>,
    mb: Vec<u64>,
    mz: Vec<u64>,
    /// [`LiveComplex::star_boundary`]'s facet hashes and its answer.
    facets: Vec<(u64, usize)>,
    open: Vec<u32>,
}

impl Scratch {
    /// Two stamps no vertex of 0..n carries yet, `(epoch - 1, epoch)` (the stamps sized to n,
    /// cleared when the epoch would wrap).
    fn fresh_stamps(&mut self, n: usize) -> (u32, u32) {
        if self.stamp.len() < n {
            self.stamp.resize(n, 0);
            self.index.resize(n, 0);
        }
        if self.epoch >= u32::MAX - 2 {
            self.stamp.iter_mut().for_each(|x| *x = 0);
            self.epoch = 0;
        }
        self.epoch += 2;
        (self.epoch - 1, self.epoch)
    }

    /// With `coned`, ω as the common vertex after the others (its own bit; a superset of the
    /// common vertices changes no x ∩ y). False when nothing is left to test: not coned and no
    /// common vertex.
    fn cone(&mut self, coned: bool) -> bool {
        if coned {
            self.index_omega = self.common.len() as u32;
            self.common.push(OMEGA);
        }
        coned || !self.common.is_empty()
    }

    /// The word test on the families as they now stand, their maximal words kept first.
    fn first_violation(&mut self) -> Option<Vec<u32>> {
        maximal(&mut self.ma);
        maximal(&mut self.mb);
        words::first_violation(&self.common, &self.ma, &self.mb, &self.mz)
    }

    /// The common vertices of `t` as a word.
    #[inline]
    fn mask(&self, t: &[u32]) -> u64 {
        t.iter()
            .filter(|&&v| self.stamp[v as usize] == self.epoch)
            .fold(0u64, |m, &v| m | 1 << self.index[v as usize])
    }

    /// Word `m` without vertex `x`'s bit (when x is common).
    #[inline]
    fn without(&self, m: u64, x: u32) -> u64 {
        if self.stamp[x as usize] == self.epoch {
            m & !(1 << self.index[x as usize])
        } else {
            m
        }
    }
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Vertices other than a and b in a top of St(a) and in a top of St(b), into `s.common`
/// (a superset of V(F_a) ∩ V(F_b), which changes no x ∩ y), numbered in `s.index` in order of
/// discovery: one pass over each star with per-vertex stamps, no sort.
fn common_vertices<'a>(
    fa: impl Iterator<Item = &'a [u32]>,
    fb: impl Iterator<Item = &'a [u32]>,
    a: u32,
    b: u32,
    n: usize,
    s: &mut Scratch,
) {
    let (in_a, common) = s.fresh_stamps(n);
    for t in fa {
        for &v in t {
            s.stamp[v as usize] = in_a;
        }
    }
    s.stamp[a as usize] = 0;
    s.stamp[b as usize] = 0;
    s.common.clear();
    for t in fb {
        for &v in t {
            if s.stamp[v as usize] == in_a {
                s.stamp[v as usize] = common;
                s.index[v as usize] = s.common.len() as u32;
                s.common.push(v);
            }
        }
    }
}

/// Keeps the maximal sets of a family of words (drops zero, duplicates and subsets), in place.
fn maximal(masks: &mut Vec<u64>) {
    masks.retain(|&m| m != 0);
    masks.sort_unstable_by(|x, y| y.count_ones().cmp(&x.count_ones()).then(x.cmp(y)));
    masks.dedup();
    let mut kept = 0;
    for i in 0..masks.len() {
        let m = masks[i];
        if !masks[..kept].iter().any(|&k| m & !k == 0) {
            masks[kept] = m;
            kept += 1;
        }
    }
    masks.truncate(kept);
}

/// The common vertices as bits of one word.
mod words {
    /// A lowest-dimensional x ∩ y (x ∈ ma, y ∈ mb) face not under any z ∈ mz, as vertex ids.
    pub(super) fn first_violation(
        common: &[u32],
        ma: &[u64],
        mb: &[u64],
        mz: &[u64],
    ) -> Option<Vec<u32>> {
        let covered = |w: u64| mz.iter().any(|&z| w & !z == 0);
        let mut best: Option<u64> = None;
        for &x in ma {
            for &y in mb {
                let w = x & y;
                if w == 0 || covered(w) {
                    continue;
                }
                let m = smallest_uncovered(w, &covered);
                if best.is_none_or(|b| m.count_ones() < b.count_ones()) {
                    best = Some(m);
                }
            }
        }
        best.map(|m| {
            let mut v: Vec<u32> = (0..64)
                .filter(|i| m >> i & 1 == 1)
                .map(|i| common[i])
                .collect();
            v.sort_unstable();
            v
        })
    }

    /// A submask of `w` with the fewest bits that no z covers (w itself is uncovered).
    fn smallest_uncovered(w: u64, covered: &impl Fn(u64) -> bool) -> u64 {
        let mut best = w;
        let mut s = w;
        while s != 0 {
            if s.count_ones() < best.count_ones() && !covered(s) {
                best = s;
            }
            s = (s - 1) & w;
        }
        best
    }
}

/// Sorted id lists, for more than 64 common vertices.
mod lists {
    use super::subset;

    pub(super) fn first_violation(
        common: &[u32],
        fa: &[&[u32]],
        fb: &[&[u32]],
        fab: &[&[u32]],
    ) -> Option<Vec<u32>> {
        let restrict = |t: &[u32]| -> Vec<u32> {
            let mut v: Vec<u32> = t
                .iter()
                .copied()
                .filter(|v| common.binary_search(v).is_ok())
                .collect();
            v.sort_unstable();
            v
        };
        let xa: Vec<Vec<u32>> = fa.iter().map(|t| restrict(t)).collect();
        let xb: Vec<Vec<u32>> = fb.iter().map(|t| restrict(t)).collect();
        let covered = |w: &[u32]| fab.iter().any(|z| subset(w, z));
        let mut best: Option<Vec<u32>> = None;
        for x in &xa {
            for y in &xb {
                let w: Vec<u32> = x.iter().copied().filter(|v| y.contains(v)).collect();
                if w.is_empty() || covered(&w) {
                    continue;
                }
                // Subsets of w by increasing size (|w| ≤ 15).
                let mut m = (0..1u32 << w.len()).collect::<Vec<_>>();
                m.sort_by_key(|s| s.count_ones());
                let first = m
                    .into_iter()
                    .skip(1)
                    .map(|s| {
                        (0..w.len())
                            .filter(|i| s >> i & 1 == 1)
                            .map(|i| w[i])
                            .collect::<Vec<u32>>()
                    })
                    .find(|s| !covered(s))
                    .unwrap_or(w);
                if best.as_ref().is_none_or(|b| first.len() < b.len()) {
                    best = Some(first);
                }
            }
        }
        best
    }
}

/// The cone vertex ω of [`LiveComplex::link_condition_with_boundary`] in reported simplices.
pub const OMEGA: u32 = u32::MAX - 1;

impl LiveComplex {
    /// The link condition on the complex coned over its boundary (DEGN 1999's dummy vertex ω):
    /// a boundary facet is a simplex that is a facet of exactly one simplex (a top simplex), and
    /// ω ∗ f is added for each. On 2- and 3-manifolds with boundary this is what keeps a
    /// contraction from pinching the boundary (joining two boundary vertices through the
    /// interior), so contractions that pass it keep manifoldness and the boundary's topology;
    /// on any complex it implies [`LiveComplex::link_condition`]. A failure naming ω reports it
    /// as [`OMEGA`]; a failure of the plain test is reported as that test reports it (it is
    /// run first). Cost: the plain test, then O(d·k·log(d·k)) for each star's boundary facets
    /// and the word test again; allocates nothing once this thread's scratch is warm (up to 63
    /// common vertices).
    pub fn link_condition_with_boundary(&self, a: VertexId, b: VertexId) -> Result<(), Refusal> {
        self.checked_link(a, b, true)
    }

    /// The coned test with sorted id lists, for more than 64 common vertices (allocates).
    fn coned_by_lists(&self, a: u32, b: u32) -> Option<Vec<u32>> {
        let (mut fa, mut fab) = (Vec::new(), Vec::new());
        for t in self.star[a as usize].iter().map(|&r| self.top_raw(r)) {
            let set = t.iter().copied().filter(|&v| v != a && v != b).collect();
            if t.contains(&b) {
                fab.push(set)
            } else {
                fa.push(set)
            }
        }
        for f in self.boundary_facets(a) {
            let mut set: Vec<u32> = f.iter().copied().filter(|&v| v != a && v != b).collect();
            set.push(OMEGA);
            if f.contains(&b) {
                fab.push(set)
            } else {
                fa.push(set)
            }
        }
        let mut fb: Vec<Vec<u32>> = self.star[b as usize]
            .iter()
            .map(|&r| self.top_raw(r))
            .filter(|t| !t.contains(&a))
            .map(|t| t.iter().copied().filter(|&v| v != b).collect())
            .collect();
        for f in self.boundary_facets(b).filter(|f| !f.contains(&a)) {
            let mut set: Vec<u32> = f.iter().copied().filter(|&v| v != b).collect();
            set.push(OMEGA);
            fb.push(set);
        }
        let vs = |f: &[Vec<u32>]| {
            let mut v: Vec<u32> = f.iter().flatten().copied().collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        let vb = vs(&fb);
        let common: Vec<u32> = vs(&fa)
            .into_iter()
            .filter(|v| vb.binary_search(v).is_ok())
            .collect();
        lists::first_violation(&common, &refs(&fa), &refs(&fb), &refs(&fab))
    }

    /// The boundary facets through v: facets f ∋ v of a top t ∈ St*(v) that no other top holds
    /// ([`LiveComplex::star_boundary`]).
    fn boundary_facets(&self, v: u32) -> impl Iterator<Item = Vec<u32>> + '_ {
        let (mut facets, mut open) = (Vec::new(), Vec::new());
        self.star_boundary(v, &mut facets, &mut open);
        let star = &self.star[v as usize];
        star.iter().zip(open).flat_map(move |(&raw, open)| {
            let t = self.top_raw(raw);
            (0..t.len())
                .filter(move |j| open >> j & 1 == 1)
                .map(move |j| {
                    t.iter()
                        .enumerate()
                        .filter(|&(k, _)| k != j)
                        .map(|(_, &y)| y)
                        .collect::<Vec<u32>>()
                })
        })
    }
}

fn refs(f: &[Vec<u32>]) -> Vec<&[u32]> {
    f.iter().map(Vec::as_slice).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::Complex;
    use proptest::prelude::*;

    /// `count` simplices of `sizes` distinct vertices of `vertices`, each ascending.
    fn rows(
        vertices: std::ops::Range<u32>,
        sizes: std::ops::RangeInclusive<usize>,
        count: std::ops::Range<usize>,
    ) -> impl Strategy<Value = Vec<Vec<u32>>> {
        proptest::collection::vec(proptest::collection::btree_set(vertices, sizes), count)
            .prop_map(|v| v.into_iter().map(|t| t.into_iter().collect()).collect())
    }

    /// The boundary positions of every top of every star, by hashing and by comparing every
    /// pair (the oracle), on `simplices` over `n` vertices.
    fn assert_star_boundaries_agree(n: u32, simplices: &[Vec<u32>]) {
        let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
        let Ok(c) = Complex::from_simplices(n, &refs) else {
            return;
        };
        let live = LiveComplex::from_complex(&c);
        let (mut facets, mut open) = (Vec::new(), Vec::new());
        for v in 0..n {
            live.star_boundary(v, &mut facets, &mut open);
            let star = &live.star[v as usize];
            assert_eq!(open.len(), star.len());
            for (&r, &got) in star.iter().zip(&open) {
                assert_eq!(
                    got,
                    live.boundary_positions(v, r),
                    "vertex {v}, top {:?}",
                    live.top_raw(r)
                );
            }
        }
    }

    #[test]
    fn star_boundary_of_a_closed_and_an_open_tetrahedral_fan() {
        // Six tetrahedra around the cube's diagonal 0-7: no facet through 0 or 7 is interior
        // except the six fins; removing one tetrahedron opens the fan.
        let fan = [
            [0, 1, 3, 7],
            [0, 3, 2, 7],
            [0, 2, 6, 7],
            [0, 6, 4, 7],
            [0, 4, 5, 7],
            [0, 5, 1, 7],
        ];
        let all: Vec<Vec<u32>> = fan.iter().map(|t| t.to_vec()).collect();
        assert_star_boundaries_agree(8, &all);
        assert_star_boundaries_agree(8, &all[1..]);
        let c =
            Complex::from_simplices(8, &fan.iter().map(|t| &t[..]).collect::<Vec<_>>()).unwrap();
        let live = LiveComplex::from_complex(&c);
        let (mut facets, mut open) = (Vec::new(), Vec::new());
        live.star_boundary(0, &mut facets, &mut open);
        // Through 0, each tetrahedron shares its two fins (through 0 and 7) with its
        // neighbours; its one boundary facet leaves out 7, at position 3.
        assert_eq!(open, [1 << 3; 6]);
    }

    /// On every edge of `simplices`: the 0-dimensional shortcut finds a vertex exactly when
    /// the full test's lowest violation has dimension 0, and that vertex is one.
    fn assert_vertex_shortcut_agrees(n: u32, simplices: &[Vec<u32>]) {
        let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
        let Ok(c) = Complex::from_simplices(n, &refs) else {
            return;
        };
        let live = LiveComplex::from_complex(&c);
        let mut s = Scratch::default();
        for [a, b] in live.edges() {
            for (a, b) in [(a, b), (b, a)] {
                let quick = live.vertex_violation(a, b, &mut s);
                let full = live.full_violation(a, b, false, &mut s);
                match (quick, &full) {
                    (None, None) => {}
                    (None, Some(f)) => assert!(f.len() > 1, "{a} {b}: missed {f:?}"),
                    (Some(w), Some(f)) => {
                        assert_eq!(f.len(), 1, "{a} {b}: {w} but full {f:?}");
                        assert!(live.joined(a, w) && live.joined(b, w));
                        assert!(!live.star[a as usize].iter().any(|&r| {
                            let t = live.top_raw(r);
                            t.contains(&b) && t.contains(&w)
                        }));
                    }
                    (Some(w), None) => panic!("{a} {b}: {w} but the full test passes"),
                }
            }
        }
    }

    /// On every ordered edge (a, b) of `simplices`, plain and coned: the test read from the
    /// smaller star gives the whole test's answer (the same simplex) whenever it decides.
    /// Returns how many it decided, plain and coned.
    fn assert_skewed_agrees(n: u32, simplices: &[Vec<u32>]) -> (usize, usize) {
        let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
        let Ok(c) = Complex::from_simplices(n, &refs) else {
            return (0, 0);
        };
        let live = LiveComplex::from_complex(&c);
        let mut s = Scratch::default();
        let mut decided = (0, 0);
        for [a, b] in live.edges() {
            for (a, b) in [(a, b), (b, a)] {
                for coned in [false, true] {
                    let whole = live.whole_violation(a, b, coned, &mut s);
                    if let Some(skewed) = live.skewed_violation(a, b, coned, usize::MAX, &mut s) {
                        assert_eq!(skewed, whole, "{a} {b} coned {coned}");
                        if coned {
                            decided.1 += 1;
                        } else {
                            decided.0 += 1;
                        }
                    }
                }
            }
        }
        decided
    }

    /// A cone from vertex 0 over `base` (triangles and edges on vertices 1..n), beside
    /// `others`: vertex 0's star is as large as the base, the rest small, as simplify makes
    /// them.
    fn coned_over(base: &[Vec<u32>], others: &[Vec<u32>]) -> Vec<Vec<u32>> {
        base.iter()
            .map(|f| std::iter::once(0).chain(f.iter().copied()).collect())
            .chain(others.iter().cloned())
            .collect()
    }

    proptest! {
        /// Random mixed complexes on 8 vertices (up to 3-simplices, so facets are shared often
        /// and larger tops hold smaller tops' facets): on every ordered edge, plain and coned,
        /// the skewed test and the 0-dimensional shortcut agree with the whole test, and every
        /// star's boundary with comparing every pair.
        #[test]
        fn link_tests_agree_with_the_whole_test_on_random_complexes(
            simplices in rows(0u32..8, 2..=4, 1..14)
        ) {
            assert_skewed_agrees(8, &simplices);
            assert_vertex_shortcut_agrees(8, &simplices);
            assert_star_boundaries_agree(8, &simplices);
        }

        /// Vertex 0 with a large star (a cone over up to 80 random triangles and edges on 30
        /// vertices, so that it has boundary facets or none) beside random small simplices.
        #[test]
        fn skewed_link_test_matches_the_whole_test_around_a_large_star(
            base in rows(1u32..30, 2..=3, 20..80),
            others in rows(1u32..30, 2..=4, 0..10),
        ) {
            let all = coned_over(&base, &others);
            assert_skewed_agrees(30, &all);
        }
    }

    /// The skewed test decides (is not sent to the whole test) on a closed fan and an open one,
    /// plain and coned, so the agreement above is not vacuous.
    #[test]
    fn skewed_link_test_decides_on_closed_and_open_fans() {
        // The boundary of an octahedron on 1..=6, coned from 0 (a closed ball around 0), and
        // the same with one triangle left out (0 on the boundary).
        let octahedron: Vec<Vec<u32>> = [
            [1, 2, 3],
            [1, 3, 4],
            [1, 4, 5],
            [1, 5, 2],
            [6, 2, 3],
            [6, 3, 4],
            [6, 4, 5],
            [6, 5, 2],
        ]
        .iter()
        .map(|t| t.to_vec())
        .collect();
        let (plain, coned) = assert_skewed_agrees(7, &coned_over(&octahedron, &[]));
        assert!(plain > 0 && coned > 0, "{plain} {coned}");
        let (plain, coned) = assert_skewed_agrees(7, &coned_over(&octahedron[1..], &[]));
        assert!(plain > 0 && coned > 0, "{plain} {coned}");
    }

    proptest! {
        /// Random triangle soups (stars of triangles only, so the fan comparison answers;
        /// up to 30 triangles on 9 vertices, so some stars exceed it and are hashed).
        #[test]
        fn star_boundary_of_triangle_soups_matches_comparing_every_pair(
            simplices in rows(0u32..9, 3..=3, 1..30)
        ) {
            assert_star_boundaries_agree(9, &simplices);
        }
    }
}
