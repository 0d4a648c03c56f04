//! Output files: written under a temporary name beside the target and renamed into place, so
//! an interrupted or failed run never leaves a broken file behind.

use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::{Context, bail};

use ocean_core::input::kind_of;

/// Where an output really goes: `path` itself when it does not exist or is a regular file; the
/// file a symbolic link names when that is a regular file (written through: the link stays a
/// link). Anything else — a device node, a FIFO, a socket, a folder, a link to one of them or
/// to nothing — is refused, since the temporary renamed over it would replace what is not
/// ocean's (as root, `-o n` with `n` a device node turned the node into a JSON file).
fn resolve(path: &Path) -> anyhow::Result<PathBuf> {
    let Ok(meta) = std::fs::symlink_metadata(path) else { return Ok(path.to_owned()) };
    let t = meta.file_type();
    if t.is_file() {
        return Ok(path.to_owned());
    }
    if t.is_dir() {
        bail!("cannot write {}: it is a folder", path.display());
    }
    if !t.is_symlink() {
        bail!(
            "cannot write {}: it exists and is {}; ocean replaces only regular files",
            path.display(),
            kind_of(t)
        );
    }
    let real = std::fs::canonicalize(path).with_context(|| {
        format!("cannot write {}: it is a link to a file that does not exist", path.display())
    })?;
    let t = std::fs::metadata(&real)
        .with_context(|| format!("cannot write {}", path.display()))?
        .file_type();
    if !t.is_file() {
        bail!(
            "cannot write {}: it is a link to {}, which is {}; ocean replaces only regular files",
            path.display(),
            real.display(),
            kind_of(t)
        );
    }
    Ok(real)
}

/// The folder an output goes to, the temporary name it is first written under and the path
/// the temporary is renamed to ([`resolve`]); errors for a path without a file name, a missing
/// folder, or a path that is not (a link to) a regular file.
fn target(path: &Path) -> anyhow::Result<(PathBuf, String, PathBuf)> {
    let real = resolve(path)?;
    let file_name = real
        .file_name()
        .with_context(|| format!("output path {} has no file name", path.display()))?;
    let path = &real;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if !dir.is_dir() {
        bail!("cannot write {}: folder {} does not exist", path.display(), dir.display());
    }
    let prefix = format!(".{}.tmp-", file_name.to_string_lossy());
    Ok((dir, prefix, real))
}

/// The temporaries being written now, removed by the SIGINT/SIGTERM handler
/// ([`remove_temporaries_on_interrupt`]).
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    // A poisoned list is still a list of paths to remove.
    PENDING.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Whether process `pid` is alive (Linux: its `/proc` entry). Elsewhere every process counts
/// as alive, so nothing is removed that might still be written.
fn alive(pid: u32) -> bool {
    !Path::new("/proc/self").exists() || Path::new(&format!("/proc/{pid}")).exists()
}

/// Removes the temporaries of `prefix` (`.NAME.tmp-`) that a dead process left in `dir` (a
/// run killed with SIGKILL cannot clean up after itself). Returns how many.
fn remove_stale(dir: &Path, prefix: &str) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else { return 0 };
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(|n| n.strip_prefix(prefix)) else { continue };
        let Ok(pid) = pid.parse::<u32>() else { continue };
        if pid == std::process::id() || alive(pid) {
            continue;
        }
        let path = entry.path();
        let gone = if path.is_dir() {
            std::fs::remove_dir_all(&path).is_ok()
        } else {
            std::fs::remove_file(&path).is_ok()
        };
        if gone {
            removed += 1;
        }
    }
    removed
}

/// An output file reserved before the work that makes it: its temporary (`.NAME.tmp-PID`
/// beside it) exists from [`Self::reserve`] on, so an unwritable path fails at once, and it is
/// removed on an error, on SIGINT/SIGTERM, or (after SIGKILL) by the next run that writes the
/// same name. [`Self::commit`] writes the bytes and renames the temporary into place.
pub struct OutputFile {
    /// The path asked for, for messages.
    path: PathBuf,
    /// What the temporary is renamed to: the path, or the regular file a link at it names.
    real: PathBuf,
    tmp: PathBuf,
    file: Option<std::fs::File>,
}

impl OutputFile {
    /// Checks the path and creates its temporary.
    ///
    /// # Errors
    /// A path without a file name, a missing folder, a path that is a folder, or a folder that
    /// takes no new file.
    pub fn reserve(path: &Path) -> anyhow::Result<Self> {
        let (dir, prefix, real) = target(path)?;
        remove_stale(&dir, &prefix);
        let tmp = dir.join(format!("{prefix}{}", std::process::id()));
        pending().push(tmp.clone());
        let file = std::fs::File::create(&tmp);
        let file = match file {
            Ok(f) => f,
            Err(e) => {
                pending().retain(|p| *p != tmp);
                return Err(e).with_context(|| format!("cannot write {}", path.display()));
            }
        };
        Ok(Self { path: path.to_owned(), real, tmp, file: Some(file) })
    }

    /// Writes `bytes` and renames the temporary to the path.
    ///
    /// # Errors
    /// An I/O error (the temporary is removed).
    pub fn commit(mut self, bytes: &[u8]) -> anyhow::Result<()> {
        let result = (|| -> std::io::Result<()> {
            let mut f = self.file.take().ok_or_else(|| std::io::Error::other("already written"))?;
            f.write_all(bytes)?;
            f.sync_all()?;
            drop(f);
            std::fs::rename(&self.tmp, &self.real)
        })();
        result.with_context(|| format!("cannot write {}", self.path.display()))
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        // After a commit the temporary is renamed away: removing it then fails harmlessly.
        let _ = std::fs::remove_file(&self.tmp);
        pending().retain(|p| *p != self.tmp);
    }
}

/// A folder of outputs written under a temporary name beside its target (`.NAME.tmp-PID`) and
/// renamed into place whole by [`Self::publish`], so that a failure half-way (a full disk)
/// or an interrupt leaves no partial folder: it is removed on an error, on drop and on
/// SIGINT/SIGTERM.
pub struct StagingDir {
    target: PathBuf,
    tmp: PathBuf,
    published: bool,
}

impl StagingDir {
    /// Creates the temporary folder beside `target`.
    ///
    /// # Errors
    /// A target without a name, one that exists and is not a folder, or a parent folder that
    /// takes no new folder.
    pub fn create(target: &Path) -> anyhow::Result<Self> {
        let name = target
            .file_name()
            .with_context(|| format!("output folder {} has no name", target.display()))?;
        if let Ok(m) = std::fs::symlink_metadata(target)
            && !m.is_dir()
        {
            bail!(
                "cannot write the folder {}: it exists and is {}",
                target.display(),
                kind_of(m.file_type())
            );
        }
        let parent = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent)
            .with_context(|| format!("cannot make the folder {}", parent.display()))?;
        let prefix = format!(".{}.tmp-", name.to_string_lossy());
        remove_stale(&parent, &prefix);
        let tmp = parent.join(format!("{prefix}{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&tmp);
        pending().push(tmp.clone());
        if let Err(e) = std::fs::create_dir(&tmp) {
            pending().retain(|p| *p != tmp);
            return Err(e).with_context(|| format!("cannot write the folder {}", target.display()));
        }
        Ok(Self { target: target.to_owned(), tmp, published: false })
    }

    /// The temporary folder, to write the files into.
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// Puts the folder in place. A folder already at the target is replaced when it is empty
    /// or `replaceable` says so (a previous dump); otherwise it is kept and this is an error.
    ///
    /// # Errors
    /// A target that holds something else, or a rename that fails.
    pub fn publish(mut self, replaceable: impl Fn(&Path) -> bool) -> anyhow::Result<()> {
        let target = self.target.clone();
        if target.is_dir() {
            let empty = std::fs::read_dir(&target).is_ok_and(|mut d| d.next().is_none());
            if !empty && !replaceable(&target) {
                bail!(
                    "{} exists and holds files that are not ocean's: choose a new or an empty \
                     folder",
                    target.display()
                );
            }
            let mut old = self.tmp.clone().into_os_string();
            old.push("-old");
            let old = PathBuf::from(old);
            std::fs::rename(&target, &old)
                .with_context(|| format!("cannot replace {}", target.display()))?;
            if let Err(e) = std::fs::rename(&self.tmp, &target) {
                let _ = std::fs::rename(&old, &target);
                return Err(e).with_context(|| format!("cannot write {}", target.display()));
            }
            let _ = std::fs::remove_dir_all(&old);
        } else {
            std::fs::rename(&self.tmp, &target)
                .with_context(|| format!("cannot write {}", target.display()))?;
        }
        self.published = true;
        Ok(())
    }
}

impl Drop for StagingDir {
    fn drop(&mut self) {
        if !self.published {
            let _ = std::fs::remove_dir_all(&self.tmp);
        }
        pending().retain(|p| *p != self.tmp);
    }
}

/// Installs the SIGINT/SIGTERM handler of the command line: it removes every temporary being
/// written and exits with status 130, so an interrupted run leaves no `.NAME.tmp-PID` behind.
///
/// # Errors
/// If a handler is already installed.
pub fn remove_temporaries_on_interrupt() -> anyhow::Result<()> {
    ctrlc::set_handler(|| {
        let paths: Vec<PathBuf> = pending().drain(..).collect();
        for p in &paths {
            if p.is_dir() {
                let _ = std::fs::remove_dir_all(p);
            } else {
                let _ = std::fs::remove_file(p);
            }
        }
        eprintln!("interrupted: stopped, {} temporary file(s) removed", paths.len());
        std::process::exit(130);
    })
    .context("cannot install the interrupt handler")
}

/// Writes `bytes` to `path` atomically (temporary file in the same folder, then rename).
///
/// # Errors
/// As [`OutputFile::reserve`] and [`OutputFile::commit`].
pub fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    OutputFile::reserve(path)?.commit(bytes)
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
