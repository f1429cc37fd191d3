//! Standard output that reports a closed pipe instead of panicking, and
//! output files written all at once: a temporary file beside the target,
//! renamed into place only when complete, so a failure or an interrupt never
//! leaves a half-written file. The temporary file is created before any GPU
//! work, so an unwritable path fails at once.
//!
//! An interrupt (Ctrl-C, SIGTERM) ends the process without running
//! destructors, so temporaries are also registered with [`remove_on_interrupt`]:
//! the signal handler deletes what is registered and exits with 130. Moving
//! a finished output into place happens inside [`uninterrupted`], which the
//! handler waits for, so an interrupt never falls between two renames.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, Once};

use anyhow::{Context, Result};

/// Temporary files and directories to delete if the process is interrupted.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
/// Held while outputs move into place; the handler waits for it.
static MOVING: Mutex<()> = Mutex::new(());
static HANDLER: Once = Once::new();

fn lock<T>(m: &'static Mutex<T>) -> MutexGuard<'static, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

fn temporaries() -> MutexGuard<'static, Vec<PathBuf>> {
    lock(&TEMPORARIES)
}

/// Deletes `path` (a file or a directory tree) if the process is
/// interrupted before the returned guard is dropped.
pub fn remove_on_interrupt(path: &Path) -> InterruptGuard {
    HANDLER.call_once(|| {
        // If no handler can be installed (another one is), an interrupt
        // simply leaves the temporaries, as before.
        let _ = ctrlc::set_handler(|| {
            let _moving = lock(&MOVING);
            let paths = std::mem::take(&mut *temporaries());
            for path in paths {
                if path.is_dir() {
                    std::fs::remove_dir_all(&path).ok();
                } else {
                    std::fs::remove_file(&path).ok();
                }
            }
            eprintln!("interrupted: temporary outputs removed");
            exit_now(130);
        });
    });
    temporaries().push(path.to_path_buf());
    InterruptGuard {
        path: path.to_path_buf(),
    }
}

/// Ends the process at once, without `exit`'s atexit handlers and static
/// destructors: they tear down the Vulkan driver while another thread is
/// still rendering with it, and that crashed about one interrupt in six
/// (SIGSEGV or SIGABRT instead of exit code 130).
#[allow(unsafe_code)]
fn exit_now(code: i32) -> ! {
    // SAFETY: `_exit` takes no pointers and never returns; the temporaries
    // are already removed and stderr is unbuffered.
    unsafe { libc::_exit(code) }
}

/// Unregisters its path when dropped.
pub struct InterruptGuard {
    path: PathBuf,
}

impl Drop for InterruptGuard {
    fn drop(&mut self) {
        let mut list = temporaries();
        if let Some(i) = list.iter().rposition(|p| *p == self.path) {
            list.remove(i);
        }
    }
}

/// Runs `f` (moving outputs into place) with interrupts held off: the
/// handler waits for it to finish.
pub fn uninterrupted<T>(f: impl FnOnce() -> T) -> T {
    let _held = lock(&MOVING);
    f()
}

/// `println!` that returns the write error instead of panicking, so
/// `plait passes | head -1` ends quietly when `head` closes the pipe
/// (`main` turns a broken pipe into a silent exit).
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($arg)*)
    }};
}

/// `print!` counterpart of [`outln!`].
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        write!(std::io::stdout().lock(), $($arg)*)
    }};
}

/// Whether an error is a write to a reader that went away (`| head`).
pub fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

pub struct PendingFile {
    path: PathBuf,
    temp: tempfile::NamedTempFile,
    _interrupt: InterruptGuard,
}

impl PendingFile {
    /// Reserve `path`; `flag` names the option in the error (`--out`).
    pub fn create(path: &Path, flag: &str) -> Result<Self> {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if path.is_dir() {
            anyhow::bail!("{flag} {}: is a directory", path.display());
        }
        if !dir.is_dir() {
            anyhow::bail!("{flag} {}: no folder {}", path.display(), dir.display());
        }
        let temp = output_temp(".plait-", 0o666)
            .tempfile_in(&dir)
            .map_err(|e| cannot_write(flag, path, &e))?;
        Ok(PendingFile {
            path: path.to_path_buf(),
            _interrupt: remove_on_interrupt(temp.path()),
            temp,
        })
    }

    /// Write the whole content and move it into place.
    pub fn commit(mut self, bytes: &[u8]) -> Result<()> {
        self.temp
            .write_all(bytes)
            .with_context(|| format!("writing {}", self.path.display()))?;
        self.temp.as_file().sync_all().ok();
        let PendingFile { path, temp, .. } = self;
        uninterrupted(|| temp.persist(&path))
            .map_err(|e| anyhow::anyhow!("cannot write {}: {}", path.display(), e.error))?;
        Ok(())
    }
}

/// `--out /proc/x.png: cannot write the file: …`: the path the user gave and
/// the system's reason, without the name of the temporary file (tempfile
/// appends `at path "/proc/.plait-…"`, which the user never named).
fn cannot_write(flag: &str, path: &Path, error: &std::io::Error) -> anyhow::Error {
    // The folder was checked to exist, so "not found" here means a folder
    // that takes no new files (a virtual file system such as /proc or /sys);
    // the system's bare "No such file or directory" would send the user
    // looking for a missing folder.
    let why = if error.kind() == std::io::ErrorKind::NotFound {
        let dir = path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        format!(
            "the folder {} exists but takes no new files ({})",
            dir.display(),
            os_reason(error)
        )
    } else {
        os_reason(error)
    };
    anyhow::anyhow!("{flag} {}: cannot write the file: {why}", path.display())
}

/// The system's reason alone (`No such file or directory (os error 2)`).
/// tempfile's errors end in ` at path "/dir/.plait-…"`, the temporary name
/// the user never gave, and keep the system's error only in that text.
fn os_reason(error: &std::io::Error) -> String {
    if let Some(code) = error.raw_os_error() {
        return std::io::Error::from_raw_os_error(code).to_string();
    }
    let text = error.to_string();
    match text.rsplit_once(" at path \"") {
        Some((reason, _)) => reason.to_owned(),
        None => text,
    }
}

/// A temporary file or folder beside an output, created with the
/// permissions an ordinary one gets (`mode`: `0o666` for a file, `0o777` for
/// a folder, less the umask). tempfile's default for files is private
/// (`0o600`), which the output would keep once renamed into place.
pub fn output_temp(prefix: &str, mode: u32) -> tempfile::Builder<'_, 'static> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(prefix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(mode));
    }
    #[cfg(not(unix))]
    let _ = mode;
    builder
}

/// An output folder (a report, a frame sequence) written into a temporary
/// directory beside `out` and renamed into place at the end. An existing
/// `out` is replaced only if it holds an earlier output of the same kind
/// (its `marker` file).
pub struct PendingDir {
    out: PathBuf,
    parent: PathBuf,
    what: &'static str,
    temp: tempfile::TempDir,
    _interrupt: InterruptGuard,
}

impl PendingDir {
    /// Reserve `out`; `what` names the output in messages (`report`, `frame sequence`).
    pub fn create(out: &Path, marker: &str, what: &'static str) -> Result<Self> {
        if out.exists() && !out.is_dir() {
            anyhow::bail!("--out {}: exists and is not a directory", out.display());
        }
        if out.is_dir() {
            let empty = std::fs::read_dir(out)
                .map(|mut d| d.next().is_none())
                .unwrap_or(false);
            if !empty && !out.join(marker).exists() {
                anyhow::bail!(
                    "--out {}: exists and is not an earlier {what} (no {marker}); refusing to replace it",
                    out.display()
                );
            }
        }
        let parent = match out.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent).with_context(|| {
            format!(
                "--out {}: cannot create {}",
                out.display(),
                parent.display()
            )
        })?;
        let temp = output_temp(".plait-out-", 0o777)
            .tempdir_in(&parent)
            .map_err(|e| {
                anyhow::anyhow!(
                    "--out {}: cannot write in {}: {}",
                    out.display(),
                    parent.display(),
                    os_reason(&e)
                )
            })?;
        Ok(PendingDir {
            out: out.to_path_buf(),
            parent,
            what,
            _interrupt: remove_on_interrupt(temp.path()),
            temp,
        })
    }

    /// The temporary directory the output is written into.
    pub fn dir(&self) -> &Path {
        self.temp.path()
    }

    /// Move the finished output into place (replacing an earlier one),
    /// with interrupts held off until it is.
    pub fn commit(self) -> Result<()> {
        uninterrupted(|| self.move_into_place())
    }

    fn move_into_place(self) -> Result<()> {
        // Created with ordinary permissions (`output_temp`); the files in
        // it were written as ordinary files.
        let temp = self.temp.keep();
        let mut old = None;
        if self.out.exists() {
            let aside = tempfile::Builder::new()
                .prefix(".plait-old-")
                .tempdir_in(&self.parent)?
                .keep();
            std::fs::remove_dir(&aside).ok();
            std::fs::rename(&self.out, &aside).with_context(|| {
                format!(
                    "--out {}: cannot move the earlier {} aside",
                    self.out.display(),
                    self.what
                )
            })?;
            old = Some(aside);
        }
        std::fs::rename(&temp, &self.out).with_context(|| {
            format!(
                "--out {}: cannot move the {} into place",
                self.out.display(),
                self.what
            )
        })?;
        if let Some(old) = old {
            std::fs::remove_dir_all(old).ok();
        }
        Ok(())
    }
}

/// The image format an output path asks for by its extension: `.png`,
/// `.jpg`/`.jpeg` (8-bit RGB, the alpha channel dropped), or `.exr` (OpenEXR,
/// 32-bit float: the linear radiance, not the displayed image). Anything else is
/// refused before any work, rather than writing PNG bytes under another name.
pub fn image_format(path: &Path, flag: &str) -> Result<image::ImageFormat> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match extension.as_deref() {
        Some("png") => Ok(image::ImageFormat::Png),
        Some("jpg" | "jpeg") => Ok(image::ImageFormat::Jpeg),
        Some("exr") => Ok(image::ImageFormat::OpenExr),
        Some(other) => anyhow::bail!(
            "{flag} {}: cannot write `.{other}` images; use a .png, .jpg/.jpeg or .exr file name",
            path.display()
        ),
        None => anyhow::bail!(
            "{flag} {}: the file name needs an extension, .png, .jpg/.jpeg or .exr",
            path.display()
        ),
    }
}

/// `image` encoded as `format` (from [`image_format`]).
pub fn encode_image(image: &image::RgbaImage, format: image::ImageFormat) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut cursor = std::io::Cursor::new(&mut bytes);
    if format == image::ImageFormat::Jpeg {
        // JPEG has no alpha: the final images are opaque anyway.
        image::DynamicImage::ImageRgba8(image.clone())
            .to_rgb8()
            .write_to(&mut cursor, format)
    } else {
        image.write_to(&mut cursor, format)
    }
    .with_context(|| format!("encoding {format:?}"))?;
    Ok(bytes)
}
