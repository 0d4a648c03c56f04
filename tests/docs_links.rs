//! Every relative link of the README (and of any Markdown under `docs/`) leads somewhere: the
//! file exists in the repository, and an anchor names a heading of its file (GitHub's slugs).
//! A user's clone has nothing outside the repository, so a link out of it is an error too.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// GitHub's anchor of a heading: lower case, spaces to `-`, punctuation other than `-` and
/// `_` dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The lines of a Markdown text outside fenced code blocks.
fn prose(text: &str) -> impl Iterator<Item = &str> {
    let mut fenced = false;
    text.lines().filter(move |line| {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            return false;
        }
        !fenced
    })
}

/// The anchors of a Markdown text's headings (outside code blocks).
fn anchors(text: &str) -> Vec<String> {
    prose(text).filter(|l| l.starts_with('#')).map(|l| slug(l.trim_start_matches('#'))).collect()
}

/// The targets of a Markdown text's links and images (`](target)`), outside code blocks and
/// inline code.
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in prose(text) {
        // Inline code spans hold examples, not links.
        let prose: String =
            line.split('`').enumerate().filter(|(i, _)| i % 2 == 0).map(|(_, s)| s).collect();
        let mut rest = prose.as_str();
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let Some(end) = after.find(')') else { break };
            out.push(after[..end].split_whitespace().next().unwrap_or("").to_owned());
            rest = &after[end..];
        }
    }
    out
}

/// The broken relative links of the Markdown file `md`.
fn broken(md: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(md).unwrap();
    let dir = md.parent().unwrap();
    let mut bad = Vec::new();
    for target in links(&text) {
        if target.contains("://") || target.starts_with("mailto:") {
            continue;
        }
        let (file, anchor) = target.split_once('#').unwrap_or((&target, ""));
        let path = if file.is_empty() { md.to_owned() } else { dir.join(file) };
        let inside =
            path.canonicalize().ok().filter(|p| p.starts_with(root().canonicalize().unwrap()));
        let Some(path) = inside else {
            bad.push(format!("{}: `{target}`: no such file in the repository", md.display()));
            continue;
        };
        if !anchor.is_empty() && path.extension().is_some_and(|e| e == "md") {
            let text = std::fs::read_to_string(&path).unwrap();
            if !anchors(&text).iter().any(|a| a == anchor) {
                bad.push(format!("{}: `{target}`: no heading with that anchor", md.display()));
            }
        }
    }
    bad
}

/// The repository's Markdown pages: the README and everything under `docs/`.
fn pages() -> Vec<PathBuf> {
    let mut out = vec![root().join("README.md")];
    let mut stack = vec![root().join("docs")];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p);
            }
        }
    }
    out
}

#[test]
fn every_relative_link_of_the_docs_leads_somewhere() {
    let bad: Vec<String> = pages().iter().flat_map(|p| broken(p)).collect();
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn the_checker_finds_a_missing_file_a_missing_anchor_and_a_link_out() {
    let dir = tempfile::tempdir_in(root().join("target")).unwrap();
    let md = dir.path().join("page.md");
    std::fs::write(
        &md,
        "# A heading, with (punctuation)\n[ok](#a-heading-with-punctuation) \
         [gone](nothing.png) [no anchor](#nowhere) [out](../../../../etc/hostname) \
         `[code](not-a-link.md)`\n```\n[fenced](also-not.md)\n```\n",
    )
    .unwrap();
    let bad = broken(&md);
    assert_eq!(bad.len(), 3, "{bad:#?}");
    assert!(bad[0].contains("nothing.png") && bad[1].contains("#nowhere"), "{bad:#?}");
    assert!(bad[2].contains("etc/hostname"), "{bad:#?}");
}
