//! Checks that the repository's documents say what the code is: the error contract lists every error
//! enum with every variant, the README's layout lists every crate of the workspace, and the facade's
//! prelude stays the small set of names a first program needs. Each reads the sources as text (paths
//! from this crate's manifest directory, `crates/noether`).

use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn read(path: impl AsRef<Path>) -> String {
    let path = root().join(path);
    fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|x| x == "rs") {
            out.push(path);
        }
    }
}

/// The text between the `{` that follows `from` and its matching `}`.
fn braced(text: &str, from: usize) -> &str {
    let open = from + text[from..].find('{').expect("an opening brace");
    let mut depth = 0;
    for (i, c) in text[open..].char_indices() {
        depth += match c {
            '{' => 1,
            '}' => -1,
            _ => 0,
        };
        if depth == 0 {
            return &text[open + 1..open + i];
        }
    }
    panic!("unbalanced braces")
}

/// The error enums of one source file: `pub enum` items whose derive list names `Error` (thiserror),
/// each with the names of its variants (the identifiers at the enum's own indentation).
fn error_enums(source: &str) -> Vec<(String, Vec<String>)> {
    let mut enums = Vec::new();
    let mut search = 0;
    while let Some(at) = source[search..].find("pub enum ") {
        let at = search + at;
        search = at + 1;
        let before = &source[..at];
        let derive = before.rfind("#[derive(").map(|d| &before[d..]);
        // The derive must belong to this item: only attributes and doc lines between them.
        let Some(derive) = derive.filter(|d| d.lines().skip(1).all(|l| l.trim_start().starts_with('#')))
        else {
            continue;
        };
        if !derive.lines().next().unwrap().contains("Error") {
            continue;
        }
        let name: String = source[at + 9..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let variants = braced(source, at)
            .lines()
            .filter(|l| l.starts_with("    ") && !l.starts_with("     "))
            .map(str::trim)
            .filter(|l| l.chars().next().is_some_and(|c| c.is_ascii_uppercase()))
            .map(|l| l.chars().take_while(|c| c.is_alphanumeric()).collect())
            .collect();
        enums.push((name, variants));
    }
    enums
}

/// docs/error-contract.md's table has a row for each error enum of the workspace, in its crate's row, and
/// the row names each variant in backticks: a new enum or variant without its line in the contract fails
/// here.
#[test]
fn every_error_enum_is_in_the_contract() {
    let contract = read("docs/error-contract.md");
    let rows: Vec<&str> = contract.lines().filter(|l| l.starts_with("| noether")).collect();
    let mut files = Vec::new();
    rust_files(&root().join("crates"), &mut files);
    files.retain(|f| f.components().any(|c| c.as_os_str() == "src"));
    files.sort();
    let mut checked = 0;
    for file in &files {
        let dir = file
            .strip_prefix(root().join("crates"))
            .unwrap()
            .components()
            .next()
            .unwrap();
        let dir = dir.as_os_str().to_str().unwrap();
        let (package, path) = match dir {
            "noether" => ("noether (the facade)".to_string(), "noether".to_string()),
            other => (format!("noether-{other}"), format!("noether_{other}")),
        };
        for (name, variants) in error_enums(&fs::read_to_string(file).unwrap()) {
            let row = rows
                .iter()
                .find(|r| {
                    r.starts_with(&format!("| {package} |"))
                        && r.contains(&format!("`{path}::"))
                        && r.contains(&format!("::{name}`"))
                })
                .unwrap_or_else(|| {
                    panic!(
                        "docs/error-contract.md has no row for {path}…::{name} ({})",
                        file.display()
                    )
                });
            for v in &variants {
                assert!(
                    row.contains(&format!("`{v}")),
                    "the row of {path}…::{name} does not name its variant `{v}`"
                );
            }
            println!("{path}::{name}: {} variants documented", variants.len());
            checked += 1;
        }
    }
    // Core, linalg, discrete, constraints, rigid, particles, analysis, canonical, ensemble (two), plot,
    // the facade: the reader above must find them all, or it is reading nothing.
    assert!(
        checked >= 12,
        "found only {checked} error enums: the reader is broken"
    );
}

/// The README's layout table names every crate of the workspace (the `members` of the root
/// Cargo.toml).
#[test]
fn readme_layout_lists_every_crate() {
    let manifest = read("Cargo.toml");
    let readme = read("README.md");
    let layout = &readme[readme.find("## Layout").expect("a Layout section")..];
    let members = braced_list(&manifest, "members = [");
    assert!(members.len() >= 10, "{members:?}");
    for member in members {
        assert!(
            layout.contains(&format!("| `{member}`")),
            "README's layout table has no row for {member}"
        );
    }
}

/// The quoted strings of the list that starts at `key` in `text`.
fn braced_list(text: &str, key: &str) -> Vec<String> {
    let start = text.find(key).expect("the key") + key.len();
    let end = start + text[start..].find(']').expect("a closing bracket");
    text[start..end]
        .split('"')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

/// The facade's prelude holds the names a first program needs, about thirty (issue 31: it had 123);
/// printed, and held below 36 so that it grows only by a decision.
#[test]
fn prelude_is_small() {
    let lib = read("crates/noether/src/lib.rs");
    let body = braced(&lib, lib.find("pub mod prelude").expect("a prelude"));
    // The `pub use` statements, comments dropped; each names a list in braces or one last segment.
    let code: String = body
        .lines()
        .map(str::trim)
        .filter(|l| !l.starts_with("//"))
        .collect::<Vec<_>>()
        .join(" ");
    let names: Vec<String> = code
        .split(';')
        .filter_map(|stmt| stmt.trim().strip_prefix("pub use "))
        .flat_map(|path| match (path.find('{'), path.rfind('}')) {
            (Some(a), Some(b)) => path[a + 1..b].split(',').map(str::trim).collect::<Vec<_>>(),
            _ => vec![path.rsplit("::").next().unwrap().trim()],
        })
        .filter(|n| !n.is_empty())
        .map(str::to_owned)
        .collect();
    println!("the prelude has {} names: {}", names.len(), names.join(", "));
    assert!(
        names.len() >= 20 && names.len() <= 35,
        "{} names: {names:?}",
        names.len()
    );
}
