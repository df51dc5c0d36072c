//! What every figure shares: its width, the drawing area the one drawing code takes on either
//! backend, and the pipeline from that code to the bytes of a PNG, SVG or PDF file.

use std::path::Path;

use plotters::prelude::*;

use super::encode::{encode_png, svg_to_pdf};
use super::text::register_font;
use crate::error::{Error, Result};
use crate::files;
use crate::svg_marks::merge_marks;

/// Width of every figure in pixels (printed 8.5 cm wide: see [`TEXT`](super::TEXT)).
pub const FIGURE_WIDTH: u32 = 1000;

/// A drawing area on any backend (bitmap or SVG): the shared drawing code takes these.
pub(crate) type AreaOn<DB> = DrawingArea<DB, plotters::coord::Shift>;
/// What drawing on any backend returns.
pub(crate) type DrawResultOn<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A figure's file format, by the file's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FigureFormat {
    /// A bitmap (`.png`).
    Png,
    /// A vector drawing (`.svg`).
    Svg,
    /// A vector drawing for print (`.pdf`): the SVG, converted.
    Pdf,
}

/// The extensions a figure may have, as the output checks take them.
pub const FIGURE_EXTENSIONS: &[&str] = &["png", "svg", "pdf"];

impl FigureFormat {
    /// The format of `path` by its extension, or the one-line refusal naming the accepted ones.
    pub fn of(path: &Path) -> Result<FigureFormat> {
        match path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .as_deref()
        {
            Some("png") => Ok(FigureFormat::Png),
            Some("svg") => Ok(FigureFormat::Svg),
            Some("pdf") => Ok(FigureFormat::Pdf),
            _ => Err(Error::Refused(format!(
                "{}: a figure's file name must end in .png, .svg or .pdf",
                files::shown(path)
            ))),
        }
    }
}

/// A figure of `size` pixels as the bytes of its file, PNG, SVG or PDF: the one drawing code,
/// generic over the backend, is passed twice (`png_draw` and `svg_draw` call it on each backend;
/// a PDF is the SVG, converted); errors name `path`.
pub(crate) fn figure_bytes(
    path: &Path,
    format: FigureFormat,
    size: (u32, u32),
    png_draw: impl FnOnce(&DrawingArea<BitMapBackend, plotters::coord::Shift>) -> Result<(), String>,
    svg_draw: impl FnOnce(&DrawingArea<SVGBackend, plotters::coord::Shift>) -> Result<(), String>,
) -> Result<Vec<u8>> {
    register_font();
    let fail = |e: String| Error::Encode(format!("cannot draw {}: {e}", files::shown(path)));
    match format {
        FigureFormat::Svg | FigureFormat::Pdf => {
            let mut text = String::new();
            {
                let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
                svg_draw(&root).map_err(fail)?;
                root.present().map_err(|e| fail(e.to_string()))?;
            }
            let text = merge_marks(&text);
            if format == FigureFormat::Pdf {
                svg_to_pdf(&text).map_err(fail)
            } else {
                Ok(text.into_bytes())
            }
        }
        FigureFormat::Png => {
            let mut buf = vec![255u8; (size.0 * size.1 * 3) as usize];
            {
                let root = BitMapBackend::with_buffer(&mut buf, size).into_drawing_area();
                png_draw(&root).map_err(fail)?;
                root.present().map_err(|e| fail(e.to_string()))?;
            }
            encode_png(&buf, size.0, size.1).map_err(fail)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figure_formats_by_extension() {
        for (name, want) in [
            ("a.PNG", Some(FigureFormat::Png)),
            ("a.svg", Some(FigureFormat::Svg)),
            ("b/a.Pdf", Some(FigureFormat::Pdf)),
            ("a.gif", None),
            ("a", None),
        ] {
            assert_eq!(FigureFormat::of(Path::new(name)).ok(), want, "{name}");
        }
        let e = FigureFormat::of(Path::new("x.gif"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("x.gif") && e.contains(".png, .svg or .pdf"),
            "{e}"
        );
    }
}
