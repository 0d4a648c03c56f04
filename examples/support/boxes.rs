//! The embedding examples' own scene objects: lit, coloured boxes drawn by the caller's own
//! pipeline into the caller's colour target and depth buffer, the ones the sea shares
//! (`ocean_gpu::embed`). Nothing here is the sea's: it stands for a game's or a simulator's
//! renderer. Also used by `tests/embed.rs`, which checks how the boxes and the sea hide each
//! other.

use glam::{Mat4, Vec3};
use wgpu::util::DeviceExt;

/// One box: centre and half-extents (m, world), orientation and linear RGB colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxInstance {
    /// Centre, m.
    pub center: Vec3,
    /// Half-extents along its own axes, m.
    pub half: Vec3,
    /// Orientation (its own axes in the world).
    pub rotation: glam::Quat,
    /// Linear RGB.
    pub color: [f32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    position: [f32; 3],
    color: [f32; 3],
}

const SHADER: &str = r#"
struct View { view_proj: mat4x4<f32> }
@group(0) @binding(0) var<uniform> view: View;
struct Out { @builtin(position) position: vec4<f32>, @location(0) color: vec3<f32> }
@vertex
fn vs_main(@location(0) position: vec3<f32>, @location(1) color: vec3<f32>) -> Out {
    var out: Out;
    out.position = view.view_proj * vec4<f32>(position, 1.0);
    out.color = color;
    return out;
}
@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> { return vec4<f32>(in.color, 1.0); }
"#;

/// The caller's pipeline for boxes, with its vertex and uniform buffers.
pub struct Boxes {
    pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
    uniforms: wgpu::Buffer,
    vertices: Option<(wgpu::Buffer, u32)>,
}

impl Boxes {
    /// The pipeline for the caller's targets: `compare` is the caller's depth test (`Less`
    /// with a depth buffer cleared to 1, `Greater` with reversed Z cleared to 0).
    pub fn new(
        device: &wgpu::Device,
        color: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
        compare: wgpu::CompareFunction,
        samples: u32,
    ) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("boxes"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("boxes.view"),
            size: 64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("boxes"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("boxes"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniforms.as_entire_binding() }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("boxes"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("boxes"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<Vertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
                })],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: depth,
                depth_write_enabled: Some(true),
                depth_compare: Some(compare),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState { count: samples, ..Default::default() },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(color.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { pipeline, group, uniforms, vertices: None }
    }

    /// Uploads this frame's boxes and camera (`projection · view`).
    pub fn update(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        boxes: &[BoxInstance],
        view_proj: Mat4,
    ) {
        queue.write_buffer(&self.uniforms, 0, bytemuck::cast_slice(&view_proj.to_cols_array()));
        let vertices: Vec<Vertex> = boxes.iter().flat_map(box_vertices).collect();
        self.vertices = (!vertices.is_empty()).then(|| {
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("boxes.vertices"),
                contents: bytemuck::cast_slice(&vertices),
                usage: wgpu::BufferUsages::VERTEX,
            });
            (buffer, vertices.len() as u32)
        });
    }

    /// Records a render pass on `color` and `depth` that draws the boxes, clearing both
    /// first when `clear` says to what (colour, depth), else keeping what they hold.
    pub fn pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        clear: Option<(wgpu::Color, f32)>,
    ) {
        let (color_load, depth_load) = match clear {
            Some((c, d)) => (wgpu::LoadOp::Clear(c), wgpu::LoadOp::Clear(d)),
            None => (wgpu::LoadOp::Load, wgpu::LoadOp::Load),
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("the program's boxes"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: color,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: color_load, store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: Some(wgpu::Operations { load: depth_load, store: wgpu::StoreOp::Store }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        self.draw(&mut pass);
    }

    /// Draws the boxes in a render pass on the caller's targets.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some((buffer, count)) = &self.vertices else { return };
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
        pass.set_vertex_buffer(0, buffer.slice(..));
        pass.draw(0..*count, 0..1);
    }
}

/// The 36 vertices of a box's 12 triangles, each face shaded by a fixed light from above.
fn box_vertices(b: &BoxInstance) -> Vec<Vertex> {
    let light = Vec3::new(0.3, 0.9, 0.3).normalize();
    let rotation = b.rotation;
    let mut out = Vec::with_capacity(36);
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            // The face's two other axes.
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let corner = |a: f32, c: f32| {
                let mut p = n * b.half;
                p[u] = a * b.half[u];
                p[v] = c * b.half[v];
                b.center + rotation * p
            };
            let shade = 0.35 + 0.65 * (rotation * n).dot(light).max(0.0);
            let color = b.color.map(|c| c * shade);
            // Two triangles; the pipeline culls nothing, so their winding does not matter.
            let quad =
                [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
            out.extend(
                quad.iter().map(|&(a, c)| Vertex { position: corner(a, c).to_array(), color }),
            );
        }
    }
    out
}

/// The bytes of a 4-byte-per-texel texture (colour, or the depth aspect of `Depth32Float`),
/// row 0 first, rows packed; the texture needs `COPY_SRC`.
///
/// # Panics
/// If the device is lost while mapping (an example's or a test's failure).
pub fn read_texture(device: &wgpu::Device, queue: &wgpu::Queue, t: &wgpu::Texture) -> Vec<u8> {
    let (w, h) = (t.width(), t.height());
    let row = (4 * w).div_ceil(256) * 256;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: u64::from(row * h),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let aspect = if t.format().has_depth_aspect() {
        wgpu::TextureAspect::DepthOnly
    } else {
        wgpu::TextureAspect::All
    };
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo { texture: t, mip_level: 0, origin: Default::default(), aspect },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: None,
            },
        },
        t.size(),
    );
    queue.submit([encoder.finish()]);
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    let mapped = device.poll(wgpu::PollType::wait_indefinitely()).is_ok()
        && rx.recv().is_ok_and(|r| r.is_ok());
    assert!(mapped, "the readback buffer could not be mapped");
    let bytes = match buffer.slice(..).get_mapped_range() {
        Ok(v) => v.to_vec(),
        Err(e) => panic!("reading the texture back: {e}"),
    };
    bytes.chunks_exact(row as usize).flat_map(|r| r[..4 * w as usize].to_vec()).collect()
}
