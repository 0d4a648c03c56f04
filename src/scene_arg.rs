//! The scene a command renders: a file or the built-in default scene, and `--system`.

use std::path::PathBuf;

use ocean_core::plan::{System, Techniques};
use ocean_core::scene::Scene;

/// `--system NAME`, shared by `render`, `plan`, `compare` and `view`.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct SystemArg {
    /// The seed paper's system to render (`hu`, `chiu`, `welch`, `coastal`); overrides the
    /// scene's `system`, keeps its `[techniques]`.
    #[arg(long, value_name = "NAME")]
    pub system: Option<String>,
}

/// Loads a scene file, or the built-in default scene when none is given, and applies
/// `--system`.
///
/// # Errors
/// A scene that does not load or validate; an unknown system (the message lists the known
/// ones) or one whose techniques are not yet available.
pub fn load_scene(path: Option<&PathBuf>, system: &SystemArg) -> anyhow::Result<Scene> {
    let chosen = match &system.system {
        Some(name) => Some(System::from_name(name).map_err(|e| anyhow::anyhow!("--system: {e}"))?),
        None => None,
    };
    // Without a scene file, a system with a scene of its own (`coastal`'s island) starts there.
    let mut scene = match path {
        Some(p) => Scene::load(p)?,
        None => chosen.map_or_else(Scene::builtin, Scene::builtin_for),
    };
    apply_system(&mut scene, system, chosen)?;
    Ok(scene)
}

/// `--system` on a loaded scene: its techniques checked against the chosen system.
fn apply_system(
    scene: &mut Scene,
    system: &SystemArg,
    chosen: Option<System>,
) -> anyhow::Result<()> {
    if let (Some(name), Some(chosen)) = (&system.system, chosen) {
        Techniques::of_overrides(chosen, &scene.techniques)
            .check()
            .map_err(|e| anyhow::anyhow!("--system {name}: {e}"))?;
        scene.system = chosen;
    }
    Ok(())
}

/// A scene from its TOML text (a dump's manifest), with `--system` applied as
/// [`load_scene`] does.
///
/// # Errors
/// Text that is not a valid scene, or a `--system` its techniques do not fit.
pub fn scene_from_text(text: &str, what: &str, system: &SystemArg) -> anyhow::Result<Scene> {
    let chosen = match &system.system {
        Some(name) => Some(System::from_name(name).map_err(|e| anyhow::anyhow!("--system: {e}"))?),
        None => None,
    };
    let mut scene = Scene::from_toml(text, ocean_core::scene::SceneSource::Text)
        .map_err(|e| anyhow::anyhow!("the scene in {what}: {e}"))?;
    apply_system(&mut scene, system, chosen)?;
    Ok(scene)
}

/// Checks a scene again after command-line flags changed it (`--time`, `--size`, `--seed`),
/// so that a flag is held to the same limits as the key it overrides; the error names both.
///
/// # Errors
/// The first value out of range, as `FLAGS: key `KEY`: what is allowed`.
pub fn revalidate(scene: &Scene, flags: &str) -> anyhow::Result<()> {
    scene.validate().map_err(|(key, message)| anyhow::anyhow!("{flags}: key `{key}`: {message}"))
}
