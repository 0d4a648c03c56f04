//! The command line's contracts (docs/design.md): CSV and EXR layouts, exit codes, clear errors,
//! no output file on failure.
//!
//! The GPU commands' tests need an adapter: without one they fail under `OCEAN_REQUIRE_GPU=1`
//! (CI) and are otherwise reported ignored, with why (tests/support/gpu_harness.rs).

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;

#[path = "support/cli.rs"]
mod ocean_cli;

use std::path::Path;
use std::process::Output;

use ocean_cli::{ocean, ocean_env};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Reads every f32 channel of a single-layer EXR as (name, samples).
fn read_exr(path: &Path) -> (usize, usize, Vec<(String, Vec<f32>)>) {
    use exr::prelude::*;
    let image = read_all_flat_layers_from_file(path).expect("a readable EXR");
    let layer = &image.layer_data[0];
    let size = layer.size;
    let channels = layer
        .channel_data
        .list
        .iter()
        .map(|c| {
            let data = match &c.sample_data {
                FlatSamples::F32(v) => v.clone(),
                other => panic!("channel {} is not f32: {other:?}", c.name),
            };
            (c.name.to_string(), data)
        })
        .collect();
    (size.0, size.1, channels)
}

fn fresnel_csv_contract() {
    let o = ocean(&["fresnel", "--eta", "1.333"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).expect("utf-8");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("theta_deg,cos_theta,exact,schlick"));
    let rows: Vec<Vec<f64>> =
        lines.map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect()).collect();
    assert_eq!(rows.len(), 91);
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r.len(), 4);
        assert_eq!(r[0], i as f64);
        let cos = if i == 90 { 0.0 } else { (i as f64).to_radians().cos() };
        assert_eq!(r[1], cos, "cos printed to round-trip");
        assert!((0.0..=1.0).contains(&r[2]) && (0.0..=1.0).contains(&r[3]));
    }
    // Normal incidence: ((η − 1)/(η + 1))² = 0.0204 for water.
    assert!((rows[0][2] - 0.02040).abs() < 5e-5, "{}", rows[0][2]);
    assert_eq!(rows[90][2], 1.0);
    let o = ocean(&["fresnel", "--eta", "1.333", "--step-deg", "0.5"]);
    assert_eq!(String::from_utf8_lossy(&o.stdout).lines().count(), 182);
}

fn fresnel_rejects_bad_eta_without_panicking() {
    for bad in ["0", "-1", "nan", "inf"] {
        let o = ocean(&["fresnel", "--eta", bad]);
        assert_eq!(o.status.code(), Some(1), "--eta {bad}");
        assert!(stderr(&o).contains("--eta"), "{}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"));
    }
}

fn fresnel_table_exr_contract() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let path = dir.path().join("f.exr");
    let o = ocean(&["fresnel", "--eta", "1.333", "--table", "16", "-o", path.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, channels) = read_exr(&path);
    assert_eq!((w, h), (16, 16));
    let names: Vec<&str> = channels.iter().map(|c| c.0.as_str()).collect();
    assert_eq!(names, ["A", "B", "G", "R"]);
    let get = |n: &str| &channels.iter().find(|c| c.0 == n).unwrap().1;
    let (r, g, b, a) = (get("R"), get("G"), get("B"), get("A"));
    let n = 16usize;
    for j in 0..n {
        for i in 0..n {
            let idx = j * n + i;
            let x = 2.0 * (i as f64 + 0.5) / n as f64 - 1.0;
            let y = 2.0 * (j as f64 + 0.5) / n as f64 - 1.0;
            let r2 = x * x + y * y;
            let (ex, ey, ez) = if r2 <= 1.0 {
                (x, y, (1.0 - r2).sqrt())
            } else {
                (x / r2.sqrt(), y / r2.sqrt(), 0.0)
            };
            assert!((r[idx] as f64 - ex).abs() < 1e-6, "R at ({i},{j})");
            assert!((g[idx] as f64 - ey).abs() < 1e-6, "G at ({i},{j})");
            assert!((b[idx] as f64 - ez).abs() < 1e-6, "B at ({i},{j})");
            assert!((0.0..=1.0).contains(&a[idx]));
        }
    }
}

/// `--mapping grazing`: the edge texels are the rim (B = z = 0, A = F = 1) and the centre of
/// an odd table is the normal; an unknown mapping is refused with the known ones.
fn fresnel_table_mappings() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let path = dir.path().join("g.exr");
    let p = path.to_str().unwrap();
    let o = ocean(&["fresnel", "--eta", "1.333", "--table", "17", "--mapping", "grazing", "-o", p]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("grazing mapping"), "{}", stderr(&o));
    let (_, _, channels) = read_exr(&path);
    let get = |n: &str| &channels.iter().find(|c| c.0 == n).unwrap().1;
    let (b, a) = (get("B"), get("A"));
    let n = 17usize;
    for k in 0..n {
        for idx in [k, (n - 1) * n + k, k * n, k * n + n - 1] {
            assert_eq!((b[idx], a[idx]), (0.0, 1.0), "edge texel {idx}");
        }
    }
    assert_eq!(b[8 * n + 8], 1.0);
    let o = ocean(&["fresnel", "--eta", "1.333", "--table", "17", "--mapping", "rim", "-o", p]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("hemisphere, half-range, grazing"), "{}", stderr(&o));
}

fn fresnel_table_needs_an_exr_output() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let png = dir.path().join("f.png");
    let o = ocean(&["fresnel", "--eta", "1.333", "--table", "16", "-o", png.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(!png.exists());
    let o = ocean(&["fresnel", "--eta", "1.333", "--table", "0", "-o", "x.exr"]);
    assert_eq!(o.status.code(), Some(1));
    let o = ocean(&["fresnel", "--eta", "1.333", "--table", "16"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

fn bad_scene_names_file_line_key_and_writes_nothing() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let out = dir.path().join("h.exr");
    let cases = [
        ("[ocean]\nwind_speed = 5.0\nresolutoin = 64\n", "3:1", "resolutoin"),
        ("[ocean]\nresolution = \"big\"\n", "2:", "resolution"),
        ("[ocean]\nresolution = 0\n", "2:1", "ocean.resolution"),
        ("[camera]\nfov_y_deg = -5\n", "2:1", "camera.fov_y_deg"),
        ("[ocean]\nwind_speed = nan\n", "2:1", "ocean.wind_speed"),
    ];
    for (text, position, key) in cases {
        let scene = dir.path().join("bad.toml");
        std::fs::write(&scene, text).unwrap();
        let o = ocean(&["heightfield", scene.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{text:?}: {err}");
        assert!(err.contains(&format!("bad.toml:{position}")), "{text:?}: {err}");
        assert!(err.contains(key), "{text:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!out.exists(), "no output may be written on error");
    }
    let o = ocean(&["heightfield", "/nonexistent/scene.toml", "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("/nonexistent/scene.toml"));
}

fn heightfield_exr_contract() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let scene = dir.path().join("s.toml");
    std::fs::write(&scene, "[ocean]\nresolution = 32\npatch_size_m = 64.0\nchoppiness = 1.0\n")
        .unwrap();
    let out = dir.path().join("h.exr");
    let o = ocean(&[
        "heightfield",
        scene.to_str().unwrap(),
        "--time",
        "3.5",
        "--seed",
        "9",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, channels) = read_exr(&out);
    assert_eq!((w, h), (32, 32));
    let mut names: Vec<&str> = channels.iter().map(|c| c.0.as_str()).collect();
    names.sort_unstable();
    assert_eq!(names, ["disp_x", "disp_z", "height", "jacobian", "slope_x", "slope_z"]);
    for (name, data) in &channels {
        assert!(data.iter().all(|v| v.is_finite()), "{name} has non-finite values");
    }
    let height = &channels.iter().find(|c| c.0 == "height").unwrap().1;
    assert!(height.iter().any(|&v| v != 0.0), "a 10 m/s sea is not flat");

    // Same scene, time and seed: the same bytes (the synthesis is deterministic); another
    // seed: another sea.
    let again = dir.path().join("h2.exr");
    let args = |o: &str, seed: &str| {
        ocean(&["heightfield", scene.to_str().unwrap(), "--time", "3.5", "--seed", seed, "-o", o])
    };
    assert!(args(again.to_str().unwrap(), "9").status.success());
    assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&again).unwrap());
    assert!(args(again.to_str().unwrap(), "10").status.success());
    assert_ne!(std::fs::read(&out).unwrap(), std::fs::read(&again).unwrap());
}

/// Under waves `gerstner` the heightfield is the waves' sum at the grid's points: one explicit
/// wave at t = 0 against its closed form (θ = k D·(x, z) + φ; h = A sin θ, D = (s/k) D cos θ,
/// slopes A k D cos θ, J = 1 − s sin θ for a single wave).
fn heightfield_of_gerstner_waves_is_their_closed_form() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let scene = dir.path().join("g.toml");
    let (a, lambda, deg, s, phi) = (0.4f64, 12.0f64, 30.0f64, 0.7f64, 0.5f64);
    std::fs::write(
        &scene,
        format!(
            "[techniques]\nwaves = \"gerstner\"\nfar_field = \"mip\"\n[ocean]\nresolution = 32\npatch_size_m = 40.0\n\
             [[gerstner.waves]]\namplitude_m = {a}\nwavelength_m = {lambda}\n\
             direction_deg = {deg}\nsteepness = {s}\nphase = {phi}\n"
        ),
    )
    .unwrap();
    let out = dir.path().join("g.exr");
    let o = ocean(&["heightfield", scene.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, channels) = read_exr(&out);
    assert_eq!((w, h), (32, 32));
    let field = |n: &str| &channels.iter().find(|c| c.0 == n).expect(n).1;
    let k = std::f64::consts::TAU / lambda;
    let (dx, dz) = (deg.to_radians().cos(), deg.to_radians().sin());
    let mut worst = 0.0f64;
    for j in 0..32 {
        for i in 0..32 {
            let (x, z) = (f64::from(i) * 40.0 / 32.0, f64::from(j) * 40.0 / 32.0);
            let theta = k * (dx * x + dz * z) + phi;
            let want = [
                ("height", a * theta.sin()),
                ("disp_x", s / k * dx * theta.cos()),
                ("disp_z", s / k * dz * theta.cos()),
                ("slope_x", a * k * dx * theta.cos()),
                ("slope_z", a * k * dz * theta.cos()),
                ("jacobian", 1.0 - s * theta.sin()),
            ];
            for (name, v) in want {
                let got = f64::from(field(name)[(j * 32 + i) as usize]);
                worst = worst.max((got - v).abs());
            }
        }
    }
    // f32 output of O(1) values: a few 1e-7; a wrong sign, axis or phase is O(0.1).
    assert!(worst < 1e-6, "worst deviation from the closed form {worst}");
    // Negative control: the FFT's heightfield of the same [ocean] is another surface.
    std::fs::write(&scene, "[ocean]\nresolution = 32\npatch_size_m = 40.0\n").unwrap();
    let fft = dir.path().join("f.exr");
    assert!(
        ocean(&["heightfield", scene.to_str().unwrap(), "-o", fft.to_str().unwrap()])
            .status
            .success()
    );
    let (_, _, f) = read_exr(&fft);
    let fh = &f.iter().find(|c| c.0 == "height").unwrap().1;
    assert!(fh.iter().zip(field("height")).any(|(p, q)| (p - q).abs() > 0.01));
}

fn render_writes_png_and_exr_and_rejects_bad_input() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let png = dir.path().join("o.png");
    let o = ocean(&["render", "--size", "64x36", "-o", png.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(&png).expect("a PNG").to_rgba8();
    assert_eq!(img.dimensions(), (64, 36));
    let exr = dir.path().join("o.exr");
    let o = ocean(&["render", "--size", "64x36", "--time", "3", "-o", exr.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, channels) = read_exr(&exr);
    assert_eq!((w, h), (64, 36));
    assert_eq!(channels.len(), 4);
    assert!(channels.iter().all(|(_, d)| d.iter().all(|v| v.is_finite())));
    // Nothing is written on an error, and no error panics.
    let never = dir.path().join("never.png");
    for args in [
        vec!["render", "--size", "0x10", "-o"],
        vec!["render", "--size", "big", "-o"],
        vec!["render", "--time", "nan", "-o"],
        vec!["render", "/nonexistent.toml", "-o"],
    ] {
        let mut a = args.clone();
        a.push(never.to_str().unwrap());
        let o = ocean(&a);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"), "{args:?}");
        assert!(!never.exists(), "{args:?} wrote a file");
    }
    let o = ocean(&["render", "-o", dir.path().join("x.jpg").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
}

fn gpu_without_an_adapter_says_what_to_do_and_writes_nothing() {
    // A backend this platform's build cannot open stands for a machine without a GPU.
    let dir = tempfile::tempdir().expect("a temp dir");
    let never = dir.path().join("never.png");
    let no_gpu = [("WGPU_BACKEND", if cfg!(target_os = "macos") { "dx12" } else { "metal" })];
    let o = ocean_env(&["render", "--backend", "gpu", "-o", never.to_str().unwrap()], &no_gpu);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("no GPU adapter") && err.contains("--backend cpu"), "{err}");
    assert!(err.contains("mesa-vulkan-drivers"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!never.exists());
    let out = dir.path().join("cmp");
    let o = ocean_env(&["compare", "--size", "32x18", "--out-dir", out.to_str().unwrap()], &no_gpu);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("--backend cpu"), "{}", stderr(&o));
}

fn render_on_the_gpu_writes_png_and_exr() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let png = dir.path().join("g.png");
    let o = ocean(&["render", "--backend", "gpu", "--size", "64x36", "-o", png.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("GPU"), "{}", stderr(&o));
    let img = image::open(&png).expect("a PNG").to_rgba8();
    assert_eq!(img.dimensions(), (64, 36));
    let exr = dir.path().join("g.exr");
    let o = ocean(&["render", "--backend", "gpu", "--size", "64x36", "-o", exr.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, channels) = read_exr(&exr);
    assert_eq!((w, h, channels.len()), (64, 36, 4));
    assert!(channels.iter().all(|(_, d)| d.iter().all(|v| v.is_finite())));
}

fn compare_prints_metrics_writes_images_and_passes() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let out = dir.path().join("cmp");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("reference/scenes/calm.toml");
    let o = ocean(&[
        "compare",
        scene.to_str().unwrap(),
        "--size",
        "64x36",
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "{text}\n{}", stderr(&o));
    for needle in
        ["calm 64x36", "displacement", "fresnel_above", "hdr", "FLIP mean", "within 1/255"]
    {
        assert!(text.contains(needle), "{needle} missing from:\n{text}");
    }
    for file in ["calm.cpu.png", "calm.gpu.png", "calm.diff.png", "calm.flip.png", "calm.json"] {
        assert!(out.join(file).is_file(), "{file} not written");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("calm.json")).unwrap()).unwrap();
    assert_eq!(json["passed"], true, "{json}");
    assert!(json["adapter"]["name"].as_str().is_some_and(|n| !n.is_empty()));
}

/// `ocean compare --system chiu` on the built-in scene: every pass of Chiu & Chang's system
/// (projected grid, shading chiu, clouds, spray) within docs/design.md's tolerances, exit 0.
fn compare_system_chiu_passes() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let out = dir.path().join("cmp");
    let o = ocean(&[
        "compare",
        "--system",
        "chiu",
        "--size",
        "64x36",
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "{text}\n{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("default.json")).unwrap()).unwrap();
    assert_eq!(json["passed"], true, "{json}");
    assert!(text.contains("within 1/255"), "{text}");
}

/// Checks `ocean bench --json`'s cases: each timed, positive and finite; a frame's passes
/// fit in its total; the GPU's frames have an encode time. Returns the cases.
fn bench_cases(json: &serde_json::Value) -> Vec<serde_json::Value> {
    let cases = json["cases"].as_array().expect("cases").clone();
    for c in &cases {
        let total = c["frame_ms"].as_f64().expect("frame_ms");
        assert!(total.is_finite() && total > 0.0, "{c}");
        let passes: f64 = c["passes"]
            .as_array()
            .expect("passes")
            .iter()
            .map(|p| p[1].as_f64().expect("a pass's ms"))
            .sum();
        // The passes are parts of the frame (they are the median run's own: the GPU's ran
        // inside its wall time, the CPU's one after another in it); 1 % and 0.1 ms for clock
        // granularity.
        assert!(passes <= 1.01 * total + 0.1, "passes {passes} ms > frame {total} ms: {c}");
        if c["kind"] == "frame" {
            assert!(!c["passes"].as_array().expect("passes").is_empty(), "{c}");
            assert_eq!(c["backend"] == "gpu", c["encode_ms"].as_f64().is_some(), "{c}");
            // The encode's CPU time is the calling thread's, inside the call's wall time. The
            // CPU clock brackets the whole call and the wall time starts inside it, so the CPU
            // figure may pass it by the call's own entry and exit (µs): 1 % and 0.05 ms.
            if cfg!(unix) && c["backend"] == "gpu" {
                let (cpu, wall) = (c["encode_cpu_ms"].as_f64(), c["encode_ms"].as_f64());
                let (Some(cpu), Some(wall)) = (cpu, wall) else { panic!("no encode times: {c}") };
                assert!(
                    cpu > 0.0 && cpu <= 1.01 * wall + 0.05,
                    "CPU {cpu} ms, wall {wall} ms: {c}"
                );
            }
            // The median encode's steps are parts of its call, and most of it (the rest is
            // the frame's bookkeeping after the submission).
            if c["backend"] == "gpu" {
                let split = &c["encode_split_ms"];
                let parts: Vec<f64> = ["prepare", "record", "finish", "submit"]
                    .iter()
                    .map(|k| split[*k].as_f64().unwrap_or(f64::NAN))
                    .collect();
                let (sum, wall) = (parts.iter().sum::<f64>(), c["encode_ms"].as_f64().unwrap());
                assert!(parts.iter().all(|p| *p >= 0.0) && parts[2] > 0.0, "{c}");
                assert!(
                    sum <= wall + 1e-6 && sum >= 0.5 * wall,
                    "steps {sum} ms in {wall} ms: {c}"
                );
            } else {
                assert!(c["encode_split_ms"].is_null(), "{c}");
            }
            // The steady frame (no read-back, frames back to back) is a GPU frame's figure.
            assert_eq!(
                c["backend"] == "gpu",
                c["steady_ms"].as_f64().is_some_and(|v| v > 0.0),
                "{c}"
            );
        }
        if let Some(m) = c["peak_rss_mib"].as_f64() {
            assert!(m > 1.0, "{c}");
        }
    }
    cases
}

fn bench_quick_times_every_system_on_both_back_ends() {
    let start = std::time::Instant::now();
    let o = ocean(&["bench", "--quick", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    eprintln!("ocean bench --quick --json: {:.1} s", start.elapsed().as_secs_f64());
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let cases = bench_cases(&json);
    for system in ["hu", "chiu", "welch", "coastal"] {
        for backend in ["cpu", "gpu"] {
            let n = cases
                .iter()
                .filter(|c| c["kind"] == "frame" && c["name"] == system && c["backend"] == backend)
                .count();
            assert_eq!(n, 1, "{system} on {backend}");
        }
    }
    let waves: Vec<_> = cases.iter().filter(|c| c["kind"] == "waves").collect();
    assert_eq!(waves.len(), 8, "N = 64 and 128: the CPU, the frame's GPU FFT, both its kernels");
    assert!(json["adapter"].is_string());
    let info = &json["adapter_info"];
    for key in ["name", "vendor", "device_type", "driver", "backend"] {
        assert!(info[key].as_str().is_some_and(|v| !v.is_empty()), "adapter_info.{key}: {info}");
    }
    assert!(json["gpu_copy_gb_s"].as_f64().is_some_and(|b| b > 0.0));
    for c in waves.iter().filter(|c| c["backend"] == "gpu") {
        let bound = c["bandwidth_bound_ms"].as_f64().expect("a GPU synthesis has its bound");
        assert!(bound > 0.0 && bound < c["frame_ms"].as_f64().unwrap_or(0.0), "{c}");
    }
}

fn bench_cpu_alone_needs_no_gpu_and_prints_a_table() {
    let o = ocean_env(
        &["bench", "--quick", "--backend", "cpu", "--runs", "1"],
        &[("WGPU_BACKEND", "gl")],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let table = String::from_utf8_lossy(&o.stdout);
    eprintln!("{table}");
    assert!(table.contains("GPU: not used"), "{table}");
    for system in ["hu", "chiu", "welch", "coastal"] {
        assert!(table.lines().any(|l| l.contains(system) && l.contains(" cpu ")), "{system}");
    }
    assert!(!table.lines().any(|l| l.contains(" gpu ")), "{table}");
    // The checker's negative control: passes longer than their frame fail it.
    let inconsistent = serde_json::json!({"cases": [{"kind": "waves", "backend": "cpu",
        "frame_ms": 1.0, "encode_ms": null, "passes": [["waves", 2.0]]}]});
    let quiet = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let caught = std::panic::catch_unwind(|| bench_cases(&inconsistent)).is_err();
    std::panic::set_hook(quiet);
    assert!(caught, "passes longer than their frame passed the check");
    let bad = ocean(&["bench", "--backend", "tpu"]);
    assert_eq!(bad.status.code(), Some(2), "{}", stderr(&bad));
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        cpu: fresnel_csv_contract, fresnel_rejects_bad_eta_without_panicking,
            fresnel_table_exr_contract, fresnel_table_mappings, fresnel_table_needs_an_exr_output,
            bad_scene_names_file_line_key_and_writes_nothing, heightfield_exr_contract,
            heightfield_of_gerstner_waves_is_their_closed_form,
            render_writes_png_and_exr_and_rejects_bad_input,
            gpu_without_an_adapter_says_what_to_do_and_writes_nothing,
            bench_cpu_alone_needs_no_gpu_and_prints_a_table;
        gpu: render_on_the_gpu_writes_png_and_exr, compare_prints_metrics_writes_images_and_passes,
            compare_system_chiu_passes, bench_quick_times_every_system_on_both_back_ends;
    )
}
