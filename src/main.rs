//! The gallery: `cargo run --release` runs every worked example, prints one table of their checks
//! against closed forms, writes the pictures (SVG) to a folder, and exits non-zero if a check fails.

use clap::Parser;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use noether_gallery::{self as gallery, Check, Example, Options, Report, Tolerance};
use rayon::prelude::*;
use std::path::PathBuf;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Runs noether's worked examples and checks each against its closed form.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Cli {
    /// List the examples and exit.
    #[arg(long)]
    list: bool,
    /// Run only the example NAME (repeatable).
    #[arg(long, value_name = "NAME")]
    only: Vec<String>,
    /// Folder for the SVG pictures.
    #[arg(long, value_name = "DIR", default_value = "gallery-out")]
    out: PathBuf,
}

type Outcome = Result<Report, String>;

fn main() {
    let cli = Cli::parse();
    let examples = gallery::all();
    if cli.list {
        let w = examples.iter().map(|e| e.name.len()).max().unwrap_or(0);
        for e in &examples {
            println!("{:w$}  {}", e.name, e.about);
        }
        return;
    }
    let unknown: Vec<_> = cli
        .only
        .iter()
        .filter(|n| !examples.iter().any(|e| &e.name == n))
        .collect();
    if !unknown.is_empty() {
        eprintln!("no example named {unknown:?}; `--list` shows the names");
        std::process::exit(2);
    }
    let chosen: Vec<Example> = examples
        .into_iter()
        .filter(|e| cli.only.is_empty() || cli.only.iter().any(|n| n == e.name))
        .collect();
    let opts = Options {
        out_dir: Some(cli.out.clone()),
    };
    let start = Instant::now();
    let outcomes = run_all(&chosen, &opts);

    let mut rows = Vec::new();
    let mut figures = Vec::new();
    let mut failed = 0;
    for (ex, outcome) in chosen.iter().zip(outcomes) {
        match outcome {
            Ok(report) => {
                failed += report.checks.iter().filter(|c| !c.passed()).count();
                if report.checks.is_empty() {
                    failed += 1;
                    rows.push(error_row(ex.name, "made no checks"));
                }
                rows.extend(report.checks.iter().map(row));
                figures.extend(report.figures);
            }
            Err(e) => {
                failed += 1;
                rows.push(error_row(ex.name, &e));
            }
        }
    }
    print_table(&rows);
    let total = rows.len();
    println!(
        "\n{} checks: {} passed, {} failed ({:.1} s)",
        total,
        total - failed,
        failed,
        start.elapsed().as_secs_f64()
    );
    if !figures.is_empty() {
        println!(
            "{} pictures (SVG) written to {}/",
            figures.len(),
            cli.out.display()
        );
    }
    if failed > 0 {
        std::process::exit(1);
    }
}

/// Runs the examples in parallel; a progress bar appears on a terminal once the run takes more than
/// a moment. Results come back in the order of `examples`.
fn run_all(examples: &[Example], opts: &Options) -> Vec<Outcome> {
    let bar = ProgressBar::with_draw_target(Some(examples.len() as u64), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("{spinner} [{elapsed}] {bar:30} {pos}/{len} examples {msg}")
            .expect("valid template"),
    );
    let (tx, rx) = mpsc::channel();
    let mut outcomes: Vec<Option<Outcome>> = examples.iter().map(|_| None).collect();
    std::thread::scope(|s| {
        s.spawn(move || {
            examples.par_iter().enumerate().for_each_with(tx, |tx, (i, ex)| {
                let outcome = std::panic::catch_unwind(|| (ex.run)(opts))
                    .map_err(|p| panic_message(&p))
                    .and_then(|r| r.map_err(|e| e.to_string()));
                let _ = tx.send((i, outcome));
            });
        });
        let mut shown = false;
        let mut done = 0;
        while done < examples.len() {
            match rx.recv_timeout(Duration::from_millis(100)) {
                Ok((i, outcome)) => {
                    outcomes[i] = Some(outcome);
                    done += 1;
                    bar.inc(1);
                    bar.set_message(examples[i].name);
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(mpsc::RecvTimeoutError::Disconnected) => break,
            }
            if !shown && bar.elapsed() > Duration::from_millis(300) {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                bar.enable_steady_tick(Duration::from_millis(100));
                shown = true;
            }
        }
    });
    bar.finish_and_clear();
    outcomes
        .into_iter()
        .map(|o| o.unwrap_or_else(|| Err("did not finish".into())))
        .collect()
}

fn panic_message(p: &Box<dyn std::any::Any + Send>) -> String {
    let msg = p
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown".into());
    format!("panicked: {msg}")
}

const HEADER: [&str; 7] = [
    "example",
    "quantity",
    "computed",
    "expected",
    "rel. error",
    "tolerance",
    "result",
];

fn row(c: &Check) -> [String; 7] {
    let abs = matches!(c.tolerance, Tolerance::Absolute(_));
    [
        c.example.to_string(),
        c.quantity.clone(),
        format!("{:.10e}", c.computed),
        format!("{:.10e}", c.expected),
        format!("{:.2e}{}", c.error(), if abs { " (abs)" } else { "" }),
        format!("{:.0e}", c.tol()),
        if c.passed() { "PASS" } else { "FAIL" }.to_string(),
    ]
}

fn error_row(example: &str, msg: &str) -> [String; 7] {
    [
        example.to_string(),
        format!("error: {msg}"),
        "-".into(),
        "-".into(),
        "-".into(),
        "-".into(),
        "FAIL".into(),
    ]
}

fn print_table(rows: &[[String; 7]]) {
    // Display width: combining marks (the dot of q̇, the hat of ẑ) take no column.
    let width = |s: &str| s.chars().filter(|c| !('\u{300}'..='\u{36f}').contains(c)).count();
    let mut w: Vec<usize> = HEADER.iter().map(|h| width(h)).collect();
    for r in rows {
        for (wi, cell) in w.iter_mut().zip(r) {
            *wi = (*wi).max(width(cell));
        }
    }
    let line = |cells: &[String]| {
        let parts: Vec<String> = cells
            .iter()
            .zip(&w)
            .enumerate()
            .map(|(i, (c, &wi))| {
                let pad = " ".repeat(wi - width(c));
                // Numbers right-aligned, text left-aligned.
                if (2..6).contains(&i) {
                    format!("{pad}{c}")
                } else {
                    format!("{c}{pad}")
                }
            })
            .collect();
        println!("{}", parts.join("  ").trim_end());
    };
    line(&HEADER.map(String::from));
    println!(
        "{}",
        w.iter().map(|&n| "-".repeat(n)).collect::<Vec<_>>().join("  ")
    );
    for r in rows {
        line(r);
    }
}
