//! Each Rust pass type's constant slot handles ([`plait_graph::SlotId`])
//! checked against the names its spec gives those slots: compile binds by
//! name once and build compares handles, so a handle written for the wrong
//! slot would read another resource without a word. Swapping two handles
//! fails here.

use plait_graph::SlotId;

use crate::spec_util::assert_handles;
use crate::{
    density_clustering, depth_peeling, depth_range, occlusion_cylinders, occlusion_directions,
    simulation,
};

#[test]
fn every_handle_names_its_slot() {
    let cases: [(plait_graph::PassTypeSpec, &[(SlotId, &str)]); 6] = [
        (simulation::spec(), &[(simulation::STATUS, "status")]),
        (
            depth_range::spec(),
            &[
                (depth_range::OPAQUE_DEPTH, "opaque_depth"),
                (depth_range::RANGE, "range"),
            ],
        ),
        (
            density_clustering::spec(),
            &[(density_clustering::CLUSTERS_SLOT, "clusters")],
        ),
        (
            occlusion_directions::spec(),
            &[
                (occlusion_directions::VERTEX_AO, "vertex_ao"),
                (occlusion_directions::DIRECTION_FRAMES, "direction_frames"),
                (occlusion_directions::RANGE, "range"),
                (occlusion_directions::LAYERS, "layers"),
                (occlusion_directions::SCRATCH, "scratch"),
                (occlusion_directions::NO_OPAQUE, "no_opaque"),
            ],
        ),
        (
            occlusion_cylinders::spec(),
            &[
                (occlusion_cylinders::VERTEX_AO, "vertex_ao"),
                (occlusion_cylinders::HAIR_BOX, "hair_box"),
                (occlusion_cylinders::AO_STATUS, "ao_status"),
            ],
        ),
        (
            depth_peeling::spec(&[], &[]),
            &[
                (depth_peeling::COLOR, "color"),
                (depth_peeling::LAYER, "layer"),
                (depth_peeling::PEEL_DEPTH, "peel_depth"),
                (depth_peeling::PEEL_PREV, "peel_prev"),
            ],
        ),
    ];
    for (spec, handles) in &cases {
        assert_handles(spec, handles);
    }
}
