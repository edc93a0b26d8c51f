//! The web monitor's page in a real browser: headless Chromium (the
//! system's `chromium` package) loads it, runs its script, and dumps the
//! DOM; the variable table shows the program's values, and they change
//! between two loads. Without Chromium the test says so and passes
//! (`apt-get install chromium` to run it).

use crate::support::cli::temp_file;
use crate::web_cli::Monitor;
use std::path::Path;
use std::process::Command;

/// Where Debian's package puts the browser.
const CHROMIUM: &str = "/usr/bin/chromium";

/// The DOM of `url` after the page's script ran, from a fresh profile.
fn dump_dom(url: &str) -> String {
    let keep = temp_file(".keep", "");
    let profile_dir = Path::new(&keep).parent().unwrap().join("profile");
    std::fs::create_dir_all(&profile_dir).unwrap();
    // At most a minute: a browser that hangs fails the test, not CI.
    let out = Command::new("timeout")
        .args(["60", CHROMIUM])
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-dev-shm-usage",
            // navigator.webdriver: the page polls rather than streams, so
            // that the network settles and virtual time runs.
            "--enable-automation",
            &format!("--user-data-dir={}", profile_dir.display()),
            // Time for the fetches and the first events.
            "--virtual-time-budget=3000",
            "--dump-dom",
            url,
        ])
        .output()
        .expect("chromium runs");
    let _ = std::fs::remove_dir_all(&profile_dir);
    assert!(
        out.status.success(),
        "chromium failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The text of the value cell of the table row whose first cell is
/// `path`, in a dumped DOM.
fn shown_value(dom: &str, path: &str) -> Option<String> {
    let row_start = dom.find(&format!("<td>{path}</td>"))?;
    let row = &dom[row_start..];
    let row = &row[..row.find("</tr>")?];
    let cell = row.split("<td class=\"value\">").nth(1)?;
    Some(cell[..cell.find("</td>")?].to_string())
}

#[test]
fn the_page_shows_the_programs_values_and_they_change_between_two_loads() {
    if !Path::new(CHROMIUM).exists() {
        eprintln!(
            "skipped: {CHROMIUM} is not installed (apt-get install chromium); \
             the web page was not checked in a browser"
        );
        return;
    }
    let src = temp_file(
        "count.st",
        "PROGRAM Main
         VAR_OUTPUT count : DINT; label : STRING[20] := 'hello'; END_VAR
         count := count + 1;
         END_PROGRAM",
    );
    let m = Monitor::start(&["--cycle-time", "10ms", "--web-token", "browser-token", &src]);
    let url = format!("http://{}/", m.addr);
    let first = dump_dom(&url);
    assert!(first.contains("plcrun monitor"), "{first}");
    let a: i64 = shown_value(&first, "count")
        .unwrap_or_else(|| panic!("no value for count in the table:\n{first}"))
        .parse()
        .unwrap();
    assert_eq!(shown_value(&first, "label").as_deref(), Some("'hello'"));
    // The header shows the state and the cycle the values come from.
    assert!(first.contains("class=\"badge running\""), "{first}");
    std::thread::sleep(std::time::Duration::from_millis(500));
    let second = dump_dom(&url);
    let b: i64 = shown_value(&second, "count").unwrap().parse().unwrap();
    assert!(
        b > a,
        "count did not change between two loads: {a} then {b}"
    );
    assert!(a > 0, "the first load showed the initial value only");
}
