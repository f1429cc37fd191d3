//! `plait`: render, check, graph and compare strand-hair pipelines that are data.
//!
//! Every error a user can cause (a pipeline file, a shader, a scene, a `.hair`
//! file, a flag) is printed as `error: …` naming the file and line or the flag,
//! and exits with code 2; no output file is left half-written.

mod ab_cmd;
mod hair_cmd;
mod output;
mod pipeline_cmd;
mod render_cmd;
mod view_cmd;

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
    /// Inspect and generate `.hair` files.
    Hair(hair_cmd::HairArgs),
    /// Run several pipelines on the same scene(s) and write one report
    Ab(ab_cmd::AbArgs),
    /// Open a window that renders a pipeline live and reloads it on every save.
    View(view_cmd::ViewArgs),
}

fn main() {
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
        Command::Hair(args) => hair_cmd::run(args),
        Command::Ab(args) => ab_cmd::run(args),
        Command::View(args) => view_cmd::run(args),
    };
    if let Err(e) = result {
        // `Errors` already prefixes each line with `error:`.
        let text = format!("{e:#}");
        if text.starts_with("error:") {
            eprintln!("{text}");
        } else {
            eprintln!("error: {text}");
        }
        std::process::exit(2);
    }
}
