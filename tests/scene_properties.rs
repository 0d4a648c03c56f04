//! The invariant of issue 11: **validation accepts ⇒ the frame renders, with only finite
//! pixels**, and the displacement map it would write (`ocean heightfield`) only finite
//! samples. The scenes sit at the edges of `ocean_core::scene::LIMITS` (the validation's own
//! table, read by `tests/support/extreme_scene.rs`); the check, finiteness, is independent of
//! the code under test. The GPU runs a sample of the same scenes in `tests/gpu_frame_graph.rs`.
//!
//! Before the limits were tightened these failed: `sun.intensity = 1e300` (NaN pixels),
//! colours above f32::MAX, a 2147483647 m box, `time_s = 1e307` (NaN), `patch_size_m = 1e-300`
//! (an error naming `eye.z`), `fov_y_deg = 5e-324`.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[path = "support/extreme_scene.rs"]
mod extreme_scene;

use extreme_scene::{Rng, cost_extremes, parse, per_key_extremes, random_extreme};
use ocean_core::plan::OutputKind;
use ocean_core::waves::Synthesizer;

/// Renders an accepted scene on the CPU; `Err` names what broke the invariant.
fn check(name: &str, text: &str, kind: OutputKind) -> Result<(), String> {
    let scene = parse(text).ok_or("refused")?;
    let r = ocean_cpu::render_scene(&scene, kind, &mut |_| {})
        .map_err(|e| format!("{name}: an accepted scene failed to render: {e}\n{text}"))?;
    let bad = r.buffers.hdr.color.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
    if bad > 0 {
        return Err(format!("{name}: {bad} non-finite HDR pixels\n{text}"));
    }
    let (w, h) = (scene.camera.width as usize, scene.camera.height as usize);
    if kind == OutputKind::Ldr && r.ldr.as_ref().map(Vec::len) != Some(w * h * 4) {
        return Err(format!("{name}: no 8-bit picture of {w}×{h}"));
    }
    if scene.ocean.resolution <= 256 {
        let modes = scene.ocean.displacement_modes().map_err(|e| format!("{name}: modes: {e}"))?;
        let maps = Synthesizer::<f32>::new(modes.resolution())
            .and_then(|mut s| s.synthesize(&modes, scene.ocean.time_s, scene.ocean.choppiness))
            .map_err(|e| format!("{name}: heightfield: {e}"))?;
        for (field, data) in maps.fields() {
            let bad = data.iter().filter(|v| !v.is_finite()).count();
            if bad > 0 {
                return Err(format!(
                    "{name}: heightfield {field}: {bad} non-finite samples\n{text}"
                ));
            }
        }
    }
    Ok(())
}

/// Renders every case; `refusals` is what validation must refuse (`None`: any number, at
/// least `min_accepted` accepted).
fn run_all(cases: &[(String, String)], refusals: Option<&[&str]>, min_accepted: usize) {
    let (mut accepted, mut failures, mut refused) = (0, Vec::new(), Vec::new());
    for (i, (name, text)) in cases.iter().enumerate() {
        let kind = if i % 3 == 0 { OutputKind::Hdr } else { OutputKind::Ldr };
        let start = std::time::Instant::now();
        let result = check(name, text, kind);
        if start.elapsed().as_secs_f64() > 2.0 {
            eprintln!("{name}: {:.1} s", start.elapsed().as_secs_f64());
        }
        match result {
            Ok(()) => accepted += 1,
            Err(e) if e == "refused" => refused.push(name.clone()),
            Err(e) => failures.push(e),
        }
    }
    eprintln!("{accepted} accepted and rendered, {} refused: {refused:?}", refused.len());
    assert!(
        failures.is_empty(),
        "{} of {accepted} accepted scenes broke the invariant:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(accepted >= min_accepted, "only {accepted} of {} scenes were accepted", cases.len());
    if let Some(expected) = refusals {
        assert_eq!(refused, expected, "the scenes refused by a cross-key check");
    }
}

#[test]
fn every_key_at_its_limits_renders_finite_pixels() {
    let cases = per_key_extremes();
    // Refused by a cross-key check by design: a divisor of 1 leaves the default 256² bump map
    // no finer waves; ±f64::MAX s is beyond the wave phase without a loop period; a camera
    // 1e7 m up is beyond the water mesh; the largest patch over the default 256² grid is
    // coarser than 16 m a sample; a 1e24 kg boat of 2 m sinks; a Gerstner lifetime range with
    // its ends swapped.
    let refused = [
        "ocean.patch_size_m = Max",
        "ocean.bump_patch_divisor = Min",
        "ocean.time_s = Min",
        "ocean.time_s = Max",
        "camera.position = Min",
        "camera.position = Max",
        "objects.*.mass_kg = Max",
        "gerstner.min_lifetime_s = Max",
        "gerstner.max_lifetime_s = Min",
    ];
    run_all(&cases, Some(&refused), 0);
}

#[test]
fn random_scenes_at_extreme_values_render_finite_pixels() {
    let mut rng = Rng(2026);
    let cases: Vec<(String, String)> =
        (0..400).map(|i| (format!("random {i}"), random_extreme(&mut rng))).collect();
    run_all(&cases, None, 100);
}

#[test]
fn cost_keys_at_their_limits_render_finite_pixels() {
    let cases = cost_extremes();
    // A 2² grid over the default 256 m patch is coarser than 16 m a sample; a 2² bump map
    // holds no wave finer than the default displacement map's.
    run_all(&cases, Some(&["ocean.resolution = Min", "ocean.bump_resolution = Min"]), 0);
}

#[test]
fn the_check_catches_a_non_finite_pixel() {
    // Negative control: the finiteness check itself sees a NaN (written into a render).
    let text = extreme_scene::scene_text(
        &[("camera.width", "4".into()), ("camera.height", "2".into())],
        &[],
    );
    let scene = parse(&text).unwrap();
    let mut r = ocean_cpu::render_scene(&scene, OutputKind::Hdr, &mut |_| {}).unwrap();
    r.buffers.hdr.color[3][1] = f32::NAN;
    let bad = r.buffers.hdr.color.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
    assert_eq!(bad, 1);
    assert!(parse("[sun]\nintensity = 1e300\n").is_none(), "the old NaN case is refused");
}

/// docs/scenes.md's table row of a limit.
fn readme_row(l: &ocean_core::scene::Limit) -> String {
    let n = ocean_core::error::number;
    let what = if l.whole { " (whole)" } else { "" };
    format!("| `{}` | {} | {}{what} | {} |", l.key, n(l.min), n(l.max), l.why)
}

#[test]
fn the_scene_reference_lists_every_limit_as_validation_applies_it() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scenes.md")).unwrap();
    let missing: Vec<String> = ocean_core::scene::LIMITS
        .iter()
        .map(readme_row)
        .filter(|row| !readme.contains(row.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/scenes.md rows missing or out of date:\n{}",
        missing.join("\n")
    );
}

/// The value just past a limit's bound (`above`: past its max), `None` where nothing lies
/// past it (−f64::MAX, ∞): for a whole key one more or less, else a relative step of 1e-6
/// (at least 1e-9).
fn past(l: &ocean_core::scene::Limit, above: bool) -> Option<f64> {
    let b = if above { l.max } else { l.min };
    if !b.is_finite() || b.abs() == f64::MAX {
        return None;
    }
    let step = if l.whole { 1.0 } else { (b.abs() * 1e-6).max(1e-9) };
    Some(if above { b + step } else { b - step })
}

/// The declaration of a key's range is what validation enforces: every key of `LIMITS` set
/// just past either bound (each component of a vector) is refused, naming that key, and at
/// the bound itself (the scenes of `every_key_at_its_limits_renders_finite_pixels`) is not
/// refused for it. A limit that validation forgot to check fails here; so does a check
/// that refuses inside the declared range.
#[test]
fn every_limit_is_enforced_at_both_bounds_and_names_its_key() {
    use extreme_scene::{VECTOR_KEYS, VECTOR2_KEYS, literal, scene_text};
    use ocean_core::scene::{LIMITS, SceneError, SceneSource};
    let refused_key =
        |text: &str| match ocean_core::scene::Scene::from_toml(text, SceneSource::Text) {
            Err(SceneError::Invalid { key, .. }) => Some(key.unwrap_or_default()),
            Err(e) => Some(format!("(no key) {e}")),
            Ok(_) => None,
        };
    let (mut checked, mut failures) = (0, Vec::new());
    for l in LIMITS {
        // Where an index stands in the key, any element (an object of the kind that takes
        // the key) may be the one refused.
        let pattern = |k: &str| {
            k.split('.')
                .map(|p| if p.parse::<usize>().is_ok() { "*" } else { p })
                .collect::<Vec<_>>()
                .join(".")
        };
        let n = if VECTOR_KEYS.contains(&l.key) {
            3
        } else if VECTOR2_KEYS.contains(&l.key) {
            2
        } else {
            1
        };
        for above in [false, true] {
            let Some(v) = past(l, above) else { continue };
            // `literal` writes a whole number unsigned; one below 0 must read as itself.
            let mut value = if l.whole { format!("{}", v as i64) } else { literal(l, v) };
            if n > 1 || l.key == "chiu.scales" {
                value = format!("[{}]", vec![value; n].join(", "));
            }
            let mut values = vec![(l.key, value)];
            if !l.key.starts_with("sun.") {
                values.push(("sun.intensity", "5.0".to_owned()));
            }
            let text = scene_text(&values, &["sphere", "box", "boat"]);
            checked += 1;
            match refused_key(&text) {
                Some(k) if pattern(&k) == l.key => {}
                Some(k) => failures.push(format!("{} = {v}: refused for `{k}`", l.key)),
                None => failures.push(format!("{} = {v}: accepted", l.key)),
            }
        }
    }
    eprintln!("{checked} values just past a limit, {} not refused for their key", failures.len());
    assert!(checked > 150, "only {checked} bounds were tried");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
