//! A WGSL point's slots and params, as its `point.toml` declares them
//! (`plait_graph::techniques::point_contract`): the one place the pass
//! library reads them, so no Rust module lists a point's slots, params or
//! defaults. The Rust point modules (`visibility`, `shading`, …) and the
//! hair passes take what this returns.

use plait_gpu::PassLibrary;
use plait_graph::techniques::WgslPoint;
use plait_graph::{ParamSpec, SlotSpec, Value};

use crate::spec_util::choice;

/// Point `name`'s contract as the shader library read it; `None` when the
/// library cannot be read (loading it then reports why) or has no such point.
pub fn contract(library: &PassLibrary, name: &str) -> Option<WgslPoint> {
    let library = library.shaders.library().ok()?;
    let point = library.points.iter().find(|p| p.contract.point == name)?;
    Some(point.contract.clone())
}

/// The optional input slots any provider of point `name` may bind.
pub fn slots(library: &PassLibrary, name: &str) -> Vec<SlotSpec> {
    contract(library, name)
        .map(|c| c.contract.inputs)
        .unwrap_or_default()
}

/// The point's params: the one naming the provider (its choices the
/// providers found, its default the point file's), then those its
/// providers read. A `[params_from]` file that does not read gives none of
/// its params here: the pass library reports it at its file.
pub fn params(library: &PassLibrary, name: &str) -> Vec<ParamSpec> {
    let Some(point) = contract(library, name) else {
        return Vec::new();
    };
    let providers = library.shaders.providers(&point.param);
    let mut out = vec![choice(
        &point.param,
        &point.default.value,
        &providers.iter().map(String::as_str).collect::<Vec<_>>(),
        &format!(
            "{name} technique (provider of `{}`): {}",
            point.module, point.doc
        ),
    )];
    let declared = match point.contract.all_params() {
        Ok(all) => all,
        Err(_) => point.contract.params.clone(),
    };
    out.extend(declared.into_iter().map(|p| p.spec));
    out
}

/// The default of param `param` of point `name`, as its point file declares it.
pub fn default(library: &PassLibrary, name: &str, param: &str) -> Option<Value> {
    params(library, name)
        .into_iter()
        .find(|p| p.name == param)
        .and_then(|p| p.default)
}
