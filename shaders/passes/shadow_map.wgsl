// shadow_map: depth of the drawn geometry from the pass's view, no colour.
// Used for the opaque shadow map (Sintorn & Assarsson 2009 §3.5) and, drawing
// hair, for the modified shadow map's nearest-hair depth (Halén & Wester 2007 §3.3.2).
#import plait::frame::{view_proj, opaque_world}

#ifdef DRAW_OPAQUE
struct VertexIn {
    @location(0) position: vec3<f32>,
    // 1 for the head, which moves with the scene's animation.
    @location(3) head: f32,
}

@vertex
fn vs_main(v: VertexIn) -> @builtin(position) vec4<f32> {
    return view_proj() * vec4<f32>(opaque_world(v.position, v.head), 1.0);
}
#else
// Hair goes through the geometry choice like every other map of hair: the
// strands the `lod` technique drops are dropped here too, and a wisp vertex
// becomes its strip's corner (drawn as it is, a wisp's strip has no width).
// One-texel lines, whatever the strand's width: the nearest hair's depth is
// all the map holds, and its providers take every strand crossed behind it
// at the groom's mean width (plait::light_share), not at its texels.
#import plait::hair_map::{MapLineVertex, map_line_vertex}

@vertex
fn vs_main(v: MapLineVertex) -> @builtin(position) vec4<f32> {
    return map_line_vertex(v).clip;
}
#endif
