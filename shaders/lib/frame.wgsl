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
    // rgb: light colour times intensity.
    light_color: vec4<f32>,
    // rgb: hair base colour; a: strand alpha scale.
    hair_color: vec4<f32>,
    // Kajiya-Kay: x = diffuse kd, y = specular ks, z = specular exponent, w = specular shift.
    hair_shading: vec4<f32>,
    // rgb: background colour; w = 1 when the scene's background is an image
    // (`background_image`), 0 for the flat colour.
    background: vec4<f32>,
    // rgb: ambient light.
    ambient: vec4<f32>,
    // xy: render size in pixels; zw: 1 / size.
    screen_size: vec4<f32>,
    // xy: sub-pixel jitter in light-map texels (Sintorn & Assarsson 2009 Fig. 9); z: time in s; w: frame index.
    jitter: vec4<f32>,
    // x, y: camera near and far; z, w: light near and far (world units).
    near_far: vec4<f32>,
    // x: mean hair fragment alpha (material alpha × mean strand alpha), the
    // constant α of order-based blending; y: strands; z: segments.
    hair_stats: vec4<f32>,
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

// The vertex of a triangle covering the whole target (draw 3 vertices).
fn fullscreen_position(vertex_index: u32) -> vec4<f32> {
    let uv = vec2<f32>(f32((vertex_index << 1u) & 2u), f32(vertex_index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}
