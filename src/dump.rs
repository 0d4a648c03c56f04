//! Per-pass dumps: `ocean render --dump-passes DIR` writes every float resource of a frame as
//! an EXR with named channels and a `manifest.json` that says what each one is;
//! `ocean compare --against DIR` holds a folder in that layout (the oracle's, or one written
//! by another engine) against the oracle, resource by resource, with docs/design.md's tolerances.
//!
//! The layout (`manifest.json`, `"layout": "ocean-dump/1"`):
//!
//! - `<resource>.exr`: one single-layer EXR per resource a pass wrote, 32-bit float, four
//!   channels named as the manifest's `channels` (EXR files list channels alphabetically;
//!   the manifest gives the texture's own order r, g, b, a). Row 0 of the image is the
//!   texture's row 0.
//! - `ldr.png`: the 8-bit sRGB picture, when the plan tonemaps.
//! - `spray_step.exr` (a GPU frame with a spray): the particle pool as the frame left it on
//!   the device and after one more step run there, a row per slot and four columns (before:
//!   position and tag, velocity and age; after: the same), channels x, y, z, w; the
//!   manifest's `spray_step` names it with the step's number and the slots.
//! - `manifest.json`: the scene (its text and path), the plan (as `ocean plan --json`), the
//!   frame's time and size, the back end and its adapter (name, vendor, device type, driver,
//!   backend: the provenance of the numbers), the conventions, and per resource: the pass and
//!   technique that wrote it, its format, size, mip levels and layout, and each channel's
//!   meaning and unit.

use std::path::Path;

use anyhow::{Context, bail};
use ocean_core::plan::{FramePlan, ResourceId};
use ocean_core::scene::Scene;
use serde_json::{Value, json};

use crate::output::{Channel, encode_exr};

/// The layout's name and version, in `manifest.json`.
pub const LAYOUT: &str = "ocean-dump/1";

/// (name, meaning, unit) of a resource's four channels, in texture order (r, g, b, a).
pub fn channels(id: ResourceId) -> [(&'static str, &'static str, &'static str); 4] {
    use ResourceId as R;
    match id {
        R::Displacement => [
            ("disp_x", "horizontal displacement along +x (the choppy waves)", "m"),
            ("height", "height of the displaced point above the sea plane", "m"),
            ("disp_z", "horizontal displacement along +z", "m"),
            ("jacobian", "Jacobian of the horizontal displacement (< 1: compressed)", "1"),
        ],
        R::DisplacementSlopes => [
            ("slope_x", "∂height/∂x of the displacement map's patch", "1"),
            ("slope_z", "∂height/∂z", "1"),
            ("zero_b", "unused, 0", "1"),
            ("zero_a", "unused, 0", "1"),
        ],
        R::Bump => [
            ("slope_x", "∂height/∂x of the bump map's patch", "1"),
            ("slope_z", "∂height/∂z", "1"),
            ("height", "height", "m"),
            ("jacobian", "Jacobian of the horizontal displacement", "1"),
        ],
        R::DisplacementSlopeMips | R::BumpMips => [
            ("mean_slope_x", "mean of ∂height/∂x over the level's texel", "1"),
            ("mean_slope_z", "mean of ∂height/∂z", "1"),
            ("mean_slope_x2", "mean of (∂height/∂x)²", "1"),
            ("mean_slope_z2", "mean of (∂height/∂z)²", "1"),
        ],
        R::FresnelFilter => [
            ("fresnel_filtered", "F̄(r, σ): eq. 2 averaged over a slope spread σ", "1"),
            ("zero_g", "unused, 0", "1"),
            ("zero_b", "unused, 0", "1"),
            ("zero_a", "unused, 0", "1"),
        ],
        R::FresnelAbove | R::FresnelBelow => [
            ("view_x", "x of the local view vector the texel stands for", "1"),
            ("view_y", "y (up) of the local view vector", "1"),
            ("view_z", "z of the local view vector", "1"),
            ("fresnel", "F of eq. 2 (η from above, 1/η from below)", "1"),
        ],
        R::ShadowMap => [
            ("depth", "depth of the nearest object from the sun, 0 at the sun's side", "1"),
            ("zero_g", "unused, 0", "1"),
            ("zero_b", "unused, 0", "1"),
            ("zero_a", "unused, 0", "1"),
        ],
        R::ReflectionMap | R::RefractionMap => [
            (
                "radiance_r",
                "radiance of the mirrored (reflection) or fogged (refraction) objects",
                "scene radiance",
            ),
            ("radiance_g", "green", "scene radiance"),
            ("radiance_b", "blue", "scene radiance"),
            ("coverage", "share of the pixel the objects cover", "1"),
        ],
        R::Hdr => [
            (
                "radiance_r",
                "linear radiance reaching the camera, before exposure",
                "scene radiance",
            ),
            ("radiance_g", "green", "scene radiance"),
            ("radiance_b", "blue", "scene radiance"),
            ("alpha", "1", "1"),
        ],
        R::BloomDown | R::BloomUp => [
            ("radiance_r", "bright pass (down) or the levels summed back (up)", "scene radiance"),
            ("radiance_g", "green", "scene radiance"),
            ("radiance_b", "blue", "scene radiance"),
            ("alpha", "unused", "1"),
        ],
        R::FoamField => [
            ("foam", "foam `accumulated`'s coverage on its lattice", "1"),
            ("zero_g", "unused, 0", "1"),
            ("zero_b", "unused, 0", "1"),
            ("zero_a", "unused, 0", "1"),
        ],
        R::Ldr | R::Environment => [("", "", ""); 4],
    }
}

/// The float resources a dump holds for `plan`: those a pass writes this frame.
pub fn dumped(plan: &FramePlan) -> Vec<ResourceId> {
    ResourceId::MAPS
        .into_iter()
        .filter(|id| id.writer().is_some_and(|p| plan.runs(p)))
        .filter(|id| plan.resource(*id).is_some_and(|r| r.written))
        .collect()
}

/// The file a resource goes to.
pub fn file_name(id: ResourceId) -> String {
    format!("{}.exr", id.name())
}

/// The conventions every resource follows.
fn conventions() -> Value {
    json!({
        "texel_origin": "texel (i, j) is column i of row j; row 0 is the image's first (top) row; \
            its centre is at uv ((i + 0.5)/W, (j + 0.5)/H)",
        "world_axes": "right-handed, metres, y up; the sea plane is y = 0",
        "wave_maps": "displacement, displacement_slopes and bump tile their patch: texel (i, j) \
            is the point x = i·L/N, z = j·L/N (L the patch side, N the map side)",
        "screen_maps": "reflection_map, refraction_map and hdr are views of the scene's camera \
            (the reflection map mirrored in the sea plane), x to the right, row 0 at the top",
        "mip_chains": "a chain of n levels is one atlas W wide: level 0 in rows 0..H, level k in \
            the next H >> k rows from column 0 (at least 1), the rest of each row 0",
        "radiance": "linear, scene units (the sun's radiance is [sun] intensity × color); \
            the picture applies the camera's exposure and the tonemap",
        "fresnel_tables": "the plan's fresnel_mapping (see `ocean fresnel --table`)",
    })
}

/// A frame's maps, from either back end: (width, height) and the texels, row-major.
pub type MapOf<'a> = dyn Fn(ResourceId) -> Option<((u32, u32), &'a [[f32; 4]])> + 'a;

/// Writes the dump of a frame to `dir` (created if missing): every resource of [`dumped`],
/// `ldr.png` when there is a picture, the spray's probed step when given, and the manifest.
/// Returns the files written.
///
/// # Errors
/// A folder or file that cannot be written, or a map the back end did not keep.
#[expect(clippy::too_many_arguments, reason = "a dump's parts, each from its back end")]
pub fn write(
    dir: &Path,
    scene: &Scene,
    scene_source: (&str, &str),
    plan: &FramePlan,
    adapter: Option<&ocean_gpu::AdapterReport>,
    map: &MapOf<'_>,
    ldr: Option<&[u8]>,
    spray: Option<&crate::verdict::spray::SprayProbe>,
) -> anyhow::Result<Vec<String>> {
    let backend = if adapter.is_some() { "gpu" } else { "cpu" };
    let adapter = match adapter {
        Some(a) => json!({
            "name": a.name,
            "vendor": a.vendor,
            "device_type": a.device_type,
            "driver": a.driver,
            "backend": a.backend,
            "software": a.is_software,
        }),
        None => json!({
            "name": "ocean CPU oracle",
            "vendor": null,
            "device_type": "Cpu",
            "driver": format!("ocean {}", env!("CARGO_PKG_VERSION")),
            "backend": "cpu",
            "software": true,
        }),
    };
    // Written whole or not at all: into a temporary folder beside `dir`, renamed into place
    // once the manifest is written (a full disk half-way left a partial dump without one).
    let staging = crate::output::StagingDir::create(dir)?;
    let dir = staging.path();
    let mut files = Vec::new();
    let mut resources = Vec::new();
    for id in dumped(plan) {
        let Some(((w, h), texels)) = map(id) else {
            bail!("the {backend} back end kept no `{}` for the dump", id.name())
        };
        let names = channels(id);
        let data: Vec<Channel<'_>> = (0..4)
            .map(|c| Channel { name: names[c].0, data: texels.iter().map(|t| t[c]).collect() })
            .collect();
        let name = file_name(id);
        let bytes = encode_exr(w as usize, h as usize, data)?;
        crate::output::write_atomic(&dir.join(&name), &bytes)?;
        let r = plan.resource(id);
        let writer = id.writer();
        resources.push(json!({
            "name": id.name(),
            "file": name,
            "pass": writer.map(|p| p.name()),
            "technique": writer.and_then(|p| p.stage()).map(|s| plan.techniques.of(s).name),
            "format": r.map(|r| format!("{:?}", r.format.storage())),
            "size": [w, h],
            "plan_size": r.map(|r| r.size),
            "mip_levels": r.map_or(1, |r| r.levels),
            "channels": names.iter().map(|(n, m, u)| json!({"name": n, "meaning": m, "unit": u})).collect::<Vec<_>>(),
        }));
        files.push(name);
    }
    if let Some(rgba) = ldr {
        let png =
            crate::output::encode_png(rgba.to_vec(), scene.camera.width, scene.camera.height)?;
        crate::output::write_atomic(&dir.join("ldr.png"), &png)?;
        files.push("ldr.png".to_owned());
    }
    let spray_step = match spray {
        Some(step) => {
            files.push(SPRAY_STEP_FILE.to_owned());
            write_spray_step(dir, step)?
        }
        None => Value::Null,
    };
    let manifest = json!({
        "layout": LAYOUT,
        "backend": backend,
        "adapter": adapter,
        "scene": {"path": scene_source.0, "toml": scene_source.1},
        "frame": {
            "system": plan.system.name(),
            "time_s": scene.ocean.time_s,
            "width": scene.camera.width,
            "height": scene.camera.height,
        },
        "conventions": conventions(),
        "plan": serde_json::to_value(plan)?,
        "resources": resources,
        "spray_step": spray_step,
    });
    crate::output::write_atomic(
        &dir.join("manifest.json"),
        serde_json::to_string_pretty(&manifest)?.as_bytes(),
    )?;
    files.push("manifest.json".to_owned());
    staging.publish(|old| {
        ocean_core::input::read_text(&old.join("manifest.json"), MAX_MANIFEST_BYTES)
            .is_ok_and(|t| t.contains(LAYOUT))
    })?;
    Ok(files)
}

/// The largest `manifest.json` read, bytes: a manifest holds the scene's text (at most
/// [`ocean_core::scene::MAX_SCENE_FILE_BYTES`]) and the plan (tens of KB).
pub const MAX_MANIFEST_BYTES: u64 = ocean_core::scene::MAX_SCENE_FILE_BYTES + (1 << 20);

/// What `compare --against` takes from a dump's `manifest.json`, every number checked.
#[derive(Debug, Default)]
pub struct Manifest {
    /// The dumped scene's TOML text, when the dump holds one that is not empty.
    pub scene_toml: Option<String>,
    /// The system the frame was rendered with.
    pub system: Option<String>,
    /// The frame's size, pixels.
    pub size: Option<(u32, u32)>,
    /// The frame's time, s.
    pub time_s: Option<f64>,
    /// The names of the resources the dump lists (`None`: the manifest lists none, and every
    /// resource of the plan is looked for).
    pub resources: Option<Vec<String>>,
    /// Who made the dump (`adapter`: name, vendor, device type, driver, backend), as written.
    pub adapter: Option<Value>,
    /// The spray step the dump holds ([`SPRAY_STEP_FILE`]): the step's number and the pool's
    /// slots.
    pub spray_step: Option<(u64, u64)>,
}

impl Manifest {
    /// The dumped frame's scene as `compare --against` renders it: `scene` when given (under
    /// `system`), else the manifest's text, else the built-in scene, both under `system` or
    /// else the manifest's system; at the manifest's size and time (also for the built-in
    /// scene, whose text a dump leaves empty). `what` names the manifest in errors.
    ///
    /// # Errors
    /// The scene cannot be read or parsed, or the system is unknown.
    pub fn scene(
        &self,
        what: &str,
        scene: Option<&std::path::PathBuf>,
        system: &crate::scene_arg::SystemArg,
    ) -> anyhow::Result<ocean_core::scene::Scene> {
        // The system the dump was made with, unless one is given.
        let dumped =
            crate::scene_arg::SystemArg { system: system.system.clone().or(self.system.clone()) };
        let mut s = match (scene, self.scene_toml.as_deref()) {
            (Some(path), _) => crate::scene_arg::load_scene(Some(path), system)?,
            (None, Some(text)) => crate::scene_arg::scene_from_text(text, what, &dumped)?,
            (None, None) => crate::scene_arg::load_scene(None, &dumped)?,
        };
        if let Some((w, h)) = self.size {
            (s.camera.width, s.camera.height) = (w, h);
        }
        if let Some(t) = self.time_s {
            s.ocean.time_s = t;
        }
        Ok(s)
    }
}

/// Reads `DIR/manifest.json`: `Ok(None)` when there is none.
///
/// # Errors
/// A manifest that is not a regular file (a folder, a device, a link to `/dev/zero`), larger
/// than [`MAX_MANIFEST_BYTES`], not UTF-8, not JSON, or with a frame size, time or text of the
/// wrong type or out of range; each message names the file and the key.
pub fn read_manifest(dir: &Path) -> anyhow::Result<Option<Manifest>> {
    let path = dir.join("manifest.json");
    if std::fs::symlink_metadata(&path).is_err() {
        return Ok(None);
    }
    let text = ocean_core::input::read_text(&path, MAX_MANIFEST_BYTES)
        .map_err(|e| anyhow::anyhow!("the dump's manifest {e}"))?;
    let v: Value =
        serde_json::from_str(&text).with_context(|| format!("{} is not JSON", path.display()))?;
    let key = |k: &str| format!("{}: `{k}`", path.display());
    let string = |v: &Value, k: &str| -> anyhow::Result<Option<String>> {
        match v {
            Value::Null => Ok(None),
            Value::String(s) => Ok(Some(s.clone())),
            other => bail!("{} must be a string, got {other}", key(k)),
        }
    };
    let frame = &v["frame"];
    let side = |k: &str| -> anyhow::Result<Option<u32>> {
        let max = ocean_core::scene::MAX_IMAGE_SIDE;
        match &frame[k] {
            Value::Null => Ok(None),
            n => match n.as_u64().and_then(|n| u32::try_from(n).ok()) {
                Some(n) if (1..=max).contains(&n) => Ok(Some(n)),
                _ => bail!(
                    "{} must be a whole number of pixels, 1..={max}, got {n}",
                    key(&format!("frame.{k}"))
                ),
            },
        }
    };
    let size = match (side("width")?, side("height")?) {
        (Some(w), Some(h)) => Some((w, h)),
        (None, None) => None,
        _ => bail!("{} must give both frame.width and frame.height, or neither", path.display()),
    };
    let time_s = match &frame["time_s"] {
        Value::Null => None,
        t => match t.as_f64() {
            Some(t) if t.is_finite() => Some(t),
            _ => bail!("{} must be a finite number of seconds, got {t}", key("frame.time_s")),
        },
    };
    let resources = match &v["resources"] {
        Value::Null => None,
        Value::Array(list) => Some(
            list.iter()
                .map(|r| match &r["name"] {
                    Value::String(n) => Ok(n.clone()),
                    other => {
                        bail!("{}: every resource needs a `name`, got {other}", key("resources"))
                    }
                })
                .collect::<anyhow::Result<Vec<_>>>()?,
        ),
        other => bail!("{} must be a list, got {other}", key("resources")),
    };
    let adapter = match &v["adapter"] {
        Value::Null => None,
        a @ Value::Object(_) => Some(a.clone()),
        other => bail!("{} must be an object, got {other}", key("adapter")),
    };
    let spray_step = match &v["spray_step"] {
        Value::Null => None,
        e => {
            let whole = |k: &str| e[k].as_u64();
            match (whole("step"), whole("slots"), e["file"].as_str()) {
                (Some(step), Some(slots), Some(SPRAY_STEP_FILE)) if slots > 0 => {
                    Some((step, slots))
                }
                _ => bail!(
                    "{} must give `file` \"{SPRAY_STEP_FILE}\", a whole `step` and a whole, \
                     positive number of `slots`, got {e}",
                    key("spray_step")
                ),
            }
        }
    };
    Ok(Some(Manifest {
        spray_step,
        scene_toml: string(&v["scene"]["toml"], "scene.toml")?.filter(|t| !t.is_empty()),
        system: string(&frame["system"], "frame.system")?,
        size,
        time_s,
        resources,
        adapter,
    }))
}

/// A resource read from a dump: (width, height) and its texels, row-major.
pub type ReadMap = ((u32, u32), Vec<[f32; 4]>);

/// Reads a dumped resource: (width, height) and its texels, channels in texture order (by
/// the names [`channels`] gives; an EXR from elsewhere with R, G, B, A is read as those).
///
/// # Errors
/// A missing or unreadable file, or one without the four channels.
pub fn read(dir: &Path, id: ResourceId) -> anyhow::Result<ReadMap> {
    read_file(&dir.join(file_name(id)), channels(id).map(|c| c.0))
}

/// Reads an EXR of this layout: (width, height) and its texels, channel c from the channel
/// named `names[c]` (or R, G, B, A).
fn read_file(path: &Path, names: [&str; 4]) -> anyhow::Result<ReadMap> {
    use exr::prelude::*;
    // The header first: a forged size is refused before a texel is decoded (4 channels of
    // f32 as [f32; 4] texels, plus the samples as stored). A mip chain's atlas is up to twice
    // as tall as its level 0.
    let (size, stored) = ocean_core::input::exr_header(path).map_err(anyhow::Error::msg)?;
    let max_side = 2 * u64::from(ocean_core::scene::MAX_IMAGE_SIDE);
    ocean_core::input::check_image_size(path, size, max_side, stored + 16)
        .map_err(anyhow::Error::msg)?;
    let image = read_all_flat_layers_from_file(path)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let Some(layer) = image.layer_data.first() else { bail!("{} holds no layer", path.display()) };
    let (w, h) = (layer.size.width(), layer.size.height());
    let rgba = ["R", "G", "B", "A"];
    let mut texels = vec![[0.0f32; 4]; w * h];
    for c in 0..4 {
        let found = layer.channel_data.list.iter().find(|ch| {
            let n = ch.name.to_string();
            n == names[c] || n == rgba[c]
        });
        let Some(ch) = found else {
            bail!("{} has no channel `{}` (or `{}`)", path.display(), names[c], rgba[c])
        };
        for (t, v) in texels.iter_mut().zip(ch.sample_data.values_as_f32()) {
            t[c] = v;
        }
    }
    Ok(((w as u32, h as u32), texels))
}

/// The spray step's file in a dump: four columns, a row per slot.
pub const SPRAY_STEP_FILE: &str = "spray_step.exr";

/// The columns of [`SPRAY_STEP_FILE`].
const SPRAY_STEP_COLUMNS: [&str; 4] = [
    "before: position (x, y, z relative to the spray's origin, m), active (1) or free (0)",
    "before: velocity (m/s), age (s)",
    "after: position, active",
    "after: velocity, age",
];

/// The spray step as a dump holds it (`ocean compare`'s probe: the pool as the frame left it
/// on the device, and after one more step there), with that step's uniforms for `scene`
/// under `plan`: `None` where the dump has none.
///
/// # Errors
/// A file that is not four columns of the manifest's `slots` rows, or uniforms the scene
/// cannot make.
pub fn read_spray_step(
    dir: &Path,
    manifest: &Manifest,
    scene: &Scene,
    plan: &FramePlan,
) -> anyhow::Result<Option<crate::verdict::spray::SprayProbe>> {
    let Some((step, slots)) = manifest.spray_step else { return Ok(None) };
    let ((w, h), texels) = read_file(&dir.join(SPRAY_STEP_FILE), ["x", "y", "z", "w"])?;
    if (w, u64::from(h)) != (4, slots) {
        bail!("{}: {w}x{h}, the manifest's 4x{slots}", dir.join(SPRAY_STEP_FILE).display());
    }
    let column = |c: usize| -> Vec<ocean_core::spray::Particle> {
        texels
            .chunks_exact(4)
            .map(|row| ocean_core::spray::Particle { pos: row[c], vel: row[c + 1] })
            .collect()
    };
    let params = crate::verdict::spray::step_uniforms(scene, plan, step)?;
    Ok(Some(crate::verdict::spray::SprayProbe { before: column(0), after: column(2), params }))
}

/// The spray step's file and manifest entry: four columns ([`SPRAY_STEP_COLUMNS`]), a row
/// per slot.
fn write_spray_step(dir: &Path, step: &crate::verdict::spray::SprayProbe) -> anyhow::Result<Value> {
    let rows: Vec<[[f32; 4]; 4]> =
        step.before.iter().zip(&step.after).map(|(b, a)| [b.pos, b.vel, a.pos, a.vel]).collect();
    let data: Vec<Channel<'_>> = ["x", "y", "z", "w"]
        .into_iter()
        .enumerate()
        .map(|(c, name)| Channel {
            name,
            data: rows.iter().flat_map(|r| r.iter().map(move |t| t[c])).collect(),
        })
        .collect();
    let bytes = encode_exr(4, rows.len(), data)?;
    crate::output::write_atomic(&dir.join(SPRAY_STEP_FILE), &bytes)?;
    Ok(json!({
        "file": SPRAY_STEP_FILE,
        "pass": "spray",
        "step": step.params.step,
        "slots": rows.len(),
        "columns": SPRAY_STEP_COLUMNS,
        "meaning": "the pool as the frame left it on the device, and after one more step run there; \
                    `ocean compare --against` holds the step to its envelope",
    }))
}
