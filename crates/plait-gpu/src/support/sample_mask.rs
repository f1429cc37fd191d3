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

#[cfg(test)]
mod tests {
    use super::uses_sample_mask;

    fn uses(wgsl: &str) -> bool {
        uses_sample_mask(&naga::front::wgsl::parse_str(wgsl).expect("valid WGSL"))
    }

    #[test]
    fn the_mask_read_or_written_is_found_and_its_absence_is_not() {
        let read = "@fragment fn f(@builtin(sample_mask) m: u32) -> @location(0) vec4<f32> { return vec4<f32>(f32(m)); }";
        let written = "struct O { @location(0) c: vec4<f32>, @builtin(sample_mask) m: u32 }
            @fragment fn f() -> O { return O(vec4<f32>(1.0), 1u); }";
        let neither = "@fragment fn f(@builtin(sample_index) i: u32) -> @location(0) vec4<f32> { return vec4<f32>(f32(i)); }";
        assert!(uses(read));
        assert!(uses(written));
        assert!(!uses(neither));
    }
}
