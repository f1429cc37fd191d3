//! Mutation operators on WGSL text: each proposes replacements of one span of
//! a file. Deterministic: the same file gives the same mutants in the same
//! order, so a mutant's id (`file:line:col:operator`) names it for good.

use crate::tokens::{Kind, Token, line_col, tokenize};

/// One mutant: `span` of the file replaced by `replacement`.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Mutant {
    pub file: String,
    pub line: usize,
    pub col: usize,
    pub operator: &'static str,
    #[serde(skip)]
    pub span: (usize, usize),
    pub original: String,
    pub replacement: String,
}

impl Mutant {
    pub fn id(&self) -> String {
        format!("{}:{}:{}:{}", self.file, self.line, self.col, self.operator)
    }

    pub fn apply(&self, src: &str) -> String {
        format!(
            "{}{}{}",
            &src[..self.span.0],
            self.replacement,
            &src[self.span.1..]
        )
    }

    /// The changed line(s) before and after, as a unified-style diff.
    pub fn diff(&self, src: &str) -> String {
        let start = src[..self.span.0].rfind('\n').map_or(0, |n| n + 1);
        let end = src[self.span.1..]
            .find('\n')
            .map_or(src.len(), |n| self.span.1 + n);
        let before = &src[start..end];
        let after = format!(
            "{}{}{}",
            &src[start..self.span.0],
            self.replacement,
            &src[self.span.1..end]
        );
        let mut out = format!("@@ {}:{} {}\n", self.file, self.line, self.operator);
        for l in before.lines() {
            out += &format!("-{l}\n");
        }
        for l in after.lines() {
            out += &format!("+{l}\n");
        }
        out
    }
}

/// Every mutant of `src` (the file `file`), in source order, duplicates
/// (same mutated text) dropped.
pub fn mutants(file: &str, src: &str) -> Vec<Mutant> {
    let toks = tokenize(src);
    let mut found: Vec<(usize, usize, &'static str, String)> = Vec::new();
    for (i, _) in toks.iter().enumerate() {
        let cx = Cx {
            src,
            toks: &toks,
            i,
        };
        cx.relational(&mut found);
        cx.arithmetic(&mut found);
        cx.drop_term(&mut found);
        cx.constant(&mut found);
        cx.builtin_swap(&mut found);
        cx.swap_args(&mut found);
        cx.loop_bounds(&mut found);
        cx.return_zero(&mut found);
    }
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for (start, end, operator, replacement) in found {
        if !seen.insert((start, end, replacement.clone())) || src[start..end] == replacement {
            continue;
        }
        let (line, col) = line_col(src, start);
        out.push(Mutant {
            file: file.to_owned(),
            line,
            col,
            operator,
            span: (start, end),
            original: src[start..end].to_owned(),
            replacement,
        });
    }
    out.sort_by_key(|m| (m.span.0, m.span.1));
    out
}

type Found = Vec<(usize, usize, &'static str, String)>;

/// The token at `i` of a file, with the file.
struct Cx<'a> {
    src: &'a str,
    toks: &'a [Token],
    i: usize,
}

/// Names that look like calls but construct a type or are statements.
/// Calls whose first two arguments commute: swapping them is an equivalent
/// mutant by construction, so none is made.
const COMMUTATIVE: &[&str] = &["min", "max", "dot", "distance"];

const NOT_CALLS: &[&str] = &[
    "if", "for", "while", "switch", "return", "loop", "array", "bitcast", "f32", "u32", "i32",
    "f16", "bool",
];

impl Cx<'_> {
    fn tok(&self) -> &Token {
        &self.toks[self.i]
    }
    fn text(&self) -> &str {
        self.tok().text(self.src)
    }
    fn at(&self, j: usize) -> &str {
        self.toks.get(j).map_or("", |t| t.text(self.src))
    }
    /// A binary operator written with spaces on both sides (`a < b`), which
    /// tells comparisons from generics (`vec3<f32>`) and minus from negation.
    fn spaced_binary(&self) -> bool {
        let t = self.tok();
        t.kind == Kind::Punct && t.space_before && t.space_after
    }
    fn here(&self, out: &mut Found, op: &'static str, repl: impl Into<String>) {
        out.push((self.tok().start, self.tok().end, op, repl.into()));
    }

    /// `<` ↔ `>=`, `>` ↔ `<=`, `==` ↔ `!=`: the comparison negated; `&&` ↔ `||`.
    fn relational(&self, out: &mut Found) {
        let flipped = match self.text() {
            "<" => ">=",
            ">=" => "<",
            ">" => "<=",
            "<=" => ">",
            "==" => "!=",
            "!=" => "==",
            "&&" => "||",
            "||" => "&&",
            _ => return,
        };
        if self.spaced_binary() {
            self.here(out, "relational", flipped);
        }
    }

    /// `+` ↔ `-`, `*` ↔ `/`, and the same for compound assignments.
    fn arithmetic(&self, out: &mut Found) {
        let swapped = match self.text() {
            "+" => "-",
            "-" => "+",
            "*" => "/",
            "/" => "*",
            "+=" => "-=",
            "-=" => "+=",
            "*=" => "/=",
            "/=" => "*=",
            _ => return,
        };
        if self.spaced_binary() {
            self.here(out, "arithmetic", swapped);
        }
    }

    /// `a + b * c` → `a`: the term after a `+` or `-` dropped.
    fn drop_term(&self, out: &mut Found) {
        if self.i == 0 || !matches!(self.text(), "+" | "-") || !self.spaced_binary() {
            return;
        }
        let Some(end) = self.term_end(self.i + 1) else {
            return;
        };
        let start = self.toks[self.i - 1].end;
        out.push((start, self.toks[end - 1].end, "drop_term", String::new()));
    }

    /// One past the last token of the product starting at `j`.
    fn term_end(&self, j: usize) -> Option<usize> {
        let mut depth = 0i32;
        for (k, t) in self.toks.iter().enumerate().skip(j) {
            let s = t.text(self.src);
            let spaced = t.space_before && t.space_after;
            match s {
                "(" | "[" => depth += 1,
                ")" | "]" if depth == 0 => return Some(k),
                ")" | "]" => depth -= 1,
                "," | ";" | "{" | "}" | "=" if depth == 0 => return Some(k),
                "+" | "-" | "<" | ">" | "<=" | ">=" | "==" | "!=" | "&&" | "||" | "&" | "|"
                    if depth == 0 && spaced =>
                {
                    return Some(k);
                }
                _ => {}
            }
        }
        None
    }

    /// A float ×1.1 and ×0.9; an integer + 1. Array sizes are left alone.
    fn constant(&self, out: &mut Found) {
        let t = self.tok();
        let s = self.text();
        if t.kind != Kind::Number || s.starts_with("0x") || self.at(self.i + 1) == ">" {
            return;
        }
        let digits = s.trim_end_matches(['f', 'h', 'u', 'i']);
        let suffix = &s[digits.len()..];
        let is_float = digits.contains(['.', 'e', 'E']) || matches!(suffix, "f" | "h");
        if is_float {
            let Ok(v) = digits.parse::<f64>() else { return };
            if v == 0.0 {
                return;
            }
            for (op, k) in [("constant_x1.1", 1.1), ("constant_x0.9", 0.9)] {
                let mut r = format!("{}", (v * k) as f32);
                if !r.contains(['.', 'e']) {
                    r += ".0";
                }
                self.here(out, op, format!("{r}{suffix}"));
            }
        } else if let Ok(v) = digits.parse::<u64>() {
            self.here(out, "constant_plus1", format!("{}{suffix}", v + 1));
        }
    }

    /// `min` ↔ `max`, `floor` ↔ `ceil` in a call.
    fn builtin_swap(&self, out: &mut Found) {
        let other = match self.text() {
            "min" => "max",
            "max" => "min",
            "floor" => "ceil",
            "ceil" => "floor",
            _ => return,
        };
        if self.at(self.i + 1) == "(" {
            self.here(out, "builtin_swap", other);
        }
    }

    /// The arguments of a call, as token ranges.
    fn call_args(&self, open: usize) -> Vec<(usize, usize)> {
        let mut args = Vec::new();
        let (mut depth, mut from) = (0i32, open + 1);
        for (k, t) in self.toks.iter().enumerate().skip(open) {
            match t.text(self.src) {
                "(" | "[" => depth += 1,
                ")" | "]" => {
                    depth -= 1;
                    if depth == 0 {
                        if k > from {
                            args.push((from, k));
                        }
                        return args;
                    }
                }
                "," if depth == 1 => {
                    args.push((from, k));
                    from = k + 1;
                }
                _ => {}
            }
        }
        Vec::new()
    }

    /// `f(a, b)` → `f(b, a)`, each adjacent pair of differing arguments.
    fn swap_args(&self, out: &mut Found) {
        let t = self.tok();
        let name = self.text();
        let is_type = name.starts_with("vec") || name.starts_with("mat");
        if t.kind != Kind::Ident
            || self.at(self.i + 1) != "("
            || is_type
            || NOT_CALLS.contains(&name)
            || COMMUTATIVE.contains(&name)
        {
            return;
        }
        if self.i > 0 && self.at(self.i - 1) == "fn" {
            return;
        }
        let args = self.call_args(self.i + 1);
        for pair in args.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let span = |(f, l): (usize, usize)| (self.toks[f].start, self.toks[l - 1].end);
            let (sa, sb) = (span(a), span(b));
            let (ta, tb) = (&self.src[sa.0..sa.1], &self.src[sb.0..sb.1]);
            if ta != tb {
                let between = &self.src[sa.1..sb.0];
                out.push((sa.0, sb.1, "swap_args", format!("{tb}{between}{ta}")));
            }
        }
    }

    /// In a `for (init; cond; step)`: the bound one less (`i < n` →
    /// `i < (n) - 1`, the last iteration skipped) and the start one more
    /// (`var i = 0u` → `var i = (0u) + 1`, the first skipped).
    fn loop_bounds(&self, out: &mut Found) {
        if self.text() != "for" || self.at(self.i + 1) != "(" {
            return;
        }
        let Some(first) = (self.i..self.toks.len()).find(|&k| self.at(k) == ";") else {
            return;
        };
        if let Some(eq) = (self.i..first).find(|&k| self.at(k) == "=") {
            let (s, e) = (self.toks[eq + 1].start, self.toks[first - 1].end);
            let init = &self.src[s..e];
            out.push((s, e, "loop_start_plus1", format!("({init}) + 1")));
        }
        let Some(second) = (first + 1..self.toks.len()).find(|&k| self.at(k) == ";") else {
            return;
        };
        let cmp = (first + 1..second).find(|&k| matches!(self.at(k), "<" | "<=" | ">" | ">="));
        if let Some(c) = cmp.filter(|&c| c + 1 < second) {
            let (s, e) = (self.toks[c + 1].start, self.toks[second - 1].end);
            let bound = &self.src[s..e];
            let shrunk = if matches!(self.at(c), "<" | "<=") {
                format!("({bound}) - 1")
            } else {
                format!("({bound}) + 1")
            };
            out.push((s, e, "loop_bound", shrunk));
        }
    }

    /// `return e;` → `return T();`, the zero of the function's return type.
    fn return_zero(&self, out: &mut Found) {
        if self.text() != "return" || self.at(self.i + 1) == ";" {
            return;
        }
        let Some(ty) = self.return_type() else { return };
        let Some(semi) = (self.i..self.toks.len()).find(|&k| self.at(k) == ";") else {
            return;
        };
        let (s, e) = (self.toks[self.i + 1].start, self.toks[semi - 1].end);
        // Already a zero: the mutant would be equivalent by construction.
        let zeros = ["0", "0.0", "0u", "0i", "false"].map(|z| format!("{ty}({z})"));
        if zeros.iter().any(|z| *z == self.src[s..e])
            || ["0.0", "0u", "0", "false"].contains(&&self.src[s..e])
        {
            return;
        }
        out.push((s, e, "return_zero", format!("{ty}()")));
    }

    /// The return type of the function enclosing token `i`, as written.
    fn return_type(&self) -> Option<String> {
        let f = (0..self.i).rev().find(|&k| self.at(k) == "fn")?;
        let arrow = (f..self.i).find(|&k| self.at(k) == "->")?;
        let brace = (arrow..self.i).find(|&k| self.at(k) == "{")?;
        if brace <= arrow + 1 {
            return None;
        }
        Some(self.src[self.toks[arrow + 1].start..self.toks[brace - 1].end].to_owned())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn applied(src: &str, op: &str) -> Vec<String> {
        mutants("f.wgsl", src)
            .iter()
            .filter(|m| m.operator == op)
            .map(|m| m.apply(src))
            .collect()
    }

    const SRC: &str = "fn f(a: f32, b: vec3<f32>) -> f32 {\n    if a < 0.5 { return min(a, b.x) + a * 2.0; }\n    for (var i = 0u; i < 4u; i++) { }\n    return a;\n}\n";

    #[test]
    fn each_operator_mutates_what_it_names() {
        assert_eq!(
            applied(SRC, "relational"),
            [
                SRC.replace("a < 0.5", "a >= 0.5"),
                SRC.replace("i < 4u", "i >= 4u")
            ]
        );
        assert_eq!(
            applied(SRC, "drop_term"),
            [SRC.replace("min(a, b.x) + a * 2.0", "min(a, b.x)")]
        );
        assert!(applied(SRC, "constant_x1.1").contains(&SRC.replace("0.5", "0.55")));
        assert!(applied(SRC, "builtin_swap").contains(&SRC.replace("min(", "max(")));
        // min commutes: no swap of its arguments.
        assert!(applied(SRC, "swap_args").is_empty());
        let call = "fn g() { h(a, b); }";
        assert_eq!(applied(call, "swap_args"), ["fn g() { h(b, a); }"]);
        assert_eq!(
            applied(SRC, "loop_bound"),
            [SRC.replace("i < 4u", "i < (4u) - 1")]
        );
        assert_eq!(
            applied(SRC, "return_zero"),
            [
                SRC.replace("return min(a, b.x) + a * 2.0;", "return f32();"),
                SRC.replace("return a;", "return f32();")
            ]
        );
    }

    #[test]
    fn generics_are_not_comparisons_and_ids_are_stable() {
        let all = mutants("f.wgsl", SRC);
        assert!(all.iter().all(|m| m.original != "<" || m.line != 1));
        let again = mutants("f.wgsl", SRC);
        let ids: Vec<String> = all.iter().map(Mutant::id).collect();
        assert_eq!(ids, again.iter().map(Mutant::id).collect::<Vec<_>>());
        assert!(
            ids.contains(&"f.wgsl:2:10:relational".to_owned()),
            "{ids:?}"
        );
    }
}
