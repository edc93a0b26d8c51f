//! Colour and quietness of the command line's output: `--color
//! auto|always|never` (NO_COLOR respected) and `--quiet`, global flags set
//! once at start. Texts are built plain by the library and painted here,
//! so what a pipe or a file receives never holds an escape sequence unless
//! `--color always` asks for one.

use clap::ValueEnum;
use std::borrow::Cow;
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};

/// When to colour the output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum ColorChoice {
    /// On a terminal, unless NO_COLOR is set (to anything) or TERM is `dumb`.
    #[default]
    Auto,
    /// Always, even into a pipe or a file.
    Always,
    /// Never.
    Never,
}

static STDOUT_COLOR: AtomicBool = AtomicBool::new(false);
static STDERR_COLOR: AtomicBool = AtomicBool::new(false);
static QUIET: AtomicBool = AtomicBool::new(false);

/// Sets, once per process, what the flags asked for.
pub fn configure(color: ColorChoice, quiet: bool) {
    STDOUT_COLOR.store(
        wants_color(color, std::io::stdout().is_terminal()),
        Ordering::Relaxed,
    );
    STDERR_COLOR.store(
        wants_color(color, std::io::stderr().is_terminal()),
        Ordering::Relaxed,
    );
    QUIET.store(quiet, Ordering::Relaxed);
}

/// The choice read from the command line before clap parses it, so that
/// clap's own help and errors follow it too.
pub fn choice_in(words: &[std::ffi::OsString]) -> ColorChoice {
    let mut choice = ColorChoice::Auto;
    let mut words = words.iter().filter_map(|w| w.to_str());
    while let Some(word) = words.next() {
        let value = match word.strip_prefix("--color") {
            Some("") => words.next(),
            Some(rest) => rest.strip_prefix('='),
            None => None,
        };
        if let Some(c) = value.and_then(|v| ColorChoice::from_str(v, true).ok()) {
            choice = c;
        }
    }
    choice
}

/// Moves `--color WHEN` and `--quiet` written before a subcommand's name
/// (`plcrun --color never check a.st`) after it, where clap takes them: an
/// option before the name would otherwise make it a file of `run`.
pub fn globals_after_subcommand(
    words: Vec<std::ffi::OsString>,
    subcommands: &[String],
) -> Vec<std::ffi::OsString> {
    let mut globals = Vec::new();
    let mut i = 1;
    while let Some(word) = words.get(i).and_then(|w| w.to_str()) {
        let takes = match word {
            "--quiet" | "-q" => 1,
            "--color" => 2,
            w if w.starts_with("--color=") => 1,
            _ => break,
        };
        globals.extend(i..(i + takes).min(words.len()));
        i += takes;
    }
    let named = words.get(i).and_then(|w| w.to_str());
    if globals.is_empty() || !named.is_some_and(|n| subcommands.iter().any(|s| s == n)) {
        return words;
    }
    let mut moved: Vec<std::ffi::OsString> = Vec::with_capacity(words.len());
    moved.push(words[0].clone());
    moved.push(words[i].clone());
    moved.extend(globals.iter().map(|&g| words[g].clone()));
    moved.extend(words[i + 1..].iter().cloned());
    moved
}

/// clap's spelling of `choice`.
pub fn for_clap(choice: ColorChoice) -> clap::ColorChoice {
    match choice {
        ColorChoice::Auto => clap::ColorChoice::Auto,
        ColorChoice::Always => clap::ColorChoice::Always,
        ColorChoice::Never => clap::ColorChoice::Never,
    }
}

fn wants_color(choice: ColorChoice, terminal: bool) -> bool {
    match choice {
        ColorChoice::Always => true,
        ColorChoice::Never => false,
        ColorChoice::Auto => {
            terminal
                && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
                && std::env::var_os("TERM").is_none_or(|t| t != "dumb")
        }
    }
}

/// Whether `--quiet` was given: no progress bars, no "ok" lines.
pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// Whether standard error is coloured.
pub fn stderr_colored() -> bool {
    STDERR_COLOR.load(Ordering::Relaxed)
}

const RESET: &str = "\x1b[0m";
const BOLD_RED: &str = "\x1b[1;31m";
const BOLD_YELLOW: &str = "\x1b[1;33m";
const BOLD_CYAN: &str = "\x1b[1;36m";
const BOLD_BLUE: &str = "\x1b[1;34m";
const BOLD_GREEN: &str = "\x1b[1;32m";
const BOLD: &str = "\x1b[1m";

/// The colour of a message's severity word at the start of `line`
/// (`error[E201]:`, `warning:`, `note:`), and that word's length.
fn severity_at(line: &str) -> Option<(&'static str, usize)> {
    for (word, color) in [
        ("error", BOLD_RED),
        ("warning", BOLD_YELLOW),
        ("note", BOLD_CYAN),
        ("help", BOLD_CYAN),
    ] {
        let Some(rest) = line.strip_prefix(word) else {
            continue;
        };
        let code = if rest.starts_with('[') {
            rest.find(']').map_or(0, |i| i + 1)
        } else {
            0
        };
        if rest[code..].starts_with(':') {
            return Some((color, word.len() + code));
        }
    }
    None
}

/// The gutter of an excerpt line (` --> `, `  |`, `12 | `): its length.
fn gutter_at(line: &str) -> Option<usize> {
    let trimmed = line.trim_start_matches(|c: char| c == ' ' || c.is_ascii_digit());
    let lead = line.len() - trimmed.len();
    if trimmed.starts_with("--> ") {
        Some(lead + 3)
    } else if trimmed == "|" || trimmed.starts_with("| ") {
        Some(lead + 1)
    } else {
        None
    }
}

/// Paints diagnostics and other messages for standard error: severity
/// words in their colour, the message bold, gutters blue, carets in the
/// colour of the message they mark. Unchanged when stderr is not coloured.
pub fn messages(text: &str) -> Cow<'_, str> {
    paint_messages(text, stderr_colored())
}

fn paint_messages(text: &str, on: bool) -> Cow<'_, str> {
    if !on {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 64);
    let mut caret_color = BOLD_RED;
    for line in text.split_inclusive('\n') {
        let (body, end) = match line.strip_suffix('\n') {
            Some(b) => (b, "\n"),
            None => (line, ""),
        };
        if let Some((color, len)) = severity_at(body) {
            caret_color = color;
            let (word, message) = body.split_at(len);
            out.push_str(&format!("{color}{word}{RESET}{BOLD}{message}{RESET}{end}"));
        } else if let Some(len) = gutter_at(body) {
            let (gutter, rest) = body.split_at(len);
            let rest = match rest.find('^') {
                Some(at) if rest[..at].trim().is_empty() => {
                    let (space, carets) = rest.split_at(at);
                    format!("{space}{caret_color}{carets}{RESET}")
                }
                _ => rest.to_string(),
            };
            out.push_str(&format!("{BOLD_BLUE}{gutter}{RESET}{rest}{end}"));
        } else if body.ends_with(" warnings") || body.ends_with(" warning") {
            out.push_str(&format!("{BOLD}{body}{RESET}{end}"));
        } else {
            out.push_str(line);
        }
    }
    Cow::Owned(out)
}

/// Paints a report for standard output: a test's `PASS` green, `FAIL` and
/// `ERROR` red, `SKIP` yellow; a comparison's verdict `EQUIVALENT` green,
/// `DIFFERENT` red.
pub fn report(text: &str) -> Cow<'_, str> {
    paint_report(text, STDOUT_COLOR.load(Ordering::Relaxed))
}

fn paint_report(text: &str, on: bool) -> Cow<'_, str> {
    if !on {
        return Cow::Borrowed(text);
    }
    const WORDS: [(&str, &str); 6] = [
        ("PASS", BOLD_GREEN),
        ("FAIL", BOLD_RED),
        ("ERROR", BOLD_RED),
        ("SKIP", BOLD_YELLOW),
        ("EQUIVALENT", BOLD_GREEN),
        ("DIFFERENT", BOLD_RED),
    ];
    let mut out = String::with_capacity(text.len() + 64);
    for line in text.split_inclusive('\n') {
        let (lead, rest) = match line.strip_prefix("verdict: ") {
            Some(rest) => ("verdict: ", rest),
            None => ("", line),
        };
        let painted = WORDS.into_iter().find_map(|(word, color)| {
            rest.strip_prefix(word)
                .map(|after| format!("{lead}{color}{word}{RESET}{after}"))
        });
        out.push_str(painted.as_deref().unwrap_or(line));
    }
    Cow::Owned(out)
}

/// Prints a message to standard error, painted by [`messages`].
macro_rules! say {
    ($($arg:tt)*) => {
        eprint!("{}", $crate::cli::style::messages(&format!($($arg)*)))
    };
}

/// [`say!`] with a newline.
macro_rules! sayln {
    ($($arg:tt)*) => {
        eprintln!("{}", $crate::cli::style::messages(&format!($($arg)*)))
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(list: &[&str]) -> Vec<std::ffi::OsString> {
        list.iter().map(Into::into).collect()
    }

    #[test]
    fn the_choice_is_found_in_either_spelling() {
        assert_eq!(
            choice_in(&words(&["plcrun", "check", "a.st"])),
            ColorChoice::Auto
        );
        assert_eq!(
            choice_in(&words(&["plcrun", "--color", "never", "a.st"])),
            ColorChoice::Never
        );
        assert_eq!(
            choice_in(&words(&["plcrun", "test", "--color=always"])),
            ColorChoice::Always
        );
        // A bad value is clap's to report.
        assert_eq!(
            choice_in(&words(&["plcrun", "--color=pink"])),
            ColorChoice::Auto
        );
    }

    #[test]
    fn global_flags_before_a_subcommand_move_after_it() {
        let subs = vec!["check".to_string(), "test".to_string()];
        let moved = globals_after_subcommand(
            words(&["plcrun", "--color", "never", "-q", "check", "a.st"]),
            &subs,
        );
        assert_eq!(
            moved,
            words(&["plcrun", "check", "--color", "never", "-q", "a.st"])
        );
        // Before files of `run`, or already after the name: left alone.
        let run = words(&["plcrun", "--color=always", "a.st", "--cycles", "3"]);
        assert_eq!(globals_after_subcommand(run.clone(), &subs), run);
        let after = words(&["plcrun", "test", "--quiet", "a.st"]);
        assert_eq!(globals_after_subcommand(after.clone(), &subs), after);
    }

    #[test]
    fn severity_words_and_gutters_are_recognised() {
        assert_eq!(severity_at("error[E201]: undeclared"), Some((BOLD_RED, 11)));
        assert_eq!(severity_at("warning: x"), Some((BOLD_YELLOW, 7)));
        assert_eq!(severity_at("errors: 3"), None);
        assert_eq!(severity_at("error[E201 no colon"), None);
        assert_eq!(gutter_at(" --> a.st:1:2"), Some(4));
        assert_eq!(gutter_at("  |"), Some(3));
        assert_eq!(gutter_at("12 | x := 1;"), Some(4));
        assert_eq!(gutter_at("x | y"), None);
    }

    #[test]
    fn painting_keeps_the_text() {
        let plain = "warning[W150]: ignored\n --> a.st:1:2\n  |\n1 | x := 1;\n  | ^\n\n1 error, 1 warning\n";
        let painted = paint_messages(plain, true).into_owned();
        assert!(painted.contains("\x1b[1;33mwarning[W150]\x1b[0m"));
        assert!(painted.contains("\x1b[1;33m^\x1b[0m"), "{painted:?}");
        assert_eq!(strip(&painted), plain);
        assert_eq!(paint_messages(plain, false), plain);
        let report =
            "PASS  TEST_A (a.st, 1 cycle)\nFAIL  TEST_B (a.st, 1 cycle)\n2 tests: 1 passed\n";
        let painted = paint_report(report, true).into_owned();
        assert!(painted.starts_with("\x1b[1;32mPASS\x1b[0m"));
        assert_eq!(strip(&painted), report);
        let verdict = "lag: none\nverdict: DIFFERENT (1 of 9 seeds differ)\n";
        let painted = paint_report(verdict, true).into_owned();
        assert!(painted.contains("verdict: \x1b[1;31mDIFFERENT\x1b[0m (1 of"));
        assert_eq!(strip(&painted), verdict);
    }

    fn strip(s: &str) -> String {
        let mut out = String::new();
        let mut chars = s.chars();
        while let Some(c) = chars.next() {
            if c == '\x1b' {
                for c in chars.by_ref() {
                    if c == 'm' {
                        break;
                    }
                }
            } else {
                out.push(c);
            }
        }
        out
    }
}
