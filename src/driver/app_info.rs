//! TwinCAT's application information, `TwinCAT_SystemInfoVarList._AppInfo`
//! (a `PlcAppSystemInfo`): TcUnit strips the project's name from its test
//! paths with `_AppInfo.ProjectName`. plcrun declares it for a TwinCAT
//! project whose sources name it, in a source of its own, with what a
//! TwinCAT runtime would give the project's first PLC: its name (the
//! `.plcproj`'s `<Name>`), the ADS port 851 and the application name
//! `Port_851`. The rest is what no runtime here has (online changes,
//! persistent data, the build time: 0, FALSE, `DT#1970-01-01-00:00:00`,
//! so that every run is the same).

use super::event_classes::st_string;

/// The name of the source that declares it.
pub(crate) const APP_INFO_SOURCE: &str = "<TwinCAT application information>";

/// TwinCAT 3 gives its first PLC runtime this ADS port.
const FIRST_PLC_PORT: u32 = 851;

/// The source declaring `_AppInfo` for the project named `project`.
pub(crate) fn app_info_source(project: &str) -> String {
    format!(
        "VAR_GLOBAL\n  _AppInfo : PlcAppSystemInfo := (AdsPort := {FIRST_PLC_PORT}, \
         AppName := 'Port_{FIRST_PLC_PORT}', ProjectName := {});\nEND_VAR\n",
        st_string(&project.chars().take(63).collect::<String>())
    )
}

#[cfg(test)]
mod tests {
    use super::app_info_source;

    #[test]
    fn the_project_name_is_a_string_literal_of_at_most_63_characters() {
        let s = app_info_source("it's");
        assert!(s.contains("ProjectName := 'it$'s'"), "{s}");
        let long = "x".repeat(70);
        assert!(app_info_source(&long).contains(&format!("'{}'", "x".repeat(63))));
    }
}
