//! The only calls outside safe Rust besides the C ABI crate's: the memory map of saved files and
//! glibc's allocator knobs. Each `unsafe` block states why it is sound.
#![allow(unsafe_code)]

use std::fs::File;
use std::io;

/// Maps `file` read-only.
pub(crate) fn map_file(file: &File) -> io::Result<memmap2::Mmap> {
    // SAFETY: the map is read-only and every view into it is bounds-checked against its length.
    // Another process truncating or rewriting the file while it is mapped is the documented
    // hazard of every mmap (`save` writes a new file and renames it, so our own saves never
    // rewrite a mapped file in place).
    unsafe { memmap2::Mmap::map(file) }
}

/// Hands the pages of freed heap memory back to the system (glibc's `malloc_trim`; a no-op on
/// other C libraries and under Miri). [`crate::simplify::simplify_owned`] calls it after dropping
/// its input. Why: glibc raises its mmap threshold (up to 32 MB) each time it
/// frees a large mapped block, so a dropped input complex can sit in the heap below later
/// allocations and stay resident under the simplification's own arrays — measured at 1.2M
/// triangles, peak RSS 1.54× OpenMesh's without this and 1.0× with a fixed threshold, for the
/// same 0.94× peak heap. Cost: one pass over the heap's free blocks.
pub(crate) fn release_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu", not(miri)))]
    // SAFETY: malloc_trim takes no pointer and only returns free pages of glibc's own heap.
    unsafe {
        libc::malloc_trim(0);
    }
}

/// Fixes glibc's mmap threshold at 128 KiB for the whole process (`mallopt(M_MMAP_THRESHOLD)`;
/// a no-op on other C libraries and under Miri). For executables only: the `topoplex` CLI calls
/// it first thing in `main`; the library never does, since a host's malloc settings are the
/// host's. Why: glibc raises its threshold (up to 32 MB) each time a large mapped block is freed,
/// so once `simplify` drops its input complex the next large arrays are carved from the heaps,
/// and the worker threads' arenas keep their freed tops resident (`malloc_trim` does not trim
/// them). A fixed threshold maps every array above 128 KiB on its own and unmaps it on free:
/// measured on the 1.2M-triangle bunny in docs/benchmarks.md (Simplification).
/// Setting the threshold also turns glibc's dynamic adjustment of it (and of the trim
/// threshold) off. Call it before any thread starts.
pub fn fix_malloc_thresholds_for_executable() {
    #[cfg(all(target_os = "linux", target_env = "gnu", not(miri)))]
    // SAFETY: mallopt takes two integers and changes only glibc's own tuning parameters; it is
    // called by the executable's main before other threads exist.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024);
    }
}
