//! Fallible allocation: the one family of reservations that turn "out of memory" into `Err(bytes
//! asked for)`, so a build or a read fails with an error naming the array instead of aborting
//! the host process. Structure builds turn the bytes into `BuildError::TooLarge`, readers into
//! `ReadErrorKind::TooLarge`; [`crate::parallel::headroom`] probes a step's peak before it
//! starts.

/// The `allocation failed` abort for `bytes`, for the infallible forms of fallible functions.
pub(crate) fn abort_for(bytes: usize) -> ! {
    std::alloc::handle_alloc_error(
        std::alloc::Layout::array::<u8>(bytes).unwrap_or(std::alloc::Layout::new::<u8>()),
    )
}

/// `v.reserve_exact(extra)` made fallible: `Err(bytes asked for)` when the memory cannot be had.
/// With [`try_grow`] and [`try_push`], the one family of fallible reservations: structure builds
/// turn the bytes into `BuildError::TooLarge`, readers into `ReadErrorKind::TooLarge`.
pub fn try_reserve_exact<T>(v: &mut Vec<T>, extra: usize) -> Result<(), usize> {
    v.try_reserve_exact(extra)
        .map_err(|_| extra.saturating_mul(size_of::<T>()))
}

/// `v.reserve(extra)` made fallible (amortised: the capacity at least doubles when it grows),
/// for arrays whose final length the input decides but no count gives in advance; `Err(bytes
/// asked for)` when the memory cannot be had. Free when the capacity suffices.
#[inline]
pub fn try_grow<T>(v: &mut Vec<T>, extra: usize) -> Result<(), usize> {
    if v.capacity() - v.len() >= extra {
        return Ok(());
    }
    v.try_reserve(extra).map_err(|_| {
        v.len()
            .saturating_add(extra)
            .max(v.capacity().saturating_mul(2))
            .saturating_mul(size_of::<T>())
    })
}

/// `v.push(x)` whose growth is reserved fallibly ([`try_grow`]).
#[inline]
pub fn try_push<T>(v: &mut Vec<T>, x: T) -> Result<(), usize> {
    try_grow(v, 1)?;
    v.push(x);
    Ok(())
}

/// `v.extend_from_slice(xs)` whose growth is reserved fallibly ([`try_grow`]).
#[inline]
pub fn try_extend<T: Clone>(v: &mut Vec<T>, xs: &[T]) -> Result<(), usize> {
    try_grow(v, xs.len())?;
    v.extend_from_slice(xs);
    Ok(())
}
