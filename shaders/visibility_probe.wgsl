// visibility_probe: a data-only compute pass (no Rust) that evaluates the
// pipeline's visibility provider — the same WGSL module the shading passes
// import, chosen by the `visibility` param — on a grid of rays from the light:
// probe p = (ray r, depth step d), p = r · depths + d, rays on a uv grid of
// `rays_x` × `rays_y` over [uv0, uv1], depths evenly from `depth0` to `depth1`
// in the light's NDC depth. `plait ab` uses it for the visibility curves of
// Sintorn & Assarsson 2009 Fig. 5; tests use it against analytic visibility.
#import plait::frame::frame
#import plait::self_shadow::self_shadow

@group(1) @binding(0) var<storage, read_write> probe_out: array<f32>;

struct ProbeParams {
    probe_uv0: vec2<f32>,
    probe_uv1: vec2<f32>,
    probe_rays_x: f32,
    probe_rays_y: f32,
    probe_depths: f32,
    probe_depth0: f32,
    probe_depth1: f32,
}
@group(1) @binding(1) var<uniform> probe_params: ProbeParams;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let p = id.x;
    if (p >= arrayLength(&probe_out)) {
        return;
    }
    let depths = max(u32(probe_params.probe_depths), 1u);
    let rays_x = max(u32(probe_params.probe_rays_x), 1u);
    let d = p % depths;
    let ray = p / depths;
    let cell = vec2<f32>(f32(ray % rays_x), f32(ray / rays_x)) + 0.5;
    let uv = mix(probe_params.probe_uv0, probe_params.probe_uv1, cell / vec2<f32>(f32(rays_x), max(probe_params.probe_rays_y, 1.0)));
    let t = f32(d) / max(f32(depths) - 1.0, 1.0);
    let z = mix(probe_params.probe_depth0, probe_params.probe_depth1, t);
    let world = frame.light_inv_view_proj * vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, z, 1.0);
    probe_out[p] = self_shadow(world.xyz / world.w);
}
