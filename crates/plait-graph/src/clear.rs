//! `clear = …` on a texture resource: the value the engine fills it with
//! before its first use in the frame, and the check that a pass which
//! `loads` a target reads something a pass wrote or a declared clear value.
//!
//! Without it, a pass that `loads` a target nothing wrote earlier would read
//! the engine's default clear (zeros) silently; Weighted Blended OIT's
//! revealage (McGuire and Bavoil, "Weighted Blended Order-Independent
//! Transparency", Journal of Computer Graphics Techniques 2(2), 2013) is a
//! product of (1 - alpha) that must start at 1, which a zero start turns
//! into a black image with exit 0.

use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::format::{Format, SampleType};
use crate::load::tree::Node;
use crate::value::Value;

/// A texture's clear value, RGBA (unused channels 0, alpha 1 as WebGPU
/// fills missing channels); a depth format uses the first.
pub type ClearValue = [f64; 4];

/// Parses `clear` of resource `name` with format `format`: a number for a
/// one-channel or depth format, else a list with one number per channel.
pub(crate) fn parse(
    node: &Spanned<Node>,
    name: &str,
    format: Format,
    errors: &mut Vec<Error>,
) -> Option<Spanned<ClearValue>> {
    let n = format.components() as usize;
    let bad = |reason: String| {
        Error::new(
            node.location.clone(),
            ErrorKind::Schema(format!("resources.{name}.clear: {reason}")),
        )
    };
    let shape = if n == 1 {
        "a number".to_owned()
    } else {
        format!("a list of {n} numbers")
    };
    let numbers: Vec<Option<f64>> = match &node.value {
        Node::Scalar(v) if n == 1 => vec![v.as_f64()],
        Node::List(items) if items.len() == n => items
            .iter()
            .map(|i| match &i.value {
                Node::Scalar(v @ (Value::Int(_) | Value::Float(_))) => v.as_f64(),
                _ => None,
            })
            .collect(),
        _ => {
            errors.push(bad(format!(
                "the format is {format} ({n} channel(s)), so the clear value is {shape}"
            )));
            return None;
        }
    };
    let mut value = [0.0, 0.0, 0.0, 1.0];
    for (i, x) in numbers.into_iter().enumerate() {
        match x {
            Some(x) if x.is_finite() => value[i] = x,
            _ => {
                errors.push(bad(format!("channel {i} is not a finite number")));
                return None;
            }
        }
    }
    if let Err(reason) = fits(format, &value[..n]) {
        errors.push(bad(reason));
        return None;
    }
    Some(Spanned::new(value, node.location.clone()))
}

/// Whether the channels can be stored in `format` exactly as written.
fn fits(format: Format, channels: &[f64]) -> Result<(), String> {
    let in_range = |lo: f64, hi: f64| channels.iter().all(|&x| (lo..=hi).contains(&x));
    match format.sample_type() {
        SampleType::Depth if !in_range(0.0, 1.0) => Err(format!("{format} holds depths 0 … 1")),
        SampleType::Uint
            if !channels
                .iter()
                .all(|&x| x.fract() == 0.0 && (0.0..=u32::MAX as f64).contains(&x)) =>
        {
            Err(format!("{format} holds unsigned integers 0 … {}", u32::MAX))
        }
        SampleType::Float
            if matches!(
                format,
                Format::R8Unorm | Format::Rgba8Unorm | Format::Rgba8UnormSrgb
            ) && !in_range(0.0, 1.0) =>
        {
            Err(format!("{format} holds values 0 … 1"))
        }
        _ => Ok(()),
    }
}

/// The error for a pass whose `loads` entry (at `at`) keeps a target that
/// no earlier pass in the frame writes and that declares no clear value.
pub(crate) fn load_before_write(pass: &str, slot: &str, resource: &str, at: &Location) -> Error {
    Error::new(
        at.clone(),
        ErrorKind::Pass {
            pass: pass.to_owned(),
            message: format!(
                "`loads` keeps `{slot}` (resource `{resource}`), but no earlier pass in the frame writes `{resource}`, so it would read the default clear (zeros); write it in an earlier pass, or declare the value it starts from with `clear = …` in [resources.{resource}] (e.g. `clear = [1, 1, 1, 1]`)"
            ),
        },
    )
}

/// The error for a resource with `clear` whose first pass reads and writes
/// it: that pass sees it as it is, so the clear would never happen.
pub(crate) fn cleared_but_read(pass: &str, resource: &str, at: &Location) -> Error {
    Error::new(
        at.clone(),
        ErrorKind::Pass {
            pass: pass.to_owned(),
            message: format!(
                "`{resource}` declares `clear`, but this pass, its first in the frame, reads and writes it, which keeps it as it is and never clears it; write it in an earlier pass or drop `clear`"
            ),
        },
    )
}
