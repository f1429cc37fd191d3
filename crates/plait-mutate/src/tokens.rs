//! A WGSL token stream good enough to place mutations: identifiers, numbers
//! and punctuation with their byte spans, comments, attributes and naga_oil
//! directive lines (`#import`, `#ifdef`, …) left out.
//!
//! Why not naga: plait's shaders are naga_oil modules (`#import`, `#ifdef`,
//! `#{N}`), which naga cannot parse until they are composed against the
//! whole library, and a composed module no longer maps back to the file's
//! text. Whether a mutant is valid is decided afterwards by plait's own
//! checks (`plait check` composes and validates every shader with naga).

/// What a token is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Ident,
    Number,
    Punct,
    /// A naga_oil substitution, `#{NAME}`: a value, but not one to mutate.
    Define,
}

#[derive(Clone, Debug)]
pub struct Token {
    pub kind: Kind,
    pub start: usize,
    pub end: usize,
    /// Whitespace (or a comment) directly before / after it.
    pub space_before: bool,
    pub space_after: bool,
}

impl Token {
    pub fn text<'a>(&self, src: &'a str) -> &'a str {
        &src[self.start..self.end]
    }
}

/// Punctuation, longest first so `<=` wins over `<`.
const PUNCT: &[&str] = &[
    "<<=", ">>=", "->", "<=", ">=", "==", "!=", "&&", "||", "+=", "-=", "*=", "/=", "%=", "&=",
    "|=", "^=", "++", "--", "<<", ">>", "<", ">", "=", "+", "-", "*", "/", "%", "!", "&", "|", "^",
    "~", "(", ")", "[", "]", "{", "}", ",", ";", ":", ".", "@",
];

/// The tokens of `src`, attributes (`@location(0)`) and directive lines dropped.
pub fn tokenize(src: &str) -> Vec<Token> {
    let b = src.as_bytes();
    let mut out: Vec<Token> = Vec::new();
    let mut i = 0;
    let mut line_start = true;
    let mut spaced = true;
    while i < b.len() {
        let c = b[i];
        if c == b'\n' {
            line_start = true;
            spaced = true;
            i += 1;
        } else if c.is_ascii_whitespace() {
            spaced = true;
            i += 1;
        } else if src[i..].starts_with("//") {
            i = src[i..].find('\n').map_or(b.len(), |n| i + n);
            spaced = true;
        } else if src[i..].starts_with("/*") {
            i = src[i..].find("*/").map_or(b.len(), |n| i + n + 2);
            spaced = true;
        } else if c == b'#' && src[i..].starts_with("#{") {
            let end = src[i..].find('}').map_or(b.len(), |n| i + n + 1);
            push(&mut out, Kind::Define, i, end, spaced);
            (i, spaced, line_start) = (end, false, false);
        } else if c == b'#' && line_start {
            // A directive owns its line.
            i = src[i..].find('\n').map_or(b.len(), |n| i + n);
        } else if c == b'@' {
            i = skip_attribute(src, i);
            spaced = true;
        } else {
            let (kind, end) = if c.is_ascii_alphabetic() || c == b'_' {
                (
                    Kind::Ident,
                    scan(b, i, |c| c.is_ascii_alphanumeric() || c == b'_'),
                )
            } else if c.is_ascii_digit()
                || (c == b'.' && b.get(i + 1).is_some_and(u8::is_ascii_digit))
            {
                (Kind::Number, number_end(b, i))
            } else {
                let p = PUNCT.iter().find(|p| src[i..].starts_with(**p));
                (Kind::Punct, i + p.map_or(1, |p| p.len()))
            };
            push(&mut out, kind, i, end, spaced);
            (i, spaced, line_start) = (end, false, false);
        }
    }
    out
}

fn push(out: &mut Vec<Token>, kind: Kind, start: usize, end: usize, spaced: bool) {
    if let Some(prev) = out.last_mut() {
        prev.space_after = spaced;
    }
    out.push(Token {
        kind,
        start,
        end,
        space_before: spaced,
        space_after: true,
    });
}

fn scan(b: &[u8], mut i: usize, keep: impl Fn(u8) -> bool) -> usize {
    while i < b.len() && keep(b[i]) {
        i += 1;
    }
    i
}

/// The end of a numeric literal: digits, `.`, exponent with sign, hex, suffix.
fn number_end(b: &[u8], start: usize) -> usize {
    let mut i = start;
    while i < b.len() {
        let c = b[i];
        let exp_sign = (c == b'-' || c == b'+')
            && i > start
            && matches!(b[i - 1], b'e' | b'E')
            && !(b[start..i].starts_with(b"0x"));
        if c.is_ascii_alphanumeric() || c == b'.' || exp_sign {
            i += 1;
        } else {
            break;
        }
    }
    i
}

/// Past `@name` and its parenthesised arguments, if any.
fn skip_attribute(src: &str, at: usize) -> usize {
    let b = src.as_bytes();
    let mut i = scan(b, at + 1, |c| c.is_ascii_alphanumeric() || c == b'_');
    let j = scan(b, i, |c| c == b' ');
    if b.get(j) == Some(&b'(') {
        let mut depth = 0;
        i = j;
        while i < b.len() {
            match b[i] {
                b'(' => depth += 1,
                b')' => {
                    depth -= 1;
                    if depth == 0 {
                        return i + 1;
                    }
                }
                _ => {}
            }
            i += 1;
        }
    }
    i
}

/// 1-based line and column of byte `at`.
pub fn line_col(src: &str, at: usize) -> (usize, usize) {
    let before = &src[..at];
    let line = before.matches('\n').count() + 1;
    let col = at - before.rfind('\n').map_or(0, |n| n + 1) + 1;
    (line, col)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(src: &str) -> Vec<&str> {
        tokenize(src).iter().map(|t| t.text(src)).collect()
    }

    #[test]
    fn directives_attributes_and_comments_are_not_tokens() {
        let src = "#import plait::frame::frame\n// c < d\n@vertex fn f(@location(0) x: f32) -> f32 { return x <= 1.5e-3; }";
        assert_eq!(
            texts(src),
            [
                "fn", "f", "(", "x", ":", "f32", ")", "->", "f32", "{", "return", "x", "<=",
                "1.5e-3", ";", "}"
            ]
        );
    }

    #[test]
    fn spacing_tells_a_comparison_from_a_generic() {
        let src = "let a: vec3<f32> = b < c;";
        let t = tokenize(src);
        let lt: Vec<&Token> = t.iter().filter(|t| t.text(src) == "<").collect();
        assert!(!lt[0].space_before && !lt[0].space_after);
        assert!(lt[1].space_before && lt[1].space_after);
        assert_eq!(
            texts("array<u32, #{N}>"),
            ["array", "<", "u32", ",", "#{N}", ">"]
        );
    }
}
