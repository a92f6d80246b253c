//! The timeline as a self-contained page: the SVG inline, with pan, zoom and hover details by
//! a small script of its own (no network, no library).

const PAGE: &str = include_str!("page.html");

/// The page around `svg`, titled with `caption`.
pub fn html(caption: &str, svg: &str) -> String {
    let caption = caption
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    PAGE.replacen("{{CAPTION}}", &caption, 1)
        .replacen("{{SVG}}", svg, 1)
}
