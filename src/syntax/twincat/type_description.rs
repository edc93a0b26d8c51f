//! TwinCAT type descriptions: the `<DataTypes>` of a PLC project's `.tmc`
//! (the module class TwinCAT writes beside the `.plcproj`) or of the
//! solution's `.tsproj` (its type system). A PLC project uses a type of the
//! type system by pinning it (`<PinnedGlobalDataType Include="ST_X_IO"/>`
//! in the `.plcproj`); no source file of the project declares it, so the
//! project loader reads it from there ([`narrowed`] keeps the pinned types
//! of the file) and this reader writes each `<DataType>` as the `TYPE` it
//! stands for: a structure (`<SubItem>`s, `<ExtendsType>`), an enumeration
//! (`<EnumInfo>`s over a `<BaseType>`) or an alias (`<BaseType>`, with
//! `<ArrayInfo>` for an array). The bit sizes and offsets are TwinCAT's
//! layout and are not needed: plcrun lays the type out itself.
//!
//! A `<DataType>` with `<EventId>`s is an event class of the TwinCAT
//! EventLogger; the PLC sees it as `TC_EVENTS.<class>.<event>`, a
//! `TcEventEntry` (the class's GUID, the event's number and severity).
//! The reader declares, for class `C`, a structure `TC_EVENTS_C` of one
//! `TcEventEntry` per event, initialised from the description, and a
//! global constant `C` of it: `TC_EVENTS.C.E` is that global named with
//! its list, as any global may be (plcrun's TwinCAT library declares
//! `TcEventEntry`).

use super::codes;
use crate::diagnostics::Diagnostics;
use crate::source::FileId;
use crate::syntax::ast::CompilationUnit;
use crate::syntax::construct::State;
use crate::syntax::parser;
use crate::syntax::plcopen::emit::{Emitter, Range, child, elements, is_identifier, open_xml};
use crate::syntax::plcopen::raw::content_range;
use roxmltree::{Document, Node};
use std::collections::HashSet;

/// True when `text` is a type description: a `.tmc` (`<TcModuleClass>`)
/// or a `.tsproj` (`<TcSmProject>`).
pub fn is_type_description(text: &str) -> bool {
    matches!(
        super::root_name(text),
        Some("TcModuleClass" | "TcSmProject")
    )
}

/// The `<DataType>` elements directly under the root's `<DataTypes>`.
fn data_types<'a, 'i>(doc: &'a Document<'i>) -> impl Iterator<Item = Node<'a, 'i>> {
    child(doc.root_element(), "DataTypes")
        .into_iter()
        .flat_map(elements)
        .filter(|n| n.has_tag_name("DataType"))
}

/// The text of a data type's `<Name>`, trimmed.
fn type_name<'a>(node: Node<'a, '_>) -> Option<&'a str> {
    child(node, "Name").and_then(|n| n.text()).map(str::trim)
}

/// True for an event class: a `<DataType>` with `<EventId>`s.
fn is_event_class(node: Node) -> bool {
    child(node, "EventId").is_some()
}

/// The names of plcrun's TwinCAT library a description's text needs
/// declared without naming them: the type of an event (its event classes
/// are structures of `TcEventEntry`).
pub fn library_names(text: &str) -> &'static [&'static str] {
    if text.contains("<EventId>") {
        &["TcEventEntry"]
    } else {
        &[]
    }
}

/// `text` with every `<DataType>` blanked out (spaces, line breaks kept)
/// except the current version of each type named in `names` (compared
/// ignoring case) and of each event class not in `events` (upper case;
/// those kept are added): so the file declares exactly those, and every
/// position in it is still the file's own. A type system keeps old
/// versions of a type beside the new one; the one no other `<Hides>` is
/// current. Returns the text and how many types it keeps; `None` when
/// `text` is not well-formed XML.
pub fn narrowed(
    text: &str,
    names: &[String],
    events: &mut HashSet<String>,
) -> Option<(String, usize)> {
    let base = text.len() - text.trim_start_matches('\u{FEFF}').len();
    let doc = crate::syntax::plcopen::read_xml(&text[base..]).ok()?;
    let wanted: HashSet<String> = names.iter().map(|n| n.to_ascii_uppercase()).collect();
    let hidden = hidden_versions(&doc);
    let mut taken: HashSet<String> = HashSet::new();
    let mut blank: Vec<std::ops::Range<usize>> = Vec::new();
    for node in data_types(&doc) {
        let name = type_name(node).unwrap_or("").to_ascii_uppercase();
        let guid = child(node, "Name")
            .and_then(|n| n.attribute("GUID"))
            .map(str::to_ascii_uppercase);
        let current = guid.is_none_or(|g| !hidden.contains(&g));
        let keep = if is_event_class(node) {
            current && !name.is_empty() && events.insert(name)
        } else {
            wanted.contains(&name) && current && taken.insert(name)
        };
        if !keep {
            blank.push(node.range());
        }
    }
    let kept = data_types(&doc).count() - blank.len();
    let narrowed = crate::source::blank_out(
        text,
        blank.into_iter().map(|r| base + r.start..base + r.end),
    )?;
    Some((narrowed, kept))
}

/// The global data types of a type system (`<Name PersistentType="true">`
/// in the `.tsproj`) that a project uses without pinning them: those named
/// in `used` (upper-case identifiers of its sources), and the persistent
/// types those name in turn, except the names in `shadowed` (upper case:
/// what the project declares or pins itself). TwinCAT gives a project
/// these types (LCLS General's logger declares `ST_LoggingEventInfo`
/// nowhere: its solution's type system holds it). Only a type's current
/// version counts. Empty when `text` is not well-formed XML.
pub fn persistent_types_used(
    text: &str,
    used: &HashSet<String>,
    shadowed: &HashSet<String>,
) -> Vec<String> {
    let base = text.len() - text.trim_start_matches('\u{FEFF}').len();
    let Ok(doc) = crate::syntax::plcopen::read_xml(&text[base..]) else {
        return Vec::new();
    };
    let hidden = hidden_versions(&doc);
    let persistent: Vec<(String, Node)> = data_types(&doc)
        .filter(|t| !is_event_class(*t))
        .filter(|t| {
            let name = child(*t, "Name");
            let flag = name.and_then(|n| n.attribute("PersistentType"));
            let guid = name.and_then(|n| n.attribute("GUID"));
            flag.is_some_and(|f| f.eq_ignore_ascii_case("true"))
                && guid.is_none_or(|g| !hidden.contains(&g.to_ascii_uppercase()))
        })
        .filter_map(|t| Some((type_name(t)?.to_ascii_uppercase(), t)))
        .filter(|(name, _)| !shadowed.contains(name))
        .collect();
    let mut named = used.clone();
    let mut taken: Vec<String> = Vec::new();
    // Each round takes the types named so far; a type taken names more.
    loop {
        let before = taken.len();
        for (name, node) in &persistent {
            if named.contains(name) && !taken.contains(name) {
                taken.push(name.clone());
                super::identifiers(&doc.input_text()[node.range()], &mut named);
            }
        }
        if taken.len() == before {
            return taken;
        }
    }
}

/// The GUIDs (upper case) of the type versions a newer one `<Hides>`.
fn hidden_versions(doc: &Document) -> HashSet<String> {
    data_types(doc)
        .filter_map(|t| child(t, "Hides"))
        .flat_map(elements)
        .filter_map(|h| h.attribute("GUID"))
        .map(str::to_ascii_uppercase)
        .collect()
}

/// An event class as the PLC sees it beyond `TC_EVENTS`: its name, its
/// GUID written as a `GUID` value (`TC_EVENT_CLASSES.<class>`), and the
/// display text of each event (`<DisplayName>`) by event number.
#[derive(Debug, Clone, PartialEq)]
pub struct EventClassInfo {
    /// The class's name.
    pub name: String,
    /// Its GUID as the initial value of a `GUID` structure.
    pub guid: String,
    /// (event number, display text) of each event that has a text.
    pub texts: Vec<(u32, String)>,
}

/// The event classes `text` declares in their current version. A class
/// without a well-formed GUID, or an event without a number, is left out
/// (its `TC_EVENTS` declaration reports it). Empty when `text` is not
/// well-formed XML.
pub fn event_classes(text: &str) -> Vec<EventClassInfo> {
    let base = text.len() - text.trim_start_matches('\u{FEFF}').len();
    let Ok(doc) = crate::syntax::plcopen::read_xml(&text[base..]) else {
        return Vec::new();
    };
    let hidden = hidden_versions(&doc);
    data_types(&doc)
        .filter(|t| is_event_class(*t))
        .filter_map(|t| {
            let name = child(t, "Name")?;
            let guid = name.attribute("GUID")?;
            if hidden.contains(&guid.to_ascii_uppercase()) {
                return None;
            }
            let class = name.text()?.trim();
            if !is_identifier(class) {
                return None;
            }
            let texts = elements(t)
                .filter(|c| c.has_tag_name("EventId"))
                .filter_map(|e| {
                    let id = child(e, "Name")?.attribute("Id").and_then(event_number)?;
                    let shown = child(e, "DisplayName")?.text()?.trim();
                    Some((id, shown.to_string()))
                })
                .collect();
            Some(EventClassInfo {
                name: class.to_string(),
                guid: guid_value(guid)?,
                texts,
            })
        })
        .collect()
}

/// Parses a type description into its types. Never panics, on any input;
/// every problem is a diagnostic pointing into `text`.
pub fn parse(file: FileId, text: &str, diags: &mut Diagnostics) -> CompilationUnit {
    let (mut em, doc) = open_xml(file, text, codes::MALFORMED_XML);
    let Some(doc) = doc else {
        diags.extend(em.diags);
        return CompilationUnit::default();
    };
    for node in data_types(&doc) {
        if is_event_class(node) {
            event_class(&mut em, node);
        } else {
            data_type(&mut em, node);
        }
    }
    let Emitter {
        toks, diags: found, ..
    } = em;
    let failed = found.has_errors();
    diags.extend(found);
    if failed {
        return CompilationUnit::default();
    }
    parser::parse_tokens(State::new(file, text), toks, diags)
}

/// The range of an element's text.
fn inner(node: Node) -> Option<Range> {
    content_range(node.document().input_text(), node.range())
}

/// Emits the tokens of an element's text at its position; reports an
/// element without text.
fn lex_text(em: &mut Emitter, node: Node) -> bool {
    match inner(node) {
        Some(range) if !node.text().unwrap_or("").trim().is_empty() => em.lex_range(range, false),
        _ => {
            em.error(
                codes::MISSING,
                em.at(node),
                format!("`<{}>` is empty", node.tag_name().name()),
            );
            false
        }
    }
}

/// Emits the identifier an element holds (a type's or field's `<Name>`).
fn name(em: &mut Emitter, node: Node, owner: Node) -> bool {
    let Some(n) = child(node, "Name") else {
        em.error(
            codes::MISSING,
            em.at(owner),
            format!("`<{}>` has no `<Name>`", owner.tag_name().name()),
        );
        return false;
    };
    identifier(em, n)
}

/// Emits the IEC identifier element `n` holds; E874 when it holds another
/// text.
fn identifier(em: &mut Emitter, n: Node) -> bool {
    checked_identifier(em, n).is_some() && lex_text(em, n)
}

/// The IEC identifier element `n` holds; E874 (and `None`) when it holds
/// another text.
fn checked_identifier<'a>(em: &mut Emitter, n: Node<'a, '_>) -> Option<&'a str> {
    let text = n.text().unwrap_or("").trim();
    if !is_identifier(text) {
        em.error(
            codes::UNDECLARABLE_TYPE,
            em.at(n),
            format!("`{text}` is not an IEC 61131-3 identifier"),
        );
        return None;
    }
    Some(text)
}

/// One `<DataType>`: `TYPE name [EXTENDS base] : <structure, enumeration
/// or alias> END_TYPE`.
fn data_type(em: &mut Emitter, node: Node) {
    let fields: Vec<Node> = elements(node)
        .filter(|c| c.has_tag_name("SubItem"))
        .collect();
    let values: Vec<Node> = elements(node)
        .filter(|c| c.has_tag_name("EnumInfo"))
        .collect();
    let base = child(node, "BaseType");
    let extends = child(node, "ExtendsType");
    let shape_known = !fields.is_empty() || extends.is_some() || base.is_some();
    if !shape_known || child(node, "Method").is_some() {
        let what = type_name(node).unwrap_or("?");
        em.error(
            codes::UNDECLARABLE_TYPE,
            em.at(node),
            format!(
                "`{what}` is not a structure, an enumeration or an alias: plcrun cannot declare it from the type description"
            ),
        );
        return;
    }
    em.synth("TYPE", em.at(node));
    if !name(em, node, node) {
        return;
    }
    if let Some(ext) = extends.filter(|_| values.is_empty()) {
        em.synth("EXTENDS", em.at(ext));
        if !lex_text(em, ext) {
            return;
        }
    }
    em.synth(":", em.at(node));
    let ok = if !values.is_empty() {
        enumeration(em, &values, base)
    } else if !fields.is_empty() || extends.is_some() {
        structure(em, node, &fields)
    } else {
        // An alias: `TYPE T : [ARRAY [..] OF] base; END_TYPE`.
        base.is_some_and(|b| type_of(em, node, b))
    };
    if ok {
        em.synth("; END_TYPE", em.end_of(node));
    }
}

/// An event class `C`: `TYPE TC_EVENTS_C : STRUCT E : TcEventEntry :=
/// (...); ... END_STRUCT END_TYPE` and `VAR_GLOBAL CONSTANT C :
/// TC_EVENTS_C; END_VAR`, one field per `<EventId>`: its `<Name>` with
/// the event's number in its `Id` attribute, and its `<Severity>`
/// (Verbose when it has none).
fn event_class(em: &mut Emitter, node: Node) {
    let Some(name_node) = child(node, "Name") else {
        em.error(codes::MISSING, em.at(node), "`<DataType>` has no `<Name>`");
        return;
    };
    let Some(class) = checked_identifier(em, name_node) else {
        return;
    };
    let Some(guid) = guid_value(name_node.attribute("GUID").unwrap_or("")) else {
        em.error(
            codes::UNDECLARABLE_TYPE,
            em.at(name_node),
            format!("event class `{class}` has no GUID of the form {{XXXXXXXX-XXXX-XXXX-XXXX-XXXXXXXXXXXX}}"),
        );
        return;
    };
    em.synth(&format!("TYPE TC_EVENTS_{class} : STRUCT"), em.at(node));
    for event in elements(node).filter(|c| c.has_tag_name("EventId")) {
        let Some(n) = child(event, "Name") else {
            em.error(codes::MISSING, em.at(event), "`<EventId>` has no `<Name>`");
            return;
        };
        let Some(id) = n.attribute("Id").and_then(event_number) else {
            em.error(
                codes::UNDECLARABLE_TYPE,
                em.at(n),
                "an event's `<Name>` needs its number in an `Id` attribute (`<Name Id=\"3\">` or `<Name Id=\"#x0003\">`)",
            );
            return;
        };
        let severity = child(event, "Severity")
            .and_then(|s| s.text())
            .map(str::trim)
            .unwrap_or("Verbose");
        if !SEVERITIES.iter().any(|s| s.eq_ignore_ascii_case(severity)) {
            let range = child(event, "Severity").map_or(em.at(event), |s| em.at(s));
            em.error(
                codes::UNDECLARABLE_TYPE,
                range,
                format!(
                    "`{severity}` is not a severity (one of {})",
                    SEVERITIES.join(", ")
                ),
            );
            return;
        }
        if !identifier(em, n) {
            return;
        }
        em.synth(
            &format!(
                ": TcEventEntry := (uuidEventClass := {guid}, nEventId := {id}, eSeverity := TcEventSeverity.{severity});"
            ),
            em.end_of(event),
        );
    }
    em.synth("END_STRUCT END_TYPE", em.end_of(node));
    em.synth(
        &format!("VAR_GLOBAL CONSTANT {class} : TC_EVENTS_{class}; END_VAR"),
        em.end_of(node),
    );
}

/// An event's number as a type description writes it: decimal (`3`) or,
/// as TwinCAT's type editor writes it, hexadecimal after `#x` (`#x0001`).
fn event_number(text: &str) -> Option<u32> {
    let text = text.trim();
    match text.strip_prefix("#x").or_else(|| text.strip_prefix("#X")) {
        Some(hex) => u32::from_str_radix(hex, 16).ok(),
        None => text.parse().ok(),
    }
}

/// Tc3_EventLogger's severities (`TcEventSeverity`).
const SEVERITIES: [&str; 5] = ["Verbose", "Info", "Warning", "Error", "Critical"];

/// A GUID written `{XXXXXXXX-XXXX-XXXX-XXXX-XXXXXXXXXXXX}` as the
/// initial value of a `GUID` structure.
pub(crate) fn guid_value(text: &str) -> Option<String> {
    let hex = text.trim().trim_start_matches('{').trim_end_matches('}');
    let parts: Vec<&str> = hex.split('-').collect();
    let widths = [8, 4, 4, 4, 12];
    if parts.len() != 5
        || parts
            .iter()
            .zip(widths)
            .any(|(p, w)| p.len() != w || !p.bytes().all(|b| b.is_ascii_hexdigit()))
    {
        return None;
    }
    let tail = format!("{}{}", parts[3], parts[4]);
    let bytes: Vec<String> = (0..8)
        .map(|k| format!("16#{}", &tail[2 * k..2 * k + 2]))
        .collect();
    Some(format!(
        "(Data1 := 16#{}, Data2 := 16#{}, Data3 := 16#{}, Data4 := [{}])",
        parts[0],
        parts[1],
        parts[2],
        bytes.join(", ")
    ))
}

/// `STRUCT field : type [:= value]; ... END_STRUCT`.
fn structure(em: &mut Emitter, node: Node, fields: &[Node]) -> bool {
    em.synth("STRUCT", em.at(node));
    for &field in fields {
        if !name(em, field, field) {
            return false;
        }
        em.synth(":", em.at(field));
        let Some(ty) = child(field, "Type") else {
            em.error(codes::MISSING, em.at(field), "`<SubItem>` has no `<Type>`");
            return false;
        };
        if !type_of(em, field, ty) {
            return false;
        }
        if let Some(default) = child(field, "Default")
            && !initial_value(em, default)
        {
            return false;
        }
        em.synth(";", em.end_of(field));
    }
    em.synth("END_STRUCT", em.end_of(node));
    true
}

/// `(text := value, ...) base`.
fn enumeration(em: &mut Emitter, values: &[Node], base: Option<Node>) -> bool {
    em.synth("(", em.at(values[0]));
    for (i, &value) in values.iter().enumerate() {
        if i > 0 {
            em.synth(",", em.at(value));
        }
        let (Some(text), Some(number)) = (child(value, "Text"), child(value, "Enum")) else {
            em.error(
                codes::MISSING,
                em.at(value),
                "`<EnumInfo>` needs a `<Text>` and an `<Enum>`",
            );
            return false;
        };
        if !identifier(em, text) {
            return false;
        }
        em.synth(":=", em.at(number));
        if !lex_text(em, number) {
            return false;
        }
    }
    em.synth(")", em.end_of(values[values.len() - 1]));
    match base {
        Some(b) => lex_text(em, b),
        None => true,
    }
}

/// The type of a field or alias: `[ARRAY [l..u, ...] OF] [POINTER TO |
/// REFERENCE TO] name`, from `owner`'s `<ArrayInfo>`s and the `PointerTo`
/// and `ReferenceTo` attributes of `ty`.
fn type_of(em: &mut Emitter, owner: Node, ty: Node) -> bool {
    let dims: Vec<Node> = elements(owner)
        .filter(|c| c.has_tag_name("ArrayInfo"))
        .collect();
    if !dims.is_empty() {
        let mut bounds = Vec::new();
        for dim in &dims {
            let number = |tag: &str| {
                child(*dim, tag)
                    .and_then(|n| n.text())
                    .and_then(|t| t.trim().parse::<i64>().ok())
            };
            match (number("LBound").unwrap_or(0), number("Elements")) {
                (low, Some(count)) if count > 0 => {
                    bounds.push(format!("{low}..{}", low + count - 1));
                }
                _ => {
                    em.error(
                        codes::MISSING,
                        em.at(*dim),
                        "`<ArrayInfo>` needs an `<Elements>` count above 0 (and an integer `<LBound>`)",
                    );
                    return false;
                }
            }
        }
        em.synth(&format!("ARRAY [{}] OF", bounds.join(", ")), em.at(dims[0]));
    }
    let flag = |attr: &str| {
        ty.attribute(attr)
            .is_some_and(|v| matches!(v.trim(), "1" | "true"))
    };
    if flag("PointerTo") {
        em.synth("POINTER TO", em.at(ty));
    } else if flag("ReferenceTo") {
        em.synth("REFERENCE TO", em.at(ty));
    }
    lex_text(em, ty)
}

/// `:= value` from a field's `<Default>`: a `<Value>` (a number or a
/// literal as written) or a `<String>`.
fn initial_value(em: &mut Emitter, default: Node) -> bool {
    if let Some(value) = child(default, "Value") {
        em.synth(":=", em.at(default));
        return lex_text(em, value);
    }
    if let Some(text) = child(default, "String") {
        let quoted = format!("'{}'", text.text().unwrap_or("").replace('\'', "$'"));
        em.synth(":=", em.at(default));
        em.synth(&quoted, em.at(text));
        return true;
    }
    // Only the bounds (`<Min>`, `<Max>`) or an enumeration's `<EnumText>`
    // without a value: the type's own default applies.
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::ast::Item;

    const SYSTEM: &str = r#"<?xml version="1.0"?>
<TcSmProject>
  <DataTypes>
    <DataType>
      <Name GUID="{A}">ST_Io</Name>
      <SubItem><Name>nOld</Name><Type>INT</Type></SubItem>
    </DataType>
    <DataType>
      <Name GUID="{B}">ST_Io</Name>
      <SubItem><Name>fWidth</Name><Type>REAL</Type><Default><Value>1.5</Value></Default></SubItem>
      <SubItem><Name>sId</Name><Type>STRING(80)</Type></SubItem>
      <SubItem><Name>aRaw</Name><Type>BYTE</Type><ArrayInfo><LBound>1</LBound><Elements>4</Elements></ArrayInfo></SubItem>
      <Hides><Hide GUID="{A}"/></Hides>
    </DataType>
    <DataType>
      <Name>E_Mode</Name>
      <BaseType>INT</BaseType>
      <EnumInfo><Text>Idle</Text><Enum>0</Enum></EnumInfo>
      <EnumInfo><Text>Run</Text><Enum>5</Enum></EnumInfo>
    </DataType>
    <DataType><Name>ST_Unpinned</Name><SubItem><Name>x</Name><Type>INT</Type></SubItem></DataType>
  </DataTypes>
</TcSmProject>"#;

    fn declared(text: &str) -> (Vec<String>, Diagnostics) {
        let mut diags = Diagnostics::new();
        let unit = parse(FileId(0), text, &mut diags);
        let names = unit
            .items
            .iter()
            .flat_map(|i| match i {
                Item::Types(ts) => ts.iter().map(|t| t.name.name.clone()).collect(),
                _ => Vec::new(),
            })
            .collect();
        (names, diags)
    }

    #[test]
    fn the_pinned_types_are_declared_in_their_current_version_at_their_own_positions() {
        let (narrowed, kept) = narrowed(
            SYSTEM,
            &["st_io".into(), "E_Mode".into()],
            &mut HashSet::new(),
        )
        .unwrap();
        assert_eq!(kept, 2);
        assert_eq!(narrowed.len(), SYSTEM.len());
        assert_eq!(narrowed.lines().count(), SYSTEM.lines().count());
        assert!(!narrowed.contains("nOld") && !narrowed.contains("ST_Unpinned"));
        let at = narrowed.find("fWidth").unwrap();
        assert_eq!(&SYSTEM[at..at + 6], "fWidth");
        let (names, diags) = declared(&narrowed);
        assert!(!diags.has_errors(), "{diags:?}");
        assert_eq!(names, ["ST_Io", "E_Mode"]);
    }

    #[test]
    fn a_type_that_is_no_structure_enumeration_or_alias_is_refused_by_name() {
        let text = "<TcModuleClass><DataTypes><DataType><Name>FB_X</Name><BitSize>8</BitSize></DataType></DataTypes></TcModuleClass>";
        let (_, diags) = declared(text);
        let d = diags.iter().next().unwrap();
        assert_eq!(d.code, codes::UNDECLARABLE_TYPE);
        assert!(d.message.contains("`FB_X`"), "{}", d.message);
    }

    #[test]
    fn an_event_class_is_declared_once_with_its_guid_numbers_and_severities() {
        let text = "<TcModuleClass><DataTypes><DataType><Name GUID=\"{97CF8247-B59C-4E2C-B4B0-7350D0471457}\">Ev</Name><EventId><Name Id=\"2\">Hot</Name><Severity>Error</Severity></EventId><EventId><Name Id=\"5\">Note</Name></EventId></DataType></DataTypes></TcModuleClass>";
        let mut events = HashSet::new();
        let (first, kept) = narrowed(text, &[], &mut events).unwrap();
        assert_eq!((first.as_str(), kept), (text, 1));
        // A second description declaring it again keeps nothing.
        assert_eq!(narrowed(text, &[], &mut events).unwrap().1, 0);
        let (names, diags) = declared(text);
        assert!(!diags.has_errors(), "{diags:?}");
        assert_eq!(names, ["TC_EVENTS_Ev"]);
        assert_eq!(
            guid_value("{97CF8247-B59C-4E2C-B4B0-7350D0471457}").unwrap(),
            "(Data1 := 16#97CF8247, Data2 := 16#B59C, Data3 := 16#4E2C, Data4 := [16#B4, 16#B0, 16#73, 16#50, 16#D0, 16#47, 16#14, 16#57])"
        );
        assert_eq!(guid_value("{97CF8247-B59C-4E2C-B4B0}"), None);
        assert_eq!(guid_value("{97CF8247-B59C-4E2C-B4B0-7350D047145G}"), None);
        assert_eq!(library_names(text), ["TcEventEntry"]);
        assert_eq!(
            [
                event_number("3"),
                event_number("#x0011"),
                event_number("#X2"),
                event_number("x")
            ],
            [Some(3), Some(17), Some(2), None]
        );
    }

    #[test]
    fn every_prefix_parses_without_panicking() {
        for end in (0..SYSTEM.len()).filter(|&e| SYSTEM.is_char_boundary(e)) {
            declared(&SYSTEM[..end]);
            narrowed(&SYSTEM[..end], &["ST_Io".into()], &mut HashSet::new());
        }
    }
}
