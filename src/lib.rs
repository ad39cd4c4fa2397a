//! `topoplex report`: the census, storage and timings of every structure on a complex, as
//! Markdown, JSON or SVG. The command-line tool (src/main.rs) is this package's binary.

#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod report;
