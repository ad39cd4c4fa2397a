//! `tpx_simplify`, `tpx_simplify_file`: quadric-error edge-contraction simplification
//! ([`topoplex::simplify`]) through the C ABI.

use std::ffi::c_char;

use super::{Failure, TpxComplex, TpxStatus, build_into, guard, out_ptr, path_arg};
use topoplex::complex::Complex;
use topoplex::io::write::{WriteError, WriteErrorKind, write_complex};
use topoplex::simplify::{Options, SimplifyError, check, check_output, simplify, simplify_owned};

fn simplify_failure(e: SimplifyError) -> Failure {
    let status = match e {
        SimplifyError::Ratio(_) => TpxStatus::InvalidRatio,
        SimplifyError::Memory { .. } => TpxStatus::TooLarge,
        _ => TpxStatus::CannotSimplify,
    };
    Failure::new(status, e.to_string())
}

fn options(ratio: f64, preserve_topology: bool) -> Result<Options, Failure> {
    if !(ratio > 0.0 && ratio <= 1.0) {
        return Err(simplify_failure(SimplifyError::Ratio(ratio)));
    }
    Ok(Options::new(ratio, preserve_topology))
}

/// Simplifies `complex` by quadric-error edge contraction (Garland–Heckbert, generalised to
/// simplices of any dimension in any coordinate dimension) until about `ratio` × its top
/// simplices remain (`ceil(ratio × count)`, or fewer contractions when no edge is left, or,
/// with `preserve_topology`, none satisfies the link condition). With `preserve_topology`
/// every contraction satisfies the link condition in every dimension, so the Betti numbers and
/// 2-/3-manifoldness are kept. `complex` is not changed.
///
/// On success `*out` receives a new complex owned by the caller (free with
/// `tpx_complex_free`), with coordinates, vertices renumbered densely in ascending old id
/// order. Errors: NULL_ARGUMENT, INVALID_RATIO (`ratio` not in (0, 1]), CANNOT_SIMPLIFY (no
/// coordinates, a non-finite coordinate, too many top simplices), TOO_LARGE (the live complex's
/// arrays cannot be allocated). Cost: O(E log E) for E edges
/// plus the contractions (see the `simplify` module documentation); memory about the live
/// complex plus (n + 1)(n + 2) / 2 doubles per vertex for n coordinates.
///
/// # Safety
/// `complex` must be NULL or a live `TpxComplex`; `out` NULL or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_simplify(
    complex: *const TpxComplex,
    ratio: f64,
    preserve_topology: bool,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    build_into(complex, "complex", out, |c| {
        let options = options(ratio, preserve_topology)?;
        let done = simplify(&c.complex, &options, &mut |_, _| {}).map_err(simplify_failure)?;
        Ok(TpxComplex {
            complex: done.complex,
        })
    })
}

/// Simplifies `complex` in place, as `tpx_simplify` does: its content is replaced by the
/// result. The input is released as soon as the editable copy is built, so the peak memory
/// holds one copy of it, not two (use this when the input is no longer needed).
///
/// Errors (the complex is then unchanged): NULL_ARGUMENT, INVALID_RATIO, CANNOT_SIMPLIFY,
/// TOO_LARGE.
/// After PANIC (an internal bug) the complex holds a single isolated vertex. Cost: as
/// `tpx_simplify`.
///
/// # Safety
/// `complex` must be NULL or a live `TpxComplex` that no other thread uses during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_simplify_in_place(
    complex: *mut TpxComplex,
    ratio: f64,
    preserve_topology: bool,
) -> TpxStatus {
    guard(|| {
        let c = out_ptr(complex, "complex")?;
        let options = options(ratio, preserve_topology)?;
        check(&c.complex, &options).map_err(simplify_failure)?;
        let placeholder = Complex::from_simplices(1, &[]).expect("one isolated vertex");
        let input = std::mem::replace(&mut c.complex, placeholder);
        match simplify_owned(input, &options, &mut |_, _| {}) {
            Ok(done) => {
                c.complex = done.complex;
                Ok(())
            }
            // `check` passed, so this is a bug: the input is gone, report it as such.
            Err(e) => Err(Failure::new(TpxStatus::Panic, e.to_string())),
        }
    })
}

/// Reads `input`, simplifies it as `tpx_simplify` does and writes the result to `output`, the
/// format chosen by its extension (any format the writers know: `.off`, `.obj`, `.mesh`,
/// `.simplices`, ...). Both paths are NUL-terminated UTF-8. The output's format and
/// writability are checked before any work; on failure no new file is left behind.
///
/// Errors: NULL_ARGUMENT, INVALID_ARGUMENT (a path not UTF-8), INVALID_RATIO, IO_ERROR /
/// PARSE_ERROR / INVALID_COMPLEX (reading `input`, as `tpx_complex_from_file`),
/// CANNOT_SIMPLIFY, TOO_LARGE, UNKNOWN_FORMAT (the output's extension names no format),
/// FORMAT_CANNOT_HOLD (the format cannot hold a complex of the input's dimension or
/// coordinates), WRITE_ERROR (the file system refused the output; the message names the path).
/// Cost: `tpx_simplify` plus reading and writing.
///
/// # Safety
/// `input` and `output` must be NULL or NUL-terminated strings.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_simplify_file(
    input: *const c_char,
    output: *const c_char,
    ratio: f64,
    preserve_topology: bool,
) -> TpxStatus {
    guard(|| {
        let input = path_arg(input, "input")?;
        let output = path_arg(output, "output")?;
        let options = options(ratio, preserve_topology)?;
        let complex = topoplex::store::open_complex(input, Default::default())
            .map_err(super::complex::open_failure)?;
        let write_failure = |e: WriteError| {
            let status = match e.kind {
                WriteErrorKind::Io(_) => TpxStatus::WriteError,
                WriteErrorKind::UnknownExtension => TpxStatus::UnknownFormat,
                WriteErrorKind::CannotHold { .. } => TpxStatus::FormatCannotHold,
            };
            Failure::new(status, e.to_string())
        };
        let existed = output.exists();
        check_output(output, &complex).map_err(write_failure)?;
        let done = simplify_owned(complex, &options, &mut |_, _| {});
        let written = done
            .map_err(simplify_failure)
            .and_then(|d| write_complex(&d.complex, output, None).map_err(write_failure));
        if written.is_err() && !existed {
            let _ = std::fs::remove_file(output);
        }
        written
    })
}
