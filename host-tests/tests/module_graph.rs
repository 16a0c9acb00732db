//! No import cycle between the top-level folders of the core (`src/`).
//!
//! Reads every `src/**/*.rs` of this repository, takes the top-level folder of each file (a
//! module and its submodules count as one: `src/render/bands.rs` is `render`, `src/scene.rs`
//! is `scene`), collects the `crate::X` paths in its code (comments, doc comments and string
//! literals left out; `crate::{X, Y::z}` groups included) whose `X` is another top-level
//! folder, and fails naming a cycle if the graph of those references has one.
//!
//! Run it with `cargo test -p zscan-host --test module_graph`. It also prints the graph
//! (`-- --nocapture`), one line per folder and the folders it imports.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Folder → the folders its code names.
type Graph = BTreeMap<String, BTreeSet<String>>;

/// The code of a Rust source without its comments and the contents of its string and
/// character literals (so that `crate::` in a doc comment or a message is not a reference).
fn code_only(src: &str) -> String {
    let b = src.as_bytes();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if c == b'/' && b.get(i + 1) == Some(&b'*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == b'*' && b.get(i + 1) == Some(&b'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == b'r' && (b.get(i + 1) == Some(&b'"') || b.get(i + 1) == Some(&b'#')) {
            // A raw string r"…" or r#"…"#, unless `r#ident`.
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&b'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&b'"') {
                out.push(c as char);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= b.len() {
                    break;
                }
                if b[j] == b'"'
                    && b[j + 1..]
                        .iter()
                        .take(hashes)
                        .filter(|&&h| h == b'#')
                        .count()
                        == hashes
                {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            out.push_str("\"\"");
            i = j;
        } else if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == b'\'' {
            // A character literal ('x', '\n', '\u{..}'), or a lifetime ('a): skip the former.
            let close = if b.get(i + 1) == Some(&b'\\') {
                b[i + 2..]
                    .iter()
                    .position(|&x| x == b'\'')
                    .map(|p| i + 2 + p)
            } else if b.get(i + 2) == Some(&b'\'') {
                Some(i + 2)
            } else {
                // A multi-byte character: its UTF-8 bytes, then the quote.
                let ch = src[i + 1..].chars().next();
                ch.and_then(|ch| {
                    let end = i + 1 + ch.len_utf8();
                    (b.get(end) == Some(&b'\'') && ch.len_utf8() > 1).then_some(end)
                })
            };
            match close {
                Some(end) => {
                    out.push_str("' '");
                    i = end + 1;
                }
                None => {
                    out.push('\'');
                    i += 1;
                }
            }
        } else {
            // Copy one whole character.
            let ch = src[i..].chars().next().unwrap();
            out.push(ch);
            i += ch.len_utf8();
        }
    }
    out
}

/// The first path segments `X` of every `crate::X…` in `code`, including each member of a
/// `crate::{X, Y::z, …}` group (members' own nested groups are not first segments).
fn crate_references(code: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        // Not the tail of a longer identifier (`my_crate::`).
        let before = rest[..at].chars().next_back();
        rest = &rest[at + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest_trim = rest.trim_start();
        if let Some(group) = rest_trim.strip_prefix('{') {
            // Top-level members of the group: split on commas at brace depth 0.
            let mut depth = 0;
            let mut start = 0;
            for (k, ch) in group.char_indices() {
                match ch {
                    '{' => depth += 1,
                    '}' if depth == 0 => {
                        names.insert(ident(group[start..k].trim()));
                        break;
                    }
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        names.insert(ident(group[start..k].trim()));
                        start = k + 1;
                    }
                    _ => {}
                }
            }
        } else {
            names.insert(ident(rest_trim));
        }
    }
    names.remove("");
    names
}

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read a source folder") {
        let path = entry.expect("a folder entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level folder of a file under `src`: its first component, without `.rs`.
fn folder_of(src: &Path, file: &Path) -> String {
    let first = file.strip_prefix(src).unwrap().components().next().unwrap();
    let name = first.as_os_str().to_str().unwrap();
    name.strip_suffix(".rs").unwrap_or(name).to_string()
}

/// The graph of `crate::` references between the top-level folders of the core.
fn core_graph() -> Graph {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../src");
    let src = src.canonicalize().expect("the core's src folder");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let folders: BTreeSet<String> = files.iter().map(|f| folder_of(&src, f)).collect();
    let mut graph = Graph::new();
    for file in &files {
        let from = folder_of(&src, file);
        let text = std::fs::read_to_string(file).expect("read a source file");
        let edges = graph.entry(from.clone()).or_default();
        for to in crate_references(&code_only(&text)) {
            if to != from && folders.contains(&to) {
                edges.insert(to);
            }
        }
    }
    graph
}

/// A cycle of `graph` as the list of its folders (the first repeated at the end), or `None`.
fn find_cycle(graph: &Graph) -> Option<Vec<String>> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    fn visit<'g>(
        node: &'g str,
        graph: &'g Graph,
        marks: &mut BTreeMap<&'g str, Mark>,
        path: &mut Vec<&'g str>,
    ) -> Option<Vec<String>> {
        marks.insert(node, Mark::Open);
        path.push(node);
        for next in graph.get(node).into_iter().flatten() {
            match marks.get(next.as_str()).copied().unwrap_or(Mark::New) {
                Mark::Open => {
                    let start = path.iter().position(|n| *n == next.as_str()).unwrap();
                    let mut cycle: Vec<String> =
                        path[start..].iter().map(|s| s.to_string()).collect();
                    cycle.push(next.clone());
                    return Some(cycle);
                }
                Mark::New => {
                    if let Some(c) = visit(next, graph, marks, path) {
                        return Some(c);
                    }
                }
                Mark::Done => {}
            }
        }
        path.pop();
        marks.insert(node, Mark::Done);
        None
    }
    let mut marks = BTreeMap::new();
    for node in graph.keys() {
        if marks.get(node.as_str()).copied().unwrap_or(Mark::New) == Mark::New {
            if let Some(c) = visit(node, graph, &mut marks, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

fn graph_of(edges: &[(&str, &str)]) -> Graph {
    let mut g = Graph::new();
    for (a, b) in edges {
        g.entry(a.to_string()).or_default().insert(b.to_string());
        g.entry(b.to_string()).or_default();
    }
    g
}

#[test]
fn no_import_cycle_between_top_level_folders() {
    let graph = core_graph();
    for (from, to) in &graph {
        println!(
            "{from} -> {}",
            to.iter().cloned().collect::<Vec<_>>().join(", ")
        );
    }
    // The graph is the real one: the folders are there and reference each other.
    for (from, to) in [
        ("render", "raster"),
        ("visibility", "render"),
        ("raster", "output"),
    ] {
        assert!(
            graph.get(from).is_some_and(|t| t.contains(to)),
            "{from} should import {to}: the reader missed references"
        );
    }
    if let Some(cycle) = find_cycle(&graph) {
        panic!(
            "import cycle between top-level folders of src/: {}",
            cycle.join(" -> ")
        );
    }
}

/// The cycle finder on hand-made graphs: it finds a cycle where there is one (of two nodes,
/// of three, a self-contained one beside an acyclic part) and none in a graph without.
#[test]
fn cycle_finder_finds_cycles() {
    let acyclic = graph_of(&[("a", "b"), ("b", "c"), ("a", "c"), ("d", "a")]);
    assert_eq!(find_cycle(&acyclic), None);
    let two = graph_of(&[("a", "b"), ("b", "a")]);
    assert_eq!(find_cycle(&two).unwrap(), ["a", "b", "a"]);
    let three = graph_of(&[("x", "a"), ("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")]);
    let cycle = find_cycle(&three).unwrap();
    assert_eq!(cycle.first(), cycle.last());
    assert_eq!(cycle.len(), 4, "{cycle:?}");
    for n in ["a", "b", "c"] {
        assert!(cycle.contains(&n.to_string()), "{cycle:?}");
    }
}

/// The reader: references in code count, in comments and strings not; groups count each
/// member's first segment.
#[test]
fn reader_takes_code_references_only() {
    let src = r#"
//! See [`x`](crate::docs_only).
use crate::alpha::Thing;
use crate::{beta, gamma::{One, Two}, delta::Three};
/* crate::block_comment */
fn f() -> u8 {
    let s = "crate::in_a_string";
    let c = '"';
    let t = my_crate::not_this;
    crate::epsilon::call(); // crate::after_code
    b'x'
}
"#;
    let refs = crate_references(&code_only(src));
    let want: BTreeSet<String> = ["alpha", "beta", "gamma", "delta", "epsilon"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_eq!(refs, want);
}
