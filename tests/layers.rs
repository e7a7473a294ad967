//! The import layers of `src/`: every top-level module uses only modules
//! listed before it in the layer list at the top of `src/lib.rs`'s module
//! declarations, so imports run one way and never form a cycle.
//!
//! The check reads the sources, with no help from the compiler: the module
//! tree from `src/lib.rs`'s `mod` declarations, and in every file the paths
//! that reach another top-level module (`crate::x`, `$crate::x`,
//! `crate::{x, y}`, a `super::` chain that climbs to the crate root, and a
//! name the root re-exports, such as `crate::Mesh`), outside comments,
//! string literals and `#[cfg(test)]` items (test code may use anything).
//! Method calls on a type whose `impl` blocks live in several modules are
//! not imports, and are not seen.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A source tree: file path (relative to the crate) -> text.
type Files = BTreeMap<PathBuf, String>;

#[test]
fn src_imports_follow_the_declared_layers() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Files::new();
    read_tree(&root.join("src"), root, &mut files);
    let report = analyse(&files);
    assert!(
        report.problems.is_empty(),
        "the imports of src/ break the layer list in src/lib.rs:\n{}",
        report.problems.join("\n")
    );
    // The check saw the tree (a parse that finds nothing would pass).
    assert!(report.modules.len() > 20, "{:?}", report.modules);
    assert!(report.edges.contains_key(&("mesh".into(), "record".into())));
    assert!(report.edges.contains_key(&("ops".into(), "mesh".into())));
}

/// The check fails on an upward import and on a cycle, wherever the path
/// hides (a group, a root re-export, a `super::` chain, `$crate`), and
/// ignores test code, comments and strings.
#[test]
fn the_check_catches_an_upward_import_and_a_cycle() {
    let lib = "
// Layers (lowest first):
// - core: keys store
// - top: mesh algo
pub mod algo;
pub mod keys;
mod mesh;
mod store;
pub use mesh::Mesh;
";
    let clean = [
        ("src/lib.rs", lib),
        (
            "src/keys.rs",
            "// use crate::algo;\nconst S: &str = \"crate::algo\";",
        ),
        (
            "src/store.rs",
            "use crate::keys::K;\n#[cfg(test)]\nmod tests { use crate::Mesh; }",
        ),
        ("src/mesh.rs", "use crate::{keys::K, store};\nmod inner;"),
        (
            "src/mesh/inner.rs",
            "use super::super::store::S;\nmod deeper { use super::X; }",
        ),
        (
            "src/algo/mod.rs",
            "use crate::Mesh;\nmacro_rules! m { () => { $crate::keys::K } }",
        ),
    ];
    let files = |extra: &[(&str, &str)]| -> Files {
        let mut f: Files = clean
            .iter()
            .map(|(p, t)| (PathBuf::from(p), t.to_string()))
            .collect();
        for (p, t) in extra {
            f.insert(PathBuf::from(p), t.to_string());
        }
        f
    };
    let ok = analyse(&files(&[]));
    assert!(ok.problems.is_empty(), "{:?}", ok.problems);
    let edges: BTreeSet<_> = ok.edges.keys().cloned().collect();
    let e = |a: &str, b: &str| (a.to_string(), b.to_string());
    assert_eq!(
        edges,
        BTreeSet::from([
            e("store", "keys"),
            e("mesh", "keys"),
            e("mesh", "store"),
            e("algo", "mesh"),
            e("algo", "keys")
        ])
    );

    for (what, file, text) in [
        (
            "a plain path",
            "src/store.rs",
            "fn f() { crate::mesh::g() }",
        ),
        ("a group", "src/keys.rs", "use crate::{store::S};"),
        ("a root re-export", "src/store.rs", "use crate::Mesh;"),
        (
            "a super chain",
            "src/mesh/inner.rs",
            "use super::super::algo::A;",
        ),
        (
            "$crate",
            "src/keys.rs",
            "macro_rules! m { () => { $crate::store::S } }",
        ),
        (
            "a cfg that is not test",
            "src/keys.rs",
            "#[cfg(feature = \"x\")]\nuse crate::store::S;",
        ),
    ] {
        let bad = analyse(&files(&[(file, text)]));
        assert!(
            bad.problems.iter().any(|p| p.contains("imports")),
            "{what}: {:?}",
            bad.problems
        );
    }
    // A cycle (store -> mesh -> store) is named as such.
    let bad = analyse(&files(&[("src/store.rs", "use crate::mesh::M;")]));
    assert!(
        bad.problems
            .iter()
            .any(|p| p.starts_with("cycle") && p.contains("mesh") && p.contains("store")),
        "{:?}",
        bad.problems
    );
    // A module missing from the layer list, and a listed module that does
    // not exist.
    let unlisted = lib.replace("// - top: mesh algo", "// - top: mesh gone");
    let bad = analyse(&files(&[("src/lib.rs", &unlisted)]));
    assert!(
        bad.problems.iter().any(|p| p.contains("`algo`")),
        "{:?}",
        bad.problems
    );
    assert!(
        bad.problems.iter().any(|p| p.contains("`gone`")),
        "{:?}",
        bad.problems
    );
}

/// The modules that own `Mesh`'s storage fields (`v_halfedge`, `v_slots`,
/// `he`, `e_slots`, `f_halfedge`, `f_slots`, `holes`, `attrs`, `rec`); the
/// rest of the crate reads through the read API in `src/mesh/read.rs`
/// (and the navigation in `mesh.rs`, `circulate`, `iter`) and builds new
/// topology through `mesh::Topology`:
///
/// - `mesh`: declares the fields; `mesh/read.rs` is the read API,
///   `mesh/topology.rs` the bulk-build primitive.
/// - `ops`, `journal`, `record`: the editing operators and the undo log,
///   which write links and record the old values.
/// - `slots`, `store`, `layout`: the arenas, the attribute columns and the
///   link arrays the fields are made of.
/// - `build`: builds a mesh's arenas from polygons in one pass.
/// - `validate`: checks the raw links, including ones the read API trusts.
/// - `serde_impl`: (de)serializes the fields as they are stored.
/// - `attr`: the public attribute API over the column store (`attrs`).
const STORAGE_OWNERS: &[&str] = &[
    "mesh",
    "ops",
    "journal",
    "record",
    "slots",
    "store",
    "layout",
    "build",
    "validate",
    "serde_impl",
    "attr",
];

/// Storage field names no other struct in the crate uses.
const DISTINCT_FIELDS: &[&str] = &["v_halfedge", "v_slots", "e_slots", "f_halfedge", "f_slots"];
/// Storage field names other structs use too: flagged only on a receiver
/// that is a `Mesh` (a binding typed `Mesh`, `self.mesh`, or `self` in an
/// `impl Mesh` block).
const SHARED_FIELDS: &[&str] = &["he", "holes", "attrs", "rec"];

#[test]
fn mesh_storage_fields_are_touched_only_by_their_owners() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Files::new();
    read_tree(&root.join("src"), root, &mut files);
    let problems = storage_touches(&files);
    assert!(
        problems.is_empty(),
        "Mesh storage fields used outside their owners (use src/mesh/read.rs):\n{}",
        problems.join("\n")
    );
}

/// The storage check flags a distinct field anywhere outside the owners
/// and a shared one on a `Mesh` receiver, and leaves other structs' fields
/// of the same names, method calls, owners and test code alone.
#[test]
fn the_check_catches_a_storage_field_read_outside_the_core() {
    let clean = [
        ("src/ops/flip.rs", "fn f(m: &mut Mesh) { m.he[h].next = n; }"),
        (
            "src/algo/a.rs",
            "fn f(mesh: &Mesh, s: &Stats) -> usize { mesh.attrs().x + s.holes + mesh.halfedge_slots() }\n#[cfg(test)]\nmod tests { fn g(mesh: &Mesh) { mesh.he.len(); } }",
        ),
        ("src/io/b.rs", "fn f(soup: &mut Soup) { soup.attrs.push(1); } // mesh.he"),
    ];
    let files: Files = clean
        .iter()
        .map(|(p, t)| (PathBuf::from(p), t.to_string()))
        .collect();
    assert_eq!(storage_touches(&files), Vec::<String>::new());
    for (path, text, field) in [
        (
            "src/algo/c.rs",
            "fn f(mesh: &Mesh) { let n = mesh.he[h].next; }",
            "he",
        ),
        (
            "src/algo/c.rs",
            "fn f(m: &'a mut Mesh) { m.attrs.vertex.clear(); }",
            "attrs",
        ),
        (
            "src/iter.rs",
            "fn f(&self) -> usize { self.mesh.holes }",
            "holes",
        ),
        (
            "src/stats.rs",
            "impl Mesh {\n    fn f(&self) -> usize { self.rec.is_some() as usize }\n}",
            "rec",
        ),
        (
            "src/io/d.rs",
            "fn f(x: &Foo) -> usize { x.inner.f_slots.live() }",
            "f_slots",
        ),
        (
            "src/algo/e.rs",
            "fn f() -> Mesh { Mesh { v_halfedge: a, he: b } }",
            "v_halfedge",
        ),
    ] {
        let mut files = files.clone();
        files.insert(PathBuf::from(path), text.to_string());
        let found = storage_touches(&files);
        assert!(
            found.len() == 1 && found[0].contains(field) && found[0].starts_with(path),
            "{path}: {text:?} -> {found:?}"
        );
    }
}

/// Every use of a storage field outside [`STORAGE_OWNERS`], as
/// `path:line: field`.
fn storage_touches(files: &Files) -> Vec<String> {
    let mut out = Vec::new();
    for (path, text) in files {
        let rel: Vec<String> = path
            .iter()
            .skip(1)
            .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
            .collect();
        if rel
            .first()
            .is_some_and(|top| STORAGE_OWNERS.contains(&top.as_str()))
        {
            continue;
        }
        let src = drop_test_items(&blank_literals(text));
        let bound = mesh_bindings(&src);
        let mut in_impl_mesh = false;
        for (n, line) in src.lines().enumerate() {
            if line.starts_with("impl Mesh ")
                || line.starts_with("impl<") && line.contains("> Mesh ")
            {
                in_impl_mesh = true;
            } else if line.starts_with('}') {
                in_impl_mesh = false;
            }
            for (field, receiver) in field_uses(line) {
                let distinct = DISTINCT_FIELDS.contains(&field.as_str());
                let shared = SHARED_FIELDS.contains(&field.as_str())
                    && receiver.as_deref().is_some_and(|r| {
                        r == "self.mesh" || bound.contains(r) || (r == "self" && in_impl_mesh)
                    });
                if distinct || shared {
                    out.push(format!("{}:{}: {field}", path.display(), n + 1));
                }
            }
        }
    }
    out
}

/// The names bound with a `Mesh` type in `src` (`name: &Mesh`,
/// `name: &'a mut Mesh`, `name: Mesh`).
fn mesh_bindings(src: &str) -> BTreeSet<String> {
    let c: Vec<char> = src.chars().collect();
    let mut out = BTreeSet::new();
    let mut i = 0;
    while i < c.len() {
        if c[i] == ':' && c.get(i + 1) != Some(&':') && (i == 0 || c[i - 1] != ':') {
            let rest: String = c[i + 1..c.len().min(i + 40)].iter().collect();
            let ty = rest.trim_start().trim_start_matches('&');
            let ty = if let Some(t) = ty.strip_prefix('\'') {
                t.trim_start_matches(|ch: char| ch.is_alphanumeric() || ch == '_')
            } else {
                ty
            };
            let ty = ty.trim_start().trim_start_matches("mut ").trim_start();
            let is_mesh = ty.starts_with("Mesh")
                && !ty[4..].starts_with(|ch: char| ch.is_alphanumeric() || ch == '_');
            let mut j = i;
            while j > 0 && c[j - 1] == ' ' {
                j -= 1;
            }
            let end = j;
            while j > 0 && (c[j - 1].is_alphanumeric() || c[j - 1] == '_') {
                j -= 1;
            }
            if is_mesh && j < end {
                out.insert(c[j..end].iter().collect());
            }
        }
        i += 1;
    }
    out
}

/// The storage-named fields a line touches: `.field` not followed by `(`
/// or `::` (a field, not a method), with its receiver (`self.mesh`, or the
/// identifier before the dot), and `field:` (a struct literal) with none.
fn field_uses(line: &str) -> Vec<(String, Option<String>)> {
    let c: Vec<char> = line.chars().collect();
    let word = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        if !word(c[i]) || (i > 0 && word(c[i - 1])) {
            i += 1;
            continue;
        }
        let start = i;
        while i < c.len() && word(c[i]) {
            i += 1;
        }
        let name: String = c[start..i].iter().collect();
        let all = DISTINCT_FIELDS.iter().chain(SHARED_FIELDS);
        if !all.clone().any(|f| *f == name) {
            continue;
        }
        let after: String = c[i..].iter().collect();
        let after = after.trim_start();
        if start > 0 && c[start - 1] == '.' {
            if after.starts_with('(') || after.starts_with("::") {
                continue;
            }
            let mut j = start - 1;
            while j > 0 && word(c[j - 1]) {
                j -= 1;
            }
            let mut receiver: String = c[j..start - 1].iter().collect();
            if receiver == "mesh" && j >= 5 && c[j - 5..j].iter().collect::<String>() == "self." {
                receiver = "self.mesh".into();
            }
            out.push((name, Some(receiver)));
        } else if DISTINCT_FIELDS.contains(&name.as_str())
            && after.starts_with(':')
            && !after.starts_with("::")
        {
            out.push((name, None));
        }
    }
    out
}

/// What the check found.
struct Report {
    /// Top-level modules, as the layer list orders them.
    modules: Vec<String>,
    /// `(from, to)` -> where (file:line) the first such path is.
    edges: BTreeMap<(String, String), String>,
    problems: Vec<String>,
}

fn analyse(files: &Files) -> Report {
    let lib_raw = files
        .get(Path::new("src/lib.rs"))
        .expect("src/lib.rs is missing");
    let layers = layer_list(lib_raw);
    let lib = tokens(&drop_test_items(&blank_literals(lib_raw)));
    let reexports = root_reexports(&lib);
    let mut problems = Vec::new();

    // The module tree, from lib.rs's `mod` declarations.
    let mut module_files: Vec<(Vec<String>, PathBuf)> = Vec::new();
    let mut tops = BTreeSet::new();
    for name in mod_declarations(&lib) {
        tops.insert(name.clone());
        collect_module(files, Path::new("src"), vec![name], &mut module_files);
    }

    let rank: BTreeMap<&str, usize> = layers
        .iter()
        .enumerate()
        .map(|(i, m)| (m.as_str(), i))
        .collect();
    for m in &tops {
        if !rank.contains_key(m.as_str()) {
            problems.push(format!(
                "module `{m}` is not in the layer list at the top of src/lib.rs's module declarations"
            ));
        }
    }
    let mut seen = BTreeSet::new();
    for m in &layers {
        if !tops.contains(m) {
            problems.push(format!(
                "the layer list names `{m}`, which is no module of src/"
            ));
        }
        if !seen.insert(m) {
            problems.push(format!("the layer list names `{m}` twice"));
        }
    }

    // Every path that reaches another top-level module.
    let mut edges: BTreeMap<(String, String), String> = BTreeMap::new();
    for (path, file) in &module_files {
        let text = drop_test_items(&blank_literals(&files[file]));
        let toks = tokens(&text);
        for (target, line) in reached_modules(&toks, path, &tops, &reexports, &mut problems, file) {
            if target != path[0] {
                edges
                    .entry((path[0].clone(), target))
                    .or_insert_with(|| format!("{}:{line}", file.display()));
            }
        }
    }

    for ((from, to), at) in &edges {
        if let (Some(a), Some(b)) = (rank.get(from.as_str()), rank.get(to.as_str())) {
            if b > a {
                problems.push(format!(
                    "`{from}` imports `{to}`, which the layer list puts above it ({at})"
                ));
            }
        }
    }
    for cycle in cycles(&tops, &edges) {
        problems.push(format!("cycle between {}", cycle.join(", ")));
    }
    Report {
        modules: layers,
        edges,
        problems,
    }
}

/// The layer list: lines `// - label: a b c` at the top level of lib.rs,
/// lowest first.
fn layer_list(lib: &str) -> Vec<String> {
    lib.lines()
        .filter_map(|l| l.trim().strip_prefix("// - "))
        .filter_map(|l| l.split_once(':'))
        .flat_map(|(_, names)| names.split_whitespace().map(str::to_string))
        .collect()
}

/// Read every `.rs` file under `dir` into `files`, keyed relative to `base`.
fn read_tree(dir: &Path, base: &Path, files: &mut Files) {
    for entry in std::fs::read_dir(dir).expect("read src/") {
        let p = entry.expect("dir entry").path();
        if p.is_dir() {
            read_tree(&p, base, files);
        } else if p.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(&p).expect("read a source file");
            files.insert(p.strip_prefix(base).unwrap().to_path_buf(), text);
        }
    }
}

/// Add module `path`'s file (and its non-test submodules) to `out`.
/// `dir` is where a module declared in the parent finds its file.
fn collect_module(
    files: &Files,
    dir: &Path,
    path: Vec<String>,
    out: &mut Vec<(Vec<String>, PathBuf)>,
) {
    let name = path.last().unwrap();
    let flat = dir.join(format!("{name}.rs"));
    let nested = dir.join(name).join("mod.rs");
    let (file, child_dir) = if files.contains_key(&flat) {
        (flat, dir.join(name))
    } else if files.contains_key(&nested) {
        (nested, dir.join(name))
    } else {
        panic!(
            "no file for module {} in {}",
            path.join("::"),
            dir.display()
        );
    };
    let toks = tokens(&drop_test_items(&blank_literals(&files[&file])));
    for child in mod_declarations(&toks) {
        let mut p = path.clone();
        p.push(child);
        collect_module(files, &child_dir, p, out);
    }
    out.push((path, file));
}

// ----- lexing ------------------------------------------------------------

/// `src` with comments, string literals and char literals replaced by
/// spaces (line breaks kept, so lines still count).
fn blank_literals(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let blank = |out: &mut String, s: &[char]| {
        for &ch in s {
            out.push(if ch == '\n' { '\n' } else { ' ' });
        }
    };
    let ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut i = 0;
    while i < c.len() {
        let prev_ident = i > 0 && ident(c[i - 1]);
        let rest = &c[i..];
        let starts = |s: &str| rest.iter().take(s.len()).copied().eq(s.chars());
        let end = if starts("//") {
            rest.iter().position(|&x| x == '\n').unwrap_or(rest.len())
        } else if starts("/*") {
            let (mut depth, mut j) = (0, 0);
            loop {
                if j + 1 >= rest.len() {
                    break rest.len();
                }
                if rest[j] == '/' && rest[j + 1] == '*' {
                    depth += 1;
                    j += 2;
                } else if rest[j] == '*' && rest[j + 1] == '/' {
                    depth -= 1;
                    j += 2;
                    if depth == 0 {
                        break j;
                    }
                } else {
                    j += 1;
                }
            }
        } else if !prev_ident && (starts("r\"") || starts("r#") || starts("br\"") || starts("br#"))
        {
            let k = if rest[0] == 'b' { 2 } else { 1 };
            let hashes = rest[k..].iter().take_while(|&&x| x == '#').count();
            let open = k + hashes;
            if rest.get(open) != Some(&'"') {
                out.push(c[i]);
                i += 1;
                continue;
            }
            let close: String = std::iter::once('"')
                .chain(std::iter::repeat_n('#', hashes))
                .collect();
            let close: Vec<char> = close.chars().collect();
            let mut j = open + 1;
            while j < rest.len() && !rest[j..].starts_with(&close) {
                j += 1;
            }
            (j + close.len()).min(rest.len())
        } else if rest[0] == '"' || (!prev_ident && starts("b\"")) {
            let mut j = if rest[0] == 'b' { 2 } else { 1 };
            while j < rest.len() && rest[j] != '"' {
                j += if rest[j] == '\\' { 2 } else { 1 };
            }
            (j + 1).min(rest.len())
        } else if rest[0] == '\'' || (!prev_ident && starts("b'")) {
            let k = if rest[0] == 'b' { 1 } else { 0 };
            if rest.get(k + 1) == Some(&'\\') {
                // Past the escaped character (`'\''` ends at the next quote).
                let mut j = k + 3;
                while j < rest.len() && rest[j] != '\'' {
                    j += 1;
                }
                (j + 1).min(rest.len())
            } else if rest.get(k + 2) == Some(&'\'') {
                k + 3
            } else {
                // A lifetime or a label.
                out.push(c[i]);
                i += 1;
                continue;
            }
        } else {
            out.push(c[i]);
            i += 1;
            continue;
        };
        blank(&mut out, &rest[..end]);
        i += end;
    }
    out
}

/// `src` (literals blanked) with every `#[cfg(test)]` (or
/// `#[cfg(all(test, ...))]`) item blanked.
fn drop_test_items(src: &str) -> String {
    let mut c: Vec<char> = src.chars().collect();
    let mut i = 0;
    while i < c.len() {
        if c[i] != '#' || c.get(i + 1) != Some(&'[') {
            i += 1;
            continue;
        }
        let attr_end = matching(&c, i + 1);
        let attr: String = c[i + 2..attr_end]
            .iter()
            .filter(|x| !x.is_whitespace())
            .collect();
        let test_only = attr == "cfg(test)"
            || (attr.starts_with("cfg(all(")
                && attr["cfg(all(".len()..]
                    .split([',', ')'])
                    .any(|t| t == "test"));
        if !test_only {
            i = attr_end + 1;
            continue;
        }
        // The item: up to its `;` or its closing brace.
        let mut j = attr_end + 1;
        let end = loop {
            if j >= c.len() {
                break c.len() - 1;
            }
            match c[j] {
                ';' => break j,
                '{' => break matching(&c, j),
                '(' | '[' => j = matching(&c, j) + 1,
                _ => j += 1,
            }
        };
        for x in &mut c[i..=end] {
            if *x != '\n' {
                *x = ' ';
            }
        }
        i = end + 1;
    }
    c.into_iter().collect()
}

/// The index of the bracket that closes the one at `open`.
fn matching(c: &[char], open: usize) -> usize {
    let mut depth = 0i32;
    for (j, &x) in c.iter().enumerate().skip(open) {
        match x {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => {
                depth -= 1;
                if depth == 0 {
                    return j;
                }
            }
            _ => {}
        }
    }
    c.len() - 1
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    /// `::`
    Path,
    Punct(char),
}

/// Identifiers, `::` and other punctuation, with their line numbers.
fn tokens(src: &str) -> Vec<(Tok, usize)> {
    let c: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if ch.is_alphanumeric() || ch == '_' {
            let start = i;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push((Tok::Ident(c[start..i].iter().collect()), line));
        } else if ch == ':' && c.get(i + 1) == Some(&':') {
            out.push((Tok::Path, line));
            i += 2;
        } else {
            out.push((Tok::Punct(ch), line));
            i += 1;
        }
    }
    out
}

fn ident(t: Option<&(Tok, usize)>) -> Option<&str> {
    match t {
        Some((Tok::Ident(s), _)) => Some(s),
        _ => None,
    }
}

// ----- what a file declares and reaches ------------------------------------

/// The names of `mod name;` declarations (files, not inline modules).
fn mod_declarations(toks: &[(Tok, usize)]) -> Vec<String> {
    let mut out = Vec::new();
    for w in toks.windows(3) {
        if ident(Some(&w[0])) == Some("mod") && w[2].0 == Tok::Punct(';') {
            if let Some(name) = ident(Some(&w[1])) {
                out.push(name.to_string());
            }
        }
    }
    out
}

/// Root re-exports: `pub use module::{A, B};` maps `A` and `B` to `module`.
fn root_reexports(lib: &[(Tok, usize)]) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut i = 0;
    while i + 2 < lib.len() {
        if ident(lib.get(i)) == Some("pub") && ident(lib.get(i + 1)) == Some("use") {
            let Some(module) = ident(lib.get(i + 2)) else {
                i += 1;
                continue;
            };
            let mut j = i + 3;
            while j < lib.len() && lib[j].0 != Tok::Punct(';') {
                if let Some(name) = ident(lib.get(j)) {
                    if name != "as" && name != "self" {
                        out.insert(name.to_string(), module.to_string());
                    }
                }
                j += 1;
            }
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

/// The top-level modules the paths of one file reach, with the line of
/// each path. `path` is the file's module path (its first element, its
/// top-level module).
fn reached_modules(
    toks: &[(Tok, usize)],
    path: &[String],
    tops: &BTreeSet<String>,
    reexports: &BTreeMap<String, String>,
    problems: &mut Vec<String>,
    file: &Path,
) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    // Inline modules open at a brace depth: `(depth, name)`.
    let mut inline: Vec<(i32, String)> = Vec::new();
    let mut depth = 0i32;
    let mut i = 0;
    while i < toks.len() {
        let (t, line) = &toks[i];
        let after_path = i > 0 && toks[i - 1].0 == Tok::Path;
        match t {
            Tok::Punct('{') => {
                depth += 1;
                if i >= 2 && ident(toks.get(i - 2)) == Some("mod") {
                    if let Some(name) = ident(toks.get(i - 1)) {
                        inline.push((depth, name.to_string()));
                    }
                }
            }
            Tok::Punct('}') => {
                if inline.last().is_some_and(|(d, _)| *d == depth) {
                    inline.pop();
                }
                depth -= 1;
            }
            Tok::Ident(s)
                if s == "crate"
                    && !after_path
                    && toks.get(i + 1).map(|t| &t.0) == Some(&Tok::Path) =>
            {
                for name in first_segments(toks, i + 2) {
                    out.extend(resolve_root(&name, tops, reexports, problems, file, *line));
                }
            }
            Tok::Ident(s) if s == "super" && !after_path => {
                let mut k = 0;
                let mut j = i;
                while ident(toks.get(j)) == Some("super")
                    && toks.get(j + 1).map(|t| &t.0) == Some(&Tok::Path)
                {
                    k += 1;
                    j += 2;
                }
                let here = path.len() + inline.len();
                if k >= here {
                    for name in first_segments(toks, j) {
                        out.extend(resolve_root(&name, tops, reexports, problems, file, *line));
                    }
                }
                // Past the chain (or past a lone `super`, as in `pub(super)`).
                i = j.max(i + 1);
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// The first segment of the path that starts at `at` (after `crate::`):
/// one name, or the first name of every item of a `{...}` group.
fn first_segments(toks: &[(Tok, usize)], at: usize) -> Vec<String> {
    match toks.get(at).map(|t| &t.0) {
        Some(Tok::Ident(s)) => vec![s.clone()],
        Some(Tok::Punct('{')) => {
            let mut out = Vec::new();
            let mut depth = 0;
            let mut item_start = true;
            for (t, _) in &toks[at..] {
                match t {
                    Tok::Punct('{') => {
                        depth += 1;
                        if depth == 1 {
                            item_start = true;
                        }
                        continue;
                    }
                    Tok::Punct('}') => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    Tok::Punct(',') if depth == 1 => {
                        item_start = true;
                        continue;
                    }
                    Tok::Ident(s) if depth == 1 && item_start => out.push(s.clone()),
                    _ => {}
                }
                item_start = false;
            }
            out
        }
        _ => Vec::new(),
    }
}

/// The top-level module a name at the crate root stands for: a module, or
/// the module of a root re-export (`self`: the root itself, none).
fn resolve_root(
    name: &str,
    tops: &BTreeSet<String>,
    reexports: &BTreeMap<String, String>,
    problems: &mut Vec<String>,
    file: &Path,
    line: usize,
) -> Option<(String, usize)> {
    if tops.contains(name) {
        Some((name.to_string(), line))
    } else if let Some(m) = reexports.get(name) {
        Some((m.clone(), line))
    } else {
        if name != "self" {
            problems.push(format!(
                "{}:{line}: `crate::{name}` is neither a module nor a root re-export",
                file.display()
            ));
        }
        None
    }
}

/// The strongly connected components of more than one module (Tarjan).
fn cycles(
    nodes: &BTreeSet<String>,
    edges: &BTreeMap<(String, String), String>,
) -> Vec<Vec<String>> {
    let names: Vec<&String> = nodes.iter().collect();
    let index: BTreeMap<&String, usize> = names.iter().enumerate().map(|(i, n)| (*n, i)).collect();
    let mut adj = vec![Vec::new(); names.len()];
    for (a, b) in edges.keys() {
        if let (Some(&i), Some(&j)) = (index.get(a), index.get(b)) {
            adj[i].push(j);
        }
    }
    struct T {
        idx: Vec<Option<usize>>,
        low: Vec<usize>,
        on: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(v: usize, adj: &[Vec<usize>], t: &mut T) {
        t.idx[v] = Some(t.next);
        t.low[v] = t.next;
        t.next += 1;
        t.stack.push(v);
        t.on[v] = true;
        for &w in &adj[v] {
            match t.idx[w] {
                None => {
                    visit(w, adj, t);
                    t.low[v] = t.low[v].min(t.low[w]);
                }
                Some(iw) if t.on[w] => t.low[v] = t.low[v].min(iw),
                _ => {}
            }
        }
        if Some(t.low[v]) == t.idx[v] {
            let mut comp = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on[w] = false;
                comp.push(w);
                if w == v {
                    break;
                }
            }
            t.out.push(comp);
        }
    }
    let n = names.len();
    let mut t = T {
        idx: vec![None; n],
        low: vec![0; n],
        on: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if t.idx[v].is_none() {
            visit(v, &adj, &mut t);
        }
    }
    t.out
        .into_iter()
        .filter(|c| c.len() > 1)
        .map(|c| {
            let mut c: Vec<String> = c.into_iter().map(|i| names[i].clone()).collect();
            c.sort();
            c
        })
        .collect()
}
