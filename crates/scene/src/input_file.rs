//! Opening input files: every file a scene or job names (scene, `<include>`, OBJ and its MTL,
//! PLY, serialized meshes, spectra, textures, CSV tracks, glTF files and buffers, job files)
//! is opened here, and only a regular file is read. A FIFO would block the reader forever and
//! a device such as `/dev/zero` never ends, so anything else fails at once with an error that
//! says what the path is.
//!
//! On Unix the file is opened with `O_NONBLOCK` (opening a FIFO then returns at once instead of
//! waiting for a writer) and its type is checked on the open handle, so nothing can swap the
//! file between the check and the read. The errors are `io::Error`s; [`is_bad_input`] tells
//! the ones that are the user's to fix (a missing file, a loop of symbolic links, a FIFO)
//! from failures of the machine.
use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::Path;

/// What a path that is not a regular file is, for messages.
fn kind_of(md: &Metadata) -> &'static str {
    let t = md.file_type();
    if t.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "not a regular file"
}

fn not_regular(md: &Metadata) -> io::Error {
    let kind = kind_of(md);
    let msg = if kind.starts_with("not") {
        kind.to_string()
    } else {
        format!("it is {kind}, not a regular file")
    };
    io::Error::new(io::ErrorKind::InvalidInput, msg)
}

/// The OS's words for the common cases, in the user's terms.
fn explain(e: io::Error) -> io::Error {
    if e.kind() == io::ErrorKind::NotFound {
        io::Error::new(e.kind(), "it does not exist")
    } else if is_symlink_loop(&e) {
        // `ErrorKind::FilesystemLoop` is not stable: InvalidInput keeps it bad input.
        io::Error::new(
            io::ErrorKind::InvalidInput,
            "it is a loop of symbolic links (or a chain too long to follow)",
        )
    } else {
        e
    }
}

fn is_symlink_loop(e: &io::Error) -> bool {
    #[cfg(unix)]
    {
        e.raw_os_error() == Some(libc::ELOOP)
    }
    #[cfg(not(unix))]
    {
        let _ = e;
        false
    }
}

/// Opens `path` for reading if it is a regular file (following symbolic links).
pub fn open_input(path: &Path) -> io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(explain)?;
    let md = file.metadata()?;
    if !md.is_file() {
        return Err(not_regular(&md));
    }
    // O_NONBLOCK changes nothing for a regular file's reads.
    Ok(file)
}

/// The bytes of the regular file `path`.
pub fn read_input(path: &Path) -> io::Result<Vec<u8>> {
    let mut file = open_input(path)?;
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// The text of the regular file `path` (UTF-8, else `InvalidData`).
pub fn read_input_text(path: &Path) -> io::Result<String> {
    String::from_utf8(read_input(path)?)
        .map_err(|_| io::Error::new(io::ErrorKind::InvalidData, "not valid UTF-8 text"))
}

/// Checks that `path` is a regular file and returns its size, for readers that open the file
/// themselves (the glTF crate's buffers, the EXR reader).
pub fn check_input(path: &Path) -> io::Result<u64> {
    let md = std::fs::metadata(path).map_err(explain)?;
    if !md.is_file() {
        return Err(not_regular(&md));
    }
    Ok(md.len())
}

/// True for errors that say the path is wrong (missing, not a regular file, a loop of
/// symbolic links, unreadable, not text), false for failures of the machine (I/O errors).
pub fn is_bad_input(e: &io::Error) -> bool {
    use io::ErrorKind as K;
    matches!(
        e.kind(),
        K::NotFound
            | K::PermissionDenied
            | K::InvalidInput
            | K::InvalidData
            | K::InvalidFilename
            | K::NotADirectory
            | K::IsADirectory
    ) || is_symlink_loop(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_files_are_read() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("a.txt");
        std::fs::write(&p, "text").unwrap();
        assert_eq!(read_input_text(&p).unwrap(), "text");
        assert_eq!(check_input(&p).unwrap(), 4);
        std::fs::write(&p, [0xff, 0xfe]).unwrap();
        let e = read_input_text(&p).unwrap_err();
        assert!(is_bad_input(&e) && e.to_string().contains("UTF-8"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn fifos_devices_directories_and_loops_are_refused_without_blocking() {
        let d = tempfile::tempdir().unwrap();
        let fifo = d.path().join("pipe");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        // Without O_NONBLOCK this open would wait for a writer forever.
        let e = read_input(&fifo).unwrap_err();
        assert!(e.to_string().contains("FIFO") && is_bad_input(&e), "{e}");
        assert!(check_input(&fifo).unwrap_err().to_string().contains("FIFO"));
        let e = read_input(Path::new("/dev/zero")).unwrap_err();
        assert!(e.to_string().contains("character device"), "{e}");
        let e = read_input(d.path()).unwrap_err();
        assert!(
            e.to_string().contains("directory") && is_bad_input(&e),
            "{e}"
        );
        let lp = d.path().join("loop");
        std::os::unix::fs::symlink(&lp, &lp).unwrap();
        let e = read_input(&lp).unwrap_err();
        assert!(is_bad_input(&e), "{e:?}");
        let e = read_input(Path::new("a\0b")).unwrap_err();
        assert!(is_bad_input(&e), "{e:?}");
    }
}
