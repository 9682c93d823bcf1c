//! `whitted step`: the narration of `whitted trace`, one numbered step at a time, for a student
//! who follows a pixel's computation number by number. Each answer on stdin moves: Enter (or `n`)
//! to the next step, `b` back, a number to that step, `a` everything left, `q` to quit. Input is
//! read a line at a time, so a terminal and a pipe work alike; the end of input ends the session.
//! Each step shown is headed by where it stands in the ray tree (`P → T₁ → R₂ @ glass, level 3`),
//! so a jump lands somewhere named; an answer read from a pipe is echoed after its prompt, so a
//! transcript shows what was typed (a terminal echoes it itself).

use super::trace::{narration, TraceWhat};
use super::Failure;
use clap::Args;
use std::io::{BufRead, IsTerminal, Write};
use whitted::doc::narrate::{Lang, Step};

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
    // A closed stdout (`| head`) ends the session quietly, as for the other commands.
    let _ = session(&steps, args.what.lang(), echo, stdin.lock(), &mut out);
    Ok(())
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
}

impl Words {
    fn of(lang: Lang) -> Self {
        match lang {
            Lang::En => Self {
                steps: "steps",
                help: "Enter: next · b: back · NUMBER: that step · a: all the rest · q: quit",
                last: "the last step",
                numbered: "steps are numbered 1 to",
            },
            Lang::Ro => Self {
                steps: "pași",
                help: "Enter: următorul · b: înapoi · NUMĂR: acel pas · a: tot restul · q: ieșire",
                last: "ultimul pas",
                numbered: "pașii sunt numerotați de la 1 la",
            },
        }
    }
}

/// One step as shown: its place in the ray tree, then its text.
fn show(out: &mut impl Write, step: &Step) -> std::io::Result<()> {
    if !step.place.is_empty() {
        writeln!(out, "── {}", step.place)?;
    }
    writeln!(out, "{}", step.text)
}

/// Shows `steps` one at a time on `out`, moving as `input` says, until the last step is passed,
/// `q`, or the end of input; with `echo` (input not a terminal), each answer is written after its
/// prompt.
fn session(
    steps: &[Step],
    lang: Lang,
    echo: bool,
    input: impl BufRead,
    out: &mut impl Write,
) -> std::io::Result<()> {
    let words = Words::of(lang);
    let n = steps.len();
    writeln!(out, "{n} {}. {}\n", words.steps, words.help)?;
    let Some(first) = steps.first() else { return Ok(()) };
    show(out, first)?;
    let mut at = 0;
    let mut lines = input.lines();
    loop {
        write!(out, "[{}/{n}] > ", at + 1)?;
        out.flush()?;
        let answer = lines.next().transpose()?;
        // A terminal has echoed the answer and its Enter already; a pipe has not.
        match (&answer, echo) {
            (Some(typed), true) => writeln!(out, "{}", typed.trim_end())?,
            _ => writeln!(out)?,
        }
        let Some(answer) = answer else { return Ok(()) };
        match parse(&answer) {
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
}
