//! `ocean render --frames`: frame n is a pure function of (scene, fps, n), so the union of the
//! shards is the unsharded run bit for bit, a later range or a resumed run draws the same
//! frames, and the state that frames carry (foam `accumulated`'s field, the spray's pool) is
//! replayed, not restarted.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[path = "support/cli.rs"]
mod ocean_cli;

use std::path::{Path, PathBuf};

use ocean_cli::ocean;

fn ok(args: &[&str]) -> String {
    let o = ocean(args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "ocean {args:?} failed:\n{err}");
    err
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh folder under the target directory.
fn folder(name: &str) -> PathBuf {
    let d = root().join("target").join("test-animation").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A reference scene's text with replacements, written to `dir/scene.toml`.
fn scene(dir: &Path, reference: &str, edits: &[(&str, &str)]) -> String {
    let mut text =
        std::fs::read_to_string(root().join("reference/scenes").join(format!("{reference}.toml")))
            .unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{reference}.toml has no `{from}`");
        text = text.replacen(from, to, 1);
    }
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// Foam `accumulated` on the storm's FFT sea, small maps: every frame steps the field once
/// more, and the field shows (white water on the crests).
fn foam_scene(dir: &Path) -> String {
    scene(
        dir,
        "foam_storm",
        &[("resolution = 256", "resolution = 64"), ("warmup_steps = 60", "warmup_steps = 2")],
    )
}

/// Seed 001's rock throwing spray (the particle pool lives across frames), small maps.
fn spray_scene(dir: &Path) -> String {
    scene(
        dir,
        "chiu_rock",
        &[
            ("resolution = 256\nbump_resolution = 256", "resolution = 64\nbump_resolution = 64"),
            ("[spray]\n", "[spray]\nwarmup_steps = 5\n"),
        ],
    )
}

/// Every file of a folder but the scene, by name.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "exr"))
        .map(|p| {
            (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(&p).unwrap())
        })
        .collect();
    v.sort();
    v
}

fn render(scene: &str, dir: &Path, extra: &[&str]) -> String {
    let pattern = dir.join("f_{:03}.exr");
    let pattern = pattern.to_string_lossy();
    let mut args = vec!["render", scene, "--size", "48x27", "--fps", "10", "-o", &pattern];
    args.extend_from_slice(extra);
    ok(&args)
}

/// Issue 16's "done when": a 240-frame sequence in four shards is the single run, file for
/// file (foam `accumulated`, whose field every frame carries to the next; 48×27, small maps).
#[test]
fn a_240_frame_sequence_in_four_shards_is_the_single_run() {
    let whole = folder("240-whole");
    let parts = folder("240-shards");
    let s = foam_scene(&whole);
    let start = std::time::Instant::now();
    render(&s, &whole, &["--frames", "0..240"]);
    for i in 0..4 {
        let shard = format!("{i}/4");
        let err = render(&s, &parts, &["--frames", "0..240", "--shard", &shard]);
        assert!(err.contains("wrote 60 frame(s)"), "shard {shard}: {err}");
    }
    eprintln!("240 frames, then the same in 4 shards: {:.1} s", start.elapsed().as_secs_f64());
    let (a, b) = (files(&whole), files(&parts));
    assert_eq!(a.len(), 240);
    assert_eq!(
        a.iter().map(|f| &f.0).collect::<Vec<_>>(),
        b.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    let differ: Vec<&String> =
        a.iter().zip(&b).filter(|(x, y)| x.1 != y.1).map(|(x, _)| &x.0).collect();
    assert!(differ.is_empty(), "{} frames differ, first {:?}", differ.len(), differ.first());
    // The control: the sequence moves.
    assert!(a[0].1 != a[239].1 && a[100].1 != a[101].1);
}

#[test]
fn the_shards_together_are_the_unsharded_run_bit_for_bit() {
    // (name, scene, the time of frame 4: the scene's time_s + 4/10 s, exactly so in f64)
    let cases =
        [("foam", foam_scene as fn(&Path) -> String, "0.4"), ("spray", spray_scene, "20.4")];
    for (name, make, time4) in cases {
        let whole = folder(&format!("{name}-whole"));
        let parts = folder(&format!("{name}-shards"));
        let s = make(&whole);
        render(&s, &whole, &["--frames", "0..6"]);
        for i in 0..3 {
            let shard = format!("{i}/3");
            let err = render(&s, &parts, &["--frames", "0..6", "--shard", &shard]);
            assert!(err.contains("wrote 2 frame(s)"), "{name} shard {shard}: {err}");
        }
        let (a, b) = (files(&whole), files(&parts));
        assert_eq!(a.len(), 6, "{name}: six frames");
        assert_eq!(
            a.iter().map(|f| &f.0).collect::<Vec<_>>(),
            b.iter().map(|f| &f.0).collect::<Vec<_>>()
        );
        for ((n, x), (_, y)) in a.iter().zip(&b) {
            assert!(x == y, "{name}: {n} differs between the whole run and its shard");
        }
        // Negative control: the frames move (a comparison of six copies would pass too).
        assert!(a[1].1 != a[4].1, "{name}: frames 1 and 4 are the same file");

        // Frame 4 alone (a later range) is the sequence's frame 4: the state of frames 0–3
        // is replayed undrawn …
        let alone = folder(&format!("{name}-alone"));
        let err = render(&s, &alone, &["--frames", "4..=4"]);
        assert!(files(&alone)[0].1 == a[4].1, "{name}: frame 4 alone differs");
        assert!(err.contains("4 earlier frame(s) stepped"), "{name}: {err}");
        // … and that replay matters: a still frame at the same time starts the state afresh
        // and gives another picture.
        let still = alone.join("still.exr");
        ok(&["render", &s, "--size", "48x27", "--time", time4, "-o", &still.to_string_lossy()]);
        assert!(std::fs::read(&still).unwrap() != a[4].1, "{name}: the state made no difference");
    }
}

#[test]
fn a_killed_run_resumes_and_overwrite_redraws() {
    let dir = folder("resume");
    let s = foam_scene(&dir);
    render(&s, &dir, &["--frames", "0..5"]);
    let full = files(&dir);
    // A run killed after frame 1, and a frame damaged by hand.
    std::fs::remove_file(dir.join("f_002.exr")).unwrap();
    std::fs::remove_file(dir.join("f_004.exr")).unwrap();
    std::fs::write(dir.join("f_000.exr"), b"damaged").unwrap();
    let err = render(&s, &dir, &["--frames", "0..5"]);
    assert!(err.contains("wrote 2 frame(s) of 0..5, first 2, last 4"), "{err}");
    assert!(err.contains("3 already on disk, kept"), "{err}");
    let resumed = files(&dir);
    assert!(resumed[2] == full[2] && resumed[4] == full[4], "resumed frames differ");
    assert!(resumed[0].1 == b"damaged", "an existing frame is kept");
    let err = render(&s, &dir, &["--frames", "0..5"]);
    assert!(err.contains("nothing to render"), "{err}");
    render(&s, &dir, &["--frames", "0..5", "--overwrite"]);
    assert!(files(&dir) == full, "--overwrite draws every frame again");
}

#[test]
fn bad_sequences_are_refused_before_any_work() {
    let dir = folder("refused");
    let out = dir.join("f_{:03}.png");
    let out = out.to_string_lossy();
    let plain = dir.join("plain.png");
    let plain = plain.to_string_lossy();
    for (args, says) in [
        (vec!["--frames", "5..5", "-o", &out], "holds no frame"),
        (vec!["--frames", "9..3", "-o", &out], "holds no frame"),
        (vec!["--frames", "0..4", "--shard", "3/3", "-o", &out], "counted from 0"),
        (vec!["--frames", "0..4", "--shard", "1/0", "-o", &out], "0 parts"),
        (vec!["--frames", "0..4", "-o", &plain], "has no frame number"),
        (vec!["--frames", "0..4", "--fps", "0", "-o", &out], "--fps"),
        (vec!["--frames", "0..4", "--spp", "4", "-o", &out], "--spp"),
        (vec!["--shard", "0/2", "-o", &plain], "add --frames"),
    ] {
        let mut a = vec!["render", "--size", "16x9"];
        a.extend(args.iter().copied());
        let o = ocean(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{a:?} was accepted");
        assert!(err.contains(says), "{a:?}: {err}");
    }
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "a refused run writes nothing");
}

#[test]
fn plan_names_the_passes_an_animation_steps() {
    let dir = folder("plan");
    let foam = foam_scene(&dir);
    let out = ocean(&["plan", &foam, "--frames", "10"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("an animation steps the frames it does not draw with waves, foam"),
        "{text}"
    );
    let out = ocean(&["plan", "--frames", "10", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["state_passes"], serde_json::json!([]), "the default scene carries nothing");
    let spray = spray_scene(&dir);
    let out = ocean(&["plan", &spray, "--frames", "10", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["state_passes"], serde_json::json!(["waves", "spray"]), "{}", v["state_passes"]);
}
