#![no_main]
//! Differential: every structure built from an arbitrary simplex list answers every relation
//! exactly like the brute-force oracle. Invalid lists must be refused with a named error.
use libfuzzer_sys::fuzz_target;
use topoplex::{Complex, ComplexError};

fuzz_target!(|data: &[u8]| {
    let (n, list) = topoplex_fuzz_support::decode(data);
    let refs: Vec<&[u32]> = list.iter().map(Vec::as_slice).collect();
    match Complex::from_simplices(n, &refs) {
        Ok(c) => topoplex_fuzz_support::check_complex(&c),
        Err(
            ComplexError::RepeatedVertex { .. }
            | ComplexError::VertexOutOfRange { .. }
            | ComplexError::EmptySimplex { .. },
        ) => {}
        Err(e) => panic!("unexpected complex error {e}"),
    }
});
