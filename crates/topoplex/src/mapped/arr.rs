//! [`Arr`]: the array type of every large structure field, owned after a build or a view into a
//! mapped `.tpx` file after an open.

use std::fmt;
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut};
use std::sync::Arc;

use super::Backing;

/// An array that is either owned (`Vec<T>`) or a read-only view into a saved file's bytes, so an
/// opened structure costs the pages its queries touch. Derefs to `[T]` either way; mutable
/// access to a mapped array first copies it (copy on write), so a mapped file is never written.
pub enum Arr<T: bytemuck::Pod> {
    /// Built in memory.
    Owned(Vec<T>),
    /// `len` elements at byte `start` of an opened file; `start` was checked to be aligned and
    /// in bounds when the file was opened, so every deref succeeds.
    Mapped {
        /// The opened file's bytes, shared by every array of the file.
        backing: Arc<Backing>,
        /// Byte offset of the first element.
        start: usize,
        /// Number of elements.
        len: usize,
        /// The element type.
        _t: PhantomData<T>,
    },
}

impl<T: bytemuck::Pod> Arr<T> {
    /// An empty owned array, usable in constants.
    pub const fn new() -> Self {
        Arr::Owned(Vec::new())
    }

    /// Elements the array can hold without reallocating (its length once mapped): what
    /// `storage()` counts.
    pub fn capacity(&self) -> usize {
        match self {
            Arr::Owned(v) => v.capacity(),
            Arr::Mapped { len, .. } => *len,
        }
    }

    /// Whether the elements live in an opened file rather than on the heap.
    pub fn is_mapped(&self) -> bool {
        matches!(self, Arr::Mapped { .. })
    }

    /// The owned vector to grow or edit in place (a mapped array is copied first): lets build
    /// code fill a field as it would a `Vec`.
    pub fn vec_mut(&mut self) -> &mut Vec<T> {
        if self.is_mapped() {
            *self = Arr::Owned(self.to_vec());
        }
        match self {
            Arr::Owned(v) => v,
            Arr::Mapped { .. } => unreachable!("copied above"),
        }
    }

    /// Appends an element (see [`Arr::vec_mut`]).
    pub fn push(&mut self, x: T) {
        self.vec_mut().push(x);
    }

    /// Appends elements (see [`Arr::vec_mut`]).
    pub fn extend_from_slice(&mut self, xs: &[T]) {
        self.vec_mut().extend_from_slice(xs);
    }

    /// Reserves room for `n` more elements (see [`Arr::vec_mut`]).
    pub fn reserve(&mut self, n: usize) {
        self.vec_mut().reserve(n);
    }

    /// Reserves room for exactly `n` more elements (see [`Arr::vec_mut`]).
    pub fn reserve_exact(&mut self, n: usize) {
        self.vec_mut().reserve_exact(n);
    }

    /// Shrinks the allocation to the length (no-op once mapped).
    pub fn shrink_to_fit(&mut self) {
        if let Arr::Owned(v) = self {
            v.shrink_to_fit();
        }
    }

    /// The owned vector, copying a mapped array.
    pub fn into_vec(self) -> Vec<T> {
        match self {
            Arr::Owned(v) => v,
            mapped => mapped.to_vec(),
        }
    }
}

impl<T: bytemuck::Pod> Deref for Arr<T> {
    type Target = [T];
    // Inlined: every walk reads its arrays through here, a call per read cost a fifth of a
    // degree pass; the mapped case stays out of line.
    #[inline]
    fn deref(&self) -> &[T] {
        match self {
            Arr::Owned(v) => v,
            Arr::Mapped { .. } => self.mapped(),
        }
    }
}

impl<T: bytemuck::Pod> Arr<T> {
    /// The elements of a mapped array (empty for an owned one).
    #[inline(never)]
    fn mapped(&self) -> &[T] {
        match self {
            Arr::Owned(_) => &[],
            Arr::Mapped {
                backing,
                start,
                len,
                ..
            } => bytemuck::cast_slice(&backing.bytes()[*start..*start + len * size_of::<T>()]),
        }
    }
}

impl<T: bytemuck::Pod> DerefMut for Arr<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        self.vec_mut()
    }
}

impl<T: bytemuck::Pod> Default for Arr<T> {
    fn default() -> Self {
        Arr::new()
    }
}

impl<T: bytemuck::Pod> Arr<T> {
    /// A clone whose copy (of an owned array) is reserved fallibly: `Err(bytes)` when it cannot
    /// be had. A mapped array is shared, never copied.
    pub fn try_clone(&self) -> Result<Self, usize> {
        match self {
            Arr::Owned(v) => {
                let mut c = Vec::new();
                c.try_reserve_exact(v.len())
                    .map_err(|_| v.len().saturating_mul(size_of::<T>()))?;
                c.extend_from_slice(v);
                Ok(Arr::Owned(c))
            }
            mapped => Ok(mapped.clone()),
        }
    }
}

impl<T: bytemuck::Pod> Clone for Arr<T> {
    fn clone(&self) -> Self {
        match self {
            Arr::Owned(v) => Arr::Owned(v.clone()),
            Arr::Mapped {
                backing,
                start,
                len,
                ..
            } => Arr::Mapped {
                backing: Arc::clone(backing),
                start: *start,
                len: *len,
                _t: PhantomData,
            },
        }
    }
}

impl<T: bytemuck::Pod + fmt::Debug> fmt::Debug for Arr<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&**self, f)
    }
}

impl<T: bytemuck::Pod + PartialEq> PartialEq for Arr<T> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<T: bytemuck::Pod + Eq> Eq for Arr<T> {}

impl<T: bytemuck::Pod> From<Vec<T>> for Arr<T> {
    fn from(v: Vec<T>) -> Self {
        Arr::Owned(v)
    }
}

impl<T: bytemuck::Pod> FromIterator<T> for Arr<T> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Self {
        Arr::Owned(iter.into_iter().collect())
    }
}

impl<'a, T: bytemuck::Pod> IntoIterator for &'a Arr<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<T: bytemuck::Pod> Extend<T> for Arr<T> {
    fn extend<I: IntoIterator<Item = T>>(&mut self, iter: I) {
        self.vec_mut().extend(iter);
    }
}

impl<T: bytemuck::Pod + PartialEq> PartialEq<Vec<T>> for Arr<T> {
    fn eq(&self, other: &Vec<T>) -> bool {
        **self == **other
    }
}

impl<T: bytemuck::Pod + PartialEq> PartialEq<Arr<T>> for Vec<T> {
    fn eq(&self, other: &Arr<T>) -> bool {
        **self == **other
    }
}
