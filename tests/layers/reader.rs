//! Reading Rust source for the paths it names, without a parser: comments and literals are
//! blanked, the rest split into tokens, `#[cfg(test)]` items dropped, then the `use` trees and
//! the inline paths that start with `crate::`, `super::` or `self::` collected with the
//! module they are written in.

/// The paths `text` (the file of module `module`) names outside comments, literals and
/// `#[cfg(test)]` items, and the module files it declares under `#[cfg(test)]`
/// (`#[cfg(test)] mod x;`: test-only files).
pub fn paths(text: &str, module: &[String]) -> (Vec<NamedPath>, Vec<String>) {
    let (tokens, test_files) = without_test_items(tokens(&code_only(text)));
    (named_paths(&tokens, module), test_files)
}

/// The modules `text` declares (`pub mod x;`, `mod x;`, `mod x { .. }`) outside comments.
pub fn declared_modules(text: &str) -> Vec<String> {
    tokens(&code_only(text))
        .windows(2)
        .filter(|w| w[0].text == "mod")
        .map(|w| w[1].text.clone())
        .collect()
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
pub struct NamedPath {
    /// Its segments (`crate`, `modal`, `ModalSolution`).
    pub segments: Vec<String>,
    /// Its line, 1-based.
    pub line: usize,
    /// The module (inline modules included) where it is written.
    pub module: Vec<String>,
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
            // `use<..>` is a precise-capturing bound, not a use tree.
            "use" if tokens.get(i + 1).is_none_or(|t| t.text != "<") => {
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
pub fn absolute(path: &NamedPath) -> Option<Vec<String>> {
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
