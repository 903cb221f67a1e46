//! The gallery as one page: `index.html` in the picture folder, with every example's checks
//! (computed, expected, error, tolerance, verdict), its notes, its pictures inline, the commands that
//! run it alone and a link to its source. A page to open in a browser, with no script and no
//! dependency: the pictures are the SVG files beside it.

use crate::{Check, Example, Outcome, Tolerance};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The file name of the page inside the picture folder.
pub const INDEX: &str = "index.html";

/// Writes `index.html` into `dir` for the examples and what running them gave (in that order), and
/// returns its path. Pictures are linked relative to `dir` (where [`Report::save`](crate::Report::save)
/// writes them); the sources by their path in this repository.
pub fn write_index(dir: &Path, runs: &[(Example, Outcome)]) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join(INDEX);
    std::fs::write(&path, render(dir, runs))?;
    Ok(path)
}

/// The page's HTML (see [`write_index`]).
pub fn render(dir: &Path, runs: &[(Example, Outcome)]) -> String {
    let (checks, failed) = runs.iter().fold((0, 0), |(n, f), (_, o)| match o {
        Ok(r) => (
            n + r.checks.len(),
            f + r.checks.iter().filter(|c| !c.passed()).count(),
        ),
        Err(_) => (n + 1, f + 1),
    });
    let mut h = String::new();
    h.push_str(HEAD);
    let _ = write!(
        h,
        "<h1>The noether gallery</h1>\n<p>{} examples, {} checks against closed forms: {} passed, {} failed. \
         Each example is a complete program in <code>examples/</code>; <code>cargo run --release</code> \
         runs them all and writes this page.</p>\n<ol class=\"toc\">\n",
        runs.len(),
        checks,
        checks - failed,
        failed
    );
    for (ex, outcome) in runs {
        let _ = writeln!(
            h,
            "<li><a href=\"#{0}\">{0}</a> {1} <span class=\"about\">{2}</span></li>",
            ex.name,
            verdict(outcome),
            esc(ex.about)
        );
    }
    h.push_str("</ol>\n");
    for (ex, outcome) in runs {
        section(&mut h, dir, ex, outcome);
    }
    h.push_str("</body>\n</html>\n");
    h
}

/// One example's section: title, commands, source, checks, notes, pictures.
fn section(h: &mut String, dir: &Path, ex: &Example, outcome: &Outcome) {
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(format!("{}.rs", ex.name));
    let _ = write!(
        h,
        "<section id=\"{name}\">\n<h2>{name} {verdict}</h2>\n<p>{about}</p>\n\
         <p class=\"run\">Alone: <code>cargo run --release -- --only {name}</code> or \
         <code>cargo run --release --features examples --example {name}</code>; \
         source <a href=\"{src}\"><code>examples/{name}.rs</code></a></p>\n",
        name = ex.name,
        verdict = verdict(outcome),
        about = esc(ex.about),
        src = esc(&file_url(&source)),
    );
    match outcome {
        Err(e) => {
            let _ = writeln!(h, "<p class=\"fail\">error: {}</p>", esc(e));
        }
        Ok(report) => {
            h.push_str(
                "<table>\n<tr><th>quantity</th><th>computed</th><th>expected</th><th>error</th>\
                 <th>tolerance</th><th></th></tr>\n",
            );
            for c in &report.checks {
                check_row(h, c);
            }
            h.push_str("</table>\n");
            if !report.notes.is_empty() {
                h.push_str("<pre class=\"notes\">");
                for n in &report.notes {
                    let _ = writeln!(h, "{}", esc(n));
                }
                h.push_str("</pre>\n");
            }
            for f in &report.figures {
                let rel = f.strip_prefix(dir).unwrap_or(f);
                let _ = writeln!(
                    h,
                    "<figure><img src=\"{0}\" alt=\"{0}\"><figcaption>{0}</figcaption></figure>",
                    esc(&rel.to_string_lossy())
                );
            }
        }
    }
    h.push_str("</section>\n");
}

fn check_row(h: &mut String, c: &Check) {
    let kind = match c.tolerance {
        Tolerance::Relative(_) => "rel.",
        Tolerance::Absolute(_) => "abs.",
    };
    let ok = c.passed();
    let _ = writeln!(
        h,
        "<tr class=\"{}\"><td>{}</td><td>{:.12e}</td><td>{:.12e}</td><td>{:.2e} {kind}</td>\
         <td>{:.1e}</td><td>{}</td></tr>",
        if ok { "pass" } else { "fail" },
        esc(&c.quantity),
        c.computed,
        c.expected,
        c.error(),
        c.tol(),
        if ok { "PASS" } else { "FAIL" },
    );
}

/// PASS when the example ran and every check passed, FAIL otherwise.
fn verdict(outcome: &Outcome) -> &'static str {
    match outcome {
        Ok(r) if !r.checks.is_empty() && r.checks.iter().all(Check::passed) => {
            "<span class=\"pass\">PASS</span>"
        }
        _ => "<span class=\"fail\">FAIL</span>",
    }
}

/// A `file://` address for a local path (absolute paths only; the repository's own).
fn file_url(p: &Path) -> String {
    format!("file://{}", p.display()).replace(' ', "%20")
}

/// Text escaped for HTML.
fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            _ => o.push(c),
        }
    }
    o
}

const HEAD: &str = "<!DOCTYPE html>
<html lang=\"en\">
<head>
<meta charset=\"utf-8\">
<title>noether gallery</title>
<style>
body { font-family: system-ui, sans-serif; max-width: 70rem; margin: 2rem auto; padding: 0 1rem; }
table { border-collapse: collapse; font-size: 0.9rem; }
td, th { padding: 0.15rem 0.6rem; text-align: right; border-bottom: 1px solid #ddd; }
td:first-child, th:first-child { text-align: left; }
.pass { color: #1a7f37; } .fail { color: #cf222e; font-weight: bold; }
.about { color: #555; } .run { font-size: 0.9rem; }
figure { display: inline-block; margin: 0.5rem; } img { max-width: 32rem; }
figcaption { font-size: 0.8rem; color: #555; }
section { border-top: 1px solid #bbb; margin-top: 2rem; }
</style>
</head>
<body>
";
