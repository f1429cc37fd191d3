// plait::density_volume — the hair density volume shared by the self-shadow
// and ambient-occlusion techniques `density_volume` (binding-free: the
// passes and the provider declare their own buffers).
//
// The box (8 f32, written each frame by density_bounds.wgsl): lo.xyz, the
// resolution R, size.xyz, 0. The grid holds R³ u32,
// x fastest: per voxel q = Σ w · l · |sin(t, L)| / V^(2/3) in units of
// 1 / DENSITY_SCALE — each strand piece inside the voxel (width w, length l,
// tangent t) weighed by its projected area toward the key light L, V the
// voxel's volume. q / V^(1/3) is then the expected number of strands a ray
// toward the light crosses per world unit inside the voxel (a strand's
// shadow is its width whatever its orientation, its length counts as much
// of it as lies across the ray) — the quantity exact self-shadowing counts,
// Σ share over the fragments in front (docs/design.md, "Coverage in the
// light maps").
#define_import_path plait::density_volume

// Fixed point of q: 2^16 per unit (a strand piece crossing a whole voxel
// face-on at w = 1/8 voxel adds 8192). A voxel saturates past 65,535 strand
// widths — the splat counts any add that would wrap (status word 0).
const DENSITY_SCALE: f32 = 65536.0;

struct DensityBox {
    lo: vec3<f32>,
    res: u32,
    size: vec3<f32>,
}

fn density_box_from(words: array<f32, 8>) -> DensityBox {
    return DensityBox(vec3<f32>(words[0], words[1], words[2]), u32(words[3]), vec3<f32>(words[4], words[5], words[6]));
}

// A voxel's edge lengths (world units).
fn density_cell(b: DensityBox) -> vec3<f32> {
    return b.size / f32(max(b.res, 1u));
}

fn density_index(b: DensityBox, v: vec3<u32>) -> u32 {
    return (v.z * b.res + v.y) * b.res + v.x;
}

// The direction toward the key light from `world` (a directional light's
// direction, or toward a spot light's position).
fn density_to_light(world: vec3<f32>, light_direction: vec4<f32>, light_position: vec4<f32>) -> vec3<f32> {
    return select(light_direction.xyz, normalize(light_position.xyz - world), light_direction.w > 0.5);
}

// The parameters t (in units of the segment from o to o + d) where the
// line enters and leaves the box [0, res]³ of grid coordinates; empty when
// x > y.
fn density_clip(o: vec3<f32>, d: vec3<f32>, res: f32) -> vec2<f32> {
    let inv = 1.0 / select(d, vec3<f32>(1e-30), abs(d) < vec3<f32>(1e-30));
    let a = (vec3<f32>(0.0) - o) * inv;
    let b = (vec3<f32>(res) - o) * inv;
    let near = min(a, b);
    let far = max(a, b);
    return vec2<f32>(max(max(near.x, near.y), near.z), min(min(far.x, far.y), far.z));
}
