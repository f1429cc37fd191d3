//! The linear image: the pipeline's radiance before the display transform
//! (`[resources.radiance]`, written by the transparency technique, read by
//! the tone-mapping technique), read back as 32-bit floats and saved as
//! OpenEXR (`plait render --out x.exr`, and beside each image of a `plait ab`
//! report).

use plait_gpu::readback::TexelData;
use plait_graph::{Format, Pipeline, ResourceKind};

/// The resource every gallery pipeline keeps its linear radiance in.
pub const RADIANCE: &str = "radiance";

/// Why a pipeline has no linear image to save.
#[derive(Debug, thiserror::Error)]
pub enum LinearError {
    #[error(
        "{flag}: {pipeline} has no floating-point `{RADIANCE}` texture (the linear image \
         before the display transform), so there is no radiance to save{found}; save a .png, \
         or declare `[resources.{RADIANCE}]` as rgba16float or rgba32float and compose into it"
    )]
    NoRadiance {
        flag: String,
        pipeline: String,
        found: String,
    },
    #[error("writing OpenEXR: {0}")]
    Encode(#[from] image::ImageError),
}

/// Whether `format` holds linear floating-point colour.
pub fn is_float_colour(format: Format) -> bool {
    matches!(format, Format::Rgba16Float | Format::Rgba32Float)
}

/// Checks, before any GPU work, that `pipeline` declares a floating-point
/// `radiance` texture; `flag` (e.g. `--out x.exr`) is where the error points.
pub fn check_radiance(pipeline: &Pipeline, flag: &str) -> Result<(), LinearError> {
    let decl = pipeline.resources.get(RADIANCE);
    let format = decl
        .filter(|r| r.kind.value == ResourceKind::Texture)
        .and_then(|r| r.format.as_ref().map(|f| f.value));
    if format.is_some_and(is_float_colour) {
        return Ok(());
    }
    let found = match (decl, format) {
        (None, _) => String::new(),
        (Some(_), Some(f)) => format!(" (it is {})", f.name()),
        (Some(_), None) => " (it is a buffer)".to_owned(),
    };
    Err(LinearError::NoRadiance {
        flag: flag.to_owned(),
        pipeline: pipeline
            .files
            .first()
            .map_or_else(|| "the pipeline".into(), |f| f.display().to_string()),
        found,
    })
}

/// Texels read back as 32-bit float RGBA, values as stored (an f16 texel
/// converts to f32 exactly).
pub fn to_f32_image(texels: &TexelData) -> image::Rgba32FImage {
    let mut img = image::Rgba32FImage::new(texels.width, texels.height);
    for (i, px) in img.pixels_mut().enumerate() {
        *px = image::Rgba(texels.texel(i));
    }
    img
}

/// OpenEXR bytes of `image` (32-bit float RGBA, linear).
pub fn encode_exr(image: &image::Rgba32FImage) -> Result<Vec<u8>, LinearError> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgba32F(image.clone())
        .write_to(&mut bytes, image::ImageFormat::OpenExr)?;
    Ok(bytes.into_inner())
}
