//! Output destinations: files that appear whole or not at all, special files written as
//! streams, and a clear refusal of everything else.
//!
//! Every file tumble writes (CSV, JSON, plots, a sweep folder's files) goes through a
//! [`Destination`], classified **before any work** by [`Destination::check`]:
//!
//! | what the path is | how it is written |
//! |---|---|
//! | a regular file, or nothing yet | atomically: a temporary file beside it (same directory, so the rename is atomic), renamed over it only once complete; a failed or interrupted run leaves the old file (or nothing) |
//! | `-`, `/dev/stdout`, `/dev/fd/1`, `/proc/self/fd/1` | the process's standard output, streamed |
//! | a character device (`/dev/null`, a terminal) or a FIFO (named pipe) | opened and written directly, streaming: no temporary file, no rename |
//! | a directory, a socket, a block device | refused with [`OutputError::Unsupported`] |
//!
//! A symbolic link is followed (a chain of links too) and the rule applied to its final target;
//! an atomic write renames over the **target**, so the link itself is never replaced. A dangling
//! link is written atomically at the path it points to.
//!
//! Renaming over a device node or a FIFO would replace it with a regular file — run as root,
//! `-o /dev/null` would turn the machine's `/dev/null` into a plain file — which is why the
//! classification exists and why nothing here ever renames over anything but a regular file.
//!
//! Temporary files are named `.NAME.XXXXXX.tmp.EXT` (hidden, with the destination's
//! extension) and are removed when dropped, including on an early return with `?`; those a
//! killed process left are found by [`is_temp_name`] and removed by
//! [`remove_stale_temp_files`].
//!
//! A folder that a command writes several files into is held by a [`FolderLock`] (`lock.rs`)
//! while it does, so a second command on the same folder is refused instead of interleaving.
//!
//! # Example
//!
//! ```
//! use std::io::Write;
//! use tumble_output::{Destination, Mode};
//!
//! let dir = tempfile::tempdir()?;
//! let path = dir.path().join("run.csv");
//! let destination = Destination::check(&path)?; // before any work
//! assert!(matches!(destination.mode(), Mode::Atomic { .. }));
//! let mut out = destination.create()?;
//! writeln!(out, "t,x")?;
//! assert!(!path.exists()); // nothing visible until the file is complete
//! out.finish()?;
//! assert_eq!(std::fs::read_to_string(&path)?, "t,x\n");
//!
//! // A directory is refused, a character device is streamed to, never renamed over.
//! assert!(Destination::check(dir.path()).is_err());
//! assert!(matches!(Destination::check("/dev/null".as_ref())?.mode(), Mode::Stream));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod abort;
mod lock;
mod provenance;
pub mod table;

pub use lock::{FolderLock, LOCK_FILE, LockError, host_name};
pub use provenance::Provenance;

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use tempfile::{Builder, NamedTempFile, TempPath};

/// An output path that cannot be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// The path is a kind of file that is neither replaced nor streamed to.
    #[error(
        "{path}: is {what}; give the path of a regular file (or a character device or FIFO to stream to)"
    )]
    Unsupported {
        /// The path as given.
        path: PathBuf,
        /// What it is (`a directory`, `a socket`, `a block device`).
        what: &'static str,
    },
    /// The directory that would hold the file does not exist.
    #[error("{path}: the directory {dir} does not exist")]
    NoDirectory {
        /// The path as given.
        path: PathBuf,
        /// Its directory.
        dir: PathBuf,
    },
    /// A chain of symbolic links too long to be real (a loop).
    #[error("{path}: too many levels of symbolic links")]
    LinkLoop {
        /// The path as given.
        path: PathBuf,
    },
    /// An I/O error while classifying, writing or committing.
    #[error("{path}: {what}: {source}")]
    Io {
        /// The path as given.
        path: PathBuf,
        /// What was being done.
        what: &'static str,
        /// The underlying error.
        #[source]
        source: io::Error,
    },
}

/// How a [`Destination`] is written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Mode {
    /// Through a temporary file renamed over `target` (a regular file or a new path; the end
    /// of any chain of symbolic links).
    Atomic {
        /// The file that is replaced.
        target: PathBuf,
    },
    /// Written directly, streaming (a character device or a FIFO).
    Stream,
    /// The process's standard output.
    Stdout,
}

/// An output path, classified; see the [crate docs](crate).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Destination {
    path: PathBuf,
    mode: Mode,
}

/// Longest chain of symbolic links followed (Linux's own limit).
const MAX_LINKS: usize = 40;

/// Whether `path` names this process's standard output.
fn is_stdout_alias(path: &Path) -> bool {
    let s = path.as_os_str();
    s == "-" || s == "/dev/stdout" || s == "/dev/fd/1" || s == "/proc/self/fd/1"
}

/// `path` (a file in the existing directory `dir`) with its directory made canonical, so that
/// two spellings of one file compare equal.
fn absolute(path: &Path, dir: &Path) -> io::Result<PathBuf> {
    let dir = std::fs::canonicalize(dir)?;
    Ok(match path.file_name() {
        Some(name) => dir.join(name),
        None => dir,
    })
}

/// The directory a path lives in (`.` for a bare file name).
#[must_use]
pub fn directory_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

impl Destination {
    /// Classifies `path` (following symbolic links) without creating or changing anything.
    ///
    /// # Errors
    /// [`OutputError::Unsupported`] for a directory, socket or block device;
    /// [`OutputError::NoDirectory`] when a new file's directory does not exist;
    /// [`OutputError::LinkLoop`]; [`OutputError::Io`] when the path cannot be examined.
    pub fn check(path: &Path) -> Result<Self, OutputError> {
        let given = path.to_path_buf();
        if is_stdout_alias(path) {
            return Ok(Self {
                path: given,
                mode: Mode::Stdout,
            });
        }
        let io_err = |source| OutputError::Io {
            path: given.clone(),
            what: "cannot examine it",
            source,
        };
        let mut current = path.to_path_buf();
        for _ in 0..MAX_LINKS {
            let meta = match std::fs::symlink_metadata(&current) {
                Ok(m) => m,
                Err(e) if e.kind() == io::ErrorKind::NotFound => {
                    let dir = directory_of(&current);
                    if !dir.is_dir() {
                        return Err(OutputError::NoDirectory { path: given, dir });
                    }
                    let target = absolute(&current, &dir).map_err(io_err)?;
                    return Ok(Self {
                        path: given,
                        mode: Mode::Atomic { target },
                    });
                }
                Err(e) => return Err(io_err(e)),
            };
            let kind = meta.file_type();
            if kind.is_symlink() {
                // `/dev/stdout` → `/proc/self/fd/1` → `pipe:[…]`: the target of a descriptor
                // link is not a path, so ask the kernel what the whole chain opens to.
                match std::fs::metadata(&current) {
                    Ok(followed) if !followed.file_type().is_file() => {
                        return Self::special(given, &followed.file_type());
                    }
                    Ok(_) => {}
                    // A dangling link: follow it by hand to the new file's path.
                    Err(e) if e.kind() == io::ErrorKind::NotFound => {}
                    Err(e) => return Err(io_err(e)),
                }
                let link = std::fs::read_link(&current).map_err(io_err)?;
                current = if link.is_absolute() {
                    link
                } else {
                    directory_of(&current).join(link)
                };
                continue;
            }
            if kind.is_file() {
                let target = absolute(&current, &directory_of(&current)).map_err(io_err)?;
                return Ok(Self {
                    path: given,
                    mode: Mode::Atomic { target },
                });
            }
            return Self::special(given, &kind);
        }
        Err(OutputError::LinkLoop { path: given })
    }

    /// A destination that is neither a regular file nor a link: streamed or refused.
    fn special(path: PathBuf, kind: &std::fs::FileType) -> Result<Self, OutputError> {
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if kind.is_char_device() || kind.is_fifo() {
                return Ok(Self {
                    path,
                    mode: Mode::Stream,
                });
            }
            let what = if kind.is_dir() {
                "a directory"
            } else if kind.is_socket() {
                "a socket"
            } else if kind.is_block_device() {
                "a block device"
            } else {
                "not a regular file"
            };
            Err(OutputError::Unsupported { path, what })
        }
        #[cfg(not(unix))]
        {
            let what = if kind.is_dir() {
                "a directory"
            } else {
                "not a regular file"
            };
            Err(OutputError::Unsupported { path, what })
        }
    }

    /// The path as given.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// How it is written.
    #[must_use]
    pub fn mode(&self) -> &Mode {
        &self.mode
    }

    /// The file that is finally written: the regular file an atomic write replaces, or the
    /// given path of a stream. Two destinations with the same `file()` are the same output.
    #[must_use]
    pub fn file(&self) -> &Path {
        match &self.mode {
            Mode::Atomic { target } => target,
            Mode::Stream | Mode::Stdout => &self.path,
        }
    }

    /// Opens the destination for writing: a temporary file beside an atomic target, the
    /// special file itself, or standard output. Nothing is visible at an atomic target until
    /// [`Output::finish`].
    ///
    /// # Errors
    /// [`OutputError::Io`] if the temporary file or the special file cannot be opened.
    pub fn create(&self) -> Result<Output, OutputError> {
        let sink = match &self.mode {
            Mode::Atomic { target } => Sink::Atomic {
                temp: temp_file_beside(target).map_err(|source| OutputError::Io {
                    path: self.path.clone(),
                    what: "cannot create a file beside it",
                    source,
                })?,
                target: target.clone(),
            },
            Mode::Stream => Sink::Direct(self.open_stream()?),
            Mode::Stdout => Sink::Stdout(io::stdout()),
        };
        Ok(Output {
            path: self.path.clone(),
            sink,
        })
    }

    /// Writes `bytes` whole (atomically where the destination is a regular file).
    ///
    /// # Errors
    /// As [`Destination::create`] and [`Output::finish`].
    pub fn write_all(&self, bytes: &[u8]) -> Result<(), OutputError> {
        let mut out = self.create()?;
        out.write_all(bytes).map_err(|source| OutputError::Io {
            path: self.path.clone(),
            what: "cannot write",
            source,
        })?;
        out.finish()
    }

    /// A scratch path for writers that must open a file by name (image encoders): beside an
    /// atomic target, in the system's temporary directory otherwise. Pass it back to
    /// [`Destination::commit_scratch`] once the writer is done.
    ///
    /// # Errors
    /// [`OutputError::Io`] if the file cannot be created.
    pub fn scratch(&self) -> Result<TempPath, OutputError> {
        let made = match &self.mode {
            Mode::Atomic { target } => temp_file_beside(target),
            Mode::Stream | Mode::Stdout => temp_file_in(&self.path, &std::env::temp_dir()),
        };
        made.map(NamedTempFile::into_temp_path)
            .map_err(|source| OutputError::Io {
                path: self.path.clone(),
                what: "cannot create a scratch file for it",
                source,
            })
    }

    /// Delivers a finished scratch file: renamed over an atomic target, copied into a stream
    /// (and then removed).
    ///
    /// # Errors
    /// [`OutputError::Io`] if the rename or the copy fails; the scratch file is removed.
    pub fn commit_scratch(&self, scratch: TempPath) -> Result<(), OutputError> {
        match &self.mode {
            Mode::Atomic { target } => scratch.persist(target).map_err(|e| OutputError::Io {
                path: self.path.clone(),
                what: "cannot write",
                source: e.error,
            }),
            Mode::Stream | Mode::Stdout => {
                let io_err = |source| OutputError::Io {
                    path: self.path.clone(),
                    what: "cannot write",
                    source,
                };
                let mut from = File::open(&scratch).map_err(io_err)?;
                let mut out = self.create()?;
                io::copy(&mut from, &mut out).map_err(io_err)?;
                out.finish()
            }
        }
    }

    fn open_stream(&self) -> Result<File, OutputError> {
        // No `create`, no `truncate`: the special file exists and is not a regular file.
        OpenOptions::new()
            .write(true)
            .open(&self.path)
            .map_err(|source| OutputError::Io {
                path: self.path.clone(),
                what: "cannot open it for writing",
                source,
            })
    }
}

/// Where an [`Output`]'s bytes go.
#[derive(Debug)]
enum Sink {
    Atomic {
        temp: NamedTempFile,
        target: PathBuf,
    },
    Direct(File),
    Stdout(io::Stdout),
}

/// An open output; see [`Destination::create`]. Dropping it without [`Output::finish`]
/// removes an atomic output's temporary file and leaves the target untouched.
#[derive(Debug)]
pub struct Output {
    path: PathBuf,
    sink: Sink,
}

impl Output {
    /// Flushes and, for an atomic output, renames the temporary file over the target.
    ///
    /// # Errors
    /// [`OutputError::Io`] if the flush or the rename fails (the temporary file is removed).
    pub fn finish(mut self) -> Result<(), OutputError> {
        let path = self.path.clone();
        let io_err = |source| OutputError::Io {
            path: path.clone(),
            what: "cannot write",
            source,
        };
        self.flush().map_err(io_err)?;
        match self.sink {
            Sink::Atomic { temp, target } => temp
                .into_temp_path()
                .persist(&target)
                .map_err(|e| io_err(e.error)),
            Sink::Direct(_) | Sink::Stdout(_) => Ok(()),
        }
    }
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.sink {
            Sink::Atomic { temp, .. } => temp.write(buf),
            Sink::Direct(f) => f.write(buf),
            Sink::Stdout(s) => s.write(buf),
        }
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        match &mut self.sink {
            Sink::Atomic { temp, .. } => temp.write_all(buf),
            Sink::Direct(f) => f.write_all(buf),
            Sink::Stdout(s) => s.write_all(buf),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match &mut self.sink {
            Sink::Atomic { temp, .. } => temp.flush(),
            Sink::Direct(f) => f.flush(),
            Sink::Stdout(s) => s.flush(),
        }
    }
}

/// A new, empty temporary file for `path` in `dir`, named `.NAME.XXXXXX.tmp.EXT` with `path`'s
/// extension and created with the usual permissions (`0666` less the umask, as a plain create
/// would; tempfile's default is `0600`).
fn temp_file_in(path: &Path, dir: &Path) -> io::Result<NamedTempFile> {
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    let prefix = format!(".{name}.");
    let suffix = match path.extension() {
        Some(ext) => format!(".tmp.{}", ext.to_string_lossy()),
        None => ".tmp".to_string(),
    };
    let mut builder = Builder::new();
    builder.prefix(&prefix).suffix(&suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let file = builder.tempfile_in(dir)?;
    abort::register(file.path());
    Ok(file)
}

/// Whether `name` is the name of one of tumble's temporary files (`.NAME.XXXXXX.tmp` or
/// `.NAME.XXXXXX.tmp.EXT`, `XXXXXX` six letters or digits, `EXT` `NAME`'s own extension).
#[must_use]
pub fn is_temp_name(name: &str) -> bool {
    let Some(name) = name.strip_prefix('.') else {
        return false;
    };
    let (rest, ext) = if let Some(rest) = name.strip_suffix(".tmp") {
        (rest, None)
    } else if let Some((rest, ext)) = name.rsplit_once(".tmp.") {
        if ext.is_empty() || ext.contains('.') {
            return false;
        }
        (rest, Some(ext))
    } else {
        return false;
    };
    let Some((target, random)) = rest.rsplit_once('.') else {
        return false;
    };
    let random_ok = random.len() == 6 && random.bytes().all(|b| b.is_ascii_alphanumeric());
    let target_ext = Path::new(target).extension().and_then(|e| e.to_str());
    !target.is_empty() && random_ok && target_ext == ext
}

/// Removes the temporary files ([`is_temp_name`]) that an interrupted or killed run of tumble
/// left in `dir` and its subfolders (to a depth of two); returns the paths removed. Call it only
/// while holding `dir`'s [`FolderLock`]: a live writer's temporary file would go too.
///
/// # Errors
/// A folder that cannot be listed or a file that cannot be removed.
pub fn remove_stale_temp_files(dir: &Path) -> io::Result<Vec<PathBuf>> {
    let mut removed = Vec::new();
    remove_temp_files_in(dir, 2, &mut removed)?;
    removed.sort();
    Ok(removed)
}

fn remove_temp_files_in(dir: &Path, depth: u32, removed: &mut Vec<PathBuf>) -> io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let kind = entry.file_type()?;
        let path = entry.path();
        if kind.is_dir() {
            if depth > 0 {
                remove_temp_files_in(&path, depth - 1, removed)?;
            }
        } else if kind.is_file() && entry.file_name().to_str().is_some_and(is_temp_name) {
            match std::fs::remove_file(&path) {
                Ok(()) => removed.push(path),
                Err(e) if e.kind() == io::ErrorKind::NotFound => {}
                Err(e) => return Err(e),
            }
        }
    }
    Ok(())
}

/// A new, empty temporary file beside `path` (same directory, so the final rename is atomic).
fn temp_file_beside(path: &Path) -> io::Result<NamedTempFile> {
    temp_file_in(path, &directory_of(path))
}
