//! plait's pass library: pass types declared in TOML (`shaders/passes/`,
//! found on the search path) and the few written in Rust, each one module
//! that registers itself.
//!
//! [`library`] collects every pass type; [`compile`] compiles a pipeline
//! with every pass checked against its shader with naga (no GPU), which
//! `plait check` and `plait render` both run before any GPU work.

pub mod compute_raster;
pub mod data_only;
pub mod data_pass;
pub mod density_clustering;
pub mod depth_peeling;
pub mod depth_range;
pub mod display;
pub mod geometry;
pub mod hair_fragment;
pub mod hair_shade;
pub mod interpolation;
pub mod lighting;
pub mod multiple_scattering;
pub mod occlusion;
pub mod occlusion_cylinders;
pub mod occlusion_directions;
pub mod occupancy;
pub mod opaque_shade;
pub mod path_trace;
pub mod points;
pub mod shading;
pub mod shading_space;
pub mod simulation;
#[cfg(test)]
mod slot_handles;
pub mod spec_util;
pub mod strand_structure;
pub mod visibility;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use plait_gpu::Capabilities;
use plait_gpu::modules::Shaders;
use plait_gpu::pass::check::ShaderChecker;
use plait_gpu::pass::{PassLibrary, PassType};
use plait_graph::{CompileOptions, Errors, Pipeline, Schedule};

/// A pass type written in Rust, registered by its own module:
/// `inventory::submit! { crate::RustPassType(|_| Box::new(MyPass)) }`. It is
/// made for each library read, from the library so far (the shader library
/// and the pass types declared in TOML): a type whose params are a point's
/// takes the providers found there.
pub struct RustPassType(pub fn(&PassLibrary) -> Box<dyn PassType>);

inventory::collect!(RustPassType);

/// The library for a session rendering the pipelines at `pipelines`: the
/// search path read now, with each pipeline's own `techniques/` before it
/// ([`read_library`]). One value per session; nothing keeps it.
pub fn library_for(pipelines: &[&Path]) -> Arc<PassLibrary> {
    let mut own: Vec<PathBuf> = Vec::new();
    for root in pipelines
        .iter()
        .filter_map(|p| plait_graph::techniques::own_root(p))
    {
        if !own.contains(&root) {
            own.push(root);
        }
    }
    Arc::new(read_library(&own))
}

/// How many times this process read a pass library ([`read_library`]): a
/// render reads one.
pub fn library_reads() -> usize {
    LIBRARY_READS.load(std::sync::atomic::Ordering::Relaxed)
}

static LIBRARY_READS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Every pass type plait ships and those on the search path, and the shader
/// library, read from the search path as it is now with the `techniques/`
/// of `own_roots` (loaded pipelines' own folders) before it. A broken file
/// is kept as its error, which every compile with the library reports.
pub fn read_library(own_roots: &[PathBuf]) -> PassLibrary {
    LIBRARY_READS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let mut lib = PassLibrary {
        shaders: Arc::new(Shaders::read(own_roots)),
        // A provider's loop bounded by a texture size, wherever it is chosen.
        shared_checks: vec![lighting::check_environment_size],
        ..PassLibrary::default()
    };
    // Single-draw passes declared in TOML + WGSL (shaders/passes/*.toml),
    // found on the search path; a broken file is reported by compile.
    let (types, problems) = data_pass::discover();
    for t in types {
        lib.add(t);
    }
    lib.problems = problems;
    // The providers' params mean the same in a data-only pass that imports
    // plait::hair_fragment as in the Rust pass types; the geometry
    // provider's in every pass that draws hair. Their choices are the
    // providers this library found.
    lib.shared_params = [
        hair_fragment::shading_params(&lib),
        geometry::params(&lib),
        display::params(),
    ]
    .concat();
    // Every hair draw scales its coverage by the shading_space provider's
    // tip fading (plait::strand_coverage), so its buffers reach the
    // unshaded draws (alpha_sum) too.
    lib.shared_slots = [geometry::slots(&lib), shading_space::slots(&lib)].concat();
    // Pass types written in Rust (loops, readback, state chosen by a param):
    // each module registers its own with `inventory::submit!`, so a new one
    // is its module and no line here. Sorted by name: the registration order
    // is the linker's.
    let mut rust: Vec<Box<dyn PassType>> = inventory::iter::<RustPassType>
        .into_iter()
        .map(|r| (r.0)(&lib))
        .collect();
    rust.sort_by_key(|t| t.spec().name);
    for t in rust {
        lib.insert(t);
    }
    lib
}

/// Compile `pipeline` with the pass types and shaders of `library`, every
/// pass (live and culled) checked against its shader with naga and its
/// formats fitted to the adapter `opts` describes: the final schedule
/// (`plait check` and every render run this, before any GPU work).
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

#[cfg(test)]
mod tests {
    /// No list names the Rust pass types, so the test is that each one a
    /// module registers is in the library: a registration the linker dropped
    /// (or a module that implements `PassType` and forgot to register) fails
    /// here.
    #[test]
    fn every_rust_pass_type_registers_itself() {
        let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut implemented = 0;
        let mut registered = 0;
        for entry in std::fs::read_dir(&src).expect("src/") {
            let path = entry.expect("entry").path();
            let text = std::fs::read_to_string(&path).expect("read");
            let impls = text
                .lines()
                .filter(|l| l.starts_with("impl PassType for "))
                .count();
            let submits = text
                .lines()
                .filter(|l| l.starts_with("inventory::submit!"))
                .count();
            // The TOML pass types are found by data_pass::discover instead.
            if path.file_name().is_some_and(|n| n == "data_pass.rs") {
                continue;
            }
            assert!(
                impls == 0 || submits > 0,
                "{} implements PassType but registers nothing with inventory::submit!",
                path.display()
            );
            implemented += impls;
            registered += submits;
        }
        assert!(implemented > 0 && registered >= implemented);
        let found = inventory::iter::<super::RustPassType>.into_iter().count();
        assert_eq!(
            found, registered,
            "registrations in src/ vs found at run time"
        );
        let library = super::read_library(&[]);
        for r in inventory::iter::<super::RustPassType> {
            let name = (r.0)(&library).spec().name;
            assert!(
                library.get(&name).is_some(),
                "`{name}` is not in the library"
            );
        }
    }
}
