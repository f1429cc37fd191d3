// plait::hair_map — the vertex stage shared by every pass that draws hair into
// a per-texel map (depth range, occupancy, slabs, deep opacity, opacity shadow
// maps, density clusters, depth lists): only the position matters, and the
// fragment keeps its world position to compute its depth in the view.
#define_import_path plait::hair_map

#import plait::frame::view_proj

struct MapVertex {
    @location(0) position: vec3<f32>,
}

struct MapFragment {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
}

fn map_vertex(v: MapVertex) -> MapFragment {
    var out: MapFragment;
    out.clip = view_proj() * vec4<f32>(v.position, 1.0);
    out.world = v.position;
    return out;
}
