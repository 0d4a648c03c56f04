//! Every scene in reference/scenes parses and validates; the built-in scene is the file.

use std::path::Path;

use ocean_core::scene::{DEFAULT_SCENE_TOML, Scene, SceneSource};

fn scene_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("reference/scenes")
}

#[test]
fn reference_scenes_parse() {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(scene_dir()).expect("reference/scenes must exist") {
        let path = entry.expect("readable dir entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
            names.push(path.file_stem().map(|s| s.to_string_lossy().into_owned()));
        }
    }
    // A missing scene is a failure, not a pass over an empty folder.
    for want in [
        "default",
        "calm",
        "storm",
        "shallow_reef",
        "phillips",
        "grazing_sun",
        "looking_down",
        "underwater_object",
    ] {
        assert!(names.iter().any(|n| n.as_deref() == Some(want)), "scene {want}.toml is missing");
    }
}

#[test]
fn builtin_scene_is_the_default_file() {
    let file = std::fs::read_to_string(scene_dir().join("default.toml")).expect("default.toml");
    assert_eq!(file, DEFAULT_SCENE_TOML);
    assert_eq!(Scene::from_toml(&file, SceneSource::Text).unwrap(), Scene::builtin());
}
