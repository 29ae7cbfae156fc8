//! The workspace's layering, checked from its source text. The three crates' sources
//! (crates/core/src, crates/viewer/src, src) are read as one tree of modules: every `crate::`,
//! `super::`, `self::`, `decimate_core::`, `decimate_viewer::` and `decimate::` path is
//! resolved to the file it names, and the test fails on an import from a higher layer, between
//! two sibling areas, or on a cycle of files. Cargo already refuses imports against the crate
//! graph (core < viewer < the command line); this test holds the modules inside each crate to
//! their layers. Paths from a module to its own children (`child::f`) are not edges: a parent
//! that declares a module may use it.
//!
//! Test code (`#[cfg(test)]` items) is not checked: a unit test may build its fixtures with
//! a higher layer (io's tests decimate a mesh to have a progressive one to write).
//!
//! Layers, bottom to top. decimate-core: `alloc`, `threads`, `progress_bar`, `cancel`
//! (process plumbing, no imports) < `mesh` (data model) < `io` | `decimate` (siblings) <
//! `metro` < `tile` | `api` (siblings; `api` is the library's entry point for programs).
//! decimate-viewer: `render` < `app`. The command line: `cli` < `batch` | `tile_command` |
//! `viewer_start` (siblings) < `main` (src/main.rs, src/bin/).
//! `render` and `metro` may import `mesh` only of the layers below them.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Layer of a top-level module; areas with the same number are siblings that must not import
/// each other.
fn layer_of(top: &str) -> Option<u32> {
    Some(match top {
        "alloc" | "threads" | "progress_bar" | "cancel" => 0,
        "mesh" => 1,
        "io" | "decimate" => 2,
        "metro" => 3,
        "tile" | "api" => 4,
        "render" => 5,
        "app" => 6,
        "cli" => 7,
        "batch" | "tile_command" | "viewer_start" => 8,
        "main" => 9,
        _ => return None,
    })
}

/// Imports a layer below that are still not allowed: the renderer draws what it is given and
/// never reads files (`io`) or decimates (`decimate`); `metro` measures surfaces only.
fn forbidden(from: &str, to: &str) -> bool {
    matches!(
        (from, to),
        ("render", "io" | "decimate") | ("metro", "io" | "decimate")
    )
}

/// One source file: its module path (`["io", "vrml", "lexer"]`), whether it is a binary root
/// and its path as messages show it.
struct SourceFile {
    path: PathBuf,
    shown: String,
    module: Vec<String>,
    is_binary: bool,
}

fn collect(dir: &Path, files: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            collect(&path, files);
        } else if path.extension().is_some_and(|x| x == "rs") {
            files.push(path);
        }
    }
}

/// A crate's source folder and the name messages give it (`crates/core/src`).
struct Root {
    dir: PathBuf,
    label: String,
}

fn source_files(roots: &[Root]) -> Vec<SourceFile> {
    roots.iter().flat_map(root_files).collect()
}

fn root_files(root: &Root) -> Vec<SourceFile> {
    let src = root.dir.as_path();
    let mut paths = Vec::new();
    collect(src, &mut paths);
    paths
        .into_iter()
        .map(|path| {
            let relative = path.strip_prefix(src).expect("under src");
            let mut module: Vec<String> = relative
                .iter()
                .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
                .collect();
            let is_binary = module == ["main"] || module.first().is_some_and(|m| m == "bin");
            if is_binary {
                module = vec!["main".to_string()];
            } else if module.last().is_some_and(|m| m == "mod" || m == "lib") {
                module.pop();
            }
            let shown = format!("{}/{}", root.label, relative.display());
            SourceFile {
                path,
                shown,
                module,
                is_binary,
            }
        })
        .collect()
}

/// The source with comments, string and character literals blanked out (newlines kept).
fn code_only(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if chars[i] == '\n' {
                        out.push('\n');
                    }
                    i += 1;
                }
            }
        } else if c == 'r'
            && (next == Some('#') || next == Some('"'))
            && !ident_char_before(&chars, i)
        {
            // Raw string r#"..."#: skip to the closing quote followed by as many hashes.
            let mut j = i + 1;
            let mut hashes = 0;
            while chars.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if chars.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            while j < chars.len() {
                if chars[j] == '"' && (0..hashes).all(|h| chars.get(j + 1 + h) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                if chars[j] == '\n' {
                    out.push('\n');
                }
                j += 1;
            }
            out.push_str("\"\"");
            i = j;
        } else if c == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    i += 1;
                } else if chars[i] == '\n' {
                    out.push('\n');
                }
                i += 1;
            }
            out.push_str("\"\"");
            i += 1;
        } else if c == '\'' {
            // A character literal ('x', '\n', '\u{..}') or a lifetime ('a).
            if next == Some('\\') {
                let mut j = i + 2;
                while j < chars.len() && chars[j] != '\'' {
                    j += 1;
                }
                out.push_str("' '");
                i = j + 1;
            } else if chars.get(i + 2) == Some(&'\'') {
                out.push_str("' '");
                i += 3;
            } else {
                out.push(c);
                i += 1;
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn ident_char_before(chars: &[char], i: usize) -> bool {
    i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_')
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Path,
    Punct(char),
}

/// Tokens of the code with the line each starts on.
fn tokens(code: &str) -> Vec<(Tok, usize)> {
    let chars: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut line = 1;
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push((Tok::Ident(chars[start..i].iter().collect()), line));
        } else if c == ':' && chars.get(i + 1) == Some(&':') {
            out.push((Tok::Path, line));
            i += 2;
        } else {
            out.push((Tok::Punct(c), line));
            i += 1;
        }
    }
    out
}

/// Expands a `use` tree (`a::{b, c::{d, self}}`) into full paths.
fn use_paths(toks: &[Tok], pos: &mut usize, prefix: &[String], out: &mut Vec<Vec<String>>) {
    let mut path = prefix.to_vec();
    loop {
        match toks.get(*pos) {
            Some(Tok::Ident(name)) if name == "as" => {
                *pos += 2;
                out.push(path);
                return;
            }
            Some(Tok::Ident(name)) => {
                if name != "self" || path.is_empty() {
                    path.push(name.clone());
                }
                *pos += 1;
            }
            Some(Tok::Path) => *pos += 1,
            Some(Tok::Punct('{')) => {
                *pos += 1;
                loop {
                    match toks.get(*pos) {
                        Some(Tok::Punct('}')) => {
                            *pos += 1;
                            return;
                        }
                        Some(Tok::Punct(',')) => *pos += 1,
                        None => return,
                        _ => use_paths(toks, pos, &path, out),
                    }
                }
            }
            Some(Tok::Punct('*')) => {
                *pos += 1;
                out.push(path);
                return;
            }
            _ => {
                out.push(path);
                return;
            }
        }
    }
}

/// A module path named in the file's library code, with its line.
struct Reference {
    path: Vec<String>,
    line: usize,
}

/// Whether each token lies in a `#[cfg(test)]` item (a test module or a test-only `use`):
/// test code may build its fixtures with a higher layer.
fn in_test_code(toks: &[Tok]) -> Vec<bool> {
    let attribute: Vec<Tok> = ["#", "[", "cfg", "(", "test", ")", "]"]
        .iter()
        .map(|t| match t.chars().next() {
            Some(c) if !c.is_alphanumeric() => Tok::Punct(c),
            _ => Tok::Ident(t.to_string()),
        })
        .collect();
    let mut marks = vec![false; toks.len()];
    let mut i = 0;
    while i + attribute.len() <= toks.len() {
        if toks[i..i + attribute.len()] != attribute[..] {
            i += 1;
            continue;
        }
        // The item runs to its first `;` outside braces or to the `}` closing its body.
        let mut depth = 0;
        let mut j = i + attribute.len();
        while j < toks.len() {
            match toks[j] {
                Tok::Punct('{') => depth += 1,
                Tok::Punct('}') => {
                    depth -= 1;
                    if depth == 0 {
                        break;
                    }
                }
                Tok::Punct(';') if depth == 0 => break,
                _ => {}
            }
            j += 1;
        }
        let end = (j + 1).min(toks.len());
        marks[i..end].iter_mut().for_each(|m| *m = true);
        i = end;
    }
    marks
}

fn references(text: &str) -> Vec<Reference> {
    let toks = tokens(&code_only(text));
    let all: Vec<Tok> = toks.iter().map(|(t, _)| t.clone()).collect();
    let test = in_test_code(&all);
    let toks: Vec<(Tok, usize)> = toks
        .into_iter()
        .zip(test)
        .filter(|(_, test)| !test)
        .map(|(t, _)| t)
        .collect();
    let plain: Vec<Tok> = toks.iter().map(|(t, _)| t.clone()).collect();
    let mut out = Vec::new();
    let is_root = |t: &Tok| match t {
        Tok::Ident(n) => n == "crate" || n == "super" || n == "self" || is_crate_name(n),
        _ => false,
    };
    let mut i = 0;
    while i < plain.len() {
        if plain[i] == Tok::Ident("use".into()) {
            let line = toks[i].1;
            let mut pos = i + 1;
            let mut paths = Vec::new();
            use_paths(&plain, &mut pos, &[], &mut paths);
            for path in paths {
                if path
                    .first()
                    .is_some_and(|p| is_root(&Tok::Ident(p.clone())))
                {
                    out.push(Reference { path, line });
                }
            }
            i = pos.max(i + 1);
        } else if is_root(&plain[i])
            && plain.get(i + 1) == Some(&Tok::Path)
            && (i == 0 || plain[i - 1] != Tok::Punct('$'))
            && (i == 0 || plain[i - 1] != Tok::Path)
        {
            let line = toks[i].1;
            let mut path = Vec::new();
            let mut j = i;
            while let Some(Tok::Ident(name)) = plain.get(j) {
                path.push(name.clone());
                if plain.get(j + 1) != Some(&Tok::Path) {
                    break;
                }
                j += 2;
            }
            out.push(Reference { path, line });
            i = j + 1;
        } else {
            i += 1;
        }
    }
    out
}

/// The workspace's crates, which the checker reads as one tree of modules.
fn is_crate_name(name: &str) -> bool {
    matches!(name, "decimate" | "decimate_core" | "decimate_viewer")
}

/// The file a path names: the longest prefix of its module path that is a file of the crate.
fn resolve(
    reference: &[String],
    from: &SourceFile,
    modules: &BTreeMap<Vec<String>, usize>,
) -> Option<usize> {
    let mut segments = reference.iter().peekable();
    let mut module: Vec<String> = match segments.peek().map(|s| s.as_str()) {
        Some(n) if n == "crate" || is_crate_name(n) => {
            segments.next();
            Vec::new()
        }
        Some("self") => {
            segments.next();
            from.module.clone()
        }
        _ => from.module.clone(),
    };
    if from.is_binary && reference.first().is_some_and(|s| !is_crate_name(s)) {
        return None;
    }
    while segments.peek().is_some_and(|s| *s == "super") {
        segments.next();
        module.pop();
    }
    let mut best = modules.get(&module).copied();
    for segment in segments {
        module.push(segment.clone());
        if let Some(&file) = modules.get(&module) {
            best = Some(file);
        }
    }
    best
}

fn layer_name(file: &SourceFile) -> String {
    file.module.first().cloned().unwrap_or_else(|| "lib".into())
}

struct Edge {
    to: usize,
    line: usize,
}

/// Files and their edges to the files they name.
fn graph(roots: &[Root]) -> (Vec<SourceFile>, Vec<Vec<Edge>>) {
    let files = source_files(roots);
    let modules: BTreeMap<Vec<String>, usize> = files
        .iter()
        .enumerate()
        .filter(|(_, f)| !f.is_binary)
        .map(|(i, f)| (f.module.clone(), i))
        .collect();
    let edges = files
        .iter()
        .enumerate()
        .map(|(i, file)| {
            let text = fs::read_to_string(&file.path)
                .unwrap_or_else(|e| panic!("{}: {e}", file.path.display()));
            let mut seen = BTreeSet::new();
            references(&text)
                .into_iter()
                .filter_map(|r| {
                    let to = resolve(&r.path, file, &modules)?;
                    (to != i && seen.insert(to)).then_some(Edge { to, line: r.line })
                })
                .collect()
        })
        .collect();
    (files, edges)
}

fn shown(file: &SourceFile) -> String {
    file.shown.clone()
}

/// Imports that go up a layer or sideways between sibling areas.
fn layer_violations(roots: &[Root]) -> Vec<String> {
    let (files, edges) = graph(roots);
    let mut found = Vec::new();
    for (i, file) in files.iter().enumerate() {
        let from = layer_name(file);
        let Some(from_layer) = layer_of(&from) else {
            if from != "lib" {
                found.push(format!("{}: area `{from}` has no layer", shown(file)));
            }
            continue;
        };
        for edge in &edges[i] {
            let to = layer_name(&files[edge.to]);
            let Some(to_layer) = layer_of(&to) else {
                continue;
            };
            let upward = to_layer > from_layer || (to_layer == from_layer && to != from);
            if upward || forbidden(&from, &to) {
                found.push(format!(
                    "{}:{}: `{from}` imports `{to}` ({})",
                    shown(file),
                    edge.line,
                    shown(&files[edge.to])
                ));
            }
        }
    }
    found
}

/// Cycles between files, each printed as the path of files that closes it.
fn cycles(roots: &[Root]) -> Vec<String> {
    let (files, edges) = graph(roots);
    // Iterative depth-first search; an edge back to a file on the stack closes a cycle.
    #[derive(Clone, Copy, PartialEq)]
    enum State {
        New,
        OnStack,
        Done,
    }
    let mut state = vec![State::New; files.len()];
    let mut found = Vec::new();
    for root in 0..files.len() {
        if state[root] != State::New {
            continue;
        }
        let mut stack: Vec<(usize, usize)> = vec![(root, 0)];
        state[root] = State::OnStack;
        while let Some(&mut (node, ref mut next)) = stack.last_mut() {
            if let Some(edge) = edges[node].get(*next) {
                *next += 1;
                match state[edge.to] {
                    State::New => {
                        state[edge.to] = State::OnStack;
                        stack.push((edge.to, 0));
                    }
                    State::OnStack => {
                        let start = stack.iter().position(|&(n, _)| n == edge.to).unwrap_or(0);
                        let mut names: Vec<String> = stack[start..]
                            .iter()
                            .map(|&(n, _)| shown(&files[n]))
                            .collect();
                        names.push(shown(&files[edge.to]));
                        found.push(names.join(" -> "));
                    }
                    State::Done => {}
                }
            } else {
                state[node] = State::Done;
                stack.pop();
            }
        }
    }
    found
}

/// The workspace's three source folders, core first.
fn workspace_roots() -> Vec<Root> {
    let top = Path::new(env!("CARGO_MANIFEST_DIR"));
    ["crates/core/src", "crates/viewer/src", "src"]
        .into_iter()
        .map(|label| Root {
            dir: top.join(label),
            label: label.to_string(),
        })
        .collect()
}

#[test]
fn no_file_imports_a_higher_layer_or_a_sibling_area() {
    let found = layer_violations(&workspace_roots());
    assert!(
        found.is_empty(),
        "imports against the layers:\n{}",
        found.join("\n")
    );
}

#[test]
fn no_import_cycle_between_files() {
    let found = cycles(&workspace_roots());
    assert!(found.is_empty(), "import cycles:\n{}", found.join("\n"));
}

#[test]
fn no_two_source_files_share_a_name() {
    let mut by_name: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for file in source_files(&workspace_roots()) {
        let name = file
            .path
            .file_name()
            .map(|n| n.to_string_lossy().to_string());
        if let Some(name) = name.filter(|n| n != "mod.rs" && n != "lib.rs") {
            by_name.entry(name).or_default().push(shown(&file));
        }
    }
    let twins: Vec<String> = by_name
        .into_values()
        .filter(|paths| paths.len() > 1)
        .map(|paths| paths.join(", "))
        .collect();
    assert!(
        twins.is_empty(),
        "file names used twice:\n{}",
        twins.join("\n")
    );
}

#[test]
fn the_checker_sees_grouped_uses_and_inline_paths() {
    let text = "use crate::{mesh::Model, io::{obj, ply::read as r}};\n\
                // use crate::render::x;\n\
                fn f() { let s = \"crate::app\"; super::super::decimate::run(); }\n";
    let paths: Vec<String> = references(text).iter().map(|r| r.path.join("::")).collect();
    assert_eq!(
        paths,
        [
            "crate::mesh::Model",
            "crate::io::obj",
            "crate::io::ply::read",
            "super::super::decimate::run"
        ]
    );
    let tested = "use crate::mesh::Model;\n#[cfg(test)]\nmod tests { use crate::app::x; }\n\
                  #[cfg(test)]\nuse crate::batch::y;\nfn g() { crate::io::f(); }\n";
    let paths: Vec<String> = references(tested)
        .iter()
        .map(|r| r.path.join("::"))
        .collect();
    assert_eq!(paths, ["crate::mesh::Model", "crate::io::f"]);
}

#[test]
fn the_checker_finds_a_cycle_and_an_upward_import() {
    let dir = tempfile::tempdir().expect("temp dir");
    let src = dir.path();
    fs::create_dir_all(src.join("mesh")).expect("mkdir");
    fs::write(src.join("lib.rs"), "pub mod mesh;\npub mod io;\n").expect("write");
    fs::write(src.join("mesh/mod.rs"), "pub mod a;\npub mod b;\n").expect("write");
    fs::write(src.join("mesh/a.rs"), "use super::b::B;\npub struct A;\n").expect("write");
    fs::write(
        src.join("mesh/b.rs"),
        "use crate::{mesh::a::A, io};\npub struct B;\n",
    )
    .expect("write");
    fs::write(src.join("io.rs"), "pub fn f() {}\n").expect("write");
    let roots = [Root {
        dir: src.to_path_buf(),
        label: "src".into(),
    }];
    assert_eq!(
        cycles(&roots),
        ["src/mesh/a.rs -> src/mesh/b.rs -> src/mesh/a.rs"]
    );
    assert_eq!(
        layer_violations(&roots),
        ["src/mesh/b.rs:1: `mesh` imports `io` (src/io.rs)"]
    );
}
