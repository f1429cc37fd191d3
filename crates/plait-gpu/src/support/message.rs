//! How a pipeline the adapter cannot run is reported: every problem at the
//! line that asked for it, then what to do.

use std::fmt;

use plait_graph::Location;

use super::AdapterSupport;

/// One thing a pass (or a resource) needs that the adapter lacks.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    /// Where the pipeline (or technique) file asks for it.
    pub location: Location,
    /// The pass, `None` for a resource's own needs (copies, sample count).
    pub pass: Option<String>,
    /// The technique that declared the pass (`self_shadow/occupancy`).
    pub technique: Option<String>,
    /// The resource concerned, if any.
    pub resource: Option<String>,
    /// What plait does with it: "renders into `light_range` (rg32float)".
    pub what: String,
    /// The capability missing, in wgpu's words.
    pub missing: String,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.location)?;
        match (&self.pass, &self.technique) {
            (Some(pass), Some(t)) => write!(f, "pass `{pass}` (technique {t}) ")?,
            (Some(pass), None) => write!(f, "pass `{pass}` ")?,
            (None, _) => {}
        }
        write!(f, "{}: {}", self.what, self.missing)
    }
}

/// A schedule the opened adapter cannot run, and why.
#[derive(Clone, Debug)]
pub struct Unsupported {
    /// The adapter, its backend and driver.
    pub adapter: String,
    pub backend: wgpu::Backend,
    pub pipeline: String,
    pub problems: Vec<Problem>,
    /// `--set` flags that make the pipeline run here, when the caller found
    /// some (`techniques.self_shadow=none`); checked, never guessed.
    pub suggestion: Option<Vec<String>>,
    /// `VK_ICD_FILENAMES` / `VK_DRIVER_FILES` when set: they replace the
    /// installed Vulkan drivers, so a wrong value hides them.
    pub vulkan_override: Option<(String, String)>,
}

impl Unsupported {
    pub fn new(support: &AdapterSupport, pipeline: &str, problems: Vec<Problem>) -> Self {
        let vulkan_override = ["VK_ICD_FILENAMES", "VK_DRIVER_FILES"]
            .into_iter()
            .find_map(|name| {
                let value = std::env::var(name).ok().filter(|v| !v.is_empty())?;
                Some((name.to_owned(), value))
            });
        Unsupported {
            adapter: support.describe(),
            backend: support.backend,
            pipeline: pipeline.to_owned(),
            problems,
            suggestion: None,
            vulkan_override,
        }
    }
}

/// The package with Mesa's Vulkan drivers (lavapipe on a machine without a GPU).
pub const VULKAN_PACKAGE: &str = "mesa-vulkan-drivers";

impl fmt::Display for Unsupported {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "adapter {} cannot run pipeline `{}`:",
            self.adapter, self.pipeline
        )?;
        for p in &self.problems {
            write!(f, "\nerror: {p}")?;
        }
        // In a browser there is no driver to install: the page's WebGPU is
        // the adapter.
        let driver_help = !matches!(
            self.backend,
            wgpu::Backend::Vulkan | wgpu::Backend::BrowserWebGpu
        );
        if driver_help {
            write!(
                f,
                "\nhelp: install Mesa's Vulkan driver, which plait opens before {}: `apt-get install -y {VULKAN_PACKAGE}`",
                self.backend.to_str()
            )?;
            if let Some((name, value)) = &self.vulkan_override {
                write!(
                    f,
                    " ({name}={value} is set: Vulkan loads only the drivers it names; unset it or name an installed one)"
                )?;
            }
        }
        let or = if driver_help { "or " } else { "" };
        match &self.suggestion {
            Some(sets) if !sets.is_empty() => {
                let flags: Vec<String> = sets.iter().map(|s| format!("--set {s}")).collect();
                write!(
                    f,
                    "\nhelp: {or}choose techniques that run on this adapter: `{}`",
                    flags.join(" ")
                )
            }
            _ => write!(
                f,
                "\nhelp: {or}choose a pipeline or techniques that run on this adapter (`plait techniques` lists them; `plait check --adapter` tries one)"
            ),
        }
    }
}
