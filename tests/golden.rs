//! Golden CPU images (issue 3): small renders of the reference scenes compared bit for bit
//! with `reference/golden/<scene>.png`. A missing golden is a failure; goldens are written
//! only with `OCEAN_UPDATE_GOLDEN=1`. On a mismatch the actual image, the expected one and a
//! difference image go to `target/golden-failures/`.

use std::path::{Path, PathBuf};

use ocean_core::scene::Scene;

/// Golden size: small enough for CI, large enough to show every pass.
const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn render_small(scene_file: &Path) -> Vec<u8> {
    let mut scene = Scene::load(scene_file).expect("reference scene");
    scene.camera.width = WIDTH;
    scene.camera.height = HEIGHT;
    ocean_cpu::render_ldr(&scene).expect("render")
}

fn decode(path: &Path) -> Option<Vec<u8>> {
    let img = image::open(path).ok()?.to_rgba8();
    (img.width() == WIDTH && img.height() == HEIGHT).then(|| img.into_raw())
}

fn save(path: &Path, rgba: &[u8]) {
    image::RgbaImage::from_raw(WIDTH, HEIGHT, rgba.to_vec())
        .expect("size matches")
        .save(path)
        .expect("writable");
}

fn update_requested() -> bool {
    std::env::var_os("OCEAN_UPDATE_GOLDEN").is_some_and(|v| v == "1")
}

/// Compares `actual` with the golden of `name` (or, with `update`, replaces the golden);
/// returns a description of the mismatch.
fn check(name: &str, actual: &[u8], update: bool) -> Result<(), String> {
    let golden = root().join("reference/golden").join(format!("{name}.png"));
    if update {
        save(&golden, actual);
        return Ok(());
    }
    let Some(expected) = decode(&golden) else {
        return Err(format!(
            "golden {} is missing or unreadable: a missing golden is a failure; \
             create it with OCEAN_UPDATE_GOLDEN=1 after checking the picture",
            golden.display()
        ));
    };
    let differing = actual.chunks(4).zip(expected.chunks(4)).filter(|(a, e)| a != e).count();
    if differing == 0 {
        return Ok(());
    }
    let out = root().join("target/golden-failures");
    std::fs::create_dir_all(&out).expect("writable target dir");
    save(&out.join(format!("{name}.actual.png")), actual);
    save(&out.join(format!("{name}.expected.png")), &expected);
    let diff: Vec<u8> = actual
        .chunks(4)
        .zip(expected.chunks(4))
        .flat_map(|(a, e)| {
            let d = (0..3).map(|c| a[c].abs_diff(e[c])).max().unwrap_or(0);
            [d.saturating_mul(16), 0, 0, 255]
        })
        .collect();
    save(&out.join(format!("{name}.diff.png")), &diff);
    Err(format!("{name}: {differing} pixels differ from the golden (see {})", out.display()))
}

#[test]
fn reference_scenes_match_their_goldens() {
    let mut failures = Vec::new();
    let mut count = 0;
    let mut entries: Vec<_> = std::fs::read_dir(root().join("reference/scenes"))
        .expect("reference/scenes")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_stem().expect("file name").to_string_lossy().into_owned();
        count += 1;
        if let Err(e) = check(&name, &render_small(&path), update_requested()) {
            failures.push(e);
        }
    }
    assert!(count >= 5, "expected the reference scenes, found {count}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn golden_check_fails_on_one_changed_pixel_and_on_a_missing_golden() {
    // Negative controls of the comparator itself.
    let path = root().join("reference/scenes/calm.toml");
    let mut actual = render_small(&path);
    actual[4 * (WIDTH as usize * 90 + 160)] ^= 1;
    // Never in update mode: the control must not write a golden.
    assert!(check("calm", &actual, false).is_err(), "one changed pixel must fail");
    assert!(check("no-such-scene", &actual, false).is_err(), "a missing golden must fail");
}
