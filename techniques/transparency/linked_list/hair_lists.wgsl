// linked_list, the hair pass: per-pixel fragment lists (an "A-buffer" of
// linked lists). Every hair fragment in front of the opaque depth, shaded by
// the shared hair-fragment stage, is appended to its pixel's list — a node
// from a global atomic counter, linked in with an atomic exchange of the
// pixel's head pointer. Nodes past the capacity are dropped and counted
// (counter word 1; the technique's `overflow` declares it). The resolve pass
// (linked_list_resolve) sorts each list by depth and blends it front to
// back: exact order, the same result as depth peeling (Sintorn & Assarsson
// 2009 §2.2) in one geometry pass.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

// Head pointer per pixel: 0 = empty, else node index + 1.
@group(1) @binding(60) var<storage, read_write> list_heads: array<atomic<u32>>;
// 4 words per node: pack2x16float(r, g), pack2x16float(b, alpha), depth bits, next.
@group(1) @binding(61) var<storage, read_write> list_nodes: array<u32>;
// [0] nodes allocated (may exceed capacity), [1] fragments dropped on overflow.
@group(1) @binding(62) var<storage, read_write> list_counter: array<atomic<u32>>;
@group(1) @binding(63) var opaque_depth: texture_depth_2d;

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

// No colour target: the fragment's only output is its list node.
@fragment
fn fs_main(in: HairVaryings) {
    // Shaded first, in uniform control flow (providers may sample textures
    // with derivatives).
    let f = shade_hair(in);
    let clip = in.clip;
    let p = vec2<u32>(clip.xy);
    // Storage writes happen even for fragments the depth test would reject
    // later: test against the opaque depth here.
    if (clip.z >= textureLoad(opaque_depth, vec2<i32>(p), 0)) {
        discard;
    }
    let width = textureDimensions(opaque_depth).x;
    let capacity = arrayLength(&list_nodes) / 4u;
    let node = atomicAdd(&list_counter[0], 1u);
    if (node >= capacity) {
        atomicAdd(&list_counter[1], 1u);
        discard;
    }
    let rgb = f.rgb;
    let alpha = f.alpha;
    let prev = atomicExchange(&list_heads[p.y * width + p.x], node + 1u);
    list_nodes[node * 4u + 0u] = pack2x16float(rgb.rg);
    list_nodes[node * 4u + 1u] = pack2x16float(vec2<f32>(rgb.b, alpha));
    list_nodes[node * 4u + 2u] = bitcast<u32>(clip.z);
    list_nodes[node * 4u + 3u] = prev;
}
