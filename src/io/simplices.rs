//! Reader stub (to be written).
use super::{RawInput, ReadErrorKind};

pub fn parse(_text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    Err((
        0,
        ReadErrorKind::Syntax("reader not implemented yet".into()),
    ))
}
