//! Named data on a complex and on a live complex: integer labels and real fields on the
//! vertices and on the listed simplices ([`topoplex::complex::Attribute`]).
//!
//! On a `TpxComplex` the values are lent zero-copy (`tpx_complex_attribute_data`: a pointer
//! into the complex's own array, valid while the complex lives and no attribute of it is set or
//! removed) and set by copy (`tpx_complex_set_attribute`). On a `TpxLive` one element's row is
//! read or written by handle, as doubles.

use std::ffi::{CStr, c_char, c_void};

use super::complex::TpxComplex;
use super::live::TpxLive;
use super::{Failure, TpxStatus, guard, handle, in_slice, on, out_ptr, try_copy, write_buffer};
use topoplex::complex::attributes::MAX_COMPONENTS;
use topoplex::complex::{Attribute, Location, ValueType, Values};
use topoplex::live::{LiveComplex, Refusal, TopId, VertexPolicy};
use topoplex::relation::handle::VertexId;

/// Attribute location: one element per vertex id `0 .. n`.
pub const TPX_LOCATION_VERTICES: u32 = 0;
/// Attribute location: one element per simplex as listed, in input order (the listing of
/// `tpx_complex_listed_index`).
pub const TPX_LOCATION_LISTED: u32 = 1;

/// Attribute value type: `int32_t` (labels).
pub const TPX_VALUE_I32: u32 = 0;
/// Attribute value type: `int64_t` (labels).
pub const TPX_VALUE_I64: u32 = 1;
/// Attribute value type: `float`.
pub const TPX_VALUE_F32: u32 = 2;
/// Attribute value type: `double`.
pub const TPX_VALUE_F64: u32 = 3;

/// `tpx_complex_listed_index`'s answer for a simplex that was never listed (`SIZE_MAX`).
pub const TPX_NOT_LISTED: usize = SIZE_MAX;

const SIZE_MAX: usize = usize::MAX;

/// `tpx_live_set_vertex_policy`: a contraction {a, b} → a leaves a's vertex values as they are
/// (the default; b's stay in b's slot for a split).
pub const TPX_VERTEX_SURVIVOR: u32 = 0;
/// `tpx_live_set_vertex_policy`: a contraction {a, b} → a sets a's real vertex values to the
/// mean of a's and b's; labels stay a's.
pub const TPX_VERTEX_AVERAGE: u32 = 1;

/// What one attribute of a complex is (`tpx_complex_attribute_info`).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpxAttributeInfo {
    /// The name's UTF-8 bytes, lent (not NUL-terminated): valid while the complex lives and
    /// none of its attributes is set or removed.
    pub name: *const c_char,
    /// Length of `name` in bytes.
    pub name_len: usize,
    /// `TPX_LOCATION_VERTICES` or `TPX_LOCATION_LISTED`.
    pub location: u32,
    /// `TPX_VALUE_I32`, `TPX_VALUE_I64`, `TPX_VALUE_F32` or `TPX_VALUE_F64`.
    pub value_type: u32,
    /// Numbers per element (1 to 9).
    pub components: usize,
    /// Elements: the vertex count, or the number of listed simplices.
    pub elements: usize,
}

fn location_code(l: Location) -> u32 {
    match l {
        Location::Vertices => TPX_LOCATION_VERTICES,
        Location::Listed => TPX_LOCATION_LISTED,
    }
}

fn location_arg(code: u32) -> Result<Location, Failure> {
    match code {
        TPX_LOCATION_VERTICES => Ok(Location::Vertices),
        TPX_LOCATION_LISTED => Ok(Location::Listed),
        _ => Err(Failure::new(
            TpxStatus::InvalidArgument,
            format!("location {code} is not one of TPX_LOCATION_*"),
        )),
    }
}

fn type_code(t: ValueType) -> u32 {
    match t {
        ValueType::I32 => TPX_VALUE_I32,
        ValueType::I64 => TPX_VALUE_I64,
        ValueType::F32 => TPX_VALUE_F32,
        ValueType::F64 => TPX_VALUE_F64,
    }
}

/// A NUL-terminated UTF-8 name argument.
fn name_arg<'a>(p: *const c_char, what: &str) -> Result<&'a str, Failure> {
    if p.is_null() {
        return Err(Failure::null(what));
    }
    // SAFETY: a non-NULL name is NUL-terminated (documented contract of the callers).
    unsafe { CStr::from_ptr(p) }.to_str().map_err(|e| {
        Failure::new(
            TpxStatus::InvalidArgument,
            format!("`{what}` is not valid UTF-8: {e}"),
        )
    })
}

fn no_such(name: &str, where_: &str) -> Failure {
    Failure::new(
        TpxStatus::NoSuchAttribute,
        format!("no attribute '{}' {where_}", topoplex::error::echo(name)),
    )
}

/// Attribute `i` of `c`, or INVALID_ARGUMENT.
fn nth(c: &TpxComplex, i: usize) -> Result<&Attribute, Failure> {
    let a = c.complex.attributes();
    a.iter().nth(i).ok_or_else(|| {
        Failure::new(
            TpxStatus::InvalidArgument,
            format!("attribute {i}: the complex has {}", a.iter().len()),
        )
    })
}

/// Number of attributes of `c` into `*out` (indices `0 .. count` for the functions below, in
/// the order a file gives them, then those set). O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_attribute_count(
    c: *const TpxComplex,
    out: *mut usize,
) -> TpxStatus {
    super::get_into(c, "c", out, |c| c.complex.attributes().iter().len())
}

/// What attribute `i` of `c` is into `*out` (its name lent, see `TpxAttributeInfo`). Errors:
/// NULL_ARGUMENT, INVALID_ARGUMENT (`i` ≥ `tpx_complex_attribute_count`). O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_attribute_info(
    c: *const TpxComplex,
    i: usize,
    out: *mut TpxAttributeInfo,
) -> TpxStatus {
    on(c, "c", |c| {
        let out = out_ptr(out, "out")?;
        let a = nth(c, i)?;
        *out = TpxAttributeInfo {
            name: a.name.as_ptr().cast(),
            name_len: a.name.len(),
            location: location_code(a.location),
            value_type: type_code(a.values.value_type()),
            components: a.components,
            elements: a.element_count(),
        };
        Ok(())
    })
}

/// The index of the attribute called `name` (NUL-terminated UTF-8) at `location` into
/// `*out`. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (unknown location, name not UTF-8),
/// NO_SUCH_ATTRIBUTE. O(attributes × name length).
///
/// # Safety
/// Non-NULL pointers must be valid; `name` NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_attribute_find(
    c: *const TpxComplex,
    name: *const c_char,
    location: u32,
    out: *mut usize,
) -> TpxStatus {
    on(c, "c", |c| {
        let name = name_arg(name, "name")?;
        let location = location_arg(location)?;
        let out = out_ptr(out, "out")?;
        *out = c
            .complex
            .attributes()
            .iter()
            .position(|a| a.name == name && a.location == location)
            .ok_or_else(|| no_such(name, &format!("on the {}", location.describe())))?;
        Ok(())
    })
}

/// Lends the values of attribute `i` without a copy: `*out` points at the first number,
/// `*out_len` = elements × components numbers, of the attribute's type (cast `*out` to
/// `const int32_t *`, `const int64_t *`, `const float *` or `const double *` by
/// `TpxAttributeInfo::value_type`), element after element. Owned by the complex: valid until
/// `tpx_complex_free`, `tpx_complex_set_attribute` or `tpx_complex_remove_attribute` on it.
/// An attribute of no element lends a non-NULL dangling pointer with length 0. Errors:
/// NULL_ARGUMENT, INVALID_ARGUMENT (`i` out of range). O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_attribute_data(
    c: *const TpxComplex,
    i: usize,
    out: *mut *const c_void,
    out_len: *mut usize,
) -> TpxStatus {
    on(c, "c", |c| {
        let out = out_ptr(out, "out")?;
        let out_len = out_ptr(out_len, "out_len")?;
        let a = nth(c, i)?;
        let (p, n): (*const c_void, usize) = match &a.values {
            Values::I32(v) => (v.as_ptr().cast(), v.len()),
            Values::I64(v) => (v.as_ptr().cast(), v.len()),
            Values::F32(v) => (v.as_ptr().cast(), v.len()),
            Values::F64(v) => (v.as_ptr().cast(), v.len()),
        };
        *out = p;
        *out_len = n;
        Ok(())
    })
}

/// A copy of `count` numbers of type `value_type` at `data`.
fn copy_values(value_type: u32, data: *const c_void, count: usize) -> Result<Values, Failure> {
    // The `count` numbers at `data`, read as `T`.
    fn copied<T: Copy>(data: *const c_void, count: usize) -> Result<Vec<T>, Failure> {
        try_copy(in_slice(data.cast::<T>(), count, "data")?, "data")
    }
    Ok(match value_type {
        TPX_VALUE_I32 => Values::I32(copied(data, count)?),
        TPX_VALUE_I64 => Values::I64(copied(data, count)?),
        TPX_VALUE_F32 => Values::F32(copied(data, count)?),
        TPX_VALUE_F64 => Values::F64(copied(data, count)?),
        _ => {
            return Err(Failure::new(
                TpxStatus::InvalidArgument,
                format!("value type {value_type} is not one of TPX_VALUE_*"),
            ));
        }
    })
}

/// Sets attribute `name` (NUL-terminated UTF-8) at `location` of `c` to a copy of `data[0 ..
/// count]`: `count` numbers of `value_type`, `components` (1 to 9) per element, element after
/// element — one element per vertex (`TPX_LOCATION_VERTICES`, `count` = vertex count ×
/// components) or per listed simplex in input order (`TPX_LOCATION_LISTED`, `count` =
/// `TpxInputStats::input_simplices` × components). An attribute of the same name and location
/// is replaced (pointers lent from `c`'s attributes die); writers then carry it
/// (`tpx_complex_write`) or refuse it with FORMAT_CANNOT_HOLD. Errors (nothing changes):
/// NULL_ARGUMENT (`data` may be NULL only when `count` is 0), INVALID_ARGUMENT (unknown
/// location or type, name empty or not UTF-8, components out of 1..9, `count` not the elements
/// × components, a label name left naming no integer attribute: the message names the
/// attribute), TOO_LARGE (the copy cannot be allocated). Not to be called while another thread
/// reads `c`. Cost: O(count) copy; the replaced attribute is dropped.
///
/// # Safety
/// Non-NULL pointers must be valid; `data` holds `count` numbers of `value_type`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_set_attribute(
    c: *mut TpxComplex,
    name: *const c_char,
    location: u32,
    value_type: u32,
    components: usize,
    data: *const c_void,
    count: usize,
) -> TpxStatus {
    guard(|| {
        let c = out_ptr(c, "c")?;
        let name = name_arg(name, "name")?;
        let location = location_arg(location)?;
        let vertices = c.complex.vertex_count() as usize;
        let listed = c.complex.input_count();
        let invalid = |e: topoplex::complex::AttributeError| {
            Failure::new(TpxStatus::InvalidArgument, e.to_string())
        };
        // Its own shape first (what `Attributes::check` asks of it), so that only the label
        // names can refuse it below (replacing an integer attribute they name by reals).
        let want = match location {
            Location::Vertices => vertices,
            Location::Listed => listed,
        };
        let shape = if name.is_empty() {
            Some("the name is empty".to_string())
        } else if !(1..=MAX_COMPONENTS).contains(&components) {
            Some(format!(
                "{components} components, expected 1 to {MAX_COMPONENTS}"
            ))
        } else if want.checked_mul(components) != Some(count) {
            Some(format!(
                "{count} numbers, but {want} {} × {components} components need {}",
                location.describe(),
                want.saturating_mul(components)
            ))
        } else {
            None
        };
        // Checked before reading `data`: a wrong count never reads past the caller's array.
        if let Some(reason) = shape {
            let type_name = match value_type {
                TPX_VALUE_I32 => "i32",
                TPX_VALUE_I64 => "i64",
                TPX_VALUE_F32 => "f32",
                TPX_VALUE_F64 => "f64",
                _ => "an unknown type",
            };
            return Err(invalid(topoplex::complex::AttributeError {
                attribute: format!(
                    "'{}' (on {}, {type_name} × {components})",
                    topoplex::error::echo(name),
                    location.describe()
                ),
                reason,
            }));
        }
        let values = copy_values(value_type, data, count)?;
        let new = Attribute {
            name: name.to_string(),
            location,
            components,
            values,
        };
        let mut attributes = c.complex.take_attributes();
        let old = attributes
            .get(name, location)
            .filter(|o| o.values.value_type().is_integer() && !value_type_is_integer(value_type))
            .cloned();
        attributes.insert(new);
        if let Err(e) = attributes.check(vertices, listed) {
            if let Some(old) = old {
                attributes.insert(old);
            }
            c.complex
                .set_attributes(attributes)
                .expect("the attributes before were valid");
            return Err(invalid(e));
        }
        c.complex
            .set_attributes(attributes)
            .map_err(|e| Failure::new(TpxStatus::InvalidArgument, e.to_string()))
    })
}

fn value_type_is_integer(code: u32) -> bool {
    matches!(code, TPX_VALUE_I32 | TPX_VALUE_I64)
}

/// Removes the attributes called `name` (NUL-terminated UTF-8) at both locations and the names
/// of their labels. Pointers lent from `c`'s attributes die. Errors: NULL_ARGUMENT,
/// INVALID_ARGUMENT (name not UTF-8), NO_SUCH_ATTRIBUTE (nothing of that name; nothing
/// changes). Not to be called while another thread reads `c`. O(attributes).
///
/// # Safety
/// Non-NULL pointers must be valid; `name` NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_remove_attribute(
    c: *mut TpxComplex,
    name: *const c_char,
) -> TpxStatus {
    guard(|| {
        let c = out_ptr(c, "c")?;
        let name = name_arg(name, "name")?;
        let mut attributes = c.complex.take_attributes();
        let removed = attributes.remove(name);
        c.complex
            .set_attributes(attributes)
            .expect("removing keeps the attributes valid");
        if removed {
            Ok(())
        } else {
            Err(no_such(name, "to remove"))
        }
    })
}

/// The listing of the simplex with vertices `ids[0 .. len]` (any order) into `*out`: the
/// element of its values in the `TPX_LOCATION_LISTED` attributes — a top simplex's first
/// listing, or the first listing of a face listed on its own — or `TPX_NOT_LISTED`
/// (`SIZE_MAX`) for a simplex of the complex that was never listed, or no simplex of it.
/// Errors: NULL_ARGUMENT, INVALID_SIMPLEX (empty, more than 16 vertices, a repeated or
/// out-of-range vertex). Cost: a binary search in the top table (the first call builds the
/// listing maps), then for a non-top one among the absorbed listings (an index built on first
/// use, O(a log a)).
///
/// # Safety
/// Non-NULL pointers must be valid; `ids` holds `len` ids.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_listed_index(
    c: *const TpxComplex,
    ids: *const u32,
    len: usize,
    out: *mut usize,
) -> TpxStatus {
    on(c, "c", |c| {
        let ids = in_slice(ids, len, "ids")?;
        let out = out_ptr(out, "out")?;
        let n = c.complex.vertex_count();
        let bad =
            |why: &str| Failure::new(TpxStatus::InvalidSimplex, format!("simplex {ids:?}: {why}"));
        if ids.is_empty() || ids.len() > topoplex::complex::MAX_DIMENSION + 1 {
            return Err(bad("1 to 16 vertices expected"));
        }
        if let Some(v) = ids.iter().find(|&&v| v >= n) {
            return Err(bad(&format!("vertex {v} is out of range (0..{n})")));
        }
        if (1..ids.len()).any(|i| ids[..i].contains(&ids[i])) {
            return Err(bad("a vertex is repeated"));
        }
        *out = c.complex.listed_index(ids).unwrap_or(TPX_NOT_LISTED);
        Ok(())
    })
}

/// The name of label `label` of integer attribute `attribute` (NUL-terminated UTF-8) for
/// simplices of `dimension` (Gmsh `$PhysicalNames`), lent: `*out` points at its UTF-8 bytes
/// (not NUL-terminated), `*out_len` bytes, valid while `c` lives and none of its attributes is
/// set or removed; `*out` = NULL and `*out_len` = 0 when that label has no name. Errors:
/// NULL_ARGUMENT, INVALID_ARGUMENT (name not UTF-8). O(label names).
///
/// # Safety
/// Non-NULL pointers must be valid; `attribute` NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_label_name(
    c: *const TpxComplex,
    attribute: *const c_char,
    dimension: u32,
    label: i64,
    out: *mut *const c_char,
    out_len: *mut usize,
) -> TpxStatus {
    on(c, "c", |c| {
        let attribute = name_arg(attribute, "attribute")?;
        let out = out_ptr(out, "out")?;
        let out_len = out_ptr(out_len, "out_len")?;
        match c
            .complex
            .attributes()
            .label_name(attribute, dimension as usize, label)
        {
            Some(s) => {
                *out = s.as_ptr().cast();
                *out_len = s.len();
            }
            None => {
                *out = std::ptr::null();
                *out_len = 0;
            }
        }
        Ok(())
    })
}

/// The live top with packed id `top` (the handle API's numbering, as `tpx_live_top_vertices`
/// takes), as the live complex's own top handle. O(1).
fn live_top(live: &LiveComplex, top: u32) -> Result<TopId, Failure> {
    // The handle API's check first, for its statuses (INVALID_HANDLE, STALE_GENERATION).
    live.top_as_given_slice(topoplex::relation::handle::TopId(top))
        .map_err(super::structure::query_failure)?;
    live.top_of_packed(top).map_err(super::live::refusal)
}

/// How the rows of one kind of live element (tops or vertices) are read and written, and where
/// their attributes live (for NO_SUCH_ATTRIBUTE).
#[derive(Clone, Copy)]
struct LiveRows<K> {
    get: fn(&LiveComplex, &str, K) -> Result<Option<Values>, Refusal>,
    set: fn(&mut LiveComplex, &str, K, &[f64]) -> Result<bool, Refusal>,
    on: &'static str,
}

const TOP_ROWS: LiveRows<TopId> = LiveRows {
    get: LiveComplex::top_values,
    set: LiveComplex::set_top_values,
    on: "on the listed simplices",
};

const VERTEX_ROWS: LiveRows<VertexId> = LiveRows {
    get: LiveComplex::vertex_values,
    set: LiveComplex::set_vertex_values,
    on: "on the vertices",
};

/// Attribute `name`'s row on live element `at`, or NO_SUCH_ATTRIBUTE.
fn live_row<K>(
    live: &LiveComplex,
    name: &str,
    at: K,
    rows: LiveRows<K>,
) -> Result<Values, Failure> {
    (rows.get)(live, name, at)
        .map_err(super::live::refusal)?
        .ok_or_else(|| no_such(name, rows.on))
}

/// Sets attribute `name`'s row on live element `at` to `data`, once `data` is checked to fit it
/// (nothing changes otherwise).
fn set_live_row<K: Copy>(
    live: &mut LiveComplex,
    name: &str,
    at: K,
    data: &[f64],
    rows: LiveRows<K>,
) -> Result<(), Failure> {
    let row = live_row(live, name, at, rows)?;
    check_row(name, &row, data)?;
    (rows.set)(live, name, at, data).map_err(super::live::refusal)?;
    Ok(())
}

/// Checks `data` as a row of attribute `name` whose row is now `row`: as many numbers as its
/// components, and for labels each an integer within the type.
fn check_row(name: &str, row: &Values, data: &[f64]) -> Result<(), Failure> {
    let len = data.len();
    if row.len() != len {
        return Err(Failure::new(
            TpxStatus::InvalidArgument,
            format!(
                "attribute '{}' has {} components, {len} numbers given",
                topoplex::error::echo(name),
                row.len()
            ),
        ));
    }
    let range = match row.value_type() {
        ValueType::I32 => Some((f64::from(i32::MIN), f64::from(i32::MAX))),
        ValueType::I64 => Some((-(2f64.powi(63)), 2f64.powi(63) - 1024.0)),
        _ => None,
    };
    if let Some((lo, hi)) = range
        && let Some(k) = data
            .iter()
            .position(|&y| y.fract() != 0.0 || !(lo..=hi).contains(&y))
    {
        return Err(Failure::new(
            TpxStatus::InvalidArgument,
            format!(
                "attribute '{}' holds {} labels: number {k} ({}) is not one",
                topoplex::error::echo(name),
                row.value_type().name(),
                data[k]
            ),
        ));
    }
    Ok(())
}

/// The numbers of `row` as doubles (exact but for `int64_t` beyond 2^53).
fn row_f64(row: &Values) -> Vec<f64> {
    (0..row.len()).filter_map(|i| row.real(i)).collect()
}

/// The values of listed attribute `name` (NUL-terminated UTF-8) on live top `top` (a top id of
/// `tpx_live_structure`'s numbering, as `tpx_live_top_vertices` takes; not an isolated vertex),
/// as doubles (labels converted, exact up to 2^53), copied into `buf` (`buf_len` doubles);
/// `*out_len` = the attribute's components. A top made by an edit has labels 0 and reals NaN
/// until set; a contraction's survivors keep theirs. Errors: NULL_ARGUMENT, INVALID_HANDLE /
/// STALE_GENERATION (no live top there), NO_SUCH_ATTRIBUTE (no listed attribute of that
/// name), BUFFER_TOO_SMALL (`*out_len` = components). O(components).
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` has room for `buf_len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_top_values(
    l: *const TpxLive,
    name: *const c_char,
    top: u32,
    buf: *mut f64,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    guard(|| {
        let live = handle(l, "l")?.live();
        let name = name_arg(name, "name")?;
        let out_len = out_ptr(out_len, "out_len")?;
        let t = live_top(live, top)?;
        let row = live_row(live, name, t, TOP_ROWS)?;
        write_buffer(&row_f64(&row), buf, buf_len, out_len)
    })
}

/// Sets the values of listed attribute `name` on live top `top` to `data[0 .. len]` (`len` =
/// its components; doubles rounded to `float` for a `TPX_VALUE_F32` attribute, and exact
/// integers within the type for a label attribute). Errors (nothing changes): NULL_ARGUMENT,
/// INVALID_HANDLE / STALE_GENERATION, NO_SUCH_ATTRIBUTE, INVALID_ARGUMENT (`len` is not the
/// components; for labels, a number with a fraction, NaN, infinite or out of the type's range). Needs exclusive access
/// to `l`. O(components).
///
/// # Safety
/// Non-NULL pointers must be valid; `data` holds `len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_set_top_values(
    l: *mut TpxLive,
    name: *const c_char,
    top: u32,
    data: *const f64,
    len: usize,
) -> TpxStatus {
    guard(|| {
        let live = out_ptr(l, "l")?.live_mut();
        let name = name_arg(name, "name")?;
        let data = in_slice(data, len, "data")?;
        let t = live_top(live, top)?;
        set_live_row(live, name, t, data, TOP_ROWS)
    })
}

/// The values of vertex attribute `name` on live vertex `v`, as doubles, copied into `buf`
/// (`buf_len` doubles); `*out_len` = components. A vertex added by an edit has labels 0 and
/// reals NaN. Errors: NULL_ARGUMENT, DEAD_VERTEX, NO_SUCH_ATTRIBUTE, BUFFER_TOO_SMALL. O(1)
/// plus the attribute lookup.
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` has room for `buf_len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_vertex_values(
    l: *const TpxLive,
    name: *const c_char,
    v: u32,
    buf: *mut f64,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    guard(|| {
        let live = handle(l, "l")?.live();
        let name = name_arg(name, "name")?;
        let out_len = out_ptr(out_len, "out_len")?;
        let row = live_row(live, name, VertexId(v), VERTEX_ROWS)?;
        write_buffer(&row_f64(&row), buf, buf_len, out_len)
    })
}

/// What later contractions {a, b} → a do to a's vertex values: `TPX_VERTEX_SURVIVOR` (the
/// default: a keeps its own) or `TPX_VERTEX_AVERAGE` (reals become the mean of a's and b's;
/// labels stay a's). Errors: NULL_ARGUMENT, INVALID_ARGUMENT (another number). Needs exclusive
/// access to `l`. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_set_vertex_policy(l: *mut TpxLive, policy: u32) -> TpxStatus {
    guard(|| {
        let live = out_ptr(l, "l")?.live_mut();
        let policy = match policy {
            TPX_VERTEX_SURVIVOR => VertexPolicy::Survivor,
            TPX_VERTEX_AVERAGE => VertexPolicy::Average,
            _ => {
                return Err(Failure::new(
                    TpxStatus::InvalidArgument,
                    format!("vertex policy {policy} is not one of TPX_VERTEX_*"),
                ));
            }
        };
        live.set_vertex_policy(policy);
        Ok(())
    })
}

/// Sets the values of vertex attribute `name` on live vertex `v` to `data[0 .. len]` (`len` =
/// its components; doubles rounded to `float` for a `TPX_VALUE_F32` attribute, and exact
/// integers within the type for a label attribute). Errors (nothing changes): NULL_ARGUMENT,
/// DEAD_VERTEX, NO_SUCH_ATTRIBUTE, INVALID_ARGUMENT (`len` is not the components; for labels,
/// a number with a fraction, NaN, infinite or out of the type's range). Needs exclusive access
/// to `l`. O(attributes + components).
///
/// # Safety
/// Non-NULL pointers must be valid; `data` holds `len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_set_vertex_values(
    l: *mut TpxLive,
    name: *const c_char,
    v: u32,
    data: *const f64,
    len: usize,
) -> TpxStatus {
    guard(|| {
        let live = out_ptr(l, "l")?.live_mut();
        let name = name_arg(name, "name")?;
        let data = in_slice(data, len, "data")?;
        set_live_row(live, name, VertexId(v), data, VERTEX_ROWS)
    })
}

/// A caller's merge of vertex values at a contraction {a, b} -> a
/// (`tpx_live_set_vertex_merge`): called with the caller's `user` pointer, the attribute's name
/// (NUL-terminated UTF-8, valid during the call), a and b, a's row (`components` doubles, to
/// change in place: what it leaves there is rounded to the attribute's type, integers
/// truncated) and b's row (read only).
pub type TpxVertexMerge = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        name: *const c_char,
        a: u32,
        b: u32,
        row_a: *mut f64,
        row_b: *const f64,
        components: usize,
    ),
>;

/// The caller's `user` pointer, handed back to its callback as given.
struct User(*mut c_void);
// SAFETY: the pointer is only handed back to the caller's callback, which the caller made safe
// to call from whatever thread edits the live complex (the contract of
// `tpx_live_set_vertex_merge`).
unsafe impl Send for User {}
// SAFETY: as above; Topoplex never dereferences it.
unsafe impl Sync for User {}

/// Later contractions {a, b} -> a merge a's vertex values by `merge`, called once per vertex
/// attribute before the contraction changes the complex, with `user` as given; the split
/// restores a's values as they were. Replaces the `TPX_VERTEX_*` policy until
/// `tpx_live_set_vertex_policy` is called again. `merge` and `user` must stay valid while the
/// live complex may contract (until the policy is set again or the live complex is freed); the
/// callback runs on the thread that calls `tpx_live_contract`, must not call back into this live
/// complex and must not unwind (a C++ exception thrown through it is undefined behaviour).
/// Errors: NULL_ARGUMENT (`l` or `merge` NULL). Needs exclusive access to `l`. O(1); each
/// contraction then costs one call and 2 x components doubles copied per vertex attribute.
///
/// # Safety
/// `l` is a valid live complex; `merge` is a valid function; see above for `user`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_set_vertex_merge(
    l: *mut TpxLive,
    merge: TpxVertexMerge,
    user: *mut c_void,
) -> TpxStatus {
    guard(|| {
        let live = out_ptr(l, "l")?.live_mut();
        let Some(merge) = merge else {
            return Err(Failure::new(TpxStatus::NullArgument, "merge is NULL"));
        };
        let user = User(user);
        live.set_vertex_merge(move |name, a, b, row_a, row_b| {
            let user = &user;
            // A name with a NUL byte reaches the callback cut at it.
            let cut = name.split('\0').next().unwrap_or_default();
            let name = std::ffi::CString::new(cut).unwrap_or_default();
            // SAFETY: the caller promised a valid function and pointer (see above); the rows
            // are `components` doubles each, live for the call.
            unsafe {
                merge(
                    user.0,
                    name.as_ptr(),
                    a,
                    b,
                    row_a.as_mut_ptr(),
                    row_b.as_ptr(),
                    row_a.len(),
                )
            };
        });
        Ok(())
    })
}
