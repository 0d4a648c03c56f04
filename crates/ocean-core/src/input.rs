//! Files that come in from outside (scene files, heightmaps, a dump's manifest and maps): each
//! is checked before anything sized by its content is allocated.
//!
//! A hostile or mistaken file must cost little before it is refused: only regular files are
//! opened (a FIFO would block forever, `/dev/zero` would never end), text is read up to a
//! stated bound, and an image's header is read and its size and decoding cost checked against
//! [`decode_budget`] before its pixels are decoded (an EXR of 393 KB whose header claimed
//! 32768² texels reached 8.4 GB before the size check, when the check came after decoding).

use std::io::Read;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// The budget set by [`set_decode_budget`]; 0 = [`crate::sizes::default_limit`].
static DECODE_BUDGET: AtomicU64 = AtomicU64::new(0);

/// Sets the most memory that decoding one input image may take (the command line's
/// `--memory-limit`), for the rest of the process.
pub fn set_decode_budget(bytes: u64) {
    DECODE_BUDGET.store(bytes.max(1), Ordering::Relaxed);
}

/// The most memory that decoding one input image may take: [`set_decode_budget`]'s, else the
/// frame's default limit (three quarters of the machine's memory).
pub fn decode_budget() -> u64 {
    match DECODE_BUDGET.load(Ordering::Relaxed) {
        0 => crate::sizes::default_limit(),
        b => b,
    }
}

/// What a path that is not a regular file is ("a character device", "a named pipe (FIFO)",
/// "a folder", ...), for messages.
pub fn kind_of(t: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_fifo() {
            return "a named pipe (FIFO)";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() { "a folder" } else { "not a regular file" }
}

/// The metadata of `path` (links followed) when it is a regular file.
///
/// # Errors
/// `"PATH: what is wrong"` for a missing file, or one that is a folder, a device, a FIFO or a
/// socket (a FIFO would block the reader until someone writes to it).
pub fn regular_file(path: &Path) -> Result<std::fs::Metadata, String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if !meta.is_file() {
        return Err(format!(
            "{}: is {}, not a regular file",
            path.display(),
            kind_of(meta.file_type())
        ));
    }
    Ok(meta)
}

/// Reads a regular file of at most `max_bytes` whole.
///
/// # Errors
/// As [`regular_file`], a file larger than `max_bytes` (checked before reading, and again
/// while reading, as a file may grow), or an I/O error; each names the file.
pub fn read_bounded(path: &Path, max_bytes: u64) -> Result<Vec<u8>, String> {
    let meta = regular_file(path)?;
    let too_large = || {
        format!(
            "{}: larger than {} ({} bytes), the most this file may hold",
            path.display(),
            crate::sizes::bytes(max_bytes),
            max_bytes
        )
    };
    if meta.len() > max_bytes {
        return Err(too_large());
    }
    let file = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large());
    }
    Ok(bytes)
}

/// Reads a regular UTF-8 text file of at most `max_bytes`.
///
/// # Errors
/// As [`read_bounded`], or text that is not UTF-8 (with the offset of the first bad byte).
pub fn read_text(path: &Path, max_bytes: u64) -> Result<String, String> {
    String::from_utf8(read_bounded(path, max_bytes)?).map_err(|e| {
        format!(
            "{}: not UTF-8 text (an invalid byte at offset {})",
            path.display(),
            e.utf8_error().valid_up_to()
        )
    })
}

/// Checks an image's size, read from its header, before its pixels are decoded: each side
/// 1..=`max_side`, and `bytes_per_texel` × the texels (what decoding it allocates, its
/// conversions included) within [`decode_budget`].
///
/// # Errors
/// A message naming the file, its size and the limit it breaks.
pub fn check_image_size(
    path: &Path,
    (width, height): (u64, u64),
    max_side: u64,
    bytes_per_texel: u64,
) -> Result<(), String> {
    if width == 0 || height == 0 || width > max_side || height > max_side {
        return Err(format!(
            "{}: the image is {width}×{height} texels; it must be 1 to {max_side} per side",
            path.display()
        ));
    }
    let need = width.saturating_mul(height).saturating_mul(bytes_per_texel);
    let budget = decode_budget();
    if need > budget {
        return Err(format!(
            "{}: decoding its {width}×{height} texels needs about {}, more than the memory \
             limit of {} (--memory-limit)",
            path.display(),
            crate::sizes::bytes(need),
            crate::sizes::bytes(budget)
        ));
    }
    Ok(())
}

/// The header of an EXR file: its first layer's size and the bytes per texel of all its
/// channels together, read without its pixels.
///
/// # Errors
/// A file that is not a regular file or not an EXR, or one without a layer.
pub fn exr_header(path: &Path) -> Result<((u64, u64), u64), String> {
    regular_file(path)?;
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let header =
        meta.headers.first().ok_or_else(|| format!("{}: the EXR has no layer", path.display()))?;
    let size = header.layer_size;
    let bytes: u64 = header
        .channels
        .list
        .iter()
        .map(|c| match c.sample_type {
            exr::meta::attribute::SampleType::F16 => 2,
            exr::meta::attribute::SampleType::F32 | exr::meta::attribute::SampleType::U32 => 4,
        })
        .sum();
    Ok(((size.width() as u64, size.height() as u64), bytes))
}

/// Reads a PNG's size from its header (the decoder reads no pixel for it).
///
/// # Errors
/// A file that is not a regular file or not a readable PNG.
pub fn png_size(path: &Path) -> Result<(u64, u64), String> {
    regular_file(path)?;
    let reader = image::ImageReader::open(path)
        .and_then(image::ImageReader::with_guessed_format)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let (w, h) = reader.into_dimensions().map_err(|e| format!("{}: {e}", path.display()))?;
    Ok((u64::from(w), u64::from(h)))
}

/// Decodes an image whose size [`check_image_size`] accepted, with the decoder's own
/// allocations held to [`decode_budget`] as well.
///
/// # Errors
/// A file that does not decode.
pub fn decode_png(path: &Path) -> Result<image::DynamicImage, String> {
    let mut reader = image::ImageReader::open(path)
        .and_then(image::ImageReader::with_guessed_format)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(decode_budget());
    reader.limits(limits);
    reader.decode().map_err(|e| format!("{}: {e}", path.display()))
}
