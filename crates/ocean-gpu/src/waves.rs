//! Stage `waves` on the GPU: the wave maps of one [`WaveModes`] synthesised every frame by
//! `shaders/waves.wgsl` (h̃(k, t) and the multiplied spectra, a radix-2 Stockham inverse FFT
//! in ping-pong storage buffers, packing into three Rgba32Float textures).
//!
//! Conventions, the phase in integer turns (how h̃ stays accurate at t = 10⁶ s without f64)
//! and the FFT stage formula: ocean-core's `waves::uniforms`. The CPU mirror, dispatch for
//! dispatch: `ocean_cpu::shaders::waves`.
//!
//! N must be a power of two. The FFT ([`FftKernel`]): for N ≤ [`FFT_SHARED_MAX`] the whole frame in two dispatches
//! (`spectrum_rows_shared`, `columns_pack_shared`: a workgroup per row, then per column,
//! holds its lines in workgroup memory through every stage, two stages between barriers
//! (radix 4), the spectrum computed as the rows are loaded and the textures packed as the
//! columns are done), else `spectrum`, 2·log₂N one-stage dispatches (rows, then columns)
//! alternating ping → pong → ping …, and `pack`. Both do the same operations for every value;
//! [`GpuWaves::encode_dispatches`] runs the one-stage form, dispatch by dispatch, for the
//! comparison with the CPU mirror (whose `shared_memory` module mirrors the two-dispatch
//! form).
//!
//! The three textures are written for every map: the water stage takes `displacement` and
//! `displacement_slopes` from the displacement map's `GpuWaves` and `bump` from the bump
//! map's. They are Rgba32Float with `STORAGE_BINDING | TEXTURE_BINDING | COPY_SRC`; filtering
//! them in a sampler needs the `FLOAT32_FILTERABLE` feature.

use crate::created::{Counted, CountedView};
use std::ops::Range;

use ocean_core::dispersion::Dispersion;
use ocean_core::waves::WaveModes;
use ocean_core::waves::uniforms::{
    WAVE_ARRAYS, WaveModeData, WavesUniforms, check_fft_size, fft_passes, fft_shared_lines,
    fft_twiddles, wave_mode_table,
};

/// Errors of the GPU wave synthesis.
#[derive(Debug, thiserror::Error)]
pub enum WavesError {
    /// An argument ocean-core rejects: N not a power of two, t or choppiness not finite, |t|
    /// too large without a loop period.
    #[error(transparent)]
    Core(#[from] ocean_core::Error),
    /// The device cannot hold the buffers or textures of this N.
    #[error(
        "a {resolution}² wave map needs {needed} bytes per FFT buffer and {resolution}² \
         textures; this device allows {limit_bytes}-byte storage bindings and \
         {limit_texture}² textures: use a smaller resolution or --backend cpu"
    )]
    TooLarge {
        /// N.
        resolution: usize,
        /// Bytes of one ping-pong buffer.
        needed: u64,
        /// The device's `max_storage_buffer_binding_size` (or `max_buffer_size` if smaller).
        limit_bytes: u64,
        /// The device's `max_texture_dimension_2d`.
        limit_texture: u32,
    },
    /// A table of another size than the one the pipelines were built for.
    #[error("{what} holds {got} entries, the {resolution}² wave map needs {expected}")]
    TableSize {
        /// Which table.
        what: &'static str,
        /// N.
        resolution: usize,
        /// Entries given.
        got: usize,
        /// Entries needed.
        expected: usize,
    },
    /// wgpu reported a validation error while the pipelines were built.
    #[error("building the waves pipelines failed: {0}")]
    Validation(String),
    /// Mapping a readback buffer failed.
    #[error("reading back {what} from the GPU failed: {reason}")]
    Readback {
        /// What was read.
        what: &'static str,
        /// wgpu's message.
        reason: String,
    },
}

/// One of the three output textures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WaveTexture {
    /// (disp_x, height, disp_z, jacobian).
    Displacement,
    /// (slope_x, slope_z, 0, 0).
    DisplacementSlopes,
    /// (slope_x, slope_z, height, jacobian).
    Bump,
}

impl WaveTexture {
    /// All three, in binding order.
    pub const ALL: [Self; 3] = [Self::Displacement, Self::DisplacementSlopes, Self::Bump];

    /// The WGSL variable's name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Displacement => "displacement",
            Self::DisplacementSlopes => "displacement_slopes",
            Self::Bump => "bump",
        }
    }
}

/// One of the two ping-pong buffers (4·N² complex f32 each, array f at f·N²).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WavesBuffer {
    /// Written by `spectrum` and by every odd FFT dispatch; read by `pack`.
    Ping,
    /// Written by every even FFT dispatch (the first is 0).
    Pong,
}

pub use ocean_core::waves::uniforms::{FFT_SHARED_MAX, FFT_SHARED_THREADS};

/// How the FFT's stages are dispatched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FftKernel {
    /// One dispatch per stage and axis (2·log₂N), through the storage buffers.
    Stages,
    /// Two dispatches a frame, rows (with the spectrum) then columns (with the packing), the
    /// lines in workgroup memory between stages (N ≤ [`FFT_SHARED_MAX`], and the device's
    /// workgroup limits at least WebGPU's defaults).
    Shared,
}

impl FftKernel {
    /// The kernel the frame uses on `adapter` for N = `resolution`: [`Self::Shared`] where it
    /// fits, except on a software adapter (`DeviceType::Cpu`, e.g. lavapipe), where it was
    /// measured 1.2× (N = 1024) to 2.8× (N = 128) slower than [`Self::Stages`]: llvmpipe runs
    /// a workgroup's invocations on one thread and pays for each barrier (`ocean bench`).
    pub fn for_adapter(adapter: &wgpu::AdapterInfo, resolution: usize) -> Self {
        if adapter.device_type == wgpu::DeviceType::Cpu
            || resolution as u64 > u64::from(FFT_SHARED_MAX)
        {
            Self::Stages
        } else {
            Self::Shared
        }
    }
}

const WORKGROUP_2D: u32 = 8;
const WORKGROUP_FFT: u32 = 64;
const ARRAYS: u32 = WAVE_ARRAYS;

/// The pipelines, buffers and textures of the `waves` stage for one [`WaveModes`].
#[derive(Debug)]
pub struct GpuWaves {
    resolution: u32,
    dispersion: Dispersion,
    uniforms: wgpu::Buffer,
    modes: wgpu::Buffer,
    twiddles: wgpu::Buffer,
    ping: wgpu::Buffer,
    pong: wgpu::Buffer,
    spectrum: wgpu::ComputePipeline,
    fft_rows: wgpu::ComputePipeline,
    fft_columns: wgpu::ComputePipeline,
    spectrum_rows_shared: wgpu::ComputePipeline,
    columns_pack_shared: wgpu::ComputePipeline,
    kernel: FftKernel,
    pack: wgpu::ComputePipeline,
    shared_group: wgpu::BindGroup,
    /// Group 1 of `spectrum` (dst = ping), of each FFT pass, and of `pack` (src = ping).
    spectrum_group: wgpu::BindGroup,
    pass_groups: Vec<wgpu::BindGroup>,
    pack_group: wgpu::BindGroup,
    texture_group: wgpu::BindGroup,
    textures: [wgpu::Texture; 3],
    views: [wgpu::TextureView; 3],
}

fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format: wgpu::TextureFormat::Rgba32Float,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        count: None,
    }
}

fn buffer_group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32, resource: b.as_entire_binding() })
        .collect();
    device.new_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

impl GpuWaves {
    /// Builds the pipelines (labels `ocean.waves.<entry point>`), uploads the mode table and
    /// the twiddles of `modes` and allocates the ping-pong buffers (32·N² bytes each) and the
    /// three N × N textures.
    ///
    /// # Errors
    /// N not a power of two ([`WavesError::Core`]), larger than the device holds
    /// ([`WavesError::TooLarge`]), or a wgpu validation error.
    pub fn new(device: &wgpu::Device, modes: &WaveModes) -> Result<Self, WavesError> {
        let limits = device.limits();
        let shared = modes.resolution() as u64 <= u64::from(FFT_SHARED_MAX)
            && limits.max_compute_workgroup_storage_size >= 2 * FFT_SHARED_MAX * 8
            && limits.max_compute_invocations_per_workgroup >= FFT_SHARED_THREADS
            && limits.max_compute_workgroup_size_x >= FFT_SHARED_THREADS;
        let kernel = if shared { FftKernel::Shared } else { FftKernel::Stages };
        Self::with_kernel(device, modes, kernel)
    }

    /// [`Self::new`] with the FFT dispatched as `kernel` says ([`FftKernel::Shared`] for N
    /// beyond [`FFT_SHARED_MAX`] is [`WavesError::TooLarge`]).
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn with_kernel(
        device: &wgpu::Device,
        modes: &WaveModes,
        kernel: FftKernel,
    ) -> Result<Self, WavesError> {
        let n = modes.resolution();
        check_fft_size(n)?;
        let limits = device.limits();
        let needed = u64::from(ARRAYS) * (n * n) as u64 * 8;
        let limit_bytes = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        if needed > limit_bytes
            || (kernel == FftKernel::Shared && n as u64 > u64::from(FFT_SHARED_MAX))
            || n as u64 > u64::from(limits.max_texture_dimension_2d)
            || (n as u64) > u64::from(limits.max_compute_workgroups_per_dimension)
        {
            return Err(WavesError::TooLarge {
                resolution: n,
                needed,
                limit_bytes,
                limit_texture: limits.max_texture_dimension_2d,
            });
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let built = Self::build(device, modes, kernel);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(WavesError::Validation(e.to_string()));
        }
        Ok(built)
    }

    fn build(device: &wgpu::Device, modes: &WaveModes, kernel: FftKernel) -> Self {
        let n = modes.resolution() as u32;
        let source = ocean_core::shader_source::stage_source("waves")
            .expect("the waves stage is embedded and has no imports");
        let module = device.new_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("ocean.waves"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });

        let shared_layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ocean.waves.shared"),
            entries: &[uniform_entry(0), storage_entry(1, true), storage_entry(2, true)],
        });
        let pass_layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ocean.waves.pass"),
            entries: &[uniform_entry(0), storage_entry(1, true), storage_entry(2, false)],
        });
        let texture_layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ocean.waves.textures"),
            entries: &[texture_entry(0), texture_entry(1), texture_entry(2)],
        });
        let layout = device.new_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("ocean.waves"),
            bind_group_layouts: &[Some(&shared_layout), Some(&pass_layout), Some(&texture_layout)],
            immediate_size: 0,
        });
        let pipeline = |entry: &str| {
            device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&format!("ocean.waves.{entry}")),
                layout: Some(&layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };

        let uniforms = device.new_buffer(&wgpu::BufferDescriptor {
            label: Some("ocean.waves.uniforms"),
            size: size_of::<WavesUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let modes_buffer = device.new_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ocean.waves.modes"),
            contents: bytemuck::cast_slice(&wave_mode_table(modes)),
            usage: storage,
        });
        let twiddles = device.new_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ocean.waves.twiddles"),
            contents: bytemuck::cast_slice(&fft_twiddles(n as usize)),
            usage: storage,
        });
        let ping_pong = |label| {
            device.new_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: u64::from(ARRAYS * n * n) * 8,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let (ping, pong) = (ping_pong("ocean.waves.ping"), ping_pong("ocean.waves.pong"));
        let pass_uniforms: Vec<wgpu::Buffer> = fft_passes(n as usize)
            .iter()
            .map(|p| {
                device.new_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("ocean.waves.fft_pass"),
                    contents: bytemuck::bytes_of(p),
                    usage: wgpu::BufferUsages::UNIFORM,
                })
            })
            .collect();

        let shared_group = buffer_group(
            device,
            "ocean.waves.shared",
            &shared_layout,
            &[&uniforms, &modes_buffer, &twiddles],
        );
        let spectrum_group = buffer_group(
            device,
            "ocean.waves.spectrum",
            &pass_layout,
            &[&pass_uniforms[0], &pong, &ping],
        );
        let pass_groups = pass_uniforms
            .iter()
            .enumerate()
            .map(|(p, u)| {
                let (src, dst) = if p.is_multiple_of(2) { (&ping, &pong) } else { (&pong, &ping) };
                buffer_group(device, "ocean.waves.fft_pass", &pass_layout, &[u, src, dst])
            })
            .collect();
        let pack_group = buffer_group(
            device,
            "ocean.waves.pack",
            &pass_layout,
            &[&pass_uniforms[0], &ping, &pong],
        );

        let textures = WaveTexture::ALL.map(|which| {
            device.new_texture(&wgpu::TextureDescriptor {
                label: Some(&format!("ocean.waves.{}", which.name())),
                size: wgpu::Extent3d { width: n, height: n, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        });
        let views = textures.each_ref().map(|t| t.new_view(&Default::default()));
        let texture_group = device.new_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ocean.waves.textures"),
            layout: &texture_layout,
            entries: &[0, 1, 2].map(|i| wgpu::BindGroupEntry {
                binding: i,
                resource: wgpu::BindingResource::TextureView(&views[i as usize]),
            }),
        });

        Self {
            resolution: n,
            dispersion: *modes.dispersion(),
            uniforms,
            modes: modes_buffer,
            twiddles,
            ping,
            pong,
            spectrum: pipeline("spectrum"),
            fft_rows: pipeline("fft_rows"),
            fft_columns: pipeline("fft_columns"),
            spectrum_rows_shared: pipeline("spectrum_rows_shared"),
            columns_pack_shared: pipeline("columns_pack_shared"),
            kernel,
            pack: pipeline("pack"),
            shared_group,
            spectrum_group,
            pass_groups,
            pack_group,
            texture_group,
            textures,
            views,
        }
    }

    /// N.
    pub fn resolution(&self) -> usize {
        self.resolution as usize
    }

    /// How a frame dispatches the FFT.
    pub fn kernel(&self) -> FftKernel {
        self.kernel
    }

    /// Writes the uniforms of time `t` and `choppiness` (reduced and split in f64 on the CPU)
    /// and records the whole frame's dispatches into `encoder`.
    ///
    /// The uniforms go through `queue.write_buffer`, which takes effect at the next
    /// `queue.submit`: encode one time per submission.
    ///
    /// # Errors
    /// t or choppiness not finite, or |t| ≥ 2⁵⁵ s without a loop period.
    pub fn encode(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        t: f64,
        choppiness: f64,
    ) -> Result<(), WavesError> {
        self.encode_timed(queue, encoder, t, choppiness, None)
    }

    /// [`Self::encode`] with timestamp writes on its compute pass.
    ///
    /// # Errors
    /// As [`Self::encode`].
    pub fn encode_timed(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        t: f64,
        choppiness: f64,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), WavesError> {
        self.write_uniforms(queue, t, choppiness)?;
        match self.kernel {
            FftKernel::Stages => self.record(encoder, 0..self.dispatch_count(), timestamps),
            FftKernel::Shared => self.record_shared(encoder, timestamps),
        }
        Ok(())
    }

    /// Writes the uniforms of time `t` and `choppiness`, and returns them.
    ///
    /// # Errors
    /// As [`Self::encode`].
    pub fn write_uniforms(
        &self,
        queue: &wgpu::Queue,
        t: f64,
        choppiness: f64,
    ) -> Result<WavesUniforms, WavesError> {
        let u = WavesUniforms::new(self.resolution(), &self.dispersion, t, choppiness)?;
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&u));
        Ok(u)
    }

    /// Replaces h0 and ω with those of `modes` (same N, e.g. a new wind or seed): no pipeline
    /// or buffer is rebuilt.
    ///
    /// # Errors
    /// [`WavesError::TableSize`] for another N.
    pub fn update_modes(
        &mut self,
        queue: &wgpu::Queue,
        modes: &WaveModes,
    ) -> Result<(), WavesError> {
        self.write_mode_table(queue, &wave_mode_table(modes))?;
        self.dispersion = *modes.dispersion();
        Ok(())
    }

    /// Uploads a mode table as is (tests: a perturbed h0).
    ///
    /// # Errors
    /// [`WavesError::TableSize`] unless it holds N² modes.
    pub fn write_mode_table(
        &self,
        queue: &wgpu::Queue,
        table: &[WaveModeData],
    ) -> Result<(), WavesError> {
        let expected = self.resolution() * self.resolution();
        if table.len() != expected {
            return Err(WavesError::TableSize {
                what: "mode table",
                resolution: self.resolution(),
                got: table.len(),
                expected,
            });
        }
        queue.write_buffer(&self.modes, 0, bytemuck::cast_slice(table));
        Ok(())
    }

    /// Uploads a twiddle table as is (tests: a wrong sign).
    ///
    /// # Errors
    /// [`WavesError::TableSize`] unless it holds N/2 entries.
    pub fn write_twiddles(
        &self,
        queue: &wgpu::Queue,
        twiddles: &[[f32; 2]],
    ) -> Result<(), WavesError> {
        let expected = self.resolution() / 2;
        if twiddles.len() != expected {
            return Err(WavesError::TableSize {
                what: "twiddle table",
                resolution: self.resolution(),
                got: twiddles.len(),
                expected,
            });
        }
        queue.write_buffer(&self.twiddles, 0, bytemuck::cast_slice(twiddles));
        Ok(())
    }

    /// The number of dispatches of a frame of the one-stage FFT ([`FftKernel::Stages`], what
    /// [`Self::encode_dispatches`] runs): `spectrum`, 2·log₂N FFT passes, `pack`.
    pub fn dispatch_count(&self) -> usize {
        2 * self.resolution.trailing_zeros() as usize + 2
    }

    /// The buffer that dispatch `index` (< [`Self::dispatch_count`] − 1) writes: `spectrum`
    /// (0) writes ping, FFT pass p (index p + 1) writes pong for even p, ping for odd p.
    pub fn output_of(&self, index: usize) -> WavesBuffer {
        if index.is_multiple_of(2) { WavesBuffer::Ping } else { WavesBuffer::Pong }
    }

    /// Records dispatches `range` of the frame (0 = `spectrum`, 1 … 2·log₂N = the FFT passes,
    /// the last = `pack`) in one compute pass, with the uniforms last written. A frame is the
    /// whole range; a prefix stops after any dispatch, for pass-by-pass comparison.
    pub fn encode_dispatches(&self, encoder: &mut wgpu::CommandEncoder, range: Range<usize>) {
        self.record(encoder, range, None);
    }

    fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        range: Range<usize>,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let n = self.resolution;
        let stages = n.trailing_zeros() as usize;
        let tiles = n.div_ceil(WORKGROUP_2D);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("ocean.waves"),
            timestamp_writes,
        });
        pass.set_bind_group(0, &self.shared_group, &[]);
        pass.set_bind_group(2, &self.texture_group, &[]);
        for index in range.start..range.end.min(self.dispatch_count()) {
            if index == 0 {
                pass.set_pipeline(&self.spectrum);
                pass.set_bind_group(1, &self.spectrum_group, &[]);
                pass.dispatch_workgroups(tiles, tiles, 1);
            } else if index <= 2 * stages {
                let p = index - 1;
                pass.set_pipeline(if p < stages { &self.fft_rows } else { &self.fft_columns });
                pass.set_bind_group(1, &self.pass_groups[p], &[]);
                pass.dispatch_workgroups((n / 2).div_ceil(WORKGROUP_FFT), n, ARRAYS);
            } else {
                pass.set_pipeline(&self.pack);
                pass.set_bind_group(1, &self.pack_group, &[]);
                pass.dispatch_workgroups(tiles, tiles, 1);
            }
        }
    }

    /// A frame with the shared-memory FFT in two dispatches: `spectrum_rows_shared` (→
    /// pong; a workgroup per row and batch of [`fft_shared_lines`] arrays) and
    /// `columns_pack_shared` (pong → the textures; a workgroup per column).
    fn record_shared(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let n = self.resolution;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("ocean.waves"),
            timestamp_writes,
        });
        pass.set_bind_group(0, &self.shared_group, &[]);
        pass.set_bind_group(2, &self.texture_group, &[]);
        // The one-stage groups 0 (ping → pong) and 1 (pong → ping); their stage uniform is
        // not read, nor is the second's ping.
        pass.set_pipeline(&self.spectrum_rows_shared);
        pass.set_bind_group(1, &self.pass_groups[0], &[]);
        pass.dispatch_workgroups(n, ARRAYS / fft_shared_lines(n), 1);
        pass.set_pipeline(&self.columns_pack_shared);
        pass.set_bind_group(1, &self.pass_groups[1], &[]);
        pass.dispatch_workgroups(n, 1, 1);
    }

    /// An output texture.
    pub fn texture(&self, which: WaveTexture) -> &wgpu::Texture {
        &self.textures[which as usize]
    }

    /// A view of an output texture (the whole texture, Rgba32Float).
    pub fn view(&self, which: WaveTexture) -> &wgpu::TextureView {
        &self.views[which as usize]
    }

    /// (disp_x, height, disp_z, jacobian).
    pub fn displacement_view(&self) -> &wgpu::TextureView {
        self.view(WaveTexture::Displacement)
    }

    /// (slope_x, slope_z, 0, 0).
    pub fn displacement_slopes_view(&self) -> &wgpu::TextureView {
        self.view(WaveTexture::DisplacementSlopes)
    }

    /// (slope_x, slope_z, height, jacobian).
    pub fn bump_view(&self) -> &wgpu::TextureView {
        self.view(WaveTexture::Bump)
    }

    /// Reads an output texture back, row-major texels (blocks until the GPU is done).
    ///
    /// # Errors
    /// [`WavesError::Readback`] if mapping fails.
    pub fn read_texture(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        which: WaveTexture,
    ) -> Result<Vec<[f32; 4]>, WavesError> {
        let n = self.resolution;
        let row_bytes = n * 16;
        let padded = row_bytes.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let staging = device.new_buffer(&wgpu::BufferDescriptor {
            label: Some("ocean.waves.readback"),
            size: u64::from(padded * n),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: self.texture(which),
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &staging,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(n),
                },
            },
            wgpu::Extent3d { width: n, height: n, depth_or_array_layers: 1 },
        );
        queue.submit([encoder.finish()]);
        let bytes = map_read(device, &staging, which.name())?;
        let mut texels = Vec::with_capacity((n * n) as usize);
        for row in bytes.chunks_exact(padded as usize) {
            texels.extend_from_slice(bytemuck::cast_slice::<u8, [f32; 4]>(
                &row[..row_bytes as usize],
            ));
        }
        Ok(texels)
    }

    /// Reads a ping-pong buffer back: 4·N² complex values, array f at f·N².
    ///
    /// # Errors
    /// [`WavesError::Readback`] if mapping fails.
    pub fn read_buffer(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        which: WavesBuffer,
    ) -> Result<Vec<[f32; 2]>, WavesError> {
        let source = match which {
            WavesBuffer::Ping => &self.ping,
            WavesBuffer::Pong => &self.pong,
        };
        let staging = device.new_buffer(&wgpu::BufferDescriptor {
            label: Some("ocean.waves.readback"),
            size: source.size(),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(source, 0, &staging, 0, source.size());
        queue.submit([encoder.finish()]);
        let bytes = map_read(device, &staging, "a ping-pong buffer")?;
        Ok(bytemuck::cast_slice::<u8, [f32; 2]>(&bytes).to_vec())
    }
}

/// Maps `buffer` for reading, waits, and copies its bytes out.
fn map_read(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    what: &'static str,
) -> Result<Vec<u8>, WavesError> {
    crate::readback::map_read_bytes(device, buffer)
        .map_err(|reason| WavesError::Readback { what, reason })
}
