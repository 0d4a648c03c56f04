//! The WGSL sources of the render stages, embedded in the binary, and their `#import`s.
//!
//! Every `shaders/<stage>.wgsl` and `shaders/shared/<name>.wgsl` of the repository is compiled
//! into this crate with `include_str!`, so a program works from any folder. A stage's complete
//! source is [`stage_source`]: its file with each line of the form
//!
//! ```text
//! // #import shared/NAME.wgsl
//! ```
//!
//! replaced by the text of `shaders/shared/NAME.wgsl` (whose own imports are resolved the same
//! way). Each shared file is included once per stage, at its first import; a later import of
//! it is dropped, so two shared files may both import a third. An import of an unknown file,
//! an import cycle or a malformed import line is an error. Nothing else is preprocessed: the
//! result is plain WGSL, which `tests/wgsl.rs` parses and validates with naga.
//!
//! Adding a file: put it under `shaders/` and add it to [`STAGES`] and `STAGE_FILES` (a stage)
//! or to `SHARED_FILES` (a shared file). `tests/wgsl.rs` fails on a file in `shaders/` that is
//! not listed here.

use crate::{Error, Result};

/// The stages whose WGSL is present, in the order of `DESIGN.md`'s stage table, then
/// `present` (the real-time viewer's copy of the output into its window; not a pass of the
/// frame plan).
pub const STAGES: &[&str] =
    &["waves", "fresnel_table", "sky", "objects", "shadow", "water", "tonemap", "present"];

/// `(stage, source)` for every stage in [`STAGES`].
const STAGE_FILES: &[(&str, &str)] = &[
    ("waves", include_str!("../../../shaders/waves.wgsl")),
    ("fresnel_table", include_str!("../../../shaders/fresnel_table.wgsl")),
    ("sky", include_str!("../../../shaders/sky.wgsl")),
    ("objects", include_str!("../../../shaders/objects.wgsl")),
    ("shadow", include_str!("../../../shaders/shadow.wgsl")),
    ("water", include_str!("../../../shaders/water.wgsl")),
    ("tonemap", include_str!("../../../shaders/tonemap.wgsl")),
    ("present", include_str!("../../../shaders/present.wgsl")),
];

/// `(path below shaders/, source)` for every shared file.
const SHARED_FILES: &[(&str, &str)] = &[
    ("shared/camera.wgsl", include_str!("../../../shaders/shared/camera.wgsl")),
    ("shared/frame.wgsl", include_str!("../../../shaders/shared/frame.wgsl")),
    ("shared/fullscreen.wgsl", include_str!("../../../shaders/shared/fullscreen.wgsl")),
    ("shared/preetham.wgsl", include_str!("../../../shaders/shared/preetham.wgsl")),
];

/// What starts an import line (after leading white space).
const IMPORT_PREFIX: &str = "// #import ";

/// The paths below `shaders/` of every embedded file, stages (`sky.wgsl`) and shared files
/// (`shared/camera.wgsl`): what `tests/wgsl.rs` compares with the folder.
pub fn embedded_files() -> Vec<String> {
    STAGE_FILES
        .iter()
        .map(|(stage, _)| format!("{stage}.wgsl"))
        .chain(SHARED_FILES.iter().map(|(path, _)| (*path).to_owned()))
        .collect()
}

/// The text of a shared file as stored, imports unresolved (`path` like `shared/camera.wgsl`).
pub fn shared_file(path: &str) -> Option<&'static str> {
    SHARED_FILES.iter().find(|(p, _)| *p == path).map(|(_, src)| *src)
}

/// The complete WGSL of `stage` (one of [`STAGES`]), its imports resolved as the module doc
/// says.
///
/// # Errors
/// [`Error::ShaderSource`] for an unknown stage, an import of an unknown file, an import cycle
/// or an import line that is not exactly `// #import shared/NAME.wgsl`.
pub fn stage_source(stage: &str) -> Result<String> {
    let Some((_, source)) = STAGE_FILES.iter().find(|(s, _)| *s == stage) else {
        return Err(Error::ShaderSource {
            stage: stage.to_owned(),
            reason: format!("no such stage (known: {})", STAGES.join(", ")),
        });
    };
    let mut out = String::with_capacity(source.len() * 4);
    let mut included = Vec::new();
    let mut stack = vec![format!("{stage}.wgsl")];
    resolve(stage, source, &mut stack, &mut included, &mut out)?;
    Ok(out)
}

/// Appends `source` to `out` with its imports resolved. `stack` holds the chain of files being
/// expanded (for cycle detection), `included` every shared file already in `out`.
fn resolve(
    stage: &str,
    source: &str,
    stack: &mut Vec<String>,
    included: &mut Vec<String>,
    out: &mut String,
) -> Result<()> {
    for line in source.lines() {
        let Some(path) = import_path(stage, line)? else {
            out.push_str(line);
            out.push('\n');
            continue;
        };
        if stack.iter().any(|p| p == path) {
            return Err(Error::ShaderSource {
                stage: stage.to_owned(),
                reason: format!("import cycle: {} -> {path}", stack.join(" -> ")),
            });
        }
        if included.iter().any(|p| p == path) {
            continue;
        }
        let Some(text) = shared_file(path) else {
            return Err(Error::ShaderSource {
                stage: stage.to_owned(),
                reason: format!("`{}` imports unknown file `{path}`", stack.join(" -> ")),
            });
        };
        out.push_str(&format!("// ---- begin {path}\n"));
        stack.push(path.to_owned());
        resolve(stage, text, stack, included, out)?;
        stack.pop();
        included.push(path.to_owned());
        out.push_str(&format!("// ---- end {path}\n"));
    }
    Ok(())
}

/// The imported path if `line` is an import line, `None` for any other line.
fn import_path<'a>(stage: &str, line: &'a str) -> Result<Option<&'a str>> {
    let Some(rest) = line.trim_start().strip_prefix(IMPORT_PREFIX) else {
        return Ok(None);
    };
    let path = rest.trim_end();
    let well_formed =
        path.strip_prefix("shared/").and_then(|p| p.strip_suffix(".wgsl")).is_some_and(|name| {
            !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        });
    if well_formed {
        Ok(Some(path))
    } else {
        Err(Error::ShaderSource {
            stage: stage.to_owned(),
            reason: format!("malformed import line `{line}` (want `// #import shared/NAME.wgsl`)"),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The resolver on made-up sources, through the same `resolve` the stages use.
    fn resolve_text(text: &str) -> Result<String> {
        let mut out = String::new();
        resolve("test", text, &mut vec!["test.wgsl".into()], &mut Vec::new(), &mut out)?;
        Ok(out)
    }

    #[test]
    fn every_stage_resolves_and_imports_are_gone() {
        for stage in STAGES {
            let src = stage_source(stage).unwrap();
            assert!(!src.contains(IMPORT_PREFIX), "{stage}: an import is left");
            let render = src.contains("fn vs_main") && src.contains("fn fs_main");
            assert!(render || src.contains("@compute"), "{stage}: no entry points");
        }
    }

    #[test]
    fn each_shared_file_is_included_once() {
        let src = resolve_text(
            "// #import shared/camera.wgsl\n// #import shared/preetham.wgsl\n\
             // #import shared/camera.wgsl\n",
        )
        .unwrap();
        assert_eq!(src.matches("// ---- begin shared/camera.wgsl").count(), 1);
        assert_eq!(src.matches("struct CameraUniforms").count(), 1);
        assert_eq!(src.matches("// ---- begin shared/preetham.wgsl").count(), 1);
    }

    #[test]
    fn unknown_stage_and_unknown_import_are_errors() {
        let err = stage_source("nope").unwrap_err().to_string();
        assert!(err.contains("no such stage") && err.contains("sky"), "{err}");
        let err = resolve_text("// #import shared/missing.wgsl\n").unwrap_err().to_string();
        assert!(err.contains("unknown file `shared/missing.wgsl`"), "{err}");
    }

    #[test]
    fn malformed_imports_are_errors() {
        for line in [
            "// #import camera.wgsl",
            "// #import shared/camera",
            "// #import shared/../sky.wgsl",
            "// #import shared/.wgsl",
        ] {
            let err = resolve_text(line).unwrap_err().to_string();
            assert!(err.contains("malformed import"), "{line}: {err}");
        }
        // A comment that merely mentions imports is not an import line.
        assert_eq!(resolve_text("// imports: none\n").unwrap(), "// imports: none\n");
    }

    #[test]
    fn cycles_are_errors() {
        // A file importing itself is the smallest cycle; the stack check catches any length.
        let mut out = String::new();
        let mut stack = vec!["test.wgsl".to_owned(), "shared/camera.wgsl".to_owned()];
        let err =
            resolve("test", "// #import shared/camera.wgsl\n", &mut stack, &mut vec![], &mut out)
                .unwrap_err()
                .to_string();
        assert!(err.contains("import cycle"), "{err}");
    }

    #[test]
    fn embedded_files_lists_stages_and_shared() {
        let files = embedded_files();
        for stage in STAGES {
            assert!(files.contains(&format!("{stage}.wgsl")));
        }
        assert!(files.contains(&"shared/preetham.wgsl".to_owned()));
    }
}
