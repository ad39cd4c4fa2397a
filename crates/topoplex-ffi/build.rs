//! Names the shared library's SONAME `libtopoplex.so.MAJOR` on Linux in every build, so that
//! the library a plain `cargo build` makes is the one the CMake package installs (which names
//! the file after the SONAME), whichever command built it.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if os == "linux" {
        let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_else(|_| "0".into());
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libtopoplex.so.{major}");
    }
}
