//! Where plait waits for the GPU. Every readback is async
//! ([`crate::readback::map_buffer_async`]); native code blocks on it here. A
//! browser's thread cannot block: there the synchronous entry points fail
//! with [`CANNOT_WAIT`] instead of hanging the page, and the page awaits the
//! `_async` ones. wgpu's error scopes are waited on the same way; in a
//! browser the work runs without a scope and its errors reach the device's
//! uncaptured-error handler ([`crate::Gpu::take_uncaptured_errors`]), which
//! [`crate::Renderer::render_async`] reads after the frame is back.

use std::future::Future;

/// Why a synchronous call failed in a browser.
pub const CANNOT_WAIT: &str = "a browser cannot wait for the GPU here: this step runs natively \
only (the page awaits the asynchronous entry points)";

/// `f`'s output, blocking until it is ready (native).
#[cfg(not(target_arch = "wasm32"))]
pub fn wait_for<T>(f: impl Future<Output = T>) -> Result<T, String> {
    Ok(pollster::block_on(f))
}

/// `f`'s output if it is ready at once; otherwise [`CANNOT_WAIT`] (in a
/// browser nothing completes until the page's event loop runs again).
#[cfg(target_arch = "wasm32")]
pub fn wait_for<T>(f: impl Future<Output = T>) -> Result<T, String> {
    let mut f = std::pin::pin!(f);
    let mut cx = std::task::Context::from_waker(std::task::Waker::noop());
    match f.as_mut().poll(&mut cx) {
        std::task::Poll::Ready(v) => Ok(v),
        std::task::Poll::Pending => Err(CANNOT_WAIT.into()),
    }
}

/// Run `f` inside a validation error scope; its result and wgpu's first
/// validation error, if any.
#[cfg(not(target_arch = "wasm32"))]
pub fn validated<T>(device: &wgpu::Device, f: impl FnOnce() -> T) -> (T, Option<wgpu::Error>) {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let result = f();
    (result, pollster::block_on(scope.pop()))
}

/// In a browser: `f` unscoped (see the module's note); its errors are
/// reported with the next frame.
#[cfg(target_arch = "wasm32")]
pub fn validated<T>(_device: &wgpu::Device, f: impl FnOnce() -> T) -> (T, Option<wgpu::Error>) {
    (f(), None)
}
