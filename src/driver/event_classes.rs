//! `TC_EVENT_CLASSES`: TwinCAT's global list of the event classes' GUIDs
//! (`TC_EVENT_CLASSES.TcSystemEventClass`, beside `TC_EVENTS.<class>.<event>`
//! for the events). plcrun declares it as one constant structure with a
//! GUID member per event class that the loaded type descriptions declare
//! (a project's `.tmc` lists the system classes it uses too), in a source
//! of its own added after the descriptions.

/// The name of the source that declares `TC_EVENT_CLASSES`.
pub(crate) const EVENT_CLASSES_SOURCE: &str = "<TwinCAT event classes>";

/// The source declaring `TC_EVENT_CLASSES` for `classes` (name, GUID
/// value); `None` when there is no class.
pub(crate) fn event_classes_source(classes: &[(String, String)]) -> Option<String> {
    if classes.is_empty() {
        return None;
    }
    let members: String = classes
        .iter()
        .map(|(class, guid)| format!("  {class} : GUID := {guid};\n"))
        .collect();
    Some(format!(
        "TYPE TC_EVENT_CLASSES_LIST :\nSTRUCT\n{members}END_STRUCT\nEND_TYPE\n\
         VAR_GLOBAL CONSTANT\n  TC_EVENT_CLASSES : TC_EVENT_CLASSES_LIST;\nEND_VAR\n"
    ))
}
