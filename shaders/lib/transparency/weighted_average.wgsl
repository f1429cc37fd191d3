// plait::transparency::weighted_average — weighted-average blending
// (Bavoil & Myers 2008, as summarised in Sintorn & Assarsson 2009 §2.2):
// one unsorted additive pass sums α·rgb and α into `color` and the depth
// complexity n into `count`; the resolve pass averages.
#define_import_path plait::transparency::weighted_average

struct FragmentOut {
    @location(0) color: vec4<f32>,
    @location(1) count: vec4<f32>,
}

fn hair_fragment(clip: vec4<f32>, rgb: vec3<f32>, alpha: f32) -> FragmentOut {
    return FragmentOut(vec4<f32>(rgb * alpha, alpha), vec4<f32>(1.0, 0.0, 0.0, 0.0));
}
