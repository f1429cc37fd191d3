//! Whether a shader's fragment stage uses `@builtin(sample_mask)` (reads the
//! samples the primitive covers, or writes which of them it keeps): what
//! wgpu's GL backend cannot compile (see `AdapterSupport::sample_mask`).

use naga::{Binding, BuiltIn, Handle, Module, ShaderStage, Type, TypeInner};

/// Whether a fragment entry point of `module` takes or returns the sample
/// mask, as an argument, a result, or a member of either's struct.
pub fn uses_sample_mask(module: &Module) -> bool {
    module
        .entry_points
        .iter()
        .filter(|ep| ep.stage == ShaderStage::Fragment)
        .any(|ep| {
            let f = &ep.function;
            let arguments = f
                .arguments
                .iter()
                .any(|a| binds(module, a.ty, a.binding.as_ref()));
            let result = f
                .result
                .as_ref()
                .is_some_and(|r| binds(module, r.ty, r.binding.as_ref()));
            arguments || result
        })
}

/// `binding` is the sample mask, or `ty` is a struct with a member bound to it.
fn binds(module: &Module, ty: Handle<Type>, binding: Option<&Binding>) -> bool {
    let is_mask = |b: Option<&Binding>| matches!(b, Some(Binding::BuiltIn(BuiltIn::SampleMask)));
    if is_mask(binding) {
        return true;
    }
    match &module.types[ty].inner {
        TypeInner::Struct { members, .. } => members.iter().any(|m| is_mask(m.binding.as_ref())),
        _ => false,
    }
}
