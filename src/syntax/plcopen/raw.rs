//! Raw XML text of a body or attribute, decoded with a map back to the file.
//!
//! The XML parser gives decoded text but no position for each character;
//! the lexer needs both. So the content of an element (or an attribute
//! value) is decoded here, character by character, remembering for every
//! decoded byte the byte of the file it came from: an entity such as `&lt;`
//! maps its one decoded byte to the `&`, CDATA maps one to one.

/// Decoded text and, for each of its bytes (plus one past the end), the
/// byte offset in the XML file it came from.
#[derive(Debug, Clone, Default)]
pub struct Decoded {
    /// The decoded text.
    pub text: String,
    /// `map[i]` is the file offset of decoded byte `i`; `map[text.len()]`
    /// is the file offset just past the decoded range.
    pub map: Vec<usize>,
}

impl Decoded {
    /// The file range of the decoded range `start..end`.
    pub fn file_range(&self, start: usize, end: usize) -> (usize, usize) {
        let last = self.map.len().saturating_sub(1);
        let s = self.map.get(start.min(last)).copied().unwrap_or(0);
        let e = self.map.get(end.min(last)).copied().unwrap_or(s);
        (s, e.max(s))
    }
}

/// Why a range could not be decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RawProblem {
    /// A child element inside a text body (file offset of its `<`).
    Markup(usize),
}

/// Decodes `xml[start..end]`: character data, entity and character
/// references, CDATA sections; comments and processing instructions are
/// dropped. A child element is a [`RawProblem::Markup`].
pub fn decode(xml: &str, start: usize, end: usize) -> Result<Decoded, RawProblem> {
    let mut out = Decoded::default();
    let raw = xml.get(start..end).unwrap_or("");
    let mut i = 0;
    while i < raw.len() {
        let rest = &raw[i..];
        let at = start + i;
        if let Some(body) = rest.strip_prefix("<![CDATA[") {
            let len = body.find("]]>").unwrap_or(body.len());
            push_verbatim(&mut out, &body[..len], at + 9);
            i += 9 + len + 3;
        } else if rest.starts_with("<!--") {
            i += rest.find("-->").map_or(rest.len(), |p| p + 3);
        } else if rest.starts_with("<?") {
            i += rest.find("?>").map_or(rest.len(), |p| p + 2);
        } else if rest.starts_with('<') {
            return Err(RawProblem::Markup(at));
        } else if rest.starts_with('&') {
            let semi = rest.find(';').unwrap_or(0);
            let c = entity(&rest[1..semi.max(1)]).unwrap_or('\u{FFFD}');
            let mut buf = [0u8; 4];
            for _ in 0..c.encode_utf8(&mut buf).len() {
                out.map.push(at);
            }
            out.text.push(c);
            i += semi + 1;
        } else {
            let c = rest.chars().next().unwrap_or(' ');
            push_verbatim(&mut out, &rest[..c.len_utf8()], at);
            i += c.len_utf8();
        }
    }
    out.map.push(start + raw.len().min(i));
    Ok(out)
}

/// Appends `s`, which starts at file offset `at`, byte for byte.
fn push_verbatim(out: &mut Decoded, s: &str, at: usize) {
    out.text.push_str(s);
    out.map.extend((0..s.len()).map(|k| at + k));
}

/// The character an entity or character reference (without `&` and `;`)
/// stands for.
fn entity(name: &str) -> Option<char> {
    match name {
        "lt" => Some('<'),
        "gt" => Some('>'),
        "amp" => Some('&'),
        "quot" => Some('"'),
        "apos" => Some('\''),
        _ => {
            let code = if let Some(hex) = name.strip_prefix("#x") {
                u32::from_str_radix(hex, 16).ok()?
            } else {
                name.strip_prefix('#')?.parse().ok()?
            };
            char::from_u32(code)
        }
    }
}

/// The byte range of an element's content, between its start tag and its
/// end tag (`None` for an empty-element tag `<a/>`); `range` is the whole
/// element's range as the XML parser reports it.
pub fn content_range(xml: &str, range: std::ops::Range<usize>) -> Option<(usize, usize)> {
    let text = xml.get(range.clone())?;
    let mut quote: Option<char> = None;
    let mut open_end = None;
    for (i, c) in text.char_indices() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '>') => {
                open_end = Some(i);
                break;
            }
            _ => {}
        }
    }
    let open_end = open_end?;
    if text[..open_end].ends_with('/') {
        return None;
    }
    let close = text.rfind("</")?;
    (close > open_end).then(|| (range.start + open_end + 1, range.start + close))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entities_map_to_their_ampersand() {
        let xml = "<a>x &lt; 1</a>";
        let (s, e) = content_range(xml, 0..xml.len()).unwrap();
        let d = decode(xml, s, e).unwrap();
        assert_eq!(d.text, "x < 1");
        assert_eq!(d.file_range(2, 3), (5, 9));
        assert_eq!(d.file_range(4, 5), (10, 11));
    }

    #[test]
    fn cdata_is_verbatim_and_markup_is_refused() {
        let xml = "<a><![CDATA[a<b]]>&amp;</a>";
        let (s, e) = content_range(xml, 0..xml.len()).unwrap();
        let d = decode(xml, s, e).unwrap();
        assert_eq!(d.text, "a<b&");
        assert_eq!(d.file_range(1, 2), (13, 14));
        assert_eq!(decode("x<b/>", 0, 5).unwrap_err(), RawProblem::Markup(1));
        assert_eq!(content_range("<a x='>'/>", 0..10), None);
    }
}
