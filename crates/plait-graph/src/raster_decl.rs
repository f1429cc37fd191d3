//! The fixed-function state of a data-only raster pass, as written in TOML:
//!
//! ```toml
//! depth = { compare = "less", write = false }   # the depth test (and whether it writes)
//! blend = { accum = "additive", color = "over" } # per colour-target slot: a preset…
//! blend = { color = { color = { src = "one", dst = "one_minus_src_alpha", op = "add" },
//!                     alpha = { src = "one", dst = "one", op = "add" } } }   # …or factors
//! cull = "back"                                  # none | front | back
//! alpha_to_coverage = true                        # alpha picks the MSAA samples covered
//! loads = ["color", "depth"]                      # attachments drawn over, not cleared
//! ```
//!
//! The same keys are read from a `[passes.NAME]` table of a pipeline and from
//! a pass-type file (`shaders/passes/*.toml`), so both say state one way. No
//! wgpu here: the GPU crate maps each variant one to one.

use indexmap::IndexMap;

use crate::error::{Error, Location, Spanned};
use crate::load::{Entry, Node, Table};
use crate::node_reader::Reader;

/// The keys of a pass table that hold raster state.
pub const RASTER_KEYS: &[&str] = &["depth", "blend", "cull", "alpha_to_coverage", "loads"];

/// `name = "text"` enums with their TOML spelling, listed for messages.
macro_rules! named_enum {
    ($(#[$doc:meta])* $name:ident { $($(#[$vdoc:meta])* $variant:ident = $text:literal),+ $(,)? }) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum $name { $($(#[$vdoc])* $variant),+ }

        impl $name {
            pub const NAMES: &'static [&'static str] = &[$($text),+];
            pub fn name(self) -> &'static str {
                match self { $($name::$variant => $text),+ }
            }
            pub fn from_name(text: &str) -> Option<Self> {
                match text { $($text => Some($name::$variant),)+ _ => None }
            }
        }
    };
}

named_enum!(
    /// A depth compare function (WebGPU's names).
    Compare {
        Never = "never",
        Less = "less",
        Equal = "equal",
        LessEqual = "less_equal",
        Greater = "greater",
        NotEqual = "not_equal",
        GreaterEqual = "greater_equal",
        Always = "always",
    }
);

named_enum!(
    /// Which triangle faces are not drawn.
    Cull { None = "none", Front = "front", Back = "back" }
);

named_enum!(
    /// Named blend states, the ones plait's passes use.
    BlendPreset {
        /// No blending: the fragment replaces the target.
        Replace = "replace",
        /// dst + src, colour and alpha (accumulation targets).
        Additive = "additive",
        /// Premultiplied src over dst: dst·(1 - src.a) + src.
        Over = "over",
        /// Premultiplied src under dst, front to back: dst + src·(1 - dst.a).
        Under = "under",
        /// Straight (not premultiplied) alpha: src·src.a + dst·(1 - src.a).
        Alpha = "alpha",
        /// Per-channel minimum / maximum of src and dst.
        Min = "min",
        Max = "max",
    }
);

named_enum!(
    /// A blend factor (WebGPU's names).
    BlendFactor {
        Zero = "zero",
        One = "one",
        Src = "src",
        OneMinusSrc = "one_minus_src",
        SrcAlpha = "src_alpha",
        OneMinusSrcAlpha = "one_minus_src_alpha",
        Dst = "dst",
        OneMinusDst = "one_minus_dst",
        DstAlpha = "dst_alpha",
        OneMinusDstAlpha = "one_minus_dst_alpha",
    }
);

named_enum!(
    /// A blend operation.
    BlendOp {
        Add = "add",
        Subtract = "subtract",
        ReverseSubtract = "reverse_subtract",
        Min = "min",
        Max = "max",
    }
);

/// One channel group of a blend state: `src ⊙ factor <op> dst ⊙ factor`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BlendComponent {
    pub src: BlendFactor,
    pub dst: BlendFactor,
    pub op: BlendOp,
}

/// The blend of one colour target.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Blend {
    Preset(BlendPreset),
    Factors {
        color: BlendComponent,
        alpha: BlendComponent,
    },
}

impl Blend {
    /// The colour and alpha components; `None` for `replace`.
    pub fn components(self) -> Option<(BlendComponent, BlendComponent)> {
        use BlendFactor as F;
        let both = |src, dst, op| {
            let c = BlendComponent { src, dst, op };
            Some((c, c))
        };
        match self {
            Blend::Factors { color, alpha } => Some((color, alpha)),
            Blend::Preset(p) => match p {
                BlendPreset::Replace => None,
                BlendPreset::Additive => both(F::One, F::One, BlendOp::Add),
                BlendPreset::Over => both(F::One, F::OneMinusSrcAlpha, BlendOp::Add),
                BlendPreset::Under => both(F::OneMinusDstAlpha, F::One, BlendOp::Add),
                BlendPreset::Alpha => Some((
                    BlendComponent {
                        src: F::SrcAlpha,
                        dst: F::OneMinusSrcAlpha,
                        op: BlendOp::Add,
                    },
                    BlendComponent {
                        src: F::One,
                        dst: F::OneMinusSrcAlpha,
                        op: BlendOp::Add,
                    },
                )),
                BlendPreset::Min => both(F::One, F::One, BlendOp::Min),
                BlendPreset::Max => both(F::One, F::One, BlendOp::Max),
            },
        }
    }
}

/// The depth test of a raster pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DepthDecl {
    pub compare: Compare,
    /// `None`: write when the depth target is bound under `writes`.
    pub write: Option<bool>,
}

/// Raster state keys of one pass (or pass type), each with where it was written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RasterDecl {
    pub depth: Option<Spanned<DepthDecl>>,
    /// Per colour-target slot, in file order.
    pub blend: IndexMap<String, Spanned<Blend>>,
    pub cull: Option<Spanned<Cull>>,
    /// The fragment's alpha sets its MSAA sample mask (needs a multisampled
    /// colour target).
    pub alpha_to_coverage: Option<Spanned<bool>>,
    /// Written attachment slots whose contents the pass keeps (it draws over
    /// them) instead of clearing them first.
    pub loads: Vec<Spanned<String>>,
}

impl RasterDecl {
    pub fn is_empty(&self) -> bool {
        self.depth.is_none()
            && self.blend.is_empty()
            && self.cull.is_none()
            && self.alpha_to_coverage.is_none()
            && self.loads.is_empty()
    }

    /// Whether the pass keeps the contents of the written slot `slot`.
    pub fn keeps(&self, slot: &str) -> bool {
        self.loads.iter().any(|l| l.value == slot)
    }

    /// `self` with every key `over` sets replaced (a pass over its type's defaults).
    pub fn overridden_by(&self, over: &RasterDecl) -> RasterDecl {
        let mut out = self.clone();
        if over.depth.is_some() {
            out.depth = over.depth.clone();
        }
        if over.cull.is_some() {
            out.cull = over.cull.clone();
        }
        for (slot, blend) in &over.blend {
            out.blend.insert(slot.clone(), blend.clone());
        }
        if over.alpha_to_coverage.is_some() {
            out.alpha_to_coverage = over.alpha_to_coverage.clone();
        }
        if !over.loads.is_empty() {
            out.loads = over.loads.clone();
        }
        out
    }

    /// The keys that are set, each with its location (for "does not apply" errors).
    pub fn keys(&self) -> Vec<(&'static str, &Location)> {
        let mut out = Vec::new();
        if let Some(d) = &self.depth {
            out.push(("depth", &d.location));
        }
        if let Some(b) = self.blend.values().next() {
            out.push(("blend", &b.location));
        }
        if let Some(c) = &self.cull {
            out.push(("cull", &c.location));
        }
        if let Some(a) = &self.alpha_to_coverage {
            out.push(("alpha_to_coverage", &a.location));
        }
        if let Some(l) = self.loads.first() {
            out.push(("loads", &l.location));
        }
        out
    }

    /// One line for snapshots: `depth less (test only), blend accum=additive, cull back`.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if let Some(d) = &self.depth {
            let write = match d.write {
                Some(true) => ", write",
                Some(false) => ", test only",
                None => "",
            };
            parts.push(format!("depth {}{write}", d.compare.name()));
        }
        if !self.blend.is_empty() {
            let blends: Vec<String> = self
                .blend
                .iter()
                .map(|(slot, b)| match b.value {
                    Blend::Preset(p) => format!("{slot}={}", p.name()),
                    Blend::Factors { color, alpha } => format!(
                        "{slot}=color({} {} {}) alpha({} {} {})",
                        color.src.name(),
                        color.op.name(),
                        color.dst.name(),
                        alpha.src.name(),
                        alpha.op.name(),
                        alpha.dst.name()
                    ),
                })
                .collect();
            parts.push(format!("blend {}", blends.join(" ")));
        }
        if let Some(c) = &self.cull {
            parts.push(format!("cull {}", c.name()));
        }
        if self.alpha_to_coverage.as_ref().is_some_and(|a| a.value) {
            parts.push("alpha to coverage".into());
        }
        if !self.loads.is_empty() {
            let slots: Vec<&str> = self.loads.iter().map(|l| l.value.as_str()).collect();
            parts.push(format!("loads {}", slots.join(" ")));
        }
        parts.join(", ")
    }
}

/// Read the raster keys of a pass table (`context` names it in messages,
/// e.g. `passes.light_occupancy`). Other keys are left to the caller.
pub(crate) fn parse(table: &Table, context: &str, errors: &mut Vec<Error>) -> RasterDecl {
    let mut p = Reader { errors };
    let mut out = RasterDecl::default();
    if let Some(e) = table.get("depth") {
        out.depth = p.depth(e, &format!("{context}.depth"));
    }
    if let Some(e) = table.get("blend")
        && let Some(t) = p.table(&e.value, &format!("{context}.blend"))
    {
        for (slot, entry) in t {
            let ctx = format!("{context}.blend.{slot}");
            if let Some(b) = p.blend(&entry.value, &ctx) {
                out.blend
                    .insert(slot.clone(), Spanned::new(b, entry.value.location.clone()));
            }
        }
    }
    if let Some(e) = table.get("cull") {
        out.cull = p
            .named(&e.value, &format!("{context}.cull"), Cull::NAMES)
            .and_then(|s| Cull::from_name(&s).map(|c| Spanned::new(c, e.value.location.clone())));
    }
    if let Some(e) = table.get("alpha_to_coverage") {
        out.alpha_to_coverage = p
            .bool(&e.value, &format!("{context}.alpha_to_coverage"))
            .map(|b| Spanned::new(b, e.value.location.clone()));
    }
    if let Some(e) = table.get("loads")
        && let Some(slots) = p.spanned_strings(&e.value, &format!("{context}.loads"))
    {
        // Each entry keeps its own location: an error about one slot points
        // at that slot, not at the start of the list.
        out.loads = slots;
    }
    out
}

impl Reader<'_> {
    fn depth(&mut self, entry: &Entry, context: &str) -> Option<Spanned<DepthDecl>> {
        let t = self.table(&entry.value, context)?;
        self.keys(t, &["compare", "write"], context);
        let compare = match t.get("compare") {
            Some(e) => Compare::from_name(&self.named(
                &e.value,
                &format!("{context}.compare"),
                Compare::NAMES,
            )?)?,
            None => {
                self.schema(
                    &entry.value.location,
                    format!("{context} needs `compare` ({})", Compare::NAMES.join(", ")),
                );
                return None;
            }
        };
        let write = match t.get("write") {
            None => None,
            Some(e) => Some(self.bool(&e.value, &format!("{context}.write"))?),
        };
        Some(Spanned::new(
            DepthDecl { compare, write },
            entry.value.location.clone(),
        ))
    }

    fn blend(&mut self, node: &Spanned<Node>, context: &str) -> Option<Blend> {
        if let Node::Scalar(_) = node.value {
            let name = self.named(node, context, BlendPreset::NAMES)?;
            return BlendPreset::from_name(&name).map(Blend::Preset);
        }
        let Node::Table(t) = &node.value else {
            self.schema(
                &node.location,
                format!(
                    "{context} must be a preset ({}) or a table {{ color = {{…}}, alpha = {{…}} }}",
                    BlendPreset::NAMES.join(", ")
                ),
            );
            return None;
        };
        self.keys(t, &["color", "alpha"], context);
        let mut component = |key: &str| -> Option<BlendComponent> {
            let ctx = format!("{context}.{key}");
            let Some(e) = t.get(key) else {
                self.schema(
                    &node.location,
                    format!("{context} needs `{key} = {{ src = …, dst = …, op = … }}`"),
                );
                return None;
            };
            let ct = self.table(&e.value, &ctx)?;
            self.keys(ct, &["src", "dst", "op"], &ctx);
            let mut factor = |k: &str| -> Option<BlendFactor> {
                let Some(fe) = ct.get(k) else {
                    self.schema(&e.value.location, format!("{ctx} needs `{k}`"));
                    return None;
                };
                BlendFactor::from_name(&self.named(
                    &fe.value,
                    &format!("{ctx}.{k}"),
                    BlendFactor::NAMES,
                )?)
            };
            let src = factor("src");
            let dst = factor("dst");
            let op = match ct.get("op") {
                Some(oe) => BlendOp::from_name(&self.named(
                    &oe.value,
                    &format!("{ctx}.op"),
                    BlendOp::NAMES,
                )?),
                None => Some(BlendOp::Add),
            };
            Some(BlendComponent {
                src: src?,
                dst: dst?,
                op: op?,
            })
        };
        let color = component("color");
        let alpha = component("alpha");
        Some(Blend::Factors {
            color: color?,
            alpha: alpha?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_text(text: &str) -> (RasterDecl, Vec<Error>) {
        let root = crate::load::parse_file(std::path::Path::new("t.toml"), text)
            .expect("test TOML parses");
        let Node::Table(t) = root.value else {
            unreachable!("a file is a table")
        };
        let mut errors = Vec::new();
        (parse(&t, "passes.p", &mut errors), errors)
    }

    #[test]
    fn reads_presets_factors_depth_and_cull() {
        let (decl, errors) = parse_text(
            "depth = { compare = \"less_equal\", write = false }\n\
             blend = { a = \"additive\", b = { color = { src = \"one\", dst = \"one_minus_src_alpha\" }, alpha = { src = \"zero\", dst = \"one\", op = \"max\" } } }\n\
             cull = \"back\"\n",
        );
        assert!(errors.is_empty(), "{errors:?}");
        let depth = decl.depth.as_ref().expect("depth");
        assert_eq!(depth.compare, Compare::LessEqual);
        assert_eq!(depth.write, Some(false));
        assert_eq!(decl.blend["a"].value, Blend::Preset(BlendPreset::Additive));
        let Blend::Factors { color, alpha } = decl.blend["b"].value else {
            panic!("factors expected")
        };
        assert_eq!(color.op, BlendOp::Add, "op defaults to add");
        assert_eq!(alpha.op, BlendOp::Max);
        assert_eq!(decl.cull.as_ref().map(|c| c.value), Some(Cull::Back));
        assert_eq!(
            decl.describe(),
            "depth less_equal, test only, blend a=additive b=color(one add one_minus_src_alpha) alpha(zero max one), cull back"
        );
    }

    #[test]
    fn bad_values_name_the_place_and_the_choices() {
        let (_, errors) = parse_text(
            "depth = { compare = \"lesser\" }\nblend = { color = \"adittive\" }\ncull = 3\n",
        );
        let text: Vec<String> = errors.iter().map(|e| e.to_string()).collect();
        assert_eq!(text.len(), 3, "{text:#?}");
        assert!(text[0].starts_with("t.toml:1:21:"), "{}", text[0]);
        assert!(text[0].contains("did you mean `less`"), "{}", text[0]);
        assert!(text[1].starts_with("t.toml:2:19:"), "{}", text[1]);
        assert!(text[1].contains("did you mean `additive`"), "{}", text[1]);
        assert!(text[2].contains("none, front, back"), "{}", text[2]);
    }

    #[test]
    fn a_pass_overrides_its_types_state_key_by_key() {
        let (base, _) = parse_text("depth = { compare = \"less\" }\nblend = { a = \"over\" }\n");
        let (over, _) = parse_text("blend = { a = \"additive\", b = \"under\" }\n");
        let merged = base.overridden_by(&over);
        assert_eq!(merged.depth, base.depth);
        assert_eq!(
            merged.blend["a"].value,
            Blend::Preset(BlendPreset::Additive)
        );
        assert_eq!(merged.blend.len(), 2);
    }
}
