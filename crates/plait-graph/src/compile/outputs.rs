//! Checking `outputs`: each names a declared resource some pass writes. The
//! outputs are the roots culling keeps, so an empty list is an error too.

use crate::error::{Error, ErrorKind};
use crate::load::Pipeline;
use crate::schedule::ScheduledPass;

use super::order::writes_to;

/// Output resource indices (into `pipeline.resources`); reports unknown or
/// unwritten outputs.
pub(super) fn check_outputs(
    pipeline: &Pipeline,
    passes: &[ScheduledPass],
    errors: &mut Vec<Error>,
) -> Vec<usize> {
    if pipeline.outputs.is_empty() {
        errors.push(Error::new(
            pipeline.outputs_location.clone(),
            ErrorKind::Schema("`outputs` is empty: every pass would be culled".into()),
        ));
    }
    let mut outputs = Vec::new();
    for output in &pipeline.outputs {
        match pipeline.resources.get_index_of(&output.value) {
            None => errors.push(Error::new(
                output.location.clone(),
                ErrorKind::UnknownOutput {
                    name: output.value.clone(),
                    hint: crate::suggest::did_you_mean(
                        &output.value,
                        pipeline.resources.keys().map(String::as_str),
                    ),
                },
            )),
            Some(i) if !passes.iter().any(|p| writes_to(p, i).is_some()) => {
                errors.push(Error::new(
                    output.location.clone(),
                    ErrorKind::OutputNeverWritten(output.value.clone()),
                ))
            }
            Some(i) if !outputs.contains(&i) => outputs.push(i),
            Some(_) => {}
        }
    }
    outputs
}
