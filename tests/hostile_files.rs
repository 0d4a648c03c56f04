//! Regression tests for hostile files and runaway requests (issue 36): each case failed on
//! 502430e — an output replaced a device node, a frame range allocated before rendering, an
//! image was decoded before its size was checked, a dump's manifest was trusted, a valid dump
//! failed its own comparison, a replay of hours started without a word, a full disk left empty
//! files — and must now be refused at once, naming the file, with little memory, or work.
//!
//! Memory is measured, not guessed: the binary prints its peak resident set (Linux's VmHWM)
//! under `OCEAN_PRINT_PEAK_MEMORY`, and a refused input must stay under [`REFUSED_MIB`]. Every
//! forged file is made here, a few bytes long; none is checked in.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[path = "support/cli.rs"]
mod ocean_cli;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The most a refused input may cost, MiB (the issue's bound; the binary alone, with wgpu and
/// its fonts mapped, peaks near 20 MiB when it refuses an argument).
const REFUSED_MIB: f64 = 100.0;

fn ocean() -> Command {
    let mut c = ocean_cli::command();
    c.env("OCEAN_PRINT_PEAK_MEMORY", "1");
    c
}

/// Runs `ocean ARGS` in `dir` and returns its output, with a deadline: a run that blocks (on a
/// FIFO, say) is killed and fails the test.
fn run_in(dir: &Path, args: &[&str]) -> Output {
    let mut child = ocean()
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(120);
    while child.try_wait().unwrap().is_none() {
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("ocean {args:?} did not finish in 120 s (blocked?)");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The peak memory the run printed, MiB.
fn peak_mib(o: &Output) -> f64 {
    let e = stderr(o);
    let line = e
        .lines()
        .find_map(|l| l.strip_prefix("peak resident memory: "))
        .unwrap_or_else(|| panic!("no peak memory line in: {e}"));
    line.trim_end_matches(" MiB").parse().unwrap()
}

/// The run failed with a message holding every one of `words`, within [`REFUSED_MIB`].
fn refused(o: &Output, words: &[&str]) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    for w in words {
        assert!(e.contains(w), "`{w}` not in: {e}");
    }
    let mib = peak_mib(o);
    assert!(mib < REFUSED_MIB, "refusing took {mib} MiB: {e}");
}

/// Files in `dir` whose names hold `.tmp-` (what an interrupted or failed write leaves).
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp-"))
        .collect()
}

fn mkfifo(path: &Path) {
    let ok = Command::new("mkfifo").arg(path).status().unwrap().success();
    assert!(ok, "mkfifo {}", path.display());
}

fn is_char_device(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::metadata(path).unwrap().file_type().is_char_device()
}

// ---------------------------------------------------------------------------------------------
// Forged files

/// CRC-32 (ISO 3309, as PNG's chunks use), bit by bit: a test helper, not a fast one.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = 0xffff_ffffu32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 == 1 { 0xedb8_8320 ^ (c >> 1) } else { c >> 1 };
        }
    }
    !c
}

/// A PNG whose header says `w`×`h` 16-bit grayscale, followed by one tiny IDAT: a decoder
/// that trusted the header would allocate w·h·2 bytes.
fn forged_png(w: u32, h: u32) -> Vec<u8> {
    let mut out = vec![0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a];
    let mut chunk = |kind: &[u8; 4], data: &[u8]| {
        out.extend((data.len() as u32).to_be_bytes());
        let mut body = kind.to_vec();
        body.extend(data);
        out.extend(&body);
        out.extend(crc32(&body).to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([16, 0, 0, 0, 0]); // 16 bits, grayscale, deflate, adaptive, no interlace
    chunk(b"IHDR", &ihdr);
    chunk(b"IDAT", &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]);
    chunk(b"IEND", &[]);
    out
}

/// An EXR header (scan lines, no compression, one f32 channel `Y`) whose data window claims
/// `w`×`h`, with a short offset table and no pixels: the file is a few hundred bytes.
fn forged_exr(w: i32, h: i32) -> Vec<u8> {
    let mut out = vec![0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
    let mut attr = |name: &str, kind: &str, value: &[u8]| {
        out.extend(name.as_bytes());
        out.push(0);
        out.extend(kind.as_bytes());
        out.push(0);
        out.extend((value.len() as i32).to_le_bytes());
        out.extend(value);
    };
    // chlist: name, pixel type (2 = float), pLinear + 3 reserved, x and y sampling; then 0.
    let mut ch = b"Y\0".to_vec();
    ch.extend(2i32.to_le_bytes());
    ch.extend([0, 0, 0, 0]);
    ch.extend(1i32.to_le_bytes());
    ch.extend(1i32.to_le_bytes());
    ch.push(0);
    attr("channels", "chlist", &ch);
    attr("compression", "compression", &[0]);
    let window: Vec<u8> = [0, 0, w - 1, h - 1].iter().flat_map(|v: &i32| v.to_le_bytes()).collect();
    attr("dataWindow", "box2i", &window);
    attr("displayWindow", "box2i", &window);
    attr("lineOrder", "lineOrder", &[0]);
    attr("pixelAspectRatio", "float", &1.0f32.to_le_bytes());
    attr("screenWindowCenter", "v2f", &[0; 8]);
    attr("screenWindowWidth", "float", &1.0f32.to_le_bytes());
    out.push(0);
    out.extend([0u8; 64]);
    out
}

/// A real EXR of `samples` (w × h, channel `Y`), through the exr crate.
fn write_exr(path: &Path, w: usize, h: usize, samples: Vec<f32>) {
    use exr::prelude::*;
    let list = vec![AnyChannel::new("Y", FlatSamples::F32(samples))];
    let layer = Layer::new(
        (w, h),
        LayerAttributes::named("h"),
        Encoding::UNCOMPRESSED,
        AnyChannels::sort(list.into()),
    );
    Image::from_layer(layer).write().to_file(path).unwrap();
}

/// A scene file in `dir` whose floor reads `heightmap` (a name in `dir`).
fn heightmap_scene(dir: &Path, heightmap: &str) -> PathBuf {
    let text = format!(
        "[terrain]\nkind = \"heightmap\"\nheightmap = {heightmap:?}\nheight_range_m = [-2.0, \
         6.0]\ndepth_m = 10.0\ncenter = [0.0, -30.0]\nextent_m = 60.0\n"
    );
    let path = dir.join("floor.toml");
    std::fs::write(&path, text).unwrap();
    path
}

// ---------------------------------------------------------------------------------------------
// 1. Outputs never replace what is not a regular file

#[test]
fn an_output_never_replaces_a_device_a_fifo_or_what_a_link_names() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A link to a character device (what `mknod n c 1 3` makes, without needing root).
    std::os::unix::fs::symlink("/dev/null", d.join("null.png")).unwrap();
    let o = run_in(d, &["render", "--size", "16x9", "-o", "null.png"]);
    refused(&o, &["null.png", "/dev/null", "a character device", "only regular files"]);
    assert!(std::fs::symlink_metadata(d.join("null.png")).unwrap().file_type().is_symlink());
    assert!(is_char_device(Path::new("/dev/null")));
    // A device node itself, where this process may make one (root, as CI).
    let node = d.join("n");
    let made = Command::new("mknod").arg(&node).args(["c", "1", "3"]).status();
    if made.is_ok_and(|s| s.success()) {
        let o = run_in(d, &["bench", "--quick", "--only", "waves", "-o", "n"]);
        refused(&o, &["n: it exists and is a character device"]);
        assert!(is_char_device(&node), "the device node was replaced");
    }
    // A FIFO: refused (opening it would block, renaming over it replaces it).
    mkfifo(&d.join("pipe.exr"));
    let o = run_in(d, &["fresnel", "--eta", "1.33", "--table", "8", "-o", "pipe.exr"]);
    refused(&o, &["pipe.exr", "named pipe"]);
    assert!(temporaries(d).is_empty(), "{:?}", temporaries(d));
    // Control: a link to a regular file is written through, and stays a link.
    std::fs::write(d.join("real.exr"), b"old").unwrap();
    std::os::unix::fs::symlink("real.exr", d.join("link.exr")).unwrap();
    let o = run_in(d, &["fresnel", "--eta", "1.33", "--table", "8", "-o", "link.exr"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(d.join("link.exr")).unwrap().file_type().is_symlink());
    assert!(std::fs::read(d.join("real.exr")).unwrap().starts_with(&[0x76, 0x2f, 0x31, 0x01]));
}

// ---------------------------------------------------------------------------------------------
// 2 and 8. Frame ranges stream; what a sequence asks is checked before its first frame

#[test]
fn a_billion_frame_range_writes_its_first_frame_with_little_memory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut child = ocean()
        .args(["render", "--size", "16x9", "--frames", "0..1000000000", "-o", "o/f_{}.png"])
        .current_dir(d)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(60);
    // Before: 8.7 GB and no frame after 60 s. Now frames appear as they are drawn.
    while !d.join("o/f_2.png").exists() {
        assert!(child.try_wait().unwrap().is_none(), "the run ended early");
        assert!(Instant::now() < deadline, "no third frame in 60 s");
        std::thread::sleep(Duration::from_millis(50));
    }
    let status = std::fs::read_to_string(format!("/proc/{}/status", child.id())).unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    let kib: f64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    assert!(kib / 1024.0 < 2.0 * REFUSED_MIB, "{} MiB for 3 frames of 16×9", kib / 1024.0);
}

#[test]
fn a_replay_of_hours_is_stated_and_refused_before_it_starts() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("reference/scenes/foam_storm.toml");
    let scene = scene.to_str().unwrap();
    let o = run_in(
        dir.path(),
        &["render", scene, "--size", "16x9", "--frames", "1000000..1000001", "-o", "f{}.png"],
    );
    // Before: 14 hours of stepping with no word.
    refused(&o, &["1000000 frames undrawn", "--replay-any", "up to 1000000 earlier frame"]);
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none(), "nothing written");
    // Control: a short replay runs, and says so first.
    let o = run_in(
        dir.path(),
        &["render", scene, "--size", "16x9", "--frames", "3..4", "-o", "f{}.png"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("up to 3 earlier frame(s) are stepped"), "{}", stderr(&o));
    assert!(dir.path().join("f3.png").exists());
}

#[test]
fn sequence_arguments_are_checked_before_frame_0() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // --fps 1e-300: frame 1's time is out of the scene's range; before, frame 0 was written.
    let o = run_in(
        d,
        &["render", "--size", "16x9", "--frames", "0..2", "--fps", "1e-300", "-o", "f{}.png"],
    );
    refused(&o, &["--fps 1e-300", "time_s"]);
    assert!(!d.join("f0.png").exists());
    // An empty shard says so, instead of calling its frames "on disk".
    let o = run_in(
        d,
        &["render", "--size", "16x9", "--frames", "0..2", "--shard", "3/4", "-o", "f{}.png"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("holds no frame") && !stderr(&o).contains("on disk"),
        "{}",
        stderr(&o)
    );
    // A placeholder in a folder: every frame's folder is made (before, only frame 0's).
    let o = run_in(d, &["render", "--size", "16x9", "--frames", "0..3", "-o", "s{}/f.png"]);
    assert!(o.status.success(), "{}", stderr(&o));
    for n in 0..3 {
        assert!(d.join(format!("s{n}/f.png")).is_file(), "frame {n}");
    }
    // `bench -o` into a missing folder fails before measuring, naming the folder.
    let o = run_in(d, &["bench", "--quick", "--only", "waves", "-o", "missing/b.json"]);
    refused(&o, &["missing/b.json", "folder missing does not exist"]);
}

// ---------------------------------------------------------------------------------------------
// 3 and 8. Images: the header first, then the pixels

#[test]
fn forged_image_headers_are_refused_before_decoding() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (name, bytes, words) in [
        ("claims32k.exr", forged_exr(32768, 32768), vec!["32768×32768", "1 to 8192 per side"]),
        ("claims64k.exr", forged_exr(65536, 65536), vec!["65536×65536", "1 to 8192 per side"]),
        ("claims64k.png", forged_png(65536, 65536), vec!["claims64k.png"]),
    ] {
        std::fs::write(d.join(name), bytes).unwrap();
        let scene = heightmap_scene(d, name);
        let o = run_in(d, &["render", scene.to_str().unwrap(), "--size", "16x9", "-o", "x.png"]);
        let mut words = words.clone();
        words.push(name);
        refused(&o, &words);
        assert!(temporaries(d).is_empty(), "{name}: {:?}", temporaries(d));
    }
    // A header within the side limit but over --memory-limit: refused before decoding
    // (before: a valid 8192² PNG took 797 MB under --memory-limit 400M).
    std::fs::write(d.join("big.png"), forged_png(8192, 8192)).unwrap();
    let scene = heightmap_scene(d, "big.png");
    let args = ["render", scene.to_str().unwrap(), "--size", "16x9", "--memory-limit", "64M"];
    let o = run_in(d, &[&args[..], &["-o", "x.png"]].concat());
    refused(&o, &["big.png", "8192×8192", "--memory-limit"]);
    // A FIFO named as a heightmap: refused at once (before: blocked forever).
    mkfifo(&d.join("pipe.png"));
    let scene = heightmap_scene(d, "pipe.png");
    let o = run_in(d, &["render", scene.to_str().unwrap(), "--size", "16x9", "-o", "x.png"]);
    refused(&o, &["pipe.png", "named pipe"]);
    // A finite sample whose height overflows f32: an error, not a floor that vanishes.
    write_exr(&d.join("huge.exr"), 2, 2, vec![0.0, 0.5, 3e38, 1.0]);
    let scene = heightmap_scene(d, "huge.exr");
    let o = run_in(d, &["render", scene.to_str().unwrap(), "--size", "16x9", "-o", "x.png"]);
    refused(&o, &["huge.exr", "texel (0, 1)", "beyond f32"]);
    // Control: a sane EXR of the same shape renders.
    write_exr(&d.join("sane.exr"), 2, 2, vec![0.0, 0.5, 0.25, 1.0]);
    let scene = heightmap_scene(d, "sane.exr");
    let o = run_in(d, &["render", scene.to_str().unwrap(), "--size", "16x9", "-o", "x.png"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

// ---------------------------------------------------------------------------------------------
// 4, 5 and 7. `compare --against` and dumps

/// A dump of the built-in scene at 32×18 in `dir/name`, by the CPU.
fn dump(dir: &Path, name: &str) -> PathBuf {
    let o = run_in(dir, &["render", "--size", "32x18", "--dump-passes", name, "-o", "x.png"]);
    assert!(o.status.success(), "{}", stderr(&o));
    dir.join(name)
}

#[test]
fn a_dump_of_the_builtin_scene_passes_its_own_comparison() {
    // Before: `reflection_map FAIL size cpu (1280, 720) gpu (64, 36)`: the manifest's frame
    // was ignored when the scene text was empty.
    let dir = tempfile::tempdir().unwrap();
    let d = dump(dir.path(), "d");
    let o = run_in(dir.path(), &["compare", "--against", d.to_str().unwrap(), "--out-dir", "c"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Control: a resized manifest frame is used, and then fails on size.
    let m = std::fs::read_to_string(d.join("manifest.json")).unwrap();
    std::fs::write(d.join("manifest.json"), m.replace("\"width\": 32", "\"width\": 48")).unwrap();
    let o = run_in(dir.path(), &["compare", "--against", d.to_str().unwrap(), "--out-dir", "c"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

#[test]
fn a_hostile_manifest_is_refused_with_its_cause() {
    let dir = tempfile::tempdir().unwrap();
    let d = dump(dir.path(), "d");
    let good = std::fs::read_to_string(d.join("manifest.json")).unwrap();
    let compare = |words: &[&str]| {
        let o = run_in(dir.path(), &["compare", "--against", "d", "--out-dir", "c"]);
        refused(&o, words);
    };
    std::fs::remove_file(d.join("manifest.json")).unwrap();
    // A link to /dev/zero: before, read to 4.2 GB and then ignored.
    std::os::unix::fs::symlink("/dev/zero", d.join("manifest.json")).unwrap();
    compare(&["manifest.json", "a character device"]);
    std::fs::remove_file(d.join("manifest.json")).unwrap();
    // A folder, and bytes that are not UTF-8: before, treated as absent.
    std::fs::create_dir(d.join("manifest.json")).unwrap();
    compare(&["manifest.json", "a folder"]);
    std::fs::remove_dir(d.join("manifest.json")).unwrap();
    std::fs::write(d.join("manifest.json"), b"{\"frame\": \"\xff\xfe\"}").unwrap();
    compare(&["manifest.json", "not UTF-8"]);
    // A width of 2³² + 64 (before: truncated to 64, and passed) and of −64 (ignored).
    for bad in ["4294967328", "-64", "32.5", "\"32\""] {
        std::fs::write(
            d.join("manifest.json"),
            good.replace("\"width\": 32", &format!("\"width\": {bad}")),
        )
        .unwrap();
        compare(&["frame.width", "1..=16384"]);
    }
    // A forged map header: refused before decoding.
    std::fs::write(d.join("manifest.json"), &good).unwrap();
    std::fs::copy(d.join("hdr.exr"), dir.path().join("hdr.good")).unwrap();
    std::fs::write(d.join("hdr.exr"), forged_exr(65536, 65536)).unwrap();
    let o = run_in(dir.path(), &["compare", "--against", "d", "--out-dir", "c"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("hdr.exr") && e.contains("65536×65536"), "{e}");
    assert!(peak_mib(&o) < REFUSED_MIB, "{e}");
    // A spray step that names another file, has no whole step or no slots: refused by name.
    assert!(good.contains("\"spray_step\": null"), "the manifest says it has no spray step");
    let step =
        |entry: &str| good.replace("\"spray_step\": null", &format!("\"spray_step\": {entry}"));
    for bad in [
        r#"{"file": "../hdr.exr", "step": 1, "slots": 4}"#,
        r#"{"file": "spray_step.exr", "step": -1, "slots": 4}"#,
        r#"{"file": "spray_step.exr", "step": 1, "slots": 0}"#,
    ] {
        std::fs::write(d.join("manifest.json"), step(bad)).unwrap();
        compare(&["spray_step", "spray_step.exr"]);
    }
    // A forged spray step file: refused before decoding, under the envelope that reads it.
    std::fs::write(d.join("hdr.exr"), std::fs::read(dir.path().join("hdr.good")).unwrap()).unwrap();
    let entry = r#"{"file": "spray_step.exr", "step": 1, "slots": 4}"#;
    std::fs::write(d.join("manifest.json"), step(entry)).unwrap();
    std::fs::write(d.join("spray_step.exr"), forged_exr(65536, 65536)).unwrap();
    let o = run_in(
        dir.path(),
        &["compare", "--against", "d", "--out-dir", "c", "--tolerance", "envelope"],
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("spray_step.exr") && e.contains("65536×65536"), "{e}");
    assert!(peak_mib(&o) < REFUSED_MIB, "{e}");
}

/// Runs `ocean ARGS` in `dir` with writes past `kib` KiB failing (EFBIG, as on a full disk):
/// `ulimit -f`, with SIGXFSZ ignored so that the write returns an error instead of killing.
fn run_on_a_full_disk(dir: &Path, kib: u32, args: &[&str]) -> Output {
    let exe = env!("CARGO_BIN_EXE_ocean");
    Command::new("bash")
        .arg("-c")
        .arg(format!("trap '' XFSZ; ulimit -f {kib}; exec \"$0\" \"$@\""))
        .arg(exe)
        .args(args)
        .current_dir(dir)
        .env("RUST_BACKTRACE", "0")
        .output()
        .unwrap()
}

#[test]
fn a_full_disk_leaves_no_empty_picture_and_no_partial_dump() {
    let dir = tempfile::tempdir().unwrap();
    dump(dir.path(), "d");
    // compare --against: every diff picture written whole or not at all (before: nine
    // 0-byte .diff.png and an error naming no file).
    let o = run_on_a_full_disk(dir.path(), 0, &["compare", "--against", "d", "--out-dir", "c"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("cannot write") && e.contains("c/"), "{e}");
    for f in std::fs::read_dir(dir.path().join("c")).unwrap().flatten() {
        assert!(f.metadata().unwrap().len() > 0, "empty {}", f.path().display());
    }
    assert!(temporaries(&dir.path().join("c")).is_empty());
    // --dump-passes: no folder without its manifest (before: a partial dump).
    let o = run_on_a_full_disk(
        dir.path(),
        0,
        &["render", "--size", "32x18", "--dump-passes", "e", "-o", "y.png"],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(!dir.path().join("e").exists(), "a partial dump was left");
    assert!(temporaries(dir.path()).is_empty(), "{:?}", temporaries(dir.path()));
    // Control: the same dump on a disk with room, twice (the second replaces the first).
    assert!(dump(dir.path(), "e").join("manifest.json").is_file());
    assert!(dump(dir.path(), "e").join("manifest.json").is_file());
    // And a folder of someone else's files is not replaced.
    std::fs::create_dir(dir.path().join("mine")).unwrap();
    std::fs::write(dir.path().join("mine/notes.txt"), "keep").unwrap();
    let o =
        run_in(dir.path(), &["render", "--size", "32x18", "--dump-passes", "mine", "-o", "z.png"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("mine exists and holds files that are not ocean's"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(dir.path().join("mine/notes.txt")).unwrap(), "keep");
}
