//! Who may change the PLC through the monitor: anyone may read; a write,
//! force, unforce or reset needs the token, given as `Authorization:
//! Bearer TOKEN` or `X-Plcrun-Token: TOKEN`. The token is set by
//! `--web-token` (or `web.token`), or drawn at random at start and printed.

/// Bytes of a random token (printed as twice as many hexadecimal digits).
const RANDOM_BYTES: usize = 16;

/// The shortest token accepted from the command line or the file.
pub(super) const MIN_TOKEN: usize = 8;

/// A random token from the operating system's generator.
pub(super) fn random_token() -> Result<String, String> {
    let mut bytes = [0u8; RANDOM_BYTES];
    getrandom::getrandom(&mut bytes)
        .map_err(|e| format!("E960: web: no random token could be drawn: {e}"))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// Checks a token given by the user.
pub(super) fn check_token(token: &str) -> Result<(), String> {
    if token.len() < MIN_TOKEN || token.chars().any(|c| c.is_whitespace() || c.is_control()) {
        return Err(format!(
            "E961: web: the token must be at least {MIN_TOKEN} characters, without spaces"
        ));
    }
    Ok(())
}

/// The token a request carries, if any (`headers` named in lower case).
pub(super) fn presented(headers: &[(String, String)]) -> Option<&str> {
    for (name, value) in headers {
        if name == "authorization" {
            if let Some((scheme, rest)) = value.trim().split_once(' ')
                && scheme.eq_ignore_ascii_case("bearer")
            {
                return Some(rest.trim());
            }
        } else if name == "x-plcrun-token" {
            return Some(value.trim());
        }
    }
    None
}

/// Whether `given` is `expected`, compared in a time that does not depend
/// on where they first differ.
pub(super) fn matches(given: &str, expected: &str) -> bool {
    let (a, b) = (given.as_bytes(), expected.as_bytes());
    let mut diff = u8::from(a.len() != b.len());
    for (i, &x) in b.iter().enumerate() {
        diff |= x ^ a.get(i).copied().unwrap_or(!x);
    }
    diff == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_same_token_matches() {
        assert!(matches("secret-token", "secret-token"));
        assert!(!matches("secret-tokeN", "secret-token"));
        assert!(!matches("secret-toke", "secret-token"));
        assert!(!matches("secret-token2", "secret-token"));
        assert!(!matches("", "secret-token"));
    }

    #[test]
    fn random_tokens_are_long_and_differ() {
        let (a, b) = (random_token().unwrap(), random_token().unwrap());
        assert_eq!(a.len(), 2 * RANDOM_BYTES);
        assert_ne!(a, b);
        assert!(check_token(&a).is_ok());
        assert!(check_token("short").is_err());
        assert!(check_token("has a space").is_err());
    }

    #[test]
    fn the_token_is_read_from_either_header() {
        let h = |f: &str, v: &str| (f.to_string(), v.to_string());
        assert_eq!(presented(&[h("authorization", "Bearer abc")]), Some("abc"));
        assert_eq!(
            presented(&[h("authorization", "bearer  abc ")]),
            Some("abc")
        );
        assert_eq!(presented(&[h("x-plcrun-token", "xyz")]), Some("xyz"));
        assert_eq!(presented(&[h("authorization", "Basic abc")]), None);
        assert_eq!(presented(&[]), None);
    }
}
