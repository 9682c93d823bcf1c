//! The command line: the only code that knows clap, files, stdout/stderr and exit codes.
//! `Cli` and `Command` are the interface of product.md; their doc comments are the `--help` text.
//!
//! It is thin: between clap and the output each command calls `whitted::request`, as `web/` does,
//! so both word every error alike. One file per command; the cargo feature `cli` (default on)
//! brings clap and indicatif.
#![allow(clippy::print_stdout)]

mod accel;
mod check;
mod course;
mod exercises;
mod figure;
mod grade;
mod lessons;
mod output;
mod render;
mod sampling;
mod step;
mod trace;
mod tradeoff;

use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use whitted::format::{json_text, terminal_text};
use whitted::memory;
use whitted::scene::load::{load_str_with, MAX_OBJ_BYTES, MAX_SCENE_BYTES};
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
    /// Measure what accuracy costs: per sweep (sampling, depth, structure), each setting's rays,
    /// tests and time against its error to a reference differing in that sweep only; Markdown
    /// tables (or --json), plots with --out.
    Tradeoff(tradeoff::TradeoffArgs),
    /// Check a student's trace of one pixel (docs/grading.md) against whitted's: the first
    /// divergence with its formula and, where a classic mistake explains it, that mistake; exit 0
    /// when everything agrees, 1 at a divergence, 2 for a bad document.
    Grade(grade::GradeArgs),
    /// Write an exercise sheet and its worked answers for one pixel (exercises.html, answers.html):
    /// 6–10 questions drawn from the pixel's trace, answered as the narration works them.
    Exercises(exercises::ExercisesArgs),
}

/// An error with its exit code: 2 for bad input (scene, arguments), 1 for anything else.
pub use whitted::request::Failure;

/// Reads and validates a scene file; every problem becomes one line of the failure. A mesh's
/// OBJ file is read relative to the scene file's folder.
pub fn load_scene(path: &Path) -> Result<AnyScene, Failure> {
    load_scene_from(path, &read_text)
}

/// [`load_scene`] with the files read by `read` (path, byte limit): the disk, or the course the
/// binary carries (`course`).
pub fn load_scene_from(
    path: &Path,
    read: &dyn Fn(&Path, u64) -> Result<String, String>,
) -> Result<AnyScene, Failure> {
    let text = read(path, MAX_SCENE_BYTES)
        .map_err(|e| Failure::input(format!("{}: cannot read the scene: {e}", path.display())))?;
    let folder = path.parent().unwrap_or_else(|| Path::new("."));
    let read_obj = |name: &str| read(&folder.join(name), MAX_OBJ_BYTES);
    load_str_with(&text, &read_obj).map_err(|errors| {
        let lines: Vec<String> = errors.iter().map(|e| format!("{}: {e}", path.display())).collect();
        Failure::input(lines.join("\n"))
    })
}

/// Reads a regular file of at most `limit` bytes as UTF-8 text. A device, a folder or a named
/// pipe is refused before it is opened (`/dev/zero` never ends, a pipe blocks until written), and
/// the read stops one byte past the limit, so a file that grows meanwhile cannot exhaust memory.
///
/// # Errors
/// The reason, naming the limit when the file is too large.
pub fn read_text(path: &Path, limit: u64) -> Result<String, String> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    let too_big = || format!("larger than the limit of {limit} bytes");
    if meta.len() > limit {
        return Err(too_big());
    }
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    if bytes.len() as u64 > limit {
        return Err(too_big());
    }
    String::from_utf8(bytes).map_err(|e| format!("not UTF-8 text ({e})"))
}

/// Every file the tool writes goes through this one function: whole or untouched (a temporary
/// file renamed over the destination, `output`).
pub use output::write_file;

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
        eprintln!("whitted: {}", terminal_text(note));
    }
}

/// Prints to stdout, whole: a closed pipe (`| head`, the reader has all it wanted) is not an
/// error; any other failure to write (`> /dev/full`, a full disk) is, so that a truncated answer
/// never exits 0.
///
/// # Errors
/// [`stdout_failure`] of the write's error.
///
/// Control and bidirectional characters are shown escaped ([`terminal_text`]): a scene's names
/// cannot hold them, but a path or an argument may.
pub fn print_out(text: &str) -> Result<(), Failure> {
    write_stdout(&terminal_text(text))
}

/// Prints JSON text to stdout as [`print_out`] prints text, with the characters a terminal would
/// act on as `\uXXXX` escapes ([`json_text`]), so the document still reads back the same.
///
/// # Errors
/// As [`print_out`].
pub fn print_json(json: &str) -> Result<(), Failure> {
    write_stdout(&json_text(json))
}

fn write_stdout(text: &str) -> Result<(), Failure> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes()).and_then(|()| out.flush()).or_else(stdout_failure)
}

/// What a failed write to stdout means: nothing for a closed pipe (`EPIPE`: the reader stopped
/// reading, as `head` does), else a failure (exit code 1) on one line naming standard output.
///
/// # Errors
/// Every error but [`std::io::ErrorKind::BrokenPipe`].
pub fn stdout_failure(e: std::io::Error) -> Result<(), Failure> {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        Ok(())
    } else {
        Err(Failure::other(format!("standard output: cannot write: {e}")))
    }
}

/// The process's memory budget (`whitted::memory`), from the kernel's own files where they exist:
/// the address-space limit, what the process maps already, the memory available.
fn set_memory_budget() {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let (limits, status, meminfo) =
        (read("/proc/self/limits"), read("/proc/self/status"), read("/proc/meminfo"));
    memory::set_budget(memory::Budget::from_proc(limits.as_deref(), status.as_deref(), meminfo.as_deref()));
}

/// Runs the command line and returns the exit code.
pub fn main() -> u8 {
    set_memory_budget();
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
        Command::Grade(args) => grade::run(&args),
        Command::Exercises(args) => exercises::run(&args),
    };
    match result {
        Ok(()) => 0,
        Err(f) => {
            // An empty message: the answer was printed and only the exit code remains to say.
            if !f.message.is_empty() {
                eprintln!("{}", prefix_lines(&terminal_text(&f.message)));
            }
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

#[cfg(test)]
mod tests {
    use super::read_text;

    /// The limit is a parameter, so a small one shows the refusal without a large file.
    #[test]
    fn read_text_refuses_past_its_limit_and_non_files() {
        let scratch = tempfile::tempdir().unwrap();
        let dir = scratch.path();
        let file = dir.join("ten.json");
        super::write_file(&file, b"0123456789").unwrap();
        assert_eq!(read_text(&file, 10).as_deref(), Ok("0123456789"));
        assert_eq!(read_text(&file, 9), Err("larger than the limit of 9 bytes".to_string()));
        assert_eq!(read_text(dir, 10), Err("not a regular file".to_string()));
        assert_eq!(read_text(std::path::Path::new("/dev/zero"), 10), Err("not a regular file".to_string()));
    }
}
