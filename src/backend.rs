//! What `ocean render` and its animations share: the back end a frame is drawn on, and the
//! file a frame becomes.

use anyhow::Context;
use ocean_core::plan::OutputKind;

use ocean::output::{Channel, encode_exr, encode_png};

/// Render back ends.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub(crate) enum Backend {
    /// The deterministic software renderer (the correctness oracle).
    Cpu,
    /// The wgpu real-time path.
    Gpu,
}

impl Backend {
    /// The memory estimate's side of this back end.
    pub(crate) fn memory(self) -> ocean_core::plan::memory::MemoryBackend {
        match self {
            Self::Cpu => ocean_core::plan::memory::MemoryBackend::Cpu,
            Self::Gpu => ocean_core::plan::memory::MemoryBackend::Gpu,
        }
    }
}

/// A frame's file: the 8-bit picture as PNG, or the linear HDR frame as an RGBA EXR.
pub(crate) fn encode(
    kind: OutputKind,
    ldr: Option<Vec<u8>>,
    hdr: &[[f32; 4]],
    w: u32,
    h: u32,
) -> anyhow::Result<Vec<u8>> {
    Ok(match kind {
        OutputKind::Ldr => {
            let rgba = ldr.context("the plan has no tonemap pass")?;
            encode_png(rgba, w, h)?
        }
        OutputKind::Hdr => {
            let channel = |c: usize| hdr.iter().map(|p| p[c]).collect::<Vec<f32>>();
            let channels = ["R", "G", "B", "A"]
                .iter()
                .enumerate()
                .map(|(c, name)| Channel { name, data: channel(c) })
                .collect();
            encode_exr(w as usize, h as usize, channels)?
        }
    })
}
