//! `plait hair info` and `plait hair generate`.

use std::path::PathBuf;

use anyhow::{Context, bail};
use plait_hair::{GroomSpec, HairFile, Style, generate};

/// `plait hair ...`
#[derive(clap::Args, Debug)]
pub struct HairArgs {
    /// What to do.
    #[command(subcommand)]
    pub command: HairCommand,
}

/// The `hair` subcommands.
#[derive(clap::Subcommand, Debug)]
pub enum HairCommand {
    /// Print a .hair file's counts, arrays, defaults, bounds and info string.
    Info {
        /// The .hair file.
        file: PathBuf,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Write a procedural groom as a .hair file.
    Generate {
        /// straight, wavy or curly.
        #[arg(long, default_value = "straight")]
        style: String,
        /// Number of strands (≥ 1).
        #[arg(long, default_value_t = 1000)]
        strands: u32,
        /// Segments per strand (1..=65535).
        #[arg(long, default_value_t = 16)]
        segments: u32,
        /// PRNG seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output .hair file.
        #[arg(long)]
        out: PathBuf,
    },
}

/// Runs a `hair` subcommand.
pub fn run(args: HairArgs) -> anyhow::Result<()> {
    match args.command {
        HairCommand::Info { file, json } => info(&file, json),
        HairCommand::Generate {
            style,
            strands,
            segments,
            seed,
            out,
        } => {
            let spec = generate_spec(&style, strands, segments, seed)?;
            let strands = generate(&spec);
            let mut hair = strands
                .to_hair_file()
                .with_context(|| format!("converting the groom for {}", out.display()))?;
            hair.set_info(&format!(
                "plait hair generate --style {style} --seed {seed}"
            ));
            hair.write(&out)?;
            outln!(
                "wrote {}: {} strands, {} points, {} segments",
                out.display(),
                strands.strand_count(),
                strands.point_count(),
                strands.segment_count()
            )?;
            Ok(())
        }
    }
}

/// Validates the `generate` flags (messages name the flag) and builds the spec.
pub fn generate_spec(
    style: &str,
    strands: u32,
    segments: u32,
    seed: u64,
) -> anyhow::Result<GroomSpec> {
    let style: Style = style
        .parse()
        .map_err(|e: String| anyhow::anyhow!("--style: {e}"))?;
    if strands < 1 {
        bail!("--strands must be at least 1, got {strands}");
    }
    if !(1..=65535).contains(&segments) {
        bail!("--segments must be in 1..=65535, got {segments}");
    }
    let points = u64::from(strands) * (u64::from(segments) + 1);
    if points > u64::from(u32::MAX) {
        bail!(
            "--strands {strands} × (--segments {segments} + 1) = {points} points exceeds the .hair limit of 2^32-1"
        );
    }
    let spec = GroomSpec {
        style,
        strands,
        segments,
        seed,
        ..GroomSpec::default()
    };
    spec.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok(spec)
}

fn info(path: &std::path::Path, json: bool) -> anyhow::Result<()> {
    let (file, warnings) = HairFile::read(path)?;
    let b = file.bounds();
    let (min, max) = if b.is_empty() {
        ([0.0f32; 3], [0.0f32; 3])
    } else {
        (b.min.to_array(), b.max.to_array())
    };
    let warnings: Vec<String> = warnings.iter().map(|w| w.to_string()).collect();
    if json {
        let v = serde_json::json!({
            "file": path.display().to_string(),
            "strands": file.strand_count(),
            "points": file.point_count(),
            "segments": file.segment_count(),
            "arrays": file.arrays(),
            "bounds": { "min": min, "max": max },
            "defaults": {
                "segments": file.default_segments,
                "thickness": file.default_thickness,
                "transparency": file.default_transparency,
                "color": file.default_color,
            },
            "info": file.info_string(),
            "warnings": warnings,
        });
        outln!("{v}")?;
    } else {
        outln!("file:         {}", path.display())?;
        outln!("strands:      {}", file.strand_count())?;
        outln!("points:       {}", file.point_count())?;
        outln!("segments:     {}", file.segment_count())?;
        outln!("arrays:       {}", file.arrays().join(", "))?;
        outln!(
            "defaults:     segments {}, thickness {}, transparency {}, color [{}, {}, {}]",
            file.default_segments,
            file.default_thickness,
            file.default_transparency,
            file.default_color[0],
            file.default_color[1],
            file.default_color[2]
        )?;
        outln!("bounds:       min {min:?} max {max:?}")?;
        outln!("info:         {:?}", file.info_string())?;
        for w in &warnings {
            eprintln!("warning: {}: {w}", path.display());
        }
    }
    Ok(())
}
