//! Program text from files: the main program and the program directory
//! where `M98 P10` finds `O0010` or `O0010.nc`. Files are read on demand
//! through positioned reads, never loaded whole.

use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};
use vcnc_syntax::TextSource;

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
}
