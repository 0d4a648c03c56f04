//! The CPU ↔ GPU cross-check (issue 4): the same scene and plan through ocean-cpu (the
//! oracle) and ocean-gpu, compared map by map and picture by picture with the comparators of
//! [`crate::compare`], every map held to the plan's size. Used by `tests/gpu_cross_check.rs`,
//! `tests/gpu_frame_graph.rs` and `ocean compare`.

use std::path::Path;

use ocean_core::plan::{FramePlan, OutputKind, Pass, ResourceId};
use ocean_core::scene::Scene;
use ocean_cpu::frame::FrameBuffers;
use ocean_gpu::{AdapterReport, FloatMap, FrameMap, GpuFrame, Renderer};
use serde_json::{Value, json};

use crate::compare::{
    FloatStats, ImageLimits, ImageStats, allowance_in, compare_float, compare_float_in,
    compare_image,
};

/// A CPU map by its resource id: (size, texels); `ldr` (not a float map) is empty.
pub fn cpu_map(b: &FrameBuffers, which: FrameMap) -> ((u32, u32), &[[f32; 4]]) {
    b.map(which).map_or(((0, 0), &[][..]), |(w, h, t)| ((w, h), t))
}

fn gpu_map(m: &FloatMap) -> ((u32, u32), &[[f32; 4]]) {
    ((m.width, m.height), &m.texels)
}

/// Both renders of a scene.
pub struct Renders {
    /// The CPU oracle's frame.
    pub cpu: ocean_cpu::Rendered,
    /// The GPU's frame.
    pub gpu: GpuFrame,
}

/// The cross-check of one scene.
#[derive(Clone, Debug)]
pub struct SceneCheck {
    /// The scene's name.
    pub scene: String,
    /// Image size.
    pub size: (u32, u32),
    /// The adapter that rendered the GPU side.
    pub adapter: AdapterReport,
    /// The wave-map source of the GPU side.
    pub wave_source: Option<&'static str>,
    /// Every float buffer, in the frame's order.
    pub maps: Vec<FloatStats>,
    /// The 8-bit pictures, when the plan tonemaps.
    pub image: Option<ImageStats>,
    /// Whether the plan tonemaps (then a missing picture is a failure).
    pub tonemapped: bool,
    /// The limits the picture is held to.
    pub image_limits: ImageLimits,
}

impl SceneCheck {
    /// Everything beyond the limits, one line each; empty when the scene passes.
    pub fn failures(&self) -> Vec<String> {
        let mut f: Vec<String> = self
            .maps
            .iter()
            .filter(|m| !m.passed())
            .map(|m| format!("{}: {}", self.scene, m.line()))
            .collect();
        match &self.image {
            Some(i) => f.extend(
                i.failures(&self.image_limits)
                    .into_iter()
                    .map(|e| format!("{}: ldr: {e}", self.scene)),
            ),
            None if self.tonemapped => {
                f.push(format!("{}: no 8-bit picture to compare", self.scene))
            }
            // An EXR plan has no 8-bit picture: its HDR frame is compared as a float map.
            None => {}
        }
        f
    }

    /// The per-buffer summary lines.
    pub fn lines(&self) -> Vec<String> {
        let mut l: Vec<String> = self.maps.iter().map(FloatStats::line).collect();
        if let Some(i) = &self.image {
            l.push(i.line(&self.image_limits));
        }
        l
    }

    /// The summary as JSON.
    pub fn to_json(&self) -> Value {
        json!({
            "scene": self.scene, "width": self.size.0, "height": self.size.1,
            "adapter": {"name": self.adapter.name, "backend": self.adapter.backend,
                        "device_type": self.adapter.device_type, "driver": self.adapter.driver,
                        "software": self.adapter.is_software},
            "wave_source": self.wave_source,
            "passed": self.failures().is_empty(),
            "maps": self.maps.iter().map(FloatStats::to_json).collect::<Vec<_>>(),
            "ldr": self.image.as_ref().map(|i| i.to_json(&self.image_limits)),
        })
    }
}

/// Errors of a cross-check run.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    /// The CPU renderer failed.
    #[error("CPU render: {0}")]
    Cpu(#[from] ocean_cpu::frame::Error),
    /// The GPU renderer failed.
    #[error("GPU render: {0}")]
    Gpu(#[from] ocean_gpu::Error),
}

/// Renders `scene` (validated) on both back ends with 8-bit output and compares every map.
///
/// # Errors
/// [`CheckError`] if either renderer fails.
pub fn check_scene(
    renderer: &mut Renderer,
    name: &str,
    scene: &Scene,
) -> Result<(SceneCheck, Renders), CheckError> {
    check_plan(renderer, name, scene, FramePlan::new(scene, OutputKind::Ldr))
}

/// [`check_scene`] by a given plan (e.g. for EXR output, or the full plan): both back ends
/// run that plan, and every map must have the plan's size on both.
///
/// # Errors
/// [`CheckError`] if either renderer fails.
pub fn check_plan(
    renderer: &mut Renderer,
    name: &str,
    scene: &Scene,
    plan: FramePlan,
) -> Result<(SceneCheck, Renders), CheckError> {
    let cpu = ocean_cpu::render_scene_with_plan(scene, plan.clone(), &mut |_| {})?;
    let gpu = renderer.run(scene, &plan)?;
    let mut maps = Vec::new();
    // Pass `bloom` on the same input as the GPU's: the CPU mirror run on the GPU's HDR frame
    // (docs/design.md's float tolerance is for the same inputs). Its bright pass x − threshold
    // cancels digits, so the HDR frames' own allowed difference (rel 1e-5) can become a
    // larger relative one in the pyramid; fed the same frame, the pass's arithmetic is what
    // is compared. The picture still compares the two frames end to end.
    let same_input_bloom = match (plan.runs(Pass::Bloom), gpu.map(ResourceId::Hdr)) {
        (true, Some(hdr)) => {
            let inputs = ocean_core::graph::BloomInputs::new(scene);
            let frame =
                ocean_cpu::sampler::Texture2D::new(hdr.width, hdr.height, hdr.texels.clone());
            Some(ocean_cpu::shaders::bloom::dispatch(&frame, &inputs))
        }
        _ => None,
    };
    for which in ResourceId::MAPS {
        let ran = which.writer().is_none_or(|p| plan.runs(p));
        let cpu_side = match (&same_input_bloom, which) {
            (Some((down, _)), ResourceId::BloomDown) => {
                ((down.atlas.width, down.atlas.height), &down.atlas.texels[..])
            }
            (Some((_, up)), ResourceId::BloomUp) => {
                ((up.atlas.width, up.atlas.height), &up.atlas.texels[..])
            }
            _ => cpu_map(&cpu.buffers, which),
        };
        let format = plan.resource(which).map_or(Default::default(), |r| r.format.storage());
        let mut stats = match gpu.map(which) {
            Some(g) => compare_float_in(which.name(), ran, cpu_side, gpu_map(g), format),
            None => compare_float(which.name(), ran, cpu_map(&cpu.buffers, which), ((0, 0), &[])),
        };
        stats.plan_size = plan.resource(which).map(|r| {
            let [w, h] = r.readback_size();
            (w, h)
        });
        maps.push(stats);
    }
    let (w, h) = (scene.camera.width, scene.camera.height);
    let image = match (&cpu.ldr, &gpu.ldr) {
        (Some(c), Some(g)) if c.len() == g.len() => Some(compare_image(c, g, w, h)),
        _ => None,
    };
    let check = SceneCheck {
        scene: name.to_owned(),
        size: (w, h),
        adapter: gpu.adapter.clone(),
        wave_source: gpu.wave_source,
        maps,
        image,
        tonemapped: plan.runs(Pass::Tonemap),
        image_limits: ImageLimits::for_adapter(&gpu.adapter),
    };
    Ok((check, Renders { cpu, gpu }))
}

/// Passes whose maps a [`SceneCheck`] compares, for reports.
pub fn map_pass(name: &str) -> Option<Pass> {
    ResourceId::MAPS.iter().find(|m| m.name() == name).and_then(|m| m.writer())
}

/// An RGBA8 picture encoded as PNG.
///
/// # Errors
/// A pixel count that does not match the size, or an encoder error.
pub fn rgba_png(w: u32, h: u32, rgba: Vec<u8>) -> std::io::Result<Vec<u8>> {
    let img = image::RgbaImage::from_raw(w, h, rgba)
        .ok_or_else(|| std::io::Error::other("image size does not match its pixels"))?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png).map_err(std::io::Error::other)?;
    Ok(bytes.into_inner())
}

/// A float map as a PNG: RGB × 255 clamped (for a look, not for measurement), alpha opaque.
fn float_png(m: ((u32, u32), &[[f32; 4]])) -> Vec<u8> {
    let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    m.1.iter().flat_map(|t| [q(t[0]), q(t[1]), q(t[2]), 255]).collect()
}

/// A difference heat map of two same-size float maps: red = max channel |Δ| / allowance,
/// 0 at the limit's 1/16, 255 at 16× the limit (log scale); green marks values beyond it.
pub fn float_diff_png(
    cpu: &[[f32; 4]],
    gpu: &[[f32; 4]],
    format: ocean_core::frame_format::FrameFormat,
) -> Vec<u8> {
    cpu.iter()
        .zip(gpu)
        .flat_map(|(c, g)| {
            let ratio = (0..4)
                .map(|k| (f64::from(g[k]) - f64::from(c[k])).abs() / allowance_in(c[k], format))
                .fold(0.0f64, |a, b| if b.is_nan() { f64::INFINITY } else { a.max(b) });
            let red = ((ratio.max(1.0 / 16.0).log2() + 4.0) / 8.0 * 255.0).clamp(0.0, 255.0) as u8;
            [red, if ratio > 1.0 { 255 } else { 0 }, 0, 255]
        })
        .collect()
}

/// The files of a check, encoded, with their names: `<scene>.{cpu,gpu,diff,flip}.png`, a PNG
/// pair and difference map of every float buffer beyond its limit
/// (`<scene>.<map>.{cpu,gpu,diff}.png`), and `<scene>.json` with the summary. The caller
/// writes them (`ocean compare` each atomically, so a full disk leaves no empty file).
///
/// # Errors
/// If a picture cannot be encoded.
pub fn artefacts(check: &SceneCheck, renders: &Renders) -> std::io::Result<Vec<(String, Vec<u8>)>> {
    let mut files = Vec::new();
    let mut save = |file: String, w: u32, h: u32, rgba: Vec<u8>| -> std::io::Result<()> {
        files.push((file, rgba_png(w, h, rgba)?));
        Ok(())
    };
    let name = &check.scene;
    let (w, h) = check.size;
    if let (Some(c), Some(g)) = (&renders.cpu.ldr, &renders.gpu.ldr) {
        save(format!("{name}.cpu.png"), w, h, c.clone())?;
        save(format!("{name}.gpu.png"), w, h, g.clone())?;
        let diff: Vec<u8> = c
            .chunks_exact(4)
            .zip(g.chunks_exact(4))
            .flat_map(|(a, b)| {
                let d = (0..3).map(|k| a[k].abs_diff(b[k])).max().unwrap_or(0);
                [d.saturating_mul(32), u8::from(d > 1) * 255, 0, 255]
            })
            .collect();
        save(format!("{name}.diff.png"), w, h, diff)?;
        if let Some(i) = &check.image {
            let flip: Vec<u8> = i
                .flip_map
                .iter()
                .flat_map(|e| {
                    let v = (e.clamp(0.0, 1.0) * 255.0) as u8;
                    [v, v, v, 255]
                })
                .collect();
            save(format!("{name}.flip.png"), w, h, flip)?;
        }
    }
    for m in check.maps.iter().filter(|m| !m.passed()) {
        let Some(which) = ResourceId::MAPS.iter().find(|f| f.name() == m.name) else { continue };
        let Some(g) = renders.gpu.map(*which) else { continue };
        let c = cpu_map(&renders.cpu.buffers, *which);
        if c.0 != (g.width, g.height) {
            continue;
        }
        let (mw, mh) = c.0;
        save(format!("{name}.{}.cpu.png", m.name), mw, mh, float_png(c))?;
        save(format!("{name}.{}.gpu.png", m.name), mw, mh, float_png(gpu_map(g)))?;
        save(
            format!("{name}.{}.diff.png", m.name),
            mw,
            mh,
            float_diff_png(c.1, &g.texels, m.format),
        )?;
    }
    let text = serde_json::to_string_pretty(&check.to_json()).map_err(std::io::Error::other)?;
    files.push((format!("{name}.json"), text.into_bytes()));
    Ok(files)
}

/// Writes [`artefacts`] into `dir` (created if missing), plainly: for the tests' output
/// folders.
///
/// # Errors
/// If a file cannot be written.
pub fn write_artefacts(dir: &Path, check: &SceneCheck, renders: &Renders) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for (file, bytes) in artefacts(check, renders)? {
        std::fs::write(dir.join(file), bytes)?;
    }
    Ok(())
}
