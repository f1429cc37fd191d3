//! A tiny arithmetic evaluator for integer-valued fields written as strings,
//! e.g. `size = ["screen_width/2", "${light_size}*2"]`.
//!
//! Grammar: `+ - * / ( )`, integer and float literals and named variables
//! (`screen_width`, `screen_height`). Arithmetic is done in `f64` so that
//! `screen_width*0.5` works; [`eval_int`] rounds the result down, the same
//! rule `size = "screen/N"` uses for odd screen sizes.

/// Evaluates `text`, looking names up with `var`. The error says what is wrong
/// in words, ready to be wrapped in an [`crate::ErrorKind`].
pub fn eval(text: &str, var: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
    let tokens = tokenize(text)?;
    let mut parser = Parser {
        tokens: &tokens,
        pos: 0,
        var,
    };
    let value = parser.sum()?;
    match parser.tokens.get(parser.pos) {
        None => Ok(value),
        Some(t) => Err(format!("unexpected `{t}` in expression `{text}`")),
    }
}

/// Evaluates `text` to a whole number, rounding down.
pub fn eval_int(text: &str, var: &dyn Fn(&str) -> Option<f64>) -> Result<i64, String> {
    let value = eval(text, var)?;
    if !value.is_finite() || value.abs() > i64::MAX as f64 {
        return Err(format!(
            "expression `{text}` does not evaluate to a finite number"
        ));
    }
    Ok(value.floor() as i64)
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Number(f64),
    Name(String),
    Op(char),
}

impl std::fmt::Display for Token {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Token::Number(n) => write!(f, "{n}"),
            Token::Name(n) => f.write_str(n),
            Token::Op(c) => write!(f, "{c}"),
        }
    }
}

fn tokenize(text: &str) -> Result<Vec<Token>, String> {
    let mut tokens = Vec::new();
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if "+-*/()".contains(c) {
            tokens.push(Token::Op(c));
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len()
                && (chars[i].is_ascii_digit() || chars[i] == '.' || chars[i] == '_')
            {
                i += 1;
            }
            let literal: String = chars[start..i].iter().filter(|&&c| c != '_').collect();
            let n = literal
                .parse::<f64>()
                .map_err(|_| format!("`{literal}` is not a number in expression `{text}`"))?;
            tokens.push(Token::Number(n));
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            tokens.push(Token::Name(chars[start..i].iter().collect()));
        } else {
            return Err(format!("unexpected character `{c}` in expression `{text}`"));
        }
    }
    if tokens.is_empty() {
        return Err("empty expression".to_owned());
    }
    Ok(tokens)
}

struct Parser<'a> {
    tokens: &'a [Token],
    pos: usize,
    var: &'a dyn Fn(&str) -> Option<f64>,
}

impl Parser<'_> {
    fn peek_op(&self) -> Option<char> {
        match self.tokens.get(self.pos) {
            Some(Token::Op(c)) => Some(*c),
            _ => None,
        }
    }

    fn sum(&mut self) -> Result<f64, String> {
        let mut acc = self.product()?;
        while let Some(op @ ('+' | '-')) = self.peek_op() {
            self.pos += 1;
            let rhs = self.product()?;
            acc = if op == '+' { acc + rhs } else { acc - rhs };
        }
        Ok(acc)
    }

    fn product(&mut self) -> Result<f64, String> {
        let mut acc = self.unary()?;
        while let Some(op @ ('*' | '/')) = self.peek_op() {
            self.pos += 1;
            let rhs = self.unary()?;
            if op == '*' {
                acc *= rhs;
            } else if rhs == 0.0 {
                return Err("division by zero".to_owned());
            } else {
                acc /= rhs;
            }
        }
        Ok(acc)
    }

    fn unary(&mut self) -> Result<f64, String> {
        match self.peek_op() {
            Some('-') => {
                self.pos += 1;
                Ok(-self.unary()?)
            }
            Some('+') => {
                self.pos += 1;
                self.unary()
            }
            _ => self.atom(),
        }
    }

    fn atom(&mut self) -> Result<f64, String> {
        let token = self.tokens.get(self.pos).cloned();
        self.pos += 1;
        match token {
            Some(Token::Number(n)) => Ok(n),
            Some(Token::Name(name)) => (self.var)(&name).ok_or_else(|| {
                format!("unknown name `{name}` (known: screen_width, screen_height)")
            }),
            Some(Token::Op('(')) => {
                let value = self.sum()?;
                if self.peek_op() == Some(')') {
                    self.pos += 1;
                    Ok(value)
                } else {
                    Err("missing `)`".to_owned())
                }
            }
            Some(t) => Err(format!("unexpected `{t}`")),
            None => Err("expression ends too early".to_owned()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn screen(name: &str) -> Option<f64> {
        match name {
            "screen_width" => Some(960.0),
            "screen_height" => Some(720.0),
            _ => None,
        }
    }

    #[test]
    fn precedence_and_parentheses() {
        assert_eq!(eval_int("1 + 2 * 3", &screen), Ok(7));
        assert_eq!(eval_int("(1 + 2) * 3", &screen), Ok(9));
        assert_eq!(eval_int("-4 + 10", &screen), Ok(6));
        assert_eq!(eval_int("10 - 2 - 3", &screen), Ok(5));
        assert_eq!(eval_int("64 / 4 / 2", &screen), Ok(8));
    }

    #[test]
    fn names_floats_and_rounding() {
        assert_eq!(eval_int("screen_width / 2", &screen), Ok(480));
        assert_eq!(eval_int("screen_height * 0.5", &screen), Ok(360));
        assert_eq!(eval_int("7 / 2", &screen), Ok(3));
        assert_eq!(eval_int("1_024", &screen), Ok(1024));
    }

    #[test]
    fn errors_are_words_not_panics() {
        for bad in [
            "",
            "1 +",
            "(1",
            "1 / 0",
            "2 $ 3",
            "light * 2",
            "1 2",
            ")",
            "1..2",
        ] {
            assert!(eval_int(bad, &screen).is_err(), "{bad:?} should fail");
        }
    }
}
