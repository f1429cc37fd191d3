// plait::self_shadow — the visibility provider a pass's `visibility` param
// names (`#ifdef VISIBILITY_<NAME>`), behind one function. Every pass that
// needs hair self-shadowing imports this module, so a new provider is one
// module in shaders/lib/visibility/ plus one line here.
#define_import_path plait::self_shadow

#ifdef VISIBILITY_MODIFIED_SHADOW_MAP
#import plait::visibility::modified_shadow_map::hair_visibility
#else ifdef VISIBILITY_OCCUPANCY
#import plait::visibility::occupancy::hair_visibility
#else ifdef VISIBILITY_DEEP_OPACITY
#import plait::visibility::deep_opacity::hair_visibility
#else ifdef VISIBILITY_OPACITY_SHADOW_MAPS
#import plait::visibility::opacity_shadow_maps::hair_visibility
#else ifdef VISIBILITY_DENSITY_CLUSTERING
#import plait::visibility::density_clustering::hair_visibility
#else ifdef VISIBILITY_EXACT
#import plait::visibility::exact::hair_visibility
#else ifdef VISIBILITY_TRESSFX
#import plait::visibility::tressfx::hair_visibility
#else
#import plait::visibility::none::hair_visibility
#endif

// Fraction of the light reaching `world` through the hair (1 = unshadowed).
fn self_shadow(world: vec3<f32>) -> f32 {
    return hair_visibility(world);
}
