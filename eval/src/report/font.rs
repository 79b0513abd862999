//! The bundled plot font (DejaVu Sans), registered with plotters once per process, so every PNG
//! looks the same on machines without system fonts.

use std::path::Path;
use std::sync::OnceLock;

use plotters::style::{FontStyle, register_font};

use crate::error::EvalError;

/// DejaVu Sans (Bitstream Vera licence, see `assets/DejaVu-LICENSE.txt`).
const FONT_TTF: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
pub(crate) const FONT: &str = "sans-serif";

/// Registers the bundled font once; an error names the PNG that needed it.
pub(crate) fn ensure_font(path: &Path) -> Result<(), EvalError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| register_font(FONT, FontStyle::Normal, FONT_TTF).is_ok());
    if ok {
        Ok(())
    } else {
        Err(EvalError::Plot {
            path: path.to_owned(),
            message: "the bundled DejaVu Sans font could not be loaded".into(),
        })
    }
}
