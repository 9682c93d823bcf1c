//! `whitted step`: the narration of `whitted trace`, one numbered step at a time, for a student
//! who follows a pixel's computation number by number. Each answer on stdin moves: Enter (or `n`)
//! to the next step, `b` back, a number to that step, `a` everything left, `q` to quit. Input is
//! read a line at a time, so a terminal and a pipe work alike; the end of input ends the session.
//! Each step shown is headed by where it stands in the ray tree (`P → T₁ → R₂ @ glass, level 3`),
//! so a jump lands somewhere named; an answer read from a pipe is echoed after its prompt, so a
//! transcript shows what was typed (a terminal echoes it itself).

use super::trace::{narration, TraceWhat};
use super::{stdout_failure, Failure};
use clap::Args;
use std::io::{BufRead, IsTerminal, Write};
use whitted::doc::narrate::{Lang, Step};
use whitted::format::terminal_text;

/// Options of `whitted step`: those of `whitted trace` without `--json`.
#[derive(Args, Debug)]
pub struct StepArgs {
    #[command(flatten)]
    what: TraceWhat,
}

/// Runs `whitted step`.
pub fn run(args: &StepArgs) -> Result<(), Failure> {
    let steps = narration(&args.what)?.steps();
    let stdin = std::io::stdin();
    let echo = !stdin.is_terminal();
    let mut out = std::io::stdout().lock();
    match session(&steps, args.what.lang(), echo, stdin.lock(), &mut out) {
        Ok(()) => Ok(()),
        // A closed stdout (`| head`) ends the session quietly, as for the other commands; any
        // other write error is one.
        Err(Ended::Write(e)) => stdout_failure(e),
        Err(Ended::Read(e)) => Err(Failure::other(format!("standard input: cannot read: {e}"))),
    }
}

/// Why a session stopped before its end: stdout or stdin failed.
#[derive(Debug)]
enum Ended {
    /// Writing a step or a prompt failed.
    Write(std::io::Error),
    /// Reading an answer failed.
    Read(std::io::Error),
}

impl From<std::io::Error> for Ended {
    fn from(e: std::io::Error) -> Self {
        Self::Write(e)
    }
}

/// What an answer asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Move {
    Next,
    Back,
    To(usize),
    All,
    Quit,
    Unknown,
    /// A line that is not UTF-8 text.
    Invalid,
}

fn parse(answer: &str) -> Move {
    match answer.trim() {
        "" | "n" | "next" => Move::Next,
        "b" | "back" | "p" => Move::Back,
        "a" | "all" => Move::All,
        "q" | "quit" => Move::Quit,
        other => other.parse().map_or(Move::Unknown, Move::To),
    }
}

/// The session's own words, in the narration's language.
struct Words {
    steps: &'static str,
    help: &'static str,
    last: &'static str,
    numbered: &'static str,
    invalid: &'static str,
}

impl Words {
    fn of(lang: Lang) -> Self {
        match lang {
            Lang::En => Self {
                steps: "steps",
                help: "Enter: next · b: back · NUMBER: that step · a: all the rest · q: quit",
                last: "the last step",
                numbered: "steps are numbered 1 to",
                invalid: "not a valid answer",
            },
            Lang::Ro => Self {
                steps: "pași",
                help: "Enter: următorul · b: înapoi · NUMĂR: acel pas · a: tot restul · q: ieșire",
                last: "ultimul pas",
                numbered: "pașii sunt numerotați de la 1 la",
                invalid: "nu este un răspuns valid",
            },
        }
    }
}

/// One step as shown: its place in the ray tree, then its text, with any control character shown
/// escaped ([`terminal_text`]).
fn show(out: &mut impl Write, step: &Step) -> std::io::Result<()> {
    if !step.place.is_empty() {
        writeln!(out, "── {}", terminal_text(&step.place))?;
    }
    writeln!(out, "{}", terminal_text(&step.text))
}

/// The next line of `input` without its line end: `None` at the end of input, `Err(bytes)` (shown
/// lossily) when the line is not UTF-8, which is answered and not fatal.
fn next_line(input: &mut impl BufRead) -> std::io::Result<Option<Result<String, String>>> {
    let mut bytes = Vec::new();
    if input.read_until(b'\n', &mut bytes)? == 0 {
        return Ok(None);
    }
    if bytes.last() == Some(&b'\n') {
        bytes.pop();
    }
    Ok(Some(String::from_utf8(bytes).map_err(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())))
}

/// Shows `steps` one at a time on `out`, moving as `input` says, until the last step is passed,
/// `q`, or the end of input; with `echo` (input not a terminal), each answer is written after its
/// prompt. A line that is not UTF-8 is answered "not a valid answer" and the session goes on.
fn session(
    steps: &[Step],
    lang: Lang,
    echo: bool,
    mut input: impl BufRead,
    out: &mut impl Write,
) -> Result<(), Ended> {
    let words = Words::of(lang);
    let n = steps.len();
    writeln!(out, "{n} {}. {}\n", words.steps, words.help)?;
    let Some(first) = steps.first() else { return Ok(()) };
    show(out, first)?;
    let mut at = 0;
    loop {
        write!(out, "[{}/{n}] > ", at + 1)?;
        out.flush()?;
        let answer = next_line(&mut input).map_err(Ended::Read)?;
        // A terminal has echoed the answer and its Enter already; a pipe has not.
        match (&answer, echo) {
            (Some(Ok(typed) | Err(typed)), true) => writeln!(out, "{}", terminal_text(typed.trim_end()))?,
            _ => writeln!(out)?,
        }
        let Some(answer) = answer else { return Ok(()) };
        match answer.as_deref().map_or(Move::Invalid, parse) {
            Move::Next if at + 1 < n => at += 1,
            Move::Next => {
                writeln!(out, "({})", words.last)?;
                return Ok(());
            }
            Move::Back => at = at.saturating_sub(1),
            Move::To(k) if (1..=n).contains(&k) => at = k - 1,
            Move::To(_) => {
                writeln!(out, "({} {n})", words.numbered)?;
                continue;
            }
            Move::All => {
                for step in &steps[at + 1..] {
                    show(out, step)?;
                }
                return Ok(());
            }
            Move::Quit => return Ok(()),
            Move::Unknown => {
                writeln!(out, "({})", words.help)?;
                continue;
            }
            Move::Invalid => {
                writeln!(out, "({}; {})", words.invalid, words.help)?;
                continue;
            }
        }
        show(out, &steps[at])?;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn three() -> Vec<Step> {
        let step = |number: usize, text: &str, place: &str| Step {
            number,
            text: text.to_owned(),
            events: Vec::new(),
            place: place.to_owned(),
        };
        vec![
            step(1, "1. one", "pixel (0)"),
            step(2, "2. two\n     detail", "P @ glass, level 1"),
            step(3, "   3. three", "P → T₁ @ glass, level 2"),
        ]
    }

    fn run_with(input: &str) -> String {
        run_echo(input, false)
    }

    fn run_echo(input: &str, echo: bool) -> String {
        let mut out = Vec::new();
        session(&three(), Lang::En, echo, input.as_bytes(), &mut out).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn answers_move_through_the_steps() {
        let shown = run_with("\nb\n3\nb\nq\n");
        let order: Vec<&str> =
            shown.lines().skip(1).filter(|l| l.trim_start().starts_with(char::is_numeric)).collect();
        assert_eq!(order, ["1. one", "2. two", "1. one", "   3. three", "2. two"]);
        assert!(shown.starts_with("3 steps."));
    }

    #[test]
    fn the_end_of_input_all_and_the_last_step_end_the_session() {
        assert!(run_with("").contains("1. one") && !run_with("").contains("2. two"));
        let all = run_with("a\n");
        assert!(all.contains("2. two\n     detail") && all.contains("   3. three"));
        assert!(run_with("\n\n\n").ends_with("(the last step)\n"));
        assert!(run_with("9\nx\nq\n").contains("(steps are numbered 1 to 3)"));
        assert!(run_with("x\n").contains(Words::of(Lang::En).help));
    }

    #[test]
    fn each_step_says_where_it_stands_and_a_pipe_is_echoed() {
        let shown = run_echo("3\nb\nq\n", true);
        assert!(shown.contains("── P → T₁ @ glass, level 2\n   3. three"), "{shown}");
        assert!(shown.contains("── pixel (0)\n1. one"), "{shown}");
        // The answers after their prompts, as a terminal would have shown them.
        assert!(
            shown.contains("[1/3] > 3\n") && shown.contains("[3/3] > b\n") && shown.contains("[2/3] > q\n"),
            "{shown}"
        );
        // Without echo (a terminal), the prompt's line is only ended.
        assert!(run_with("3\n").contains("[1/3] > \n"));
    }

    #[test]
    fn a_line_that_is_not_text_is_answered_and_the_session_goes_on() {
        let mut out = Vec::new();
        session(&three(), Lang::Ro, true, &b"\xff\xfe\n2\nq\n"[..], &mut out).unwrap();
        let shown = String::from_utf8(out).unwrap();
        assert!(shown.contains("[1/3] > \u{fffd}\u{fffd}\n(nu este un răspuns valid; "), "{shown}");
        assert!(shown.contains("[1/3] > 2\n── P @ glass, level 1\n2. two"), "{shown}");
    }

    /// A writer whose every write fails as a full disk does.
    struct Full;

    impl Write for Full {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::ErrorKind::StorageFull.into())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_failed_write_ends_the_session_with_its_error() {
        let ended = session(&three(), Lang::En, false, &b"a\n"[..], &mut Full);
        assert!(matches!(ended, Err(Ended::Write(e)) if e.kind() == std::io::ErrorKind::StorageFull));
    }
}
