// linked_list_resolve: walk the pixel's fragment list (built by the hair
// pass of techniques/transparency/linked_list/hair_lists.wgsl), keep the nearest
// `max_sorted` (≤ 256) fragments sorted by depth (insertion sort), blend them front to
// back: C += (1 - A) · α · rgb, A += (1 - A) · α — exactly what depth peeling
// computes one layer at a time (Sintorn & Assarsson 2009 §2.2).
//
// lavapipe gives each group of 8 fragments (a 4×2 block) one budget of
// 65,535 loop iterations for all its loops and silently ends every loop once
// it is spent: a block of long lists (dense.toml at 160x120: lists of 615
// fragments) would blend a partial list. A pixel whose walk, insertion or
// blend stopped early adds 1 to `list_counter[2]`, the `incomplete` word of
// the counter's overflow declaration, and the frame fails instead.
#import plait::frame::{frame, fullscreen_position}

@group(1) @binding(0) var<storage, read> list_heads: array<u32>;
@group(1) @binding(1) var<storage, read> list_nodes: array<u32>;

struct Params {
    max_sorted: u32,
}
@group(1) @binding(2) var<uniform> params: Params;
// [0] nodes asked for and [1] dropped (the hair pass), [2] pixels whose
// resolve could not finish (this pass).
@group(1) @binding(3) var<storage, read_write> list_counter: array<atomic<u32>>;

// Room for the nearest SORT_CAPACITY fragments; `max_sorted` may lower it.
const SORT_CAPACITY: u32 = 256u;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    var depth: array<f32, SORT_CAPACITY>;
    var node: array<u32, SORT_CAPACITY>;
    let width = u32(frame.screen_size.x);
    let keep = clamp(params.max_sorted, 1u, SORT_CAPACITY);
    let p = vec2<u32>(pixel.xy);
    var n = 0u;
    var at = list_heads[p.y * width + p.x];
    var guard = 0u;
    let capacity = arrayLength(&list_nodes) / 4u;
    var cut = false;
    while (at != 0u && guard < capacity) {
        let i = at - 1u;
        let z = bitcast<f32>(list_nodes[i * 4u + 2u]);
        // Insert into the sorted prefix; when full, the farthest falls off.
        var j = n;
        if (n == keep) {
            j = n - 1u;
            if (z >= depth[j]) {
                at = list_nodes[i * 4u + 3u];
                guard++;
                continue;
            }
        } else {
            n++;
        }
        while (j > 0u && depth[j - 1u] > z) {
            depth[j] = depth[j - 1u];
            node[j] = node[j - 1u];
            j--;
        }
        // The shift stopped before its place: the loop was ended for it.
        cut = cut || (j > 0u && depth[j - 1u] > z);
        depth[j] = z;
        node[j] = i;
        at = list_nodes[i * 4u + 3u];
        guard++;
    }
    // A list left before its end (`guard` is the pool's own bound).
    cut = cut || (at != 0u && guard < capacity);
    var c = vec3<f32>(0.0);
    var a = 0.0;
    var k = 0u;
    for (; k < n; k++) {
        let i = node[k];
        let rg = unpack2x16float(list_nodes[i * 4u]);
        let ba = unpack2x16float(list_nodes[i * 4u + 1u]);
        c += (1.0 - a) * ba.y * vec3<f32>(rg, ba.x);
        a += (1.0 - a) * ba.y;
    }
    if (cut || k < n) {
        atomicAdd(&list_counter[2], 1u);
    }
    return vec4<f32>(c, a);
}
