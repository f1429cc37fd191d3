// plait::frame — the standard inputs every pass gets at group 0.
//
// Keep in sync with `FrameUniforms` in crates/plait-gpu/src/frame.rs (a test
// compares the two layouts through naga's reflection).
#define_import_path plait::frame

struct Frame {
    camera_view_proj: mat4x4<f32>,
    camera_view: mat4x4<f32>,
    camera_inv_view_proj: mat4x4<f32>,
    light_view_proj: mat4x4<f32>,
    light_view: mat4x4<f32>,
    light_inv_view_proj: mat4x4<f32>,
    // xyz: eye position in world space.
    camera_position: vec4<f32>,
    // xyz: unit vector from the scene towards a directional light; w = 1 for a spot light.
    light_direction: vec4<f32>,
    // xyz: position of a spot light.
    light_position: vec4<f32>,
    // rgb: light colour times intensity: the irradiance on a surface facing a
    // directional light, the radiant intensity of a spot light
    // (docs/formats.md, "Light and units"; `light_irradiance`).
    light_color: vec4<f32>,
    // rgb: hair base colour; a: strand alpha scale.
    hair_color: vec4<f32>,
    // Kajiya-Kay: x = diffuse kd, y = specular ks, z = specular exponent, w = specular shift.
    hair_shading: vec4<f32>,
    // rgb: background colour; w = 1 when the scene's background is an image
    // (`background_image`), 0 for the flat colour.
    background: vec4<f32>,
    // rgb: ambient light, the radiance of a uniform environment.
    ambient: vec4<f32>,
    // xy: render size in pixels; zw: 1 / size.
    screen_size: vec4<f32>,
    // xy: unused; z: time in s (frame index / fps); w: frame index.
    jitter: vec4<f32>,
    // x, y: camera near and far; z, w: light near and far (world units).
    near_far: vec4<f32>,
    // x: mean hair fragment alpha (material alpha × mean strand alpha × strand
    // coverage while it is on) over every vertex: occupancy order's α only
    // with mean_alpha = "frame" (by default Σα / n per pixel, alpha_sum);
    // y: strands; z: segments; w: the mean alpha without coverage.
    hair_stats: vec4<f32>,
    // The conventions every visibility provider shares (docs/design.md, "In
    // front of"): x = self-shadow bias in light linear depth; y = 1 to jitter
    // light-map lookups by up to half a texel (Fig. 9), 0 to read the texel
    // the point falls in; z = 1 when strands thinner than a pixel weigh by
    // the part of it they cover (plait::strand_coverage).
    conventions: vec4<f32>,
    // World-from-rest matrix of the head at this frame's time (the scene's
    // [animation]; identity for a still head), and one frame earlier.
    head_model: mat4x4<f32>,
    head_model_previous: mat4x4<f32>,
    // The hair's bounding sphere: xyz centre, w radius (world units).
    hair_sphere: vec4<f32>,
    // x: the strands' mean width (thickness, world units) over every vertex:
    // what the depth-only self-shadow maps take each strand crossed to be
    // (plait::light_share); y: the widest strand across the camera's view in
    // pixels, z: across the light's in its normalized device units (the
    // CPU's, for whether the hair draws need their quads); w unused.
    hair_width: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var linear_sampler: sampler;
@group(0) @binding(2) var nearest_sampler: sampler;
@group(0) @binding(3) var shadow_sampler: sampler_comparison;
// The scene's background image, stretched over the frame (1×1 when the
// background is a colour).
@group(0) @binding(4) var background_image: texture_2d<f32>;

// What lies behind everything at a pixel: the background image or colour.
fn background_at(pixel: vec2<f32>) -> vec3<f32> {
    if (frame.background.w > 0.5) {
        return textureSampleLevel(background_image, linear_sampler, pixel * frame.screen_size.zw, 0.0).rgb;
    }
    return frame.background.rgb;
}

// An opaque vertex in the world: the head (weight 1) moves with
// `head_model`, everything else (weight 0: the ground) stays.
fn opaque_world(position: vec3<f32>, head_weight: f32) -> vec3<f32> {
    let moved = (frame.head_model * vec4<f32>(position, 1.0)).xyz;
    return mix(position, moved, head_weight);
}

// An opaque vertex's normal in the world (the head's turns rigidly).
fn opaque_world_normal(normal: vec3<f32>, head_weight: f32) -> vec3<f32> {
    let moved = (frame.head_model * vec4<f32>(normal, 0.0)).xyz;
    return mix(normal, moved, head_weight);
}

// The view a raster pass draws from: the engine defines LIGHT_VIEW for `view = "light"`.
fn view_proj() -> mat4x4<f32> {
#ifdef LIGHT_VIEW
    return frame.light_view_proj;
#else
    return frame.camera_view_proj;
#endif
}

// Light-space texture coordinate (0..1, y down) and the depth a depth target
// rendered from the light stores for a world-space point.
fn light_uv_depth(world: vec3<f32>) -> vec3<f32> {
    let clip = frame.light_view_proj * vec4<f32>(world, 1.0);
    let ndc = clip.xyz / clip.w;
    return vec3<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5, ndc.z);
}

// Distance along the light's axis, 0 at its near plane and 1 at its far plane.
// Equal to the stored depth for a directional light (orthographic); linear for
// a spot light too, where stored depth is not.
fn light_linear_depth(world: vec3<f32>) -> f32 {
    let view_z = -(frame.light_view * vec4<f32>(world, 1.0)).z;
    return (view_z - frame.near_far.z) / (frame.near_far.w - frame.near_far.z);
}

// Light linear depth (as `light_linear_depth`) of a depth the light's
// projection stored in a depth map: the same value for an orthographic
// (directional) light; undone from the perspective of a spot light.
fn light_depth_to_linear(stored: f32) -> f32 {
    if (frame.light_direction.w < 0.5) {
        return stored;
    }
    let n = frame.near_far.z;
    let f = frame.near_far.w;
    let distance = f * n / (f - stored * (f - n));
    return (distance - n) / (f - n);
}

// Linear depth (0 at near, 1 at far) of a world-space point in the pass's
// view: the light's for `view = "light"`, the camera's otherwise. The
// occupancy maps slice this depth uniformly.
fn view_linear_depth(world: vec3<f32>) -> f32 {
#ifdef LIGHT_VIEW
    return light_linear_depth(world);
#else
    let view_z = -(frame.camera_view * vec4<f32>(world, 1.0)).z;
    return (view_z - frame.near_far.x) / (frame.near_far.y - frame.near_far.x);
#endif
}

// Linear camera depth, whatever the pass's view.
fn camera_linear_depth(world: vec3<f32>) -> f32 {
    let view_z = -(frame.camera_view * vec4<f32>(world, 1.0)).z;
    return (view_z - frame.near_far.x) / (frame.near_far.y - frame.near_far.x);
}

// Unit vector from a world-space point towards the light.
fn to_light(world: vec3<f32>) -> vec3<f32> {
    if (frame.light_direction.w > 0.5) {
        return normalize(frame.light_position.xyz - world);
    }
    return frame.light_direction.xyz;
}

// The irradiance the key light brings to a surface at `world` facing it:
// the light's colour × intensity for a directional light; for a spot light,
// whose intensity is radiant intensity, that over the squared distance.
fn light_irradiance(world: vec3<f32>) -> vec3<f32> {
    if (frame.light_direction.w > 0.5) {
        let d = frame.light_position.xyz - world;
        return frame.light_color.rgb / max(dot(d, d), 1e-8);
    }
    return frame.light_color.rgb;
}

// The vertex of a triangle covering the whole target (draw 3 vertices).
fn fullscreen_position(vertex_index: u32) -> vec4<f32> {
    let uv = vec2<f32>(f32((vertex_index << 1u) & 2u), f32(vertex_index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

// A point's light-map lookup, the same for every visibility provider and the
// exact reference (docs/design.md, "In front of"): the texel it reads and the
// light depth below which hair counts as in front of the point.
struct LightLookup {
    // false outside the light map: fully lit.
    inside: bool,
    texel: vec2<u32>,
    uv: vec2<f32>,
    // Hair fragments with light linear depth < this are in front of the point:
    // its own depth less the self-shadow bias, so it never counts itself.
    in_front_below: f32,
}

// Hash of a world position to [-0.5, 0.5]², the per-point jitter of Fig. 9.
fn jitter_hash(p: vec3<f32>) -> vec2<f32> {
    let q = vec3<u32>(bitcast<u32>(p.x), bitcast<u32>(p.y), bitcast<u32>(p.z));
    var h = (q.x * 0x9E3779B1u) ^ (q.y * 0x85EBCA77u) ^ (q.z * 0xC2B2AE3Du);
    h = (h ^ (h >> 15u)) * 0x2C1B3C6Du;
    h = (h ^ (h >> 12u)) * 0x297A2D39u;
    h = h ^ (h >> 15u);
    return vec2<f32>(f32(h & 0xFFFFu), f32(h >> 16u)) / 65535.0 - 0.5;
}

fn light_lookup(world: vec3<f32>, size: vec2<u32>) -> LightLookup {
    var out: LightLookup;
    let p = light_uv_depth(world);
    out.inside = all(p.xy >= vec2<f32>(0.0)) && all(p.xy <= vec2<f32>(1.0));
    let texels = p.xy * vec2<f32>(size) + jitter_hash(world) * frame.conventions.y;
    out.texel = vec2<u32>(clamp(texels, vec2<f32>(0.0), vec2<f32>(size) - 1.0));
    out.uv = (vec2<f32>(out.texel) + 0.5) / vec2<f32>(size);
    out.in_front_below = light_linear_depth(world) - frame.conventions.x;
    return out;
}

// The light linear depths between which hair lies behind `world` along the
// light's ray (the self_shadow contract's `hair_strands_along_light` y;
// docs/design.md, "In front of"): x, past the point's own strand — what is
// in front of the point two self-shadow biases farther from the light; y,
// beyond the hair's bounding sphere, what is in front of the point two
// biases past the sphere's diameter farther on (every strand behind). A
// provider counts the hair in front of y less that in front of x, in the
// texel of `world`'s own `light_lookup`: the same ray (along it the light
// maps' texel does not change), read once.
fn light_behind(world: vec3<f32>) -> vec2<f32> {
    let bias = frame.conventions.x * (frame.near_far.w - frame.near_far.z);
    let away = -to_light(world);
    let past_own = light_linear_depth(world + away * (2.0 * bias)) - frame.conventions.x;
    let beyond = light_linear_depth(world + away * (2.0 * frame.hair_sphere.w + 2.0 * bias)) - frame.conventions.x;
    return vec2<f32>(past_own, beyond);
}
