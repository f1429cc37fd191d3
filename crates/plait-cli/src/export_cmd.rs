//! `plait export mitsuba`: a scene written as a folder the Mitsuba 3 path
//! tracer renders (`scripts/mitsuba/render.py`); the exporter is
//! `plait::mitsuba`.

use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::{Args, Subcommand};
use plait::mitsuba::{self, Fibre};
use plait::session::SceneData;

use crate::args::{parse_scene, parse_size};

#[derive(Args)]
pub struct ExportArgs {
    #[command(subcommand)]
    command: ExportCommand,
}

#[derive(Subcommand)]
enum ExportCommand {
    /// Write a scene for Mitsuba 3: scene.xml, hair curves, meshes, plait.json
    /// (render it with `scripts/mitsuba/render.py DIR out.exr`).
    Mitsuba(MitsubaArgs),
}

#[derive(Args)]
struct MitsubaArgs {
    /// Scene file (default: the built-in scene).
    #[arg(value_parser = parse_scene)]
    scene: Option<PathBuf>,
    /// Image size, `WIDTHxHEIGHT`.
    #[arg(long, value_parser = parse_size, default_value = "960x720")]
    size: (u32, u32),
    /// Folder to write (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Longitudinal roughness β_m of the hair BSDF (Chiang et al. 2016), in (0, 1]
    /// (default: the shading point's `chiang_beta_m`).
    #[arg(long)]
    beta_m: Option<f32>,
    /// Azimuthal roughness β_n, in (0, 1]; also maps colour to absorption
    /// (default: the shading point's `chiang_beta_n`).
    #[arg(long)]
    beta_n: Option<f32>,
    /// Cuticle scale tilt α in degrees, in [-90, 90] (default: the shading
    /// point's `chiang_tilt`).
    #[arg(long)]
    alpha_degrees: Option<f32>,
    /// Index of refraction η of the fibre, above 1 (default: the shading
    /// point's `chiang_eta`).
    #[arg(long)]
    eta: Option<f32>,
}

pub fn run(args: ExportArgs) -> Result<()> {
    match args.command {
        ExportCommand::Mitsuba(a) => mitsuba(a),
    }
}

fn mitsuba(a: MitsubaArgs) -> Result<()> {
    let fibre = fibre(&a)?;
    let data = SceneData::load(a.scene.as_deref())?;
    let scene = mitsuba::plan(&data, a.size, fibre)?;
    let written = scene.write(&a.out)?;
    for note in &scene.notes {
        outln!("note: {note}")?;
    }
    let strands: usize = scene.hair.iter().map(|g| g.strands.len()).sum();
    outln!(
        "wrote {} ({} files: {} strands in {} hair group(s), {} mesh(es))",
        written.scene_xml.display(),
        written.files.len(),
        strands,
        scene.hair.len(),
        scene.meshes.len()
    )?;
    Ok(())
}

/// The fibre flags over the library's standard fibre (the shading point's
/// defaults, read once here), each checked against its range (exit 2 naming
/// the flag).
fn fibre(a: &MitsubaArgs) -> Result<Fibre> {
    let standard = Fibre::standard(&plait_passes::read_library(&[]));
    let beta_m = a.beta_m.unwrap_or(standard.longitudinal_roughness);
    let beta_n = a.beta_n.unwrap_or(standard.azimuthal_roughness);
    let alpha_degrees = a.alpha_degrees.unwrap_or(standard.scale_tilt_degrees);
    let eta = a.eta.unwrap_or(standard.eta);
    let unit = |v: f32| v.is_finite() && v > 0.0 && v <= 1.0;
    if !unit(beta_m) {
        bail!("--beta-m {}: must be in (0, 1]", beta_m);
    }
    if !unit(beta_n) {
        bail!("--beta-n {}: must be in (0, 1]", beta_n);
    }
    if !(alpha_degrees.is_finite() && alpha_degrees.abs() <= 90.0) {
        bail!("--alpha-degrees {}: must be in [-90, 90]", alpha_degrees);
    }
    if !(eta.is_finite() && eta > 1.0) {
        bail!("--eta {}: must be a finite number above 1", eta);
    }
    Ok(Fibre {
        longitudinal_roughness: beta_m,
        azimuthal_roughness: beta_n,
        scale_tilt_degrees: alpha_degrees,
        eta,
    })
}
