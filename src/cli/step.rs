//! `whitted step`: the narration of `whitted trace`, one numbered step at a time, for a student
//! who follows a pixel's computation number by number. Each answer on stdin moves: Enter (or `n`)
//! to the next step, `b` back, a number to that step, `a` everything left, `q` to quit. Input is
//! read a line at a time, so a terminal and a pipe work alike; the end of input ends the session.

use super::trace::{narration, TraceWhat};
use super::Failure;
use clap::Args;
use std::io::{BufRead, Write};
use whitted::doc::narrate::{steps, Lang};

/// Options of `whitted step`: those of `whitted trace` without `--json`.
#[derive(Args, Debug)]
pub struct StepArgs {
    #[command(flatten)]
    what: TraceWhat,
}

/// Runs `whitted step`.
pub fn run(args: &StepArgs) -> Result<(), Failure> {
    let steps = steps(&narration(&args.what)?);
    let stdin = std::io::stdin();
    let mut out = std::io::stdout().lock();
    // A closed stdout (`| head`) ends the session quietly, as for the other commands.
    let _ = session(&steps, args.what.lang(), stdin.lock(), &mut out);
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

/// Shows `steps` one at a time on `out`, moving as `input` says, until the last step is passed,
/// `q`, or the end of input.
fn session(steps: &[String], lang: Lang, input: impl BufRead, out: &mut impl Write) -> std::io::Result<()> {
    let words = Words::of(lang);
    let n = steps.len();
    writeln!(out, "{n} {}. {}\n", words.steps, words.help)?;
    let Some(first) = steps.first() else { return Ok(()) };
    writeln!(out, "{first}")?;
    let mut at = 0;
    let mut lines = input.lines();
    loop {
        write!(out, "[{}/{n}] > ", at + 1)?;
        out.flush()?;
        let answer = lines.next().transpose()?;
        // A piped answer is not echoed: end the prompt's line either way.
        writeln!(out)?;
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
                    writeln!(out, "{step}")?;
                }
                return Ok(());
            }
            Move::Quit => return Ok(()),
            Move::Unknown => {
                writeln!(out, "({})", words.help)?;
                continue;
            }
        }
        writeln!(out, "{}", steps[at])?;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run_with(input: &str) -> String {
        let steps: Vec<String> = ["1. one", "2. two\n     detail", "   3. three"].map(String::from).to_vec();
        let mut out = Vec::new();
        session(&steps, Lang::En, input.as_bytes(), &mut out).unwrap();
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
}
