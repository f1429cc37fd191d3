//! `plait`: render, check, graph and compare strand-hair pipelines that are data.
//!
//! Every error a user can cause (a pipeline file, a shader, a scene, a `.hair`
//! file, a flag) is printed as `error: …` naming the file and line or the flag,
//! and exits with code 2; no output file is left half-written. Standard output
//! goes through `outln!` (never `println!`), so a reader that closes the pipe
//! early (`plait passes | head -1`) ends the program quietly.
#![warn(clippy::print_stdout)]

#[macro_use]
mod output;
mod ab_cmd;
mod args;
mod export_cmd;
mod hair_cmd;
mod pipeline_cmd;
mod render_cmd;
mod sequence;
mod show;
mod table;
mod techniques_cmd;
mod view_cmd;

use std::io::Write as _;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "plait",
    version = env!("PLAIT_BUILD_VERSION"),
    about = "Real-time strand-hair render pipelines as data"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a pipeline on a scene to a PNG and print per-pass GPU times.
    Render(render_cmd::RenderArgs),
    /// Validate pipeline files without a GPU (names, types, formats, cycles, shader bindings).
    Check(pipeline_cmd::CheckArgs),
    /// Print the compiled schedule as Graphviz DOT, or write it as SVG.
    Graph(pipeline_cmd::GraphArgs),
    /// List the registered pass types with their inputs, outputs and params.
    Passes(pipeline_cmd::PassesArgs),
    /// List the choice points and their techniques (`--set techniques.POINT=NAME`): papers, params, memory.
    Techniques(techniques_cmd::TechniquesArgs),
    /// Inspect, convert and generate `.hair` and `.tfx` files.
    Hair(hair_cmd::HairArgs),
    /// Run several pipelines on the same scene(s) and write one report
    Ab(ab_cmd::AbArgs),
    /// Write a scene for another renderer (Mitsuba 3, the path-traced reference).
    Export(export_cmd::ExportArgs),
    /// Open a window that renders a pipeline live and reloads it on every save.
    View(view_cmd::ViewArgs),
}

fn main() {
    quiet_display_probe_when_headless();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // clap exits 2 on usage errors and 0 for --help/--version.
            e.exit();
        }
    };
    let result = match cli.command {
        Command::Render(args) => render_cmd::run(args),
        Command::Check(args) => pipeline_cmd::check(args),
        Command::Graph(args) => pipeline_cmd::graph(args),
        Command::Passes(args) => pipeline_cmd::passes(args),
        Command::Techniques(args) => techniques_cmd::run(args),
        Command::Hair(args) => hair_cmd::run(args),
        Command::Ab(args) => ab_cmd::run(args),
        Command::Export(args) => export_cmd::run(args),
        Command::View(args) => view_cmd::run(args),
    };
    let result = result.and_then(|()| Ok(std::io::stdout().flush()?));
    if let Err(e) = result {
        if output::is_broken_pipe(&e) {
            // The reader has all it wanted (`| head`): end quietly, as Unix tools do.
            std::process::exit(0);
        }
        // `Errors` already prefixes each line with `error:`. A write error on
        // stderr itself has nowhere to go.
        let text = error_text(&e);
        let _ = if text.starts_with("error:") {
            writeln!(std::io::stderr(), "{text}")
        } else {
            writeln!(std::io::stderr(), "error: {text}")
        };
        std::process::exit(2);
    }
}

/// The error and its causes, `outer: inner`, leaving out a cause whose text
/// the message already holds: an error that displays its source (the pipeline
/// errors inside a render error) would otherwise be printed twice, the second
/// time joined onto the last line of the first.
fn error_text(error: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in error.chain() {
        let part = cause.to_string();
        if text.contains(part.trim()) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&part);
    }
    text
}

/// Mesa's device-select Vulkan layer (`VK_LAYER_MESA_device_select`, an
/// implicit layer installed with the drivers) asks the Wayland compositor
/// which GPU drives the display whenever the instance enables
/// `VK_KHR_wayland_surface`, which wgpu always does when the driver offers it.
/// Without `XDG_RUNTIME_DIR` there can be no compositor, and libwayland prints
/// `error: XDG_RUNTIME_DIR is invalid or not set in the environment.` on every
/// device plait opens. On such a machine there is no display to pick a GPU
/// for, so switch the layer off through its own documented variable; wgpu
/// still chooses the adapter. A user's own `NODEVICE_SELECT` is kept.
#[allow(unsafe_code)]
fn quiet_display_probe_when_headless() {
    let unset = |name: &str| std::env::var_os(name).is_none_or(|v| v.is_empty());
    if unset("XDG_RUNTIME_DIR") && unset("WAYLAND_SOCKET") && unset("NODEVICE_SELECT") {
        // SAFETY: the first statement of `main`, before any thread exists, so
        // nothing reads the environment while it changes.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}
