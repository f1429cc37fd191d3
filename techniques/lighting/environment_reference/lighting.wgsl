// plait::lighting::environment_reference — environment light by brute force
// (Xing et al. 2012 Fig. 3a, 3c): every texel of the environment cube is a
// directional light of irradiance L·Ω (its mean radiance times its solid
// angle, on a surface facing it), reflected by the chosen fibre's own
// response to a light, the shading point's `shade_direct` (S·cos θi per unit
// irradiance; techniques/shading/point.toml), at the fragment's tangent and
// eye. So it is the sum the environment integral ∫ S·cos θi·L dωi is for
// every shading technique (Kajiya-Kay, Marschner, Chiang), with no map
// resolution and no interpolation: the ground truth of irradiance_maps and
// sh_irradiance_maps. Its cost is one loop over the 6·s² texels per
// fragment, each a key-light evaluation of the fibre (chiang's a 64-point
// mean over the width: the size check in crates/plait-passes/src/lighting.rs
// counts it).
#define_import_path plait::lighting::environment_reference

#import plait::cube::cube_texel_direction
#import plait::shading::shade_direct

@group(1) @binding(32) var light_environment: texture_2d<f32>;

fn hair_environment(world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let t = normalize(tangent);
    let dims = textureDimensions(light_environment);
    var sum = vec3<f32>(0.0);
    for (var y = 0u; y < dims.y; y++) {
        for (var x = 0u; x < dims.x; x++) {
            let texel = textureLoad(light_environment, vec2<u32>(x, y), 0);
            let light = cube_texel_direction(vec2<u32>(x, y), dims.y);
            sum += shade_direct(t, light, to_eye, base) * (texel.rgb * texel.a);
        }
    }
    return sum;
}
