//! The XML files of one scene (the main file and everything it `<include>`s) in one offset
//! space: each file starts where the previous one ended, so a plain `usize` locates any
//! element of any file, and diagnostics name the file it is in.
use crate::diagnostic::{Diagnostic, Severity, SourceMap};
use std::path::{Path, PathBuf};

pub(crate) struct Sources {
    /// (path, text, first offset), in the order the files were read.
    files: Vec<(PathBuf, String, usize)>,
    /// Folders named by `<path>`, the latest first (searched before the main file's folder).
    search: Vec<PathBuf>,
}

impl Sources {
    pub(crate) fn new(main: &Path, text: &str) -> Self {
        Sources {
            files: vec![(main.to_path_buf(), text.to_string(), 0)],
            search: Vec::new(),
        }
    }

    /// Adds a file; returns the offset its text starts at.
    pub(crate) fn add(&mut self, path: &Path, text: &str) -> usize {
        let (_, last, base) = self.files.last().expect("the main file");
        let base = base + last.len() + 1;
        self.files
            .push((path.to_path_buf(), text.to_string(), base));
        base
    }

    /// The main scene file.
    pub(crate) fn main(&self) -> &Path {
        &self.files[0].0
    }

    /// The file holding `offset` and the offset of its first byte.
    fn file_at(&self, offset: usize) -> &(PathBuf, String, usize) {
        let i = self.files.partition_point(|f| f.2 <= offset);
        &self.files[i.saturating_sub(1)]
    }

    /// The file `offset` is in (relative names in it are resolved from its folder).
    pub(crate) fn path_at(&self, offset: usize) -> &Path {
        &self.file_at(offset).0
    }

    /// 1-based line of `offset` in its own file.
    pub(crate) fn line(&self, offset: usize) -> usize {
        self.diag(Severity::Warning, offset, String::new()).line
    }

    fn diag(&self, severity: Severity, offset: usize, message: String) -> Diagnostic {
        let (file, text, base) = self.file_at(offset);
        SourceMap { file, text }.at(severity, offset - base, message)
    }

    pub(crate) fn error(&self, offset: usize, message: impl Into<String>) -> Diagnostic {
        self.diag(Severity::Error, offset, message.into())
    }

    pub(crate) fn warning(&self, offset: usize, message: impl Into<String>) -> Diagnostic {
        self.diag(Severity::Warning, offset, message.into())
    }

    /// A problem with the scene as a whole (no line): named after the main file.
    pub(crate) fn whole(&self, severity: Severity, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity,
            file: self.main().to_path_buf(),
            line: 0,
            col: 0,
            message: message.into(),
        }
    }

    pub(crate) fn add_search_folder(&mut self, dir: PathBuf) {
        self.search.insert(0, dir);
    }

    /// Where a file name given in the scene is looked for, as Mitsuba's file resolver does:
    /// absolute names as they are; otherwise the `<path>` folders (latest first), then the main
    /// file's folder. The first that exists wins; when none does, the main folder's candidate
    /// (so that the error names it).
    pub(crate) fn resolve(&self, name: &str) -> PathBuf {
        let name = Path::new(name);
        if name.is_absolute() {
            return name.to_path_buf();
        }
        let main_dir = self.main().parent().unwrap_or(Path::new("."));
        let fallback = main_dir.join(name);
        self.search
            .iter()
            .map(|d| d.join(name))
            .find(|p| p.exists())
            .unwrap_or(fallback)
    }

    /// Like [`Sources::resolve`], but the folder of the file at `offset` is searched first
    /// (Mitsuba does so for `<include>`).
    pub(crate) fn resolve_from(&self, offset: usize, name: &str) -> PathBuf {
        if Path::new(name).is_absolute() {
            return PathBuf::from(name);
        }
        let dir = self.path_at(offset).parent().unwrap_or(Path::new("."));
        let here = dir.join(name);
        if here.exists() {
            return here;
        }
        let found = self.resolve(name);
        if found.exists() { found } else { here }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_name_the_file_and_its_own_line() {
        let mut s = Sources::new(Path::new("main.xml"), "a\nb\n");
        let base = s.add(Path::new("inc.xml"), "x\ny\nz");
        assert_eq!(s.error(2, "m").line, 2);
        assert_eq!(s.error(2, "m").file, Path::new("main.xml"));
        let d = s.error(base + 4, "m");
        assert_eq!(
            (d.file.as_path(), d.line, d.col),
            (Path::new("inc.xml"), 3, 1)
        );
        assert_eq!(s.path_at(base), Path::new("inc.xml"));
    }
}
