//! A reader that stops reading (`plcrun prog.st --cycles 100000 | head`)
//! closes the pipe plcrun prints into. Rust ignores SIGPIPE (so the
//! servers see a closed socket as an error, not a death), and `print!`
//! then panics on the broken pipe, and the trace writer gets an error. The
//! command line ends quietly instead,
//! with the status a process killed by SIGPIPE has (128 + 13), as other
//! command-line tools do.

/// Exit status of a command whose output pipe was closed.
pub(super) const BROKEN_PIPE_STATUS: i32 = 141;

/// Makes a panic of `print!` on a closed stdout or stderr end the process
/// quietly with [`BROKEN_PIPE_STATUS`]; any other panic is reported as
/// before.
pub(super) fn end_quietly_on_broken_pipe() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to std") && message.contains("Broken pipe") {
            std::process::exit(BROKEN_PIPE_STATUS);
        }
        previous(info);
    }));
}

/// True when `e` is a write into a closed pipe, also when it wraps one
/// (the CSV writer's error around the I/O error).
pub(super) fn is_broken_pipe(e: &std::io::Error) -> bool {
    let mut cause: Option<&(dyn std::error::Error + 'static)> = Some(e);
    // A chain of causes is short; the bound only guards a cycle.
    for _ in 0..16 {
        let Some(c) = cause else {
            return false;
        };
        if c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
        {
            return true;
        }
        let csv_io = c.downcast_ref::<csv::Error>().and_then(|e| match e.kind() {
            csv::ErrorKind::Io(io) => Some(io as &(dyn std::error::Error + 'static)),
            _ => None,
        });
        cause = csv_io.or_else(|| c.source()).or_else(|| {
            c.downcast_ref::<std::io::Error>()
                .and_then(|io| io.get_ref())
                .map(|inner| inner as &(dyn std::error::Error + 'static))
        });
    }
    false
}
