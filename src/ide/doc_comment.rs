//! The comment that documents a declaration: the comment lines right above
//! it, or the comment after it on the same line (`speed : INT; (* rpm *)`),
//! the two places PLC code puts one.

/// The documentation comment of the declaration spanning `start..end` of
/// `text`, without its comment markers; `None` when there is none.
pub(super) fn doc_comment(text: &str, start: usize, end: usize) -> Option<String> {
    let above = comment_above(text, start);
    let after = comment_after(text, end);
    let parts: Vec<String> = above.into_iter().chain(after).collect();
    (!parts.is_empty()).then(|| parts.join("\n"))
}

/// The comment ending on the line before the one `start` is on.
fn comment_above(text: &str, start: usize) -> Option<String> {
    let line_start = text.get(..start)?.rfind('\n').map_or(0, |i| i + 1);
    if !text[line_start..start].trim().is_empty() {
        return None;
    }
    let before = text[..line_start].trim_end();
    if let Some(open) = before.strip_suffix("*)").and_then(|b| b.rfind("(*")) {
        let open_line = before[..open].rfind('\n').map_or(0, |i| i + 1);
        if !before[open_line..open].trim().is_empty() {
            return None;
        }
        return Some(strip_block(&before[open..]));
    }
    let mut lines: Vec<&str> = before
        .lines()
        .rev()
        .map(str::trim)
        .take_while(|l| l.starts_with("//"))
        .map(|l| l.trim_start_matches('/').trim())
        .collect();
    lines.reverse();
    (!lines.is_empty()).then(|| lines.join("\n"))
}

/// The comment after `end` on the same line.
fn comment_after(text: &str, end: usize) -> Option<String> {
    let rest = text.get(end..)?;
    let line = rest.split('\n').next().unwrap_or("");
    let line = line.trim_start_matches(';').trim();
    if let Some(comment) = line.strip_prefix("//") {
        let comment = comment.trim();
        return (!comment.is_empty()).then(|| comment.to_string());
    }
    if line.starts_with("(*") {
        let close = rest.find("*)")?;
        let open = rest.find("(*")?;
        return Some(strip_block(&rest[open..close + 2]));
    }
    None
}

/// The text of a `(* ... *)` comment, its lines trimmed.
fn strip_block(comment: &str) -> String {
    let inner = comment
        .strip_prefix("(*")
        .and_then(|c| c.strip_suffix("*)"))
        .unwrap_or(comment);
    inner
        .lines()
        .map(|l| l.trim().trim_start_matches('*').trim())
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::doc_comment;

    fn doc(text: &str, decl: &str) -> Option<String> {
        let start = text.find(decl).unwrap();
        doc_comment(text, start, start + decl.len())
    }

    #[test]
    fn comment_lines_above_document_the_declaration() {
        let text = "VAR\n  // motor speed\n  // in rpm\n  speed : INT;\nEND_VAR";
        assert_eq!(doc(text, "speed : INT"), Some("motor speed\nin rpm".into()));
    }

    #[test]
    fn a_block_comment_above_or_after_on_the_line() {
        let text = "(* The conveyor.\n * Runs forward. *)\nFUNCTION_BLOCK Conveyor";
        assert_eq!(
            doc(text, "FUNCTION_BLOCK Conveyor"),
            Some("The conveyor.\nRuns forward.".into())
        );
        let text = "VAR\n  x : BOOL; (* lamp *)\n  y : BOOL;\nEND_VAR";
        assert_eq!(doc(text, "x : BOOL"), Some("lamp".into()));
        assert_eq!(doc(text, "y : BOOL"), None);
    }

    #[test]
    fn code_on_the_line_above_is_not_documentation() {
        let text = "a := 1; (* set *)\nb : INT;";
        assert_eq!(doc(text, "b : INT"), None);
    }
}
