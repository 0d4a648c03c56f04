//! What every scene text must hold, whatever its bytes, shared by the coverage-guided
//! `cargo fuzz` target (`fuzz/fuzz_targets/scene.rs`, nightly) and the stable mutation
//! fuzzer that CI runs (`tests/fuzz_scenes.rs`), plus that fuzzer's mutations.
//!
//! [`check_scene_text`] parses and validates; a refused text must name a line (when it
//! names a key) and never panic; an accepted scene must plan, estimate its memory, build its
//! derived quantities and survive a round trip through TOML unchanged. Any violation panics,
//! which is what a fuzzer reports.

use crate::plan::FramePlan;
use crate::plan::OutputKind;
use crate::plan::memory::{MemoryBackend, MemoryEstimate};
use crate::scene::{Scene, SceneError, SceneSource};

/// What validation made of a text.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// Refused, with the message a user would read.
    Refused(String),
    /// Accepted (boxed: a scene is large, a refusal small).
    Accepted(Box<Scene>),
}

/// Parses, validates and checks the accepted scene's plan, memory estimate, camera, spectrum,
/// wave modes' parameters and TOML round trip. Panics on a violation.
///
/// # Panics
/// Where the text breaks the property: that is the fuzzer's finding.
pub fn check_scene_text(text: &str) -> Outcome {
    let scene = match Scene::from_toml(text, SceneSource::Text) {
        Ok(s) => s,
        Err(e) => {
            // Every refusal says where: a line, or the key of a value that is not in the text
            // (a default inconsistent with a value that is).
            if let SceneError::Invalid { key, line, .. } = &e {
                assert!(
                    *line > 0 || key.is_some(),
                    "a refusal that names neither line nor key: {e}"
                );
            }
            return Outcome::Refused(e.to_string());
        }
    };
    for output in [OutputKind::Ldr, OutputKind::Hdr] {
        let plan = FramePlan::new(&scene, output);
        let estimate = MemoryEstimate::of(&scene, &plan, MemoryBackend::Cpu).total();
        assert!(estimate > 0, "an accepted scene's memory estimate is 0");
        let _ = FramePlan::full(&scene, output);
    }
    let camera = crate::camera::Camera::from_scene(&scene.camera)
        .unwrap_or_else(|e| panic!("accepted, but the camera fails: {e}\n{text}"));
    assert!(camera.view_proj().is_finite(), "accepted, but view_proj is not finite\n{text}");
    scene
        .ocean
        .wave_spectrum()
        .unwrap_or_else(|e| panic!("accepted, but the spectrum fails: {e}\n{text}"));
    scene
        .ocean
        .ocean_params()
        .unwrap_or_else(|e| panic!("accepted, but the ocean parameters fail: {e}\n{text}"));
    let again = toml::to_string(&scene)
        .map_err(|e| e.to_string())
        .and_then(|t| Scene::from_toml(&t, SceneSource::Text).map_err(|e| format!("{e}\n{t}")))
        .unwrap_or_else(|e| panic!("accepted, but its TOML does not load again: {e}\n{text}"));
    assert!(again == scene, "the TOML round trip changed the scene\n{text}");
    Outcome::Accepted(Box::new(scene))
}

/// SplitMix64, the mutator's source of choices.
#[derive(Clone, Debug)]
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `0..n` (`n` > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    fn pick<'a>(&mut self, xs: &[&'a str]) -> &'a str {
        xs[self.below(xs.len())]
    }
}

/// Values a hostile user types: f32 and f64 edges, integer widths, NaN and infinities,
/// denormals, and the validation's own bounds (`scene::LIMITS`) nudged past them.
const INTERESTING: &[&str] = &[
    "0",
    "-0.0",
    "1",
    "-1",
    "2",
    "0.5",
    "1e-300",
    "5e-324",
    "1e-310",
    "1e300",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "3.4e38",
    "3.5e38",
    "1e39",
    "inf",
    "-inf",
    "nan",
    "2147483647",
    "2147483648",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "-9223372036854775808",
    "65536",
    "65537",
    "4096",
    "4097",
    "16384",
    "16385",
    "8192",
    "8193",
    "1e7",
    "1e9",
    "1e16",
    "3.602879701896397e16",
    "1e-4",
    "0.0001",
    "179.99",
    "180",
    "1e-7",
    "\"x\"",
    "true",
    "[]",
    "[1, 2]",
    "[1, 2, 3, 4]",
    "{}",
];

/// Keys to insert or rename to: real ones (in the wrong table too) and near misses.
const KEYS: &[&str] = &[
    "system",
    "wind_speed",
    "resolution",
    "bump_patch_divisor",
    "time_s",
    "loop_period_s",
    "position",
    "look_at",
    "fov_y_deg",
    "width",
    "height",
    "intensity",
    "color",
    "direction",
    "ior",
    "kind",
    "radius",
    "size",
    "center",
    "heading_deg",
    "mass_kg",
    "fresnel_table_size",
    "lod_split_threshold",
    "projected_grid_cell_px",
    "clipmap_cells",
    "zeta_m",
    "roughness",
    "kd_per_m",
    "slope",
    "extent_m",
    "coverage",
    "altitude_m",
    "waves",
    "shading",
    "resolutoin",
    "",
    "\"quoted key\"",
    "a.b.c",
];

/// Tables to insert.
const TABLES: &[&str] = &[
    "[ocean]",
    "[camera]",
    "[sun]",
    "[water]",
    "[terrain]",
    "[chiu]",
    "[ggx]",
    "[clouds]",
    "[quality]",
    "[techniques]",
    "[[objects]]",
    "[ocean.sub]",
    "[[camera]]",
    "[objects]",
    "[",
];

/// One mutation of `text`: a number replaced by an interesting value, a line deleted,
/// duplicated or swapped, a key inserted or renamed, a table header inserted, an object
/// block appended, bytes inserted, or the text truncated. Several may be stacked by calling
/// it again on its result.
pub fn mutate(text: &str, rng: &mut Rng) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    if lines.is_empty() {
        lines.push(String::new());
    }
    let at = rng.below(lines.len());
    match rng.below(10) {
        0..=2 => {
            // Replace the value of a `key = value` line, or one number inside an array.
            let line = &lines[at];
            if let Some((k, v)) = line.split_once('=') {
                let new = if v.trim_start().starts_with('[') && rng.below(2) == 0 {
                    let parts: Vec<&str> =
                        v.trim().trim_start_matches('[').trim_end_matches(']').split(',').collect();
                    let i = rng.below(parts.len());
                    let mut p: Vec<String> = parts.iter().map(|s| s.trim().to_owned()).collect();
                    p[i] = rng.pick(INTERESTING).to_owned();
                    format!("[{}]", p.join(", "))
                } else {
                    rng.pick(INTERESTING).to_owned()
                };
                lines[at] = format!("{}= {new}", k);
            } else {
                lines.insert(at, format!("{} = {}", rng.pick(KEYS), rng.pick(INTERESTING)));
            }
        }
        3 => {
            lines.remove(at);
        }
        4 => {
            let l = lines[at].clone();
            lines.insert(at, l);
        }
        5 => {
            let other = rng.below(lines.len());
            lines.swap(at, other);
        }
        6 => lines.insert(at, rng.pick(TABLES).to_owned()),
        7 => {
            let kind = rng.pick(&["\"sphere\"", "\"box\"", "\"boat\"", "\"cone\"", "1"]);
            lines.push(format!(
                "[[objects]]\nkind = {kind}\ncenter = [{}, {}, {}]\nradius = {}\nsize = [1, 1, 1]",
                rng.pick(INTERESTING),
                rng.pick(INTERESTING),
                rng.pick(INTERESTING),
                rng.pick(INTERESTING)
            ));
            if rng.below(2) == 0 {
                // Keep the one key the kind takes.
                let last = lines.len() - 1;
                let drop =
                    if kind.contains("sphere") { "\nsize = [1, 1, 1]" } else { "\nradius = " };
                if let Some(i) = lines[last].find(drop) {
                    let end =
                        lines[last][i + 1..].find('\n').map_or(lines[last].len(), |j| i + 1 + j);
                    lines[last].replace_range(i..end, "");
                }
            }
        }
        8 => {
            let bytes = rng.pick(&["\"", "'", "=", "\\", "#", "\u{0}", "é", "\u{FEFF}", "]", "\t"]);
            let line = &mut lines[at];
            let mut pos = rng.below(line.len() + 1);
            while !line.is_char_boundary(pos) {
                pos -= 1;
            }
            line.insert_str(pos, bytes);
        }
        _ => {
            let keep = rng.below(text.len() + 1);
            let mut cut = keep;
            while !text.is_char_boundary(cut) {
                cut -= 1;
            }
            return text[..cut].to_owned();
        }
    }
    lines.join("\n") + "\n"
}
