//! `occupancy_slabs` builds the occupancy bits and slab counts of
//! `occupancy.toml` in one draw per view instead of two: the maps must be the
//! same, bit for bit (integer atomics are exact in any order), so the image
//! is too. GPU test: runs on lavapipe (no adapter is a failure, never a skip).

use plait::gpu::Gpu;
use plait::session::{SceneData, prepare, repo_root};

fn one_draw_sets() -> Vec<String> {
    let mut sets = Vec::new();
    for view in ["light", "camera"] {
        sets.push(format!("passes.{view}_occupancy.type=occupancy_slabs"));
        sets.push(format!("passes.{view}_occupancy.writes.slabs={view}_slabs"));
        sets.push(format!("passes.{view}_slabs.enabled=false"));
    }
    sets
}

#[test]
fn occupancy_and_slabs_in_one_draw_give_the_same_maps_and_image() {
    let gpu = Gpu::new()
        .unwrap_or_else(|e| panic!("GPU tests need an adapter and none could be opened: {e}"));
    let root = repo_root();
    let scene = SceneData::load(Some(&root.join("examples/scenes/small.toml")))
        .unwrap_or_else(|e| panic!("{e}"));
    let pipeline = root.join("pipelines/occupancy.toml");
    let size = (64, 48);
    let two = prepare(&gpu, &pipeline, &[], &scene, size).unwrap_or_else(|e| panic!("{e}"));
    let one =
        prepare(&gpu, &pipeline, &one_draw_sets(), &scene, size).unwrap_or_else(|e| panic!("{e}"));
    let draws = |p: &plait::session::Prepared| {
        p.schedule()
            .passes
            .iter()
            .filter(|p| p.type_name == "occupancy_slabs")
            .count()
    };
    assert_eq!(draws(&two), 0);
    assert_eq!(draws(&one), 2, "one map pass per view");
    assert_eq!(
        two.schedule().passes.len(),
        one.schedule().passes.len() + 2,
        "the two slab passes are gone"
    );
    two.render().unwrap_or_else(|e| panic!("{e}"));
    one.render().unwrap_or_else(|e| panic!("{e}"));
    for map in ["light_bits", "light_slabs", "camera_bits", "camera_slabs"] {
        let a = two.read_buffer(map).unwrap_or_else(|e| panic!("{e}"));
        let b = one.read_buffer(map).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            a.iter().any(|&x| x != 0),
            "{map} is empty: the scene drew no hair"
        );
        assert!(a == b, "{map} differs between one and two draws");
    }
    let (a, b) = (
        two.image().unwrap_or_else(|e| panic!("{e}")),
        one.image().unwrap_or_else(|e| panic!("{e}")),
    );
    assert!(a == b, "the image differs between one and two draws");
}
