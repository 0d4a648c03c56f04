//! The reference scenes (`reference/scenes/*.toml`), for the tests that run every one.

use ocean_core::scene::Scene;

/// Every reference scene with its name (the file's stem), in name order; a file that does not
/// load fails the test that asked, naming it.
pub fn reference_scenes() -> Vec<(String, Scene)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("reference/scenes");
    let mut paths: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|p| {
            let name = p.file_stem().unwrap_or_default().to_string_lossy().into_owned();
            let scene = Scene::load(&p).unwrap_or_else(|e| panic!("{name}: {e}"));
            (name, scene)
        })
        .collect()
}
