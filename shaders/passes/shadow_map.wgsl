// shadow_map: depth of the drawn geometry from the pass's view, no colour.
// Used for the opaque shadow map (Sintorn & Assarsson 2009 §3.5) and, drawing
// hair, for the modified shadow map's nearest-hair depth (Halén & Wester 2007 §3.3.2).
#import plait::frame::{view_proj, opaque_world}

struct VertexIn {
    @location(0) position: vec3<f32>,
#ifdef DRAW_OPAQUE
    // 1 for the head, which moves with the scene's animation.
    @location(3) head: f32,
#endif
}

@vertex
fn vs_main(v: VertexIn) -> @builtin(position) vec4<f32> {
#ifdef DRAW_OPAQUE
    return view_proj() * vec4<f32>(opaque_world(v.position, v.head), 1.0);
#else
    return view_proj() * vec4<f32>(v.position, 1.0);
#endif
}
