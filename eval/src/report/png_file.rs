//! A PNG written whole or not at all: plots are drawn into a hidden sibling file and renamed over
//! the final name only once the image library has written all of it, so a full disk or a failed
//! drawing never leaves a 0-byte or half-written PNG under the name a reader opens (issue 26).

use std::path::{Path, PathBuf};

use crate::error::EvalError;

/// The final path of a plot and the hidden sibling it is drawn into first.
#[derive(Debug)]
pub(crate) struct PngFile {
    final_path: PathBuf,
    drawing_path: PathBuf,
    committed: bool,
}

impl PngFile {
    /// A plot that will be `final_path`; draw into [`PngFile::drawing_path`], then commit.
    pub fn new(final_path: &Path) -> Self {
        let name = final_path
            .file_name()
            .map_or_else(|| "plot".into(), |n| n.to_string_lossy().into_owned());
        // The image library picks the format from the extension, so the sibling ends in `.png`.
        let drawing_path = final_path.with_file_name(format!(".{name}.partial.png"));
        Self {
            final_path: final_path.to_owned(),
            drawing_path,
            committed: false,
        }
    }

    /// Where to draw.
    pub fn drawing_path(&self) -> &Path {
        &self.drawing_path
    }

    /// Moves the finished drawing to its final name.
    pub fn commit(mut self) -> Result<(), EvalError> {
        std::fs::rename(&self.drawing_path, &self.final_path)
            .map_err(|e| EvalError::io(&self.final_path, e))?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for PngFile {
    /// A drawing that was not committed (an error on the way) leaves nothing behind.
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.drawing_path);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_committed_drawing_appears_under_its_final_name_only() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        let png = PngFile::new(&path);
        std::fs::write(png.drawing_path(), b"drawn").unwrap();
        assert!(!path.exists());
        png.commit().unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"drawn");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn an_abandoned_drawing_leaves_no_file_behind() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        {
            let png = PngFile::new(&path);
            std::fs::write(png.drawing_path(), b"half").unwrap();
        }
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
