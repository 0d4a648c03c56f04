//! `ocean report --quick` and `ocean plan` on the command line (issue 5): the CSV contract
//! (`knob,setting,error_metric,error,time_ms,backend`), one row per knob at least, finite
//! numbers, the plot and report.md with its Pareto, planner and stability sections; `ocean
//! plan --json` carries the new passes and the per-pass object lists.

use std::process::{Command, Output};

fn ocean(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ocean"))
        .args(args)
        .env("RUST_BACKTRACE", "0")
        .output()
        .expect("the ocean binary runs")
}

const HEADER: &str = "knob,setting,error_metric,error,time_ms,backend";

/// The problems of an error_vs_time.csv text: wrong header, missing knobs, bad numbers.
fn csv_problems(text: &str) -> Vec<String> {
    let mut problems = Vec::new();
    let mut lines = text.lines();
    if lines.next() != Some(HEADER) {
        problems.push("header".into());
    }
    let mut knobs = Vec::new();
    for line in lines {
        // Settings hold no commas in this report, so a plain split is exact.
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != 6 {
            problems.push(format!("fields: {line}"));
            continue;
        }
        let ok = |v: &str| v.parse::<f64>().is_ok_and(|x| x.is_finite() && x >= 0.0);
        if !ok(f[3]) || !ok(f[4]) {
            problems.push(format!("numbers: {line}"));
        }
        if !knobs.contains(&f[0]) {
            knobs.push(f[0]);
        }
    }
    for want in [
        "fresnel",
        "wave_resolution",
        "precision",
        "bump_resolution",
        "reflection_map_resolution",
        "backend",
        "far_field",
        "shading",
        "post",
        "frame_format",
        "lod",
    ] {
        if !knobs.contains(&want) {
            problems.push(format!("knob {want} missing"));
        }
    }
    problems
}

#[test]
fn quick_report_writes_csv_plot_and_markdown() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    let o = ocean(&["report", "--quick", "--out-dir", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("error_vs_time.csv")).unwrap();
    let problems = csv_problems(&csv);
    assert!(problems.is_empty(), "{problems:?}");
    let svg = std::fs::read_to_string(out.join("error_vs_time.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("reflection_map_resolution"));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    for section in
        ["## Pareto-optimal settings", "## Planner", "## Scaling", "## Numerical stability"]
    {
        assert!(md.contains(section), "{section} missing");
    }
    // The planner's pictures are bit-identical and every stability case holds.
    assert!(!md.contains("FAIL"), "{md}");
    // No temporary file is left behind.
    let names: Vec<_> = std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names.len(), 4, "{names:?}");
    // The scaling plot: both panels, every fitted series labelled with its exponent (the GPU's
    // too under OCEAN_REQUIRE_GPU=1, where an adapter must be here).
    let scaling = std::fs::read_to_string(out.join("scaling.svg")).unwrap();
    assert!(scaling.contains("wave synthesis") && scaling.contains("frame: time"), "panels");
    for series in ["cpu_synthesizer_f32 cpu: exponent", "hu cpu: exponent", "coastal cpu"] {
        assert!(scaling.contains(series), "{series} missing from scaling.svg");
    }
    if std::env::var("OCEAN_REQUIRE_GPU").is_ok_and(|v| v == "1") {
        assert!(scaling.contains("gpu_fft gpu: exponent") && scaling.contains("hu gpu: exponent"));
    }
    let section = md.split("## Scaling").nth(1).unwrap();
    let section = section.split("\n## ").next().unwrap();
    let exponents: Vec<f64> = section
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| what"))
        .map(|l| l.split('|').nth(4).unwrap().trim().parse::<f64>().unwrap())
        .collect();
    assert!(exponents.len() >= 5 && exponents.iter().all(|e| e.is_finite()), "{exponents:?}");

    // Negative controls of the CSV check: a changed header, a NaN, a missing knob.
    assert!(!csv_problems(&csv.replacen("time_ms", "time", 1)).is_empty());
    assert!(
        !csv_problems(&csv.replacen(",cpu\n", ",cpu\nlod,x,flip_mean,NaN,1.0,cpu\n", 1)).is_empty()
    );
    let without_lod: String =
        csv.lines().filter(|l| !l.starts_with("lod,")).map(|l| format!("{l}\n")).collect();
    assert!(!csv_problems(&without_lod).is_empty());
}

#[test]
fn plan_json_names_the_new_passes_and_the_object_lists() {
    let scenes = concat!(env!("CARGO_MANIFEST_DIR"), "/reference/scenes/");
    let o = ocean(&["plan", &format!("{scenes}looking_down.toml"), "--json"]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let names = |k: &str| -> Vec<String> {
        v[k].as_array().unwrap().iter().map(|p| p["name"].as_str().unwrap().to_string()).collect()
    };
    assert!(names("skipped").contains(&"far_patch".to_string()), "{v}");
    assert!(names("skipped").contains(&"cycle".to_string()), "{v}");
    assert_eq!(v["objects"]["refraction_map"], serde_json::json!([0]));
    // A looping scene planned for many frames precomputes its cycle; the full plan builds the
    // far patch.
    let o = ocean(&["plan", &format!("{scenes}shallow_reef.toml"), "--json", "--frames", "100"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["passes"].as_array().unwrap().iter().any(|p| p["name"] == "cycle"), "{v}");
    let o = ocean(&["plan", &format!("{scenes}looking_down.toml"), "--json", "--full"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["passes"].as_array().unwrap().iter().any(|p| p["name"] == "far_patch"), "{v}");
}
