//! The probe reads no library of its own (issue 41 item 1): `plait ab`
//! probes every variant with the one library its run rendered them with.

use std::path::{Path, PathBuf};

use plait::probe::{ProbeGrid, probe_visibility};
use plait::session::SceneData;
use plait::source::PipelineSource;
use plait_gpu::Gpu;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("checkout")
}

/// The library-read counter is per process, and this file's one test is the
/// only thing in its process that reads a library after the source is made.
#[test]
fn a_probe_compiles_and_builds_with_the_library_it_is_given() {
    let root = root();
    let scene = SceneData::load(Some(&root.join("examples/scenes/small.toml"))).expect("scene");
    let gpu = Gpu::new().expect("an adapter");
    let source = PipelineSource::new(&root.join("pipelines/occupancy.toml"), &[]);
    let grid = ProbeGrid::through_hair(&scene, (4, 4), 8);

    let reads = plait_passes::library_reads();
    let probed = probe_visibility(&gpu, &source, &scene, (32, 24), &grid)
        .expect("probes")
        .expect("occupancy has a visibility provider");
    assert_eq!(
        plait_passes::library_reads(),
        reads,
        "the probe read a library of its own"
    );
    assert_eq!(probed.visibility, "occupancy");
    assert_eq!(probed.values.len(), grid.ray_count() * grid.depths as usize);
}
