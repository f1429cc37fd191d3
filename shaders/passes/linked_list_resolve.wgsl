// linked_list_resolve: walk the pixel's fragment list (built by the hair
// pass of techniques/transparency/linked_list/hair_lists.wgsl), keep the
// nearest `max_sorted` (≤ 256) fragments, sort them by depth, blend them
// front to back: C += (1 - A) · α · rgb, A += (1 - A) · α — exactly what depth
// peeling computes one layer at a time (Sintorn & Assarsson 2009 §2.2).
//
// The nearest ones are kept in a max-heap (the farthest kept at its root): a
// fragment is pushed while the heap has room, else it replaces the root if
// it is nearer, then the heap is sorted in place. Equal depths keep the
// walk's order (the key is depth, then position in the walk), so the set
// and order are the ones an insertion sort into a sorted array gives. Why a
// heap: lavapipe gives each group of 8 fragments (a 4×2 block) one budget of
// 65,535 loop laps for all its loops and silently ends every loop once it
// is spent; the insertion sort cost up to keep / 2 laps a fragment (dense.toml
// at 160x120, lists of 615: cut), the heap at most log₂ keep + 1 = 9.
// A pixel whose walk, heap or blend loop still stopped early adds 1 to
// `list_counter[2]`, the `incomplete` word of the counter's overflow
// declaration, and the frame fails instead of blending part of a list.
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

// The heap of kept fragments: depth, position in the walk, node.
struct Kept {
    depth: f32,
    walk: u32,
    node: u32,
}
var<private> heap: array<Kept, SORT_CAPACITY>;

// `a` blends before `b`: nearer, or as near and met first in the walk.
fn before(a: Kept, b: Kept) -> bool {
    return a.depth < b.depth || (a.depth == b.depth && a.walk < b.walk);
}

// Places `x` at slot `c` of a max-heap of `n` whose slot `c` is free (its
// subtree otherwise a heap), moving it down past later children. Returns
// false if the loop was ended before `x` found its place.
fn sift_down(x: Kept, start: u32, n: u32) -> bool {
    var c = start;
    var moving = true;
    while (moving) {
        let l = 2u * c + 1u;
        if (l >= n) {
            moving = false;
            break;
        }
        var m = l;
        if (l + 1u < n && before(heap[l], heap[l + 1u])) {
            m = l + 1u;
        }
        if (!before(x, heap[m])) {
            moving = false;
            break;
        }
        heap[c] = heap[m];
        c = m;
    }
    heap[c] = x;
    return !moving;
}

// Adds `x` at slot `n` of a heap of `n`, moving it up past earlier
// parents. Returns false if the loop was ended first.
fn sift_up(x: Kept, n: u32) -> bool {
    var c = n;
    while (c > 0u && before(heap[(c - 1u) / 2u], x)) {
        heap[c] = heap[(c - 1u) / 2u];
        c = (c - 1u) / 2u;
    }
    let done = !(c > 0u && before(heap[(c - 1u) / 2u], x));
    heap[c] = x;
    return done;
}

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let width = u32(frame.screen_size.x);
    let keep = clamp(params.max_sorted, 1u, SORT_CAPACITY);
    let p = vec2<u32>(pixel.xy);
    var n = 0u;
    var at = list_heads[p.y * width + p.x];
    var guard = 0u;
    let capacity = arrayLength(&list_nodes) / 4u;
    var complete = true;
    while (at != 0u && guard < capacity) {
        let i = at - 1u;
        let x = Kept(bitcast<f32>(list_nodes[i * 4u + 2u]), guard, i);
        if (n < keep) {
            complete = sift_up(x, n) && complete;
            n++;
        } else if (before(x, heap[0])) {
            // Full: the farthest kept falls off for a nearer one.
            complete = sift_down(x, 0u, n) && complete;
        }
        at = list_nodes[i * 4u + 3u];
        guard++;
    }
    // A list left before its end (`guard` is the pool's own bound).
    complete = complete && !(at != 0u && guard < capacity);
    // Heap sort in place: the farthest goes last.
    var end = n;
    while (end > 1u) {
        end--;
        let last = heap[end];
        heap[end] = heap[0];
        complete = sift_down(last, 0u, end) && complete;
    }
    complete = complete && end <= 1u;
    var c = vec3<f32>(0.0);
    var a = 0.0;
    var k = 0u;
    for (; k < n; k++) {
        let i = heap[k].node;
        let rg = unpack2x16float(list_nodes[i * 4u]);
        let ba = unpack2x16float(list_nodes[i * 4u + 1u]);
        c += (1.0 - a) * ba.y * vec3<f32>(rg, ba.x);
        a += (1.0 - a) * ba.y;
    }
    if (!complete || k < n) {
        atomicAdd(&list_counter[2], 1u);
    }
    return vec4<f32>(c, a);
}
