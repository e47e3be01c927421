//! The crate's layers are kept: no module imports a module of a higher layer, and no modules
//! import each other in a circle.
//!
//! The layer table is written once, in the crate docs (`src/lib.rs`, section "Layers"): one
//! numbered line per layer, bottom first, naming its modules as links (``[`stats`]``). This
//! test reads that table, then every library file under `src/` (not the binary's `main.rs`,
//! `cli.rs`, `commands/`): the `use` declarations and the inline paths that start with
//! `crate::`, `super::` or `self::`, outside comments, string literals and `#[cfg(test)]` items
//! (`reader.rs`).
//! Each path names the module that holds it (the longest prefix that is a module file); an
//! import between two modules is counted between the two siblings under their common parent
//! (`crate::modal::lanczos` -> `crate::modal::refine` is lanczos -> refine under modal; a
//! module and its own parent or child are never counted). Then:
//! - between top-level modules, the importer's layer must not be below the imported one's;
//! - under every parent, the siblings' imports must not make a circle.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

mod reader;

use reader::absolute;

/// Imports that break the layers today and are being removed elsewhere, as
/// (importing file, imported module path): each is reported, not failed. An entry that no
/// longer matches fails, so that the list only shrinks.
const KNOWN_EXCEPTIONS: &[(&str, &str)] = &[];

/// One import between two sibling modules.
#[derive(Clone, Debug)]
struct Edge {
    parent: Vec<String>,
    from: String,
    to: String,
    /// Where: `file:line: path`.
    at: String,
    file: String,
    target: String,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// One layer of the crate docs' table.
#[derive(Debug, Clone, PartialEq)]
struct Layer {
    /// Its name (`foundations`).
    name: String,
    /// Its top-level modules, in the table's order.
    modules: Vec<String>,
}

/// The layer table of the crate docs, bottom first: the numbered lines
/// `N. name: [`module`], ...` of the section `# Layers`.
fn layers(lib: &str) -> Vec<Layer> {
    let mut out: Vec<Layer> = Vec::new();
    let mut in_section = false;
    for line in lib.lines() {
        let Some(doc) = line.strip_prefix("//!") else {
            continue;
        };
        let doc = doc.trim();
        if doc.starts_with('#') {
            in_section = doc.trim_start_matches('#').trim() == "Layers";
            continue;
        }
        let Some((number, rest)) = doc.split_once(". ") else {
            continue;
        };
        if !in_section || number.is_empty() || !number.chars().all(|c| c.is_ascii_digit()) {
            continue;
        }
        let (name, mut links) = rest.split_once(": ").unwrap_or(("", rest));
        let mut modules = Vec::new();
        while let Some(start) = links.find("[`") {
            let after = &links[start + 2..];
            let end = after.find("`]").expect("unclosed link in the layer table");
            modules.push(after[..end].to_string());
            links = &after[end + 2..];
        }
        assert_eq!(
            number,
            (out.len() + 1).to_string(),
            "the layers of src/lib.rs are numbered 1, 2, ... in order"
        );
        assert!(
            !name.is_empty() && !modules.is_empty(),
            "a layer line of src/lib.rs reads `N. name: [`module`], ...`: {doc}"
        );
        out.push(Layer {
            name: name.to_string(),
            modules,
        });
    }
    assert!(
        out.len() >= 2,
        "src/lib.rs has no layer table (a '# Layers' section with numbered lines)"
    );
    out
}

/// Top-level module -> its layer (0 = bottom).
fn layer_table(layers: &[Layer]) -> BTreeMap<String, usize> {
    let mut table = BTreeMap::new();
    for (i, layer) in layers.iter().enumerate() {
        for m in &layer.modules {
            assert!(
                table.insert(m.clone(), i).is_none(),
                "{m} appears twice in the layer table"
            );
        }
    }
    table
}

/// The library's module files: module path -> file (relative to the crate root).
fn module_files(top: &BTreeSet<String>) -> BTreeMap<Vec<String>, PathBuf> {
    fn walk(dir: &Path, module: Vec<String>, out: &mut BTreeMap<Vec<String>, PathBuf>) {
        let mut entries: Vec<_> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for path in entries {
            let name = path.file_stem().unwrap().to_string_lossy().to_string();
            if path.is_dir() {
                let mut m = module.clone();
                m.push(name);
                walk(&path, m, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let mut m = module.clone();
                if name != "mod" {
                    m.push(name);
                }
                out.insert(m, path);
            }
        }
    }
    let src = root().join("src");
    let mut out = BTreeMap::new();
    for name in top {
        let dir = src.join(name);
        if dir.is_dir() {
            walk(&dir, vec![name.clone()], &mut out);
        }
        let file = src.join(format!("{name}.rs"));
        if file.is_file() {
            out.insert(vec![name.clone()], file);
        }
    }
    out
}

/// Every import between sibling modules of the library.
fn edges(table: &BTreeMap<String, usize>) -> Vec<Edge> {
    let top: BTreeSet<String> = table.keys().cloned().collect();
    let files = module_files(&top);
    let mut test_only: BTreeSet<Vec<String>> = BTreeSet::new();
    let mut parsed = Vec::new();
    for (module, path) in &files {
        let text = fs::read_to_string(path).unwrap();
        let (named, test_files) = reader::paths(&text, module);
        for name in test_files {
            let mut m = module.clone();
            m.push(name);
            test_only.insert(m);
        }
        parsed.push((module.clone(), path.clone(), named));
    }
    let mut out = Vec::new();
    for (module, path, named_paths) in parsed {
        if test_only.iter().any(|t| module.starts_with(t)) {
            continue;
        }
        let file = path
            .strip_prefix(root())
            .unwrap()
            .to_string_lossy()
            .to_string();
        for named in named_paths {
            let Some(target) = absolute(&named) else {
                continue;
            };
            // The module the path names: its longest prefix that is a module file.
            let Some(target) = (0..=target.len())
                .rev()
                .map(|n| target[..n].to_vec())
                .find(|p| files.contains_key(p))
            else {
                continue;
            };
            let from = &named.module;
            let common = from.iter().zip(&target).take_while(|(a, b)| a == b).count();
            if common == from.len() || common == target.len() {
                continue; // a module and its own ancestor or descendant
            }
            out.push(Edge {
                parent: from[..common].to_vec(),
                from: from[common].clone(),
                to: target[common].clone(),
                at: format!("{file}:{}: {}", named.line, named.segments.join("::")),
                file: file.clone(),
                target: target.join("::"),
            });
        }
    }
    out
}

/// The circles among the imports under one parent: the groups of two or more modules that
/// each reach all the others (strongly connected components, by plain reachability).
fn circles(edges: &[&Edge]) -> Vec<BTreeSet<String>> {
    let nodes: BTreeSet<&str> = edges
        .iter()
        .flat_map(|e| [e.from.as_str(), e.to.as_str()])
        .collect();
    let reach = |start: &str| {
        let mut seen = BTreeSet::from([start.to_string()]);
        let mut stack = vec![start.to_string()];
        while let Some(n) = stack.pop() {
            for e in edges.iter().filter(|e| e.from == n) {
                if seen.insert(e.to.clone()) {
                    stack.push(e.to.clone());
                }
            }
        }
        seen
    };
    let reaches: BTreeMap<&str, BTreeSet<String>> = nodes.iter().map(|&n| (n, reach(n))).collect();
    let mut out: Vec<BTreeSet<String>> = Vec::new();
    for &n in &nodes {
        let component: BTreeSet<String> = nodes
            .iter()
            .filter(|&&m| reaches[n].contains(m) && reaches[m].contains(n))
            .map(|m| m.to_string())
            .collect();
        if component.len() > 1 && !out.contains(&component) {
            out.push(component);
        }
    }
    out
}

#[test]
fn imports_keep_to_the_layers() {
    let lib = fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let table = layer_table(&layers(&lib));
    let declared: BTreeSet<String> = reader::declared_modules(&lib).into_iter().collect();
    let tabled: BTreeSet<String> = table.keys().cloned().collect();
    assert_eq!(
        declared, tabled,
        "lib.rs's modules and its layer table differ"
    );

    let all = edges(&table);
    let known = |e: &Edge| {
        KNOWN_EXCEPTIONS
            .iter()
            .any(|(file, target)| e.file == *file && e.target.starts_with(target))
    };
    let mut problems = Vec::new();
    let mut excused = Vec::new();
    for e in all.iter().filter(|e| e.parent.is_empty()) {
        if table[&e.to] > table[&e.from] {
            let line = format!(
                "{}: {} (layer {}) imports {} (layer {})",
                e.at,
                e.from,
                table[&e.from] + 1,
                e.to,
                table[&e.to] + 1
            );
            if known(e) {
                excused.push(line);
            } else {
                problems.push(line);
            }
        }
    }
    let parents: BTreeSet<&Vec<String>> = all.iter().map(|e| &e.parent).collect();
    for parent in parents {
        let under: Vec<&Edge> = all
            .iter()
            .filter(|e| &e.parent == parent && !known(e))
            .collect();
        for circle in circles(&under) {
            let parent = if parent.is_empty() {
                "crate".to_string()
            } else {
                format!("crate::{}", parent.join("::"))
            };
            let mut text = format!("a circle under {parent}: {circle:?}, by");
            for e in under
                .iter()
                .filter(|e| circle.contains(&e.from) && circle.contains(&e.to))
            {
                text.push_str(&format!("\n    {} ({} -> {})", e.at, e.from, e.to));
            }
            problems.push(text);
        }
    }
    for (file, target) in KNOWN_EXCEPTIONS {
        assert!(
            all.iter()
                .any(|e| e.file == *file && e.target.starts_with(target)),
            "the known exception {file} -> {target} no longer occurs: remove it from the list"
        );
    }
    for line in &excused {
        eprintln!("known exception: {line}");
    }
    assert!(
        problems.is_empty(),
        "imports against the layers of src/lib.rs:\n{}",
        problems.join("\n")
    );
}

#[test]
fn a_circle_is_found() {
    let edge = |from: &str, to: &str| Edge {
        parent: Vec::new(),
        from: from.into(),
        to: to.into(),
        at: String::new(),
        file: String::new(),
        target: String::new(),
    };
    let edges = [
        edge("a", "b"),
        edge("b", "c"),
        edge("c", "a"),
        edge("c", "d"),
    ];
    let refs: Vec<&Edge> = edges.iter().collect();
    let found = circles(&refs);
    assert_eq!(found.len(), 1);
    assert_eq!(
        found[0],
        ["a", "b", "c"].iter().map(|s| s.to_string()).collect()
    );
    assert!(circles(&refs[..2]).is_empty());
}

/// The file of a top-level module: `src/NAME.rs`, else `src/NAME/mod.rs`.
fn top_file(name: &str) -> PathBuf {
    let file = root().join(format!("src/{name}.rs"));
    if file.is_file() {
        file
    } else {
        root().join(format!("src/{name}/mod.rs"))
    }
}

#[test]
fn every_module_and_the_layout_doc_state_the_layers() {
    let lib = fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let layers = layers(&lib);
    let readme = fs::read_to_string(root().join("docs/layout.md")).unwrap();
    let mut missing = Vec::new();
    for (i, layer) in layers.iter().enumerate() {
        let n = i + 1;
        let line = format!("{n}. {}: {}", layer.name, layer.modules.join(", "));
        if !readme.lines().any(|l| l.trim() == line) {
            missing.push(format!("docs/layout.md lacks the line `{line}`"));
        }
        for module in &layer.modules {
            let file = top_file(module);
            let docs: String = fs::read_to_string(&file)
                .unwrap()
                .lines()
                .take_while(|l| l.starts_with("//!"))
                .map(|l| l.trim_start_matches("//!").trim())
                .collect::<Vec<_>>()
                .join(" ");
            let says = format!("Layer {n} ({};", layer.name);
            if !docs.contains(&says) {
                missing.push(format!(
                    "{}: the module docs do not say `{says} ...` (what it may import)",
                    file.strip_prefix(root()).unwrap().display()
                ));
            }
        }
    }
    assert!(missing.is_empty(), "{}", missing.join("\n"));
}

#[test]
fn the_layer_table_is_read_from_numbered_lines_of_its_section() {
    let lib = "//! 1. [`a`]: before the section\n//! # Layers\n//! Text [`x`].\n//!\n\
               //! 1. ground: [`a`], [`b`]\n//! 2. top: [`c`]\n//! # Next\n//! 3. [`d`]\n";
    let found = layers(lib);
    assert_eq!(
        found,
        vec![
            Layer {
                name: "ground".into(),
                modules: vec!["a".into(), "b".into()],
            },
            Layer {
                name: "top".into(),
                modules: vec!["c".into()],
            },
        ]
    );
    assert_eq!(layer_table(&found)["c"], 1);
}
