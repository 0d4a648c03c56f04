//! Real hardware in the tests: the NVIDIA H200's frames of 19 scenes (`reference/hardware/h200`,
//! made with the shaders of 502430e; see its README) against the CPU oracle of today.
//!
//! Each scene is one test. The snapshot is of one commit's shaders, so a scene counts only while
//! the oracle still renders that commit's frame of it: `oracle.json` holds a 64-bit FNV-1a digest
//! of the bits of the oracle's HDR frame as it was then, and a scene whose frame has changed since
//! is reported **ignored, stale**, with the reason — never as passing. A scene that is not stale
//! must pass the hardware picture row of docs/design.md's tolerance table (the dump's `ldr.png`
//! against the oracle's: FLIP mean ≤ 0.02, P99 ≤ 0.1); its HDR frame's relative error is printed
//! (p50, p99), for the per-texel envelope that is to replace the picture row.
//!
//! Each scene is also held to the envelope of any conformant GPU (docs/tolerances.md) as a user
//! would: `ocean compare --against DIR --tolerance envelope`, which judges the picture against
//! the `tonemap` envelope of the dump's own HDR frame, and the HDR frame's sky pixels (where the
//! oracle draws no geometry, one pixel in from its edge) against the sky's envelope, and the
//! wave maps that three dumps keep (`calm`, `chiu_shallow`, `foam_storm`) against the `waves`
//! pass's envelope, and `foam_storm`'s foam field against the `foam` pass's.
//! That verdict does not depend on the oracle's frame, only on the judged passes' shaders, per
//! resource (`DEPENDS`): a resource whose shaders differ from the snapshot's
//! (`envelope_shaders_fnv64`) is reported stale, never passed, while the scene's other
//! resources are still judged; a scene all of whose resources are stale is ignored, with the
//! reason. A scene whose picture's inputs are not all in the dump (pass bloom's chains) must
//! show its picture as not judged, and its sky judged.
//!
//! Negative controls: a planted change to a picture (a tenth of it 25 % darker) fails the row,
//! and one bit flipped in a frame changes its digest.
//!
//! Limits of the design, on purpose: the digest is of the HDR frame, so a change of the
//! tonemap alone would show as a failure of the picture row rather than as stale (the fix is
//! the same: re-render); the oracle frames, and the envelope verdicts of scenes with something
//! fresh to judge, are computed before the tests are filtered (19
//! frames at 256×144, a few seconds); and when every scene is stale only the controls run —
//! the snapshot then needs a GPU session, which CI does not have. `OCEAN_HARDWARE_DIGESTS=1` prints the digests
//! of this build's oracle (to refresh `oracle.json` after re-rendering the snapshot on a GPU).

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

use libtest_mimic::{Arguments, Failed, Trial};

#[path = "support/cli.rs"]
mod cli;
use ocean_core::plan::OutputKind;
use ocean_verify::compare::{ImageLimits, compare_image};

fn snapshot_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference/hardware/h200")
}

/// 64-bit FNV-1a of a byte stream.
fn fnv1a(bytes: impl IntoIterator<Item = u8>) -> u64 {
    bytes
        .into_iter()
        .fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

/// 64-bit FNV-1a over the bits of a frame's texels.
fn digest(texels: &[[f32; 4]]) -> u64 {
    fnv1a(texels.iter().flatten().flat_map(|v| v.to_bits().to_le_bytes()))
}

/// The oracle's frame of a dump's scene, as `ocean compare --against` renders it.
struct Oracle {
    width: u32,
    height: u32,
    hdr: Vec<[f32; 4]>,
    ldr: Vec<u8>,
}

fn oracle(dir: &Path) -> Oracle {
    let manifest = ocean::dump::read_manifest(dir).unwrap().unwrap();
    let none = ocean::scene_arg::SystemArg { system: None };
    let scene = manifest.scene("manifest.json", None, &none).unwrap();
    let (width, height) = manifest.size.unwrap();
    let r = ocean_cpu::render_scene(&scene, OutputKind::Ldr, &mut |_| {}).unwrap();
    Oracle { width, height, hdr: r.buffers.hdr.color.clone(), ldr: r.ldr.unwrap() }
}

fn picture(path: &Path) -> Vec<u8> {
    image::open(path).unwrap().to_rgba8().into_raw()
}

/// The hardware picture row: Err with the figures past it.
fn picture_row(ours: &[u8], theirs: &[u8], w: u32, h: u32) -> Result<String, String> {
    let limits = ImageLimits::HARDWARE;
    let stats = compare_image(ours, theirs, w, h);
    let line = stats.line(&limits);
    if stats.failures(&limits).is_empty() { Ok(line) } else { Err(line) }
}

/// p50 and p99 of |gpu − cpu| / max(|cpu|, 1e-3) over the HDR frame's RGB.
fn relative_error(ours: &[[f32; 4]], theirs: &[[f32; 4]]) -> (f64, f64) {
    let mut e: Vec<f64> = ours
        .iter()
        .zip(theirs)
        .flat_map(|(a, b)| {
            (0..3).map(move |c| {
                let (x, y) = (f64::from(a[c]), f64::from(b[c]));
                (y - x).abs() / x.abs().max(1e-3)
            })
        })
        .collect();
    e.sort_by(f64::total_cmp);
    let q = |f: f64| e[((e.len() - 1) as f64 * f) as usize];
    (q(0.5), q(0.99))
}

fn check_scene(dir: &Path, o: &Oracle) -> Result<(), Failed> {
    let theirs = picture(&dir.join("ldr.png"));
    let row = picture_row(&o.ldr, &theirs, o.width, o.height);
    let ((w, h), hdr) = ocean::dump::read(dir, ocean_core::plan::ResourceId::Hdr).unwrap();
    assert_eq!((w, h), (o.width, o.height));
    let (p50, p99) = relative_error(&o.hdr, &hdr);
    let name = dir.file_name().unwrap().to_string_lossy();
    match row {
        Ok(line) => {
            println!("{name}: {line}; HDR relative error p50 {p50:.1e}, p99 {p99:.1e}");
            Ok(())
        }
        Err(line) => Err(format!("{name}: the H200's picture is off the oracle's: {line}").into()),
    }
}

/// The controls, on the oracle's own frame of a scene: the picture row passes it against
/// itself and fails it with a tenth of it 25 % darker; one bit flipped in one texel of the HDR
/// frame changes the digest (so a changed frame is stale).
fn controls(o: &Oracle) -> Result<(), Failed> {
    picture_row(&o.ldr, &o.ldr, o.width, o.height).map_err(|l| format!("itself failed: {l}"))?;
    let mut dark = o.ldr.clone();
    let w = o.width as usize;
    for y in 0..o.height as usize / 10 {
        for x in 0..w {
            for c in 0..3 {
                let v = &mut dark[4 * (y * w + x) + c];
                *v = (f32::from(*v) * 0.75) as u8;
            }
        }
    }
    if picture_row(&o.ldr, &dark, o.width, o.height).is_ok() {
        return Err("a tenth of the picture 25 % darker passed the picture row".into());
    }
    let mut hdr = o.hdr.clone();
    let mid = hdr.len() / 2;
    hdr[mid][1] = f32::from_bits(hdr[mid][1].to_bits() ^ 1);
    if digest(&hdr) == digest(&o.hdr) {
        return Err("one bit flipped left the digest unchanged".into());
    }
    Ok(())
}

/// 64-bit FNV-1a of a file's bytes.
fn file_digest(path: &Path) -> u64 {
    fnv1a(std::fs::read(path).unwrap())
}

/// The shaders of the passes the envelope judges from the dump's own inputs whose bytes differ
/// from the snapshot's (`oracle.json`'s `envelope_shaders_fnv64`): a resource whose shaders
/// (`DEPENDS`) are all unchanged has a verdict that does not depend on the oracle's frame.
fn changed_envelope_shaders(digests: &serde_json::Value) -> Vec<String> {
    let shaders = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("shaders");
    let stored = digests["envelope_shaders_fnv64"].as_object().expect("envelope_shaders_fnv64");
    assert!(!stored.is_empty(), "no shader digests");
    for file in stored.keys() {
        assert!(
            DEPENDS.iter().any(|(_, files)| files.contains(&file.as_str())),
            "{file} is in envelope_shaders_fnv64 but no resource of DEPENDS reads it"
        );
    }
    stored
        .iter()
        .filter(|(file, d)| {
            format!("{:016x}", file_digest(&shaders.join(file))) != d.as_str().unwrap()
        })
        .map(|(file, _)| file.clone())
        .collect()
}

/// What each resource that `ocean compare --against` judges from a dump is computed by: the
/// snapshot's shader files (of `envelope_shaders_fnv64`) whose change makes its verdict on the
/// H200's frames stale. One shader changed (a pass moved to compute, say) stales only the
/// resources it computes; the others keep their hardware verdict. A resource not listed here
/// depends on every stored file.
const DEPENDS: [(&str, &[&str]); 10] = [
    ("ldr", &["tonemap.wgsl", "shared/fullscreen.wgsl", "bloom.wgsl"]),
    ("bloom_down", &["bloom.wgsl", "shared/fullscreen.wgsl"]),
    ("bloom_up", &["bloom.wgsl", "shared/fullscreen.wgsl"]),
    (
        "hdr (sky pixels)",
        &[
            "sky.wgsl",
            "sky/preetham.wgsl",
            "sky/preetham_clouds.wgsl",
            "sky/atmosphere.wgsl",
            "shared/preetham.wgsl",
            "shared/sky_lut.wgsl",
            "shared/camera.wgsl",
            "shared/fullscreen.wgsl",
        ],
    ),
    ("displacement", &["waves.wgsl", "shared/trig.wgsl"]),
    ("bump", &["waves.wgsl", "shared/trig.wgsl"]),
    ("foam_field", &["foam.wgsl", "shared/gerstner.wgsl", "shared/trig.wgsl"]),
    ("reflection_map", &["objects.wgsl", "shadow.wgsl"]),
    ("refraction_map", &["objects.wgsl", "shadow.wgsl"]),
    ("shadow_map", &["shadow.wgsl"]),
];

/// Whether the verdict on `resource` is stale because a shader it depends on changed.
fn shader_stale(resource: &str, changed: &[String]) -> bool {
    match DEPENDS.iter().find(|(r, _)| *r == resource) {
        Some((_, files)) => changed.iter().any(|c| files.contains(&c.as_str())),
        None => !changed.is_empty(),
    }
}

/// The resources a dump's envelope verdict may judge (the picture, the sky's pixels, and the
/// maps the dump keeps) that are fresh: none of their shaders changed, and for one judged from
/// the scene's geometry, not `stale_geometry`. Empty: the scene's envelope verdict on the H200
/// is wholly stale.
fn fresh_resources(dir: &Path, changed: &[String], stale_geometry: bool) -> Vec<&'static str> {
    let kept = |r: &str| match r {
        "ldr" | "hdr (sky pixels)" => true,
        map => dir.join(format!("{map}.exr")).is_file(),
    };
    DEPENDS
        .iter()
        .map(|(r, _)| *r)
        .filter(|r| kept(r) && !shader_stale(r, changed))
        .filter(|r| !(stale_geometry && GEOMETRY_JUDGED.contains(r)))
        .collect()
}

/// What a scene's envelope verdict came to when nothing failed.
enum Envelope {
    /// A fresh resource was judged, and inside.
    Judged,
    /// Every resource judged is stale (the reason): the trial is ignored, never passed.
    AllStale(String),
}

/// `ocean compare --against DIR --tolerance envelope` on one scene of the snapshot: exit 0,
/// the picture judged with 0 bytes outside (and pass bloom's chains, where the dump holds
/// them), everything else listed as not judged.
/// The resources judged from the scene's geometry (the objects' triangles, the terrain):
/// stale, not failed, when the scene's oracle frame has changed since the snapshot.
const GEOMETRY_JUDGED: [&str; 3] = ["reflection_map", "refraction_map", "shadow_map"];

fn envelope_scene(
    dir: &Path,
    lacks_bloom: bool,
    stale_geometry: bool,
    changed: &[String],
) -> Result<Envelope, Failed> {
    let name = dir.file_name().unwrap().to_string_lossy().into_owned();
    let out =
        std::env::temp_dir().join(format!("ocean-h200-envelope-{name}-{}", std::process::id()));
    let out_s = out.to_string_lossy().into_owned();
    let dir_s = dir.to_string_lossy().into_owned();
    let o = cli::ocean(&[
        "compare",
        "--size",
        "256x144",
        "--against",
        &dir_s,
        "--tolerance",
        "envelope",
        "--out-dir",
        &out_s,
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let fail = || {
        format!(
            "{name}: exit {:?}\n{stdout}{}",
            o.status.code(),
            String::from_utf8_lossy(&o.stderr)
        )
    };
    let Ok(text) = std::fs::read_to_string(out.join("against.json")) else {
        return Err(fail().into());
    };
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let _ = std::fs::remove_dir_all(&out);
    let resources = json["resources"].as_array().unwrap();
    let failed: Vec<&str> = resources
        .iter()
        .filter(|r| r["passed"] == false)
        .map(|r| r["name"].as_str().unwrap_or(""))
        .collect();
    // A geometry-judged map of a stale scene may differ, and so may a resource whose shaders
    // changed since the snapshot: each is reported stale, never passed; anything else failing
    // fails.
    let is_stale =
        |r: &str| (stale_geometry && GEOMETRY_JUDGED.contains(&r)) || shader_stale(r, changed);
    let stale_failed = failed.iter().filter(|f| is_stale(f)).count();
    if !o.status.success() && (stale_failed == 0 || stale_failed != failed.len()) {
        return Err(fail().into());
    }
    let stale: Vec<&str> = resources
        .iter()
        .filter(|r| r["judged"] != false)
        .map(|r| r["name"].as_str().unwrap_or(""))
        .filter(|r| is_stale(r))
        .collect();
    if !stale.is_empty() {
        println!(
            "{name}: {} stale — its shaders changed since the snapshot, or it is judged from the scene's geometry and the scene's oracle frame has changed",
            stale.join(", ")
        );
    }
    let ldr = resources.iter().find(|r| r["name"] == "ldr").ok_or("no ldr entry")?;
    // Without the bloom chain in the dump the picture cannot be judged; otherwise it must be,
    // and inside.
    let ldr_ok = if lacks_bloom {
        ldr["judged"] == false
    } else if is_stale("ldr") {
        true
    } else {
        ldr["passed"] == true && ldr["outside"] == 0
    };
    if !ldr_ok {
        return Err(format!("{name}: the picture was not judged inside: {ldr}").into());
    }
    // The sky's pixels of the HDR frame, where the scene's sky has an envelope (Preetham).
    if let Some(sky) = resources.iter().find(|r| r["name"] == "hdr (sky pixels)")
        && !is_stale("hdr (sky pixels)")
        && (sky["passed"] != true || sky["outside"] != 0)
    {
        return Err(format!("{name}: the sky's pixels were not judged inside: {sky}").into());
    }
    // The wave maps, where the dump holds them (pass `waves`, from the uploaded modes alone),
    // and the foam field (pass `foam`, from the dump's displacement map).
    for map in ["displacement", "bump", "foam_field"] {
        if !dir.join(format!("{map}.exr")).is_file() || is_stale(map) {
            continue;
        }
        let entry = resources.iter().find(|r| r["name"] == map).ok_or("no wave-map entry")?;
        if entry["passed"] != true || entry["outside"] != 0 {
            return Err(format!("{name}: {map} was not judged inside: {entry}").into());
        }
    }
    let judged: Vec<&str> = resources
        .iter()
        .filter(|r| r["judged"] != false && !stale.contains(&r["name"].as_str().unwrap_or("")))
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    if judged.is_empty() {
        if stale.is_empty() {
            return Err(format!("{name}: nothing judged").into());
        }
        return Ok(Envelope::AllStale(format!(
            "{name}: stale for the envelope: nothing fresh was judged ({} stale)",
            stale.join(", ")
        )));
    }
    println!(
        "{name}: envelope: {} judged, 0 outside{}",
        judged.join(", "),
        if lacks_bloom {
            " (ldr not judged: bloom_up is not in the dump)".to_owned()
        } else if is_stale("ldr") {
            String::new()
        } else {
            format!(" (ldr width p50 {} / p99 {} codes)", ldr["codes_p50"], ldr["codes_p99"])
        }
    );
    Ok(Envelope::Judged)
}

/// The envelope verdict's negative control: the `calm` dump with one byte of its picture three
/// codes off must fail `ocean compare --against` (exit 1, 1 byte outside).
fn envelope_control() -> Result<(), Failed> {
    let src = snapshot_dir().join("calm");
    let tmp =
        std::env::temp_dir().join(format!("ocean-h200-envelope-control-{}", std::process::id()));
    let dump = tmp.join("calm");
    std::fs::create_dir_all(&dump).unwrap();
    for f in std::fs::read_dir(&src).unwrap().flatten().map(|e| e.file_name()) {
        if f != "ldr.png" {
            std::fs::copy(src.join(&f), dump.join(&f)).unwrap();
        }
    }
    let mut ldr = image::open(src.join("ldr.png")).unwrap().to_rgba8();
    let p = ldr.get_pixel_mut(100, 100);
    p[1] = if p[1] > 128 { p[1] - 3 } else { p[1] + 3 };
    ldr.save(dump.join("ldr.png")).unwrap();
    let (d, out) =
        (dump.to_string_lossy().into_owned(), tmp.join("out").to_string_lossy().into_owned());
    let o = cli::ocean(&["compare", "--against", &d, "--tolerance", "envelope", "--out-dir", &out]);
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let _ = std::fs::remove_dir_all(&tmp);
    if o.status.code() != Some(1) || !stdout.contains("1 of 110592 bytes outside") {
        return Err(format!("one byte three codes off was not caught:\n{stdout}").into());
    }
    Ok(())
}

fn main() -> ExitCode {
    let args = Arguments::from_args();
    let root = snapshot_dir();
    let digests: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("oracle.json")).unwrap()).unwrap();
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("manifest.json").is_file())
        .collect();
    scenes.sort();
    assert_eq!(scenes.len(), 19, "the snapshot holds 19 scenes");
    let print = std::env::var_os("OCEAN_HARDWARE_DIGESTS").is_some_and(|v| v == "1");
    let changed = changed_envelope_shaders(&digests);
    let mut trials = Vec::new();
    let mut first = None;
    let mut out = serde_json::Map::new();
    for dir in scenes {
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        // The envelope's verdict from the dump's own inputs: stale only when the judged
        // passes' shaders changed; a scene whose picture's inputs are not all in the dump
        // (pass bloom's chains) is ignored with that reason, never passed.
        let manifest = ocean::dump::read_manifest(&dir).unwrap().unwrap();
        let none = ocean::scene_arg::SystemArg { system: None };
        let scene = manifest.scene("manifest.json", None, &none).unwrap();
        let bloom = ocean_core::plan::FramePlan::new(&scene, OutputKind::Ldr)
            .runs(ocean_core::plan::Pass::Bloom);
        let lacks_bloom = bloom && !dir.join("bloom_up.exr").is_file();
        let trial_name = format!("{name} (envelope)");
        let o = Arc::new(oracle(&dir));
        let now = digest(&o.hdr);
        let stale_geometry = digests["hdr_fnv64"][&name]
            .as_str()
            .is_none_or(|s| u64::from_str_radix(s, 16).ok() != Some(now));
        let fresh = fresh_resources(&dir, &changed, stale_geometry);
        let outcome = (!fresh.is_empty())
            .then(|| envelope_scene(&dir, lacks_bloom, stale_geometry, &changed));
        if let Some(Ok(Envelope::AllStale(why))) = outcome {
            println!("{why}");
            trials.push(
                Trial::test(trial_name, move || Err(why.clone().into())).with_ignored_flag(true),
            );
        } else if fresh.is_empty() {
            let why = format!(
                "{name}: stale for the envelope: every resource it judges reads a shader changed \
                 since the snapshot ({})",
                changed.join(", ")
            );
            println!("{why}");
            trials.push(
                Trial::test(trial_name, move || Err(why.clone().into())).with_ignored_flag(true),
            );
        } else {
            let outcome = outcome.expect("a scene with fresh resources was judged");
            trials.push(Trial::test(trial_name, move || outcome.map(|_| ())));
        }
        first.get_or_insert_with(|| o.clone());
        out.insert(name.clone(), format!("{now:016x}").into());
        let stored =
            digests["hdr_fnv64"][&name].as_str().map(|s| u64::from_str_radix(s, 16).unwrap());
        let Some(stored) = stored else {
            // A scene without a digest is a failure, not a pass.
            trials.push(Trial::test(name.clone(), move || {
                Err(format!("{name}: no digest in oracle.json").into())
            }));
            continue;
        };
        if now == stored {
            trials.push(Trial::test(name, move || check_scene(&dir, &o)));
        } else {
            println!(
                "{name}: stale — the oracle's frame has changed since the snapshot's commit (digest {now:016x}, snapshot {stored:016x}); re-render it on a GPU to test it again"
            );
            // Run anyway (`--ignored`), a stale scene fails: it is never a pass.
            let why = format!("{name} is stale: the oracle's frame has changed since the snapshot");
            trials.push(
                Trial::test(format!("{name} (stale)"), move || Err(why.clone().into()))
                    .with_ignored_flag(true),
            );
        }
    }
    if print {
        println!("{}", serde_json::to_string_pretty(&out).unwrap());
    }
    let first = first.unwrap();
    trials.push(Trial::test("controls", move || controls(&first)));
    trials.push(Trial::test("envelope control", envelope_control));
    libtest_mimic::run(&args, trials).exit_code()
}
