//! The sea inside someone else's wgpu program (issue 16, `ocean_gpu::embed`): on a device the
//! test opens itself, with its own colour target, depth buffer, camera matrices and boxes
//! (`examples/support/boxes.rs`, the embedding examples' own objects):
//!
//! - the picture composited into the caller's target is the renderer's picture of the same
//!   camera, byte for byte (the composite copies; on an sRGB target it inverts the curve the
//!   target applies again);
//! - the caller's boxes and the sea hide each other by depth, whichever is drawn first, with a
//!   `Less` buffer and with a reversed-Z `Greater` one; with the wrong convention declared,
//!   the same check fails (its negative control);
//! - the depth the composite writes is the surface the height query gives: each water pixel,
//!   unprojected with the caller's projection, lies on `SurfaceSource::water_height`;
//! - bad targets and cameras are errors, not panics.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;
#[path = "../examples/support/boxes.rs"]
mod boxes;

use boxes::{BoxInstance, Boxes};
use glam::{Mat4, Vec3};
use ocean_core::floating::WaterHeight;
use ocean_core::frame::SurfaceSource;
use ocean_core::graph::FrameState;
use ocean_core::plan::OutputKind;
use ocean_core::scene::Scene;
use ocean_gpu::embed::{CameraView, DepthCompare, EmbeddedOcean, Output, Target};
use ocean_gpu::{Readback, Renderer};

const W: u32 = 160;
const H: u32 = 90;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The caller's own device, opened as an application would, with the sea's features.
struct Caller {
    adapter: wgpu::Adapter,
    device: wgpu::Device,
    queue: wgpu::Queue,
}

fn caller() -> Caller {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter =
        pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(&instance, None))
            .unwrap();
    let required_features = ocean_gpu::device::required_features(&adapter).unwrap();
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("the caller's device"),
        required_features,
        ..Default::default()
    }))
    .unwrap();
    Caller { adapter, device, queue }
}

fn texture(c: &Caller, format: wgpu::TextureFormat) -> wgpu::Texture {
    c.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("the caller's target"),
        size: wgpu::Extent3d { width: W, height: H, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// The texels of a 4-byte-per-texel texture (colour, or the depth aspect of Depth32Float).
fn read(c: &Caller, t: &wgpu::Texture) -> Vec<[u8; 4]> {
    boxes::read_texture(&c.device, &c.queue, t)
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect()
}

fn depths(c: &Caller, t: &wgpu::Texture) -> Vec<f32> {
    read(c, t).into_iter().map(f32::from_le_bytes).collect()
}

/// The caller's camera: eye, target, vertical field of view (rad) and its projection
/// convention.
fn camera(eye: Vec3, at: Vec3, fov: f32, compare: DepthCompare) -> CameraView {
    let aspect = W as f32 / H as f32;
    let projection = match compare {
        DepthCompare::Less => {
            glam::camera::rh::proj::directx::perspective(fov, aspect, 0.5, 3000.0)
        }
        DepthCompare::Greater => {
            glam::camera::rh::proj::directx::perspective_infinite_reverse(fov, aspect, 0.1)
        }
    };
    CameraView {
        view: glam::camera::rh::view::look_at_mat4(eye, at, Vec3::Y),
        projection,
        width: W,
        height: H,
    }
}

fn far(compare: DepthCompare) -> f32 {
    match compare {
        DepthCompare::Less => 1.0,
        DepthCompare::Greater => 0.0,
    }
}

fn target(color: wgpu::TextureFormat, compare: DepthCompare) -> Target {
    Target {
        color_format: color,
        depth_format: DEPTH,
        depth_compare: compare,
        sample_count: 1,
        output: Output::Display,
    }
}

/// What one caller's frame holds afterwards.
struct Drawn {
    color: Vec<[u8; 4]>,
    depth: Vec<f32>,
}

/// One caller's frame: clear (magenta, far depth), then the boxes and the sea in the given
/// order (either may be absent).
#[allow(clippy::too_many_arguments)]
fn draw(
    c: &Caller,
    ocean: Option<&mut EmbeddedOcean>,
    boxes: &[BoxInstance],
    color_format: wgpu::TextureFormat,
    declared: DepthCompare,
    cam: &CameraView,
    time_s: f64,
    boxes_first: bool,
) -> Drawn {
    let color = texture(c, color_format);
    let depth = texture(c, DEPTH);
    let (cv, dv) = (color.create_view(&Default::default()), depth.create_view(&Default::default()));
    let compare = match declared {
        DepthCompare::Less => wgpu::CompareFunction::Less,
        DepthCompare::Greater => wgpu::CompareFunction::Greater,
    };
    let mut b = Boxes::new(&c.device, color_format, DEPTH, compare, 1);
    b.update(&c.device, &c.queue, boxes, cam.projection * cam.view);
    let mut e = c.device.create_command_encoder(&Default::default());
    let magenta = wgpu::Color { r: 1.0, g: 0.0, b: 1.0, a: 1.0 };
    let nothing = Boxes::new(&c.device, color_format, DEPTH, compare, 1);
    let first = if boxes_first { &b } else { &nothing };
    first.pass(&mut e, &cv, &dv, Some((magenta, far(declared))));
    if let Some(ocean) = ocean {
        ocean.encode(&mut e, cam, time_s, &cv, &dv).unwrap();
    }
    if !boxes_first {
        b.pass(&mut e, &cv, &dv, None);
    }
    c.queue.submit([e.finish()]);
    Drawn { color: read(c, &color), depth: depths(c, &depth) }
}

fn scene() -> Scene {
    let mut s = Scene::builtin();
    (s.camera.width, s.camera.height) = (W, H);
    s
}

/// Pixels whose colour differs, and the largest channel difference.
fn differing(a: &[[u8; 4]], b: &[[u8; 4]]) -> (usize, u8) {
    let mut n = 0;
    let mut worst = 0;
    for (p, q) in a.iter().zip(b) {
        let d = (0..3).map(|i| p[i].abs_diff(q[i])).max().unwrap_or(0);
        n += usize::from(d > 0);
        worst = worst.max(d);
    }
    (n, worst)
}

fn the_embedded_sea_is_the_renderers_picture() {
    let c = caller();
    let s = scene();
    let eye = Vec3::from_array(s.camera.position.map(|v| v as f32));
    let at = Vec3::from_array(s.camera.look_at.map(|v| v as f32));
    let cam = camera(eye, at, s.camera.fov_y_deg.to_radians() as f32, DepthCompare::Less);
    let mut reference = Renderer::new().unwrap();
    for format in [wgpu::TextureFormat::Rgba8Unorm, wgpu::TextureFormat::Rgba8UnormSrgb] {
        let mut ocean = EmbeddedOcean::new(
            &c.adapter,
            &c.device,
            &c.queue,
            s.clone(),
            target(format, DepthCompare::Less),
        )
        .unwrap();
        let got = draw(&c, Some(&mut ocean), &[], format, DepthCompare::Less, &cam, 3.0, true);
        assert!(got.color.iter().all(|p| p[3] == 255), "{format:?}: the sea is opaque");
        let mut picture = |t: f64| {
            let (sc, plan, cm) = ocean.frame_scene(&cam, t).unwrap();
            let mut state = FrameState::new(0.0);
            let f = reference
                .run_frame_with_camera(&sc, &plan, &mut state, Readback::Output, Some(cm))
                .unwrap();
            f.ldr.unwrap().chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]).collect::<Vec<_>>()
        };
        let (n, worst) = differing(&got.color, &picture(3.0));
        eprintln!("{format:?}: {n} of {} pixels differ from the renderer's, by ≤ {worst}", W * H);
        assert_eq!((n, worst), (0, 0), "{format:?}: the composite changed the picture");
        // Negative control: the same comparison against the sea half a second later.
        let (n, _) = differing(&got.color, &picture(3.5));
        assert!(n > (W * H / 10) as usize, "{format:?}: another time differs in only {n}");
    }
}

fn the_sea_and_the_callers_boxes_hide_each_other() {
    let c = caller();
    let format = wgpu::TextureFormat::Rgba8UnormSrgb;
    // A pillar 30 m ahead standing from 6 m under the water to 6 m above it, and a crate
    // floating 12 m off to the side: both stand partly in front of the sea and partly
    // under it.
    let boxes = [
        BoxInstance {
            center: Vec3::new(0.0, 0.0, -30.0),
            half: Vec3::new(2.0, 6.0, 2.0),
            rotation: glam::Quat::from_rotation_y(0.4),
            color: [0.8, 0.1, 0.05],
        },
        BoxInstance {
            center: Vec3::new(9.0, 0.0, -18.0),
            half: Vec3::new(1.5, 1.0, 1.5),
            rotation: glam::Quat::from_rotation_y(-0.3),
            color: [0.9, 0.7, 0.1],
        },
    ];
    let eye = Vec3::new(0.0, 6.0, 0.0);
    let at = Vec3::new(0.0, 0.0, -60.0);
    for compare in [DepthCompare::Less, DepthCompare::Greater] {
        let cam = camera(eye, at, 0.9, compare);
        let mut ocean =
            EmbeddedOcean::new(&c.adapter, &c.device, &c.queue, scene(), target(format, compare))
                .unwrap();
        let sea = draw(&c, Some(&mut ocean), &[], format, compare, &cam, 2.0, true);
        let only_boxes = draw(&c, None, &boxes, format, compare, &cam, 2.0, true);
        let nearer = |a: f32, b: f32| match compare {
            DepthCompare::Less => a < b,
            DepthCompare::Greater => a > b,
        };
        let mut box_over_sea = 0;
        let mut sea_over_box = 0;
        for i in 0..(W * H) as usize {
            let on_box = only_boxes.depth[i] != far(compare);
            if on_box && nearer(only_boxes.depth[i], sea.depth[i]) {
                box_over_sea += 1;
            } else if on_box {
                sea_over_box += 1;
            }
        }
        eprintln!(
            "{compare:?}: {box_over_sea} box pixels in front of the sea or sky, {sea_over_box} \
             under the sea"
        );
        assert!(box_over_sea > 200 && sea_over_box > 100, "the scene tests both ways");
        for boxes_first in [true, false] {
            let both = draw(&c, Some(&mut ocean), &boxes, format, compare, &cam, 2.0, boxes_first);
            let bad = check_occlusion(&both, &sea, &only_boxes, compare);
            assert_eq!(bad, 0, "{compare:?}, boxes first {boxes_first}: {bad} pixels wrong");
        }
        // Negative control: the sea told the opposite convention of the caller's buffer.
        let other = match compare {
            DepthCompare::Less => DepthCompare::Greater,
            DepthCompare::Greater => DepthCompare::Less,
        };
        let mut wrong =
            EmbeddedOcean::new(&c.adapter, &c.device, &c.queue, scene(), target(format, other))
                .unwrap();
        let both = draw(&c, Some(&mut wrong), &boxes, format, compare, &cam, 2.0, true);
        let bad = check_occlusion(&both, &sea, &only_boxes, compare);
        assert!(bad > 100, "{compare:?}: the wrong convention passed the check ({bad} wrong)");
    }
}

/// Pixels of `both` that are neither the box (where its depth is nearer than the sea's) nor
/// the sea (elsewhere), in colour or in depth.
fn check_occlusion(both: &Drawn, sea: &Drawn, boxes: &Drawn, compare: DepthCompare) -> usize {
    let nearer = |a: f32, b: f32| match compare {
        DepthCompare::Less => a < b,
        DepthCompare::Greater => a > b,
    };
    (0..(W * H) as usize)
        .filter(|&i| {
            let on_box = boxes.depth[i] != far(compare);
            let want = if on_box && nearer(boxes.depth[i], sea.depth[i]) { boxes } else { sea };
            both.color[i] != want.color[i] || both.depth[i] != want.depth[i]
        })
        .count()
}

fn the_written_depth_is_the_surface_of_the_height_query() {
    let c = caller();
    let s = scene();
    let t = 5.0;
    // Reversed Z: depth = near / distance, precise at every distance.
    let cam =
        camera(Vec3::new(3.0, 9.0, 4.0), Vec3::new(10.0, 0.0, -30.0), 0.9, DepthCompare::Greater);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let mut ocean = EmbeddedOcean::new(
        &c.adapter,
        &c.device,
        &c.queue,
        s.clone(),
        target(format, DepthCompare::Greater),
    )
    .unwrap();
    let drawn = draw(&c, Some(&mut ocean), &[], format, DepthCompare::Greater, &cam, t, true);
    let plan = ocean_core::plan::FramePlan::new(&s, OutputKind::Ldr);
    let sea = SurfaceSource::new(&s, &plan).unwrap();
    let (now, later) = (sea.at(t).unwrap(), sea.at(t + 1.3).unwrap());
    let inverse_view = cam.view.as_dmat4().inverse();
    let p = cam.projection.as_dmat4();
    let (mut errors, mut control) = (Vec::new(), Vec::new());
    for y in (0..H).step_by(3) {
        for x in (0..W).step_by(3) {
            let d = f64::from(drawn.depth[(y * W + x) as usize]);
            if d <= 0.0 {
                continue;
            }
            // View depth from the caller's reversed-Z infinite projection: d = near / z.
            let z = p.w_axis.z / d;
            let (nx, ny) = ocean_core::camera::pixel_centre_ndc(x, y, W, H);
            let v = glam::DVec4::new(nx * z / p.x_axis.x, ny * z / p.y_axis.y, -z, 1.0);
            let w = inverse_view * v;
            if z > 60.0 {
                continue;
            }
            errors.push((w.y - now.water_height(w.x, w.z)).abs());
            control.push((w.y - later.water_height(w.x, w.z)).abs());
        }
    }
    let median_and_p90 = |e: &[f64]| {
        let mut sorted = e.to_vec();
        sorted.sort_by(f64::total_cmp);
        let q = |f: f64| sorted[((sorted.len() - 1) as f64 * f) as usize];
        (q(0.5), q(0.9), q(0.99), sorted[sorted.len() - 1])
    };
    let (p50, p90, p99, worst) = median_and_p90(&errors);
    let (c50, ..) = median_and_p90(&control);
    eprintln!(
        "{} water pixels within 60 m: drawn vs height query median {p50:.4} m, p90 {p90:.4}, \
         p99 {p99:.4}, worst {worst:.4}; against the sea 1.3 s later median {c50:.4} m",
        errors.len(),
    );
    assert!(errors.len() > 300, "too few water pixels: {}", errors.len());
    // The drawn surface is a mesh of 1 m cells over the displaced surface; the query sums
    // every mode. Linear interpolation over a cell leaves (Δx²/8)·|η''|, ~1 cm for the
    // 2 m waves' centimetre amplitudes: measured median 0.9 cm, p90 2.9 cm. The tail (p99
    // 16 cm) is at crests that fold (choppiness 1, Jacobian < 0), where the query's
    // inversion picks one of two sheets, and at grazing pixels, where a millimetre of depth
    // moves the point along the ray; it is reported, not bounded.
    assert!(p50 < 0.02 && p90 < 0.05, "the drawn surface is not the query's");
    assert!(c50 > 10.0 * p50, "the control does not tell the seas apart");
}

fn bad_targets_and_cameras_are_errors() {
    let c = caller();
    let new = |t: Target| EmbeddedOcean::new(&c.adapter, &c.device, &c.queue, scene(), t);
    let bad_color = new(target(wgpu::TextureFormat::Rgba8Uint, DepthCompare::Less));
    assert!(bad_color.is_err(), "an integer colour target was accepted");
    let mut no_depth = target(wgpu::TextureFormat::Rgba8Unorm, DepthCompare::Less);
    no_depth.depth_format = wgpu::TextureFormat::Rgba8Unorm;
    assert!(new(no_depth).is_err(), "a colour format was accepted as the depth buffer");
    let ocean = new(target(wgpu::TextureFormat::Rgba8Unorm, DepthCompare::Less)).unwrap();
    let good =
        camera(Vec3::new(0.0, 5.0, 0.0), Vec3::new(0.0, 0.0, -10.0), 0.9, DepthCompare::Less);
    assert!(ocean.frame_scene(&good, 1.0).is_ok());
    let mut squashed = good;
    squashed.height = 2 * H;
    let mut scaled = good;
    scaled.view *= Mat4::from_scale(Vec3::splat(2.0));
    let mut nan = good;
    nan.view.x_axis.x = f32::NAN;
    let mut ortho = good;
    ortho.projection =
        glam::camera::rh::proj::directx::orthographic(-1.0, 1.0, -1.0, 1.0, 0.1, 100.0);
    for (what, cam, t) in [
        ("an aspect ratio other than the image's", squashed, 1.0),
        ("a scaled view", scaled, 1.0),
        ("a NaN view", nan, 1.0),
        ("an orthographic projection", ortho, 1.0),
        ("an infinite time", good, f64::INFINITY),
    ] {
        let e = ocean.frame_scene(&cam, t).err();
        eprintln!("{what}: {e:?}");
        assert!(e.is_some(), "{what} was accepted");
    }
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        gpu: the_embedded_sea_is_the_renderers_picture,
            the_sea_and_the_callers_boxes_hide_each_other,
            the_written_depth_is_the_surface_of_the_height_query,
            bad_targets_and_cameras_are_errors;
    )
}
