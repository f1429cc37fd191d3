//! plait's pass library: one Rust module and one WGSL file per pass type.
//!
//! [`library`] registers every pass type; [`check`] validates a compiled
//! schedule against its shaders with naga (no GPU), which `plait check` and
//! `plait render` both run before any GPU work.

pub mod data_only;
pub mod data_pass;
pub mod density_clustering;
pub mod depth_peeling;
pub mod depth_range;
pub mod hair_fragment;
pub mod hair_shade;
pub mod interpolation;
pub mod lighting;
pub mod occlusion;
pub mod occlusion_cylinders;
pub mod occlusion_directions;
pub mod occupancy;
pub mod opaque_shade;
pub mod shading;
pub mod simulation;
pub mod spec_util;
pub mod visibility;

use plait_gpu::pass::{PassLibrary, check_pass};
use plait_graph::{Errors, Schedule};

/// Every pass type plait ships.
pub fn library() -> PassLibrary {
    let mut lib = PassLibrary {
        // The providers' params mean the same in a data-only pass that
        // imports plait::hair_fragment as in the Rust pass types.
        shared_params: hair_fragment::shading_params(),
        ..PassLibrary::default()
    };
    // Single-draw passes declared in TOML + WGSL (shaders/passes/*.toml).
    for t in data_pass::builtin_types() {
        lib.add(t);
    }
    lib.add(depth_range::DepthRange);
    lib.add(density_clustering::DensityClustering);
    lib.add(opaque_shade::OpaqueShade);
    // Ambient occlusion precomputes (issue 11).
    lib.add(occlusion_directions::OcclusionDirections);
    lib.add(occlusion_cylinders::OcclusionCylinders);
    lib.add(hair_shade::HairShade);
    // Transparency methods (issue 5): each shades with hair_shade.wgsl.
    lib.add(depth_peeling::HairDepthPeel);
    // Simulation (issue 12): guides simulated, drawn strands interpolated.
    lib.add(simulation::HairSimulation);
    lib.add(interpolation::GuideInterpolation);
    lib.add(data_only::FULLSCREEN);
    lib.add(data_only::RASTER);
    lib.add(data_only::COMPUTE);
    lib
}

/// Check every pass (live and culled) against its shader with naga, and
/// settle how the slots of data-only passes are accessed.
pub fn check(schedule: &mut Schedule, library: &PassLibrary) -> Result<(), Errors> {
    // A broken library module (a provider breaking its contract) is one
    // error, not one per pass importing it.
    if let Err(e) = plait_gpu::modules::check_library() {
        return Err(Errors(vec![plait_graph::Error::new(
            plait_graph::Location::Path {
                path: e.path.clone(),
            },
            plait_graph::ErrorKind::Shader {
                path: e.path,
                message: e.message,
            },
        )]));
    }
    let mut errors = Vec::new();
    let resources = schedule.resources.clone();
    let passes = schedule
        .passes
        .iter_mut()
        .chain(schedule.culled.iter_mut().map(|c| &mut c.pass));
    for pass in passes {
        if let Some(t) = library.get(&pass.type_name) {
            errors.extend(check_pass(t, pass, &resources));
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(Errors(errors))
    }
}
