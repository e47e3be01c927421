//! The crate's layers are kept: no module imports a module of a higher layer, and no modules
//! import each other in a circle.
//!
//! The layer table is written once, in the crate docs (`src/lib.rs`, section "Layers"): one
//! numbered line per layer, bottom first, naming its modules as links (``[`stats`]``). This
//! test reads that table, then every library file under `src/` (not the binary's `main.rs`,
//! `cli.rs`, `commands/`): the `use` declarations and the inline paths that start with
//! `crate::`, `super::` or `self::`, outside comments, string literals and `#[cfg(test)]` items.
//! Each path names the module that holds it (the longest prefix that is a module file); an
//! import between two modules is counted between the two siblings under their common parent
//! (`crate::modal::lanczos` -> `crate::modal::refine` is lanczos -> refine under modal; a
//! module and its own parent or child are never counted). Then:
//! - between top-level modules, the importer's layer must not be below the imported one's;
//! - under every parent, the siblings' imports must not make a circle.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

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

/// Replaces comments and the contents of string and character literals by spaces, keeping
/// line breaks (so that line numbers stay right).
fn code_only(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |c: char| if c == '\n' { '\n' } else { ' ' };
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied().unwrap_or('\0');
        if c == '/' && next == '/' {
            while i < b.len() && b[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c == '/' && next == '*' {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
        } else if c == 'r'
            && (next == '"' || next == '#')
            && (i == 0 || !(b[i - 1].is_alphanumeric() || b[i - 1] == '_'))
        {
            // A raw string r"..." or r#"..."#.
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            out.push('"');
            j += 1;
            loop {
                if j >= b.len() {
                    break;
                }
                if b[j] == '"' && (0..hashes).all(|h| b.get(j + 1 + h) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                out.push(blank(b[j]));
                j += 1;
            }
            out.push('"');
            i = j;
        } else if c == '"' {
            out.push('"');
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < b.len() {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
            out.push('"');
            i += 1;
        } else if c == '\'' {
            // A character literal ('x', '\n', '\u{..}'), or else a lifetime ('a).
            let close = if next == '\\' {
                (i + 3..b.len().min(i + 12)).find(|&j| b[j] == '\'')
            } else {
                (b.get(i + 2) == Some(&'\'')).then_some(i + 2)
            };
            match close {
                Some(j) => {
                    out.push_str(&" ".repeat(j + 1 - i));
                    i = j + 1;
                }
                None => {
                    out.push(c);
                    i += 1;
                }
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// A token of the code: an identifier or a punctuation mark, with its line.
#[derive(Clone, Debug, PartialEq)]
struct Token {
    text: String,
    line: usize,
}

fn tokens(code: &str) -> Vec<Token> {
    let b: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut line = 1;
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_') {
                i += 1;
            }
            out.push(Token {
                text: b[start..i].iter().collect(),
                line,
            });
        } else if c == ':' && b.get(i + 1) == Some(&':') {
            out.push(Token {
                text: "::".into(),
                line,
            });
            i += 2;
        } else {
            out.push(Token {
                text: c.to_string(),
                line,
            });
            i += 1;
        }
    }
    out
}

/// Drops every item under `#[cfg(test)]` (attributes, then up to its `;` or its closing
/// brace), and returns the names of the module files it declared (`#[cfg(test)] mod x;`).
fn without_test_items(tokens: Vec<Token>) -> (Vec<Token>, Vec<String>) {
    let t = |k: usize| tokens.get(k).map(|t| t.text.as_str()).unwrap_or("");
    let mut out = Vec::with_capacity(tokens.len());
    let mut test_files = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let is_cfg_test = t(i) == "#"
            && t(i + 1) == "["
            && t(i + 2) == "cfg"
            && t(i + 3) == "("
            && t(i + 4) == "test"
            && t(i + 5) == ")"
            && t(i + 6) == "]";
        if !is_cfg_test {
            out.push(tokens[i].clone());
            i += 1;
            continue;
        }
        i += 7;
        // Further attributes.
        while t(i) == "#" {
            let mut depth = 0;
            loop {
                match t(i) {
                    "[" => depth += 1,
                    "]" => depth -= 1,
                    _ => {}
                }
                i += 1;
                if depth == 0 && t(i - 1) == "]" || i >= tokens.len() {
                    break;
                }
            }
        }
        let item_start = i;
        let mut depth = 0;
        while i < tokens.len() {
            match t(i) {
                "{" => depth += 1,
                "}" => {
                    depth -= 1;
                    if depth == 0 {
                        i += 1;
                        break;
                    }
                }
                ";" if depth == 0 => {
                    let head: Vec<&str> = (item_start..i).map(t).collect();
                    if let Some(p) = head.iter().position(|&w| w == "mod")
                        && let Some(name) = head.get(p + 1)
                    {
                        test_files.push(name.to_string());
                    }
                    i += 1;
                    break;
                }
                _ => {}
            }
            i += 1;
        }
    }
    (out, test_files)
}

/// One path the code names, with its line.
struct NamedPath {
    segments: Vec<String>,
    line: usize,
    /// The module (inline modules included) where it is written.
    module: Vec<String>,
}

/// Reads a use tree from `tokens[*i]` on, with the segments before it in `prefix`.
fn use_tree(
    tokens: &[Token],
    i: &mut usize,
    prefix: Vec<String>,
    module: &[String],
    out: &mut Vec<NamedPath>,
) {
    let mut path = prefix;
    let line = tokens.get(*i).map_or(0, |t| t.line);
    loop {
        let Some(tok) = tokens.get(*i) else { return };
        match tok.text.as_str() {
            "{" => {
                *i += 1;
                loop {
                    match tokens.get(*i).map(|t| t.text.as_str()) {
                        Some("}") => {
                            *i += 1;
                            return;
                        }
                        Some(",") => *i += 1,
                        None => return,
                        _ => use_tree(tokens, i, path.clone(), module, out),
                    }
                }
            }
            "::" => *i += 1,
            "*" => {
                *i += 1;
            }
            "as" => {
                *i += 2;
            }
            "," | "}" | ";" => {
                let mut path = path;
                if path.last().is_some_and(|s| s == "self") {
                    path.pop();
                }
                out.push(NamedPath {
                    segments: path,
                    line,
                    module: module.to_vec(),
                });
                return;
            }
            word => {
                path.push(word.to_string());
                *i += 1;
            }
        }
    }
}

/// The paths a file names: its `use` trees and its inline `crate::`, `super::`, `self::`
/// paths.
fn named_paths(tokens: &[Token], file_module: &[String]) -> Vec<NamedPath> {
    let mut out = Vec::new();
    // Inline modules (`mod x { .. }`) as (name, brace depth inside).
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0;
    let module = |inline: &[(String, usize)]| -> Vec<String> {
        let mut m = file_module.to_vec();
        m.extend(inline.iter().map(|(n, _)| n.clone()));
        m
    };
    let mut i = 0;
    while i < tokens.len() {
        let text = tokens[i].text.as_str();
        match text {
            "{" => {
                depth += 1;
                if i >= 2 && tokens[i - 2].text == "mod" {
                    inline.push((tokens[i - 1].text.clone(), depth));
                }
            }
            "}" => {
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
                depth -= 1;
            }
            "use" => {
                let m = module(&inline);
                i += 1;
                use_tree(tokens, &mut i, Vec::new(), &m, &mut out);
                continue;
            }
            "crate" | "super" | "self"
                if tokens.get(i + 1).is_some_and(|t| t.text == "::")
                    && (i == 0 || tokens[i - 1].text != "::") =>
            {
                let line = tokens[i].line;
                let mut segments = vec![text.to_string()];
                let mut j = i + 1;
                while tokens.get(j).is_some_and(|t| t.text == "::")
                    && tokens
                        .get(j + 1)
                        .is_some_and(|t| t.text.chars().all(|c| c.is_alphanumeric() || c == '_'))
                {
                    segments.push(tokens[j + 1].text.clone());
                    j += 2;
                }
                out.push(NamedPath {
                    segments,
                    line,
                    module: module(&inline),
                });
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// The absolute module path a path names (without `crate`), or None for a path outside the
/// crate (std, faer, a child module named by a bare name, ...).
fn absolute(path: &NamedPath) -> Option<Vec<String>> {
    let mut segments = path.segments.iter();
    let mut base: Vec<String> = match segments.next()?.as_str() {
        "crate" => Vec::new(),
        "self" => path.module.clone(),
        "super" => {
            let mut m = path.module.clone();
            m.pop()?;
            m
        }
        _ => return None,
    };
    let mut rest = segments.peekable();
    while rest.peek().is_some_and(|s| *s == "super") {
        rest.next();
        base.pop()?;
    }
    base.extend(rest.cloned());
    Some(base)
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
        let (tokens, test_files) = without_test_items(tokens(&code_only(&text)));
        for name in test_files {
            let mut m = module.clone();
            m.push(name);
            test_only.insert(m);
        }
        parsed.push((module.clone(), path.clone(), tokens));
    }
    let mut out = Vec::new();
    for (module, path, tokens) in parsed {
        if test_only.iter().any(|t| module.starts_with(t)) {
            continue;
        }
        let file = path
            .strip_prefix(root())
            .unwrap()
            .to_string_lossy()
            .to_string();
        for named in named_paths(&tokens, &module) {
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
    let declared: BTreeSet<String> = tokens(&code_only(&lib))
        .windows(3)
        .filter(|w| w[0].text == "pub" && w[1].text == "mod")
        .map(|w| w[2].text.clone())
        .collect();
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
fn the_reader_sees_imports_and_skips_comments_strings_and_tests() {
    let text = r#"
//! [`crate::a::b`] in a doc comment
use crate::{
    a::{self, B},
    c::d::E as F,
};
use super::g;
/* crate::h::i */
fn f() { let s = "crate::j::k"; let c = '"'; crate::l::m(); super::super::n::o(); }
mod inner { use super::p; }
#[cfg(test)]
mod tests { use crate::q::r; }
#[cfg(test)]
mod test_file;
"#;
    let (tokens, test_files) = without_test_items(tokens(&code_only(text)));
    assert_eq!(test_files, vec!["test_file".to_string()]);
    let module = vec!["x".to_string(), "y".to_string()];
    let paths: Vec<(String, Vec<String>)> = named_paths(&tokens, &module)
        .into_iter()
        .map(|p| (p.segments.join("::"), p.module))
        .collect();
    let xy = module.clone();
    let inner = vec!["x".to_string(), "y".to_string(), "inner".to_string()];
    assert_eq!(
        paths,
        vec![
            ("crate::a".to_string(), xy.clone()),
            ("crate::a::B".to_string(), xy.clone()),
            ("crate::c::d::E".to_string(), xy.clone()),
            ("super::g".to_string(), xy.clone()),
            ("crate::l::m".to_string(), xy.clone()),
            ("super::super::n::o".to_string(), xy.clone()),
            ("super::p".to_string(), inner),
        ]
    );
    let absolute_of = |segments: &[&str], module: &[&str]| {
        absolute(&NamedPath {
            segments: segments.iter().map(|s| s.to_string()).collect(),
            line: 1,
            module: module.iter().map(|s| s.to_string()).collect(),
        })
    };
    assert_eq!(
        absolute_of(&["super", "super", "n", "o"], &["x", "y"]),
        Some(vec!["n".to_string(), "o".to_string()])
    );
    assert_eq!(absolute_of(&["std", "fs"], &["x"]), None);
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
fn every_module_and_the_readme_state_the_layers() {
    let lib = fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let layers = layers(&lib);
    let readme = fs::read_to_string(root().join("README.md")).unwrap();
    let mut missing = Vec::new();
    for (i, layer) in layers.iter().enumerate() {
        let n = i + 1;
        let line = format!("{n}. {}: {}", layer.name, layer.modules.join(", "));
        if !readme.lines().any(|l| l.trim() == line) {
            missing.push(format!("README.md (Layout) lacks the line `{line}`"));
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
