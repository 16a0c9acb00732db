//! The README's "Using the core" code block is the marked region of `examples/readme.rs`
//! (between the `// [readme]` and `// [/readme]` lines), character for character, so the
//! README shows code that compiles and runs (`cargo run --example readme`).

use std::path::Path;

/// The lines strictly between the line `open` and the line `close` of `text`.
fn between<'a>(text: &'a str, open: &str, close: &str) -> Vec<&'a str> {
    let mut lines = text.lines();
    assert!(
        lines.by_ref().any(|l| l.trim_end() == open),
        "no line {open:?}"
    );
    let region: Vec<&str> = lines
        .by_ref()
        .take_while(|l| l.trim_end() != close)
        .collect();
    region
}

#[test]
fn readme_block_is_the_example_region() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let example = std::fs::read_to_string(root.join("examples/readme.rs")).expect("example");
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let code = between(&example, "// [readme]", "// [/readme]");
    assert!(code.len() > 10, "the example's region is empty");
    // The README's block: the fenced `rust` block right after the marker comment.
    let after_marker = between(
        &readme,
        "<!-- quoted from examples/readme.rs -->",
        "<!-- end -->",
    );
    let fenced: Vec<&str> = after_marker
        .iter()
        .copied()
        .skip_while(|l| *l != "```rust")
        .skip(1)
        .take_while(|l| *l != "```")
        .collect();
    assert_eq!(
        fenced.join("\n"),
        code.join("\n"),
        "README.md's \"Using the core\" block differs from examples/readme.rs's marked region; \
         copy the region into the README"
    );
}
