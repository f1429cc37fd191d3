//! Writes the files the example scenes read that the repository makes
//! itself: `examples/scenes/head.glb` (the ellipsoid as a mesh, which the
//! tests hold against the built-in head), `examples/scenes/sculpted_head.glb`,
//! the head of `mesh_head.toml` (the same skull with a face, ears and a neck:
//! `plait_hair::sculpted_head`), and
//! `examples/scenes/groom.usda`, its groom (`plait_hair::usd::example_groom_usda`:
//! the procedural groom grown over the same ellipsoid, written as USD).
//!
//!     cargo run --example make_assets [-- OUT_DIR]
//!
//! The head is the built-in scene's ellipsoid (centre 0, radii 0.9, 1.05, 1.0,
//! 32 × 64 quads), so a scene can swap `[head]` for the mesh and keep its
//! groom, and the simulation's collision tests run against both. The bytes
//! depend only on the mesh: `plait_hair::mesh_file::write::example_head_glb`
//! writes them, and a test checks the committed file equals its output.

use std::path::PathBuf;

fn main() -> std::io::Result<()> {
    let dir = std::env::args_os().nth(1).map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes"),
        PathBuf::from,
    );
    std::fs::create_dir_all(&dir)?;
    let path = dir.join("head.glb");
    let bytes = plait_hair::mesh_file::write::example_head_glb();
    std::fs::write(&path, &bytes)?;
    println!("{}: {} bytes", path.display(), bytes.len());
    let path = dir.join("sculpted_head.glb");
    let bytes = plait_hair::mesh_file::write::example_sculpted_head_glb();
    std::fs::write(&path, &bytes)?;
    println!("{}: {} bytes", path.display(), bytes.len());
    let path = dir.join("groom.usda");
    let bytes = plait_hair::usd::example_groom_usda();
    std::fs::write(&path, &bytes)?;
    println!("{}: {} bytes", path.display(), bytes.len());
    Ok(())
}
