//! Resolving a declared resource into a [`ResourceDesc`]: its size, layers
//! and samples evaluated and checked against the adapter's limits (WebGPU's
//! defaults without a GPU), so a pipeline that compiles can be allocated.

use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::load::{ResourceDecl, SizeDecl};
use crate::schedule::{CompileOptions, ResourceDesc};
use crate::value::Value;

use super::values::int_value;

pub(super) fn resolve_resource(
    r: &ResourceDecl,
    opts: &CompileOptions,
    errors: &mut Vec<Error>,
) -> Option<ResourceDesc> {
    let bad = |location: &Location, reason: String| {
        Error::new(
            location.clone(),
            ErrorKind::BadResource {
                resource: r.name.clone(),
                reason,
            },
        )
    };
    let eval = |v: &Spanned<Value>, what: &str, errors: &mut Vec<Error>| match int_value(v, opts) {
        Ok(n) => Some(n),
        Err(reason) => {
            errors.push(bad(&v.location, format!("{what}: {reason}")));
            None
        }
    };
    match &r.size {
        SizeDecl::Bytes(size) => {
            let bytes = eval(size, "size", errors)?;
            if bytes <= 0 {
                errors.push(bad(
                    &size.location,
                    format!("buffer size is {bytes} bytes; it must be positive"),
                ));
                return None;
            }
            let limit = opts.max_buffer_binding_size;
            if bytes as u64 > limit {
                errors.push(bad(
                    &size.location,
                    format!(
                        "buffer `{}` is {} ({bytes} bytes); a pass can bind at most {} ({limit} bytes) as storage (WebGPU's default limit when checking without a GPU, the adapter's when rendering)",
                        r.name,
                        mib(bytes as u64),
                        mib(limit),
                    ),
                ));
                return None;
            }
            Some(ResourceDesc::Buffer { size: bytes as u64 })
        }
        SizeDecl::Scene(_) => Some(ResourceDesc::AccelerationStructure),
        SizeDecl::Screen { .. } | SizeDecl::Extent { .. } => {
            let (width, height) = match &r.size {
                SizeDecl::Screen { divisor, .. } => {
                    // Rounded down like integer division, never below one texel.
                    (
                        (opts.screen.0 / divisor).max(1) as i64,
                        (opts.screen.1 / divisor).max(1) as i64,
                    )
                }
                SizeDecl::Extent { width, height, .. } => (
                    eval(width, "width", errors)?,
                    eval(height, "height", errors)?,
                ),
                SizeDecl::Bytes(_) | SizeDecl::Scene(_) => return None,
            };
            let limit = opts.max_texture_dimension;
            if width < 1 || height < 1 || width > limit as i64 || height > limit as i64 {
                errors.push(Error::new(
                    r.size.location().clone(),
                    ErrorKind::TextureSize {
                        resource: r.name.clone(),
                        width,
                        height,
                        limit,
                    },
                ));
                return None;
            }
            let mut count = |field: &Option<Spanned<Value>>, what: &str| -> Option<u32> {
                let Some(v) = field else { return Some(1) };
                let n = eval(v, what, errors)?;
                if !(1..=2048).contains(&n) {
                    errors.push(bad(
                        &v.location,
                        format!("{what} is {n}; it must be between 1 and 2048"),
                    ));
                    return None;
                }
                Some(n as u32)
            };
            let layers = count(&r.layers, "layers")?;
            let samples = count(&r.samples, "samples")?;
            if !crate::schedule::SAMPLE_COUNTS.contains(&samples) {
                let at = r.samples.as_ref().map_or(&r.location, |v| &v.location);
                errors.push(bad(
                    at,
                    format!(
                        "samples is {samples}; no texture format allows it (counts are 1, 2, 4, 8 or 16, and each format allows a subset: rgba16float 1 or 4 on lavapipe)"
                    ),
                ));
                return None;
            }
            let format = r.format.as_ref()?.value;
            Some(ResourceDesc::Texture {
                format,
                width: width as u32,
                height: height as u32,
                layers,
                samples,
            })
        }
    }
}

/// `1.5 MiB`, `1 GiB`: a byte count for messages.
fn mib(bytes: u64) -> String {
    if bytes >= 1 << 30 && bytes.is_multiple_of(1 << 30) {
        format!("{} GiB", bytes >> 30)
    } else {
        format!("{:.1} MiB", bytes as f64 / (1u64 << 20) as f64)
    }
}
