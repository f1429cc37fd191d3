// plait::geometry::wisps — polygon wisps with a strand texture (Halén &
// Wester, "Real-Time Hair Simulation and Visualization for Games", M.Sc.
// thesis, Lund University, 2007, §2.2–2.4). Every hair draw draws the wisps'
// triangles (plait_hair::wisps::WispMesh: two vertices per guide point, even
// = one side, odd = the other; `thickness` holds v along the wisp,
// `strand_id` the hair vertex the wisp vertex stands for). How and why:
// techniques/geometry/wisps/technique.toml.
#define_import_path plait::geometry::wisps

#import plait::frame::{frame, view_proj}

struct GeometryParams {
    // A wisp's width across the view (model units).
    wisp_width: f32,
}
@group(1) @binding(45) var<uniform> geometry_params: GeometryParams;
// The strand texture and its mip chain side by side (strand_texture.wgsl).
@group(1) @binding(46) var wisp_texture: texture_2d<f32>;

// Every wisp is drawn, for itself: the strip's width and the texture's
// alpha are its coverage.
fn strand_weight(strand_id: u32) -> f32 {
    return 1.0;
}

// Across the wisp and the view ray from `world`: the direction the strip
// spreads in so it faces the view (the light in light views).
fn wisp_side(world: vec3<f32>, tangent: vec3<f32>) -> vec3<f32> {
#ifdef LIGHT_VIEW
    // A spot light (w = 1) from its position; a directional one along its direction.
    let to_eye = select(frame.light_direction.xyz, normalize(frame.light_position.xyz - world), frame.light_direction.w > 0.5);
#else
    let to_eye = normalize(frame.camera_position.xyz - world);
#endif
    var side = cross(tangent, to_eye);
    if (dot(side, side) < 1e-12) {
        side = cross(select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(to_eye.y) > 0.9), to_eye);
    }
    return normalize(side);
}

// The strip's corner of wisp vertex `index` at guide point `world`.
fn wisp_corner(world: vec3<f32>, tangent: vec3<f32>, index: u32) -> vec3<f32> {
    let across = select(-0.5, 0.5, (index & 1u) == 1u);
    return world + wisp_side(world, tangent) * across * geometry_params.wisp_width;
}

// u across the wisp (0 or 1 at its sides), for the texture.
fn wisp_u(index: u32) -> f32 {
    return f32(index & 1u);
}

// The texture's levels, down to 1 × 1: floor(log2(size)) + 1.
fn wisp_levels() -> u32 {
    let size = textureDimensions(wisp_texture).y;
    return firstLeadingBit(max(size, 1u)) + 1u;
}

// The mip level whose texels match the wisp's width on screen at `world`:
// log2(texels across / pixels across), from the camera's projection.
fn wisp_level(world: vec3<f32>, tangent: vec3<f32>) -> f32 {
    let a = frame.camera_view_proj * vec4<f32>(world, 1.0);
    let b = frame.camera_view_proj * vec4<f32>(world + wisp_side(world, tangent) * geometry_params.wisp_width, 1.0);
    if (a.w <= 0.0 || b.w <= 0.0) {
        return 0.0;
    }
    let pixels = max(length((b.xy / b.w - a.xy / a.w) * 0.5 * frame.screen_size.xy), 1e-3);
    let texels = f32(textureDimensions(wisp_texture).y);
    return clamp(log2(texels / pixels), 0.0, f32(wisp_levels() - 1u));
}

// Texel (u, v) of level `level`, nearest.
fn wisp_level_texel(u: f32, v: f32, level: u32) -> vec4<f32> {
    let size = textureDimensions(wisp_texture).y;
    // Level l starts where the levels before it end (each half the one
    // before, rounded down, at least 1: strand_texture.wgsl's layout).
    var start = 0u;
    var width = size;
    for (var l = 0u; l < level; l += 1u) {
        start += width;
        width = max(width / 2u, 1u);
    }
    let x = min(u32(clamp(u, 0.0, 1.0) * f32(width)), width - 1u);
    let y = min(u32(clamp(v, 0.0, 1.0) * f32(width)), width - 1u);
    return textureLoad(wisp_texture, vec2<u32>(start + x, y), 0);
}

// The strand texture at (u, v), blended between the two levels around
// `level` (trilinear in level, nearest within one): rgb multiplies the
// strand's colour, alpha is the fragment's coverage.
fn wisp_texel(u: f32, v: f32, level: f32) -> vec4<f32> {
    let l0 = u32(floor(level));
    let l1 = min(l0 + 1u, wisp_levels() - 1u);
    let a = wisp_level_texel(u, v, l0);
    let b = wisp_level_texel(u, v, l1);
    let t = level - floor(level);
    let alpha = mix(a.a, b.a, t);
    let rgb = mix(a.rgb * a.a, b.rgb * b.a, t) / max(alpha, 1e-6);
    return vec4<f32>(select(vec3<f32>(1.0), rgb, alpha > 1e-6), alpha);
}
