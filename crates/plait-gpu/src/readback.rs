//! Copy a texture back to the CPU as an 8-bit sRGB image.

use plait_graph::Format;

use crate::GpuError;

/// Texel values of a texture read back, before conversion to an image.
pub struct TexelData {
    pub width: u32,
    pub height: u32,
    pub format: Format,
    /// Tightly packed rows.
    pub bytes: Vec<u8>,
}

/// Read layer 0 of a single-sampled texture, waiting for it (a browser
/// cannot block: it awaits [`read_texture_async`], see [`crate::wait`]).
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    format: Format,
    name: &str,
) -> Result<TexelData, GpuError> {
    crate::wait::wait_for(read_texture_async(device, queue, texture, format, name)).map_err(
        |message| GpuError::Readback {
            resource: name.to_owned(),
            message,
        },
    )?
}

/// Read layer 0 of a single-sampled texture: the one readback of a frame's
/// image, native and in the browser.
pub async fn read_texture_async(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    format: Format,
    name: &str,
) -> Result<TexelData, GpuError> {
    let (width, height) = (texture.width(), texture.height());
    let bpp = format.bytes_per_texel() as u32;
    let unpadded = width * bpp;
    let padded = unpadded.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: padded as u64 * height as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("readback"),
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);
    let bytes = map_buffer_async(device, &buffer)
        .await
        .map_err(|message| GpuError::Readback {
            resource: name.to_owned(),
            message,
        })?;
    let mut out = Vec::with_capacity((unpadded * height) as usize);
    for row in bytes.chunks(padded as usize) {
        out.extend_from_slice(&row[..unpadded as usize]);
    }
    Ok(TexelData {
        width,
        height,
        format,
        bytes: out,
    })
}

/// Map a MAP_READ buffer and copy its contents out, waiting for the GPU (a
/// browser cannot: there this fails, see [`crate::wait`]).
pub fn map_buffer(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>, String> {
    crate::wait::wait_for(map_buffer_async(device, buffer))?
}

/// Map a MAP_READ buffer and copy its contents out: the one place plait
/// waits for the GPU's results. Native code polls the device until the
/// mapping is done; in a browser the mapping completes from the page's event
/// loop, so the future yields to it.
pub async fn map_buffer_async(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
) -> Result<Vec<u8>, String> {
    let (done, mapped) = oneshot();
    buffer.map_async(wgpu::MapMode::Read, .., move |r| done.send(r));
    #[cfg(not(target_arch = "wasm32"))]
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| e.to_string())?;
    #[cfg(target_arch = "wasm32")]
    let _ = device;
    mapped.await.map_err(|e| e.to_string())?;
    let data = buffer
        .get_mapped_range(..)
        .map_err(|e| e.to_string())?
        .to_vec();
    buffer.unmap();
    Ok(data)
}

/// A value sent once from a callback, awaited (no executor needed: the
/// sender wakes whoever polled).
fn oneshot<T>() -> (Sender<T>, Receiver<T>) {
    let slot = std::sync::Arc::new(std::sync::Mutex::new(Slot {
        value: None,
        waker: None,
    }));
    (Sender(slot.clone()), Receiver(slot))
}

struct Slot<T> {
    value: Option<T>,
    waker: Option<std::task::Waker>,
}

struct Sender<T>(std::sync::Arc<std::sync::Mutex<Slot<T>>>);
struct Receiver<T>(std::sync::Arc<std::sync::Mutex<Slot<T>>>);

impl<T> Sender<T> {
    fn send(self, value: T) {
        let mut slot = self.0.lock().unwrap_or_else(|e| e.into_inner());
        slot.value = Some(value);
        if let Some(w) = slot.waker.take() {
            w.wake();
        }
    }
}

impl<T> std::future::Future for Receiver<T> {
    type Output = T;
    fn poll(self: std::pin::Pin<&mut Self>, cx: &mut std::task::Context<'_>) -> std::task::Poll<T> {
        let mut slot = self.0.lock().unwrap_or_else(|e| e.into_inner());
        match slot.value.take() {
            Some(v) => std::task::Poll::Ready(v),
            None => {
                slot.waker = Some(cx.waker().clone());
                std::task::Poll::Pending
            }
        }
    }
}

fn linear_to_srgb(x: f32) -> u8 {
    let x = if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = if x <= 0.003_130_8 {
        x * 12.92
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

impl TexelData {
    /// Texel `i` as linear RGBA floats (sRGB formats decoded by the caller's intent:
    /// 8-bit values are returned as stored).
    pub fn texel(&self, i: usize) -> [f32; 4] {
        let b = &self.bytes;
        let f32_at = |o: usize| f32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]);
        let u32_at = |o: usize| u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]) as f32;
        let f16_at = |o: usize| half_to_f32(u16::from_le_bytes([b[o], b[o + 1]]));
        let n = self.format.bytes_per_texel() as usize;
        let o = i * n;
        match self.format {
            Format::Rgba8Unorm | Format::Rgba8UnormSrgb => [
                b[o] as f32 / 255.0,
                b[o + 1] as f32 / 255.0,
                b[o + 2] as f32 / 255.0,
                b[o + 3] as f32 / 255.0,
            ],
            Format::R8Unorm => [b[o] as f32 / 255.0; 4],
            Format::R16Float => [f16_at(o); 4],
            Format::Rg16Float => [f16_at(o), f16_at(o + 2), 0.0, 1.0],
            Format::Rgba16Float => [f16_at(o), f16_at(o + 2), f16_at(o + 4), f16_at(o + 6)],
            Format::R32Float | Format::Depth32Float => [f32_at(o); 4],
            Format::Rg32Float => [f32_at(o), f32_at(o + 4), 0.0, 1.0],
            Format::Rgba32Float => [f32_at(o), f32_at(o + 4), f32_at(o + 8), f32_at(o + 12)],
            Format::R32Uint => [u32_at(o); 4],
            Format::Rg32Uint => [u32_at(o), u32_at(o + 4), 0.0, 1.0],
            Format::Rgba32Uint => [u32_at(o), u32_at(o + 4), u32_at(o + 8), u32_at(o + 12)],
        }
    }

    /// An 8-bit sRGB picture: 8-bit formats as stored, float formats
    /// encoded from linear, single-channel formats as grey, alpha opaque.
    pub fn to_image(&self) -> image::RgbaImage {
        let mut img = image::RgbaImage::new(self.width, self.height);
        let stored_8bit = matches!(
            self.format,
            Format::Rgba8Unorm | Format::Rgba8UnormSrgb | Format::R8Unorm
        );
        for (i, px) in img.pixels_mut().enumerate() {
            let t = self.texel(i);
            let c = |x: f32| {
                if stored_8bit {
                    (x.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
                } else {
                    linear_to_srgb(x)
                }
            };
            *px = image::Rgba([c(t[0]), c(t[1]), c(t[2]), 255]);
        }
        img
    }
}

fn half_to_f32(h: u16) -> f32 {
    half::f16::from_bits(h).to_f32()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_values() {
        assert_eq!(half_to_f32(0x3c00), 1.0);
        assert_eq!(half_to_f32(0xc000), -2.0);
        assert_eq!(half_to_f32(0x3800), 0.5);
        assert_eq!(half_to_f32(0x0000), 0.0);
    }

    #[test]
    fn srgb_endpoints() {
        assert_eq!(linear_to_srgb(0.0), 0);
        assert_eq!(linear_to_srgb(1.0), 255);
        assert_eq!(linear_to_srgb(f32::NAN), 0);
        // 0.2158 linear is 0.502 in sRGB, the middle of the 8-bit range.
        assert_eq!(linear_to_srgb(0.2158), 128);
    }
}
