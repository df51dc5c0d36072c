//! The encoders behind a figure's bytes: an RGB buffer as PNG, and the SVG as a PDF a printed
//! column wide, the shipped font embedded.

use image::ImageEncoder;

use super::text::FONT;

/// How SVG is read for PDF: the shipped font loaded, and the family every text of ours names
/// (`sans-serif`) and the default family both mapped to it.
pub(crate) fn svg_options() -> Result<usvg::Options<'static>, String> {
    let mut opt = usvg::Options::default();
    let db = opt.fontdb_mut();
    db.load_font_data(FONT.to_vec());
    let family = db
        .faces()
        .next()
        .and_then(|f| f.families.first().map(|(name, _)| name.clone()))
        .ok_or("the shipped font does not load")?;
    db.set_sans_serif_family(family.clone());
    opt.font_family = family;
    Ok(opt)
}

/// Width of a PDF figure's page (cm): one column of a printed page, the width the text sizes
/// are chosen for.
pub const PDF_WIDTH_CM: f64 = 8.5;

/// The PDF of an SVG drawn by [`figure_bytes`](super::figure_bytes), its page [`PDF_WIDTH_CM`]
/// wide; the shipped font is embedded (the SVG names it by its family only).
pub(super) fn svg_to_pdf(svg: &str) -> Result<Vec<u8>, String> {
    let tree = usvg::Tree::from_str(svg, &svg_options()?).map_err(|e| e.to_string())?;
    // The page's width in points is the drawing's width in pixels × 72 / dpi.
    let dpi = tree.size().width() as f64 * 2.54 / PDF_WIDTH_CM;
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions { dpi: dpi as f32 },
    )
    .map_err(|e| e.to_string())
}

/// An RGB pixel buffer of `w` × `h` as PNG bytes.
pub(crate) fn encode_png(buf: &[u8], w: u32, h: u32) -> Result<Vec<u8>, String> {
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(buf, w, h, image::ExtendedColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(png)
}
