// shortcut, the first hair draw (AMD TressFX 4.1 ShortCut): every visible
// fragment inserts its depth into its pixel's k-buffer of the `nearest`
// smallest depths, and adds its alpha to the pixel's coverage 1 - Π(1-α)
// (the pass's blend c' = α + c·(1-α), in any order). No shading: only the
// alpha is needed here.
//
// A fragment fainter than `min_alpha` (TressFX's SHORTCUT_MIN_ALPHA, 0.02)
// takes no slot: it would push a fragment that has a colour out of the k
// nearest while adding next to nothing to their sum (16.4% of `dense`'s
// fragments at 160×120 are that faint) — and k such fragments in front (a
// strand drawn at zero alpha) left a pixel with coverage but no colour, so
// the resolve dropped its hair. Unlike TressFX it still counts in the
// coverage.
//
// The k-buffer holds inverted depth bits, !bits(z): depths in [0, 1] are
// non-negative floats, whose bits order as the floats do, so the largest key
// is the nearest depth, and the engine's zeroed buffer reads as "empty"
// (farther than any depth). Insertion is one atomicMax per slot: a slot keeps
// the larger key and the smaller one moves on to the next slot, so after
// every fragment the slots hold the k nearest keys in order, whatever the
// fragments' order. Hidden fragments never get here: the engine runs this
// pass's depth test before the shader (docs/design.md, "Storage writes
// respect the depth test").
#import plait::frame::frame
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, fragment_alpha}

struct ShortcutParams {
    min_alpha: f32,
}
@group(1) @binding(60) var<storage, read_write> nearest_depths: array<atomic<u32>>;
@group(1) @binding(61) var<uniform> shortcut_params: ShortcutParams;

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    let alpha = fragment_alpha(in);
    if (alpha < shortcut_params.min_alpha) {
        return vec4<f32>(alpha);
    }
    let p = vec2<u32>(in.clip.xy);
    let base = (p.y * u32(frame.screen_size.x) + p.x) * #{NEAREST}u;
    var key = ~bitcast<u32>(in.clip.z);
    for (var i = 0u; i < #{NEAREST}u; i++) {
        let kept = atomicMax(&nearest_depths[base + i], key);
        key = min(key, kept);
        if (key == 0u) {
            break;
        }
    }
    return vec4<f32>(alpha);
}
