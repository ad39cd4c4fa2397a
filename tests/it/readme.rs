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

#[test]
fn readme_cpp_live_example_is_examples_cpp_live_cpp() {
    let root = env!("CARGO_MANIFEST_DIR");
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let example = std::fs::read_to_string(format!("{root}/examples/cpp/live.cpp")).unwrap();
    let block = readme
        .split("```cpp\n")
        .skip(1)
        .filter_map(|b| b.split("\n```").next())
        .find(|b| b.contains("topoplex::Live") && b.contains("int main"))
        .expect("a whole ```cpp program with topoplex::Live in the README");
    assert_eq!(
        block,
        example.trim_end(),
        "README's C++ block differs from examples/cpp/live.cpp"
    );
}
