//! Integer values of a pipeline file: a literal, a whole float, or an
//! expression over the render size (`"screen_width / 4"`), evaluated here
//! because only compile knows the screen.

use crate::expr;
use crate::schedule::CompileOptions;
use crate::value::Value;

fn screen_var(opts: &CompileOptions) -> impl Fn(&str) -> Option<f64> {
    let (w, h) = opts.screen;
    move |name| match name {
        "screen_width" => Some(w as f64),
        "screen_height" => Some(h as f64),
        _ => None,
    }
}

/// An integer, a whole float, or an expression string.
pub(super) fn int_value(v: &Value, opts: &CompileOptions) -> Result<i64, String> {
    match v {
        Value::Int(i) => Ok(*i),
        Value::Float(f) if f.fract() == 0.0 && f.abs() < i64::MAX as f64 => Ok(*f as i64),
        Value::Str(s) => expr::eval_int(s, &screen_var(opts)),
        other => Err(format!(
            "expected an integer or an expression, found {other}"
        )),
    }
}
