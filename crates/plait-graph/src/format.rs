//! Texture formats a pipeline file may name, without depending on wgpu.
//!
//! The spelling is wgpu's (`rgba16float`, `r32uint`, `depth32float`, …) so a
//! reader who knows WebGPU recognises them; the GPU crate maps each variant to
//! `wgpu::TextureFormat` one to one.

use std::fmt;
use std::str::FromStr;

/// A texel format of a texture resource.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(into = "String")]
pub enum Format {
    R8Unorm,
    Rgba8Unorm,
    Rgba8UnormSrgb,
    R16Float,
    Rg16Float,
    Rgba16Float,
    R32Float,
    Rg32Float,
    Rgba32Float,
    R32Uint,
    Rg32Uint,
    Rgba32Uint,
    Depth32Float,
}

/// How a shader sees the texel values of a format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SampleType {
    Float,
    Uint,
    Depth,
}

impl Format {
    pub const ALL: &'static [Format] = &[
        Format::R8Unorm,
        Format::Rgba8Unorm,
        Format::Rgba8UnormSrgb,
        Format::R16Float,
        Format::Rg16Float,
        Format::Rgba16Float,
        Format::R32Float,
        Format::Rg32Float,
        Format::Rgba32Float,
        Format::R32Uint,
        Format::Rg32Uint,
        Format::Rgba32Uint,
        Format::Depth32Float,
    ];

    /// The name used in pipeline files (wgpu's spelling).
    pub fn name(self) -> &'static str {
        match self {
            Format::R8Unorm => "r8unorm",
            Format::Rgba8Unorm => "rgba8unorm",
            Format::Rgba8UnormSrgb => "rgba8unorm-srgb",
            Format::R16Float => "r16float",
            Format::Rg16Float => "rg16float",
            Format::Rgba16Float => "rgba16float",
            Format::R32Float => "r32float",
            Format::Rg32Float => "rg32float",
            Format::Rgba32Float => "rgba32float",
            Format::R32Uint => "r32uint",
            Format::Rg32Uint => "rg32uint",
            Format::Rgba32Uint => "rgba32uint",
            Format::Depth32Float => "depth32float",
        }
    }

    pub fn bytes_per_texel(self) -> u64 {
        match self {
            Format::R8Unorm => 1,
            Format::R16Float => 2,
            Format::Rgba8Unorm | Format::Rgba8UnormSrgb | Format::Rg16Float => 4,
            Format::R32Float | Format::R32Uint | Format::Depth32Float => 4,
            Format::Rgba16Float | Format::Rg32Float | Format::Rg32Uint => 8,
            Format::Rgba32Float | Format::Rgba32Uint => 16,
        }
    }

    pub fn sample_type(self) -> SampleType {
        match self {
            Format::R32Uint | Format::Rg32Uint | Format::Rgba32Uint => SampleType::Uint,
            Format::Depth32Float => SampleType::Depth,
            _ => SampleType::Float,
        }
    }

    pub fn is_depth(self) -> bool {
        self.sample_type() == SampleType::Depth
    }

    /// Number of channels (1–4).
    pub fn components(self) -> u32 {
        match self {
            Format::R8Unorm
            | Format::R16Float
            | Format::R32Float
            | Format::R32Uint
            | Format::Depth32Float => 1,
            Format::Rg16Float | Format::Rg32Float | Format::Rg32Uint => 2,
            _ => 4,
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl From<Format> for String {
    fn from(f: Format) -> String {
        f.name().to_owned()
    }
}

/// The error of parsing an unknown format name; lists the known ones.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown texture format `{0}` (known: {known})", known = Format::ALL.iter().map(|f| f.name()).collect::<Vec<_>>().join(", "))]
pub struct UnknownFormat(pub String);

impl FromStr for Format {
    type Err = UnknownFormat;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Format::ALL
            .iter()
            .copied()
            .find(|f| f.name() == s)
            .ok_or_else(|| UnknownFormat(s.to_owned()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for &f in Format::ALL {
            assert_eq!(f.name().parse::<Format>().unwrap(), f);
        }
        assert!("rgba9float".parse::<Format>().is_err());
    }
}
