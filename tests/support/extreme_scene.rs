//! Scenes at the edges of what validation accepts, drawn from the validation's own table
//! (`ocean_core::scene::LIMITS`), for the invariant "validation accepts ⇒ finite pixels"
//! (`tests/scene_properties.rs` on the CPU, `tests/gpu_frame_graph.rs` on the GPU).
//!
//! The generator writes scene *text*, so every scene goes through `Scene::from_toml` as a
//! user's does; what it checks (finiteness) does not come from the code under test.

#![allow(dead_code, reason = "each test binary uses part of the generator")]

use ocean_core::scene::{LIMITS, Limit, Scene, SceneSource};

pub use ocean_core::fuzz::Rng;

/// Keys whose value is a 3-vector (each component has the key's limit).
pub const VECTOR_KEYS: &[&str] = &[
    "camera.position",
    "camera.look_at",
    "sun.direction",
    "sun.color",
    "water.color",
    "terrain.color",
    "coastal.dull_color",
    "spray.color",
    "foam.color",
    "objects.*.center",
    "objects.*.size",
    "objects.*.color",
];

/// The reef's heightmap, the floor of scenes that set `terrain.height_range_m`.
pub const REEF: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/reference/terrain/reef.png");

/// Keys whose value is a list (one element is drawn).
pub const LIST_KEYS: &[&str] = &["chiu.scales"];

/// Keys whose value is a 2-vector, (x, z).
pub const VECTOR2_KEYS: &[&str] =
    &["terrain.center", "terrain.height_range_m", "clouds.wind", "coastal.center"];

/// Keys that set the cost of a frame (grid sizes, table size, image size, mesh density): the
/// random scenes keep them small, and [`cost_extremes`] takes each to its limit once.
pub const COST_KEYS: &[&str] = &[
    "ocean.resolution",
    "ocean.bump_resolution",
    "camera.width",
    "camera.height",
    "quality.fresnel_table_size",
    "quality.lod_split_threshold",
    "spray.particles",
    "spray.warmup_steps",
    "foam.warmup_steps",
    "foam.grid",
];

/// How to draw a value in a limit's range.
#[derive(Clone, Copy, Debug)]
pub enum Draw {
    /// The smallest accepted value.
    Min,
    /// The largest accepted value (the largest finite one where the limit is ∞, and ∞ too).
    Max,
    /// Anywhere in the range: log-uniform in magnitude across the range's decades, either
    /// sign where both are allowed, and at a bound one time in five.
    Random,
}

/// A value of `limit` drawn by `how`.
pub fn draw(limit: &Limit, how: Draw, rng: &mut Rng) -> f64 {
    let v = match how {
        Draw::Min => limit.min,
        Draw::Max => {
            if limit.max.is_infinite() && rng.next_u64().is_multiple_of(2) {
                f64::MAX
            } else {
                limit.max
            }
        }
        Draw::Random => {
            if rng.next_u64().is_multiple_of(5) {
                return draw(
                    limit,
                    if rng.next_u64().is_multiple_of(2) { Draw::Min } else { Draw::Max },
                    rng,
                );
            }
            let hi = limit.max.min(f64::MAX);
            let lo = limit.min.max(-f64::MAX);
            // A magnitude from 1e-6 of the range's larger end up to it, log-uniform.
            let top = hi.abs().max(lo.abs()).max(1e-300);
            let m = top * 10f64.powf(-12.0 * rng.unit());
            let v = if lo < 0.0 && rng.next_u64().is_multiple_of(2) { -m } else { m };
            v.clamp(lo, hi)
        }
    };
    if limit.whole { v.round() } else { v }
}

/// The TOML literal of `v` for `limit`.
pub fn literal(limit: &Limit, v: f64) -> String {
    if limit.whole {
        format!("{}", v as u64)
    } else if v.is_infinite() {
        if v > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        // `{:?}` round-trips an f64 and is valid TOML (`1e300`, `0.5`, `-3.0`).
        format!("{v:?}")
    }
}

/// Scene text with `values` (key → TOML literal) set and everything else defaulted. Object
/// keys (`objects.*.field`) go to every object in `objects` (kinds), each getting the field
/// its kind takes.
pub fn scene_text(values: &[(&str, String)], objects: &[&str]) -> String {
    let mut tables: Vec<(&str, Vec<String>)> = Vec::new();
    let mut object_lines = Vec::new();
    let mut wave_lines = Vec::new();
    let mut correction_lines = Vec::new();
    for (key, value) in values {
        if let Some(field) = key.strip_prefix("coastal.corrections.*.") {
            correction_lines.push(format!("{field} = {value}"));
            continue;
        }
        if let Some(field) = key.strip_prefix("objects.*.") {
            object_lines.push((field, value.clone()));
            continue;
        }
        if let Some(field) = key.strip_prefix("gerstner.waves.*.") {
            wave_lines.push(format!("{field} = {value}"));
            continue;
        }
        let (table, field) = key.split_once('.').unwrap_or(("", key));
        let line = format!("{field} = {value}");
        match tables.iter_mut().find(|(t, _)| *t == table) {
            Some((_, lines)) => lines.push(line),
            None => tables.push((table, vec![line])),
        }
    }
    let mut text = String::new();
    let mut techniques = Vec::new();
    // The bloom keys act only under post technique `bloom`: scenes that set one run it.
    if tables.iter().any(|(t, lines)| *t == "post" && lines.iter().any(|l| l.starts_with("bloom_")))
    {
        techniques.push("post = \"bloom\"");
    }
    // The foam keys act under a foam technique: the crest keys under `heuristic`, the
    // others under `accumulated` (which reads every key but the crests').
    if let Some((_, lines)) = tables.iter().find(|(t, _)| *t == "foam") {
        if lines.iter().all(|l| l.starts_with("crest_")) {
            techniques.push("foam = \"heuristic\"");
        } else {
            techniques.push("foam = \"accumulated\"");
        }
    }
    // The coastal keys act under waves `coastal` (and shading `coastal` for its own).
    if !correction_lines.is_empty() || tables.iter().any(|(t, _)| *t == "coastal") {
        techniques.push("waves = \"coastal\"\nshading = \"coastal\"");
    }
    if !techniques.is_empty() {
        text += &format!("[techniques]\n{}\n", techniques.join("\n"));
    }
    for (table, mut lines) in tables {
        // A relief's range only acts on a heightmap floor: give it the reef's.
        if table == "terrain" && lines.iter().any(|l| l.starts_with("height_range_m")) {
            lines.push("kind = \"heightmap\"".to_owned());
            lines.push(format!("heightmap = {REEF:?}"));
        }
        text += &format!("[{table}]\n{}\n", lines.join("\n"));
    }
    if !wave_lines.is_empty() {
        // One explicit wave with the drawn fields; the two it needs default here.
        for (field, default) in [("amplitude_m", "0.5"), ("wavelength_m", "20.0")] {
            if !wave_lines.iter().any(|l| l.starts_with(field)) {
                wave_lines.push(format!("{field} = {default}"));
            }
        }
        text += &format!("[[gerstner.waves]]\n{}\n", wave_lines.join("\n"));
    }
    if !correction_lines.is_empty() {
        // One correction wave with the drawn fields; the others it needs default here.
        for (field, default) in
            [("direction_deg", "30.0"), ("wavelength_m", "5.0"), ("amplitude_m", "0.05")]
        {
            if !correction_lines.iter().any(|l| l.starts_with(field)) {
                correction_lines.push(format!("{field} = {default}"));
            }
        }
        text += &format!("[[coastal.corrections]]\n{}\n", correction_lines.join("\n"));
    }
    for kind in objects {
        text += &format!("[[objects]]\nkind = \"{kind}\"\n");
        let mut has_center = false;
        for (field, value) in &object_lines {
            // Each kind gets the keys it takes: a sphere its radius, a box its size, a boat its
            // size, heading and mass.
            let takes = match *field {
                "radius" => *kind == "sphere",
                "size" => *kind != "sphere",
                "heading_deg" | "mass_kg" => *kind == "boat",
                _ => true,
            };
            if takes {
                text += &format!("{field} = {value}\n");
                has_center |= *field == "center";
            }
        }
        if !has_center {
            text += "center = [0.0, 2.0, -20.0]\n";
        }
        if !object_lines
            .iter()
            .any(|(f, _)| *f == if *kind == "sphere" { "radius" } else { "size" })
        {
            text += if *kind == "sphere" { "radius = 2.0\n" } else { "size = [2.0, 2.0, 2.0]\n" };
        }
    }
    text
}

/// The literal of `key` drawn by `how` (three or two components for a vector key).
pub fn drawn(limit: &Limit, how: Draw, rng: &mut Rng) -> String {
    let n = if VECTOR_KEYS.contains(&limit.key) {
        3
    } else if VECTOR2_KEYS.contains(&limit.key) {
        2
    } else {
        1
    };
    if n > 1 || LIST_KEYS.contains(&limit.key) {
        let c: Vec<String> = (0..n).map(|_| literal(limit, draw(limit, how, rng))).collect();
        format!("[{}]", c.join(", "))
    } else {
        literal(limit, draw(limit, how, rng))
    }
}

/// Parses scene text; `None` where validation refuses it (a cross-key check).
pub fn parse(text: &str) -> Option<Scene> {
    Scene::from_toml(text, SceneSource::Text).ok()
}

/// One scene per (key, bound) of every non-cost key: that key at its min or max, everything
/// else at its default, with a sun and a sphere and a box, at 16×9; a boat too where the key
/// is an object's or the FFT sea's, the default (what a boat's settle run reads; a boat on
/// the default 256² sea costs ~1 s, too much for every scene). Some are refused by a cross-key check (the
/// camera's target at its own position, say); those come back `None`.
pub fn per_key_extremes() -> Vec<(String, String)> {
    let mut rng = Rng(7);
    let mut out = Vec::new();
    for limit in LIMITS.iter().filter(|l| !COST_KEYS.contains(&l.key)) {
        for how in [Draw::Min, Draw::Max] {
            let mut values =
                vec![("camera.width", "16".to_owned()), ("camera.height", "9".to_owned())];
            values.push((limit.key, drawn(limit, how, &mut rng)));
            if !values.iter().any(|(k, _)| k.starts_with("sun.")) {
                values.push(("sun.intensity", "5.0".to_owned()));
            }
            let kinds: &[&str] = if ["objects.", "ocean."].iter().any(|p| limit.key.starts_with(p))
            {
                &["sphere", "box", "boat"]
            } else {
                &["sphere", "box"]
            };
            out.push((format!("{} = {how:?}", limit.key), scene_text(&values, kinds)));
        }
    }
    out
}

/// A scene with every key drawn at random ([`Draw::Random`]), cost keys small, 0–3 objects.
pub fn random_extreme(rng: &mut Rng) -> String {
    let mut values = Vec::new();
    for limit in LIMITS {
        if COST_KEYS.contains(&limit.key) {
            continue;
        }
        if limit.key == "ocean.time_s" && rng.next_u64().is_multiple_of(2) {
            // Half the time within the phase's range without a loop; else any finite time.
            values.push((limit.key, literal(limit, (rng.unit() - 0.5) * 7.0e16)));
            continue;
        }
        values.push((limit.key, drawn(limit, Draw::Random, rng)));
    }
    // A lifetime range is drawn as two ends in order (validation refuses them swapped).
    let life = |k: &str| values.iter().position(|(key, _)| *key == k);
    if let (Some(a), Some(b)) = (life("gerstner.min_lifetime_s"), life("gerstner.max_lifetime_s")) {
        let num = |i: usize| values[i].1.parse::<f64>().unwrap_or(0.0);
        if num(a) > num(b) {
            let (lo, hi) = (values[b].1.clone(), values[a].1.clone());
            (values[a].1, values[b].1) = (lo, hi);
        }
    }
    let small =
        |rng: &mut Rng, xs: &[u32]| xs[(rng.next_u64() % xs.len() as u64) as usize].to_string();
    values.push(("ocean.resolution", small(rng, &[2, 3, 16, 64])));
    values.push(("ocean.bump_resolution", small(rng, &[16, 33, 64])));
    values.push(("camera.width", small(rng, &[1, 16, 17])));
    values.push(("camera.height", small(rng, &[1, 9, 10])));
    values.push(("quality.fresnel_table_size", small(rng, &[2, 17, 64])));
    values.push(("foam.warmup_steps", small(rng, &[0, 1, 7])));
    values.push(("foam.grid", small(rng, &[2, 16, 64])));
    values.push((
        "quality.lod_split_threshold",
        ["0.05", "0.5", "10.0"][(rng.next_u64() % 3) as usize].into(),
    ));
    let kinds: &[&str] =
        [&[][..], &["sphere"], &["box"], &["sphere", "box", "sphere"], &["boat", "sphere"]]
            [(rng.next_u64() % 5) as usize];
    scene_text(&values, kinds)
}

/// Each cost key at its limits once, the rest default (the slow cases).
pub fn cost_extremes() -> Vec<(String, String)> {
    let mut rng = Rng(11);
    let mut out = Vec::new();
    for limit in LIMITS.iter().filter(|l| COST_KEYS.contains(&l.key)) {
        for how in [Draw::Min, Draw::Max] {
            let mut values = vec![(limit.key, drawn(limit, how, &mut rng))];
            if limit.key == "ocean.resolution" && matches!(how, Draw::Max) {
                // The bump map must hold finer waves than a 4096² displacement map.
                values.push(("ocean.bump_resolution", "4096".to_owned()));
            }
            for (k, v) in [("camera.width", "16"), ("camera.height", "9")] {
                if limit.key != k {
                    values.push((k, v.to_owned()));
                }
            }
            out.push((format!("{} = {how:?}", limit.key), scene_text(&values, &["sphere"])));
        }
    }
    out
}
