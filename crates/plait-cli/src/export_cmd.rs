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
    /// Longitudinal roughness β_m of the hair BSDF (Chiang et al. 2016), in (0, 1].
    #[arg(long, default_value_t = Fibre::default().longitudinal_roughness)]
    beta_m: f32,
    /// Azimuthal roughness β_n, in (0, 1]; also maps colour to absorption.
    #[arg(long, default_value_t = Fibre::default().azimuthal_roughness)]
    beta_n: f32,
    /// Cuticle scale tilt α in degrees, in [-90, 90].
    #[arg(long, default_value_t = Fibre::default().scale_tilt_degrees)]
    alpha_degrees: f32,
    /// Index of refraction η of the fibre, above 1.
    #[arg(long, default_value_t = Fibre::default().eta)]
    eta: f32,
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

/// The fibre flags, each checked against its range (exit 2 naming the flag).
fn fibre(a: &MitsubaArgs) -> Result<Fibre> {
    let unit = |v: f32| v.is_finite() && v > 0.0 && v <= 1.0;
    if !unit(a.beta_m) {
        bail!("--beta-m {}: must be in (0, 1]", a.beta_m);
    }
    if !unit(a.beta_n) {
        bail!("--beta-n {}: must be in (0, 1]", a.beta_n);
    }
    if !(a.alpha_degrees.is_finite() && a.alpha_degrees.abs() <= 90.0) {
        bail!("--alpha-degrees {}: must be in [-90, 90]", a.alpha_degrees);
    }
    if !(a.eta.is_finite() && a.eta > 1.0) {
        bail!("--eta {}: must be a finite number above 1", a.eta);
    }
    Ok(Fibre {
        longitudinal_roughness: a.beta_m,
        azimuthal_roughness: a.beta_n,
        scale_tilt_degrees: a.alpha_degrees,
        eta: a.eta,
    })
}
