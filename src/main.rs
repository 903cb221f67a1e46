//! The gallery: `cargo run --release` runs every worked example, prints one line per example (its
//! checks against closed forms, the worst error as a fraction of its tolerance), writes the pictures
//! (SVG) and a page of everything (`index.html`) to a folder, and exits non-zero if a check fails.
//! `--checks` prints every check, `--notes` the examples' further measurements.

use clap::Parser;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use noether_gallery::{self as gallery, Check, Example, Options, Outcome, Tolerance};
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
    /// Folder for the SVG pictures and the page of the gallery (index.html).
    #[arg(long, value_name = "DIR", default_value = "gallery-out")]
    out: PathBuf,
    /// Print every check (quantity, computed, expected, error, tolerance), not one line per example.
    #[arg(long)]
    checks: bool,
    /// Print the examples' further measurements (also on the page).
    #[arg(long)]
    notes: bool,
}

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
    let seconds = start.elapsed().as_secs_f64();

    let runs: Vec<(Example, Outcome)> = chosen.into_iter().zip(outcomes).collect();
    print_summary(&runs);
    let rows = check_rows(&runs);
    let failed: Vec<[String; 7]> = rows.iter().filter(|r| r[6] != "PASS").cloned().collect();
    if cli.checks {
        println!();
        print_table(&rows);
    } else if !failed.is_empty() {
        println!("\nFailed:");
        print_table(&failed);
    }
    if cli.notes {
        for (ex, outcome) in &runs {
            for n in outcome.iter().flat_map(|r| &r.notes) {
                println!("{}: {n}", ex.name);
            }
        }
    }
    let checks = rows.len();
    let pictures: usize = runs
        .iter()
        .map(|(_, o)| o.as_ref().map_or(0, |r| r.figures.len()))
        .sum();
    println!(
        "\n{} checks: {} passed, {} failed ({seconds:.1} s)",
        checks,
        checks - failed.len(),
        failed.len(),
    );
    match gallery::page::write_index(&cli.out, &runs) {
        Ok(page) => println!(
            "{pictures} pictures and the page of every check: {}",
            page.display()
        ),
        Err(e) => {
            eprintln!("could not write the page into {}: {e}", cli.out.display());
            std::process::exit(1);
        }
    }
    if !failed.is_empty() {
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
                let _ = tx.send((i, gallery::run_caught(ex, opts)));
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

/// One line per example: checks passed of made, the worst error as a fraction of its tolerance
/// (≤ 1 passes), the verdict. Narrow enough for a terminal; `--checks` and the page give the rest.
fn print_summary(runs: &[(Example, Outcome)]) {
    let w = runs.iter().map(|(e, _)| e.name.len()).max().unwrap_or(7).max(7);
    println!("{:w$}  {:>6}  {:>11}  result", "example", "checks", "worst error");
    println!("{}  ------  -----------  ------", "-".repeat(w));
    for (ex, outcome) in runs {
        match outcome {
            Ok(r) if !r.checks.is_empty() => {
                let passed = r.checks.iter().filter(|c| c.passed()).count();
                let worst = r
                    .checks
                    .iter()
                    // A check met exactly counts 0 (also when its tolerance is 0).
                    .map(|c| {
                        if c.error() == 0.0 {
                            0.0
                        } else {
                            c.error() / c.tol()
                        }
                    })
                    .fold(0.0_f64, |m, x| if x.is_nan() { x } else { m.max(x) });
                let verdict = if passed == r.checks.len() { "PASS" } else { "FAIL" };
                println!(
                    "{:w$}  {:>6}  {:>11}  {verdict}",
                    ex.name,
                    format!("{passed}/{}", r.checks.len()),
                    format!("{:.2} tol", worst),
                );
            }
            Ok(_) => println!("{:w$}  {:>6}  {:>11}  FAIL (made no checks)", ex.name, "0/0", "-"),
            Err(e) => println!("{:w$}  {:>6}  {:>11}  FAIL ({})", ex.name, "-", "-", short(e)),
        }
    }
}

/// The first line of an error, at most 60 characters.
fn short(e: &str) -> String {
    let line = e.lines().next().unwrap_or("");
    match line.char_indices().nth(60) {
        Some((i, _)) => format!("{}…", &line[..i]),
        None => line.to_string(),
    }
}

/// Every check as a row of the full table, an example's error as a failed row.
fn check_rows(runs: &[(Example, Outcome)]) -> Vec<[String; 7]> {
    let mut rows = Vec::new();
    for (ex, outcome) in runs {
        match outcome {
            Ok(report) if report.checks.is_empty() => rows.push(error_row(ex.name, "made no checks")),
            Ok(report) => rows.extend(report.checks.iter().map(row)),
            Err(e) => rows.push(error_row(ex.name, e)),
        }
    }
    rows
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
