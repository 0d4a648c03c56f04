//! Stage `water` (`shaders/water.wgsl`): the sea surface, shaded by the shading technique
//! composed into its WGSL (`shaders/shading/hu.wgsl`, `shaders/shading/chiu.wgsl` or
//! `shaders/shading/ggx.wgsl`), with the foam technique's white water over it
//! (`shaders/foam/none.wgsl`, `shaders/foam/heuristic.wgsl`, `shaders/foam/jacobian.wgsl` or
//! `shaders/foam/accumulated.wgsl`, and `shaders/shared/foam.wgsl`). Bindings (as the WGSL declares them): group 0 — 0 `FrameUniforms`,
//! 1 `displacement`, 2 `displacement_slopes`, 3 `bump`, 4 `fresnel_above`, 5 `fresnel_below`,
//! 6 `reflection_map`, 7 `refraction_map`, 8 `shadow_map` (`textureLoad` only),
//! 9 `wrap_linear`, 10 `clamp_linear`, 11 `fresnel_filter`, 12 `floor_map`, 13 `foam_field`
//! (foam `accumulated`'s field, stage `foam`); group 1 — 0 `SkyUniforms`, 1 `SkyLut` (sky `atmosphere`'s table,
//! `shaders/shared/sky_lut.wgsl`). Vertices: ocean-core's
//! `geometry::WaterVertex` (12 bytes), u32 indices. State: reversed-Z `Greater` with depth
//! writes, no blending, no culling (the surface is seen from below under water).
//!
//! Two paths ([`ShadingPath`], the same bits): the raster pass writes the visibility buffer
//! (`fs_visibility`, group 2's textures) and a compute pass shades it (`cs_shade`, storing
//! into the HDR frame), or each fragment is shaded where it is rasterised (`fs_main`).
//! CPU mirror: `ocean-cpu/src/shaders/water.rs` (samplers `WRAP_LINEAR`, `CLAMP_LINEAR`).

use crate::created::Counted;
use ocean_core::geometry::WaterVertex;

use crate::common::{
    Load, begin_render_pass, entry, eye_depth, frame_storage_module, label, linear_sampler,
    pipeline_layout, primitive, replace_target, sampler_entry, texture_entry, uniform_entry,
};
use crate::device::Error;
use crate::shading_path::{
    Shading, ShadingPath, WATER_VISIBILITY, begin_visibility_pass, encode_shading,
    split_timestamps, visibility_color_targets, visibility_layout, visibility_targets,
};

/// The vertex buffer layout of `WaterVertex`: pos (Float32x2), weight (Float32).
pub const WATER_VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<WaterVertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x2, 1 => Float32],
};

/// The textures of group 0, in binding order 1–8, 11–13.
pub struct WaterTextures<'a> {
    /// binding 1.
    pub displacement: &'a wgpu::TextureView,
    /// binding 2.
    pub displacement_slopes: &'a wgpu::TextureView,
    /// binding 3.
    pub bump: &'a wgpu::TextureView,
    /// binding 4.
    pub fresnel_above: &'a wgpu::TextureView,
    /// binding 5.
    pub fresnel_below: &'a wgpu::TextureView,
    /// binding 6.
    pub reflection_map: &'a wgpu::TextureView,
    /// binding 7.
    pub refraction_map: &'a wgpu::TextureView,
    /// binding 8.
    pub shadow_map: &'a wgpu::TextureView,
    /// binding 11: the filtered Fresnel table of far field `variance`.
    pub fresnel_filter: &'a wgpu::TextureView,
    /// binding 12: the sea floor's relief.
    pub floor_map: &'a wgpu::TextureView,
    /// binding 13: foam `accumulated`'s field.
    pub foam_field: &'a wgpu::TextureView,
}

/// What the water pass draws.
pub enum WaterDraw<'a> {
    /// Surface `hu_patches`: the mesh's buffers.
    Mesh(WaterMeshBuffers<'a>),
    /// Surface `projected_grid`: this many vertices of `vs_projected_grid`, no buffer.
    Grid(u32),
    /// Surface `clipmap`: this many vertices of `vs_clipmap`, no buffer.
    Clipmap(u32),
}

/// The water mesh on the GPU.
pub struct WaterMeshBuffers<'a> {
    /// `WaterVertex` buffer.
    pub vertices: &'a wgpu::Buffer,
    /// u32 index buffer (three per triangle).
    pub indices: &'a wgpu::Buffer,
    /// Number of indices.
    pub index_count: u32,
}

/// The compute path's shading pipeline and the layout of its visibility group.
struct ComputeShading {
    shade: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

/// The stage's pipelines (one raster pipeline per surface's vertex entry point) and samplers.
pub struct WaterStage {
    /// Mesh, grid, clipmap: shading each fragment (`fs_main`) on the fragment path, writing
    /// the visibility buffer (`fs_visibility`) on the compute path.
    raster: [wgpu::RenderPipeline; 3],
    /// The compute path's shading (`None` on the fragment path).
    compute: Option<ComputeShading>,
    layout: wgpu::BindGroupLayout,
    sky_layout: wgpu::BindGroupLayout,
    wrap_linear: wgpu::Sampler,
    clamp_linear: wgpu::Sampler,
}

impl WaterStage {
    /// Creates the pipeline `"ocean.water"` for the sky and shading techniques of
    /// `techniques`, drawing into a frame of `target` format (`Rgba32Float` or
    /// `Rgba16Float`), on `path`, and its samplers.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled; [`Error::Unavailable`] if the compute
    /// path's storage declaration cannot be made the frame's format.
    pub fn new(
        device: &wgpu::Device,
        techniques: &ocean_core::plan::Techniques,
        target: wgpu::TextureFormat,
        path: ShadingPath,
    ) -> Result<Self, Error> {
        let name = label("water");
        let module = frame_storage_module(device, "water", techniques, target)?;
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
        let fragment = wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
        let layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[
                uniform_entry(0, vf),
                texture_entry(1, vf, true),
                texture_entry(2, fragment, true),
                texture_entry(3, fragment, true),
                texture_entry(4, fragment, true),
                texture_entry(5, fragment, true),
                texture_entry(6, fragment, true),
                texture_entry(7, fragment, true),
                texture_entry(8, fragment, false),
                sampler_entry(9, vf),
                // The floor's depth fades waves `coastal` at the vertices.
                sampler_entry(10, vf),
                texture_entry(11, fragment, true),
                texture_entry(12, vf, true),
                texture_entry(13, fragment, true),
            ],
        });
        let sky_layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ocean.water.sky"),
            entries: &[uniform_entry(0, fragment), uniform_entry(1, fragment)],
        });
        let raster_layout = pipeline_layout(device, &name, &[&layout, &sky_layout]);
        let (fs, targets) = match path {
            ShadingPath::Fragment => ("fs_main", replace_target(target).to_vec()),
            ShadingPath::Compute => ("fs_visibility", visibility_color_targets().to_vec()),
        };
        let make = |vs: &str, buffers: &[Option<wgpu::VertexBufferLayout<'_>>]| {
            Ok::<_, Error>(device.new_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&name),
                layout: Some(&raster_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(entry("water", vs)?),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: primitive(),
                depth_stencil: Some(eye_depth()),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(entry("water", fs)?),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            }))
        };
        let raster = [
            make("vs_main", &[Some(WATER_VERTEX_LAYOUT)])?,
            make("vs_projected_grid", &[])?,
            make("vs_clipmap", &[])?,
        ];
        let compute = match path {
            ShadingPath::Fragment => None,
            ShadingPath::Compute => {
                let vis_layout = visibility_layout(device, "ocean.water.visibility", target);
                let shade_layout =
                    pipeline_layout(device, &name, &[&layout, &sky_layout, &vis_layout]);
                let shade = device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(&name),
                    layout: Some(&shade_layout),
                    module: &module,
                    entry_point: Some(entry("water", "cs_shade")?),
                    compilation_options: Default::default(),
                    cache: None,
                });
                Some(ComputeShading { shade, layout: vis_layout })
            }
        };
        Ok(Self {
            raster,
            compute,
            layout,
            sky_layout,
            wrap_linear: linear_sampler(
                device,
                "ocean.water.wrap_linear",
                wgpu::AddressMode::Repeat,
            ),
            clamp_linear: linear_sampler(
                device,
                "ocean.water.clamp_linear",
                wgpu::AddressMode::ClampToEdge,
            ),
        })
    }

    /// Records the pass over what the sky and objects drew (colour kept; depth as
    /// `depth_load` says: cleared when no pass has drawn into it since the sky):
    /// on the compute path, the raster pass into the visibility buffer (kept in `kept`) and
    /// the compute pass shading it into `hdr`, timed as one span.
    #[expect(clippy::too_many_arguments, reason = "one argument per binding and attachment")]
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        frame: &wgpu::Buffer,
        sky: &wgpu::Buffer,
        sky_lut: &wgpu::Buffer,
        textures: &WaterTextures<'_>,
        draw: &WaterDraw<'_>,
        hdr: (&wgpu::TextureView, [u32; 2]),
        (depth, depth_load): (&wgpu::TextureView, Load<f32>),
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let name = label("water");
        let t = textures;
        let group = kept.bind_group(
            &name,
            &self.layout,
            &[
                frame.as_entire_binding(),
                wgpu::BindingResource::TextureView(t.displacement),
                wgpu::BindingResource::TextureView(t.displacement_slopes),
                wgpu::BindingResource::TextureView(t.bump),
                wgpu::BindingResource::TextureView(t.fresnel_above),
                wgpu::BindingResource::TextureView(t.fresnel_below),
                wgpu::BindingResource::TextureView(t.reflection_map),
                wgpu::BindingResource::TextureView(t.refraction_map),
                wgpu::BindingResource::TextureView(t.shadow_map),
                wgpu::BindingResource::Sampler(&self.wrap_linear),
                wgpu::BindingResource::Sampler(&self.clamp_linear),
                wgpu::BindingResource::TextureView(t.fresnel_filter),
                wgpu::BindingResource::TextureView(t.floor_map),
                wgpu::BindingResource::TextureView(t.foam_field),
            ],
        );
        let sky_group = kept.bind_group(
            "ocean.water.sky",
            &self.sky_layout,
            &[sky.as_entire_binding(), sky_lut.as_entire_binding()],
        );
        let (hdr_view, [width, height]) = hdr;
        let Some(compute) = &self.compute else {
            let mut pass = begin_render_pass(
                encoder,
                &name,
                hdr_view,
                Load::Keep,
                Some((depth, depth_load)),
                timestamps,
            );
            self.draw(&mut pass, draw, &group, &sky_group);
            return;
        };
        let vis = visibility_targets(kept, WATER_VISIBILITY, [width, height]);
        let (raster_ts, shade_ts) = split_timestamps(timestamps);
        {
            let mut pass = begin_visibility_pass(
                encoder,
                "ocean.water.visibility",
                &vis,
                (depth, depth_load),
                raster_ts,
            );
            self.draw(&mut pass, draw, &group, &sky_group);
        }
        let shading =
            Shading { vis: &vis, target: hdr_view, size: [width, height], layout: &compute.layout };
        encode_shading(
            kept,
            encoder,
            "ocean.water.shade",
            (&compute.shade, &[&group, &sky_group]),
            &shading,
            shade_ts,
        );
    }

    /// The surface's draw on its raster pipeline with the stage's groups.
    fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        draw: &WaterDraw<'_>,
        group: &wgpu::BindGroup,
        sky_group: &wgpu::BindGroup,
    ) {
        let [mesh_pipeline, grid_pipeline, clipmap_pipeline] = &self.raster;
        match draw {
            WaterDraw::Mesh(mesh) => {
                pass.set_pipeline(mesh_pipeline);
                pass.set_bind_group(0, group, &[]);
                pass.set_bind_group(1, sky_group, &[]);
                if mesh.index_count > 0 {
                    pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                    pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..mesh.index_count, 0, 0..1);
                }
            }
            WaterDraw::Grid(vertices) | WaterDraw::Clipmap(vertices) => {
                pass.set_pipeline(if matches!(draw, WaterDraw::Grid(_)) {
                    grid_pipeline
                } else {
                    clipmap_pipeline
                });
                pass.set_bind_group(0, group, &[]);
                pass.set_bind_group(1, sky_group, &[]);
                pass.draw(0..*vertices, 0..1);
            }
        }
    }
}
