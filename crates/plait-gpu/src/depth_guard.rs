//! The engine's guarantee that a raster pass's storage writes respect its
//! depth test.
//!
//! A fragment shader that writes storage (atomics into occupancy bits, slab
//! counts, fragment lists) performs those writes even when the depth test that
//! runs *after* it then rejects the fragment: hair hidden behind the head would
//! be counted. No pass author should have to remember this, so the engine
//! decides it here, once, for built-in and data-only passes alike:
//!
//! - with `SHADER_EARLY_DEPTH_TEST` (Vulkan, GLES 3.1+) the fragment entry
//!   point gets `@early_depth_test(force)`: the test runs before the shader;
//! - otherwise the shader gets a test of its own at its first statement: the
//!   pass's depth attachment is also bound as a texture
//!   ([`GUARD_BINDING`] of group 1) and a fragment that fails the pass's
//!   compare function is discarded (a discarded invocation writes no storage).

use naga::{
    AddressSpace, BinaryOperator, Binding, BuiltIn, Expression, ImageClass, ImageDimension,
    Literal, ResourceBinding, Scalar, ScalarKind, ShaderStage, Span, Statement, SwizzleComponent,
    Type, TypeInner, VectorSize,
};

/// Group 1 binding of the depth texture the in-shader test reads: far above
/// any binding a pass author writes, and below WebGPU's (and wgpu's GL)
/// `maxBindingsPerBindGroup` of 1000 — binding numbers must be less than it,
/// and these adapters are the ones without an early depth test that need
/// the guard (1000 was refused in a browser).
pub const GUARD_BINDING: u32 = 999;

/// How a pass's storage writes are kept to fragments that pass its depth test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthGuard {
    /// Nothing to guard: no depth test, or no storage writes.
    Unneeded,
    /// `@early_depth_test(force)` on the fragment entry point.
    EarlyTest,
    /// A test of the attachment's depth at the top of the fragment shader.
    InShader(wgpu::CompareFunction),
}

impl DepthGuard {
    /// The guard for a raster pass with a depth test of `compare` (if any) whose
    /// shader writes storage (`writes_storage`).
    pub fn choose(
        compare: Option<wgpu::CompareFunction>,
        writes_storage: bool,
        early_depth_test: bool,
    ) -> DepthGuard {
        match compare {
            Some(c) if writes_storage && c != wgpu::CompareFunction::Always => {
                if early_depth_test {
                    DepthGuard::EarlyTest
                } else {
                    DepthGuard::InShader(c)
                }
            }
            _ => DepthGuard::Unneeded,
        }
    }

    /// Apply the guard to the composed module's fragment entry point.
    pub fn apply(self, module: &mut naga::Module) {
        match self {
            DepthGuard::Unneeded => {}
            DepthGuard::EarlyTest => {
                for ep in module
                    .entry_points
                    .iter_mut()
                    .filter(|e| e.stage == ShaderStage::Fragment)
                {
                    ep.early_depth_test = Some(naga::EarlyDepthTest::Force);
                }
            }
            DepthGuard::InShader(compare) => insert_depth_test(module, compare),
        }
    }
}

/// The comparison that *rejects* a fragment of depth `z` against the stored
/// depth, for a pass whose depth test is `compare`; `None` never rejects.
fn reject_op(compare: wgpu::CompareFunction) -> Option<BinaryOperator> {
    use wgpu::CompareFunction as C;
    Some(match compare {
        C::Less => BinaryOperator::GreaterEqual,
        C::LessEqual => BinaryOperator::Greater,
        C::Greater => BinaryOperator::LessEqual,
        C::GreaterEqual => BinaryOperator::Less,
        C::Equal => BinaryOperator::NotEqual,
        C::NotEqual => BinaryOperator::Equal,
        C::Always => return None,
        C::Never => BinaryOperator::Equal, // with z == z below: always rejects
    })
}

/// `if (position.z <reject> textureLoad(guard, vec2<i32>(position.xy), 0)) { discard; }`
/// as the first statement of every fragment entry point.
fn insert_depth_test(module: &mut naga::Module, compare: wgpu::CompareFunction) {
    let Some(op) = reject_op(compare) else {
        return;
    };
    let depth_ty = module.types.insert(
        Type {
            name: None,
            inner: TypeInner::Image {
                dim: ImageDimension::D2,
                arrayed: false,
                class: ImageClass::Depth { multi: false },
            },
        },
        Span::UNDEFINED,
    );
    let position_ty = module.types.insert(
        Type {
            name: None,
            inner: TypeInner::Vector {
                size: VectorSize::Quad,
                scalar: Scalar::F32,
            },
        },
        Span::UNDEFINED,
    );
    let guard = module.global_variables.append(
        naga::GlobalVariable {
            name: Some("plait_depth_guard".into()),
            space: AddressSpace::Handle,
            binding: Some(ResourceBinding {
                group: 1,
                binding: GUARD_BINDING,
            }),
            ty: depth_ty,
            init: None,
            memory_decorations: Default::default(),
        },
        Span::UNDEFINED,
    );
    for ep in module
        .entry_points
        .iter_mut()
        .filter(|e| e.stage == ShaderStage::Fragment)
    {
        let f = &mut ep.function;
        // The fragment position: an argument of its own, a member of a struct
        // argument, or (when the shader never reads it) a new argument.
        let is_position =
            |b: &Option<Binding>| matches!(b, Some(Binding::BuiltIn(BuiltIn::Position { .. })));
        let mut direct = f.arguments.iter().position(|a| is_position(&a.binding));
        let mut member = None;
        if direct.is_none() {
            for (i, a) in f.arguments.iter().enumerate() {
                if let TypeInner::Struct { members, .. } = &module.types[a.ty].inner
                    && let Some(m) = members.iter().position(|m| is_position(&m.binding))
                {
                    member = Some((i, m as u32));
                    break;
                }
            }
        }
        if direct.is_none() && member.is_none() {
            f.arguments.push(naga::FunctionArgument {
                name: Some("plait_position".into()),
                ty: position_ty,
                binding: Some(Binding::BuiltIn(BuiltIn::Position { invariant: false })),
            });
            direct = Some(f.arguments.len() - 1);
        }
        let e = &mut f.expressions;
        let append = |e: &mut naga::Arena<Expression>, x| e.append(x, Span::UNDEFINED);
        // Expressions that need no Emit first, then one contiguous emitted range.
        let (arg_index, access) = match (direct, member) {
            (Some(i), _) => (i, None),
            (None, Some((i, m))) => (i, Some(m)),
            _ => unreachable!("a position argument was found or added"),
        };
        let arg = append(e, Expression::FunctionArgument(arg_index as u32));
        let image = append(e, Expression::GlobalVariable(guard));
        let level = append(e, Expression::Literal(Literal::I32(0)));
        // A direct argument is already a value; a struct member needs an
        // AccessIndex, which (unlike the argument) must be emitted.
        let member_access = access.map(|m| {
            append(
                e,
                Expression::AccessIndex {
                    base: arg,
                    index: m,
                },
            )
        });
        let position = member_access.unwrap_or(arg);
        let z = append(
            e,
            Expression::AccessIndex {
                base: position,
                index: 2,
            },
        );
        let xy = append(
            e,
            Expression::Swizzle {
                size: VectorSize::Bi,
                vector: position,
                pattern: [
                    SwizzleComponent::X,
                    SwizzleComponent::Y,
                    SwizzleComponent::X,
                    SwizzleComponent::X,
                ],
            },
        );
        let texel = append(
            e,
            Expression::As {
                expr: xy,
                kind: ScalarKind::Sint,
                convert: Some(4),
            },
        );
        let stored = append(
            e,
            Expression::ImageLoad {
                image,
                coordinate: texel,
                array_index: None,
                sample: None,
                level: Some(level),
            },
        );
        let (left, right) = if compare == wgpu::CompareFunction::Never {
            (z, z)
        } else {
            (z, stored)
        };
        let rejected = append(e, Expression::Binary { op, left, right });
        let emit_start = member_access.unwrap_or(z);
        let test = vec![
            Statement::Emit(naga::Range::new_from_bounds(emit_start, rejected)),
            Statement::If {
                condition: rejected,
                accept: naga::Block::from_vec(vec![Statement::Kill]),
                reject: naga::Block::new(),
            },
        ];
        let mut body = std::mem::take(&mut f.body);
        let mut guarded = naga::Block::from_vec(test);
        guarded.append(&mut body);
        f.body = guarded;
    }
}
