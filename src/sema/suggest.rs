//! "Did you mean ...?" for misspelt names: the closest candidate by edit
//! distance (case-insensitive, a swap of two neighbours counts as one
//! edit), offered only when it is close: at most one edit for names of up
//! to four characters, two up to eight, three beyond.

/// Standard functions offered for a misspelt function name (the typed
/// variants and conversions are too many to be useful suggestions).
pub const STANDARD_FUNCTIONS: [&str; 48] = [
    "ABS", "SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "ADD", "SUB",
    "MUL", "DIV", "MOD", "EXPT", "MOVE", "SHL", "SHR", "ROL", "ROR", "AND", "OR", "XOR", "NOT",
    "SEL", "MAX", "MIN", "LIMIT", "MUX", "GT", "GE", "EQ", "LE", "LT", "NE", "LEN", "LEFT",
    "RIGHT", "MID", "CONCAT", "INSERT", "DELETE", "REPLACE", "FIND", "TRUNC", "ATAN2",
];

/// Standard function block types offered for a misspelt type name.
pub const STANDARD_FBS: [&str; 10] = [
    "TON", "TOF", "TP", "CTU", "CTD", "CTUD", "R_TRIG", "F_TRIG", "SR", "RS",
];

/// Edit distance between `a` and `b`, ignoring ASCII case: insertions,
/// deletions, substitutions and transpositions of neighbours cost one.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().map(|c| c.to_ascii_uppercase()).collect();
    let b: Vec<char> = b.chars().map(|c| c.to_ascii_uppercase()).collect();
    // Three rows of the optimal-string-alignment table.
    let mut before: Vec<usize> = vec![0; b.len() + 1];
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur: Vec<usize> = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        cur[0] = i;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut d = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d = d.min(before[j - 2] + 1);
            }
            cur[j] = d;
        }
        std::mem::swap(&mut before, &mut prev);
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// The most edits a suggestion for `name` may be away.
fn max_edits(name: &str) -> usize {
    match name.chars().count() {
        0..=4 => 1,
        5..=8 => 2,
        _ => 3,
    }
}

/// The candidate closest to `name`, if one is close enough (ties: the
/// alphabetically first, so messages are stable). A candidate equal to
/// `name` apart from case is not a suggestion.
pub fn closest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let limit = max_edits(name);
    let mut best: Option<(usize, &'a str)> = None;
    for c in candidates {
        if c.is_empty() || c.eq_ignore_ascii_case(name) {
            continue;
        }
        // Lengths further apart than the limit cannot be close.
        if c.chars().count().abs_diff(name.chars().count()) > limit {
            continue;
        }
        let d = edit_distance(name, c);
        if d > limit {
            continue;
        }
        let better = match best {
            None => true,
            Some((bd, bc)) => {
                d < bd || (d == bd && c.to_ascii_uppercase() < bc.to_ascii_uppercase())
            }
        };
        if better {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c)
}

/// `message` followed by "; did you mean `x`?" when a candidate is close.
pub fn with_suggestion<'a>(
    message: String,
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> String {
    match closest(name, candidates) {
        Some(c) => format!("{message}; did you mean `{c}`?"),
        None => message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(edit_distance("counter", "counter"), 0);
        assert_eq!(edit_distance("countr", "counter"), 1);
        assert_eq!(edit_distance("cuonter", "counter"), 1);
        assert_eq!(edit_distance("COUNTER", "counter"), 0);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }

    #[test]
    fn only_close_names_are_offered() {
        let names = ["Counter", "Limit", "Start", "x"];
        assert_eq!(closest("countr", names), Some("Counter"));
        assert_eq!(closest("LIMTI", names), Some("Limit"));
        assert_eq!(closest("y", names), Some("x"));
        assert_eq!(closest("speed", names), None);
        assert_eq!(
            closest("counter", names),
            None,
            "same name is no suggestion"
        );
        assert_eq!(
            with_suggestion("undeclared variable `strat`".into(), "strat", names),
            "undeclared variable `strat`; did you mean `Start`?"
        );
    }
}
