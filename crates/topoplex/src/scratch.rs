//! Per-thread pooled scratch buffers: queries take `&self` and keep no state in the structure,
//! so each call borrows its sets and stacks from its thread's pool ([`Scratch`]) and hands them
//! back on drop; after a first call of a given size the same call allocates nothing.

use std::cell::RefCell;
use std::thread::LocalKey;

/// A buffer that is reset and handed back between uses: the per-thread pools of [`Scratch`].
pub trait Pooled: Default + 'static {
    /// This type's pool on the current thread.
    fn pool() -> &'static LocalKey<RefCell<Vec<Self>>>;
    /// Empties the buffer, keeping its allocation.
    fn reset(&mut self);
    /// The allocation size kept (what the pool sorts by).
    fn capacity(&self) -> usize;
}

/// Buffers a thread keeps per type; more than this are dropped on return.
const POOL_CAP: usize = 32;

/// A scratch buffer taken from this thread's pool and returned to it on drop, so that queries
/// (which take `&self` and keep no state in the structure) reuse the same allocations call after
/// call: after a first call of a given size, the same call allocates nothing. Reentrant: a nested
/// query takes another buffer from the pool (or a fresh one).
pub struct Scratch<T: Pooled>(Option<T>);

impl<T: Pooled> Scratch<T> {
    /// An empty buffer from the pool.
    pub fn take() -> Scratch<T> {
        let kept = T::pool()
            .try_with(|p| p.try_borrow_mut().ok().and_then(|mut p| p.pop()))
            .ok()
            .flatten();
        Scratch(Some(kept.unwrap_or_default()))
    }
}

impl<T: Pooled> Drop for Scratch<T> {
    fn drop(&mut self) {
        if let Some(mut v) = self.0.take() {
            v.reset();
            // During thread teardown or while the pool is borrowed, the buffer is just freed.
            let _ = T::pool().try_with(|p| {
                // Kept by ascending capacity and taken from the top: a query nested k deep
                // gets the k-th largest buffer, so sizes settle after one pass.
                if let Ok(mut p) = p.try_borrow_mut()
                    && p.len() < POOL_CAP
                {
                    let at = p.partition_point(|x| x.capacity() <= v.capacity());
                    p.insert(at, v);
                }
            });
        }
    }
}

impl<T: Pooled> std::ops::Deref for Scratch<T> {
    type Target = T;
    fn deref(&self) -> &T {
        self.0.as_ref().expect("held until drop")
    }
}

impl<T: Pooled> std::ops::DerefMut for Scratch<T> {
    fn deref_mut(&mut self) -> &mut T {
        self.0.as_mut().expect("held until drop")
    }
}

/// Implements [`Pooled`] for `Vec<T>` with a thread-local pool per element type.
macro_rules! pooled_vec {
    ($($t:ty),*) => {$(
        impl $crate::scratch::Pooled for Vec<$t> {
            fn pool() -> &'static ::std::thread::LocalKey<::std::cell::RefCell<Vec<Self>>> {
                thread_local! {
                    static POOL: ::std::cell::RefCell<Vec<Vec<$t>>> =
                        const { ::std::cell::RefCell::new(Vec::new()) };
                }
                &POOL
            }
            fn reset(&mut self) {
                self.clear();
            }
            fn capacity(&self) -> usize {
                Vec::capacity(self)
            }
        }
    )*};
}
pub(crate) use pooled_vec;

pooled_vec!(u32, usize, bool, (u32, u32));
