//! `--opcua-expose GLOB`: which variables the server serves, by path.
//! `*` stands for any run of characters (dots and brackets included), `?`
//! for one character; letters match either case, as IEC names do.

/// A set of patterns; an empty set selects every variable.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Globs {
    patterns: Vec<Vec<char>>,
}

impl Globs {
    /// The patterns `patterns` (none: everything).
    pub fn new(patterns: &[String]) -> Globs {
        Globs {
            patterns: patterns
                .iter()
                .map(|p| p.trim().to_lowercase().chars().collect())
                .collect(),
        }
    }

    /// Whether `path` is selected.
    pub fn matches(&self, path: &str) -> bool {
        if self.patterns.is_empty() {
            return true;
        }
        let text: Vec<char> = path.to_lowercase().chars().collect();
        self.patterns.iter().any(|p| matches(p, &text))
    }
}

/// Whether `text` matches `pattern`: a linear walk that remembers the last
/// `*` and where it resumed, so no pattern can make it exponential.
fn matches(pattern: &[char], text: &[char]) -> bool {
    let (mut p, mut t) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while t < text.len() {
        if p < pattern.len() && (pattern[p] == '?' || pattern[p] == text[t]) {
            p += 1;
            t += 1;
        } else if p < pattern.len() && pattern[p] == '*' {
            star = Some((p, t));
            p += 1;
        } else if let Some((sp, st)) = star {
            p = sp + 1;
            t = st + 1;
            star = Some((sp, st + 1));
        } else {
            return false;
        }
    }
    pattern[p..].iter().all(|&c| c == '*')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn globs(p: &[&str]) -> Globs {
        Globs::new(&p.iter().map(|s| s.to_string()).collect::<Vec<_>>())
    }

    #[test]
    fn stars_questions_and_case() {
        let g = globs(&["t1.*", "KM??", "arr"]);
        assert!(g.matches("T1.ET"));
        assert!(g.matches("kmav"));
        assert!(!g.matches("kmavx"));
        assert!(g.matches("arr"));
        assert!(!g.matches("arr[1]"));
        assert!(!g.matches("t2.Q"));
        assert!(globs(&[]).matches("anything"));
        assert!(globs(&["*"]).matches(""));
        assert!(globs(&["a*b*c"]).matches("a.x[1].b.yc"));
        assert!(!globs(&["a*b*c"]).matches("a.x[1].b.y"));
    }
}
