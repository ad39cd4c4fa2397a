//! Helpers several structures share: the union–find. (Walking scratch sets live in
//! [`super::ia`] for now; see issue 13, step 6.)

/// Union–find over `0..n` with path halving; the smaller root wins, so the classes' roots do not
/// depend on the order of the unions.
pub(crate) struct UnionFind(Vec<u32>);

impl UnionFind {
    /// `n` singletons.
    pub(crate) fn new(n: usize) -> Self {
        UnionFind((0..n as u32).collect())
    }

    /// The root of `x`'s class.
    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let up = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = up;
            x = up;
        }
        x
    }

    /// Merges the classes of `a` and `b`.
    pub(crate) fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra < rb {
            self.0[rb as usize] = ra;
        } else if rb < ra {
            self.0[ra as usize] = rb;
        }
    }
}
