//! A small indenting XML writer with escaping (attribute values, and
//! CDATA for bodies).

/// Builds an XML document line by line.
#[derive(Debug, Default)]
pub struct Writer {
    out: String,
    depth: usize,
}

impl Writer {
    /// An empty document with the XML declaration.
    pub fn new() -> Writer {
        Writer {
            out: "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n".to_string(),
            depth: 0,
        }
    }

    /// Writes `<name attrs>` and indents what follows.
    pub fn open(&mut self, name: &str, attrs: &[(&str, &str)]) {
        self.line(&format!("<{name}{}>", attributes(attrs)));
        self.depth += 1;
    }

    /// Writes `</name>`.
    pub fn close(&mut self, name: &str) {
        self.depth = self.depth.saturating_sub(1);
        self.line(&format!("</{name}>"));
    }

    /// Writes `<name attrs/>`.
    pub fn empty(&mut self, name: &str, attrs: &[(&str, &str)]) {
        self.line(&format!("<{name}{}/>", attributes(attrs)));
    }

    /// Writes a textual body: `<LANG><xhtml:p><![CDATA[text]]></xhtml:p></LANG>`.
    pub fn text_body(&mut self, lang: &str, text: &str) {
        let pad = "  ".repeat(self.depth);
        self.out.push_str(&format!(
            "{pad}<{lang}>\n{pad}  <xhtml:p><![CDATA[{}]]></xhtml:p>\n{pad}</{lang}>\n",
            cdata(text)
        ));
    }

    /// Writes `<name attrs>text</name>` on one line, the text escaped.
    pub fn text_element(&mut self, name: &str, attrs: &[(&str, &str)], text: &str) {
        self.line(&format!(
            "<{name}{}>{}</{name}>",
            attributes(attrs),
            escape(text)
        ));
    }

    /// Writes one indented line.
    fn line(&mut self, text: &str) {
        for _ in 0..self.depth {
            self.out.push_str("  ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    /// The document.
    pub fn finish(self) -> String {
        self.out
    }
}

/// ` a="v" b="w"` with values escaped.
fn attributes(attrs: &[(&str, &str)]) -> String {
    attrs
        .iter()
        .map(|(k, v)| format!(" {k}=\"{}\"", escape(v)))
        .collect()
}

/// Escapes an attribute value.
pub fn escape(value: &str) -> String {
    let mut s = String::with_capacity(value.len());
    for c in value.chars() {
        match c {
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '&' => s.push_str("&amp;"),
            '"' => s.push_str("&quot;"),
            '\n' => s.push_str("&#10;"),
            '\r' => s.push_str("&#13;"),
            '\t' => s.push_str("&#9;"),
            c => s.push(c),
        }
    }
    s
}

/// Text safe inside one CDATA section: a `]]>` in it is split across two.
fn cdata(text: &str) -> String {
    text.replace("]]>", "]]]]><![CDATA[>")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_and_splits_cdata() {
        let mut w = Writer::new();
        w.open(
            "a",
            &[
                ("v", "x<\"&"),
                ("xmlns:xhtml", "http://www.w3.org/1999/xhtml"),
            ],
        );
        w.text_body("ST", "a]]>b");
        w.close("a");
        let doc = w.finish();
        assert!(doc.contains("v=\"x&lt;&quot;&amp;\""));
        let parsed = roxmltree::Document::parse(&doc).unwrap();
        let text: String = parsed.descendants().filter_map(|n| n.text()).collect();
        assert!(text.contains("a]]>b"));
    }
}
