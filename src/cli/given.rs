//! Which flags the user typed: `plcrun serve` lets them override the
//! project file, and `check`, `test` and `compare` let them override the
//! file's reading settings, while clap's defaults override nothing.

use clap::ArgMatches;
use clap::parser::ValueSource;
use std::collections::BTreeSet;

/// The ids (field names) of the arguments given on the command line.
#[derive(Debug, Default)]
pub struct Given(BTreeSet<String>);

impl Given {
    /// The arguments of `matches` that came from the command line.
    pub fn of(matches: &ArgMatches) -> Given {
        Given(
            matches
                .ids()
                .map(|id| id.as_str())
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
