//! `ocean render --dump-passes DIR` and `ocean compare --against DIR`: the dump holds every
//! resource the frame's passes wrote, each as the manifest describes it; the oracle's own dump
//! compares clean; a texel past the tolerance, a missing resource or a wrong size fails, naming
//! the resource; a file with plain R, G, B, A channels is read too.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[path = "support/cli.rs"]
mod ocean_cli;

use std::path::{Path, PathBuf};
use std::process::Output;

use ocean_core::plan::ResourceId;

use ocean_cli::ocean;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh folder under the target directory.
fn folder(name: &str) -> PathBuf {
    let d = root().join("target").join("test-dump").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Dumps `scene` (a reference scene's name) at 64×36 into a fresh folder.
fn dump(scene: &str, name: &str) -> PathBuf {
    dump_at(scene, name, "64x36")
}

/// [`dump`] at `size` (WIDTHxHEIGHT).
fn dump_at(scene: &str, name: &str, size: &str) -> PathBuf {
    let dir = folder(name);
    let path = root().join("reference/scenes").join(format!("{scene}.toml"));
    let out = dir.join("picture.png");
    let o = ocean(&[
        "render",
        &path.to_string_lossy(),
        "--size",
        size,
        "--time",
        "3.5",
        "--dump-passes",
        &dir.join("dump").to_string_lossy(),
        "-o",
        &out.to_string_lossy(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    dir.join("dump")
}

fn against(dir: &Path, out: &Path) -> Output {
    ocean(&["compare", "--against", &dir.to_string_lossy(), "--out-dir", &out.to_string_lossy()])
}

fn manifest(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).unwrap()).unwrap()
}

#[test]
fn the_manifest_describes_every_file_of_the_dump() {
    // The default scene (waves, mips, Fresnel, shadow, reflection, refraction) and the storm's
    // foam `accumulated` (its field).
    for (scene, extra) in [("default", "shadow_map"), ("foam_storm", "foam_field")] {
        let dir = dump(scene, &format!("manifest-{scene}"));
        let m = manifest(&dir);
        assert_eq!(m["layout"], "ocean-dump/1");
        assert_eq!(m["frame"]["width"], 64);
        assert_eq!(m["frame"]["time_s"], 3.5);
        assert!(m["scene"]["toml"].as_str().unwrap().contains("[camera]"), "the scene's text");
        assert!(m["plan"]["passes"].as_array().is_some_and(|p| !p.is_empty()), "the plan");
        let resources = m["resources"].as_array().unwrap();
        let names: Vec<&str> = resources.iter().map(|r| r["name"].as_str().unwrap()).collect();
        for must in ["displacement", "bump", "fresnel_above", "hdr", extra] {
            assert!(names.contains(&must), "{scene}: {must} not in {names:?}");
        }
        for r in resources {
            let id = ResourceId::MAPS.into_iter().find(|id| id.name() == r["name"]).unwrap();
            let file = r["file"].as_str().unwrap();
            assert!(dir.join(file).exists(), "{file} listed but not written");
            let ((w, h), texels) = ocean::dump::read(&dir, id).unwrap();
            assert_eq!(
                [w, h],
                [r["size"][0].as_u64().unwrap() as u32, r["size"][1].as_u64().unwrap() as u32]
            );
            assert_eq!(texels.len(), (w * h) as usize);
            let channels = r["channels"].as_array().unwrap();
            assert_eq!(channels.len(), 4);
            for c in channels {
                assert!(
                    !c["meaning"].as_str().unwrap().is_empty()
                        && !c["unit"].as_str().unwrap().is_empty()
                );
            }
            assert!(r["pass"].is_string(), "{file}: the pass that wrote it");
        }
        // Every file but the picture and the manifest is a listed resource.
        let listed = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|f| f.ends_with(".exr"))
            .count();
        assert_eq!(listed, resources.len());
        assert!(dir.join("ldr.png").exists());
        // A spot check of one named channel's content: the displacement's height channel
        // holds the waves, not zeros.
        let (_, d) = ocean::dump::read(&dir, ResourceId::Displacement).unwrap();
        assert!(d.iter().any(|t| t[1] != 0.0), "{scene}: the height channel holds the waves");
    }
}

#[test]
fn compare_against_passes_on_the_oracles_dump_and_fails_on_a_changed_one() {
    let dir = dump("default", "against");
    let out = dir.parent().unwrap().join("cmp");
    let o = against(&dir, &out);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}\n{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("hdr") && text.contains("shadow_map"), "{text}");
    assert!(out.join("hdr.diff.png").exists() && out.join("against.json").exists());

    // One texel of the HDR frame 1e-4 off (ten times the relative limit) fails, naming it.
    let write = |id: ResourceId, names: [&str; 4], texels: &[[f32; 4]], w: u32, h: u32| {
        let channels = (0..4)
            .map(|c| ocean::output::Channel {
                name: names[c],
                data: texels.iter().map(|t| t[c]).collect(),
            })
            .collect();
        let bytes = ocean::output::encode_exr(w as usize, h as usize, channels).unwrap();
        std::fs::write(dir.join(ocean::dump::file_name(id)), bytes).unwrap();
    };
    let names = |id: ResourceId| ocean::dump::channels(id).map(|c| c.0);
    let ((w, h), hdr) = ocean::dump::read(&dir, ResourceId::Hdr).unwrap();
    let mut changed = hdr.clone();
    changed[w as usize * 20 + 30][1] *= 1.0 + 1e-4;
    write(ResourceId::Hdr, names(ResourceId::Hdr), &changed, w, h);
    let o = against(&dir, &out);
    let text = String::from_utf8_lossy(&o.stdout);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "a changed texel passed:\n{text}");
    assert!(err.contains("hdr") && err.contains("beyond limit 1"), "{err}");
    // One ULP-sized change is within the limit.
    let mut close = hdr.clone();
    close[w as usize * 20 + 30][1] = f32::from_bits(close[w as usize * 20 + 30][1].to_bits() + 1);
    write(ResourceId::Hdr, names(ResourceId::Hdr), &close, w, h);
    assert!(against(&dir, &out).status.success(), "one ULP failed");

    // Plain R, G, B, A channel names are read as the texture's order.
    write(ResourceId::Hdr, ["R", "G", "B", "A"], &hdr, w, h);
    assert!(against(&dir, &out).status.success(), "an RGBA file was not read");

    // A wrong size and a missing resource fail, naming them.
    write(ResourceId::Hdr, names(ResourceId::Hdr), &hdr[..(w * (h - 1)) as usize], w, h - 1);
    std::fs::remove_file(dir.join("shadow_map.exr")).unwrap();
    let o = against(&dir, &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("shadow_map") && err.contains("hdr"), "{err}");
}

/// A built-in scene's dump carries no scene text, only its system: `--against` renders the
/// built-in scene under that system (it rendered `hu`'s, and every map of a `chiu` dump failed).
#[test]
fn a_built_in_systems_dump_is_compared_under_its_system() {
    let dir = folder("against-chiu");
    let o = ocean(&[
        "render",
        "--system",
        "chiu",
        "--size",
        "64x36",
        "--dump-passes",
        &dir.join("dump").to_string_lossy(),
        "-o",
        &dir.join("picture.png").to_string_lossy(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = against(&dir.join("dump"), &dir.join("cmp"));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}\n{}", String::from_utf8_lossy(&o.stderr));
    // Negative control: the same dump held to another system fails.
    let o = ocean(&[
        "compare",
        "--against",
        &dir.join("dump").to_string_lossy(),
        "--system",
        "hu",
        "--out-dir",
        &dir.join("cmp").to_string_lossy(),
    ]);
    assert!(!o.status.success(), "a chiu dump passed as hu's");
}

#[test]
fn the_dumps_picture_is_compared_with_the_oracles() {
    let dir = dump("default", "against-ldr");
    let out = dir.parent().unwrap().join("cmp");
    let o = against(&dir, &out);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}\n{}", String::from_utf8_lossy(&o.stderr));
    // The CPU oracle's dump says `software`: the lavapipe row (99.5 % within 1/255).
    assert!(
        text.contains("ldr") && text.contains("100.000 %") && text.contains("(lavapipe)"),
        "{text}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("against.json")).unwrap()).unwrap();
    let ldr = json["resources"].as_array().unwrap().iter().find(|r| r["name"] == "ldr").unwrap();
    assert_eq!(ldr["passed"], true, "{ldr}");

    // A block of 20×10 pixels 40 levels darker (8.7 % of the picture) fails, naming `ldr`.
    let path = dir.join("ldr.png");
    let mut rgba = image::open(&path).unwrap().to_rgba8();
    let (w, h) = rgba.dimensions();
    for y in 10..20 {
        for x in 20..40 {
            let p = rgba.get_pixel_mut(x, y);
            for c in 0..3 {
                p[c] = p[c].saturating_sub(40);
            }
        }
    }
    std::fs::write(&path, ocean::output::encode_png(rgba.into_raw(), w, h).unwrap()).unwrap();
    let o = against(&dir, &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "a darkened picture passed");
    assert!(err.contains("ldr") && err.contains("within 1/255"), "{err}");

    // A picture of the wrong size fails; none at all is `not in dump`, a failure only with
    // --require-all.
    std::fs::write(&path, ocean::output::encode_png(vec![0; 4 * 8 * 8], 8, 8).unwrap()).unwrap();
    let o = against(&dir, &out);
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("8x8"));
    std::fs::remove_file(&path).unwrap();
    let o = against(&dir, &out);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success() && text.contains("not in dump"), "{text}");
    let strict = ocean(&[
        "compare",
        "--against",
        &dir.to_string_lossy(),
        "--out-dir",
        &out.to_string_lossy(),
        "--require-all",
    ]);
    assert!(!strict.status.success());
    assert!(String::from_utf8_lossy(&strict.stderr).contains("ldr"));
}

#[test]
fn the_manifest_names_its_adapter_and_a_resource_left_out_is_not_in_dump() {
    let dir = dump("default", "provenance");
    let out = dir.parent().unwrap().join("cmp");
    let m = manifest(&dir);
    assert_eq!(m["backend"], "cpu");
    assert_eq!(m["adapter"]["name"], "ocean CPU oracle", "{}", m["adapter"]);
    assert_eq!(m["adapter"]["backend"], "cpu");
    // A dump that leaves a resource out (another engine may make only some): its manifest
    // does not list it, and the comparison reports it and passes ...
    let mut less = m.clone();
    less["resources"].as_array_mut().unwrap().retain(|r| r["name"] != "shadow_map");
    std::fs::write(dir.join("manifest.json"), serde_json::to_string(&less).unwrap()).unwrap();
    std::fs::remove_file(dir.join("shadow_map.exr")).unwrap();
    let o = against(&dir, &out);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}\n{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("shadow_map") && text.contains("not in dump"), "{text}");
    assert!(text.contains("made by ocean CPU oracle"), "{text}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("against.json")).unwrap()).unwrap();
    assert_eq!(summary["not_in_dump"], serde_json::json!(["shadow_map"]));
    // ... unless --require-all asks for every resource.
    let o = ocean(&[
        "compare",
        "--against",
        &dir.to_string_lossy(),
        "--out-dir",
        &out.to_string_lossy(),
        "--require-all",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("not in dump (--require-all): shadow_map"), "{err}");
    // Control: a resource the manifest lists but whose file is gone is a failure either way.
    std::fs::write(dir.join("manifest.json"), serde_json::to_string(&m).unwrap()).unwrap();
    let o = against(&dir, &out);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stdout));
}

#[test]
fn a_dump_is_refused_with_frames_or_supersampling() {
    let dir = folder("refused");
    let d = dir.join("dump");
    let d = d.to_string_lossy();
    for extra in [["--spp", "4"], ["--frames", "0..2"]] {
        let out = dir.join("f_{}.png");
        let mut args = vec!["render", "--size", "16x9", "--dump-passes", &d];
        args.extend_from_slice(&extra);
        let out = out.to_string_lossy();
        args.extend(["-o", &out]);
        let o = ocean(&args);
        assert!(!o.status.success(), "{args:?} was accepted");
        assert!(String::from_utf8_lossy(&o.stderr).contains("--dump-passes"));
    }
    assert!(!dir.join("dump").exists(), "a refused run dumps nothing");
}

/// `--against DIR --tolerance envelope` judges the water from the dump's own maps: what a
/// dump does not hold, the GPU bound all the same (a map the plan does not write is a 1×1
/// zero map, the Gerstner scene's wave maps; the Fresnel filter is the plan's upload). The
/// oracle's own frames lie inside (at 160×90, at Vulkan's minimum precision: the oracle's
/// dump names no GPU); the water's nearest rows 2 % brighter over Gerstner waves leave, and
/// black over `calm`'s wave maps (whose envelope at that precision is ±90 % at the median).
#[test]
fn the_envelope_judges_the_water_of_a_dump() {
    for (scene, gain) in [("gerstner_swell", 1.02), ("calm", 0.0)] {
        let dir = dump_at(scene, &format!("envelope-{scene}"), "160x90");
        let out = dir.parent().unwrap().join("cmp");
        let judge = || {
            let o = ocean(&[
                "compare",
                "--against",
                &dir.to_string_lossy(),
                "--tolerance",
                "envelope",
                "--out-dir",
                &out.to_string_lossy(),
            ]);
            let text = String::from_utf8_lossy(&o.stdout).into_owned();
            let water = text.lines().find(|l| l.contains("[water")).unwrap_or_default().to_owned();
            (o.status.success(), water)
        };
        let (ok, water) = judge();
        println!("{scene}: {water}");
        assert!(ok && water.contains(" 0 of ") && water.contains(") ok ("), "{scene}: {water}");
        // The nearest rows of water brighter (the lower quarter of the frame is sea).
        let ((w, h), hdr) = ocean::dump::read(&dir, ResourceId::Hdr).unwrap();
        let brighter: Vec<[f32; 4]> = hdr
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let k = if i / w as usize > h as usize * 3 / 4 { gain } else { 1.0 };
                [t[0] * k, t[1] * k, t[2] * k, t[3]]
            })
            .collect();
        let channels = (0..4)
            .map(|c| ocean::output::Channel {
                name: ocean::dump::channels(ResourceId::Hdr)[c].0,
                data: brighter.iter().map(|t| t[c]).collect(),
            })
            .collect();
        let bytes = ocean::output::encode_exr(w as usize, h as usize, channels).unwrap();
        std::fs::write(dir.join(ocean::dump::file_name(ResourceId::Hdr)), bytes).unwrap();
        let (ok, water) = judge();
        assert!(
            !ok && water.contains("FAIL"),
            "{scene}, the water {gain} times as bright: {water}"
        );
    }
}
