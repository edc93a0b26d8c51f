//! The one place that writes SVG text: elements, attributes, escaping and
//! numbers. The pictures (`chart_svg`, `timing_svg`) build elements with
//! [`Element`] and hand them to an [`SvgWriter`]; no other code writes a
//! tag, so escaping and number formatting cannot differ between pictures.

use std::fmt::Write;

/// Formats a coordinate or length deterministically: at most two decimals,
/// no trailing zeros, no `-0`, no exponent (`12`, `3.5`, `-0.25`).
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        // Never produced by the layouts; a defined text keeps the output valid.
        return "0".to_string();
    }
    let rounded = (v * 100.0).round() / 100.0;
    let mut s = format!("{rounded:.2}");
    while s.ends_with('0') {
        s.pop();
    }
    if s.ends_with('.') {
        s.pop();
    }
    if s == "-0" { "0".to_string() } else { s }
}

/// Escapes text for element content and attribute values (both quoted
/// with `"`); characters XML 1.0 does not allow become U+FFFD.
fn escape_into(out: &mut String, text: &str) {
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
}

/// One element's name and attributes, in the order given (the order is
/// part of the output, so the same drawing gives the same bytes).
#[derive(Debug, Clone)]
pub struct Element {
    name: &'static str,
    attrs: Vec<(&'static str, String)>,
}

impl Element {
    /// An element without attributes.
    pub fn new(name: &'static str) -> Element {
        Element {
            name,
            attrs: Vec::new(),
        }
    }

    /// Adds a text attribute (escaped when written).
    pub fn attr(mut self, name: &'static str, value: impl Into<String>) -> Element {
        self.attrs.push((name, value.into()));
        self
    }

    /// Adds a numeric attribute, formatted by [`num`].
    pub fn num(mut self, name: &'static str, value: f64) -> Element {
        self.attrs.push((name, num(value)));
        self
    }

    /// Adds a `points` attribute (polyline, polygon) from `(x, y)` pairs.
    pub fn points(mut self, points: &[(f64, f64)]) -> Element {
        let mut text = String::new();
        for (i, (x, y)) in points.iter().enumerate() {
            if i > 0 {
                text.push(' ');
            }
            let _ = write!(text, "{},{}", num(*x), num(*y));
        }
        self.attrs.push(("points", text));
        self
    }
}

/// Writes one SVG document, indenting nested elements by two spaces.
#[derive(Debug)]
pub struct SvgWriter {
    out: String,
    open: Vec<&'static str>,
}

impl SvgWriter {
    /// Starts a document of `width` × `height` user units (pixels) with a
    /// white background and `font-family` monospace: the layouts measure
    /// text as monospace glyphs of 0.6 em.
    pub fn new(width: f64, height: f64) -> SvgWriter {
        let mut w = SvgWriter {
            out: String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"),
            open: Vec::new(),
        };
        let (wt, ht) = (num(width), num(height));
        w.open(
            Element::new("svg")
                .attr("xmlns", "http://www.w3.org/2000/svg")
                .attr("width", wt.clone())
                .attr("height", ht.clone())
                .attr("viewBox", format!("0 0 {wt} {ht}"))
                .attr("font-family", "DejaVu Sans Mono, monospace")
                .attr("font-size", "12"),
        );
        w.empty(
            Element::new("rect")
                .attr("width", "100%")
                .attr("height", "100%")
                .attr("fill", "white"),
        );
        w
    }

    fn start_tag(&mut self, e: &Element) {
        for _ in 0..self.open.len() {
            self.out.push_str("  ");
        }
        self.out.push('<');
        self.out.push_str(e.name);
        for (name, value) in &e.attrs {
            self.out.push(' ');
            self.out.push_str(name);
            self.out.push_str("=\"");
            escape_into(&mut self.out, value);
            self.out.push('"');
        }
    }

    /// Opens `e`; its children follow until [`Self::close`].
    pub fn open(&mut self, e: Element) {
        self.start_tag(&e);
        self.out.push_str(">\n");
        self.open.push(e.name);
    }

    /// Closes the innermost open element (nothing when none is open).
    pub fn close(&mut self) {
        if let Some(name) = self.open.pop() {
            for _ in 0..self.open.len() {
                self.out.push_str("  ");
            }
            let _ = writeln!(self.out, "</{name}>");
        }
    }

    /// Writes `e` without children.
    pub fn empty(&mut self, e: Element) {
        self.start_tag(&e);
        self.out.push_str("/>\n");
    }

    /// Writes `e` with `text` as its only content (escaped).
    pub fn text(&mut self, e: Element, text: &str) {
        let name = e.name;
        self.start_tag(&e);
        self.out.push('>');
        escape_into(&mut self.out, text);
        let _ = writeln!(self.out, "</{name}>");
    }

    /// Closes every open element and returns the document.
    pub fn finish(mut self) -> String {
        while !self.open.is_empty() {
            self.close();
        }
        self.out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_stable() {
        assert_eq!(num(12.0), "12");
        assert_eq!(num(3.5), "3.5");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(1.0 / 3.0), "0.33");
        assert_eq!(num(-2.25), "-2.25");
        assert_eq!(num(f64::NAN), "0");
    }

    #[test]
    fn text_and_attributes_are_escaped() {
        let mut w = SvgWriter::new(10.0, 10.0);
        w.text(
            Element::new("text").attr("class", "a\"b"),
            "x < y & 'z'\u{1}",
        );
        let svg = w.finish();
        assert!(svg.contains(r#"<text class="a&quot;b">x &lt; y &amp; &apos;z&apos;"#));
        assert!(svg.contains('\u{FFFD}'));
        assert!(svg.trim_end().ends_with("</svg>"));
    }
}
