//! What the PLC sees of the event classes beyond `TC_EVENTS`:
//! `TC_EVENT_CLASSES`, TwinCAT's global list of the classes' GUIDs
//! (`TC_EVENT_CLASSES.TcSystemEventClass`), and the events' display texts,
//! which `FB_RequestEventText` gives. plcrun declares them, for the event
//! classes the loaded type descriptions declare (a project's `.tmc` lists
//! the system classes it uses too), in a source of its own added after the
//! descriptions: `TC_EVENT_CLASSES` as one constant structure with a GUID
//! member per class, and `plcrun_EventText` as a function over a table of
//! the texts, which replaces the TwinCAT library's (that one knows none).

use crate::syntax::twincat::type_description::{EventClassInfo, guid_value};
use std::collections::HashSet;

/// The name of the source that declares them.
pub(crate) const EVENT_CLASSES_SOURCE: &str = "<TwinCAT event classes>";

/// TwinCAT's own event classes, which its installation describes: a
/// project's type descriptions list the ones it uses only sometimes
/// (lcls-twincat-general's logger names all five, its `.tsproj` none).
/// Their GUIDs as TwinCAT's type descriptions give them; `None` for the
/// one no public description we found gives (it gets the null GUID).
const SYSTEM_CLASSES: [(&str, Option<&str>); 5] = [
    (
        "TcGeneralAdsEventClass",
        Some("{7D760066-D373-4A0C-B0F1-328B1620B0F0}"),
    ),
    (
        "TcRouterEventClass",
        Some("{E759605A-2341-48FC-9F3F-C8FA405C4B24}"),
    ),
    ("TcRTimeEventClass", None),
    (
        "TcSystemEventClass",
        Some("{BB2A9999-102E-421A-8D3D-B0660E07B1FE}"),
    ),
    (
        "Win32EventClass",
        Some("{4ABEFBBF-6620-4349-91AD-E6110A3BE851}"),
    ),
];

/// TwinCAT's own classes that sources naming `used` (upper case) name.
pub(crate) fn system_classes_named(used: &HashSet<String>) -> Vec<&'static str> {
    SYSTEM_CLASSES
        .iter()
        .map(|(name, _)| *name)
        .filter(|name| used.contains(&name.to_ascii_uppercase()))
        .collect()
}

/// The source declaring `TC_EVENT_CLASSES` and, when an event has a text,
/// `plcrun_EventText` for `classes` and the TwinCAT classes `system` the
/// sources name that no description declares; `None` when there is no
/// class.
pub(crate) fn event_classes_source(classes: &[EventClassInfo], system: &[&str]) -> Option<String> {
    let mut members: String = classes
        .iter()
        .map(|c| format!("  {} : GUID := {};\n", c.name, c.guid))
        .collect();
    for name in system {
        if classes.iter().any(|c| c.name.eq_ignore_ascii_case(name)) {
            continue;
        }
        let known = SYSTEM_CLASSES
            .iter()
            .find(|(n, _)| n == name)
            .and_then(|(_, g)| g.and_then(guid_value));
        members.push_str(&match known {
            Some(guid) => format!("  {name} : GUID := {guid};\n"),
            None => format!("  {name} : GUID; (* its GUID is not known to plcrun *)\n"),
        });
    }
    if members.is_empty() {
        return None;
    }
    let mut text = format!(
        "TYPE TC_EVENT_CLASSES_LIST :\nSTRUCT\n{members}END_STRUCT\nEND_TYPE\n\
         VAR_GLOBAL CONSTANT\n  TC_EVENT_CLASSES : TC_EVENT_CLASSES_LIST;\nEND_VAR\n"
    );
    let texts: Vec<(&str, u32, &str)> = classes
        .iter()
        .flat_map(|c| {
            c.texts
                .iter()
                .map(|(id, t)| (c.guid.as_str(), *id, t.as_str()))
        })
        .collect();
    if !texts.is_empty() {
        text.push_str(&text_function(&texts));
    }
    Some(text)
}

/// `plcrun_EventText(stClass, nEventId, bFound =>)`: the display text of
/// an event, looked up in constant tables of `texts` (class GUID value,
/// event number, text).
fn text_function(texts: &[(&str, u32, &str)]) -> String {
    let last = texts.len() - 1;
    let join = |f: &dyn Fn(&(&str, u32, &str)) -> String| {
        texts.iter().map(f).collect::<Vec<_>>().join(",\n    ")
    };
    let guids = join(&|t| t.0.to_string());
    let ids = join(&|t| t.1.to_string());
    let shown = join(&|t| st_string(t.2));
    format!(
        "FUNCTION plcrun_EventText : STRING(1023)\n\
         VAR_INPUT stClass : GUID; nEventId : UDINT; END_VAR\n\
         VAR_OUTPUT bFound : BOOL; END_VAR\n\
         VAR k : UDINT; END_VAR\n\
         VAR CONSTANT\n  aClass : ARRAY[0..{last}] OF GUID := [\n    {guids}];\n  \
         aId : ARRAY[0..{last}] OF UDINT := [\n    {ids}];\n  \
         aText : ARRAY[0..{last}] OF STRING(1023) := [\n    {shown}];\nEND_VAR\n\
         FOR k := 0 TO {last} DO\n  IF aId[k] = nEventId AND plcrun_SameGuid(aClass[k], stClass) THEN\n    \
         plcrun_EventText := aText[k];\n    bFound := TRUE;\n    RETURN;\n  END_IF\nEND_FOR\n\
         END_FUNCTION\n"
    )
}

/// `text` as an ST string literal: `$` and `'` escaped, line breaks and
/// tabs as `$N` and `$T`, other control characters dropped, at most
/// 1 023 characters.
pub(crate) fn st_string(text: &str) -> String {
    let mut out = String::from("'");
    for c in text.chars().take(1023) {
        match c {
            '$' => out.push_str("$$"),
            '\'' => out.push_str("$'"),
            '\n' => out.push_str("$N"),
            '\t' => out.push_str("$T"),
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
    out.push('\'');
    out
}

#[cfg(test)]
mod tests {
    use super::st_string;

    #[test]
    fn texts_are_escaped_as_st_literals() {
        assert_eq!(st_string("50 $ and 'x'\n"), "'50 $$ and $'x$'$N'");
    }
}
