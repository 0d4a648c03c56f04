//! Reading textures back: `copy_texture_to_buffer` needs rows padded to
//! `wgpu::COPY_BYTES_PER_ROW_ALIGNMENT` (256 bytes); [`Readbacks`] records the copies of a
//! frame into its command encoder, maps every buffer after the one submission and strips the
//! padding. The staging buffers of a renderer's frames come from its [`FramePool`].

use std::sync::{Arc, Mutex};

use crate::created::Counted;
use crate::device::{Error, Gpu};
use crate::pool::FramePool;
use crate::texture::{GpuTexture, HALF_FORMAT, LDR_FORMAT, MAP_FORMAT, SHADOW_FORMAT};

/// An `Rgba32Float` map read back from the GPU: the layout of ocean-cpu's `Texture2D`
/// (row-major, texel (i, j) at `j · width + i`, row 0 at the top).
#[derive(Clone, Debug, PartialEq)]
pub struct FloatMap {
    /// Width, texels.
    pub width: u32,
    /// Height, texels.
    pub height: u32,
    /// `width · height` texels.
    pub texels: Vec<[f32; 4]>,
}

/// What a readback holds.
#[derive(Clone, Debug, PartialEq)]
pub enum TexelData {
    /// A float texture (`R32Float` as (r, 0, 0, 0)).
    Float(FloatMap),
    /// `Rgba8Unorm` bytes, 4 per pixel, row-major.
    Rgba8(Vec<u8>),
}

/// One texture copy waiting for its buffer to be mapped.
struct Pending<K> {
    key: K,
    label: String,
    buffer: wgpu::Buffer,
    width: u32,
    height: u32,
    bytes_per_texel: u32,
    padded_row: u32,
    format: wgpu::TextureFormat,
}

/// Where a buffer's `map_async` leaves its result: `None` until the device is polled after
/// the GPU finished with the buffer.
pub(crate) type MapState = Arc<Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>;

/// Starts mapping `slice` for reading; the result arrives in the returned state.
pub(crate) fn map_for_reading(slice: wgpu::BufferSlice<'_>) -> MapState {
    let state: MapState = Arc::new(Mutex::new(None));
    let slot = Arc::clone(&state);
    slice.map_async(wgpu::MapMode::Read, move |r| {
        if let Ok(mut s) = slot.lock() {
            *s = Some(r);
        }
    });
    state
}

/// Maps the whole of `buffer` (MAP_READ, its copy already submitted) for reading, waits for
/// the device, and copies its bytes out; the error's text otherwise.
pub(crate) fn map_read_bytes(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
) -> Result<Vec<u8>, String> {
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |r| {
        // The receiver outlives the wait below; a failed send only means nobody listens.
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| e.to_string())?;
    rx.recv().map_err(|e| e.to_string())?.map_err(|e| e.to_string())?;
    let bytes = buffer.get_mapped_range(..).map_err(|e| e.to_string())?.to_vec();
    buffer.unmap();
    Ok(bytes)
}

/// The texture copies of one submission.
pub struct Readbacks<K> {
    pending: Vec<Pending<K>>,
    kept: Option<FramePool>,
}

impl<K> Default for Readbacks<K> {
    fn default() -> Self {
        Self { pending: Vec::new(), kept: None }
    }
}

impl<K: Copy> Readbacks<K> {
    /// Copies whose staging buffers come from `kept` (a renderer's frames: the same buffers
    /// frame after frame) instead of being made for this submission.
    pub fn kept(kept: &FramePool) -> Self {
        Self { pending: Vec::new(), kept: Some(kept.clone()) }
    }

    /// Records a copy of `texture` (of `format`: [`MAP_FORMAT`], [`HALF_FORMAT`],
    /// [`SHADOW_FORMAT`] or [`LDR_FORMAT`]) into `encoder`, to be read back under `key`.
    ///
    /// # Panics
    /// On another format (a bug in the caller).
    pub fn copy(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        key: K,
        label: &str,
        texture: &GpuTexture,
        format: wgpu::TextureFormat,
    ) {
        self.copy_texture(device, encoder, key, label, &texture.texture, format);
    }

    /// [`Self::copy`] of any texture with `COPY_SRC`, e.g. a window's surface texture;
    /// `Bgra8Unorm` texels are also accepted and come back as RGBA bytes.
    ///
    /// # Panics
    /// On a format without a readback (a bug in the caller).
    pub fn copy_texture(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        key: K,
        label: &str,
        texture: &wgpu::Texture,
        format: wgpu::TextureFormat,
    ) {
        let bytes_per_texel = match format {
            MAP_FORMAT => 16,
            HALF_FORMAT => 8,
            SHADOW_FORMAT | LDR_FORMAT | wgpu::TextureFormat::Bgra8Unorm => 4,
            other => panic!("no readback for {other:?}"),
        };
        let (width, height) = (texture.width(), texture.height());
        let row = width * bytes_per_texel;
        let padded_row =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer_label = format!("ocean.readback.{label}");
        let size = u64::from(padded_row) * u64::from(height);
        let buffer = match &self.kept {
            Some(kept) => kept.staging(&buffer_label, size),
            None => device.new_buffer(&wgpu::BufferDescriptor {
                label: Some(&buffer_label),
                size,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            }),
        };
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        );
        self.pending.push(Pending {
            key,
            label: label.to_owned(),
            buffer,
            width,
            height,
            bytes_per_texel,
            padded_row,
            format,
        });
    }

    /// Maps every buffer (after the encoder that holds the copies was submitted) and returns
    /// the texels, in the order of the copies.
    ///
    /// # Errors
    /// [`Error::Readback`] if a buffer cannot be mapped.
    pub fn finish(self, gpu: &Gpu) -> Result<Vec<(K, TexelData)>, Error> {
        let Self { pending, kept } = self;
        let read = Self::read(pending, gpu);
        if read.is_err()
            && let Some(kept) = kept
        {
            // A failed read may leave a buffer mapped: the next frame gets new ones.
            kept.drop_staging();
        }
        read
    }

    fn read(pending: Vec<Pending<K>>, gpu: &Gpu) -> Result<Vec<(K, TexelData)>, Error> {
        if pending.is_empty() {
            // Nothing to read: no reason to wait for the GPU.
            return Ok(Vec::new());
        }
        let results: Vec<MapState> =
            pending.iter().map(|p| map_for_reading(p.buffer.slice(..))).collect();
        gpu.wait()?;
        let mut out = Vec::with_capacity(pending.len());
        for (p, slot) in pending.into_iter().zip(results) {
            let fail = |message: String| Error::Readback { what: p.label.clone(), message };
            let status = slot.lock().map_err(|_| fail("poisoned lock".into()))?.take();
            match status {
                Some(Ok(())) => {}
                Some(Err(e)) => return Err(fail(e.to_string())),
                None => return Err(fail("the buffer was not mapped after the wait".into())),
            }
            let data = {
                let view =
                    p.buffer.slice(..).get_mapped_range().map_err(|e| fail(e.to_string()))?;
                let row = (p.width * p.bytes_per_texel) as usize;
                let rows = (0..p.height as usize)
                    .map(|y| &view[y * p.padded_row as usize..y * p.padded_row as usize + row]);
                match p.format {
                    LDR_FORMAT => TexelData::Rgba8(rows.flatten().copied().collect()),
                    wgpu::TextureFormat::Bgra8Unorm => TexelData::Rgba8(
                        rows.flat_map(|r| r.chunks_exact(4))
                            .flat_map(|c| [c[2], c[1], c[0], c[3]])
                            .collect(),
                    ),
                    SHADOW_FORMAT => {
                        let texels = rows
                            .flat_map(|r| r.chunks_exact(4))
                            .map(|c| [f32::from_le_bytes([c[0], c[1], c[2], c[3]]), 0.0, 0.0, 0.0])
                            .collect();
                        TexelData::Float(FloatMap { width: p.width, height: p.height, texels })
                    }
                    HALF_FORMAT => {
                        // binary16 → f32 is exact: the values the texture holds.
                        let texels = rows
                            .flat_map(|r| r.chunks_exact(8))
                            .map(|c| {
                                std::array::from_fn(|k| {
                                    half::f16::from_le_bytes([c[2 * k], c[2 * k + 1]]).to_f32()
                                })
                            })
                            .collect();
                        TexelData::Float(FloatMap { width: p.width, height: p.height, texels })
                    }
                    _ => {
                        let texels = rows
                            .flat_map(|r| r.chunks_exact(16))
                            .map(|c| {
                                std::array::from_fn(|k| {
                                    f32::from_le_bytes([
                                        c[4 * k],
                                        c[4 * k + 1],
                                        c[4 * k + 2],
                                        c[4 * k + 3],
                                    ])
                                })
                            })
                            .collect();
                        TexelData::Float(FloatMap { width: p.width, height: p.height, texels })
                    }
                }
            };
            p.buffer.unmap();
            out.push((p.key, data));
        }
        Ok(out)
    }
}
