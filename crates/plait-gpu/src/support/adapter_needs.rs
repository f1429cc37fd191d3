//! What chosen techniques say they need of the adapter (`[technique]
//! adapter`), against its capabilities: a technique that traces rays is
//! refused on an adapter without ray queries before any GPU work, at the
//! line of its file that asks, with how to get a driver that has them.

use plait_graph::techniques::technique_keys::RAY_QUERY;
use plait_graph::{ResourceDesc, Schedule};

use super::Problem;
use crate::Capabilities;

/// How to get ray queries on a machine without a GPU: Mesa ≥ 25's lavapipe
/// exposes `VK_KHR_ray_query` (Debian 12's own Mesa 22.3 does not).
pub const RAY_QUERY_FIX: &str = "`bash scripts/ensure-vulkan.sh` installs Mesa ≥ 25's software Vulkan driver (lavapipe), which has them";

/// One problem per need of a chosen technique the adapter lacks.
pub(super) fn technique_problems(schedule: &Schedule, caps: &Capabilities, out: &mut Vec<Problem>) {
    for t in &schedule.techniques {
        for need in &t.adapter {
            let missing = match need.value.as_str() {
                RAY_QUERY if !caps.ray_query => format!(
                    "the adapter lacks ray queries (wgpu's EXPERIMENTAL_RAY_QUERY, Vulkan's VK_KHR_ray_query); {RAY_QUERY_FIX}"
                ),
                _ => continue,
            };
            out.push(Problem {
                location: need.location.clone(),
                pass: None,
                technique: Some(t.label()),
                resource: None,
                what: format!(
                    "technique {} traces rays (`adapter = [\"{}\"]`)",
                    t.label(),
                    need.value
                ),
                missing,
            });
        }
    }
}

/// A pipeline's own passes that trace rays (an `acceleration_structure`
/// resource declared outside any technique, as `pipelines/physical/path_traced.toml`
/// does): refused at the resource's declaration on an adapter without ray
/// queries, unless a technique's own need already said so.
pub(super) fn structure_problems(schedule: &Schedule, caps: &Capabilities, out: &mut Vec<Problem>) {
    if caps.ray_query || out.iter().any(|p| p.missing.contains("ray queries")) {
        return;
    }
    let structure = schedule
        .resources
        .iter()
        .find(|r| matches!(r.desc, ResourceDesc::AccelerationStructure));
    if let Some(r) = structure {
        out.push(Problem {
            location: r.location.clone(),
            pass: None,
            technique: None,
            resource: Some(r.name.clone()),
            what: format!(
                "`{}` is an acceleration structure the pipeline traces rays through",
                r.name
            ),
            missing: format!(
                "the adapter lacks ray queries (wgpu's EXPERIMENTAL_RAY_QUERY, Vulkan's VK_KHR_ray_query); {RAY_QUERY_FIX}"
            ),
        });
    }
}
