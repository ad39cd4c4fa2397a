//! Union–find over `0..n` (path halving, smaller root wins): O(α(n)) amortised per `find` and
//! `union`, 4 bytes per element. The concurrent form used by parallel builds is
//! [`crate::parallel::SharedUnionFind`].

/// Union–find over `0..n` with path halving; the smaller root wins, so the classes' roots do not
/// depend on the order of the unions.
pub(crate) struct UnionFind(Vec<u32>);

impl UnionFind {
    /// `n` singletons in `buf`'s allocation (cleared first); [`UnionFind::into_inner`] gives
    /// it back.
    pub(crate) fn reusing(mut buf: Vec<u32>, n: usize) -> Self {
        buf.clear();
        buf.extend(0..n as u32);
        UnionFind(buf)
    }

    /// The parent array, to reuse its allocation.
    pub(crate) fn into_inner(self) -> Vec<u32> {
        self.0
    }

    /// `n` singletons, or `Err(bytes asked for)` when the memory cannot be had.
    pub(crate) fn try_new(n: usize) -> Result<Self, usize> {
        let mut v = Vec::new();
        crate::alloc::try_reserve_exact(&mut v, n)?;
        v.extend(0..n as u32);
        Ok(UnionFind(v))
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
