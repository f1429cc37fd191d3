//! The memory plan: which resources share one physical allocation because
//! their spans of use never overlap, and the peak bytes that leaves.

use crate::schedule::{MemoryReport, PhysicalId, PhysicalResource, ResolvedResource, ResourceId};

/// Greedy sharing: in order of first use, each resource takes the first
/// physical allocation with an identical descriptor whose users all ended
/// strictly before it starts (wgpu cannot alias different shapes).
pub(super) fn plan_memory(
    resources: &mut [ResolvedResource],
) -> (Vec<PhysicalResource>, MemoryReport) {
    let mut by_start: Vec<ResourceId> = (0..resources.len()).map(ResourceId::new).collect();
    by_start.sort_by_key(|&r| (resources[r].first_use, r));
    let mut physical: Vec<PhysicalResource> = Vec::new();
    for r in by_start {
        let (desc, first_use) = (resources[r].desc.clone(), resources[r].first_use);
        // The scene's buffers are its own: never shared; nor an acceleration
        // structure, which its pass builds once for the hair it holds.
        let own = matches!(desc, crate::schedule::ResourceDesc::AccelerationStructure);
        let reusable = physical.iter().position(|p| {
            !resources[r].scene
                && !own
                && p.desc == desc
                && p.users
                    .iter()
                    .all(|&u| !resources[u].scene && resources[u].last_use < first_use)
        });
        let id = match reusable {
            Some(id) => PhysicalId::new(id),
            None => {
                physical.push(PhysicalResource {
                    desc,
                    users: Vec::new(),
                });
                PhysicalId::new(physical.len() - 1)
            }
        };
        physical[id].users.push(r);
        resources[r].physical = id;
    }
    let memory = MemoryReport {
        peak_bytes: physical.iter().map(|p| p.desc.bytes()).sum(),
        unpooled_bytes: resources.iter().map(|r| r.desc.bytes()).sum(),
    };
    (physical, memory)
}
