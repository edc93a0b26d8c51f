//! The flags given with `plcrun serve`, laid over the options the project
//! file filled: field by field, only those the user typed.

use super::super::args::RunArgs;
use super::super::given::Given;

/// Replaces each field of `base` whose flag was given by the value of
/// `cli`; `--set` and `--force` add to the file's lists (a later item for
/// the same name wins). `files` (the project file), serve's own flags and
/// the global ones are not options of the run. A flag this list does not know is refused
/// rather than silently dropped.
pub fn apply(base: &mut RunArgs, cli: &RunArgs, given: &Given) -> Result<(), String> {
    // `color` and `quiet` are the whole command line's, not the run's.
    let mut known: Vec<&str> = vec!["files", "check", "color", "quiet"];
    macro_rules! replace {
        ($($($field:ident).+),* $(,)?) => {$({
            let id = last!($($field).+);
            known.push(id);
            if given.has(id) {
                base.$($field).+ = cli.$($field).+.clone();
            }
        })*};
    }
    macro_rules! last {
        ($only:ident) => { stringify!($only) };
        ($first:ident . $($rest:ident).+) => { last!($($rest).+) };
    }
    replace!(
        cycles,
        cycle_time,
        program,
        stimulus,
        trace,
        format,
        changes_only,
        output,
        no_trace,
        watchdog,
        realtime,
        rt_priority,
        cpu,
        no_lock_memory,
        allow_cpu_sleep,
        stats,
        stats_format,
        online_change_at,
        reload,
        retain,
        retain_every,
        cold,
        retain_partial,
        svg,
        svg_chart,
        svg_chart_cycle,
        grafcet,
        modbus,
        modbus_max_clients,
        modbus_idle_timeout,
        web,
        web_token,
        max_data_mib,
        no_optimize,
        reading.strict,
        reading.encoding,
        reading.addressing,
    );
    #[cfg(feature = "opcua")]
    replace!(
        opcua.opcua,
        opcua.opcua_expose,
        opcua.opcua_users,
        opcua.opcua_pki,
        opcua.opcua_allow_insecure,
        opcua.opcua_trust_clients,
    );
    for (id, list, added) in [
        ("set", &mut base.set, &cli.set),
        ("force", &mut base.force, &cli.force),
    ] {
        known.push(id);
        if given.has(id) {
            list.extend(added.iter().cloned());
        }
    }
    // A trace asked for on the command line is written.
    if ["trace", "output", "changes_only"]
        .iter()
        .any(|id| given.has(id))
        && !given.has("no_trace")
    {
        base.no_trace = false;
    }
    match given.ids().find(|id| !known.contains(id)) {
        Some(id) => Err(format!(
            "`--{}` cannot be given to `plcrun serve`",
            id.replace('_', "-")
        )),
        None => Ok(()),
    }
}
