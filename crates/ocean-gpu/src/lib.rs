//! The wgpu real-time path of `ocean`: every stage of the frame of Hu et al. 2004 from the
//! WGSL in `shaders/`, run by the same [`ocean_core::plan::FramePlan`] as the CPU oracle
//! (`ocean-cpu`), with every intermediate map readable for the cross-check.
//!
//! - [`device`]: headless adapter/device setup, the crate's [`Error`].
//! - one module per stage, each creating its pipeline(s) labelled `"ocean.<stage>"` from
//!   `ocean_core::shader_source::stage_source` and recording its pass: [`fresnel_table`],
//!   [`sky`], [`objects`], [`shadow`], [`water`], [`tonemap`], [`foam`] (foam `accumulated`'s
//!   field); stage `waves` is
//!   [`wave_maps`] (the CPU synthesis uploaded, or the GPU FFT of [`waves`]); [`present`]
//!   copies the output into a window (the real-time viewer, `ocean view`).
//! - [`frame`]: the [`Renderer`] and the [`GpuFrame`] it returns.
//! - [`texture`]: formats, render targets, readback; [`timing`]: GPU time per pass.
//!
//! ```no_run
//! use ocean_core::plan::{FramePlan, OutputKind};
//! let scene = ocean_core::scene::Scene::builtin();
//! let plan = FramePlan::new(&scene, OutputKind::Ldr);
//! let mut renderer = ocean_gpu::Renderer::new()?;
//! let frame = renderer.run(&scene, &plan)?;
//! println!("{} on {}", frame.ldr.map_or(0, |b| b.len()), frame.adapter);
//! # Ok::<(), ocean_gpu::Error>(())
//! ```

pub mod bloom;
pub mod common;
pub mod device;
pub mod foam;
pub mod frame;
pub mod fresnel_table;
pub mod objects;
pub mod present;
pub mod shadow;
pub mod sky;
pub mod spray;
pub mod texture;
pub mod timing;
pub mod tonemap;
pub mod water;
pub mod wave_maps;
pub mod wave_mips;
pub mod waves;

pub use device::{AdapterReport, Error, Gpu};
pub use frame::{FrameMap, GpuFrame, Readback, Renderer};
pub use texture::FloatMap;
pub use wave_maps::{WaveMapSource, WaveSynthesis};
