//! The WGSL sources of the render stages, embedded in the binary (the registry,
//! [`crate::registry`], holds them), and their `#import`s.
//!
//! A stage's complete source is [`stage_source_with`]: its file with each line of the form
//!
//! ```text
//! // #import shared/NAME.wgsl
//! // #import technique/STAGE
//! ```
//!
//! replaced by the text of `shaders/shared/NAME.wgsl`, or of the file of the technique the
//! frame chose for technique stage STAGE (`shaders/<stage>/<technique>.wgsl`: composition, so
//! that the water shader reads "the sky" without naming a sky model). Imported files' own
//! imports are resolved the same way. Each file is included once per stage, at its first
//! import; a later import of it is dropped, so two files may both import a third. An import of
//! an unknown file, of a technique without WGSL, an import cycle or a malformed import line is
//! an error. Nothing else is preprocessed: the result is plain WGSL, which `tests/wgsl.rs`
//! parses and validates with naga.
//!
//! Adding a file: put it under `shaders/` and list it in the registry. `tests/wgsl.rs` fails on
//! a file in `shaders/` that is not listed there, and on a listed piece that is missing.

use crate::plan::{Stage, System, Techniques};
use crate::registry::{SHARED, STAGES, TECHNIQUE_FILES};
use crate::{Error, Result};

/// What starts an import line (after leading white space).
const IMPORT_PREFIX: &str = "// #import ";

/// The names of the stages with WGSL, in the registry's order.
pub fn stage_names() -> impl Iterator<Item = &'static str> {
    STAGES.iter().map(|s| s.name)
}

/// The paths below `shaders/` of every embedded file: stages (`sky.wgsl`), shared files
/// (`shared/camera.wgsl`) and technique files (`sky/preetham.wgsl`): what `tests/wgsl.rs`
/// compares with the folder.
pub fn embedded_files() -> Vec<String> {
    STAGES
        .iter()
        .map(|s| s.file.to_owned())
        .chain(SHARED.iter().map(|f| f.file.to_owned()))
        .chain(TECHNIQUE_FILES.iter().map(|f| f.file.to_owned()))
        .collect()
}

/// The text of an embedded non-stage file as stored, imports unresolved (`path` like
/// `shared/camera.wgsl` or `sky/preetham.wgsl`).
pub fn shared_file(path: &str) -> Option<&'static str> {
    SHARED
        .iter()
        .find(|f| f.file == path)
        .map(|f| f.source)
        .or_else(|| TECHNIQUE_FILES.iter().find(|f| f.file == path).map(|f| f.source))
}

/// [`stage_source_with`] for the default system's techniques (`hu`).
///
/// # Errors
/// As [`stage_source_with`].
pub fn stage_source(stage: &str) -> Result<String> {
    stage_source_with(stage, &Techniques::of_system(System::Hu))
}

/// The complete WGSL of `stage` (one of the registry's stages) for the chosen `techniques`,
/// its imports resolved as the module doc says.
///
/// # Errors
/// [`Error::ShaderSource`] for an unknown stage, an import of an unknown file or of a
/// technique without WGSL, an import cycle or a malformed import line.
pub fn stage_source_with(stage: &str, techniques: &Techniques) -> Result<String> {
    let Some(entry) = STAGES.iter().find(|s| s.name == stage) else {
        return Err(Error::ShaderSource {
            stage: stage.to_owned(),
            reason: format!(
                "no such stage (known: {})",
                stage_names().collect::<Vec<_>>().join(", ")
            ),
        });
    };
    let mut out = String::with_capacity(entry.source.len() * 4);
    let mut included = Vec::new();
    let mut stack = vec![entry.file.to_owned()];
    let source = crate::mutants::apply(entry.file, entry.source);
    resolve(stage, &source, techniques, &mut stack, &mut included, &mut out)?;
    Ok(out)
}

/// Appends `source` to `out` with its imports resolved. `stack` holds the chain of files being
/// expanded (for cycle detection), `included` every file already in `out`.
fn resolve(
    stage: &str,
    source: &str,
    techniques: &Techniques,
    stack: &mut Vec<String>,
    included: &mut Vec<String>,
    out: &mut String,
) -> Result<()> {
    for line in source.lines() {
        let Some(import) = import_path(stage, line)? else {
            out.push_str(line);
            out.push('\n');
            continue;
        };
        let path = match import.strip_prefix("technique/") {
            Some(name) => technique_path(stage, name, techniques)?,
            None => import.to_owned(),
        };
        if stack.contains(&path) {
            return Err(Error::ShaderSource {
                stage: stage.to_owned(),
                reason: format!("import cycle: {} -> {path}", stack.join(" -> ")),
            });
        }
        if included.contains(&path) {
            continue;
        }
        let Some(text) = shared_file(&path) else {
            return Err(Error::ShaderSource {
                stage: stage.to_owned(),
                reason: format!("`{}` imports unknown file `{path}`", stack.join(" -> ")),
            });
        };
        let text = crate::mutants::apply(&path, text);
        out.push_str(&format!("// ---- begin {path}\n"));
        stack.push(path.clone());
        resolve(stage, &text, techniques, stack, included, out)?;
        stack.pop();
        included.push(path.clone());
        out.push_str(&format!("// ---- end {path}\n"));
    }
    Ok(())
}

/// The file of the technique chosen for technique stage `name`.
fn technique_path(stage: &str, name: &str, techniques: &Techniques) -> Result<String> {
    let err = |reason: String| Error::ShaderSource { stage: stage.to_owned(), reason };
    let which = Stage::ALL
        .into_iter()
        .find(|s| s.name() == name)
        .ok_or_else(|| err(format!("`// #import technique/{name}`: no such technique stage")))?;
    let t = techniques.of(which);
    crate::registry::technique_file(t)
        .map(|f| f.file.to_owned())
        .ok_or_else(|| err(format!("technique {which}/{} has no WGSL", t.name)))
}

/// The imported path if `line` is an import line, `None` for any other line.
fn import_path<'a>(stage: &str, line: &'a str) -> Result<Option<&'a str>> {
    let Some(rest) = line.trim_start().strip_prefix(IMPORT_PREFIX) else {
        return Ok(None);
    };
    let path = rest.trim_end();
    let word = |name: &str| {
        !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    let well_formed =
        path.strip_prefix("shared/").and_then(|p| p.strip_suffix(".wgsl")).is_some_and(word)
            || path.strip_prefix("technique/").is_some_and(word);
    if well_formed {
        Ok(Some(path))
    } else {
        Err(Error::ShaderSource {
            stage: stage.to_owned(),
            reason: format!(
                "malformed import line `{line}` (want `// #import shared/NAME.wgsl` or \
                 `// #import technique/STAGE`)"
            ),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The resolver on made-up sources, through the same `resolve` the stages use.
    fn resolve_text(text: &str) -> Result<String> {
        let mut out = String::new();
        let t = Techniques::of_system(System::Hu);
        resolve("test", text, &t, &mut vec!["test.wgsl".into()], &mut Vec::new(), &mut out)?;
        Ok(out)
    }

    #[test]
    fn every_stage_resolves_and_imports_are_gone() {
        for stage in stage_names() {
            let src = stage_source(stage).unwrap();
            assert!(!src.contains(IMPORT_PREFIX), "{stage}: an import is left");
            let render = src.contains("fn vs_main") && src.contains("fn fs_main");
            assert!(render || src.contains("@compute"), "{stage}: no entry points");
        }
    }

    #[test]
    fn each_shared_file_is_included_once() {
        let src = resolve_text(
            "// #import shared/camera.wgsl\n// #import technique/sky\n\
             // #import shared/camera.wgsl\n// #import technique/sky\n",
        )
        .unwrap();
        assert_eq!(src.matches("// ---- begin shared/camera.wgsl").count(), 1);
        assert_eq!(src.matches("struct CameraUniforms").count(), 1);
        assert_eq!(src.matches("// ---- begin sky/preetham.wgsl").count(), 1);
    }

    #[test]
    fn unknown_stage_and_unknown_import_are_errors() {
        let err = stage_source("nope").unwrap_err().to_string();
        assert!(err.contains("no such stage") && err.contains("sky"), "{err}");
        let err = resolve_text("// #import shared/missing.wgsl\n").unwrap_err().to_string();
        assert!(err.contains("unknown file `shared/missing.wgsl`"), "{err}");
        let err = resolve_text("// #import technique/clouds\n").unwrap_err().to_string();
        assert!(err.contains("no such technique stage"), "{err}");
        // A stage whose techniques have no WGSL file of their own is refused by name.
        let t = Techniques::of_system(System::Hu);
        let mut out = String::new();
        let err =
            resolve("test", "// #import technique/waves\n", &t, &mut vec![], &mut vec![], &mut out)
                .unwrap_err()
                .to_string();
        assert!(err.contains("waves/fft has no WGSL"), "{err}");
        let text = "// #import technique/shading\n";
        // Control: the built technique of the same stage resolves.
        let t = Techniques::with_overrides(System::Hu, [(Stage::Shading, "coastal")]).unwrap();
        resolve("test", text, &t, &mut vec![], &mut vec![], &mut String::new()).unwrap();
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
        let t = Techniques::of_system(System::Hu);
        let err = resolve(
            "test",
            "// #import shared/camera.wgsl\n",
            &t,
            &mut stack,
            &mut vec![],
            &mut out,
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("import cycle"), "{err}");
    }

    #[test]
    fn embedded_files_lists_stages_and_shared() {
        let files = embedded_files();
        for stage in stage_names() {
            assert!(files.contains(&format!("{stage}.wgsl")));
        }
        assert!(files.contains(&"sky/preetham.wgsl".to_owned()));
    }
}
