//! The crates' shape: no import circle between the top-level modules of ocean-core, ocean-cpu,
//! ocean-gpu or ocean-verify (docs/design.md, "The crates' layers"), and no function of those
//! crates or of the root package's `src/` over 150 lines outside its unit tests. A circle is a
//! strongly connected set of modules; the failure names each, with a file and line for every
//! edge inside it, so the one to cut can be chosen.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A crate's source, as (path relative to its `src`, text) pairs.
type Sources = Vec<(String, String)>;

fn sources(src: &Path) -> Sources {
    fn walk(dir: &Path, base: &Path, out: &mut Sources) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, base, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let rel = p.strip_prefix(base).unwrap().to_string_lossy().replace('\\', "/");
                out.push((rel, std::fs::read_to_string(&p).unwrap()));
            }
        }
    }
    let mut out = Vec::new();
    walk(src, src, &mut out);
    out.sort();
    out
}

/// The top-level module a file belongs to (`None`: the crate root).
fn top_module(rel: &str) -> Option<String> {
    let first = rel.split('/').next()?;
    let name = first.strip_suffix(".rs").unwrap_or(first);
    (!matches!(name, "lib" | "main")).then(|| name.to_owned())
}

/// The text of a file that the compiler builds outside tests: the unit tests' module (which
/// may import anything) and comments (doc links name modules without importing them) left
/// out.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]\nmod tests").next().unwrap_or(text);
    text.lines().map(|l| l.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n")
}

/// The modules each line of `code` names through `crate::`, with their 1-based lines:
/// `crate::x::…` and the groups of `use crate::{x, y::…}`.
fn named_modules(code: &str) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for (n, line) in code.lines().enumerate() {
        let mut rest = line;
        while let Some(at) = rest.find("crate::") {
            let after = &rest[at + "crate::".len()..];
            if let Some(group) = after.strip_prefix('{') {
                // `use crate::{a, b::c, d::{e, f}}` on one line: the first segment of each item.
                let mut depth = 0;
                let mut item = String::new();
                for c in group.chars() {
                    match c {
                        '{' => depth += 1,
                        '}' if depth == 0 => break,
                        '}' => depth -= 1,
                        ',' if depth == 0 => {
                            out.push((item.trim().split("::").next().unwrap_or("").into(), n + 1));
                            item.clear();
                            continue;
                        }
                        _ => {}
                    }
                    if depth == 0 {
                        item.push(c);
                    }
                }
                out.push((item.trim().split("::").next().unwrap_or("").into(), n + 1));
            } else {
                let name: String =
                    after.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                out.push((name, n + 1));
            }
            rest = after;
        }
    }
    out.retain(|(m, _)| !m.is_empty());
    out
}

/// The import graph: for each (from, to) module pair, the first place that makes the edge.
fn edges(files: &Sources) -> BTreeMap<(String, String), String> {
    let tops: BTreeSet<String> = files.iter().filter_map(|(r, _)| top_module(r)).collect();
    let mut out = BTreeMap::new();
    for (rel, text) in files {
        let Some(from) = top_module(rel) else { continue };
        for (to, line) in named_modules(&code(text)) {
            if to != from && tops.contains(&to) {
                out.entry((from.clone(), to)).or_insert_with(|| format!("{rel}:{line}"));
            }
        }
    }
    out
}

/// The strongly connected sets of more than one module (Tarjan), each sorted.
fn circles(edges: &BTreeMap<(String, String), String>) -> Vec<Vec<String>> {
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (a, b) in edges.keys() {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default();
    }
    struct Tarjan<'a> {
        next: &'a BTreeMap<&'a str, Vec<&'a str>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        out: Vec<Vec<String>>,
    }
    impl<'a> Tarjan<'a> {
        fn visit(&mut self, v: &'a str) {
            let i = self.index.len();
            self.index.insert(v, i);
            self.low.insert(v, i);
            self.stack.push(v);
            for &w in &self.next[v] {
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let lw = self.low[w];
                    let lv = self.low.get_mut(v).unwrap();
                    *lv = (*lv).min(lw);
                } else if self.stack.contains(&w) {
                    let iw = self.index[w];
                    let lv = self.low.get_mut(v).unwrap();
                    *lv = (*lv).min(iw);
                }
            }
            if self.low[v] == self.index[v] {
                let mut set = Vec::new();
                while let Some(w) = self.stack.pop() {
                    set.push(w.to_owned());
                    if w == v {
                        break;
                    }
                }
                if set.len() > 1 {
                    set.sort();
                    self.out.push(set);
                }
            }
        }
    }
    let mut t = Tarjan {
        next: &next,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        out: Vec::new(),
    };
    for &v in next.keys() {
        if !t.index.contains_key(v) {
            t.visit(v);
        }
    }
    t.out
}

/// Each circle of a crate, with the edges inside it and where each is made.
fn report(files: &Sources) -> Vec<String> {
    let e = edges(files);
    circles(&e)
        .into_iter()
        .map(|set| {
            let inside: Vec<String> = e
                .iter()
                .filter(|((a, b), _)| set.contains(a) && set.contains(b))
                .map(|((a, b), at)| format!("  {a} -> {b} ({at})"))
                .collect();
            format!("circle {{{}}}:\n{}", set.join(", "), inside.join("\n"))
        })
        .collect()
}

/// The workspace's library crates under `crates/`.
const CRATES: [&str; 4] = ["ocean-core", "ocean-cpu", "ocean-gpu", "ocean-verify"];

fn crate_src(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("crates").join(name).join("src")
}

#[test]
fn no_crate_has_an_import_circle_between_its_modules() {
    let mut failures = Vec::new();
    for name in CRATES {
        let files = sources(&crate_src(name));
        assert!(files.len() > 3, "{name}: no sources found");
        // The graph is not empty: the check reads real imports.
        assert!(!edges(&files).is_empty(), "{name}: no imports found");
        failures.extend(report(&files).into_iter().map(|r| format!("{name}: {r}")));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_check_finds_a_circle_and_ignores_comments_and_unit_tests() {
    let file = |p: &str, t: &str| (p.to_owned(), t.to_owned());
    let files = vec![
        file("lib.rs", "pub mod a;\npub mod b;\npub mod c;\npub mod d;"),
        file("a.rs", "use crate::{b::X, d};\n"),
        file("b/mod.rs", "fn f() {}\n"),
        file("b/inner.rs", "fn g() -> u32 { crate::a::h() }\n"),
        // A doc link and a unit test name `a` without importing it.
        file(
            "c.rs",
            "/// See [`crate::a`].\nfn k() {}\n#[cfg(test)]\nmod tests {\n    use crate::a;\n}\n",
        ),
        file("d.rs", "pub struct D;\n"),
    ];
    let r = report(&files);
    assert_eq!(r.len(), 1, "{r:?}");
    assert!(r[0].starts_with("circle {a, b}"), "{r:?}");
    assert!(r[0].contains("a -> b (a.rs:1)") && r[0].contains("b -> a (b/inner.rs:1)"), "{r:?}");
    // Without the back edge there is no circle.
    let acyclic: Sources = files.into_iter().filter(|(p, _)| p != "b/inner.rs").collect();
    assert!(report(&acyclic).is_empty());
}

/// The functions of `text` (outside its unit tests) longer than `limit` lines, as
/// (name, first line, lines): from the `fn` line to the closing brace at its indentation.
fn long_functions(text: &str, limit: usize) -> Vec<(String, usize, usize)> {
    let text = text.split("#[cfg(test)]\nmod tests").next().unwrap_or(text);
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        // `fn` after an optional visibility and qualifiers (`pub(crate) const fn`, `async fn`).
        let mut head = ["pub(crate) ", "pub(super) ", "pub "]
            .iter()
            .find_map(|v| trimmed.strip_prefix(v))
            .unwrap_or(trimmed);
        for q in ["const ", "async ", "unsafe "] {
            head = head.strip_prefix(q).unwrap_or(head);
        }
        let Some(rest) = head.strip_prefix("fn ") else { continue };
        let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        // The body's opening line: the first at or after the signature ending in `{` (a
        // declaration without a body ends in `;` first).
        let Some(open) = (i..lines.len()).find(|&k| {
            let l = lines[k].trim_end();
            l.ends_with('{') || l.ends_with(';')
        }) else {
            continue;
        };
        if lines[open].trim_end().ends_with(';') {
            continue;
        }
        let close = (open + 1..lines.len()).find(|&k| {
            let l = lines[k];
            l.trim_start().starts_with('}') && l.len() - l.trim_start().len() == indent
        });
        if let Some(close) = close
            && close - i + 1 > limit
        {
            out.push((name, i + 1, close - i + 1));
        }
    }
    out
}

/// Every source folder the length rule covers, with the path it is reported by: each crate's
/// `src`, and the root package's.
fn all_src() -> Vec<(String, PathBuf)> {
    let mut out: Vec<(String, PathBuf)> =
        CRATES.iter().map(|n| (format!("crates/{n}/src"), crate_src(n))).collect();
    out.push(("src".to_owned(), PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src")));
    out
}

#[test]
fn no_function_is_over_150_lines() {
    let mut long = Vec::new();
    for (shown, src) in all_src() {
        let files = sources(&src);
        assert!(files.len() > 3, "{shown}: no sources found");
        for (rel, text) in &files {
            long.extend(
                long_functions(text, 150)
                    .into_iter()
                    .map(|(f, at, n)| format!("{shown}/{rel}:{at}: fn {f} is {n} lines")),
            );
        }
    }
    assert!(long.is_empty(), "split these at their seams:\n{}", long.join("\n"));
    // Negative control: a 151-line function is found, with or without qualifiers; a 150-line
    // one and a unit test's are not.
    let body = |n: usize| "    let x = 1;\n".repeat(n - 2);
    let text = format!(
        "pub fn long() {{\n{}}}\nfn short() {{\n{}}}\npub(crate) const fn qualified() {{\n{}}}\n\
         #[cfg(test)]\nmod tests {{\n    fn t() {{\n{}    }}\n}}\n",
        body(151),
        body(150),
        body(151),
        body(300)
    );
    let found = long_functions(&text, 150);
    assert_eq!(found, vec![("long".to_owned(), 1, 151), ("qualified".to_owned(), 302, 151)]);
}
