//! Stage `waves` on the GPU path: where the water stage's three wave maps come from.
//!
//! The maps, all `Rgba32Float` and laid out as ocean-cpu's `FrameBuffers` holds them
//! (ocean-core's `frame::{displacement_texels, displacement_slope_texels, bump_texels}`):
//!
//! | map | size | texel |
//! |---|---|---|
//! | `displacement` | N_d² | (disp_x, height, disp_z, jacobian) |
//! | `displacement_slopes` | N_d² | (slope_x, slope_z, 0, 0) |
//! | `bump` | N_b² | (slope_x, slope_z, height, jacobian) |
//!
//! A [`WaveMapSource`] produces them for a time t. Two sources:
//! - [`GpuFft`] (the default): h0(k) uploaded once, then h̃(k, t), the choppy and slope
//!   spectra and a Stockham inverse FFT in compute passes every frame
//!   (`crates/ocean-gpu/src/waves.rs`); a new sea of the same size takes new modes in place
//!   ([`WaveMapSource::update`]). The CPU oracle runs the same `waves.wgsl` through its
//!   mirror (the plan's `WavesKernel::Shader`), and on lavapipe the two agree bit for bit.
//! - [`CpuUpload`]: ocean-core's `Synthesizer<f32>` on the CPU, uploaded with
//!   `Queue::write_texture`: what both back ends use where the plan says
//!   `WavesKernel::Synthesis` (a side that is not a power of two), and the fallback where the
//!   GPU FFT's buffers exceed the device's limits. Chosen on purpose elsewhere, its maps are
//!   ocean-core's, not the oracle's mirror's (within docs/design.md's FFT tolerance, 1e-5).

use ocean_core::frame::{bump_texels, displacement_slope_texels, displacement_texels};
use ocean_core::plan::WavesKernel;
use ocean_core::scene::Ocean;
use ocean_core::waves::{OceanSurface, Synthesizer, WaveMaps};

use crate::device::{Error, Gpu};
use crate::texture::{GpuTexture, MAP_FORMAT, map_usage};
use crate::waves::{FftKernel, GpuWaves, WaveTexture, WavesError};

/// The three maps the water stage binds (group 0, bindings 1–3).
pub struct WaveTextures {
    /// (disp_x, height, disp_z, jacobian), N_d².
    pub displacement: GpuTexture,
    /// (slope_x, slope_z, 0, 0), N_d².
    pub displacement_slopes: GpuTexture,
    /// (slope_x, slope_z, height, jacobian), N_b².
    pub bump: GpuTexture,
}

impl WaveTextures {
    /// Uninitialised maps of the given resolutions, usable by either source.
    pub fn new(device: &wgpu::Device, n_d: u32, n_b: u32) -> Self {
        let map =
            |label: &str, n: u32| GpuTexture::new(device, label, n, n, MAP_FORMAT, map_usage());
        Self {
            displacement: map("ocean.waves.displacement", n_d),
            displacement_slopes: map("ocean.waves.displacement_slopes", n_d),
            bump: map("ocean.waves.bump", n_b),
        }
    }
}

/// Which implementation of stage `waves` the GPU renderer uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WaveSynthesis {
    /// ocean-core's CPU synthesis, uploaded ([`CpuUpload`]).
    CpuUpload,
    /// The GPU FFT of `crates/ocean-gpu/src/waves.rs` ([`GpuFft`]), every frame; an ocean it
    /// cannot take (a resolution that is not a power of two) falls back to [`CpuUpload`].
    #[default]
    GpuFft,
}

/// A producer of the wave maps of one ocean (its modes are fixed; the time changes).
pub trait WaveMapSource {
    /// A short name for reports: `"cpu-upload"`, `"gpu-fft"`.
    fn name(&self) -> &'static str;

    /// Whether [`Self::encode`] records GPU passes (and so writes the timestamps it is
    /// given); a source that only uploads is timed on the CPU instead.
    fn records_gpu_passes(&self) -> bool;

    /// Produces the maps at time `t` (s) with `choppiness`: either writes them now through the
    /// queue (ordered before the next submission) or records compute passes into `encoder`
    /// (with `timestamps` on its first pass, when given). Returns the textures to bind.
    ///
    /// # Errors
    /// Whatever the synthesis reports (an invalid time or choppiness).
    fn encode(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        t: f64,
        choppiness: f64,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<&WaveTextures, Error>;

    /// Takes another ocean's modes in place when it can (same map sizes), so that a change of
    /// wind, fetch or spectrum costs one upload of N² modes and no new pipeline; returns
    /// whether it did (else the caller makes a new source).
    ///
    /// # Errors
    /// A failed upload.
    fn update(&mut self, _gpu: &Gpu, _surface: &OceanSurface) -> Result<bool, Error> {
        Ok(false)
    }
}

/// The wave-map source of `kind` for an ocean (its modes drawn by ocean-core).
///
/// # Errors
/// [`Error::Core`] if the ocean's modes cannot be drawn; [`Error::Wgpu`] or
/// [`Error::Unavailable`] if neither source can be made.
pub fn make_source(
    gpu: &Gpu,
    kind: WaveSynthesis,
    ocean: &Ocean,
) -> Result<Box<dyn WaveMapSource>, Error> {
    make_source_from(gpu, kind, ocean.surface()?)
}

/// [`make_source`] from modes already drawn (`ocean.surface()`, e.g. on another thread).
///
/// # Errors
/// As [`make_source`].
pub fn make_source_from(
    gpu: &Gpu,
    kind: WaveSynthesis,
    surface: OceanSurface,
) -> Result<Box<dyn WaveMapSource>, Error> {
    match kind {
        WaveSynthesis::CpuUpload => Ok(Box::new(CpuUpload::new(gpu, surface)?)),
        WaveSynthesis::GpuFft => {
            // The frame plan's rule (both back ends follow it): waves.wgsl where its radix-2
            // FFT can run, ocean-core's synthesis elsewhere.
            let kernel = WavesKernel::for_resolutions(
                surface.displacement.resolution() as u32,
                surface.bump.resolution() as u32,
            );
            if kernel == WavesKernel::Synthesis {
                return Ok(Box::new(CpuUpload::new(gpu, surface)?));
            }
            match GpuFft::new(gpu, surface.clone()) {
                Ok(fft) => Ok(Box::new(fft)),
                // Too large for the device's buffers: the CPU synthesis can (the frame
                // reports the source it used, `GpuFrame::wave_source`).
                Err(Error::Unavailable(_)) => Ok(Box::new(CpuUpload::new(gpu, surface)?)),
                Err(e) => Err(e),
            }
        }
    }
}

/// Stage `waves` on the GPU: the two [`GpuWaves`] FFT syntheses (displacement and bump map,
/// h0 uploaded once) run into the frame's encoder every frame; their textures are copied
/// into [`WaveTextures`] (the displacement map's displacement and slopes, the bump map's
/// bump texture).
pub struct GpuFft {
    displacement: GpuWaves,
    bump: GpuWaves,
    textures: WaveTextures,
}

impl GpuFft {
    /// Uploads both maps' modes and builds the pipelines.
    ///
    /// # Errors
    /// [`Error::Unavailable`] when the GPU FFT cannot take this ocean (a resolution that is
    /// not a power of two, or buffers the device cannot hold): [`WaveSynthesis::CpuUpload`]
    /// can.
    pub fn new(gpu: &Gpu, surface: OceanSurface) -> Result<Self, Error> {
        let unavailable = |e: WavesError| {
            Error::Unavailable(format!("stage `waves` on the GPU: {e}; use the CPU synthesis"))
        };
        // The FFT's dispatch form for this adapter (`FftKernel::for_adapter`): the same maps
        // either way.
        let waves = |modes: &ocean_core::waves::WaveModes| {
            let kernel = FftKernel::for_adapter(&gpu.info, modes.resolution());
            GpuWaves::with_kernel(&gpu.device, modes, kernel).map_err(unavailable)
        };
        let displacement = waves(&surface.displacement)?;
        let bump = waves(&surface.bump)?;
        let (n_d, n_b) = (surface.displacement.resolution(), surface.bump.resolution());
        Ok(Self {
            displacement,
            bump,
            textures: WaveTextures::new(&gpu.device, n_d as u32, n_b as u32),
        })
    }
}

fn copy(encoder: &mut wgpu::CommandEncoder, from: &wgpu::Texture, to: &GpuTexture) {
    encoder.copy_texture_to_texture(
        from.as_image_copy(),
        to.texture.as_image_copy(),
        wgpu::Extent3d { width: to.width, height: to.height, depth_or_array_layers: 1 },
    );
}

impl WaveMapSource for GpuFft {
    fn name(&self) -> &'static str {
        "gpu-fft"
    }

    fn records_gpu_passes(&self) -> bool {
        true
    }

    fn encode(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        t: f64,
        choppiness: f64,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<&WaveTextures, Error> {
        let core = |e: WavesError| match e {
            WavesError::Core(c) => Error::Core(c),
            other => Error::Unavailable(format!("stage `waves` on the GPU: {other}")),
        };
        // One timed span over both transforms: the first pass writes the beginning, the
        // second the end.
        let (first, second) = match timestamps {
            Some(ts) => (
                Some(wgpu::ComputePassTimestampWrites {
                    query_set: ts.query_set,
                    beginning_of_pass_write_index: ts.beginning_of_pass_write_index,
                    end_of_pass_write_index: None,
                }),
                Some(wgpu::ComputePassTimestampWrites {
                    query_set: ts.query_set,
                    beginning_of_pass_write_index: None,
                    end_of_pass_write_index: ts.end_of_pass_write_index,
                }),
            ),
            None => (None, None),
        };
        self.displacement.encode_timed(&gpu.queue, encoder, t, choppiness, first).map_err(core)?;
        self.bump.encode_timed(&gpu.queue, encoder, t, choppiness, second).map_err(core)?;
        copy(
            encoder,
            self.displacement.texture(WaveTexture::Displacement),
            &self.textures.displacement,
        );
        copy(
            encoder,
            self.displacement.texture(WaveTexture::DisplacementSlopes),
            &self.textures.displacement_slopes,
        );
        copy(encoder, self.bump.texture(WaveTexture::Bump), &self.textures.bump);
        Ok(&self.textures)
    }

    fn update(&mut self, gpu: &Gpu, surface: &OceanSurface) -> Result<bool, Error> {
        let same = surface.displacement.resolution() == self.displacement.resolution()
            && surface.bump.resolution() == self.bump.resolution();
        if !same {
            return Ok(false);
        }
        let fail = |e: WavesError| Error::Unavailable(format!("stage `waves` on the GPU: {e}"));
        self.displacement.update_modes(&gpu.queue, &surface.displacement).map_err(fail)?;
        self.bump.update_modes(&gpu.queue, &surface.bump).map_err(fail)?;
        Ok(true)
    }
}

/// Stage `waves` on the CPU (ocean-core's `Synthesizer<f32>`, as ocean-cpu's frame runs it
/// under `WavesKernel::Synthesis`), uploaded into [`WaveTextures`].
pub struct CpuUpload {
    surface: OceanSurface,
    displacement: Synthesizer<f32>,
    bump: Synthesizer<f32>,
    textures: WaveTextures,
}

impl CpuUpload {
    /// Plans the two FFTs and creates the textures.
    ///
    /// # Errors
    /// [`Error::Core`] for a resolution the synthesis refuses.
    pub fn new(gpu: &Gpu, surface: OceanSurface) -> Result<Self, Error> {
        let n_d = surface.displacement.resolution();
        let n_b = surface.bump.resolution();
        Ok(Self {
            displacement: Synthesizer::new(n_d)?,
            bump: Synthesizer::new(n_b)?,
            textures: WaveTextures::new(&gpu.device, n_d as u32, n_b as u32),
            surface,
        })
    }
}

/// Uploads `texels` into the whole of `texture` (ordered before the next submission).
pub(crate) fn write(gpu: &Gpu, texture: &GpuTexture, texels: &[[f32; 4]]) {
    gpu.queue.write_texture(
        texture.texture.as_image_copy(),
        bytemuck::cast_slice(texels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(texture.width * 16),
            rows_per_image: Some(texture.height),
        },
        wgpu::Extent3d { width: texture.width, height: texture.height, depth_or_array_layers: 1 },
    );
}

impl WaveMapSource for CpuUpload {
    fn name(&self) -> &'static str {
        "cpu-upload"
    }

    fn records_gpu_passes(&self) -> bool {
        false
    }

    fn encode(
        &mut self,
        gpu: &Gpu,
        _encoder: &mut wgpu::CommandEncoder,
        t: f64,
        choppiness: f64,
        _timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<&WaveTextures, Error> {
        let d: WaveMaps<f32> =
            self.displacement.synthesize(&self.surface.displacement, t, choppiness)?;
        let b: WaveMaps<f32> = self.bump.synthesize(&self.surface.bump, t, choppiness)?;
        write(gpu, &self.textures.displacement, &displacement_texels(&d));
        write(gpu, &self.textures.displacement_slopes, &displacement_slope_texels(&d));
        write(gpu, &self.textures.bump, &bump_texels(&b));
        Ok(&self.textures)
    }
}
