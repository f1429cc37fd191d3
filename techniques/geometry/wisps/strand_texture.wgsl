// The wisps' strand texture (Halén & Wester, "Real-Time Hair Simulation and
// Visualization for Games", M.Sc. thesis, Lund University, 2007, §2.3: "strands
// could then be generated in textures which are mapped onto the polygon
// wisps"; §5.3 wishes them "automatically generated given some user input").
// Drawn once (`run = "once"`), one fragment per texel.
//
// Level 0 (size × size): u across the wisp, v along it (0 root, 1 tip). Many
// thin strands run along v, each at its own place across u, slightly wavy,
// of its own brightness (rgb multiplies the strand's colour), opacity and
// length (alpha falls to 0 past its tip); the strands thin out towards the
// wisp's edges so the strip has no hard border.
//
// The mip chain sits beside level 0 in the same texture (width 2 × size):
// level l + 1, half of level l a side (rounded down, at least 1), starts
// where level l ends, row 0. Each of its texels is the box filter of the 2^l × 2^l level-0 texels it
// covers, computed here directly (colour averaged weighted by alpha), which
// is what a GPU's mip generation would give (§2.4: "the graphics cards
// ability of generating mipmaps will provide level of detail").
#import plait::frame::fullscreen_position

struct Params {
    size: i32,
}
@group(1) @binding(0) var<uniform> params: Params;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

fn hash(n: u32) -> f32 {
    var x = n * 747796405u + 2891336453u;
    x = ((x >> ((x >> 28u) + 4u)) ^ x) * 277803737u;
    x = (x >> 22u) ^ x;
    return f32(x) / 4294967295.0;
}

// Strands across the texture's width: one per 3 texels of level 0, at
// least 8.
fn strand_count() -> u32 {
    return max(u32(params.size) / 3u, 8u);
}

// Level 0 at (u, v) in [0, 1]²: premultiplied colour and alpha.
fn strands_at(u: f32, v: f32) -> vec4<f32> {
    let n = strand_count();
    let nf = f32(n);
    let half_width = 0.6 / nf;
    var out = vec4<f32>(0.0);
    // A strand strays at most one spacing from its place: its two
    // neighbours on each side can reach (u, v).
    let centre = i32(floor(u * nf));
    for (var d = -2; d <= 2; d += 1) {
        let k = centre + d;
        if (k < 0 || k >= i32(n)) {
            continue;
        }
        let s = u32(k);
        let place = (f32(s) + 0.5 + (hash(s * 4u) - 0.5) * 0.8) / nf;
        let wave = sin(6.2831853 * (v * (0.5 + 1.5 * hash(s * 4u + 1u)) + hash(s * 4u + 2u)));
        let x = place + wave * 0.6 / nf;
        // Edge thinning: strands near the wisp's borders are fainter.
        let edge = 1.0 - pow(abs(2.0 * x - 1.0), 4.0);
        let length = 0.75 + 0.25 * hash(s * 4u + 3u);
        let along = 1.0 - smoothstep(length - 0.08, length, v);
        let across = 1.0 - smoothstep(half_width * 0.5, half_width, abs(u - x));
        let opacity = (0.55 + 0.45 * hash(s * 7u + 5u)) * edge * along * across;
        let brightness = 0.65 + 0.6 * hash(s * 7u + 6u);
        // Over: nearer strands in index order (the texture has no depth).
        let c = vec4<f32>(vec3<f32>(brightness) * opacity, opacity);
        out = out + c * (1.0 - out.a);
    }
    return out;
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let size = u32(max(params.size, 1));
    let x = u32(pixel.x);
    let y = u32(pixel.y);
    // Which level this column belongs to, and where in that level.
    var level = 0u;
    var start = 0u;
    var width = size;
    loop {
        if (x < start + width || width == 1u) {
            break;
        }
        start += width;
        width = max(width / 2u, 1u);
        level += 1u;
    }
    if (x >= start + width || y >= width) {
        return vec4<f32>(0.0);
    }
    let scale = 1u << level;
    // The texel's 2^l × 2^l footprint in level 0, averaged exactly up to
    // 16 × 16 texels; beyond, 16 × 16 evenly spread samples of it (a texel
    // of level 8 or coarser would otherwise loop 65536 times and more).
    let taps = min(scale, 16u);
    let step = f32(scale) / f32(taps);
    var sum = vec4<f32>(0.0);
    for (var j = 0u; j < taps; j += 1u) {
        for (var i = 0u; i < taps; i += 1u) {
            let tx = f32((x - start) * scale) + (f32(i) + 0.5) * step;
            let ty = f32(y * scale) + (f32(j) + 0.5) * step;
            sum += strands_at(tx / f32(size), ty / f32(size));
        }
    }
    let mean = sum / f32(taps * taps);
    // Straight colour (the shader multiplies the strand's colour by it).
    let rgb = select(vec3<f32>(1.0), mean.rgb / mean.a, mean.a > 1e-6);
    return vec4<f32>(rgb, mean.a);
}
