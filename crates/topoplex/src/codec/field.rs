//! [`Field`]: how one field of a structure is saved and read back, so that a structure's
//! [`super::Persist`] impl is the list of its fields ([`crate::persist_fields`]).

use super::{Arr, Reader, StoreError, Writer};
use crate::complex::SimplexTable;

/// A value saved as one or more sections.
pub trait Field: Sized {
    /// Appends the value.
    fn put(&self, w: &mut Writer);
    /// Reads it back.
    fn get(r: &mut Reader) -> Result<Self, StoreError>;
}

impl Field for u32 {
    fn put(&self, w: &mut Writer) {
        w.scalar(*self as u64);
    }
    fn get(r: &mut Reader) -> Result<Self, StoreError> {
        r.u32("a count")
    }
}

impl Field for u8 {
    fn put(&self, w: &mut Writer) {
        w.scalar(*self as u64);
    }
    fn get(r: &mut Reader) -> Result<Self, StoreError> {
        Ok(r.bounded(u8::MAX as u64, "a small number")? as u8)
    }
}

impl Field for u64 {
    fn put(&self, w: &mut Writer) {
        w.scalar(*self);
    }
    fn get(r: &mut Reader) -> Result<Self, StoreError> {
        r.scalar()
    }
}

/// Counts and dimensions: bounded by 2^48 so that the shape checks' arithmetic on a hostile
/// value cannot overflow.
impl Field for usize {
    fn put(&self, w: &mut Writer) {
        w.scalar(*self as u64);
    }
    fn get(r: &mut Reader) -> Result<Self, StoreError> {
        Ok(r.bounded(1 << 48, "a count")? as usize)
    }
}

impl<T: bytemuck::Pod> Field for Arr<T> {
    fn put(&self, w: &mut Writer) {
        w.section::<T>(self);
    }
    fn get(r: &mut Reader) -> Result<Self, StoreError> {
        r.arr()
    }
}

/// Small vectors (per-dimension counts and the like) are copied back, not mapped.
macro_rules! small_vec {
    ($($t:ty),*) => {$(
        impl Field for Vec<$t> {
            fn put(&self, w: &mut Writer) {
                w.section::<$t>(self);
            }
            fn get(r: &mut Reader) -> Result<Self, StoreError> {
                Ok(r.arr::<$t>()?.to_vec())
            }
        }
    )*};
}
small_vec!(u8, u32, u64, usize);

impl Field for SimplexTable {
    fn put(&self, w: &mut Writer) {
        w.table(self);
    }
    fn get(r: &mut Reader) -> Result<Self, StoreError> {
        r.table()
    }
}

/// Per-dimension lists: their number, then each.
macro_rules! list {
    ($($t:ty),*) => {$(
        impl Field for Vec<$t> {
            fn put(&self, w: &mut Writer) {
                w.scalar(self.len() as u64);
                for x in self {
                    Field::put(x, w);
                }
            }
            fn get(r: &mut Reader) -> Result<Self, StoreError> {
                let n = r.bounded(super::MAX_SECTIONS, "list length")?;
                (0..n).map(|_| <$t as Field>::get(r)).collect()
            }
        }
    )*};
}
list!(Arr<u8>, Arr<u32>, Arr<u64>, SimplexTable);

impl<T: Field> Field for Option<T> {
    fn put(&self, w: &mut Writer) {
        w.scalar(self.is_some() as u64);
        if let Some(x) = self {
            x.put(w);
        }
    }
    fn get(r: &mut Reader) -> Result<Self, StoreError> {
        match r.bounded(1, "a presence flag")? {
            0 => Ok(None),
            _ => Ok(Some(T::get(r)?)),
        }
    }
}

/// For a `check` of [`crate::persist_fields`] (and a structure's validation): dimension `d` is at
/// most `max`, the highest its kind holds.
pub(crate) fn dimension_at_most(d: usize, max: usize) -> Result<(), String> {
    if d > max {
        return Err(format!("dimension {d} above {max}"));
    }
    Ok(())
}

/// Implements [`Field`] (and, with `check`, [`super::Persist`]) for a struct by listing its
/// fields in save order. `check` runs on the loaded value and names the first shape it breaks,
/// so that what `load` returns can be queried without a failed index (see the store's docs).
#[macro_export]
#[doc(hidden)]
macro_rules! persist_fields {
    ($ty:ty { $($f:ident),* $(,)? }) => {
        impl $crate::codec::Field for $ty {
            fn put(&self, w: &mut $crate::codec::Writer) {
                $( $crate::codec::Field::put(&self.$f, w); )*
            }
            fn get(r: &mut $crate::codec::Reader) -> Result<Self, $crate::codec::StoreError> {
                Ok(Self { $( $f: $crate::codec::Field::get(r)?, )* })
            }
        }
    };
    ($ty:ty { $($f:ident),* $(,)? } check $check:expr) => {
        $crate::persist_fields!($ty { $($f),* });
        impl $crate::codec::Persist for $ty {
            fn save(&self, w: &mut $crate::codec::Writer) {
                $crate::codec::Field::put(self, w);
            }
            fn load(r: &mut $crate::codec::Reader) -> Result<Self, $crate::codec::StoreError> {
                let s: $ty = $crate::codec::Field::get(r)?;
                let check: fn(&$ty) -> Result<(), String> = $check;
                check(&s).map_err(|e| r.corrupt(e))?;
                Ok(s)
            }
        }
    };
}
