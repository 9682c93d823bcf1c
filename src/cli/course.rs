//! Where `whitted lessons` reads the course from: a folder on disk (`--lessons DIR`, or `lessons/`
//! of the current folder), or the copy the binary carries (`build.rs`: every lesson, the scenes of
//! `lessons/scenes/` and `scenes/`, and the WebAssembly module when it was built with the binary),
//! so that an installed `whitted` writes the whole course from any folder.

use super::{load_scene_from, read_text, Failure};
use std::path::{Component, Path, PathBuf};
use whitted::scene::AnyScene;

/// What `build.rs` embedded: `FILES` (path in the repository, text) and `MODULE`.
mod embedded {
    include!(concat!(env!("OUT_DIR"), "/course.rs"));
}

/// Where the lesson files and their scenes are read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Files {
    /// The file system, paths as given.
    Disk,
    /// The copy in the binary, paths relative to the repository's root (`lessons/01-….json`,
    /// `lessons/../scenes/whitted.json` = `scenes/whitted.json`).
    Embedded,
}

/// The lessons folder when `--lessons` is not given.
pub const DEFAULT_LESSONS: &str = "lessons";

impl Files {
    /// The lessons folder and where to read it: `--lessons DIR` from disk; else `lessons/` of the
    /// current folder when there is one (the repository: its edits count without a rebuild); else
    /// the copy in the binary.
    pub fn choose(lessons: Option<&Path>) -> (Self, PathBuf) {
        match lessons {
            Some(dir) => (Self::Disk, dir.to_path_buf()),
            None if Path::new(DEFAULT_LESSONS).is_dir() => (Self::Disk, PathBuf::from(DEFAULT_LESSONS)),
            None => (Self::Embedded, PathBuf::from(DEFAULT_LESSONS)),
        }
    }

    /// The `.json` files directly in `dir`, in file-name order.
    ///
    /// # Errors
    /// Why the folder cannot be read.
    pub fn json_files(self, dir: &Path) -> Result<Vec<PathBuf>, String> {
        let mut files: Vec<PathBuf> = match self {
            Self::Disk => std::fs::read_dir(dir)
                .map_err(|e| e.to_string())?
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == "json"))
                .collect(),
            Self::Embedded => {
                let dir = tidy(dir);
                embedded::FILES
                    .iter()
                    .map(|(path, _)| Path::new(path))
                    .filter(|p| p.parent().is_some_and(|d| tidy(d) == dir))
                    .filter(|p| p.extension().is_some_and(|e| e == "json"))
                    .map(Path::to_path_buf)
                    .collect()
            }
        };
        files.sort();
        Ok(files)
    }

    /// A text file of at most `limit` bytes.
    ///
    /// # Errors
    /// Why it cannot be read (`cli::read_text`'s reasons; "not in this binary" for the copy).
    pub fn read(self, path: &Path, limit: u64) -> Result<String, String> {
        match self {
            Self::Disk => read_text(path, limit),
            Self::Embedded => {
                let key = tidy(path);
                embedded::FILES
                    .iter()
                    .find(|(p, _)| *p == key)
                    .map(|(_, text)| (*text).to_owned())
                    .ok_or_else(|| "not among the files this whitted carries".to_owned())
            }
        }
    }

    /// A scene and its meshes, read from here (`cli::load_scene`'s errors).
    ///
    /// # Errors
    /// Every problem of the scene, one line each (exit code 2).
    pub fn load_scene(self, path: &Path) -> Result<AnyScene, Failure> {
        load_scene_from(path, &|p: &Path, limit: u64| self.read(p, limit))
    }
}

/// The WebAssembly module built into the binary (`build.rs`), if it was.
#[must_use]
pub fn module() -> Option<&'static [u8]> {
    embedded::MODULE
}

/// A path with `.` and `name/..` taken out, written with `/` (`lessons/../scenes/whitted.json` →
/// `scenes/whitted.json`): how a reader would type it, and the key of an embedded file. Lexical,
/// as a shown command needs no more.
#[must_use]
pub fn tidy(path: &Path) -> String {
    let mut parts: Vec<String> = Vec::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir if parts.last().is_some_and(|p| p != "..") => {
                parts.pop();
            }
            other => parts.push(other.as_os_str().to_string_lossy().into_owned()),
        }
    }
    parts.join("/")
}

#[cfg(test)]
mod tests {
    use super::{tidy, Files};
    use std::path::Path;

    #[test]
    fn tidy_takes_out_dots() {
        assert_eq!(tidy(Path::new("lessons/../scenes/whitted.json")), "scenes/whitted.json");
        assert_eq!(tidy(Path::new("./lessons/scenes/a.json")), "lessons/scenes/a.json");
        assert_eq!(tidy(Path::new("../../x.json")), "../../x.json");
    }

    /// The copy in the binary is the repository's: the same lesson files, the same texts, and
    /// every scene a lesson names.
    #[test]
    fn the_embedded_course_is_the_repositorys() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let on_disk = Files::Disk.json_files(&root.join("lessons")).unwrap();
        let embedded = Files::Embedded.json_files(Path::new("lessons")).unwrap();
        assert!(on_disk.len() > 10, "{on_disk:?}");
        let names = |files: &[std::path::PathBuf]| -> Vec<String> {
            files.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect()
        };
        assert_eq!(names(&embedded), names(&on_disk));
        for (disk, copy) in on_disk.iter().zip(&embedded) {
            assert_eq!(
                Files::Embedded.read(copy, 1 << 20),
                Files::Disk.read(disk, 1 << 20),
                "{}",
                copy.display()
            );
            let lesson = whitted::lesson::parse(&Files::Embedded.read(copy, 1 << 20).unwrap()).unwrap();
            for spec in &lesson.figures {
                let scene = Path::new("lessons").join(&spec.scene);
                assert!(
                    Files::Embedded.load_scene(&scene).is_ok(),
                    "{}: {}",
                    copy.display(),
                    scene.display()
                );
            }
        }
        assert!(Files::Embedded.read(Path::new("lessons/none.json"), 1 << 20).is_err());
    }
}
