//! `plcrun.toml`, the project file (docs/project-file.md): every key lands
//! on the flag of `plcrun run` it stands for (`plcrun serve --check`
//! prints the command a project amounts to), paths are relative to the
//! file's folder, globs expand, flags given to `serve` override the file,
//! and each kind of error has its code and its line:column.

use crate::support::cli;

use cli::{plcrun, temp_file};
use std::path::{Path, PathBuf};

const PROG: &str = "PROGRAM Main
VAR_INPUT start : BOOL; setpoint : INT; END_VAR
VAR_OUTPUT lamp : BOOL; level : INT; END_VAR
VAR valve : BOOL; END_VAR
lamp := start; level := setpoint;
END_PROGRAM
";

/// A fresh folder holding `files` (relative name, contents); its path.
fn project(files: &[(&str, &str)]) -> PathBuf {
    let first = temp_file(".keep", "");
    let dir = Path::new(&first).parent().unwrap().to_path_buf();
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

fn path_str(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `plcrun serve FILE --check EXTRA...`: exit status, stdout, stderr.
fn serve_check(file: &Path, extra: &[&str]) -> (i32, String, String) {
    let mut args = vec!["serve", path_str(file), "--check"];
    args.extend_from_slice(extra);
    plcrun(&args)
}

/// The command line a valid project amounts to.
fn command_of(file: &Path, extra: &[&str]) -> String {
    let (code, out, err) = serve_check(file, extra);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("ok: "), "{err}");
    out.trim().to_string()
}

/// The error output of an invalid project (exit status 2).
fn errors_of(file: &Path) -> String {
    let (code, out, err) = serve_check(file, &[]);
    assert_eq!(code, 2, "{out}{err}");
    err
}

#[test]
fn a_minimal_file_runs_its_source_in_real_time_without_a_trace() {
    let dir = project(&[
        ("main.st", PROG),
        ("plcrun.toml", "sources = [\"main.st\"]\n"),
    ]);
    let main = dir.join("main.st");
    assert_eq!(
        command_of(&dir.join("plcrun.toml"), &[]),
        format!("plcrun run --realtime --no-trace -- {}", main.display())
    );
}

#[test]
fn every_key_lands_on_its_flag() {
    let toml = r#"
sources = ["main.st"]
program = "Main"
cycle_time = "20ms"
watchdog = "0"
grafcet = true
optimize = false
max_data_mib = 64
encoding = "utf-8"
addressing = "openplc"
strict = true
stimulus = "stim.csv"
reload = true
stats = "json"

[realtime]
priority = 40
cpu = 1
lock_memory = false
cpu_sleep = true

[retain]
file = "state/plc.retain"
every = 50
partial = true

[set]
"Main.setpoint" = 12

[force]
Main.valve = true
"Main.level" = "INT#3"

[trace]
variables = ["Main.lamp", "Main.level"]
format = "jsonl"
changes_only = true
output = "out/trace.jsonl"

[modbus]
listen = "127.0.0.1:5020"
max_clients = 3
idle_timeout = "5s"

[web]
listen = "127.0.0.1:8081"
token = "0123456789abcdef"
"#;
    let dir = project(&[
        ("main.st", PROG),
        ("stim.csv", "cycle,Main.start\n0,TRUE\n"),
        ("plcrun.toml", toml),
    ]);
    let d = dir.display();
    let expected = format!(
        "plcrun run --realtime --cycle-time 20ms --program Main --watchdog 0 --grafcet \
         --no-optimize --max-data-mib 64 --encoding utf-8 --addressing openplc --strict \
         --stimulus {d}/stim.csv --reload --stats --stats-format json --rt-priority 40 --cpu 1 \
         --no-lock-memory --allow-cpu-sleep --retain {d}/state/plc.retain --retain-every 50 \
         --retain-partial --set Main.setpoint=12 --force Main.valve=TRUE \
         --force Main.level=INT#3 --trace Main.lamp,Main.level --format jsonl --changes-only \
         --output {d}/out/trace.jsonl --modbus 127.0.0.1:5020 --modbus-max-clients 3 \
         --modbus-idle-timeout 5s --web 127.0.0.1:8081 --web-token 0123456789abcdef \
         -- {d}/main.st"
    );
    let (code, out, err) = serve_check(&dir.join("plcrun.toml"), &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.trim(), expected);
}

#[cfg(feature = "opcua")]
#[test]
fn the_opcua_table_lands_on_the_opcua_flags() {
    let toml = r#"sources = ["main.st"]
[opcua]
listen = "4841"
expose = ["Main.*", "G*"]
users = "users.txt"
pki = "certs"
allow_insecure = true
trust_clients = true
"#;
    let dir = project(&[("main.st", PROG), ("plcrun.toml", toml)]);
    let d = dir.display();
    assert_eq!(
        command_of(&dir.join("plcrun.toml"), &[]),
        format!(
            "plcrun run --realtime --no-trace --opcua 4841 --opcua-expose 'Main.*' \
             --opcua-expose 'G*' --opcua-users {d}/users.txt --opcua-pki {d}/certs \
             --opcua-allow-insecure --opcua-trust-clients -- {d}/main.st"
        )
    );
    // Without `pki`, the certificates are kept next to the file too.
    let dir = project(&[
        ("main.st", PROG),
        (
            "plcrun.toml",
            "sources = [\"main.st\"]\n[opcua]\nlisten = \"127.0.0.1:0\"\n",
        ),
    ]);
    let command = command_of(&dir.join("plcrun.toml"), &[]);
    assert!(
        command.contains(&format!("--opcua-pki {}/opcua-pki", dir.display())),
        "{command}"
    );
}

#[test]
fn paths_are_relative_to_the_folder_of_the_file() {
    // The file is in conf/, the sources in src/, the command runs from the
    // repository root: only the file's folder counts.
    let dir = project(&[
        ("src/main.st", PROG),
        (
            "conf/plcrun.toml",
            "sources = [\"../src/main.st\"]\n[retain]\nfile = \"../state/a.retain\"\n",
        ),
    ]);
    let d = dir.display();
    assert_eq!(
        command_of(&dir.join("conf/plcrun.toml"), &[]),
        format!("plcrun run --realtime --retain {d}/state/a.retain --no-trace -- {d}/src/main.st")
    );
}

#[test]
fn globs_expand_in_path_order_and_name_each_file_once() {
    let dir = project(&[
        (
            "src/b.st",
            "PROGRAM B VAR_OUTPUT y : INT; END_VAR y := 2; END_PROGRAM\n",
        ),
        (
            "src/a.st",
            "PROGRAM A VAR_OUTPUT x : INT; END_VAR x := 1; END_PROGRAM\n",
        ),
        ("src/lib/c.st", "FUNCTION C : INT C := 3; END_FUNCTION\n"),
        ("src/notes.txt", "not a source"),
        (
            "plcrun.toml",
            "sources = [\"src/b.st\", \"src/**/*.st\", \"*.il\"]\nprogram = \"A\"\n",
        ),
    ]);
    let d = dir.display();
    // b.st first (named first), then the glob's other matches sorted; the
    // `*.il` glob matches nothing, which is allowed.
    assert_eq!(
        command_of(&dir.join("plcrun.toml"), &[]),
        format!(
            "plcrun run --realtime --program A --no-trace -- {d}/src/b.st {d}/src/a.st {d}/src/lib/c.st"
        )
    );
}

#[test]
fn flags_given_to_serve_override_the_file() {
    let toml = "sources = [\"main.st\"]\ncycle_time = \"20ms\"\n[force]\n\"Main.valve\" = true\n[modbus]\nlisten = \"127.0.0.1:5020\"\nmax_clients = 3\n";
    let dir = project(&[("main.st", PROG), ("plcrun.toml", toml)]);
    let d = dir.display();
    let command = command_of(
        &dir.join("plcrun.toml"),
        &[
            "--cycle-time",
            "5ms",
            "--modbus",
            "127.0.0.1:0",
            "--force",
            "Main.start=TRUE",
            "--trace",
            "Main.lamp",
            "--cycles",
            "7",
        ],
    );
    // Values replaced, forces added, a trace asked for is written; the
    // keys not overridden (max_clients) stay.
    assert_eq!(
        command,
        format!(
            "plcrun run --cycles 7 --realtime --cycle-time 5ms --force Main.valve=TRUE \
             --force Main.start=TRUE --trace Main.lamp --modbus 127.0.0.1:0 \
             --modbus-max-clients 3 -- {d}/main.st"
        )
    );
    // A flag that needs --realtime is accepted alone: serve is real time.
    let command = command_of(&dir.join("plcrun.toml"), &["--cpu", "0"]);
    assert!(command.contains("--cpu 0"), "{command}");
}

/// The first diagnostic's header: `error[CODE]: message` and `--> place`.
fn first_error(err: &str) -> (String, String) {
    let mut lines = err.lines().skip_while(|l| !l.starts_with("error["));
    let head = lines.next().unwrap_or_default().to_string();
    let place = lines.next().unwrap_or_default().trim().to_string();
    (head, place)
}

fn error_case(toml: &str) -> (String, String, String, PathBuf) {
    let dir = project(&[("main.st", PROG), ("plcrun.toml", toml)]);
    let file = dir.join("plcrun.toml");
    let err = errors_of(&file);
    let (head, place) = first_error(&err);
    (head, place, err, file)
}

#[test]
fn a_toml_syntax_error_is_e971_at_its_place() {
    let (head, place, err, file) = error_case("sources = [\"main.st\"]\ncycle_time = 10ms\n");
    assert!(head.starts_with("error[E971]: "), "{err}");
    assert_eq!(place, format!("--> {}:2:14", file.display()), "{err}");
    assert!(err.contains("2 | cycle_time = 10ms"), "{err}");
}

#[test]
fn an_unknown_key_is_e972_naming_the_key_and_its_table() {
    let (head, place, err, file) = error_case("sources = [\"main.st\"]\ncycle = \"10ms\"\n");
    assert!(
        head.starts_with("error[E972]: unknown key `cycle`"),
        "{err}"
    );
    assert_eq!(place, format!("--> {}:2:1", file.display()), "{err}");
    let (head, place, err, file) =
        error_case("sources = [\"main.st\"]\n\n[modbus]\nlisten = \"127.0.0.1:502\"\nport = 502\n");
    assert_eq!(
        head, "error[E972]: unknown key `port` in `[modbus]`",
        "{err}"
    );
    assert!(
        err.contains("= note: the keys here: listen, max_clients, idle_timeout"),
        "{err}"
    );
    assert_eq!(place, format!("--> {}:5:1", file.display()), "{err}");
    // An unknown table too.
    let (head, _, err, _) = error_case("sources = [\"main.st\"]\n[http]\nlisten = \"x\"\n");
    assert!(head.starts_with("error[E972]: unknown key `http`"), "{err}");
}

#[test]
fn a_value_of_the_wrong_type_is_e973_naming_the_key() {
    let (head, place, err, file) = error_case(
        "sources = [\"main.st\"]\n[modbus]\nlisten = \"127.0.0.1:502\"\nmax_clients = \"four\"\n",
    );
    assert!(
        head.starts_with("error[E973]: `modbus.max_clients`: invalid type"),
        "{err}"
    );
    assert_eq!(place, format!("--> {}:4:15", file.display()), "{err}");
    // A missing required key.
    let (head, _, err, _) = error_case("cycle_time = \"10ms\"\n");
    assert!(
        head.starts_with("error[E973]: missing key `sources`"),
        "{err}"
    );
    let (head, _, err, _) = error_case("sources = [\"main.st\"]\n[retain]\nevery = 5\n");
    assert!(
        head.starts_with("error[E973]: missing key `file` in `[retain]`"),
        "{err}"
    );
    // A value in [force] that is no value.
    let (head, place, err, file) =
        error_case("sources = [\"main.st\"]\n[force]\n\"Main.valve\" = [1, 2]\n");
    assert!(
        head.starts_with("error[E973]: `force.Main.valve`: an array"),
        "{err}"
    );
    assert_eq!(place, format!("--> {}:3:16", file.display()), "{err}");
}

#[test]
fn bad_values_are_e974_and_all_are_reported() {
    let toml = "sources = [\"main.st\"]
cycle_time = \"soon\"
watchdog = \"-1s\"
encoding = \"ebcdic\"
stats = \"loud\"
[realtime]
priority = 120
[modbus]
listen = \"nowhere\"
idle_timeout = \"0s\"
[web]
token = \"short\"
";
    let (head, place, err, file) = error_case(toml);
    assert!(
        head.starts_with("error[E974]: `cycle_time`: `soon` is not a duration"),
        "{err}"
    );
    assert_eq!(place, format!("--> {}:2:14", file.display()), "{err}");
    let f = file.display();
    for (message, at) in [
        ("`watchdog` must be 0 or more, not `-1s`", "3:12"),
        ("`encoding`: unknown encoding `ebcdic`", "4:12"),
        ("`stats`: `loud` is not one of", "5:9"),
        ("`realtime.priority` must be from 1 to 99, not 120", "7:12"),
        ("`modbus.listen`: `nowhere` is not HOST:PORT", "9:10"),
        ("`modbus.idle_timeout` must be positive, not `0s`", "10:16"),
        ("`web.token` must be at least 8 characters", "12:9"),
    ] {
        let found = err
            .split("error[E974]: ")
            .any(|d| d.starts_with(message) && d.contains(&format!("--> {f}:{at}\n")));
        assert!(found, "no E974 `{message}` at {at}:\n{err}");
    }
    assert!(err.ends_with("8 errors in the project file\n"), "{err}");
}

#[test]
fn sources_that_name_no_file_are_e975() {
    let (head, place, err, file) =
        error_case("sources = [\n  \"main.st\",\n  \"missing.st\",\n]\n");
    assert!(head.starts_with("error[E975]: `sources`: `"), "{err}");
    assert!(head.ends_with("missing.st` does not exist"), "{err}");
    assert_eq!(place, format!("--> {}:3:3", file.display()), "{err}");
    // Globs matching nothing at all.
    let (head, place, err, file) = error_case("sources = [\"src/*.st\", \"*.il\"]\n");
    assert!(
        head.starts_with("error[E975]: `sources` names no file"),
        "{err}"
    );
    assert_eq!(place, format!("--> {}:1:11", file.display()), "{err}");
    let (head, _, err, _) = error_case("sources = []\n");
    assert!(
        head.starts_with("error[E975]: `sources` names no file"),
        "{err}"
    );
    let (head, _, err, _) = error_case("sources = [\"src/***.st\"]\n");
    assert!(
        head.starts_with("error[E975]: `sources`: `src/***.st` is not a valid pattern"),
        "{err}"
    );
}

#[test]
fn a_missing_project_file_is_e970() {
    let dir = project(&[]);
    let file = dir.join("nothing.toml");
    let (code, _, err) = plcrun(&["serve", path_str(&file)]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.starts_with("error[E970]: cannot read the project file: "),
        "{err}"
    );
    assert!(err.contains("plcrun init"), "{err}");
    // No file named and none in the current folder (the repository's root).
    let (code, _, err) = plcrun(&["serve", "--check"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.starts_with("error[E970]: "), "{err}");
    assert!(err.contains("--> plcrun.toml"), "{err}");
}

#[test]
fn a_project_whose_sources_do_not_compile_fails_the_check() {
    let dir = project(&[
        ("main.st", "PROGRAM Main x := 1; END_PROGRAM\n"),
        ("plcrun.toml", "sources = [\"main.st\"]\n"),
    ]);
    let (code, out, err) = serve_check(&dir.join("plcrun.toml"), &[]);
    assert_eq!(code, 1, "{err}");
    assert!(out.is_empty(), "{out}");
    assert!(err.contains("error[E201]"), "{err}");
}

#[test]
fn a_folder_source_is_given_to_the_loader_as_it_is() {
    // A folder stands for its sources wherever a source file may be named.
    let dir = project(&[
        ("plc/main.st", PROG),
        ("plcrun.toml", "sources = [\"plc\"]\n"),
    ]);
    let (code, out, err) = serve_check(&dir.join("plcrun.toml"), &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("ok: 1 file checked"), "{err}");
    assert!(
        out.trim().ends_with(&format!("-- {}/plc", dir.display())),
        "{out}"
    );
}

#[test]
fn check_reports_set_and_force_lines_the_program_cannot_take_at_their_place() {
    let toml = "sources = [\"main.st\"]\n[set]\n\"Main.setpoint\" = 12\n\"Main.nothing\" = 1\n[force]\n\"Main.valve\" = \"maybe\"\n";
    let (head, place, err, file) = error_case(toml);
    assert_eq!(
        head, "error[E974]: `set.Main.nothing`: `Main.nothing`: Main has no member `nothing`",
        "{err}"
    );
    assert_eq!(place, format!("--> {}:4:18", file.display()), "{err}");
    let f = file.display();
    assert!(
        err.contains(
            "error[E974]: `force.Main.valve`: `Main.valve` is of type BOOL and cannot take `maybe`"
        ),
        "{err}"
    );
    assert!(err.contains(&format!("--> {f}:6:16\n")), "{err}");
    assert!(err.ends_with("2 errors in the project file\n"), "{err}");
}
