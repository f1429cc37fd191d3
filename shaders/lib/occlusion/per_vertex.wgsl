// plait::ambient_occlusion::per_vertex — ambient occlusion precomputed per hair
// vertex: the ambient visibility (1 = open) a precompute pass of the
// technique wrote, one f32 per vertex of the hair vertex buffer. Both
// `ambient_occlusion` techniques that compute it export this provider:
// deep_opacity_directions (Xing et al. 2012 §4) and cylinders (Halén &
// Wester 2007 §3.3.1). Read in the hair vertex shader, as Xing et al. load
// their transmittance "as vertex attribute".
#define_import_path plait::ambient_occlusion::per_vertex

@group(1) @binding(41) var<storage, read> occ_vertex_ao: array<f32>;

fn vertex_occlusion(vertex_index: u32) -> f32 {
    if (vertex_index >= arrayLength(&occ_vertex_ao)) {
        return 1.0;
    }
    return clamp(occ_vertex_ao[vertex_index], 0.0, 1.0);
}
