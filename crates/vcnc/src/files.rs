//! Program text from files: the main program and the program directory
//! where `M98 P10` finds `O0010` or `O0010.nc`. Files are read on demand
//! through positioned reads, never loaded whole.

use std::fs::File;
use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use vcnc_syntax::{MemSource, TextSource};

/// Where a main program comes from: a file, or standard input (`-`),
/// which is read whole into memory.
#[derive(Debug, Clone)]
pub enum Input {
    /// A file on disk.
    File(PathBuf),
    /// Standard input's text.
    Stdin(Arc<[u8]>),
}

impl Input {
    /// `-` reads standard input now; anything else is a file.
    pub fn from_arg(path: &Path) -> Result<Input, String> {
        if path.as_os_str() == "-" {
            let mut text = Vec::new();
            io::stdin()
                .lock()
                .read_to_end(&mut text)
                .map_err(|e| format!("cannot read standard input: {e}"))?;
            return Ok(Input::Stdin(text.into()));
        }
        Ok(Input::File(path.to_path_buf()))
    }

    /// How the program is named in reports.
    pub fn name(&self) -> String {
        match self {
            Input::File(p) => p.display().to_string(),
            Input::Stdin(_) => "<stdin>".to_string(),
        }
    }

    /// The program's text source.
    pub fn open(&self) -> Result<Box<dyn TextSource>, String> {
        match self {
            Input::File(p) => open_program(p),
            Input::Stdin(text) => Ok(Box::new(MemSource(text.to_vec()))),
        }
    }

    /// The program's first `limit` bytes (all of standard input's, within
    /// the limit), for dialect detection.
    pub fn head(&self, limit: usize) -> Result<Vec<u8>, String> {
        match self {
            Input::File(p) => {
                let file =
                    File::open(p).map_err(|e| format!("cannot open {}: {e}", p.display()))?;
                let mut head = Vec::new();
                file.take(u64::try_from(limit).unwrap_or(u64::MAX))
                    .read_to_end(&mut head)
                    .map_err(|e| format!("cannot read {}: {e}", p.display()))?;
                Ok(head)
            }
            Input::Stdin(text) => Ok(text.get(..limit.min(text.len())).unwrap_or(text).to_vec()),
        }
    }

    /// The file's name, for the extension rule of detection (none for
    /// standard input).
    pub fn file_name(&self) -> Option<&str> {
        match self {
            Input::File(p) => p.file_name().and_then(|n| n.to_str()),
            Input::Stdin(_) => None,
        }
    }

    /// Where its called programs are, unless `--program-dir` says.
    pub fn dir(&self) -> PathBuf {
        match self {
            Input::File(p) => parent_dir(p),
            Input::Stdin(_) => PathBuf::from("."),
        }
    }

    /// The raw bytes of the line that starts at `offset` (no line end).
    pub fn line_at(&self, offset: u64) -> Option<Vec<u8>> {
        let mut buf = match self {
            Input::File(p) => {
                use std::io::{Seek, SeekFrom};
                let mut f = File::open(p).ok()?;
                f.seek(SeekFrom::Start(offset)).ok()?;
                let mut buf = vec![0; 4096];
                let n = f.read(&mut buf).ok()?;
                buf.truncate(n);
                buf
            }
            Input::Stdin(text) => {
                let start = usize::try_from(offset).ok()?;
                let rest = text.get(start..)?;
                rest[..rest.len().min(4096)].to_vec()
            }
        };
        let mut end = buf.iter().position(|b| *b == b'\n').unwrap_or(buf.len());
        if end > 0 && buf[end - 1] == b'\r' {
            end -= 1;
        }
        buf.truncate(end);
        Some(buf)
    }
}

/// The programs the command line names: files, directories walked
/// ([`programs_under`]), `-` for standard input. Also whether it named one
/// file (not a directory), which `check` reports in detail.
pub fn inputs(paths: &[PathBuf]) -> Result<(Vec<Input>, bool), String> {
    let mut inputs = Vec::new();
    let mut single_file = paths.len() == 1;
    for path in paths {
        if path.as_os_str() == "-" {
            inputs.push(Input::from_arg(path)?);
            continue;
        }
        let found = programs_under(path)?;
        if found.is_empty() {
            return Err(format!("no programs found under {}", path.display()));
        }
        single_file &= !path.is_dir();
        inputs.extend(found.into_iter().map(Input::File));
    }
    Ok((inputs, single_file))
}

/// Program files under `root` (itself when it is a file): the usual
/// extensions, and extension-less `O1234` files; sorted, so that reports
/// come in a stable order.
pub fn programs_under(root: &Path) -> Result<Vec<PathBuf>, String> {
    let meta =
        std::fs::metadata(root).map_err(|e| format!("cannot open {}: {e}", root.display()))?;
    if !meta.is_dir() {
        return Ok(vec![root.to_path_buf()]);
    }
    let mut out = Vec::new();
    let mut dirs = vec![root.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        let entries =
            std::fs::read_dir(&dir).map_err(|e| format!("cannot list {}: {e}", dir.display()))?;
        for entry in entries.flatten() {
            let path = entry.path();
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                dirs.push(path);
            } else if kind.is_file() && is_program_name(&path) {
                out.push(path);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Whether a file name looks like a part program.
fn is_program_name(path: &Path) -> bool {
    const EXTENSIONS: [&str; 7] = ["nc", "ngc", "tap", "cnc", "gcode", "mpf", "txt"];
    match path.extension().and_then(|e| e.to_str()) {
        Some(ext) => EXTENSIONS.iter().any(|x| x.eq_ignore_ascii_case(ext)),
        None => path.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
            let mut chars = n.chars();
            matches!(chars.next(), Some('O' | 'o'))
                && n.len() > 1
                && chars.all(|c| c.is_ascii_digit())
        }),
    }
}

/// A file read at offsets.
pub struct FileSource(File);

impl TextSource for FileSource {
    fn read_at(&mut self, offset: u64, buf: &mut [u8]) -> io::Result<usize> {
        #[cfg(unix)]
        {
            std::os::unix::fs::FileExt::read_at(&self.0, buf, offset)
        }
        #[cfg(not(unix))]
        {
            use std::io::{Read, Seek, SeekFrom};
            self.0.seek(SeekFrom::Start(offset))?;
            self.0.read(buf)
        }
    }
}

/// Opens the main program.
pub fn open_program(path: &Path) -> Result<Box<dyn TextSource>, String> {
    match File::open(path) {
        Ok(f) if f.metadata().is_ok_and(|m| m.is_dir()) => {
            Err(format!("{} is a directory", path.display()))
        }
        Ok(f) => Ok(Box::new(FileSource(f))),
        Err(e) => Err(format!("cannot open {}: {e}", path.display())),
    }
}

/// The directory of `file` (`.` when it has none).
pub fn parent_dir(file: &Path) -> PathBuf {
    match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Looks called programs up in one directory.
pub struct DirStore {
    dir: PathBuf,
}

impl DirStore {
    /// A store over `dir`.
    pub fn new(dir: PathBuf) -> DirStore {
        DirStore { dir }
    }
}

impl vcnc_interp::ProgramStore for DirStore {
    fn open(&mut self, number: u32) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let names = [
            format!("O{number:04}"),
            format!("O{number:04}.nc"),
            format!("O{number:04}.NC"),
            format!("O{number}"),
            format!("O{number}.nc"),
        ];
        let path = names
            .iter()
            .map(|n| self.dir.join(n))
            .find(|p| p.is_file())?;
        let name = path.display().to_string();
        Some(File::open(&path).map(|f| (Box::new(FileSource(f)) as Box<dyn TextSource>, name)))
    }

    /// Syntec's extended G-code and M-code macros: `G0200`, `M0123` (the
    /// controller's files have no extension; `.nc` is accepted too).
    fn open_named(&mut self, name: &str) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let names = [name.to_string(), format!("{name}.nc"), format!("{name}.NC")];
        let path = names
            .iter()
            .map(|n| self.dir.join(n))
            .find(|p| p.is_file())?;
        let shown = path.display().to_string();
        Some(File::open(&path).map(|f| (Box::new(FileSource(f)) as Box<dyn TextSource>, shown)))
    }

    /// LinuxCNC's subroutine files: `name.ngc` in the directory, and only
    /// there — a name with a path in it, or a file that resolves outside
    /// the directory (a symbolic link), is an error, never read.
    fn open_subroutine(&mut self, name: &str) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let path = self.dir.join(format!("{name}.ngc"));
        if !path.is_file() {
            return None;
        }
        let shown = path.display().to_string();
        Some(inside(&self.dir, name, &path).and_then(|p| {
            File::open(p).map(|f| (Box::new(FileSource(f)) as Box<dyn TextSource>, shown))
        }))
    }
}

/// `path`, the file `name.ngc` of `dir`, when it is one plain file name
/// and resolves (links followed) inside `dir`; otherwise an error that
/// says so without reading it.
fn inside(dir: &Path, name: &str, path: &Path) -> io::Result<PathBuf> {
    let refuse = |why: &str| io::Error::new(io::ErrorKind::PermissionDenied, why.to_string());
    let plain = Path::new(name)
        .components()
        .all(|c| matches!(c, std::path::Component::Normal(_)))
        && !name.contains(['/', '\\', ':']);
    if !plain {
        return Err(refuse("a subroutine name is a file name, not a path"));
    }
    let root = dir.canonicalize()?;
    let real = path.canonicalize()?;
    if !real.starts_with(&root) {
        return Err(refuse("it leads outside the program directory"));
    }
    Ok(real)
}
