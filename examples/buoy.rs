//! A buoy floating on the sea the GPU draws: the height query (`ocean_core::frame::
//! SurfaceSource`, the same waves as the frame's) places and tilts a buoy that the program
//! draws with its own pipeline (`support/boxes.rs`), and `ocean_gpu::embed` draws the sea into
//! the same colour target and depth buffer; headless, on the program's own device.
//!
//! ```text
//! cargo run --release --example buoy -- [scene.toml] [-o buoy.png] [--frames N]
//! ```
//!
//! Defaults: the built-in scene, `buoy.png`, 90 frames (3 s at 30 Hz from the scene's time).
//! Prints one CSV row a frame: the time (s), the water's height at the mooring (m), where the
//! buoy's waterline rides, and the buoy's tilt from the vertical (degrees); writes the last
//! frame as a PNG.

#[path = "support/boxes.rs"]
mod boxes;

use std::path::PathBuf;

use anyhow::Context;
use boxes::{BoxInstance, Boxes};
use glam::{Quat, Vec3};
use ocean_core::floating::WaterHeight;
use ocean_core::frame::SurfaceSource;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;
use ocean_gpu::embed::{CameraView, DepthCompare, EmbeddedOcean, Output, Target};

const WIDTH: u32 = 960;
const HEIGHT: u32 = 540;
const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Where the buoy is moored, m.
const MOORING: (f64, f64) = (0.0, -22.0);
/// The buoy's half-extents and its draft (how deep its bottom sits below the waterline), m.
const HALF: Vec3 = Vec3::new(0.6, 1.0, 0.6);
const DRAFT: f32 = 0.7;

fn main() -> anyhow::Result<()> {
    let (mut scene_path, mut out, mut frames) = (None, PathBuf::from("buoy.png"), 90u32);
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "-o" => out = args.next().context("-o needs a path")?.into(),
            "--frames" => {
                let n = args.next().context("--frames needs a count")?;
                frames = n.parse().with_context(|| format!("--frames `{n}`"))?;
            }
            path => scene_path = Some(PathBuf::from(path)),
        }
    }
    let scene = match &scene_path {
        Some(p) => Scene::load(p).with_context(|| format!("loading {}", p.display()))?,
        None => Scene::builtin(),
    };

    // The program's own device (headless), with the features the sea needs.
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter =
        pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(&instance, None))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("buoy example"),
        required_features: ocean_gpu::device::required_features(&adapter)?,
        ..Default::default()
    }))?;
    let target = Target {
        color_format: COLOR,
        depth_format: DEPTH,
        depth_compare: DepthCompare::Less,
        sample_count: 1,
        output: Output::Display,
    };
    let mut ocean = EmbeddedOcean::new(&adapter, &device, &queue, scene.clone(), target)?;
    let mut boxes = Boxes::new(&device, COLOR, DEPTH, wgpu::CompareFunction::Less, 1);
    // The height query of the same sea: the modes drawn once, the surface at each time.
    let plan = FramePlan::new(&scene, OutputKind::Ldr);
    let sea = SurfaceSource::new(&scene, &plan)?;

    let color = texture(&device, COLOR);
    let depth = texture(&device, DEPTH);
    let (color_view, depth_view) =
        (color.create_view(&Default::default()), depth.create_view(&Default::default()));
    let eye = Vec3::new(4.0, 3.5, 0.0);
    let camera = CameraView {
        view: glam::camera::rh::view::look_at_mat4(
            eye,
            Vec3::new(MOORING.0 as f32, 0.0, MOORING.1 as f32),
            Vec3::Y,
        ),
        projection: glam::camera::rh::proj::directx::perspective(
            0.7,
            WIDTH as f32 / HEIGHT as f32,
            0.1,
            5000.0,
        ),
        width: WIDTH,
        height: HEIGHT,
    };

    println!("t_s,water_m,tilt_deg");
    for n in 0..frames {
        let t = scene.ocean.time_s + f64::from(n) / 30.0;
        let water = sea.at(t)?;
        let (x, z) = MOORING;
        let eta = water.water_height(x, z);
        // Tilted with the surface: its normal from central differences over the buoy's width.
        let e = f64::from(HALF.x);
        let dx = (water.water_height(x + e, z) - water.water_height(x - e, z)) / (2.0 * e);
        let dz = (water.water_height(x, z + e) - water.water_height(x, z - e)) / (2.0 * e);
        let normal = Vec3::new(-dx as f32, 1.0, -dz as f32).normalize();
        let rotation = Quat::from_rotation_arc(Vec3::Y, normal);
        let center = Vec3::new(x as f32, eta as f32, z as f32)
            + rotation * Vec3::new(0.0, HALF.y - DRAFT, 0.0);
        let buoy = BoxInstance { center, half: HALF, rotation, color: [0.9, 0.25, 0.05] };
        let mast = BoxInstance {
            center: center + rotation * Vec3::new(0.0, HALF.y + 0.6, 0.0),
            half: Vec3::new(0.08, 0.6, 0.08),
            rotation,
            color: [0.9, 0.9, 0.85],
        };
        boxes.update(&device, &queue, &[buoy, mast], camera.projection * camera.view);
        let mut encoder = device.create_command_encoder(&Default::default());
        boxes.pass(&mut encoder, &color_view, &depth_view, Some((wgpu::Color::BLACK, 1.0)));
        ocean.encode(&mut encoder, &camera, t, &color_view, &depth_view)?;
        queue.submit([encoder.finish()]);
        println!("{t:.4},{eta:.4},{:.2}", normal.y.acos().to_degrees());
    }
    let pixels = boxes::read_texture(&device, &queue, &color);
    image::save_buffer(&out, &pixels, WIDTH, HEIGHT, image::ExtendedColorType::Rgba8)
        .with_context(|| format!("writing {}", out.display()))?;
    eprintln!("buoy: {frames} frames on {}; wrote {}", adapter.get_info().name, out.display());
    Ok(())
}

fn texture(device: &wgpu::Device, format: wgpu::TextureFormat) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("the program's target"),
        size: wgpu::Extent3d { width: WIDTH, height: HEIGHT, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}
