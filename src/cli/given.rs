//! Which flags the user typed: `plcrun serve` lets them override the
//! project file, and `check`, `test` and `compare` let them override the
//! file's reading settings, while clap's defaults override nothing.

use clap::parser::ValueSource;
use clap::{ArgMatches, Command};
use std::collections::BTreeSet;

/// The ids (field names) of the arguments given on the command line.
#[derive(Debug, Default)]
pub struct Given(BTreeSet<String>);

impl Given {
    /// The arguments of `matches`, parsed by `command`, that came from the
    /// command line. Only arguments: the groups clap makes of flattened
    /// option structs (`OpcUaArgs`, `ReadingArgs`) are not flags.
    pub fn of(matches: &ArgMatches, command: &Command) -> Given {
        let arguments: BTreeSet<&str> = command
            .get_arguments()
            .map(|a| a.get_id().as_str())
            .collect();
        Given(
            matches
                .ids()
                .map(|id| id.as_str())
                .filter(|id| arguments.contains(id))
                .filter(|id| matches.value_source(id) == Some(ValueSource::CommandLine))
                .map(str::to_string)
                .collect(),
        )
    }

    /// Whether `id` was given.
    pub fn has(&self, id: &str) -> bool {
        self.0.contains(id)
    }

    /// The ids given, in name order.
    pub fn ids(&self) -> impl Iterator<Item = &str> {
        self.0.iter().map(String::as_str)
    }
}
