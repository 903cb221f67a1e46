//! The compiled equations as Rust source: one function, straight-line code over `let` bindings (one
//! per node the outputs need, in the order of evaluation), for ahead-of-time use — a build script
//! writes it into `OUT_DIR` (or a test into the repository) and `include!`s it, and LLVM compiles it
//! with the rest of the crate: the graph's simplified arithmetic at native speed, with no interpreter
//! and no code generator at run time.
//!
//! The function computes exactly what the [`Program`](crate::Program) of the same outputs computes
//! (the same operations in the same order, so the same bits).

use crate::graph::{Binary, Graph, Id, Node, Unary};
use std::fmt::Write;

/// Rust source of `pub fn <name>(x: &[f64; I]) -> [f64; O]`: the `outputs` of `graph` from its first
/// `inputs` inputs, with `doc` as its doc comment (one line per element).
pub fn rust_function(graph: &Graph, inputs: usize, outputs: &[Id], name: &str, doc: &[&str]) -> String {
    let mut s = String::new();
    for line in doc {
        let _ = writeln!(s, "/// {line}");
    }
    let _ = writeln!(s, "#[inline]");
    let _ = writeln!(s, "#[allow(clippy::all, unused_parens)]");
    let _ = writeln!(
        s,
        "pub fn {name}(x: &[f64; {inputs}]) -> [f64; {}] {{",
        outputs.len()
    );
    if outputs.is_empty() {
        let _ = writeln!(s, "    let _ = x;\n    []\n}}");
        return s;
    }
    let needed = graph.needed(outputs);
    for v in (0..needed.len() as Id).filter(|&v| needed[v as usize]) {
        let _ = writeln!(s, "    let v{v}: f64 = {};", expression(graph.node(v)));
    }
    let list: Vec<String> = outputs.iter().map(|y| format!("v{y}")).collect();
    let _ = writeln!(s, "    [{}]\n}}", list.join(", "));
    s
}

/// A constant as a Rust expression (round-trip exact).
fn literal(c: f64) -> String {
    if c.is_nan() {
        "f64::NAN".into()
    } else if c.is_infinite() {
        if c > 0.0 {
            "f64::INFINITY"
        } else {
            "f64::NEG_INFINITY"
        }
        .into()
    } else {
        format!("{c:?}")
    }
}

/// The right-hand side of node `node`'s binding.
fn expression(node: Node) -> String {
    match node {
        Node::Input(k) => format!("x[{k}]"),
        Node::Const(bits) => literal(f64::from_bits(bits)),
        Node::Binary(op, a, b) => match op {
            Binary::Add => format!("v{a} + v{b}"),
            Binary::Sub => format!("v{a} - v{b}"),
            Binary::Mul => format!("v{a} * v{b}"),
            Binary::Div => format!("v{a} / v{b}"),
            Binary::Atan2 => format!("v{a}.atan2(v{b})"),
        },
        Node::Unary(Unary::Neg, a) => format!("-v{a}"),
        Node::Unary(Unary::Sign, a) => format!(
            "if v{a} > 0.0 {{ 1.0 }} else if v{a} < 0.0 {{ -1.0 }} else if v{a} == 0.0 {{ 0.0 }} else {{ f64::NAN }}"
        ),
        Node::Unary(f, a) => format!("v{a}.{}()", f.name()),
        Node::Powi(a, n) => format!("v{a}.powi({n})"),
        Node::Powf(a, e) => format!("v{a}.powf({})", literal(f64::from_bits(e))),
    }
}
