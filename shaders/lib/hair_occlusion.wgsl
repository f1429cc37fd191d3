// plait::hair_occlusion — the per-vertex ambient-occlusion provider a hair
// pass's `occlusion` param names (`#ifdef OCCLUSION_<NAME>`), evaluated in
// the vertex shader and interpolated along the strand. A new provider is one
// module in shaders/lib/occlusion/ plus one line here.
#define_import_path plait::hair_occlusion

#ifdef OCCLUSION_NONE
#import plait::occlusion::none::vertex_occlusion
#else ifdef OCCLUSION_PER_VERTEX
#import plait::occlusion::per_vertex::vertex_occlusion
#else
#import plait::occlusion::none::vertex_occlusion
#endif

// Fraction of the environment's light reaching vertex `vertex_index` (1 = open).
fn occlusion_at(vertex_index: u32) -> f32 {
    return vertex_occlusion(vertex_index);
}
