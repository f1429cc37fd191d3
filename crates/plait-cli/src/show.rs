//! `plait render --show NAME`: any texture of the pipeline as a picture.
//!
//! The name is checked against the pipeline before any GPU work. The
//! resource is made an extra output of the pipeline
//! ([`plait::source::PipelineSource::with_output`]), so the passes that
//! write it are not culled and its memory is not shared with a resource
//! written after it.
//!
//! Data textures (depth ranges, depth buffers, counts) hold values far
//! outside 0…1; encoding them as colour saturates them, so such textures are
//! mapped linearly from their smallest to their largest value, and the range
//! used is reported.

use anyhow::Result;
use plait_gpu::readback::TexelData;
use plait_graph::{Format, Pipeline, ResourceKind};

/// `name` must be a texture the pipeline declares; otherwise the error lists
/// the textures, nearest to the name first.
pub fn check_name(pipeline: &Pipeline, name: &str) -> Result<()> {
    let textures: Vec<&str> = pipeline
        .resources
        .values()
        .filter(|r| r.kind.value == ResourceKind::Texture)
        .map(|r| r.name.as_str())
        .collect();
    let listing = || plait_graph::suggest::nearest_first(name, textures.iter().copied()).join(", ");
    match pipeline.resources.get(name) {
        Some(r) if r.kind.value == ResourceKind::Texture => Ok(()),
        Some(_) => anyhow::bail!(
            "--show {name}: `{name}` is a buffer; --show takes a texture: {}",
            listing()
        ),
        None => anyhow::bail!(
            "--show {name}: no texture `{name}` in {}{} (its textures: {})",
            pipeline
                .files
                .first()
                .map_or_else(|| "the pipeline".into(), |f| f.display().to_string()),
            plait_graph::suggest::did_you_mean(name, textures.iter().copied()),
            listing()
        ),
    }
}

/// A multisampled texture cannot be read back (it is resolved first by the
/// pipeline, if at all); say so before opening the GPU.
pub fn check_readable(schedule: &plait_graph::Schedule, name: &str) -> Result<()> {
    let Some(id) = schedule.resource(name) else {
        anyhow::bail!("--show {name}: `{name}` is not in the compiled schedule");
    };
    if let plait_graph::ResourceDesc::Texture { samples, .. } = schedule.resources[id].desc
        && samples > 1
    {
        anyhow::bail!(
            "--show {name}: `{name}` is multisampled ({samples} samples) and cannot be read \
             back; show the texture it is resolved into"
        );
    }
    Ok(())
}

/// A texture read back, as a picture and (for mapped data) a note saying
/// which range of values became black … full intensity.
pub fn picture(name: &str, data: &TexelData) -> (image::RgbaImage, Option<String>) {
    let format = data.format;
    if matches!(
        format,
        Format::Rgba8Unorm | Format::Rgba8UnormSrgb | Format::R8Unorm
    ) {
        return (data.to_image(), None);
    }
    // Colour channels only: alpha of a colour texture is coverage, not data.
    let channels = (format.components() as usize).min(3);
    let texels = (data.width * data.height) as usize;
    let values = |c: usize| (0..texels).map(move |i| data.texel(i)[c]);
    // Texels no pass touched hold the value the texture was cleared to (a
    // depth of 1, a range of (1, 0)); such a value at either end of the range
    // would squeeze everything else into a few grey levels, so it is left out
    // of the range and shown black.
    let cleared: Vec<Option<f32>> = (0..channels)
        .map(|c| clear_value(values(c), texels))
        .collect();
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for (c, clear) in cleared.iter().enumerate() {
        for v in values(c) {
            if v.is_finite() && Some(v) != *clear {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
    }
    let is_colour = matches!(format, Format::Rgba16Float | Format::Rgba32Float);
    let all_in_unit_range = (0..channels)
        .flat_map(values)
        .filter(|v| v.is_finite())
        .all(|v| (0.0..=1.0).contains(&v));
    if is_colour && all_in_unit_range {
        // A colour image already in range: linear values encoded to sRGB.
        return (data.to_image(), None);
    }
    if lo > hi {
        return (
            data.to_image(),
            Some(format!(
                "--show {name} ({format}): no value besides the clear value to show"
            )),
        );
    }
    let span = hi - lo;
    let level = |v: f32, clear: Option<f32>| -> u8 {
        if !v.is_finite() || Some(v) == clear {
            0
        } else if span > 0.0 {
            (((v - lo) / span).clamp(0.0, 1.0) * 255.0).round() as u8
        } else {
            128
        }
    };
    let mut img = image::RgbaImage::new(data.width, data.height);
    for (i, px) in img.pixels_mut().enumerate() {
        let t = data.texel(i);
        let l = |c: usize| level(t[c], cleared[c]);
        *px = match channels {
            1 => {
                let g = l(0);
                image::Rgba([g, g, g, 255])
            }
            2 => image::Rgba([l(0), l(1), 0, 255]),
            _ => image::Rgba([l(0), l(1), l(2), 255]),
        };
    }
    let what = match channels {
        1 => "grey",
        2 => "red (r) and green (g)",
        _ => "red, green, blue",
    };
    let mut note = if span > 0.0 {
        format!(
            "values {} … {} mapped linearly to black … full {what}",
            short(lo),
            short(hi)
        )
    } else {
        format!("every texel is {} (shown as mid grey)", short(lo))
    };
    let names = ["r", "g", "b"];
    let clears: Vec<String> = cleared
        .iter()
        .enumerate()
        .filter_map(|(c, v)| {
            v.map(|v| match channels {
                1 => short(v),
                _ => format!("{} = {}", names[c], short(v)),
            })
        })
        .collect();
    if !clears.is_empty() {
        note.push_str(&format!(
            "; texels left at the clear value ({}) are black",
            clears.join(", ")
        ));
    }
    (img, Some(format!("--show {name} ({format}): {note}")))
}

/// The value most texels of a channel hold, when it is the channel's
/// smallest or largest and covers at least a twentieth of the texture: what
/// the texture was cleared to where nothing was drawn.
fn clear_value(values: impl Iterator<Item = f32> + Clone, texels: usize) -> Option<f32> {
    let mut counts: std::collections::HashMap<u32, usize> = std::collections::HashMap::new();
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        *counts.entry(v.to_bits()).or_default() += 1;
        lo = lo.min(v);
        hi = hi.max(v);
    }
    let mut ranked: Vec<(usize, u32)> = counts.into_iter().map(|(bits, n)| (n, bits)).collect();
    ranked.sort_unstable_by(|a, b| b.cmp(a));
    let (count, bits) = *ranked.first()?;
    // One value must stand out: held by more texels than any other, and by
    // more than one.
    let stands_out = count > 1 && ranked.get(1).is_none_or(|&(next, _)| next < count);
    let mode = f32::from_bits(bits);
    let at_an_end = mode == lo || mode == hi;
    // A texture of a single value has nothing to squeeze.
    (stands_out && at_an_end && count * 20 >= texels && lo < hi).then_some(mode)
}

/// Values in the note: enough digits to tell depths apart, no more.
fn short(x: f32) -> String {
    let magnitude = x.abs();
    if x == 0.0 || (1e-3..1e5).contains(&magnitude) {
        format!("{}", (x as f64 * 1e4).round() / 1e4)
    } else {
        format!("{x:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texels(format: Format, values: &[f32]) -> TexelData {
        let bytes = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let per_texel = format.components() as usize;
        TexelData {
            width: (values.len() / per_texel) as u32,
            height: 1,
            format,
            bytes,
        }
    }

    #[test]
    fn depths_are_spread_over_the_grey_range() {
        let data = texels(Format::R32Float, &[2.0, 3.0, 4.0]);
        let (img, note) = picture("d", &data);
        let greys: Vec<u8> = img.pixels().map(|p| p[0]).collect();
        assert_eq!(greys, [0, 128, 255]);
        let note = note.expect("a note on the range");
        assert!(note.contains("2 … 4"), "{note}");
    }

    #[test]
    fn two_channels_share_one_range() {
        // Near in red, far in green: one range keeps them comparable.
        let data = texels(Format::Rg32Float, &[1.0, 0.0, 5.0, 9.0]);
        let (img, note) = picture("light_range", &data);
        assert_eq!(img.get_pixel(1, 0).0, [142, 255, 0, 255]);
        assert!(note.expect("note").contains("0 … 9"));
    }

    #[test]
    fn colour_in_range_stays_colour() {
        let data = texels(Format::Rgba32Float, &[1.0, 0.0, 0.2158, 1.0]);
        let (img, note) = picture("hair", &data);
        assert_eq!(img.get_pixel(0, 0).0, [255, 0, 128, 255]);
        assert!(note.is_none());
    }

    #[test]
    fn the_clear_value_is_left_out_of_the_range() {
        // A depth buffer: most texels at the far plane (1), the head near 0.98.
        let mut depths = vec![1.0; 20];
        depths.extend([0.98, 0.99]);
        let (img, note) = picture("depth", &texels(Format::Depth32Float, &depths));
        let greys: Vec<u8> = img.pixels().map(|p| p[0]).collect();
        assert_eq!(&greys[18..], [0, 0, 0, 255]);
        let note = note.expect("note");
        assert!(
            note.contains("0.98 … 0.99") && note.contains("clear value (1)"),
            "{note}"
        );
    }

    #[test]
    fn infinities_do_not_stretch_the_range() {
        let data = texels(Format::R32Float, &[f32::INFINITY, 1.0, 3.0]);
        let (img, _) = picture("d", &data);
        let greys: Vec<u8> = img.pixels().map(|p| p[0]).collect();
        assert_eq!(greys, [0, 0, 255]);
    }
}
