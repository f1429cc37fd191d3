//! `plait hair info`, `plait hair convert` and `plait hair generate`.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use plait_hair::usd::{self, UsdGroom, UsdOptions, WriteFormat};
use plait_hair::{Asset, Format, GroomSpec, HairFile, Strands, Style, TfxFile, generate};

use crate::output::PendingFile;

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
    /// Print a .hair, .tfx or USD file's counts, arrays, header fields and bounds.
    Info {
        /// The .hair, .tfx or USD (.usda, .usdc, .usdz, .usd) file.
        file: PathBuf,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        usd: UsdArgs,
    },
    /// Convert between .hair, .tfx and USD (the output's extension picks the
    /// format; USD is written as linear BasisCurves).
    Convert {
        /// The .hair, .tfx or USD file to read.
        input: PathBuf,
        /// The file to write: *.hair, *.tfx, *.usda, *.usdc or *.usdz.
        output: PathBuf,
        #[command(flatten)]
        usd: UsdArgs,
        /// Vertices per strand in a .tfx output (default: the most any
        /// strand has); strands with another count are resampled by arc
        /// length. TressFX itself loads 4, 8, 16, 32 or 64.
        #[arg(long)]
        vertices_per_strand: Option<u32>,
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

/// What to read from a USD input.
#[derive(clap::Args, Debug)]
pub struct UsdArgs {
    /// USD input: read the BasisCurves under this prim (default: the whole stage).
    #[arg(long)]
    prim: Option<String>,
    /// USD input: polyline segments per cubic curve span (1..=256).
    #[arg(long, default_value_t = usd::DEFAULT_SEGMENTS_PER_SPAN)]
    segments_per_span: u32,
}

impl UsdArgs {
    fn options(&self, input: &Path) -> anyhow::Result<UsdOptions> {
        let options = UsdOptions {
            prim: self.prim.clone(),
            segments_per_span: self.segments_per_span,
        };
        options
            .validate("--prim", "--segments-per-span")
            .map_err(|e| anyhow::anyhow!(e))?;
        let given = self.prim.is_some() || self.segments_per_span != usd::DEFAULT_SEGMENTS_PER_SPAN;
        if given && Format::from_extension(input) != Some(Format::Usd) {
            bail!(
                "--prim and --segments-per-span apply to a USD input (.usda, .usdc, .usdz or .usd)"
            );
        }
        Ok(options)
    }
}

/// Runs a `hair` subcommand.
pub fn run(args: HairArgs) -> anyhow::Result<()> {
    match args.command {
        HairCommand::Info { file, json, usd } => info(&file, json, &usd.options(&file)?),
        HairCommand::Convert {
            input,
            output,
            usd,
            vertices_per_strand,
        } => convert(&input, &output, &usd.options(&input)?, vertices_per_strand),
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
            PendingFile::create(&out, "--out")?.commit(&hair.to_bytes())?;
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

fn convert(
    input: &Path,
    output: &Path,
    usd_options: &UsdOptions,
    vertices_per_strand: Option<u32>,
) -> anyhow::Result<()> {
    let Some(format) = Format::from_extension(output) else {
        bail!(
            "{}: the output's extension must be .hair, .tfx, .usda, .usdc or .usdz",
            output.display()
        );
    };
    if vertices_per_strand.is_some() && format != Format::Tfx {
        bail!("--vertices-per-strand applies to a .tfx output only");
    }
    if let Some(n) = vertices_per_strand
        && !(2..=65536).contains(&n)
    {
        bail!("--vertices-per-strand must be in 2..=65536, got {n}");
    }
    // Reserve the output first, so an unwritable path fails before reading.
    let pending = PendingFile::create(output, "OUTPUT")?;
    let (asset, warnings) = Asset::read_with(input, usd_options)?;
    for w in &warnings {
        eprintln!("warning: {}: {w}", input.display());
    }
    let strands = asset.strands();
    let bytes = match format {
        Format::Hair => {
            let mut hair = strands
                .to_hair_file()
                .with_context(|| format!("converting {} to .hair", input.display()))?;
            hair.set_info(&format!(
                "plait hair convert {}",
                input.file_name().unwrap_or_default().to_string_lossy()
            ));
            hair.to_bytes()
        }
        Format::Tfx => tfx_bytes(&strands, vertices_per_strand)
            .with_context(|| format!("converting {} to .tfx", input.display()))?,
        Format::Usd => {
            let container = WriteFormat::from_extension(output).unwrap_or(WriteFormat::Usda);
            usd::write(&strands, container)
                .map_err(|e| e.in_file(output))
                .with_context(|| format!("converting {} to USD", input.display()))?
        }
    };
    pending.commit(&bytes)?;
    // What `plait hair info` would warn about the written file (a vertex
    // count TressFX does not load), said now rather than at its next use.
    let (written, written_warnings) = Asset::from_bytes(output, &bytes)?;
    for w in &written_warnings {
        eprintln!("warning: {}: {w}", output.display());
    }
    let out = written.strands();
    outln!(
        "wrote {}: {} strands, {} points",
        output.display(),
        out.strand_count(),
        out.point_count()
    )?;
    Ok(())
}

fn tfx_bytes(strands: &Strands, vertices_per_strand: Option<u32>) -> anyhow::Result<Vec<u8>> {
    let counts: std::collections::BTreeSet<usize> = strands.ranges().map(|r| r.len()).collect();
    let file = TfxFile::from_strands(strands, vertices_per_strand)?;
    if counts.len() > 1 || counts.first() != Some(&(file.vertices_per_strand as usize)) {
        eprintln!(
            "note: strands resampled by arc length to {} vertices each (.tfx holds one count per file)",
            file.vertices_per_strand
        );
    }
    Ok(file.to_bytes()?)
}

fn info(path: &Path, json: bool, usd: &UsdOptions) -> anyhow::Result<()> {
    let (asset, warnings) = Asset::read_with(path, usd)?;
    match asset {
        Asset::Hair(file) => hair_info(path, &file, warnings, json),
        Asset::Tfx(file) => tfx_info(path, &file, warnings, json),
        Asset::Usd(groom) => usd_info(path, &groom, warnings, json),
    }
}

fn curve_kind(p: &usd::CurvesPrim) -> String {
    let kind = match p.kind {
        usd::CurveKind::Linear => "linear".to_string(),
        usd::CurveKind::Cubic(b) => format!("cubic {}", b.token()),
    };
    let wrap = match p.wrap {
        usd::Wrap::Nonperiodic => "nonperiodic",
        usd::Wrap::Pinned => "pinned",
    };
    format!("{kind}, {wrap}")
}

fn usd_info(path: &Path, g: &UsdGroom, warnings: Vec<String>, json: bool) -> anyhow::Result<()> {
    let (min, max) = bounds_of(g.strands.bounds());
    let interp = |i: Option<usd::Interpolation>| i.map(|i| i.token());
    if json {
        let prims: Vec<_> = g
            .prims
            .iter()
            .map(|p| {
                serde_json::json!({
                    "path": p.path,
                    "curves": curve_kind(p),
                    "curve_count": p.curves,
                    "control_points": p.points,
                    "widths": interp(p.widths),
                    "display_color": interp(p.colors),
                    "display_opacity": interp(p.opacity),
                })
            })
            .collect();
        let v = serde_json::json!({
            "file": path.display().to_string(),
            "format": "usd",
            "container": g.container,
            "prim": g.options.prim.as_deref().unwrap_or("/"),
            "segments_per_span": g.options.segments_per_span,
            "meters_per_unit": g.units.meters_per_unit,
            "meters_per_unit_authored": g.units.meters_authored,
            "up_axis": if g.units.z_up { "Z" } else { "Y" },
            "prims": prims,
            "strands": g.strands.strand_count(),
            "points": g.strands.point_count(),
            "segments": g.strands.segment_count(),
            "bounds": { "min": min, "max": max },
            "warnings": warnings,
        });
        outln!("{v}")?;
        return Ok(());
    }
    outln!("file:         {}", path.display())?;
    outln!("format:       USD ({}), BasisCurves", g.container)?;
    outln!(
        "stage:        metersPerUnit {}{}, upAxis {} (read as metres, Y up)",
        g.units.meters_per_unit,
        if g.units.meters_authored {
            ""
        } else {
            " (not authored: USD's fallback)"
        },
        if g.units.z_up { "Z" } else { "Y" }
    )?;
    for p in &g.prims {
        let arrays: Vec<String> = [
            ("widths", p.widths),
            ("displayColor", p.colors),
            ("displayOpacity", p.opacity),
        ]
        .iter()
        .filter_map(|(n, i)| i.map(|i| format!("{n} ({})", i.token())))
        .collect();
        outln!(
            "prim:         {} — {} curves, {} control points, {}; {}",
            p.path,
            p.curves,
            p.points,
            curve_kind(p),
            if arrays.is_empty() {
                "no widths or colours".to_string()
            } else {
                arrays.join(", ")
            }
        )?;
    }
    outln!(
        "strands:      {} ({} points, {} segments; cubic spans at {} segments)",
        g.strands.strand_count(),
        g.strands.point_count(),
        g.strands.segment_count(),
        g.options.segments_per_span
    )?;
    outln!("bounds:       min {min:?} max {max:?}")?;
    for w in &warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(())
}

fn bounds_of(b: plait_hair::Aabb) -> ([f32; 3], [f32; 3]) {
    if b.is_empty() {
        ([0.0f32; 3], [0.0f32; 3])
    } else {
        (b.min.to_array(), b.max.to_array())
    }
}

fn tfx_info(path: &Path, file: &TfxFile, warnings: Vec<String>, json: bool) -> anyhow::Result<()> {
    let (min, max) = bounds_of(file.bounds());
    if json {
        let v = serde_json::json!({
            "file": path.display().to_string(),
            "format": "tfx",
            "version": file.version,
            "strands": file.strand_count(),
            "vertices_per_strand": file.vertices_per_strand,
            "points": file.vertex_count(),
            "segments": file.strand_count() * (file.vertices_per_strand as usize - 1),
            "arrays": file.arrays(),
            "follow_strands_per_guide": file.follow_strands_per_guide,
            "both_ends_immovable": file.both_ends_immovable,
            "bounds": { "min": min, "max": max },
            "warnings": warnings,
        });
        outln!("{v}")?;
        return Ok(());
    }
    outln!("file:         {}", path.display())?;
    outln!("format:       TressFX .tfx, version {}", file.version)?;
    outln!("strands:      {} (guide strands)", file.strand_count())?;
    outln!(
        "vertices:     {} per strand, {} in all",
        file.vertices_per_strand,
        file.vertex_count()
    )?;
    outln!("arrays:       {}", file.arrays().join(", "))?;
    if file.major_version() == 3 {
        outln!(
            "header:       {} follow strands per guide, both ends immovable: {}",
            file.follow_strands_per_guide,
            file.both_ends_immovable
        )?;
    }
    outln!("bounds:       min {min:?} max {max:?}")?;
    for w in &warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(())
}

fn hair_info(
    path: &Path,
    file: &HairFile,
    warnings: Vec<String>,
    json: bool,
) -> anyhow::Result<()> {
    let (min, max) = bounds_of(file.bounds());
    if json {
        let v = serde_json::json!({
            "file": path.display().to_string(),
            "format": "hair",
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
