//! State across frames in the compiled schedule: `history = N` adds
//! `NAME.previous` … `NAME.previous.N` (read-only resources the loader
//! declares), `persistent = true` keeps contents. Here: their lifetimes, the
//! copies that age a history after each frame, which younger versions a read
//! of an older one needs, and the load-time errors about them.

use std::cmp::Reverse;

use crate::error::{Error, ErrorKind, Spanned};
use crate::load::{Pipeline, ResourceDecl};
use crate::schedule::{HistoryCopy, Lifetime, ResolvedResource, ResourceDesc, ResourceId};

/// The resources a read of resource `r` (a declaration index) needs besides
/// itself: for `NAME.previous.K`, `NAME` and every younger version it is
/// copied through; nothing for other resources.
pub(crate) fn chain(pipeline: &Pipeline, r: usize) -> Vec<usize> {
    let Some(of) = &pipeline.resources[r].previous_of else {
        return Vec::new();
    };
    (0..of.frames_ago)
        .filter_map(|k| {
            let name = match k {
                0 => of.resource.clone(),
                k => crate::load::previous_name(&of.resource, k),
            };
            pipeline.resources.get_index_of(&name)
        })
        .collect()
}

/// The copies that age every history after a frame, oldest first: a
/// version is copied on before it is overwritten.
pub(crate) fn copies(resources: &[ResolvedResource]) -> Vec<HistoryCopy> {
    let mut history = Vec::new();
    for (r, resource) in resources.iter().enumerate() {
        if let Lifetime::Previous { of, frames_ago } = resource.lifetime {
            // Aged from the version one frame younger (the resource itself for 1).
            let younger = match frames_ago {
                1 => Some(of),
                k => resources
                    .iter()
                    .position(|y| {
                        y.lifetime
                            == Lifetime::Previous {
                                of,
                                frames_ago: k - 1,
                            }
                    })
                    .map(ResourceId::new),
            };
            if let Some(from) = younger {
                history.push((
                    frames_ago,
                    HistoryCopy {
                        from,
                        to: ResourceId::new(r),
                    },
                ));
            }
        }
    }
    history.sort_by_key(|(frames_ago, copy)| (Reverse(*frames_ago), copy.to));
    history.into_iter().map(|(_, c)| c).collect()
}

/// The lifetime a declaration asks for; `new_id` maps declaration indices to
/// schedule ids.
pub(crate) fn declared_lifetime(
    decl: &ResourceDecl,
    pipeline: &Pipeline,
    new_id: &[Option<ResourceId>],
) -> Lifetime {
    // A live version keeps the resource it ages (`history_chain`); one whose
    // base has no descriptor is an error compile reports, so it is a frame
    // resource here rather than an id that names nothing.
    if let Some(of) = &decl.previous_of
        && let Some(base) = pipeline
            .resources
            .get_index_of(&of.resource)
            .and_then(|i| new_id[i])
    {
        return Lifetime::Previous {
            of: base,
            frames_ago: of.frames_ago,
        };
    }
    match (&decl.history, &decl.persistent) {
        (Some(h), _) => Lifetime::History { frames: h.value },
        (None, Some(_)) => Lifetime::Persistent,
        (None, None) => Lifetime::Frame,
    }
}

/// A resource name that matches no declaration. `R.previous…` gets a message
/// about `R`'s history; anything else the nearest declared name.
pub(crate) fn undeclared(pipeline: &Pipeline, resource: &Spanned<String>) -> Error {
    let name = &resource.value;
    let kind = match crate::load::parse_previous_name(name) {
        Some((base, frames_ago)) if pipeline.resources.contains_key(base) => {
            let decl = &pipeline.resources[base];
            let reason = match &decl.history {
                None => format!(
                    "`{base}` keeps no history; add `history = {frames_ago}` to [resources.{base}] ({}) to keep {}",
                    decl.location,
                    if frames_ago == 1 {
                        "last frame's version".to_owned()
                    } else {
                        format!("the last {frames_ago} frames")
                    }
                ),
                Some(h) => format!(
                    "`{base}` keeps {} frame{} of history ({}); `{name}` needs `history = {frames_ago}`",
                    h.value,
                    if h.value == 1 { "" } else { "s" },
                    h.location
                ),
            };
            ErrorKind::NoHistory {
                name: name.clone(),
                reason,
            }
        }
        _ => ErrorKind::UndeclaredResource {
            name: name.clone(),
            hint: crate::suggest::did_you_mean(name, pipeline.resources.keys().map(String::as_str)),
        },
    };
    Error::new(resource.location.clone(), kind)
}

/// A history is kept by copying the resource after each frame; multisampled
/// textures cannot be copied.
pub(crate) fn check(pipeline: &Pipeline, descs: &[Option<ResourceDesc>], errors: &mut Vec<Error>) {
    for (decl, desc) in pipeline.resources.values().zip(descs) {
        if let (Some(h), Some(ResourceDesc::Texture { samples, .. })) = (&decl.history, desc)
            && *samples > 1
        {
            errors.push(Error::new(
                h.location.clone(),
                ErrorKind::BadResource {
                    resource: decl.name.clone(),
                    reason: format!(
                        "a multisampled texture ({samples} samples) cannot be copied, so it cannot keep a history; resolve it into a single-sampled texture and give that one `history`"
                    ),
                },
            ));
        }
    }
}
