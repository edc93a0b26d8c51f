//! `--opcua-users FILE`: the users who may write, as salted password
//! hashes (PBKDF2 with HMAC-SHA-256). One user a line:
//!
//! ```text
//! # comment
//! operator:pbkdf2-sha256:100000:<salt, hex>:<hash, hex>
//! ```
//!
//! `plcrun opcua-user add FILE NAME` makes or replaces a line (the
//! password read from standard input); [`Users::add_to_file`] is the same
//! from Rust.

use hmac::{Hmac, Mac};
use sha2::Sha256;
use std::fmt;
use std::path::{Path, PathBuf};

/// The scheme name of a line.
const SCHEME: &str = "pbkdf2-sha256";
/// Iterations for a new entry.
pub const DEFAULT_ITERATIONS: u32 = 100_000;
/// Salt bytes for a new entry.
const SALT_BYTES: usize = 16;
/// The most iterations a line may ask for (a bound on the work one
/// login costs the server).
const MAX_ITERATIONS: u32 = 10_000_000;

/// One user's salted hash.
#[derive(Clone, PartialEq, Eq)]
struct Entry {
    name: String,
    iterations: u32,
    salt: Vec<u8>,
    hash: [u8; 32],
}

/// The users of a users file.
#[derive(Clone, Default, PartialEq, Eq)]
pub struct Users {
    entries: Vec<Entry>,
}

impl fmt::Debug for Users {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = self.entries.iter().map(|e| e.name.as_str()).collect();
        f.debug_struct("Users").field("names", &names).finish()
    }
}

/// Why a users file cannot be used.
#[derive(Debug)]
#[non_exhaustive]
pub enum UsersError {
    /// The file cannot be read or written.
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// A line is not `name:pbkdf2-sha256:iterations:salt:hash`.
    BadLine {
        /// The file.
        path: PathBuf,
        /// Its line number, from 1.
        line: usize,
        /// What is wrong.
        problem: String,
    },
    /// A user name that cannot be written in the file.
    BadName(String),
    /// No random salt could be drawn.
    Random(String),
}

impl fmt::Display for UsersError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UsersError::Io { path, source } => {
                write!(f, "users file `{}`: {source}", path.display())
            }
            UsersError::BadLine {
                path,
                line,
                problem,
            } => write!(f, "users file `{}`, line {line}: {problem}", path.display()),
            UsersError::BadName(name) => write!(
                f,
                "user name `{name}`: must be non-empty, without `:`, `#` or spaces"
            ),
            UsersError::Random(e) => write!(f, "cannot draw a random salt: {e}"),
        }
    }
}

impl std::error::Error for UsersError {}

impl Users {
    /// No users: every client is anonymous and reads only.
    pub fn none() -> Users {
        Users::default()
    }

    /// Reads a users file.
    pub fn load(path: &Path) -> Result<Users, UsersError> {
        let text = std::fs::read_to_string(path).map_err(|source| UsersError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Users::parse(&text, path)
    }

    /// Reads the text of a users file (`path` names it in errors).
    pub fn parse(text: &str, path: &Path) -> Result<Users, UsersError> {
        let mut entries: Vec<Entry> = Vec::new();
        for (k, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let bad = |problem: &str| UsersError::BadLine {
                path: path.to_path_buf(),
                line: k + 1,
                problem: problem.to_string(),
            };
            let entry = parse_line(line).map_err(bad)?;
            if entries.iter().any(|e| e.name == entry.name) {
                return Err(bad("the user is listed twice"));
            }
            entries.push(entry);
        }
        Ok(Users { entries })
    }

    /// Whether no user is listed.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The listed names.
    pub fn names(&self) -> Vec<&str> {
        self.entries.iter().map(|e| e.name.as_str()).collect()
    }

    /// Whether `password` is `name`'s.
    pub fn verify(&self, name: &str, password: &str) -> bool {
        let Some(e) = self.entries.iter().find(|e| e.name == name) else {
            return false;
        };
        let hash = pbkdf2(password.as_bytes(), &e.salt, e.iterations);
        // Compared without an early exit, so timing tells nothing.
        hash.iter()
            .zip(&e.hash)
            .fold(0u8, |acc, (a, b)| acc | (a ^ b))
            == 0
    }

    /// Adds `name` with `password` to the users file `path` (made if
    /// missing; a line for `name` already there is replaced), with a new
    /// random salt. On Unix a new file is readable by its owner only.
    pub fn add_to_file(path: &Path, name: &str, password: &str) -> Result<(), UsersError> {
        if name.is_empty() || name.contains([':', '#']) || name.chars().any(char::is_whitespace) {
            return Err(UsersError::BadName(name.to_string()));
        }
        let io = |source| UsersError::Io {
            path: path.to_path_buf(),
            source,
        };
        let old = match std::fs::read_to_string(path) {
            Ok(text) => text,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => String::new(),
            Err(e) => return Err(io(e)),
        };
        // The file must be one we can read back.
        Users::parse(&old, path)?;
        let mut salt = [0u8; SALT_BYTES];
        getrandom::getrandom(&mut salt).map_err(|e| UsersError::Random(e.to_string()))?;
        let hash = pbkdf2(password.as_bytes(), &salt, DEFAULT_ITERATIONS);
        let line = format!(
            "{name}:{SCHEME}:{DEFAULT_ITERATIONS}:{}:{}",
            hex(&salt),
            hex(&hash)
        );
        let mut text = String::new();
        if old.is_empty() {
            text.push_str("# plcrun OPC UA users: name:pbkdf2-sha256:iterations:salt:hash\n");
        }
        for l in old.lines() {
            if l.trim().split(':').next() != Some(name) {
                text.push_str(l);
                text.push('\n');
            }
        }
        text.push_str(&line);
        text.push('\n');
        write_private(path, &text).map_err(io)
    }
}

/// Writes `text` to `path`, owner-only on Unix when the file is new.
fn write_private(path: &Path, text: &str) -> std::io::Result<()> {
    use std::io::Write;
    let mut options = std::fs::OpenOptions::new();
    options.write(true).create(true).truncate(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.mode(0o600);
    }
    options.open(path)?.write_all(text.as_bytes())
}

/// One line's entry, or what is wrong with it.
fn parse_line(line: &str) -> Result<Entry, &'static str> {
    let parts: Vec<&str> = line.split(':').collect();
    let [name, scheme, iterations, salt, hash] = parts[..] else {
        return Err("expected name:pbkdf2-sha256:iterations:salt:hash");
    };
    if name.is_empty() {
        return Err("the user name is empty");
    }
    if scheme != SCHEME {
        return Err("the scheme is not pbkdf2-sha256");
    }
    let iterations: u32 = iterations
        .parse()
        .map_err(|_| "the iteration count is not a number")?;
    if iterations == 0 || iterations > MAX_ITERATIONS {
        return Err("the iteration count must be 1 to 10000000");
    }
    let salt = unhex(salt).ok_or("the salt is not hexadecimal")?;
    if salt.len() < 8 {
        return Err("the salt is shorter than 8 bytes");
    }
    let hash: [u8; 32] = unhex(hash)
        .and_then(|h| h.try_into().ok())
        .ok_or("the hash is not 64 hexadecimal digits")?;
    Ok(Entry {
        name: name.to_string(),
        iterations,
        salt,
        hash,
    })
}

/// PBKDF2 (RFC 8018) with HMAC-SHA-256, one 32-byte block.
fn pbkdf2(password: &[u8], salt: &[u8], iterations: u32) -> [u8; 32] {
    let mac = Hmac::<Sha256>::new_from_slice(password).expect("HMAC takes a key of any length");
    let mut first = mac.clone();
    first.update(salt);
    first.update(&1u32.to_be_bytes());
    let mut u: [u8; 32] = first.finalize().into_bytes().into();
    let mut out = u;
    for _ in 1..iterations {
        let mut next = mac.clone();
        next.update(&u);
        u = next.finalize().into_bytes().into();
        for (o, x) in out.iter_mut().zip(&u) {
            *o ^= x;
        }
    }
    out
}

/// Lower-case hexadecimal.
fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The bytes of a hexadecimal text.
fn unhex(text: &str) -> Option<Vec<u8>> {
    if !text.len().is_multiple_of(2) || !text.is_ascii() {
        return None;
    }
    (0..text.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&text[i..i + 2], 16).ok())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pbkdf2_matches_the_rfc_7914_vector() {
        // RFC 7914, section 11: PBKDF2-HMAC-SHA256 ("passwd", "salt", 1).
        let out = pbkdf2(b"passwd", b"salt", 1);
        assert_eq!(
            hex(&out),
            "55ac046e56e3089fec1691c22544b605f94185216dde0465e68b9d57c20dacbc"
        );
    }

    #[test]
    fn added_users_verify_and_bad_lines_are_located() {
        let dir = std::env::temp_dir().join(format!("plcrun-users-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("users");
        let _ = std::fs::remove_file(&path);
        Users::add_to_file(&path, "op", "secret").unwrap();
        Users::add_to_file(&path, "eng", "other").unwrap();
        Users::add_to_file(&path, "op", "changed").unwrap();
        let users = Users::load(&path).unwrap();
        assert_eq!(users.names(), ["eng", "op"]);
        assert!(users.verify("op", "changed"));
        assert!(!users.verify("op", "secret"));
        assert!(!users.verify("nobody", "changed"));
        assert!(Users::add_to_file(&path, "a:b", "x").is_err());
        let e = Users::parse("# c\nop:md5:1:00:00\n", &path).unwrap_err();
        assert!(e.to_string().contains("line 2"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
