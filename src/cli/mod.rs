//! The command line: the only code that knows clap, files, stdout/stderr and exit codes.
//! `Cli` and `Command` are the interface of product.md; their doc comments are the `--help` text.
#![allow(clippy::print_stdout)]

mod accel;
mod check;
mod figure;
mod lessons;
mod render;
mod sampling;
mod step;
mod trace;
mod tradeoff;

use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use whitted::scene::load::load_str_with;
use whitted::scene::AnyScene;

/// Recursive (Whitted) ray tracing, taught in the open.
#[derive(Parser, Debug)]
#[command(name = "whitted", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The commands.
#[derive(Subcommand, Debug)]
enum Command {
    /// Render an image (one ray per pixel centre, or --aa corners|adaptive); a one-line summary on stderr.
    Render(render::RenderArgs),
    /// Trace one pixel (or one ray) and tell every step, or print the trace document with --json.
    Trace(trace::TraceArgs),
    /// Step through one pixel's (or ray's) narrated trace: Enter for the next step, b back, a
    /// number to jump, a for all the rest, q to quit.
    Step(step::StepArgs),
    /// Validate a scene and say what it models; every error at once (exit code 2).
    Check(check::CheckArgs),
    /// Draw one diagram of the lecture from a recorded trace, as PNG or SVG (--list names them).
    Figure(figure::FigureArgs),
    /// Draw every lesson's figures (lessons/) in both languages, PNG and SVG, with index pages.
    Lessons(lessons::LessonsArgs),
    /// Measure what accuracy costs: time, rays and tests per setting (sampling, depth, structure)
    /// and the error against a reference image; a Markdown table (or --json), plots with --out.
    Tradeoff(tradeoff::TradeoffArgs),
}

/// An error with its exit code: 2 for bad input (scene, arguments), 1 for anything else.
pub use whitted::request::Failure;

/// Reads and validates a scene file; every problem becomes one line of the failure. A mesh's
/// OBJ file is read relative to the scene file's folder.
pub fn load_scene(path: &Path) -> Result<AnyScene, Failure> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Failure::input(format!("{}: cannot read the scene: {e}", path.display())))?;
    let folder = path.parent().unwrap_or_else(|| Path::new("."));
    let read_obj = |name: &str| std::fs::read_to_string(folder.join(name)).map_err(|e| e.to_string());
    load_str_with(&text, &read_obj).map_err(|errors| {
        let lines: Vec<String> = errors.iter().map(|e| format!("{}: {e}", path.display())).collect();
        Failure::input(lines.join("\n"))
    })
}

/// Writes bytes to a file.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    std::fs::write(path, bytes).map_err(|e| Failure::other(format!("{}: cannot write: {e}", path.display())))
}

/// The worker threads of `--threads` (default: rayon's, one per core).
pub fn thread_pool(threads: Option<u32>) -> Result<rayon::ThreadPool, Failure> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        builder = builder.num_threads(n as usize);
    }
    builder.build().map_err(|e| Failure::other(format!("cannot start the worker threads: {e}")))
}

/// Says on stderr the options a command ignores (`whitted: --threshold applies to …`).
pub fn print_notes(notes: &[String]) {
    for note in notes {
        eprintln!("whitted: {note}");
    }
}

/// Prints to stdout; a closed pipe (`| head`) is not an error.
pub fn print_out(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
}

/// Runs the command line and returns the exit code.
pub fn main() -> u8 {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return code;
        }
    };
    let result = match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Trace(args) => trace::run(&args),
        Command::Step(args) => step::run(&args),
        Command::Check(args) => check::run(&args),
        Command::Figure(args) => figure::run(&args),
        Command::Lessons(args) => lessons::run(&args),
        Command::Tradeoff(args) => tradeoff::run(&args),
    };
    match result {
        Ok(()) => 0,
        Err(f) => {
            eprintln!("{}", prefix_lines(&f.message));
            f.code()
        }
    }
}

fn prefix_lines(message: &str) -> String {
    message.lines().map(|l| format!("error: {l}")).collect::<Vec<_>>().join("\n")
}

/// The default output file: the scene's name with `.png`, in the current folder.
pub fn default_output(scene: &Path, ext: &str) -> PathBuf {
    let stem = scene.file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
    PathBuf::from(format!("{stem}.{ext}"))
}
