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
pub mod shading;
pub mod shading_space;
pub mod simulation;
pub mod spec_util;
pub mod visibility;

use std::cell::RefCell;
use std::rc::Rc;

use plait_gpu::Capabilities;
use plait_gpu::pass::check::ShaderChecker;
use plait_gpu::pass::{PassLibrary, PassType};
use plait_graph::{CompileOptions, Errors, Pipeline, Schedule};

/// A pass type written in Rust, registered by its own module:
/// `inventory::submit! { crate::RustPassType(|| Box::new(MyPass)) }`.
pub struct RustPassType(pub fn() -> Box<dyn PassType>);

inventory::collect!(RustPassType);

/// Every pass type plait ships, and those on the search path.
///
/// Read once per thread and again only when a pass-type file or its shader
/// on the search path changes (the viewer edits them live): a render asks
/// for the library when it compiles, checks against the adapter and builds,
/// and should parse its files once.
pub fn library() -> Rc<PassLibrary> {
    thread_local! {
        static CACHE: RefCell<Option<(u64, Rc<PassLibrary>)>> = const { RefCell::new(None) };
    }
    let stamp = library_stamp();
    CACHE.with_borrow_mut(|cache| match cache {
        Some((s, lib)) if *s == stamp => lib.clone(),
        _ => {
            let lib = Rc::new(read_library());
            *cache = Some((stamp, lib.clone()));
            lib
        }
    })
}

/// How many times this process parsed the pass library's files
/// ([`library`] reads them again only when they change).
pub fn library_reads() -> usize {
    LIBRARY_READS.load(std::sync::atomic::Ordering::Relaxed)
}

static LIBRARY_READS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// The pass-type files and shaders on the search path, by name, size and
/// modification time, and the shader library's stamp (the providers found
/// are the choices of the shared params).
fn library_stamp() -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    plait_gpu::modules::library_stamp().hash(&mut h);
    for ext in ["toml", "wgsl"] {
        for path in plait_assets::list(data_pass::PASS_TYPE_DIR, ext) {
            path.hash(&mut h);
            if let Ok(meta) = std::fs::metadata(&path) {
                meta.len().hash(&mut h);
                meta.modified().ok().hash(&mut h);
            }
        }
    }
    h.finish()
}

/// Parse every pass type (what [`library`] caches).
fn read_library() -> PassLibrary {
    LIBRARY_READS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let mut lib = PassLibrary {
        // The providers' params mean the same in a data-only pass that
        // imports plait::hair_fragment as in the Rust pass types; the
        // geometry provider's in every pass that draws hair.
        shared_params: [
            hair_fragment::shading_params(),
            geometry::params(),
            display::params(),
        ]
        .concat(),
        // Every hair draw scales its coverage by the shading_space
        // provider's tip fading (plait::strand_coverage), so its buffers
        // reach the unshaded draws (alpha_sum) too.
        shared_slots: [geometry::slots(), shading_space::slots()].concat(),
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
    // Pass types written in Rust (loops, readback, state chosen by a param):
    // each module registers its own with `inventory::submit!`, so a new one
    // is its module and no line here. Sorted by name: the registration order
    // is the linker's.
    let mut rust: Vec<Box<dyn PassType>> = inventory::iter::<RustPassType>
        .into_iter()
        .map(|r| (r.0)())
        .collect();
    rust.sort_by_key(|t| t.spec().name);
    for t in rust {
        lib.insert(t);
    }
    lib
}

/// Compile `pipeline` with every pass (live and culled) checked against its
/// shader with naga and its formats fitted to the adapter `opts` describes:
/// the final schedule (`plait check` and every render run this, before any
/// GPU work).
pub fn compile(pipeline: &Pipeline, opts: &CompileOptions) -> Result<Schedule, Errors> {
    let _one_library = plait_gpu::modules::LibrarySnapshot::take();
    compile_in(&library(), pipeline, opts)
}

/// [`compile`] with the pass types of `library`.
pub fn compile_in(
    library: &PassLibrary,
    pipeline: &Pipeline,
    opts: &CompileOptions,
) -> Result<Schedule, Errors> {
    let _one_library = plait_gpu::modules::LibrarySnapshot::take();
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
        let library = super::library();
        for r in inventory::iter::<super::RustPassType> {
            let name = (r.0)().spec().name;
            assert!(
                library.get(&name).is_some(),
                "`{name}` is not in the library"
            );
        }
    }
}
