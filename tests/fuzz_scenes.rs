//! The bounded mutation fuzzer CI runs (issue 11): scene texts mutated from the reference
//! scenes (`ocean_core::fuzz::mutate`: interesting numbers, deleted, duplicated and swapped
//! lines, keys, tables, objects, stray bytes, truncation; up to four stacked) through
//! `ocean_core::fuzz::check_scene_text` (parse, validate, plan, memory estimate, derived
//! quantities, TOML round trip), with any panic a failure that prints the input. One accepted
//! scene in twenty is also rendered at 8×4 on the CPU and must give finite pixels (the
//! grid-cost keys bounded, so that the run stays short).
//!
//! `OCEAN_FUZZ_CASES` sets the number of cases (default 20000, about 30 s here); the
//! coverage-guided run of the same property is `fuzz/` (`cargo +nightly fuzz run scene`).

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use std::panic::{AssertUnwindSafe, catch_unwind};

use ocean_core::fuzz::{Outcome, Rng, check_scene_text, mutate};
use ocean_core::plan::OutputKind;

fn seeds() -> Vec<String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("reference/scenes");
    let mut seeds: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| std::fs::read_to_string(e.unwrap().path()).unwrap())
        .collect();
    seeds.sort();
    assert!(seeds.len() >= 8, "the reference scenes are the fuzzer's seeds");
    seeds
}

/// Renders an accepted scene at 8×4 when its grids are small; panics on a non-finite pixel.
fn render_small(scene: &ocean_core::scene::Scene) -> bool {
    let o = &scene.ocean;
    let q = &scene.quality;
    if o.resolution > 256
        || o.bump_resolution > 256
        || q.fresnel_table_size > 256
        || q.lod_split_threshold < 0.01
        || scene.objects.len() > 8
    {
        return false;
    }
    let mut s = scene.clone();
    (s.camera.width, s.camera.height) = (8, 4);
    let r = ocean_cpu::render_scene(&s, OutputKind::Hdr, &mut |_| {})
        .unwrap_or_else(|e| panic!("an accepted scene failed to render: {e}"));
    let bad = r.buffers.hdr.color.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
    assert_eq!(bad, 0, "{bad} non-finite pixels");
    true
}

/// Runs `cases` mutated texts through `check`; panics (with the input) on the first panic.
/// Returns (accepted, rendered, refused).
fn fuzz(cases: usize, check: &dyn Fn(&str) -> Outcome) -> (usize, usize, usize) {
    let seeds = seeds();
    let mut rng = Rng(0x0CEA_2026);
    let (mut accepted, mut rendered, mut refused) = (0usize, 0usize, 0usize);
    for case in 0..cases {
        let mut text = seeds[rng.below(seeds.len())].clone();
        for _ in 0..=rng.below(4) {
            text = mutate(&text, &mut rng);
        }
        let render = case % 20 == 0;
        let result = catch_unwind(AssertUnwindSafe(|| match check(&text) {
            Outcome::Accepted(s) => (true, render && render_small(&s)),
            Outcome::Refused(_) => (false, false),
        }));
        match result {
            Ok((true, r)) => {
                accepted += 1;
                rendered += usize::from(r);
            }
            Ok((false, _)) => refused += 1,
            Err(_) => panic!("case {case} panicked on this scene text:\n{text}"),
        }
    }
    (accepted, rendered, refused)
}

#[test]
fn mutated_scenes_never_panic_and_accepted_ones_render_finite_pixels() {
    let cases: usize =
        std::env::var("OCEAN_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(20_000);
    let start = std::time::Instant::now();
    let (accepted, rendered, refused) = fuzz(cases, &check_scene_text);
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "fuzz: {cases} cases in {secs:.1} s ({:.0}/s): {accepted} accepted ({rendered} rendered \
         at 8×4, all finite), {refused} refused, 0 panics",
        cases as f64 / secs
    );
    // The mutations must reach both sides of validation, or the run tests little.
    assert!(accepted > cases / 20 && refused > cases / 4, "{accepted} accepted, {refused} refused");
}

#[test]
fn the_fuzzer_reports_a_panicking_input() {
    // Negative control: a check that panics on one kind of mutation (an `inf` anywhere stands for any
    // defect) makes the run fail with the input.
    let planted = |text: &str| {
        assert!(!text.contains("inf"), "planted defect");
        check_scene_text(text)
    };
    let run = std::panic::catch_unwind(|| fuzz(2_000, &planted));
    let message = run.unwrap_err();
    let message = message.downcast_ref::<String>().cloned().unwrap_or_default();
    assert!(message.contains("panicked on this scene text"), "{message}");
    assert!(matches!(check_scene_text("[ocean]\nresolution = 0\n"), Outcome::Refused(_)));
    assert!(matches!(check_scene_text(""), Outcome::Accepted(_)));
}
