//! ST expressions a debugger evaluates (watches, conditional breakpoints):
//! literals, variable paths, `NOT`, unary `-`, `**`-free arithmetic
//! (`+ - * / MOD`), comparisons, `AND`/`&`, `XOR`, `OR`, parentheses —
//! over the values read from a stopped PLC. Calls are not evaluated: an
//! expression never changes the program.

use super::plc_value::Value;
use crate::elementary::ElemType;
use crate::value::text::{Lit, parse_literal_text};

/// A value while evaluating.
#[derive(Debug, Clone, PartialEq)]
enum V {
    Bool(bool),
    /// An integer (or duration, date...) with the type it keeps.
    Int(i64, ElemType),
    Real(f64),
    Str(String, bool),
}

impl V {
    fn of(v: Value) -> V {
        match v {
            Value::Scalar(ElemType::Bool, raw) => V::Bool(raw != 0),
            Value::Scalar(ElemType::Real, raw) => V::Real(f32::from_bits(raw as u32) as f64),
            Value::Scalar(ElemType::Lreal, raw) => V::Real(f64::from_bits(raw)),
            Value::Scalar(t, raw) => V::Int(raw as i64, t),
            Value::String(s, wide) => V::Str(s, wide),
            Value::Enum(_, x) => V::Int(x, ElemType::Lint),
        }
    }

    fn into_value(self) -> Value {
        match self {
            V::Bool(b) => Value::Scalar(ElemType::Bool, b as u64),
            V::Int(i, t) => Value::Scalar(t, i as u64),
            V::Real(x) => Value::Scalar(ElemType::Lreal, x.to_bits()),
            V::Str(s, wide) => Value::String(s, wide),
        }
    }
}

/// A token of an expression.
#[derive(Debug, Clone, PartialEq)]
enum Tok {
    /// A variable path or a literal (told apart when evaluated).
    Word(String),
    Str(String),
    Op(&'static str),
    Open,
    Close,
}

fn tokens(text: &str) -> Result<Vec<Tok>, String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        if c == '(' {
            out.push(Tok::Open);
            i += 1;
            continue;
        }
        if c == ')' {
            out.push(Tok::Close);
            i += 1;
            continue;
        }
        if c == '\'' || c == '"' {
            let start = i;
            i += 1;
            while i < chars.len() && chars[i] != c {
                if chars[i] == '$' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push(Tok::Str(chars[start..i.min(chars.len())].iter().collect()));
            continue;
        }
        let two: String = chars[i..(i + 2).min(chars.len())].iter().collect();
        if let Some(op) = ["<=", ">=", "<>"].into_iter().find(|o| *o == two) {
            out.push(Tok::Op(op));
            i += 2;
            continue;
        }
        if let Some(op) = ["=", "<", ">", "+", "-", "*", "/", "&"]
            .into_iter()
            .find(|o| o.starts_with(c))
        {
            out.push(Tok::Op(op));
            i += 1;
            continue;
        }
        if c.is_alphanumeric() || c == '_' || c == '%' {
            let start = i;
            let mut depth = 0;
            while i < chars.len() {
                let d = chars[i];
                let more = d.is_alphanumeric()
                    || matches!(d, '_' | '.' | '#' | '%' | ':')
                    || d == '['
                    || depth > 0
                    // A signed exponent or a literal's sign after `#`.
                    || ((d == '-' || d == '+')
                        && i > start
                        && (matches!(chars[i - 1], '#') || (chars[i - 1] == 'e' || chars[i - 1] == 'E') && chars[start].is_ascii_digit()));
                if !more {
                    break;
                }
                if d == '[' {
                    depth += 1;
                } else if d == ']' {
                    depth -= 1;
                }
                i += 1;
            }
            let word: String = chars[start..i].iter().collect();
            let op = match word.to_ascii_uppercase().as_str() {
                "AND" => Some("AND"),
                "OR" => Some("OR"),
                "XOR" => Some("XOR"),
                "NOT" => Some("NOT"),
                "MOD" => Some("MOD"),
                _ => None,
            };
            out.push(match op {
                Some(op) => Tok::Op(op),
                None => Tok::Word(word),
            });
            continue;
        }
        return Err(format!("unexpected `{c}` in the expression"));
    }
    Ok(out)
}

/// A recursive-descent evaluator over the tokens.
struct Eval<'r> {
    toks: Vec<Tok>,
    at: usize,
    read: &'r dyn Fn(&str) -> Result<Value, String>,
}

type R = Result<V, String>;

impl Eval<'_> {
    fn peek_op(&self) -> Option<&'static str> {
        match self.toks.get(self.at) {
            Some(Tok::Op(o)) => Some(o),
            _ => None,
        }
    }

    fn binary(&mut self, ops: &[&str], next: fn(&mut Self) -> R) -> R {
        let mut left = next(self)?;
        while let Some(op) = self.peek_op().filter(|o| ops.contains(o)) {
            self.at += 1;
            let right = next(self)?;
            left = apply(op, left, right)?;
        }
        Ok(left)
    }

    fn or(&mut self) -> R {
        self.binary(&["OR"], Self::xor)
    }
    fn xor(&mut self) -> R {
        self.binary(&["XOR"], Self::and)
    }
    fn and(&mut self) -> R {
        self.binary(&["AND", "&"], Self::compare)
    }
    fn compare(&mut self) -> R {
        self.binary(&["=", "<>", "<", "<=", ">", ">="], Self::sum)
    }
    fn sum(&mut self) -> R {
        self.binary(&["+", "-"], Self::product)
    }
    fn product(&mut self) -> R {
        self.binary(&["*", "/", "MOD"], Self::unary)
    }

    fn unary(&mut self) -> R {
        match self.peek_op() {
            Some("NOT") => {
                self.at += 1;
                match self.unary()? {
                    V::Bool(b) => Ok(V::Bool(!b)),
                    V::Int(i, t) => Ok(V::Int(!i, t)),
                    _ => Err("NOT needs a BOOL or a bit string".into()),
                }
            }
            Some("-") => {
                self.at += 1;
                match self.unary()? {
                    V::Int(i, t) => Ok(V::Int(i.wrapping_neg(), t)),
                    V::Real(x) => Ok(V::Real(-x)),
                    _ => Err("`-` needs a number".into()),
                }
            }
            _ => self.primary(),
        }
    }

    fn primary(&mut self) -> R {
        let tok = self.toks.get(self.at).cloned();
        self.at += 1;
        match tok {
            Some(Tok::Open) => {
                let v = self.or()?;
                if self.toks.get(self.at) != Some(&Tok::Close) {
                    return Err("a `)` is missing".into());
                }
                self.at += 1;
                Ok(v)
            }
            Some(Tok::Str(s)) => match parse_literal_text(&s) {
                Ok((Lit::Str { value, wide }, _)) => Ok(V::Str(value, wide)),
                _ => Err(format!("`{s}` is not a string literal")),
            },
            Some(Tok::Word(w)) => word(&w, self.read),
            Some(t) => Err(format!("unexpected {t:?}")),
            None => Err("the expression ends too early".into()),
        }
    }
}

/// A literal, or else a variable read from the PLC.
fn word(w: &str, read: &dyn Fn(&str) -> Result<Value, String>) -> R {
    let starts_like_literal = w.chars().next().is_some_and(|c| c.is_ascii_digit())
        || w.eq_ignore_ascii_case("TRUE")
        || w.eq_ignore_ascii_case("FALSE")
        || (w.contains('#') && !w.starts_with('%'));
    if starts_like_literal {
        match parse_literal_text(w) {
            Ok((Lit::Bool(b), _)) => return Ok(V::Bool(b)),
            Ok((Lit::Int(i), t)) => {
                let i = i64::try_from(i).map_err(|_| format!("`{w}` is too large"))?;
                return Ok(V::Int(i, t.unwrap_or(ElemType::Lint)));
            }
            Ok((Lit::Real(x), _)) => return Ok(V::Real(x)),
            Ok((Lit::Nanos { nanos, ty }, _)) => return Ok(V::Int(nanos, ty)),
            Ok(_) => {}
            Err(e) if w.chars().next().is_some_and(|c| c.is_ascii_digit()) => return Err(e),
            Err(_) => {}
        }
    }
    read(w).map(V::of)
}

fn num(v: &V) -> Option<f64> {
    match v {
        V::Int(i, _) => Some(*i as f64),
        V::Real(x) => Some(*x),
        _ => None,
    }
}

fn apply(op: &str, a: V, b: V) -> R {
    use std::cmp::Ordering;
    let order = |a: &V, b: &V| -> Option<Ordering> {
        match (a, b) {
            (V::Int(x, _), V::Int(y, _)) => Some(x.cmp(y)),
            (V::Bool(x), V::Bool(y)) => Some(x.cmp(y)),
            (V::Str(x, _), V::Str(y, _)) => Some(x.cmp(y)),
            _ => num(a)?.partial_cmp(&num(b)?),
        }
    };
    match op {
        "=" | "<>" | "<" | "<=" | ">" | ">=" => {
            let o = order(&a, &b).ok_or_else(|| format!("cannot compare {a:?} and {b:?}"))?;
            Ok(V::Bool(match op {
                "=" => o == Ordering::Equal,
                "<>" => o != Ordering::Equal,
                "<" => o == Ordering::Less,
                "<=" => o != Ordering::Greater,
                ">" => o == Ordering::Greater,
                _ => o != Ordering::Less,
            }))
        }
        "AND" | "&" | "OR" | "XOR" => match (a, b) {
            (V::Bool(x), V::Bool(y)) => Ok(V::Bool(match op {
                "OR" => x || y,
                "XOR" => x ^ y,
                _ => x && y,
            })),
            (V::Int(x, t), V::Int(y, _)) => Ok(V::Int(
                match op {
                    "OR" => x | y,
                    "XOR" => x ^ y,
                    _ => x & y,
                },
                t,
            )),
            _ => Err(format!("{op} needs BOOL or bit-string operands")),
        },
        _ => match (a, b) {
            (V::Int(x, t), V::Int(y, _)) => {
                let v = match op {
                    "+" => x.checked_add(y),
                    "-" => x.checked_sub(y),
                    "*" => x.checked_mul(y),
                    "/" => x.checked_div(y),
                    _ => x.checked_rem(y),
                };
                v.map(|v| V::Int(v, t))
                    .ok_or_else(|| format!("{x} {op} {y}: division by zero or overflow"))
            }
            (a, b) => {
                let (x, y) = (num(&a), num(&b));
                let (Some(x), Some(y)) = (x, y) else {
                    return Err(format!("{op} needs numbers"));
                };
                Ok(V::Real(match op {
                    "+" => x + y,
                    "-" => x - y,
                    "*" => x * y,
                    "/" => x / y,
                    _ => x % y,
                }))
            }
        },
    }
}

/// Evaluates `text`, reading variables through `read`.
pub(super) fn evaluate(
    text: &str,
    read: &dyn Fn(&str) -> Result<Value, String>,
) -> Result<Value, String> {
    let toks = tokens(text)?;
    if toks.is_empty() {
        return Err("the expression is empty".into());
    }
    // A variable alone keeps its own type and text.
    if let [Tok::Word(w)] = toks.as_slice()
        && let Ok(v) = read(w)
    {
        return Ok(v);
    }
    let mut e = Eval { toks, at: 0, read };
    let v = e.or()?;
    if e.at < e.toks.len() {
        return Err(format!(
            "unexpected {:?} after the expression",
            e.toks[e.at]
        ));
    }
    Ok(v.into_value())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(text: &str) -> Result<String, String> {
        let read = |p: &str| match p {
            "n" => Ok(Value::Scalar(ElemType::Int, 5)),
            "ok" => Ok(Value::Scalar(ElemType::Bool, 1)),
            "t" => Ok(Value::Scalar(ElemType::Time, 3_000_000_000)),
            _ => Err(format!("no `{p}`")),
        };
        evaluate(text, &read).map(|v| v.to_literal())
    }

    #[test]
    fn arithmetic_comparisons_and_logic() {
        assert_eq!(eval("n").unwrap(), "5");
        assert_eq!(eval("n + 2 * 3").unwrap(), "11");
        assert_eq!(eval("(n + 1) MOD 4 = 2").unwrap(), "TRUE");
        assert_eq!(eval("ok AND n > 4 OR FALSE").unwrap(), "TRUE");
        assert_eq!(eval("NOT ok & n <> 5").unwrap(), "FALSE");
        assert_eq!(eval("t >= T#3s").unwrap(), "TRUE");
        assert_eq!(eval("-n < 0").unwrap(), "TRUE");
        assert!(eval("nope + 1").unwrap_err().contains("nope"));
        assert!(eval("n +").is_err());
        assert!(eval("n / 0").is_err());
    }
}
