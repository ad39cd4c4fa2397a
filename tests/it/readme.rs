//! The README's C example is the file the C/C++ tests build and run.

/// Asserts that the README's code block that `block` picks out is the example file `path`
/// (from the repository root), to its last newline.
fn assert_readme_block_is(path: &str, block: impl FnOnce(&str) -> Option<&str>) {
    let root = env!("CARGO_MANIFEST_DIR");
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let example = std::fs::read_to_string(format!("{root}/{path}")).unwrap();
    let block = block(&readme).unwrap_or_else(|| panic!("no README block for {path}"));
    assert_eq!(
        block,
        example.trim_end(),
        "a README block differs from {path}"
    );
}

#[test]
fn readme_c_example_is_examples_c_example_c() {
    assert_readme_block_is("examples/c/example.c", |readme| {
        // The first ```c block.
        readme.split("```c\n").nth(1)?.split("\n```").next()
    });
}

#[test]
fn readme_cpp_live_example_is_examples_cpp_live_cpp() {
    assert_readme_block_is("examples/cpp/live.cpp", |readme| {
        // The whole ```cpp program with topoplex::Live.
        readme
            .split("```cpp\n")
            .skip(1)
            .filter_map(|b| b.split("\n```").next())
            .find(|b| b.contains("topoplex::Live") && b.contains("int main"))
    });
}
