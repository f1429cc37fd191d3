//! plait's wgpu executor: a compiled [`plait_graph::Schedule`] becomes command
//! buffers. The device is headless and runs on whatever adapter exists (Mesa's
//! lavapipe in CI); optional features are probed and used when present.

pub mod cache;
pub mod depth_guard;
pub mod device;
pub mod environment;
pub mod executor;
pub mod frame;
pub mod geometry;
pub mod library;
pub mod loop_budget;
pub mod modules;
pub mod overflow;
pub mod pass;
pub mod pool;
pub mod readback;
pub mod reflect;
pub mod shader;
pub mod strand_structure;
pub mod support;
pub mod timing;
pub mod wait;

pub use device::{Capabilities, Gpu, NO_ADAPTER_HELP};
pub use executor::{FrameReport, PassTiming, Renderer};
pub use overflow::Overflow;
pub use pass::{PassLibrary, PassType};
pub use shader::{Define, ShaderError, ShaderLibrary};
pub use support::{AdapterSupport, Unsupported};
pub use timing::TimestampWay;

/// Failures of the GPU side. Messages name the pass or shader at fault.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error("{0}")]
    NoAdapter(String),
    #[error("could not open the GPU device: {0}")]
    Device(String),
    #[error("pass `{pass}` needs the GPU feature {feature}, which adapter `{adapter}` lacks")]
    MissingFeature {
        pass: String,
        feature: String,
        adapter: String,
    },
    /// The adapter cannot run the schedule: every problem, found before
    /// anything was created ([`support::check_schedule`]).
    #[error("{0}")]
    Unsupported(Box<Unsupported>),
    #[error("resource `{resource}`: {message}")]
    Resource { resource: String, message: String },
    #[error("pass `{pass}`: {message}")]
    Pass { pass: String, message: String },
    #[error(transparent)]
    Shader(#[from] ShaderError),
    #[error("GPU validation error in pass `{pass}`: {message}")]
    Validation { pass: String, message: String },
    #[error("reading back `{resource}`: {message}")]
    Readback { resource: String, message: String },
}

/// A wgpu error with its whole chain of causes on one line.
pub fn describe_wgpu_error(e: &wgpu::Error) -> String {
    let mut text = e.to_string().trim().to_owned();
    let mut source = std::error::Error::source(e);
    while let Some(s) = source {
        let part = s.to_string();
        if !text.contains(part.trim()) {
            text.push_str(": ");
            text.push_str(part.trim());
        }
        source = s.source();
    }
    text.replace("\n", " ")
}
