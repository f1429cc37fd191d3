//! The shader checker compile runs ([`plait_graph::PassChecker`]): every pass
//! against its WGSL with naga — sizes, bindings, params, fixed-function
//! state, the depth guard — and, from the shader, how a data-only pass
//! accesses its slots and which colour targets it blends. No GPU involved:
//! `plait check` runs it with WebGPU's defaults, a device with its own
//! capabilities.

use plait_graph::{
    Error as GraphError, ErrorKind, Location, PassCheck, PassChecker, PassShape, ResolvedResource,
    ScheduledPass,
};

use super::pass_type::{PassLibrary, PassType, shader_source};
use super::plan::{BindingPlan, binding_aliases, pass_module, unguardable};
use super::state::from_decl;
use crate::Capabilities;
use crate::reflect;
use crate::shader::ShaderError;

/// Checks passes of `library`'s types for an adapter with `caps`.
pub struct ShaderChecker<'a> {
    pub library: &'a PassLibrary,
    pub caps: Capabilities,
}

impl<'a> ShaderChecker<'a> {
    pub fn new(library: &'a PassLibrary, caps: Capabilities) -> Self {
        ShaderChecker { library, caps }
    }
}

/// A library error at its place: the library's own messages start with
/// `PATH:LINE:COLUMN: ` or `PATH: ` (an import, a duplicate module, a
/// contract), which becomes the error's location; naga's diagnostics carry
/// their own and are kept whole.
fn library_error(e: ShaderError) -> GraphError {
    let prefix = format!("{}:", e.path.display());
    let Some(rest) = e.message.strip_prefix(&prefix) else {
        return GraphError::new(
            Location::Path {
                path: e.path.clone(),
            },
            ErrorKind::Shader {
                path: e.path,
                message: e.message,
            },
        );
    };
    let mut parts = rest.splitn(3, ':');
    let place = (parts.next(), parts.next(), parts.next());
    let (location, message) = match place {
        (Some(line), Some(column), Some(message))
            if line.parse::<u32>().is_ok() && column.parse::<u32>().is_ok() =>
        {
            (
                Location::File {
                    path: e.path.clone(),
                    line: line.parse().unwrap_or(1),
                    column: column.parse().unwrap_or(1),
                },
                message,
            )
        }
        _ => (
            Location::Path {
                path: e.path.clone(),
            },
            rest,
        ),
    };
    GraphError::new(location, ErrorKind::Schema(message.trim_start().to_owned()))
}

impl PassChecker for ShaderChecker<'_> {
    fn check_library(&self) -> Vec<GraphError> {
        match self.library.shaders.check() {
            Ok(()) => Vec::new(),
            Err(e) => vec![library_error(e)],
        }
    }

    fn check_pass(&self, pass: &ScheduledPass, resources: &[ResolvedResource]) -> PassCheck {
        // An unknown type was reported by compile already.
        let Some(t) = self.library.pass_type(pass) else {
            return PassCheck::default();
        };
        let shared: Vec<&str> = self
            .library
            .shared_params
            .iter()
            .map(|p| p.name.as_str())
            .collect();
        let mut check = check_pass(
            t,
            pass,
            resources,
            &shared,
            &self.caps,
            &self.library.shaders,
        );
        for shared_check in &self.library.shared_checks {
            if let Err(message) = shared_check(pass, resources) {
                check.errors.push(GraphError::new(
                    pass.location.clone(),
                    ErrorKind::Pass {
                        pass: pass.name.clone(),
                        message,
                    },
                ));
            }
        }
        check
    }
}

/// Check one pass against its shader (see the module).
pub fn check_pass(
    t: &dyn PassType,
    pass: &ScheduledPass,
    resources: &[ResolvedResource],
    shared_params: &[&str],
    caps: &Capabilities,
    shaders: &crate::modules::Shaders,
) -> PassCheck {
    let module = match pass_module(t, pass, shaders) {
        Ok(m) => m,
        Err(e) => {
            return PassCheck {
                errors: vec![*e],
                ..PassCheck::default()
            };
        }
    };
    let spec = t.spec();
    let mut errors = Vec::new();
    let err = |loc: &Location, message: String| {
        GraphError::new(
            loc.clone(),
            ErrorKind::Pass {
                pass: pass.name.clone(),
                message,
            },
        )
    };
    if let Err(message) = t.check_sizes(pass, resources) {
        errors.push(err(&pass.location, message));
    }
    if spec.dynamic_slots {
        errors.extend(
            unread_params(t, pass, &module, shared_params, shaders)
                .into_iter()
                .map(|m| err(&pass.location, m)),
        );
    }
    let aliases = binding_aliases(&spec);
    let (plan, plan_errors) = BindingPlan::new(
        &module,
        pass,
        resources,
        spec.shape,
        spec.dynamic_slots,
        &aliases,
    );
    let source = shader_source(t, pass, shaders).ok();
    let source = source.as_ref().map(|(p, s)| (p.as_path(), s.as_ref()));
    errors.extend(super::storage_format::at_wgsl(
        plan_errors,
        pass,
        &aliases,
        source,
    ));
    // Only where the generic recorder draws with exactly the plan's colour
    // targets: a type written in Rust may record its own passes with other
    // targets (depth peeling's layer and blend draws). A culled pass whose
    // targets were dropped with it has no colour targets left to check.
    let dropped = pass.writes.iter().any(|b| b.resource.is_none());
    if spec.state_from_data && spec.shape != PassShape::Compute && !dropped {
        let outputs = super::outputs::check(&module, &plan, pass, source);
        errors.extend(outputs.into_iter().map(|(loc, m)| err(&loc, m)));
    }
    // The state is read from the pass as it will be: accesses settled.
    let mut settled_pass = pass.clone();
    plait_graph::apply_settled(&mut settled_pass, &plan.settled);
    let mut blended = Vec::new();
    if spec.state_from_data && spec.shape != PassShape::Compute {
        let decl = t.raster_decl(&settled_pass);
        match from_decl(&decl, &settled_pass, resources) {
            Err(list) => errors.extend(list.into_iter().map(|(loc, m)| err(&loc, m))),
            Ok(state) => {
                if let Some(message) = unguardable(&plan, state.depth, false) {
                    let loc = decl.depth.as_ref().map_or(&pass.location, |d| &d.location);
                    errors.push(err(loc, message));
                }
                blended = blended_targets(&plan, &state.blend);
            }
        }
    } else if spec.shape != PassShape::Compute
        && let Ok(state) = t.raster_state(&settled_pass, caps)
    {
        blended = blended_targets(&plan, &state.blend);
    }
    PassCheck {
        errors,
        settled: plan.settled,
        blended,
    }
}

/// The colour targets of `plan` that `blend` (one entry per target) blends.
fn blended_targets(
    plan: &BindingPlan,
    blend: &[Option<wgpu::BlendState>],
) -> Vec<plait_graph::ResourceId> {
    plan.colors
        .iter()
        .zip(blend)
        .filter(|(_, b)| b.is_some())
        .map(|(c, _)| c.resource)
        .collect()
}

/// The params of a data-only pass its shader does not read
/// ([`super::param_use`]). The providers' params (`shared_params`) are held
/// to their specs at compile and, as in a pass type written in Rust, may be
/// given to a pass whose chosen provider does not read them.
fn unread_params(
    t: &dyn PassType,
    pass: &ScheduledPass,
    module: &naga::Module,
    shared_params: &[&str],
    shaders: &crate::modules::Shaders,
) -> Vec<String> {
    let mut members: std::collections::BTreeSet<String> = module
        .global_variables
        .iter()
        .filter_map(|(_, v)| v.name.as_deref())
        .filter(|n| reflect::plain_name(n).ends_with("params"))
        .filter_map(|n| reflect::params_layout(module, reflect::plain_name(n)))
        .flat_map(|(_, members)| members.into_iter().map(|m| m.name))
        .collect();
    members.extend(shared_params.iter().map(|s| s.to_string()));
    let mut defines = super::param_use::library_define_names(shaders);
    if let Ok((_, source)) = shader_source(t, pass, shaders) {
        defines.extend(super::param_use::define_names(&source));
    }
    super::param_use::unread_params(pass, &members, &defines)
}
