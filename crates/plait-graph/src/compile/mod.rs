//! Checking a loaded [`Pipeline`] against the pass [`Registry`] and compiling
//! it into a [`Schedule`]: execution order, culling, lifetimes, memory plan.
//!
//! Compile reports as many problems as it can find in one go (sorted by
//! location) rather than stopping at the first, so one edit-run cycle fixes
//! several mistakes.
//!
//! The steps, one module each: `resources` sizes the declared resources,
//! `passes` checks each pass's type, params and slot bindings, `outputs`
//! checks what the pipeline promises to produce, `order` builds the
//! dependency graph and the execution order, `schedule` culls, renumbers and
//! sets lifetimes, and `memory` shares allocations between resources.

mod bind;
pub mod fit;
mod memory;
mod order;
mod outputs;
mod passes;
mod resources;
mod schedule;
mod values;

use crate::error::{Error, ErrorKind, Errors, Location};
use crate::load::{Pipeline, location_order};
use crate::scene_resources::{SCENE_RESOURCES, scene_resource};
use crate::schedule::*;
use crate::spec::Registry;

use order::order_passes;
use outputs::check_outputs;
use passes::resolve_pass;
use resources::resolve_resource;
use schedule::build_schedule;

/// Checks `pipeline` and builds its schedule, or returns every problem
/// found: what the pipeline files say, not what its shaders do (for that,
/// [`compile_with`] and a shader checker).
pub fn compile(
    pipeline: &Pipeline,
    registry: &Registry,
    opts: &CompileOptions,
) -> Result<Schedule, Errors> {
    compile_with(pipeline, registry, opts, &fit::NoShaders)
}

/// [`compile`], every pass also checked by `checker` against its shader
/// (accesses settled from it) and the formats fitted to
/// `opts.capabilities`: the schedule returned is final.
pub fn compile_with(
    pipeline: &Pipeline,
    registry: &Registry,
    opts: &CompileOptions,
    checker: &dyn fit::PassChecker,
) -> Result<Schedule, Errors> {
    crate::counters::COMPILES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let mut errors = Vec::new();

    // Resource descriptors, indexed like `pipeline.resources`.
    let mut descs: Vec<Option<ResourceDesc>> = pipeline
        .resources
        .values()
        .map(|r| resolve_resource(r, opts, &mut errors))
        .collect();
    crate::history::check(pipeline, &descs, &mut errors);
    for r in pipeline.resources.values() {
        if scene_resource(&r.name).is_some() {
            errors.push(Error::new(
                r.location.clone(),
                ErrorKind::BadResource {
                    resource: r.name.clone(),
                    reason: "is a scene resource, provided by the scene (sized by its hair); name it in `reads` or `writes` without declaring it".into(),
                },
            ));
        }
    }
    // Scene resources follow the declared ones; their size is the scene's,
    // unknown here (0: they take no memory of the pipeline's).
    descs.extend(
        SCENE_RESOURCES
            .iter()
            .map(|_| Some(ResourceDesc::Buffer { size: 0 })),
    );

    let passes: Vec<ScheduledPass> = pipeline
        .passes
        .values()
        .map(|p| resolve_pass(p, registry, pipeline, &descs, opts, &mut errors))
        .collect();

    let outputs = check_outputs(pipeline, &passes, &mut errors);
    crate::run_once::check_writers(pipeline, &passes, &mut errors);
    let order = order_passes(&passes, pipeline, &mut errors);
    crate::overflow::check(pipeline, opts, &mut errors);

    let Some(order) = order.filter(|_| errors.is_empty()) else {
        let mut errors = merge_flag_param_errors(errors);
        errors.sort_by(|a, b| location_order(&a.location, &b.location));
        return Err(Errors(errors));
    };
    let mut schedule = build_schedule(
        pipeline,
        passes,
        order,
        &outputs,
        descs,
        checker,
        &opts.capabilities,
    )
    .map_err(|mut errors| {
        errors.sort_by(|a, b| location_order(&a.location, &b.location));
        Errors(errors)
    })?;
    schedule.overflow = crate::overflow::counters(pipeline, &schedule.resources, opts);
    Ok(schedule)
}

/// An integer value or expression over the render size, as resource sizes
/// are evaluated.
pub(crate) fn int_of(v: &crate::value::Value, opts: &CompileOptions) -> Result<i64, String> {
    values::int_value(v, opts)
}

/// One error per `--set` flag, param and reason: a flag whose value every
/// pass taking the param refuses (`params.lod_screen_fraction=1.5` reaches
/// every hair draw) is one mistake, named once with the passes it reached.
fn merge_flag_param_errors(errors: Vec<Error>) -> Vec<Error> {
    let mut out: Vec<Error> = Vec::new();
    for e in errors {
        let (
            Location::Flag { .. },
            ErrorKind::BadParam {
                pass,
                param,
                reason,
            },
        ) = (&e.location, &e.kind)
        else {
            out.push(e);
            continue;
        };
        let same = out.iter_mut().find(|o| {
            o.location == e.location
                && matches!(&o.kind,
                    ErrorKind::BadParam { param: p, reason: r, .. }
                    | ErrorKind::BadParamOfPasses { param: p, reason: r, .. }
                    if p == param && r == reason)
        });
        match same {
            Some(o) => {
                o.kind = match std::mem::replace(&mut o.kind, ErrorKind::Io(String::new())) {
                    ErrorKind::BadParam {
                        pass: first,
                        param,
                        reason,
                    } => ErrorKind::BadParamOfPasses {
                        passes: vec![first, pass.clone()],
                        param,
                        reason,
                    },
                    ErrorKind::BadParamOfPasses {
                        mut passes,
                        param,
                        reason,
                    } => {
                        passes.push(pass.clone());
                        ErrorKind::BadParamOfPasses {
                            passes,
                            param,
                            reason,
                        }
                    }
                    other => other,
                };
            }
            None => out.push(e),
        }
    }
    out
}
