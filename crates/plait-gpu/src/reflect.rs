//! What a shader binds, read from naga's IR: the basis of checking a pipeline
//! file against its shaders without a GPU, and of building bind group layouts.

use naga::{AddressSpace, ImageClass, Module, ScalarKind, StorageAccess, TypeInner};
use plait_graph::{Format, ResourceKind, Value};

/// The kind of one shader binding.
#[derive(Clone, Debug, PartialEq)]
pub enum BindingKind {
    Uniform {
        size: u64,
    },
    Storage {
        read_only: bool,
        min_size: u64,
    },
    Texture {
        sample: TextureSample,
        multisampled: bool,
        arrayed: bool,
    },
    StorageTexture {
        format: Option<Format>,
        access_write: bool,
        access_read: bool,
        arrayed: bool,
    },
    Sampler {
        comparison: bool,
    },
    /// `acceleration_structure` (ray queries): the strands' structure.
    AccelerationStructure,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureSample {
    Float,
    Uint,
    Sint,
    Depth,
}

/// One `@group(g) @binding(b) var name: T` of a shader.
#[derive(Clone, Debug)]
pub struct ShaderBinding {
    pub name: String,
    pub group: u32,
    pub binding: u32,
    pub kind: BindingKind,
}

impl ShaderBinding {
    /// Texture or buffer, or `None` for samplers.
    pub fn resource_kind(&self) -> Option<ResourceKind> {
        match self.kind {
            BindingKind::Uniform { .. } | BindingKind::Storage { .. } => Some(ResourceKind::Buffer),
            BindingKind::Texture { .. } | BindingKind::StorageTexture { .. } => {
                Some(ResourceKind::Texture)
            }
            BindingKind::Sampler { .. } => None,
            BindingKind::AccelerationStructure => Some(ResourceKind::AccelerationStructure),
        }
    }

    /// Whether the shader can write through this binding.
    pub fn writes(&self) -> bool {
        match self.kind {
            BindingKind::Storage { read_only, .. } => !read_only,
            BindingKind::StorageTexture { access_write, .. } => access_write,
            _ => false,
        }
    }

    /// Whether a resource of `format` can be bound here; `Err` says why not.
    pub fn accepts_format(&self, format: Format) -> Result<(), String> {
        match &self.kind {
            BindingKind::Texture { sample, .. } => {
                let ok = match sample {
                    TextureSample::Float => {
                        !format.is_depth()
                            && format.sample_type() == plait_graph::format::SampleType::Float
                    }
                    TextureSample::Uint => {
                        format.sample_type() == plait_graph::format::SampleType::Uint
                    }
                    TextureSample::Sint => false,
                    TextureSample::Depth => format.is_depth(),
                };
                if ok {
                    Ok(())
                } else {
                    Err(format!(
                        "the shader samples it as {sample:?}, which {format} is not"
                    ))
                }
            }
            BindingKind::StorageTexture {
                format: Some(want), ..
            } if *want != format => Err(format!("{}{want}", crate::pass::storage_format::STORAGE)),
            BindingKind::StorageTexture { format: None, .. } => {
                Err("the shader's storage texture format is not one plait supports".into())
            }
            _ => Ok(()),
        }
    }
}

fn storage_format(f: naga::StorageFormat) -> Option<Format> {
    use naga::StorageFormat as S;
    Some(match f {
        S::R32Float => Format::R32Float,
        S::Rg32Float => Format::Rg32Float,
        S::Rgba32Float => Format::Rgba32Float,
        S::R32Uint => Format::R32Uint,
        S::Rg32Uint => Format::Rg32Uint,
        S::Rgba32Uint => Format::Rgba32Uint,
        S::Rgba16Float => Format::Rgba16Float,
        S::Rgba8Unorm => Format::Rgba8Unorm,
        S::R8Unorm => Format::R8Unorm,
        S::R16Float => Format::R16Float,
        S::Rg16Float => Format::Rg16Float,
        _ => return None,
    })
}

/// naga_oil renames items imported from a module to `nameX_naga_oil_mod_X<path>X`;
/// bindings are matched by the name the author wrote.
pub fn plain_name(name: &str) -> &str {
    name.split("X_naga_oil_mod_X").next().unwrap_or(name)
}

/// Every resource binding of a module, sorted by group and binding.
pub fn bindings(module: &Module) -> Vec<ShaderBinding> {
    let mut out = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let Some(rb) = &var.binding else { continue };
        let name = plain_name(var.name.as_deref().unwrap_or_default()).to_owned();
        let inner = &module.types[var.ty].inner;
        let kind = match (var.space, inner) {
            (AddressSpace::Uniform, _) => BindingKind::Uniform {
                size: inner.size(module.to_ctx()) as u64,
            },
            (AddressSpace::Storage { access }, _) => BindingKind::Storage {
                read_only: !access.contains(StorageAccess::STORE),
                min_size: inner.size(module.to_ctx()) as u64,
            },
            (
                _,
                TypeInner::Image {
                    dim: _,
                    arrayed,
                    class,
                },
            ) => match *class {
                ImageClass::Sampled { kind, multi } => BindingKind::Texture {
                    sample: match kind {
                        ScalarKind::Uint => TextureSample::Uint,
                        ScalarKind::Sint => TextureSample::Sint,
                        _ => TextureSample::Float,
                    },
                    multisampled: multi,
                    arrayed: *arrayed,
                },
                ImageClass::Depth { multi } => BindingKind::Texture {
                    sample: TextureSample::Depth,
                    multisampled: multi,
                    arrayed: *arrayed,
                },
                ImageClass::Storage { format, access } => BindingKind::StorageTexture {
                    format: storage_format(format),
                    access_write: access.contains(StorageAccess::STORE)
                        || access.contains(StorageAccess::ATOMIC),
                    access_read: access.contains(StorageAccess::LOAD),
                    arrayed: *arrayed,
                },
                ImageClass::External => continue,
            },
            (_, TypeInner::Sampler { comparison }) => BindingKind::Sampler {
                comparison: *comparison,
            },
            (_, TypeInner::AccelerationStructure { .. }) => BindingKind::AccelerationStructure,
            _ => continue,
        };
        out.push(ShaderBinding {
            name,
            group: rb.group,
            binding: rb.binding,
            kind,
        });
    }
    out.sort_by_key(|b| (b.group, b.binding));
    out
}

/// Resource bindings of a module that [`bindings`] leaves out because plait
/// cannot bind them to a pass: (name, group, binding, what it is). Reported
/// by the binding plan, so `plait check` refuses such a shader instead of
/// the render failing at pipeline creation with wgpu's "binding is missing
/// from the pipeline layout".
pub fn unbindable(module: &Module) -> Vec<(String, u32, u32, &'static str)> {
    let mut out = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let Some(rb) = &var.binding else { continue };
        let what = match &module.types[var.ty].inner {
            TypeInner::Image {
                class: ImageClass::External,
                ..
            } => "an external texture",
            TypeInner::BindingArray { .. } => "a binding array",
            _ => continue,
        };
        let name = plain_name(var.name.as_deref().unwrap_or_default()).to_owned();
        out.push((name, rb.group, rb.binding, what));
    }
    out
}

/// A member of a shader's `params` uniform struct.
#[derive(Clone, Debug)]
pub struct ParamMember {
    pub name: String,
    pub offset: u32,
    pub ty: ParamScalar,
    /// 1 for scalars, 2–4 for vectors.
    pub components: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamScalar {
    F32,
    I32,
    U32,
}

/// The layout of the uniform struct `name` of a module, if it has one.
pub fn params_layout(module: &Module, name: &str) -> Option<(u64, Vec<ParamMember>)> {
    let (_, var) = module.global_variables.iter().find(|(_, v)| {
        v.name.as_deref().map(plain_name) == Some(name) && v.space == AddressSpace::Uniform
    })?;
    let ty = &module.types[var.ty];
    let TypeInner::Struct { members, span } = &ty.inner else {
        return None;
    };
    let mut out = Vec::new();
    for m in members {
        let (scalar, components) = match &module.types[m.ty].inner {
            TypeInner::Scalar(s) => (s.kind, 1),
            TypeInner::Vector { size, scalar } => (scalar.kind, *size as u32),
            _ => continue,
        };
        let ty = match scalar {
            ScalarKind::Float => ParamScalar::F32,
            ScalarKind::Sint => ParamScalar::I32,
            ScalarKind::Uint => ParamScalar::U32,
            _ => continue,
        };
        out.push(ParamMember {
            name: m.name.clone().unwrap_or_default(),
            offset: m.offset,
            ty,
            components,
        });
    }
    Some((*span as u64, out))
}

/// Pack pass params into the bytes of a `params` uniform; `Err` names a member
/// the pass does not provide or cannot convert.
pub fn pack_params(
    size: u64,
    members: &[ParamMember],
    values: &indexmap::IndexMap<String, Value>,
) -> Result<Vec<u8>, String> {
    let mut bytes = vec![0u8; size as usize];
    for m in members {
        let Some(value) = values.get(&m.name) else {
            return Err(format!(
                "the shader's `params.{}` has no pass param of that name",
                m.name
            ));
        };
        let scalars: Vec<f64> = match value {
            Value::List(items) => items.iter().filter_map(Value::as_f64).collect(),
            Value::Bool(b) => vec![if *b { 1.0 } else { 0.0 }],
            v => v.as_f64().into_iter().collect(),
        };
        if scalars.len() != m.components as usize {
            return Err(format!(
                "param `{}` = {value} does not fit the shader's {}-component member",
                m.name, m.components
            ));
        }
        for (i, x) in scalars.iter().enumerate() {
            let at = m.offset as usize + i * 4;
            let word = match m.ty {
                ParamScalar::F32 => (*x as f32).to_le_bytes(),
                ParamScalar::I32 => (*x as i32).to_le_bytes(),
                ParamScalar::U32 => (*x as u32).to_le_bytes(),
            };
            bytes[at..at + 4].copy_from_slice(&word);
        }
    }
    Ok(bytes)
}
