//! The default pipeline's ten passes as data written by hand: shader file,
//! defines, group-1 bindings, targets, depth state and clears of each —
//! what plait derives from `pipelines/occupancy.toml`, its techniques and
//! the pass library.

#[derive(Clone, Copy)]
pub enum Geometry {
    Hair,
    Opaque,
    Fullscreen,
}

/// A group-1 binding: its number, layout type and the resource it takes.
pub struct Bind {
    pub binding: u32,
    pub ty: wgpu::BindingType,
    pub resource: &'static str,
}

fn texture(binding: u32, sample_type: wgpu::TextureSampleType, resource: &'static str) -> Bind {
    Bind {
        binding,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        resource,
    }
}

/// rg32float and rgba32float cannot be filtered without an optional feature.
fn float_texture(binding: u32, resource: &'static str) -> Bind {
    texture(
        binding,
        wgpu::TextureSampleType::Float { filterable: false },
        resource,
    )
}

fn depth_texture(binding: u32, resource: &'static str) -> Bind {
    texture(binding, wgpu::TextureSampleType::Depth, resource)
}

fn storage(binding: u32, read_only: bool, resource: &'static str) -> Bind {
    Bind {
        binding,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        resource,
    }
}

fn uniform(binding: u32, resource: &'static str) -> Bind {
    Bind {
        binding,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        resource,
    }
}

/// The light maps as the occupancy visibility provider binds them (8–15).
fn light_maps() -> Vec<Bind> {
    vec![
        float_texture(9, "light_range"),
        storage(10, true, "light_bits"),
        storage(11, true, "light_slabs"),
        uniform(15, "visibility_params"),
    ]
}

/// (texture, format, blend, write mask, cleared to)
pub type ColorTarget = (
    &'static str,
    wgpu::TextureFormat,
    Option<wgpu::BlendState>,
    wgpu::ColorWrites,
    Option<wgpu::Color>,
);

/// What one hand-written pass is.
pub struct PassDesc {
    pub name: &'static str,
    /// A pass type's shader in `shaders/passes/`, or a technique's own
    /// (a path from the repository root, as the search path holds it).
    pub shader: &'static str,
    pub defines: &'static [&'static str],
    pub geometry: Geometry,
    pub binds: Vec<Bind>,
    pub colors: Vec<ColorTarget>,
    /// (texture, compare, written, cleared to)
    pub depth: Option<(&'static str, wgpu::CompareFunction, bool, Option<f32>)>,
    /// Storage buffers zeroed before the pass.
    pub clears: &'static [&'static str],
    /// `@early_depth_test(force)`: storage writes only for fragments that
    /// pass the depth test (what plait's depth guard does on Vulkan).
    pub early_depth_test: bool,
}

/// The ten passes of `occupancy.toml`, in its schedule's order.
pub fn passes() -> Vec<PassDesc> {
    use wgpu::CompareFunction::{Greater, Less};
    let red = wgpu::ColorWrites::RED;
    let green = wgpu::ColorWrites::GREEN;
    let all = wgpu::ColorWrites::ALL;
    let far_clear = wgpu::Color {
        r: 1.0,
        g: 0.0,
        b: 0.0,
        a: 0.0,
    };
    let additive = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    };
    let additive = Some(wgpu::BlendState {
        color: additive,
        alpha: additive,
    });
    let range = wgpu::TextureFormat::Rg32Float;
    // Depth range: near (Less, red) then far (Greater, green), one scratch depth.
    let range_pair = |prefix: &'static str,
                      range_tex: &'static str,
                      scratch: &'static str,
                      opaque: &'static str,
                      defines: &'static [&'static str]| {
        [
            PassDesc {
                name: prefix,
                shader: "depth_range.wgsl",
                defines,
                geometry: Geometry::Hair,
                binds: vec![depth_texture(0, opaque)],
                colors: vec![(range_tex, range, None, red, Some(far_clear))],
                depth: Some((scratch, Less, true, Some(1.0))),
                clears: &[],
                early_depth_test: false,
            },
            PassDesc {
                name: prefix,
                shader: "depth_range.wgsl",
                defines,
                geometry: Geometry::Hair,
                binds: vec![depth_texture(0, opaque)],
                colors: vec![(range_tex, range, None, green, None)],
                depth: Some((scratch, Greater, true, Some(0.0))),
                clears: &[],
                early_depth_test: false,
            },
        ]
    };
    let map = |name: &'static str,
               shader: &'static str,
               range_tex: &'static str,
               out: &'static str,
               depth: &'static str,
               clears: &'static [&'static str],
               defines: &'static [&'static str]| PassDesc {
        name,
        shader,
        defines,
        geometry: Geometry::Hair,
        binds: vec![float_texture(0, range_tex), storage(1, false, out)],
        colors: vec![],
        depth: Some((depth, Less, false, None)),
        clears,
        early_depth_test: true,
    };
    let light: &'static [&'static str] = &["LIGHT_VIEW"];
    let mut passes = vec![PassDesc {
        name: "opaque_shadow",
        shader: "shadow_map.wgsl",
        defines: &["LIGHT_VIEW", "DRAW_OPAQUE"],
        geometry: Geometry::Opaque,
        binds: vec![],
        colors: vec![],
        depth: Some(("opaque_shadow", Less, true, Some(1.0))),
        clears: &[],
        early_depth_test: false,
    }];
    passes.extend(range_pair(
        "light_range",
        "light_range",
        "light_scratch",
        "opaque_shadow",
        light,
    ));
    passes.push(map(
        "light_occupancy",
        "occupancy.wgsl",
        "light_range",
        "light_bits",
        "opaque_shadow",
        &["light_bits"],
        light,
    ));
    passes.push(map(
        "light_slabs",
        "slice_counts.wgsl",
        "light_range",
        "light_slabs",
        "opaque_shadow",
        &["light_slabs"],
        light,
    ));
    let mut opaque_binds = vec![depth_texture(0, "opaque_shadow")];
    opaque_binds.extend(light_maps());
    passes.push(PassDesc {
        name: "opaque",
        shader: "opaque_shade.wgsl",
        defines: &["SELF_SHADOW_OCCUPANCY", "DRAW_OPAQUE"],
        geometry: Geometry::Opaque,
        binds: opaque_binds,
        colors: vec![(
            "scene",
            wgpu::TextureFormat::Rgba16Float,
            None,
            all,
            Some(wgpu::Color::TRANSPARENT),
        )],
        depth: Some(("depth", Less, true, Some(1.0))),
        clears: &[],
        early_depth_test: false,
    });
    passes.extend(range_pair(
        "camera_range",
        "camera_range",
        "camera_scratch",
        "depth",
        &[],
    ));
    passes.push(map(
        "camera_occupancy",
        "occupancy.wgsl",
        "camera_range",
        "camera_bits",
        "depth",
        &["camera_bits"],
        &[],
    ));
    passes.push(map(
        "camera_slabs",
        "slice_counts.wgsl",
        "camera_range",
        "camera_slabs",
        "depth",
        &["camera_slabs"],
        &[],
    ));
    // Σα and n per pixel: the pixel's mean alpha (occupancy_order.toml).
    passes.push(PassDesc {
        name: "camera_alpha",
        shader: "alpha_sum.wgsl",
        defines: &[],
        geometry: Geometry::Hair,
        binds: vec![],
        colors: vec![(
            "camera_alpha",
            wgpu::TextureFormat::Rg32Float,
            additive,
            all,
            Some(wgpu::Color::TRANSPARENT),
        )],
        depth: Some(("depth", Less, false, None)),
        clears: &[],
        early_depth_test: false,
    });
    let mut hair_binds = vec![depth_texture(0, "opaque_shadow")];
    hair_binds.extend(light_maps());
    hair_binds.extend([
        float_texture(60, "camera_range"),
        storage(61, true, "camera_bits"),
        storage(62, true, "camera_slabs"),
        float_texture(63, "camera_alpha"),
    ]);
    // The transparency technique's own hair pass (its slots start at 60).
    passes.push(PassDesc {
        name: "hair",
        shader: "techniques/transparency/occupancy_order/hair.wgsl",
        defines: &[
            "SELF_SHADOW_OCCUPANCY",
            "SHADING_SPACE_FRAGMENT",
            "SHADING_KAJIYA_KAY",
            "LIGHTING_AMBIENT",
            "AMBIENT_OCCLUSION_NONE",
            "MEAN_ALPHA_PIXEL",
        ],
        geometry: Geometry::Hair,
        binds: hair_binds,
        colors: vec![(
            "hair",
            wgpu::TextureFormat::Rgba32Float,
            additive,
            all,
            Some(wgpu::Color::TRANSPARENT),
        )],
        depth: Some(("depth", Less, false, None)),
        clears: &[],
        early_depth_test: false,
    });
    passes.push(PassDesc {
        name: "compose",
        shader: "compose.wgsl",
        defines: &["MEAN_ALPHA_PIXEL"],
        geometry: Geometry::Fullscreen,
        binds: vec![
            float_texture(0, "hair"),
            float_texture(1, "scene"),
            storage(2, true, "camera_slabs"),
            float_texture(3, "camera_alpha"),
        ],
        colors: vec![(
            "final",
            wgpu::TextureFormat::Rgba8UnormSrgb,
            None,
            all,
            Some(wgpu::Color::TRANSPARENT),
        )],
        depth: None,
        clears: &[],
        early_depth_test: false,
    });
    passes
}
