//! The failure classes that decide the process exit code (0 done, 2 bad input or usage,
//! 75 transient — worth a retry, 128 + N stopped by signal N after committing what was done,
//! 1 anything else).
use std::fmt;
use std::io;
use std::path::Path;

#[derive(Debug)]
pub enum Failure {
    /// Bad input or usage: exit 2.
    Input(String),
    /// A condition a retry can fix (disk full, I/O error, busy): exit 75 (EX_TEMPFAIL).
    Transient(String),
    /// Anything else: exit 1.
    Other(String),
    /// Stopped by signal `signal` (SIGINT, SIGTERM) with everything done so far committed:
    /// exit 128 + signal, as a shell reports a process killed by it.
    Stopped { signal: i32, message: String },
}

impl Failure {
    pub fn exit_code(&self) -> u8 {
        match self {
            Failure::Input(_) => 2,
            Failure::Transient(_) => 75,
            Failure::Other(_) => 1,
            Failure::Stopped { signal, .. } => (128 + signal).clamp(129, 255) as u8,
        }
    }

    /// Classifies an I/O error on `path` while doing `what`.
    ///
    /// A read-only file system (EROFS) counts as transient: the output directory was writable
    /// when the job was planned, and read-only storage is an administrative state (a remount
    /// after disk errors, maintenance, a snapshot), not a property of the job, so retrying once
    /// the storage is back resumes where the run stopped. Farm submitters cap exit-75 retries.
    pub fn io(what: &str, path: &Path, e: &io::Error) -> Failure {
        let msg = format!("{what} {}: {e}", path.display());
        // ENOSPC 28, EDQUOT 122, EIO 5, EAGAIN 11, EINTR 4, ESTALE 116, ETIMEDOUT 110, EBUSY 16,
        // EROFS 30
        match e.raw_os_error() {
            Some(28 | 122 | 5 | 11 | 4 | 116 | 110 | 16 | 30) => Failure::Transient(msg),
            // Content that is not what it must be (a CSV that is not UTF-8): bad input.
            _ if e.kind() == io::ErrorKind::InvalidData => Failure::Input(msg),
            _ => match e.kind() {
                io::ErrorKind::StorageFull
                | io::ErrorKind::Interrupted
                | io::ErrorKind::TimedOut
                | io::ErrorKind::WouldBlock
                | io::ErrorKind::ReadOnlyFilesystem => Failure::Transient(msg),
                _ => Failure::Other(msg),
            },
        }
    }
}

impl Failure {
    /// An error reading the input file `path` ([`eyeadapt_scene::open_input`]): bad input
    /// (exit 2) when the path is wrong (missing, a FIFO or device, a loop of symbolic links,
    /// unreadable), else classified as [`Failure::io`].
    pub fn input_io(what: &str, path: &Path, e: &io::Error) -> Failure {
        if eyeadapt_scene::is_bad_input(e) {
            Failure::Input(format!("{}: {what}: {e}", path.display()))
        } else {
            Failure::io(what, path, e)
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Input(m) | Failure::Other(m) => write!(f, "{m}"),
            Failure::Stopped { message, .. } => write!(f, "{message}"),
            Failure::Transient(m) => write!(f, "{m} (transient: retrying may succeed)"),
        }
    }
}

impl std::error::Error for Failure {}

impl From<eyeadapt_scene::SceneError> for Failure {
    fn from(e: eyeadapt_scene::SceneError) -> Self {
        Failure::Input(e.to_string())
    }
}
