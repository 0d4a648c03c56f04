//! Output files: written under a temporary name beside the target and renamed into place, so
//! an interrupted or failed run never leaves a broken file behind.

use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};

/// The folder an output goes to and the temporary name it is first written under; errors for
/// a path without a file name, a missing folder, or a path that is a folder.
fn target(path: &Path) -> anyhow::Result<(PathBuf, PathBuf)> {
    let file_name = path
        .file_name()
        .with_context(|| format!("output path {} has no file name", path.display()))?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if !dir.is_dir() {
        bail!("cannot write {}: folder {} does not exist", path.display(), dir.display());
    }
    if path.is_dir() {
        bail!("cannot write {}: it is a folder", path.display());
    }
    let tmp = dir.join(format!(".{}.tmp-{}", file_name.to_string_lossy(), std::process::id()));
    Ok((dir, tmp))
}

/// Checks, before any work, that [`write_atomic`] will be able to write `path`: its folder
/// exists and takes a new file (the temporary is created and removed), and `path` is not a
/// folder. A render of minutes then never ends in "cannot write".
///
/// # Errors
/// What [`write_atomic`] would report.
pub fn check_writable(path: &Path) -> anyhow::Result<()> {
    let (_, tmp) = target(path)?;
    std::fs::File::create(&tmp).with_context(|| format!("cannot write {}", path.display()))?;
    std::fs::remove_file(&tmp).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// Writes `bytes` to `path` atomically (temporary file in the same folder, then rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let (_, tmp) = target(path)?;
    let result = (|| -> std::io::Result<()> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(e).with_context(|| format!("cannot write {}", path.display()));
    }
    Ok(())
}

/// One named f32 channel of an image, row-major (x fastest), top row first.
pub struct Channel<'a> {
    /// EXR channel name.
    pub name: &'a str,
    /// width × height samples.
    pub data: Vec<f32>,
}

/// Encodes named f32 channels as a single-layer EXR (lossless ZIP compression) in memory.
pub fn encode_exr(
    width: usize,
    height: usize,
    channels: Vec<Channel<'_>>,
) -> anyhow::Result<Vec<u8>> {
    use exr::prelude::*;
    let list: Vec<AnyChannel<FlatSamples>> = channels
        .into_iter()
        .map(|c| {
            debug_assert_eq!(c.data.len(), width * height);
            AnyChannel::new(c.name, FlatSamples::F32(c.data))
        })
        .collect();
    let layer = Layer::new(
        (width, height),
        LayerAttributes::named("ocean"),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(list.into()),
    );
    let mut buf = Cursor::new(Vec::new());
    Image::from_layer(layer).write().to_buffered(&mut buf).context("cannot encode EXR")?;
    Ok(buf.into_inner())
}

/// Checks that an output path ends in the given extension (case-insensitive).
pub fn require_extension(path: &Path, ext: &str) -> anyhow::Result<()> {
    let ok = path.extension().is_some_and(|e| e.eq_ignore_ascii_case(ext));
    if !ok {
        bail!("output {} must end in .{ext}", path.display());
    }
    Ok(())
}

/// Encodes 8-bit RGBA rows (top row first) as PNG.
pub fn encode_png(rgba: Vec<u8>, width: u32, height: u32) -> anyhow::Result<Vec<u8>> {
    let img = image::RgbaImage::from_raw(width, height, rgba).with_context(|| {
        format!(
            "an RGBA image of {width}×{height} needs {} bytes",
            4 * width as usize * height as usize
        )
    })?;
    let mut buf = Cursor::new(Vec::new());
    img.write_to(&mut buf, image::ImageFormat::Png).context("cannot encode PNG")?;
    Ok(buf.into_inner())
}

/// Parses `WIDTHxHEIGHT`.
pub fn parse_size(s: &str) -> anyhow::Result<(u32, u32)> {
    let (w, h) = s
        .split_once(['x', 'X', '×'])
        .with_context(|| format!("--size must be WIDTHxHEIGHT, e.g. 1280x720, got {s:?}"))?;
    let parse = |v: &str| -> anyhow::Result<u32> {
        // Parsed wide, so that a negative or huge side gets the range error, not a parse one.
        let n: i128 = v.trim().parse().with_context(|| format!("--size: {v:?} is not a number"))?;
        let max = ocean_core::scene::MAX_IMAGE_SIDE;
        match u32::try_from(n) {
            Ok(n) if (1..=max).contains(&n) => Ok(n),
            _ => bail!("--size: each side must be 1..={max}, got {n}"),
        }
    };
    Ok((parse(w)?, parse(h)?))
}

/// `--seed`: a whole number ≥ 0 (the generator's seed is a u64), with a range error for a
/// negative one.
///
/// # Errors
/// A value that is not a whole number in 0..=2⁶⁴−1.
pub fn parse_seed(s: &str) -> Result<u64, String> {
    match s.trim().parse::<i128>() {
        Ok(n) => u64::try_from(n).map_err(|_| format!("must be 0..={}, got {n}", u64::MAX)),
        Err(_) => Err(format!("{s:?} is not a whole number")),
    }
}
