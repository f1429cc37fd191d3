//! A stand-in for one line wgpu's WebGPU backend lacks: wgpu 30.0.1's
//! `begin_render_pass` (`src/backend/webgpu.rs`) copies the colour and depth
//! attachments and the timestamp writes into the browser's
//! `GPURenderPassDescriptor`, but never `occlusion_query_set`, and WebGPU
//! refuses `beginOcclusionQuery` in a pass without one ("The
//! occlusionQuerySet in RenderPassDescriptor is not set"). Native wgpu
//! passes it on, so depth peeling ran natively and stopped on the page.
//!
//! Until wgpu forwards it, the page's device puts it back: every occlusion
//! query set created is remembered by its label, and a render pass that
//! names none gets the set labelled `occlusion:` + the pass's own label
//! (how `hair_depth_peel` labels its set, `crates/plait-passes/src/depth_peeling.rs`).
//! A query set in a pass that begins no query is allowed by WebGPU, so the
//! pass's other render passes (its clear, under the same label) are unaffected.

use wasm_bindgen::JsValue;

const SHIM: &str = r#"
if (globalThis.GPUDevice && !GPUDevice.prototype.plaitOcclusionShim) {
  const sets = new Map();
  const create = GPUDevice.prototype.createQuerySet;
  GPUDevice.prototype.createQuerySet = function (desc) {
    const set = create.call(this, desc);
    if (desc.type === 'occlusion' && desc.label) sets.set(desc.label, new WeakRef(set));
    return set;
  };
  const begin = GPUCommandEncoder.prototype.beginRenderPass;
  GPUCommandEncoder.prototype.beginRenderPass = function (desc) {
    if (desc.occlusionQuerySet === undefined && desc.label) {
      const set = sets.get('occlusion:' + desc.label)?.deref();
      if (set) desc.occlusionQuerySet = set;
    }
    return begin.call(this, desc);
  };
  GPUDevice.prototype.plaitOcclusionShim = true;
}
"#;

/// Installs the stand-in (once per page), before the device creates anything.
pub fn install() -> Result<(), JsValue> {
    js_sys::Function::new_no_args(SHIM)
        .call0(&JsValue::NULL)
        .map(|_| ())
}
