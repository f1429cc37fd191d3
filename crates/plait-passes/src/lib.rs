//! plait's pass library: one Rust module and one WGSL file per pass type.
//!
//! [`library`] registers every pass type; [`compile`] compiles a pipeline
//! with every pass checked against its shader with naga (no GPU), which
//! `plait check` and `plait render` both run before any GPU work.

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

use plait_gpu::Capabilities;
use plait_gpu::pass::PassLibrary;
use plait_gpu::pass::check::ShaderChecker;
use plait_graph::{CompileOptions, Errors, Pipeline, Schedule};

/// Every pass type plait ships.
pub fn library() -> PassLibrary {
    let mut lib = PassLibrary {
        // The providers' params mean the same in a data-only pass that
        // imports plait::hair_fragment as in the Rust pass types.
        shared_params: hair_fragment::shading_params(),
        ..PassLibrary::default()
    };
    // Single-draw passes declared in TOML + WGSL (shaders/passes/*.toml),
    // found on the search path; a broken file is reported by compile.
    let (types, problems) = data_pass::discover();
    for t in types {
        lib.add(t);
    }
    lib.problems = problems;
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

/// Compile `pipeline` with every pass (live and culled) checked against its
/// shader with naga and its formats fitted to the adapter `opts` describes:
/// the final schedule (`plait check` and every render run this, before any
/// GPU work).
pub fn compile(pipeline: &Pipeline, opts: &CompileOptions) -> Result<Schedule, Errors> {
    compile_in(&library(), pipeline, opts)
}

/// [`compile`] with the pass types of `library`.
pub fn compile_in(
    library: &PassLibrary,
    pipeline: &Pipeline,
    opts: &CompileOptions,
) -> Result<Schedule, Errors> {
    let checker = ShaderChecker::new(library, Capabilities::of_compile(opts));
    // A broken pass-type file or shader library first: the params' choices
    // (the providers found) and the pass types come from them, so what
    // follows from a broken one would only be noise.
    let mut broken = library.problems.clone();
    broken.extend(plait_graph::compile::fit::PassChecker::check_library(
        &checker,
    ));
    if !broken.is_empty() {
        return Err(Errors(broken));
    }
    plait_graph::compile_with(pipeline, &library.registry(), opts, &checker)
}
