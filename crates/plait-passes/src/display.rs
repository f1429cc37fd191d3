//! The display transform's params (`techniques/tone_mapping/`): each
//! tone-mapping technique is a data-only pass with its own WGSL, so no Rust
//! lists the operators; only the exposure they all read is declared here, so
//! that a non-finite or absurd value is refused at the flag or file that set
//! it, before any GPU work.

use plait_graph::ParamSpec;

use crate::spec_util::float;

/// Params of the display transform (filled into `display_params` by member name).
pub fn params() -> Vec<ParamSpec> {
    vec![float(
        "exposure",
        0.0,
        -64.0,
        64.0,
        "stops: the radiance is scaled by 2^exposure before the tone-mapping operator",
    )]
}
