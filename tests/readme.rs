//! The README's C example is the file the C/C++ tests build and run.

#[test]
fn readme_c_example_is_examples_c_example_c() {
    let root = env!("CARGO_MANIFEST_DIR");
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let example = std::fs::read_to_string(format!("{root}/examples/c/example.c")).unwrap();
    let block = readme
        .split("```c\n")
        .nth(1)
        .and_then(|b| b.split("\n```").next())
        .expect("a ```c block in the README");
    assert_eq!(
        block,
        example.trim_end(),
        "README's C block differs from examples/c/example.c"
    );
}
