//! Which depth textures a shader reads as values (`textureLoad`, or a
//! `textureSample*` without a comparison): what wgpu's GL backend cannot
//! compile, since naga's GLSL output declares every single-sampled depth
//! texture a `sampler2DShadow` (see `AdapterSupport::depth_values_readable`).

use naga::{Expression, Function, Handle, ImageClass, Module, Statement, TypeInner};

/// The global variables (the bindings) a module reads as depth values, also
/// through function arguments, in module order.
pub fn depth_value_reads(module: &Module) -> Vec<Handle<naga::GlobalVariable>> {
    let mut globals = Vec::new();
    // (function, argument index) pairs read as depth values, resolved to
    // the globals their callers pass below.
    let mut arguments = Vec::new();
    for (handle, function) in functions(module) {
        for (_, e) in function.expressions.iter() {
            let image = match *e {
                Expression::ImageSample {
                    image,
                    depth_ref: None,
                    ..
                } => image,
                Expression::ImageLoad { image, .. } => image,
                _ => continue,
            };
            match function.expressions[image] {
                Expression::GlobalVariable(g)
                    if is_depth(module, module.global_variables[g].ty) =>
                {
                    globals.push(g)
                }
                Expression::FunctionArgument(i)
                    if is_depth(module, function.arguments[i as usize].ty) =>
                {
                    if let Some(h) = handle {
                        arguments.push((h, i as usize));
                    }
                }
                _ => {}
            }
        }
    }
    // Follow arguments to their callers, a few levels up (a depth texture
    // passed through helper functions).
    for _ in 0..4 {
        let mut next = Vec::new();
        for (_, caller) in functions(module) {
            let mut calls = Vec::new();
            collect_calls(&caller.body, &mut calls);
            for (callee, args) in calls {
                for &(_, i) in arguments.iter().filter(|(f, _)| *f == callee) {
                    let Some(&arg) = args.get(i) else { continue };
                    match caller.expressions[arg] {
                        Expression::GlobalVariable(g) => globals.push(g),
                        Expression::FunctionArgument(j) => {
                            if let Some(h) = handle_of(module, caller) {
                                next.push((h, j as usize));
                            }
                        }
                        _ => {}
                    }
                }
            }
        }
        if next.is_empty() {
            break;
        }
        arguments = next;
    }
    globals.sort_by_key(|g| g.index());
    globals.dedup();
    globals
}

fn functions(module: &Module) -> impl Iterator<Item = (Option<Handle<Function>>, &Function)> {
    module
        .functions
        .iter()
        .map(|(h, f)| (Some(h), f))
        .chain(module.entry_points.iter().map(|e| (None, &e.function)))
}

fn handle_of(module: &Module, function: &Function) -> Option<Handle<Function>> {
    module
        .functions
        .iter()
        .find(|(_, f)| std::ptr::eq(*f, function))
        .map(|(h, _)| h)
}

fn is_depth(module: &Module, ty: Handle<naga::Type>) -> bool {
    matches!(
        module.types[ty].inner,
        TypeInner::Image {
            class: ImageClass::Depth { multi: false },
            ..
        }
    )
}

/// Every call in a block, nested blocks included.
fn collect_calls(block: &naga::Block, out: &mut Vec<(Handle<Function>, Vec<Handle<Expression>>)>) {
    for statement in block.iter() {
        match statement {
            Statement::Call {
                function,
                arguments,
                ..
            } => out.push((*function, arguments.clone())),
            Statement::Block(b) => collect_calls(b, out),
            Statement::If { accept, reject, .. } => {
                collect_calls(accept, out);
                collect_calls(reject, out);
            }
            Statement::Switch { cases, .. } => {
                for case in cases {
                    collect_calls(&case.body, out);
                }
            }
            Statement::Loop {
                body, continuing, ..
            } => {
                collect_calls(body, out);
                collect_calls(continuing, out);
            }
            _ => {}
        }
    }
}
