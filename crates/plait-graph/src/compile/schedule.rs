//! Turning checked, ordered passes into the [`Schedule`]: culling the passes
//! no output depends on, renumbering the resources live passes touch, deciding
//! which writes clear and which load, and each resource's span of use.

use std::collections::HashSet;

use crate::error::{Error, Location};
use crate::load::Pipeline;
use crate::scene_resources::SCENE_RESOURCES;
use crate::schedule::*;

use super::fit::{Capabilities, PassChecker, check_passes, fit_formats};
use super::memory::plan_memory;
use super::order::implicit_reads;

pub(super) fn build_schedule(
    pipeline: &Pipeline,
    mut passes: Vec<ScheduledPass>,
    order: Vec<usize>,
    outputs: &[usize],
    descs: Vec<Option<ResourceDesc>>,
    checker: &dyn PassChecker,
    caps: &Capabilities,
) -> Result<Schedule, Vec<Error>> {
    let live = live_passes(pipeline, &passes, &order, outputs);
    let Renumbered {
        new_id,
        mut resources,
        dropped_resources,
    } = renumber_resources(pipeline, &mut passes, &live, &descs);
    let history = crate::history::copies(&resources);
    let (mut scheduled, mut culled) = split_culled(passes, &order, &live);
    let clear_errors = settle_clears(&mut scheduled, &resources);
    let output_ids: Vec<ResourceId> = outputs.iter().filter_map(|&o| new_id[o]).collect();
    set_spans(&scheduled, &mut resources, &output_ids);

    // The shaders and the adapter, before the memory plan: what they settle
    // is final (see `fit`).
    let (errors, blended) = check_passes(
        checker,
        scheduled
            .iter_mut()
            .chain(culled.iter_mut().map(|c: &mut CulledPass| &mut c.pass)),
        &resources,
    );
    let errors: Vec<Error> = clear_errors.into_iter().chain(errors).collect();
    if !errors.is_empty() {
        return Err(errors);
    }
    let mut notes = pipeline.notes.clone();
    notes.extend(fit_formats(&mut resources, &blended, &history, caps));

    let (physical, memory) = plan_memory(&mut resources);
    Ok(Schedule {
        name: pipeline.name.value.clone(),
        description: pipeline.description.value.clone(),
        files: pipeline.files.clone(),
        techniques: pipeline.techniques.clone(),
        params: pipeline
            .params
            .iter()
            .map(|(k, v)| (k.clone(), v.value.clone()))
            .collect(),
        passes: scheduled,
        culled,
        resources,
        dropped_resources,
        physical,
        outputs: output_ids,
        history,
        memory,
        overflow: Vec::new(),
        notes,
    })
}

/// The versions a read of resource `r` also needs through its history, if
/// it is a declared resource (scene resources have no history).
fn history_chain(pipeline: &Pipeline, r: usize) -> Vec<usize> {
    if r < pipeline.resources.len() {
        crate::history::chain(pipeline, r)
    } else {
        Vec::new()
    }
}

/// Marks the live passes, indexed like `passes`: writers of outputs and
/// everything they depend on.
fn live_passes(
    pipeline: &Pipeline,
    passes: &[ScheduledPass],
    order: &[usize],
    outputs: &[usize],
) -> Vec<bool> {
    // Walking the execution order backwards sees every consumer before its
    // producers.
    let declared = pipeline.resources.len();
    let mut needed: HashSet<usize> = outputs.iter().copied().collect();
    let mut live = vec![false; passes.len()];
    // A history makes a read of `R.previous` need `R` (and the younger
    // versions it is copied through), whose writers may come later in the
    // order: walk again until nothing new is needed.
    loop {
        let before = needed.len();
        for &p in order.iter().rev() {
            if !live[p]
                && passes[p]
                    .writes
                    .iter()
                    .any(|b| needed.contains(&b.id().index()))
            {
                live[p] = true;
                needed.extend(passes[p].reads.iter().map(|b| b.id().index()));
                needed.extend(implicit_reads(&passes[p], declared));
                // A load-writer keeps earlier contents: their writers are needed too.
                needed.extend(
                    passes[p]
                        .writes
                        .iter()
                        .filter(|b| b.loads)
                        .map(|b| b.id().index()),
                );
            }
        }
        let chained: Vec<usize> = needed
            .iter()
            .flat_map(|&r| history_chain(pipeline, r))
            .collect();
        needed.extend(chained);
        if needed.len() == before {
            break;
        }
    }
    live
}

/// The resources that survive renumbering.
struct Renumbered {
    /// Old index (declared, then scene) to new id, or `None` when dropped.
    new_id: Vec<Option<ResourceId>>,
    resources: Vec<ResolvedResource>,
    dropped_resources: Vec<String>,
}

/// Keeps the resources a live pass touches, in declaration order, then the
/// scene resources named, and renumbers every pass's bindings to match.
fn renumber_resources(
    pipeline: &Pipeline,
    passes: &mut [ScheduledPass],
    live: &[bool],
    descs: &[Option<ResourceDesc>],
) -> Renumbered {
    let declared = pipeline.resources.len();
    let total = declared + SCENE_RESOURCES.len();
    let mut used = vec![false; total];
    for (p, pass) in passes.iter().enumerate() {
        if live[p] {
            for b in pass.reads.iter().chain(&pass.writes) {
                used[b.id().index()] = true;
                for r in history_chain(pipeline, b.id().index()) {
                    used[r] = true;
                }
            }
        }
    }
    let mut new_id: Vec<Option<ResourceId>> = vec![None; total];
    let mut resources = Vec::new();
    let mut dropped_resources = Vec::new();
    for (i, decl) in pipeline.resources.values().enumerate() {
        match (&descs[i], used[i]) {
            (Some(desc), true) => {
                new_id[i] = Some(ResourceId::new(resources.len()));
                resources.push(ResolvedResource {
                    name: decl.name.clone(),
                    desc: desc.clone(),
                    first_use: usize::MAX,
                    last_use: 0,
                    physical: PhysicalId::new(0),
                    scene: false,
                    // A history's versions come after it in declaration
                    // order, so `of` is already renumbered.
                    lifetime: crate::history::declared_lifetime(decl, pipeline, &new_id),
                    kept: false,
                    clear: decl.clear.as_ref().map(|c| c.value),
                    location: decl.location.clone(),
                });
            }
            _ => dropped_resources.push(decl.name.clone()),
        }
    }
    // Scene resources a live pass names: after the declared ones, never dropped.
    for (i, scene) in SCENE_RESOURCES.iter().enumerate() {
        if used[declared + i] {
            new_id[declared + i] = Some(ResourceId::new(resources.len()));
            resources.push(ResolvedResource {
                name: scene.name.to_owned(),
                desc: ResourceDesc::Buffer { size: 0 },
                first_use: usize::MAX,
                last_use: 0,
                physical: PhysicalId::new(0),
                scene: true,
                // The scene's buffers outlive every frame, like `persistent`.
                lifetime: Lifetime::Persistent,
                kept: false,
                clear: None,
                location: Location::Builtin,
            });
        }
    }
    for pass in passes.iter_mut() {
        for b in pass.reads.iter_mut().chain(pass.writes.iter_mut()) {
            b.resource = new_id[b.id().index()];
        }
    }
    Renumbered {
        new_id,
        resources,
        dropped_resources,
    }
}

/// Splits the passes into the live ones, in execution order, and the culled
/// ones with why.
fn split_culled(
    passes: Vec<ScheduledPass>,
    order: &[usize],
    live: &[bool],
) -> (Vec<ScheduledPass>, Vec<CulledPass>) {
    let mut slots: Vec<Option<ScheduledPass>> = passes.into_iter().map(Some).collect();
    let mut scheduled = Vec::new();
    let mut culled = Vec::new();
    for &p in order {
        let Some(pass) = slots[p].take() else {
            continue;
        };
        if live[p] {
            scheduled.push(pass);
        } else {
            let reason = cull_reason(&pass);
            culled.push((p, CulledPass { pass, reason }));
        }
    }
    // Culled passes in file order: they have no execution order to follow.
    culled.sort_by_key(|(p, _)| *p);
    let culled = culled.into_iter().map(|(_, c)| c).collect();
    (scheduled, culled)
}

/// Decides which writes clear and which load; reports a `loads` entry that
/// would keep what no earlier pass wrote and no `clear` declares.
fn settle_clears(scheduled: &mut [ScheduledPass], resources: &[ResolvedResource]) -> Vec<Error> {
    // The first writer of a resource has nothing to load: it clears (to the
    // resource's `clear`, else zeros). A persistent resource is never
    // cleared by the engine: every writer loads.
    let mut errors = Vec::new();
    let mut written = vec![false; resources.len()];
    for pass in scheduled.iter_mut() {
        for b in &mut pass.writes {
            let r = &resources[b.id()];
            if r.lifetime == Lifetime::Persistent {
                b.loads = true;
            } else if !written[b.id().index()] {
                let also_read = pass.reads.iter().any(|x| x.resource == b.resource);
                // A pass-type slot that accumulates means "clear, then
                // accumulate"; a `loads` entry in the file asks for what
                // is there, which must have been written or declared.
                let entry = pass.raster.loads.iter().find(|l| l.value == b.slot);
                if let Some(entry) = entry.filter(|_| !also_read && r.clear.is_none()) {
                    errors.push(crate::clear::load_before_write(
                        &pass.name,
                        &b.slot,
                        &r.name,
                        &entry.location,
                    ));
                }
                if also_read && r.clear.is_some() {
                    errors.push(crate::clear::cleared_but_read(
                        &pass.name,
                        &r.name,
                        &b.location,
                    ));
                }
                if !also_read {
                    b.loads = false;
                }
            }
        }
        for b in &pass.writes {
            written[b.id().index()] = true;
        }
    }
    errors
}

/// Sets each resource's span of use over the scheduled passes: outputs and
/// contents that outlive the frame last to its end.
fn set_spans(
    scheduled: &[ScheduledPass],
    resources: &mut [ResolvedResource],
    output_ids: &[ResourceId],
) {
    for (index, pass) in scheduled.iter().enumerate() {
        for b in pass.reads.iter().chain(&pass.writes) {
            let r = &mut resources[b.id()];
            r.first_use = r.first_use.min(index);
            r.last_use = r.last_use.max(index);
        }
    }
    let end = scheduled.len().saturating_sub(1);
    for &o in output_ids {
        resources[o].last_use = end;
    }
    // Contents that outlive the frame span all of it, so the memory plan
    // never lends their allocation to another resource.
    for r in resources.iter_mut().filter(|r| !r.lifetime.is_frame()) {
        r.first_use = 0;
        r.last_use = end;
    }
    crate::run_once::keep_across_frames(scheduled, resources);
}

fn cull_reason(pass: &ScheduledPass) -> String {
    if pass.writes.is_empty() {
        return "writes nothing".to_owned();
    }
    let mut names: Vec<String> = pass
        .writes
        .iter()
        .map(|b| format!("`{}`", b.resource_name))
        .collect();
    names.dedup();
    let which = if names.len() == 1 {
        "which"
    } else {
        "which none of"
    };
    format!(
        "writes only {}, {which} no output depends on",
        names.join(", ")
    )
}
