// plait::geometry::wisps — polygon wisps with a strand texture (Halén &
// Wester, "Real-Time Hair Simulation and Visualization for Games", M.Sc.
// thesis, Lund University, 2007, §2.2–2.4). Every hair draw draws the wisps'
// triangles (plait_hair::wisps::WispMesh: two vertices per spine point, even
// = one side, odd = the other; the hair vertex layout's slots hold a
// plait_hair::wisps::WispVertex, read by `wisp_point`). A wisp vertex follows
// the hair vertex it stands for in the scene's `hair_vertices` — the buffer
// simulation, guide interpolation and the head's animation rewrite — so the
// wisps move with the hair. How and why: techniques/geometry/wisps/technique.toml.
#define_import_path plait::geometry::wisps

#import plait::frame::{frame, view_proj}
#import plait::groom_screen::groom_screen_fraction
#import plait::hair_point::HairPoint

struct GeometryParams {
    // A wisp's width across the view (model units).
    wisp_width: f32,
    // The groom's height on screen (fraction of the screen height) from which
    // every wisp is drawn; below it fewer, wider wisps (0: always every wisp).
    wisp_lod_screen_fraction: f32,
}
@group(1) @binding(45) var<uniform> geometry_params: GeometryParams;
// The strand texture and its mip chain side by side (strand_texture.wgsl).
@group(1) @binding(46) var wisp_texture: texture_2d<f32>;
// The drawn hair now (bound by name: the scene's hair vertex buffer).
@group(1) @binding(47) var<storage, read> hair_vertices: array<HairPoint>;

// Every wisp stands for itself in the geometry point's sense: the wisps'
// own level of detail (`wisp_point`) drops and widens them.
fn strand_weight(strand_id: u32) -> f32 {
    return 1.0;
}

// A wisp vertex this frame.
struct WispPoint {
    // Its spine point (the middle of the strip) and its strip's corner.
    spine: vec3<f32>,
    corner: vec3<f32>,
    tangent: vec3<f32>,
    // The hair vertex's alpha and colour now.
    alpha: f32,
    color: vec3<f32>,
    // 1 when drawn, 0 when the wisps' level of detail leaves it out.
    weight: f32,
    // The strand-texture coordinates: u across, v along, mip level.
    texture: vec3<f32>,
    // The strand of the hair vertex it stands for and that strand's first
    // hair vertex; `point` its index along that strand.
    strand: u32,
    first: u32,
    point: f32,
}

// `v` turned by the rotation that takes unit `a` to unit `b` along the
// shortest arc (Rodrigues' formula with c = a × b, d = a · b):
// v + c × v + c × (c × v) / (1 + d). Exactly v when the two are equal; when
// they are opposite the arc's axis is undefined and v is kept.
fn turned(v: vec3<f32>, a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    let c = cross(a, b);
    let d = dot(a, b);
    if (d <= -0.9999) {
        return v;
    }
    return v + cross(c, v) + cross(c, cross(c, v)) / (1.0 + d);
}

fn unit_or(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let l = length(v);
    return select(fallback, v / l, l > 1e-12);
}

// The wisps' level of detail (§2.4: "reducing the number of wisps and at the
// same time increasing their width"): of the mesh's n wisps the first
// m = ceil(k · n) of the dart throwing's acceptance order are drawn, k the
// kept fraction, each n / m times as wide, so m · width' = n · width: the
// wisps cover the area the whole set did. The acceptance order is a
// progressive Poisson-disk sample (every prefix is spread evenly over the
// scalp) and fixed at load: as the groom recedes wisps vanish one by one
// from the end of that order, never a new subset. x = drawn (1) or not (0),
// y = the width factor.
fn wisp_lod(order: f32, count: f32) -> vec2<f32> {
#ifdef LIGHT_VIEW
    // The light's frustum is fitted to the hair: it sees the groom whole.
    return vec2<f32>(1.0, 1.0);
#else
    let f = geometry_params.wisp_lod_screen_fraction;
    let n = max(count, 1.0);
    if (f <= 0.0) {
        return vec2<f32>(1.0, 1.0);
    }
    let k = clamp(groom_screen_fraction() / f, 1.0 / n, 1.0);
    if (k >= 1.0) {
        return vec2<f32>(1.0, 1.0);
    }
    let kept = clamp(ceil(k * n), 1.0, n);
    return vec2<f32>(select(0.0, 1.0, order < kept), n / kept);
#endif
}

// Wisp vertex `index` of wisp `order` (of `count`) standing for hair vertex
// `hair_vertex`, `offset` from it at rest where its tangent was
// `rest_tangent`, `along` its wisp (0 root, 1 tip), at index `point` of its
// strand. The spine point is the hair vertex now plus the offset turned as
// the hair's tangent has turned since rest: the offset (the wisp's guide
// shape moved to its centre, minus the strand there) is kept in the strand's
// frame rather than the world's, so a turned head or a swung strand carries
// it along. A tangent fixes that frame but for a twist about itself, which
// the strands do not carry; the offset is 0 when the wisps follow the groom's
// own strands, so there they follow exactly.
fn wisp_point(offset: vec3<f32>, along: f32, rest_tangent: vec3<f32>, point: f32, order: vec3<f32>, hair_vertex: u32, index: u32) -> WispPoint {
    let hair = hair_vertices[hair_vertex];
    let rest = unit_or(rest_tangent, vec3<f32>(0.0, -1.0, 0.0));
    let now = unit_or(hair.tangent, rest);
    let lod = wisp_lod(order.x, order.y);
    let width = geometry_params.wisp_width * lod.y;
    var p: WispPoint;
    p.spine = hair.position + turned(offset, rest, now);
    // The hair's own tangent, as a strand's vertex passes it on.
    p.tangent = hair.tangent;
    p.corner = wisp_corner(p.spine, hair.tangent, index, width);
    p.alpha = hair.alpha;
    p.color = hair.color;
    p.weight = lod.x;
    p.texture = vec3<f32>(wisp_u(index), along, wisp_level(p.spine, hair.tangent, width));
    p.strand = hair.strand;
    p.point = point;
    p.first = hair_vertex - u32(point);
    return p;
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

// The strip's corner of wisp vertex `index` at spine point `world`, the
// strip `width` wide.
fn wisp_corner(world: vec3<f32>, tangent: vec3<f32>, index: u32, width: f32) -> vec3<f32> {
    let across = select(-0.5, 0.5, (index & 1u) == 1u);
    return world + wisp_side(world, tangent) * across * width;
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

// The mip level whose texels match the wisp's width (`width`) on screen at
// `world`: log2(texels across / pixels across), from the camera's projection.
fn wisp_level(world: vec3<f32>, tangent: vec3<f32>, width: f32) -> f32 {
    let a = frame.camera_view_proj * vec4<f32>(world, 1.0);
    let b = frame.camera_view_proj * vec4<f32>(world + wisp_side(world, tangent) * width, 1.0);
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
