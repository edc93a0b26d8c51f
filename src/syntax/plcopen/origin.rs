//! Which tool wrote a PLCopen project, as far as the addressing of its
//! located variables is concerned: a project from the OpenPLC Editor or
//! Beremiz numbers `%QW`, `%MW`, `%MD` in matiec's separate tables (the
//! `openplc` convention, `docs/runtime.md`, "Addressing").
//!
//! Two marks say so, either one enough:
//!
//! - the `<fileHeader>`'s `companyName` or `productName` names OpenPLC or
//!   Beremiz (any case);
//! - the root `<project>` binds the prefix `ns1` to the TC6 2.01
//!   namespace. Beremiz's XML writer (which the OpenPLC Editor inherits)
//!   declares it on every project it saves, whatever the user typed in the
//!   project's properties; the header's defaults there are the neutral
//!   `Unknown`/`Unnamed`, so the header alone would miss most files.
//!
//! An explicit `--addressing` (`Options::addressing`) always wins.

use super::NAMESPACE_0201;

/// True when the PLCopen project `text` was exported by CODESYS (its
/// `<fileHeader>` names the product), whose dialect its ST is written in.
pub fn written_by_codesys(text: &str) -> bool {
    text.contains("productName=\"CODESYS")
}

/// Words in `companyName`/`productName` that name the matiec family.
const TOOL_NAMES: [&str; 2] = ["openplc", "beremiz"];

/// True when the PLCopen project `text` carries a mark of the OpenPLC
/// Editor or Beremiz (see the module documentation). False for anything
/// else, malformed XML included.
pub fn written_by_matiec_tools(text: &str) -> bool {
    let xml = text.trim_start_matches('\u{FEFF}');
    let options = roxmltree::ParsingOptions {
        allow_dtd: false,
        ..roxmltree::ParsingOptions::default()
    };
    let Ok(doc) = roxmltree::Document::parse_with_options(xml, options) else {
        return false;
    };
    let root = doc.root_element();
    if root.tag_name().name() != "project" {
        return false;
    }
    let ns1 = root
        .namespaces()
        .any(|ns| ns.name() == Some("ns1") && ns.uri() == NAMESPACE_0201);
    let named = root
        .children()
        .filter(|n| n.tag_name().name() == "fileHeader")
        .flat_map(|h| [h.attribute("companyName"), h.attribute("productName")])
        .flatten()
        .any(|v| {
            let v = v.to_ascii_lowercase();
            TOOL_NAMES.iter().any(|t| v.contains(t))
        });
    ns1 || named
}

#[cfg(test)]
mod tests {
    use super::*;

    fn project(root_attrs: &str, header: &str) -> String {
        format!(
            "<?xml version='1.0' encoding='utf-8'?>\n<project {root_attrs}>\
             <fileHeader {header} creationDateTime=\"2026-01-01T00:00:00\"/></project>"
        )
    }

    const PLAIN: &str = "xmlns=\"http://www.plcopen.org/xml/tc6_0201\"";
    const BEREMIZ: &str = "xmlns:ns1=\"http://www.plcopen.org/xml/tc6_0201\" \
         xmlns:xhtml=\"http://www.w3.org/1999/xhtml\" xmlns=\"http://www.plcopen.org/xml/tc6_0201\"";

    #[test]
    fn the_beremiz_writer_signature_is_enough() {
        let xml = project(BEREMIZ, "companyName=\"Unknown\" productName=\"Unnamed\"");
        assert!(written_by_matiec_tools(&xml));
    }

    #[test]
    fn a_header_naming_the_tools_is_enough() {
        for header in [
            "companyName=\"OpenPLC\" productName=\"Tank\"",
            "companyName=\"ACME\" productName=\"Beremiz\"",
            "companyName='openplc project' productName='x'",
        ] {
            assert!(written_by_matiec_tools(&project(PLAIN, header)), "{header}");
        }
    }

    #[test]
    fn other_tools_and_broken_files_are_not_taken_for_openplc() {
        let codesys = project(
            "xmlns=\"http://www.plcopen.org/xml/tc6_0200\"",
            "companyName=\"CODESYS Development GmbH\" productName=\"CODESYS\"",
        );
        assert!(!written_by_matiec_tools(&codesys));
        let own = project(PLAIN, "companyName=\"plcrun\" productName=\"plcrun\"");
        assert!(!written_by_matiec_tools(&own));
        // ns1 bound to another namespace is not the signature.
        let other = project(
            "xmlns:ns1=\"urn:other\" xmlns=\"http://www.plcopen.org/xml/tc6_0201\"",
            "companyName=\"x\" productName=\"y\"",
        );
        assert!(!written_by_matiec_tools(&other));
        assert!(!written_by_matiec_tools("<project companyName=\"OpenPLC\""));
        assert!(!written_by_matiec_tools("PROGRAM P END_PROGRAM"));
    }
}
