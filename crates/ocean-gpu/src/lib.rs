//! The wgpu real-time path of `ocean`: every stage of each system's frame (Hu, Chiu, Welch,
//! coastal) from the WGSL in `shaders/`, run by the same [`ocean_core::plan::FramePlan`] as
//! the CPU oracle (`ocean-cpu`), with every intermediate map readable for the cross-check.
//!
//! - [`device`]: headless adapter/device setup, the crate's [`Error`].
//! - one module per stage, each creating its pipeline(s) labelled `"ocean.<stage>"` from
//!   `ocean_core::shader_source::stage_source` and recording its pass: [`fresnel_table`],
//!   [`sky`], [`objects`], [`shadow`], [`water`], [`tonemap`], [`foam`] (foam `accumulated`'s
//!   field); stage `waves` is
//!   [`wave_maps`] (the CPU synthesis uploaded, or the GPU FFT of [`waves`]); [`present`]
//!   copies the output into a window (the real-time viewer, `ocean view`).
//! - [`frame`]: the [`Renderer`] and the [`GpuFrame`] it returns.
//! - [`embed`]: the sea inside someone else's wgpu program: [`EmbeddedOcean`] records a
//!   frame into the caller's encoder and composites it ([`composite`]) into the caller's
//!   colour target and depth buffer, seen through the caller's camera matrices at the
//!   caller's clock (`examples/embed.rs`: a winit window with its own objects;
//!   `examples/buoy.rs`: an object floating on the drawn sea by the height query).
//! - [`texture`]: formats, render targets, readback; [`timing`]: GPU time per pass.
//!
//! Headless, on a device of its own (the `ocean render --backend gpu` path):
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
pub mod composite;
pub mod created;
pub mod device;
pub mod embed;
pub mod foam;
pub mod frame;
pub mod fresnel_table;
pub mod objects;
pub mod pool;
pub mod present;
pub mod readback;
pub mod shading_path;
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
pub use embed::EmbeddedOcean;
pub use frame::{EncodeSplit, FrameMap, GpuFrame, Readback, Renderer};
/// The glam the embedding API's [`embed::CameraView`] takes its matrices in.
pub use glam;
pub use readback::FloatMap;
pub use shading_path::ShadingPath;
pub use wave_maps::{WaveMapSource, WaveSynthesis};
