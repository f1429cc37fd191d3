//! Any resource of a schedule as a picture, with the value under the cursor.
//!
//! Colour textures are shown as `plait render --show` writes them; one
//! channel of any texture, and buffers, as a heat map (FLIP's magma scale)
//! over the range the values actually span, which the legend states. A buffer
//! is laid out as the texels of a texture of the schedule whose size divides
//! it — k `u32` words per texel, interleaved, the layout plait's passes use
//! (occupancy bits, slab counts) — and shown word by word, summed, as set
//! bits (occupied slices) or one bit (one slice).

use image::{Rgba, RgbaImage};
use plait::session::Prepared;
use plait_gpu::readback::TexelData;
use plait_graph::{Format, ResourceDesc, Schedule};

use crate::published::texture_sizes;

/// How a resource is turned into a picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Display {
    /// As stored (8-bit) or linear values encoded to sRGB.
    Color,
    /// One channel of a texture as a heat map.
    Channel(usize),
    /// One `u32` word per texel of a buffer.
    Word(u32),
    /// The sum of a texel's words (e.g. all slab counts).
    WordSum,
    /// How many bits of a texel's words are set (e.g. occupied slices).
    BitCount,
    /// One bit of a texel's words (e.g. one slice of an occupancy map).
    Bit(u32),
}

impl Display {
    pub fn label(self) -> String {
        match self {
            Display::Color => "colour".into(),
            Display::Channel(c) => format!("channel {}", CHANNELS[c.min(3)]),
            Display::Word(w) => format!("word {w}"),
            Display::WordSum => "sum of words".into(),
            Display::BitCount => "set bits".into(),
            Display::Bit(b) => format!("bit {b}"),
        }
    }
}

const CHANNELS: [&str; 4] = ["r", "g", "b", "a"];

/// Number of channels a format stores.
pub fn channels(format: Format) -> usize {
    match format {
        Format::R8Unorm
        | Format::R16Float
        | Format::R32Float
        | Format::R32Uint
        | Format::Depth32Float => 1,
        Format::Rg16Float | Format::Rg32Float | Format::Rg32Uint => 2,
        Format::Rgba8Unorm
        | Format::Rgba8UnormSrgb
        | Format::Rgba16Float
        | Format::Rgba32Float
        | Format::Rgba32Uint => 4,
    }
}

fn is_uint(format: Format) -> bool {
    matches!(
        format,
        Format::R32Uint | Format::Rg32Uint | Format::Rgba32Uint
    )
}

/// The display a resource starts with: colour for colour images, otherwise a
/// heat map of the first channel or word.
pub fn default_display(desc: &ResourceDesc) -> Display {
    match desc {
        ResourceDesc::Texture { format, .. } if channels(*format) == 4 && !is_uint(*format) => {
            Display::Color
        }
        ResourceDesc::Texture { .. } => Display::Channel(0),
        ResourceDesc::Buffer { .. } | ResourceDesc::AccelerationStructure => Display::Word(0),
    }
}

/// The displays that make sense for a resource (`words_per_texel` for buffers).
pub fn displays(desc: &ResourceDesc, words_per_texel: u32) -> Vec<Display> {
    match desc {
        ResourceDesc::Texture { format, .. } => {
            let n = channels(*format);
            let mut out = Vec::new();
            if n == 4 && !is_uint(*format) {
                out.push(Display::Color);
            }
            out.extend((0..n).map(Display::Channel));
            out
        }
        // Nothing plait can read back and show.
        ResourceDesc::AccelerationStructure => Vec::new(),
        ResourceDesc::Buffer { .. } => {
            let mut out: Vec<Display> = (0..words_per_texel.min(64)).map(Display::Word).collect();
            out.extend([Display::WordSum, Display::BitCount, Display::Bit(0)]);
            out
        }
    }
}

/// Texels of a buffer: `width × height`, `per_texel` words each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BufferLayout {
    pub width: u32,
    pub height: u32,
    pub per_texel: u32,
}

/// Lay `bytes` of a buffer out as texels of one of the `sizes` (the
/// schedule's texture sizes and the screen): the largest whose texel count
/// divides the word count. A buffer no size divides is shown as a square of
/// single words.
pub fn buffer_layout(bytes: u64, sizes: &[(u32, u32)]) -> BufferLayout {
    let words = bytes / 4;
    let best = sizes
        .iter()
        .filter(|(w, h)| {
            let texels = *w as u64 * *h as u64;
            texels > 0 && words >= texels && words.is_multiple_of(texels)
        })
        .max_by_key(|(w, h)| *w as u64 * *h as u64);
    match best {
        Some(&(width, height)) => BufferLayout {
            width,
            height,
            per_texel: (words / (width as u64 * height as u64)) as u32,
        },
        None => {
            let side = (words as f64).sqrt().ceil().max(1.0) as u32;
            BufferLayout {
                width: side,
                height: (words as u32).div_ceil(side).max(1),
                per_texel: 1,
            }
        }
    }
}

/// Raw values kept to answer "what is under the cursor".
#[derive(Clone, Debug)]
enum Raw {
    Texels {
        format: Format,
        values: Vec<[f32; 4]>,
    },
    Words {
        layout: BufferLayout,
        words: Vec<u32>,
    },
}

/// A resource as a picture.
#[derive(Clone, Debug)]
pub struct Inspected {
    pub name: String,
    pub display: Display,
    pub image: RgbaImage,
    /// What the colours mean (the range mapped to the scale).
    pub legend: String,
    raw: Raw,
}

fn f32_at(b: &[u8], o: usize) -> f32 {
    f32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]])
}
fn u32_at(b: &[u8], o: usize) -> u32 {
    u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]])
}
fn f16_at(b: &[u8], o: usize) -> f32 {
    half::f16::from_bits(u16::from_le_bytes([b[o], b[o + 1]])).to_f32()
}

/// Texel values as floats (8-bit formats as 0..1, integers exactly up to 2^24).
fn decode(t: &TexelData) -> Vec<[f32; 4]> {
    let b = &t.bytes;
    let n = t.format.bytes_per_texel() as usize;
    (0..(t.width * t.height) as usize)
        .map(|i| {
            let o = i * n;
            match t.format {
                Format::Rgba8Unorm | Format::Rgba8UnormSrgb => {
                    [0, 1, 2, 3].map(|c| b[o + c] as f32 / 255.0)
                }
                Format::R8Unorm => [b[o] as f32 / 255.0, 0.0, 0.0, 1.0],
                Format::R16Float => [f16_at(b, o), 0.0, 0.0, 1.0],
                Format::Rg16Float => [f16_at(b, o), f16_at(b, o + 2), 0.0, 1.0],
                Format::Rgba16Float => [0, 2, 4, 6].map(|c| f16_at(b, o + c)),
                Format::R32Float | Format::Depth32Float => [f32_at(b, o), 0.0, 0.0, 1.0],
                Format::Rg32Float => [f32_at(b, o), f32_at(b, o + 4), 0.0, 1.0],
                Format::Rgba32Float => [0, 4, 8, 12].map(|c| f32_at(b, o + c)),
                Format::R32Uint => [u32_at(b, o) as f32, 0.0, 0.0, 1.0],
                Format::Rg32Uint => [u32_at(b, o) as f32, u32_at(b, o + 4) as f32, 0.0, 1.0],
                Format::Rgba32Uint => [0, 4, 8, 12].map(|c| u32_at(b, o + c) as f32),
            }
        })
        .collect()
}

/// `values` as a magma heat map over their finite range; returns the image
/// and the range.
fn heat(values: &[f32], width: u32, height: u32) -> (RgbaImage, Option<(f32, f32)>) {
    let lut = plait_compare::heatmap::magma();
    let finite = values.iter().copied().filter(|v| v.is_finite());
    let range = finite.fold(None, |acc: Option<(f32, f32)>, v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    });
    let (lo, hi) = range.unwrap_or((0.0, 1.0));
    let span = hi - lo;
    let mut img = RgbaImage::new(width, height);
    for (px, v) in img.pixels_mut().zip(values) {
        *px = if !v.is_finite() {
            // Non-finite values stand out in a colour the scale never uses.
            Rgba([0, 160, 255, 255])
        } else {
            let t = if span > 0.0 { (v - lo) / span } else { 0.5 };
            let [r, g, b] = lut[(t.clamp(0.0, 1.0) * 255.0).round() as usize];
            Rgba([r, g, b, 255])
        };
    }
    (img, range)
}

fn number(v: f32) -> String {
    if v.fract() == 0.0 && v.abs() < 1e9 {
        format!("{v:.0}")
    } else if v.abs() >= 1e4 || (v != 0.0 && v.abs() < 1e-3) {
        format!("{v:.4e}")
    } else {
        format!("{v:.4}")
    }
}

fn range_legend(what: &str, range: Option<(f32, f32)>) -> String {
    match range {
        Some((lo, hi)) if lo == hi => format!("{what}: every value is {}", number(lo)),
        Some((lo, hi)) => format!(
            "{what}: {} (dark) … {} (bright), magma scale over the values present",
            number(lo),
            number(hi)
        ),
        None => format!("{what}: no finite values"),
    }
}

/// A texture read back, as `display` shows it.
pub fn texture(name: &str, texels: &TexelData, display: Display) -> Inspected {
    let values = decode(texels);
    let (image, legend) = match display {
        Display::Channel(c) => {
            let c = c.min(channels(texels.format) - 1);
            let channel: Vec<f32> = values.iter().map(|v| v[c]).collect();
            let (img, range) = heat(&channel, texels.width, texels.height);
            (img, range_legend(&Display::Channel(c).label(), range))
        }
        _ => (
            texels.to_image(),
            if matches!(texels.format, Format::Rgba8Unorm | Format::Rgba8UnormSrgb) {
                "colour as stored".to_owned()
            } else {
                "linear values encoded to sRGB, clamped to 0…1".to_owned()
            },
        ),
    };
    Inspected {
        name: name.to_owned(),
        display,
        image,
        legend: format!(
            "{} {}×{}: {legend}",
            texels.format, texels.width, texels.height
        ),
        raw: Raw::Texels {
            format: texels.format,
            values,
        },
    }
}

/// A buffer read back, laid out by `layout`, as `display` shows it.
pub fn buffer(name: &str, bytes: &[u8], layout: BufferLayout, display: Display) -> Inspected {
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let k = layout.per_texel.max(1) as usize;
    let texels = (layout.width * layout.height) as usize;
    let texel_words = |i: usize| {
        let start = (i * k).min(words.len());
        &words[start..(start + k).min(words.len())]
    };
    let per_texel: Vec<f32> = (0..texels)
        .map(|i| {
            let w = texel_words(i);
            match display {
                Display::Word(j) => w.get(j as usize).copied().unwrap_or(0) as f32,
                Display::WordSum => w.iter().map(|&x| x as f64).sum::<f64>() as f32,
                Display::BitCount => w.iter().map(|x| x.count_ones()).sum::<u32>() as f32,
                Display::Bit(b) => {
                    let word = w.get((b / 32) as usize).copied().unwrap_or(0);
                    ((word >> (b % 32)) & 1) as f32
                }
                Display::Color | Display::Channel(_) => w.first().copied().unwrap_or(0) as f32,
            }
        })
        .collect();
    let (image, range) = heat(&per_texel, layout.width, layout.height);
    Inspected {
        name: name.to_owned(),
        display,
        image,
        legend: format!(
            "buffer as {}×{} texels of {} u32 word{}: {}",
            layout.width,
            layout.height,
            layout.per_texel,
            if layout.per_texel == 1 { "" } else { "s" },
            range_legend(&display.label(), range)
        ),
        raw: Raw::Words { layout, words },
    }
}

impl Inspected {
    /// What is stored at texel (x, y), as text.
    pub fn value_at(&self, x: u32, y: u32) -> Option<String> {
        if x >= self.image.width() || y >= self.image.height() {
            return None;
        }
        let i = (y * self.image.width() + x) as usize;
        Some(match &self.raw {
            Raw::Texels { format, values } => {
                let v = values.get(i)?;
                let parts: Vec<String> = (0..channels(*format))
                    .map(|c| format!("{} {}", CHANNELS[c], number(v[c])))
                    .collect();
                format!("({x}, {y}): {}", parts.join(", "))
            }
            Raw::Words { layout, words } => {
                let k = layout.per_texel.max(1) as usize;
                let start = i * k;
                let w = words.get(start..(start + k).min(words.len()))?;
                let bits = matches!(self.display, Display::BitCount | Display::Bit(_));
                let shown: Vec<String> = w
                    .iter()
                    .take(8)
                    .map(|x| {
                        if bits {
                            format!("{x:#010x}")
                        } else {
                            x.to_string()
                        }
                    })
                    .collect();
                let more = if w.len() > 8 { ", …" } else { "" };
                format!("({x}, {y}): [{}{more}]", shown.join(", "))
            }
        })
    }
}

/// The resource `name` of a built pipeline read back and shown `display`
/// (its default display when `None`); an unknown name suggests the nearest.
pub fn resource(
    prepared: &Prepared<'_>,
    schedule: &Schedule,
    name: &str,
    display: Option<Display>,
) -> Result<Inspected, String> {
    let id = schedule.resource(name).ok_or_else(|| {
        let names: Vec<&str> = schedule.resources.iter().map(|r| r.name.as_str()).collect();
        format!(
            "error: --inspect: no resource `{name}` in this pipeline{} (it has {})",
            plait_graph::suggest::did_you_mean(name, names.iter().copied()),
            names.join(", ")
        )
    })?;
    let desc = &schedule.resources[id].desc;
    let display = display.unwrap_or_else(|| default_display(desc));
    let r = prepared;
    match desc {
        ResourceDesc::Texture { .. } => r
            .read_resource(name)
            .map(|t| texture(name, &t, display))
            .map_err(|e| crate::engine::error_text(&e)),
        ResourceDesc::Buffer { size } => {
            let layout = buffer_layout(*size, &texture_sizes(schedule));
            r.read_buffer(name)
                .map(|b| buffer(name, &b, layout, display))
                .map_err(|e| crate::engine::error_text(&e))
        }
        ResourceDesc::AccelerationStructure => Err(format!(
            "`{name}` is an acceleration structure: it cannot be read back and shown"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buffers_take_the_largest_texture_size_that_divides_them() {
        // The occupancy bits of a 512² light map: 4 words per texel.
        let l = buffer_layout(512 * 512 * 16, &[(320, 240), (512, 512), (256, 256)]);
        assert_eq!(
            l,
            BufferLayout {
                width: 512,
                height: 512,
                per_texel: 4
            }
        );
        // Nothing divides 10 words: a square of single words.
        let l = buffer_layout(40, &[(3, 3)]);
        assert_eq!((l.width, l.height, l.per_texel), (4, 3, 1));
    }

    #[test]
    fn slab_counts_become_a_heat_map_with_values_under_the_cursor() {
        let layout = BufferLayout {
            width: 2,
            height: 1,
            per_texel: 4,
        };
        let words: Vec<u8> = [1u32, 2, 3, 4, 0, 0, 0, 8]
            .iter()
            .flat_map(|w| w.to_le_bytes())
            .collect();
        let sum = buffer("slabs", &words, layout, Display::WordSum);
        assert!(
            sum.legend.contains("8 (dark) … 10 (bright)"),
            "{}",
            sum.legend
        );
        assert_eq!(sum.value_at(0, 0).as_deref(), Some("(0, 0): [1, 2, 3, 4]"));
        assert_eq!(sum.value_at(2, 0), None);
        let bits = buffer("slabs", &words, layout, Display::BitCount);
        // 1,2,3,4 have 1+1+2+1 set bits; 8 has one.
        assert!(
            bits.legend.contains("1 (dark) … 5 (bright)"),
            "{}",
            bits.legend
        );
        let slice = buffer("slabs", &words, layout, Display::Bit(99));
        // Bit 99 = word 3, bit 3: clear in 4, set in 8 — darkest and brightest.
        let magma = plait_compare::heatmap::magma();
        let rgba = |c: [u8; 3]| Rgba([c[0], c[1], c[2], 255]);
        assert_eq!(slice.image.get_pixel(0, 0), &rgba(magma[0]));
        assert_eq!(slice.image.get_pixel(1, 0), &rgba(magma[255]));
    }

    #[test]
    fn float_channels_are_mapped_over_their_range_and_read_back_exactly() {
        let texels = TexelData {
            width: 2,
            height: 1,
            format: Format::Rg32Float,
            bytes: [0.5f32, 2.0, 1.5, f32::INFINITY]
                .iter()
                .flat_map(|v| v.to_le_bytes())
                .collect(),
        };
        let near = texture("light_range", &texels, Display::Channel(0));
        assert!(
            near.legend.contains("0.5000 (dark) … 1.5000 (bright)"),
            "{}",
            near.legend
        );
        assert_eq!(
            near.value_at(1, 0).as_deref(),
            Some("(1, 0): r 1.5000, g inf")
        );
        let far = texture("light_range", &texels, Display::Channel(1));
        // The infinite value is left out of the range and drawn in its own colour.
        assert!(far.legend.contains("every value is 2"), "{}", far.legend);
        assert_eq!(far.image.get_pixel(1, 0), &Rgba([0, 160, 255, 255]));
    }
}
