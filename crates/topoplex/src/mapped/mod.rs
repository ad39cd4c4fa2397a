//! The owned-or-mapped array ([`Arr`]) and the bytes it may view ([`Backing`]): a structure's
//! fields are owned after a build and views into a memory-mapped `.tpx` file after an open.

mod arr;
pub use arr::Arr;

/// The bytes of an opened file: mapped, or (for [`crate::store::Saved::from_bytes`]) an aligned
/// heap copy.
pub enum Backing {
    /// A memory-mapped file.
    Map(memmap2::Mmap),
    /// Bytes held in 8-byte words (so every section's start is aligned), and their length.
    Heap(Vec<u64>, usize),
}

impl Backing {
    /// All bytes of the file.
    pub fn bytes(&self) -> &[u8] {
        match self {
            Backing::Map(m) => m,
            Backing::Heap(words, len) => &bytemuck::cast_slice(words)[..*len],
        }
    }
}
