//! The compiled equations shown: as formulas, in text or LaTeX ([`Equations`]), and as Rust source
//! ([`rust_function`]).
//!
//! The Rust source is one function, straight-line code over `let` bindings (one per node the outputs
//! need, in the order of evaluation), for ahead-of-time use — a build script writes it into `OUT_DIR`
//! (or a test into the repository) and `include!`s it, and LLVM compiles it with the rest of the
//! crate: the graph's simplified arithmetic at native speed, with no interpreter and no code generator
//! at run time. It computes exactly what the [`Program`](crate::Program) of the same outputs computes
//! (the same operations in the same order, so the same bits).
//!
//! The formulas are the simplified graph written out as expressions, each shared subexpression
//! repeated where it is used (so they are for models of a few degrees of freedom: a 10-link chain's
//! are pages long).

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

/// How formulas are written: Unicode text (`θ̇₂²·sin(θ₁ − θ₂)`) or LaTeX (`\dot{\theta}_2^{2} \, \sin\left(\theta_1 - \theta_2\right)`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Notation {
    /// Unicode text.
    Text,
    /// LaTeX (math mode).
    Latex,
}

/// Node `y` of `graph` as a formula in `notation`, input k printed as `names[k]`.
///
/// For reading, not for computing: the node is rewritten as a sum of terms c·∏ bᵉ — products
/// distributed over sums while that stays small, equal bases collected into powers, like terms
/// collected, constant factors multiplied out — so that, for instance, the double pendulum's
/// force term prints as `−19.62·sin(θ₁) − θ̇₂²·sin(θ₁ − θ₂)`, as in a textbook. Coefficients are shown
/// to ten significant digits.
pub fn formula(graph: &Graph, y: Id, names: &[String], notation: Notation) -> String {
    let mut writer = Writer {
        graph,
        names,
        notation,
        memo: std::collections::HashMap::new(),
    };
    let sum = writer.sum(y);
    writer.write(&sum)
}

/// Products of at most this many terms are distributed (a product of two sums of 4 terms each, say).
const DISTRIBUTE_MAX: usize = 16;

/// A factor b of a product: a name (rank 0), a function of something (rank 1) or a sum in
/// parentheses (rank 2), as printed; factors are ordered by rank, then text.
type Base = (u8, String);

/// A term c·∏ bᵉ (a monomial in the bases), its factors in order, each base once.
#[derive(Clone, Debug)]
struct Monomial {
    c: f64,
    factors: Vec<(Base, f64)>,
}

/// A sum of terms, like terms collected (empty: zero).
type Sum = Vec<Monomial>;

struct Writer<'a> {
    graph: &'a Graph,
    names: &'a [String],
    notation: Notation,
    memo: std::collections::HashMap<Id, Sum>,
}

impl Writer<'_> {
    fn latex(&self) -> bool {
        self.notation == Notation::Latex
    }

    /// Node `x` as a sum of terms (each node rewritten once).
    fn sum(&mut self, x: Id) -> Sum {
        if let Some(s) = self.memo.get(&x) {
            return s.clone();
        }
        let s = match self.graph.node(x) {
            Node::Input(k) => base((0, self.names[k as usize].clone())),
            Node::Const(bits) => constant(f64::from_bits(bits)),
            Node::Binary(Binary::Add, a, b) => add(self.sum(a), self.sum(b)),
            Node::Binary(Binary::Sub, a, b) => add(self.sum(a), negate(self.sum(b))),
            Node::Binary(Binary::Mul, a, b) => {
                let (a, b) = (self.sum(a), self.sum(b));
                self.multiply(a, b)
            }
            Node::Binary(Binary::Div, a, b) => {
                let (a, b) = (self.sum(a), self.sum(b));
                let b = self.power(b, -1.0);
                self.multiply(a, b)
            }
            Node::Binary(Binary::Atan2, a, b) => {
                let args = format!("{}, {}", self.text(a), self.text(b));
                base((1, self.call("atan2", &args)))
            }
            Node::Unary(Unary::Neg, a) => negate(self.sum(a)),
            Node::Unary(Unary::Recip, a) => {
                let a = self.sum(a);
                self.power(a, -1.0)
            }
            Node::Unary(f, a) => {
                let a = self.text(a);
                base((1, self.function(f, &a)))
            }
            Node::Powi(a, n) => {
                let a = self.sum(a);
                self.power(a, f64::from(n))
            }
            Node::Powf(a, e) => {
                let a = self.sum(a);
                self.power(a, f64::from_bits(e))
            }
        };
        self.memo.insert(x, s.clone());
        s
    }

    fn text(&mut self, x: Id) -> String {
        let s = self.sum(x);
        self.write(&s)
    }

    /// a·b, distributed when that stays small, else with the sums as factors in parentheses.
    fn multiply(&self, a: Sum, b: Sum) -> Sum {
        if a.len() * b.len() > DISTRIBUTE_MAX {
            let (a, b) = (self.as_factor(a), self.as_factor(b));
            return self.multiply(a, b);
        }
        let mut out: Sum = Vec::new();
        for s in &a {
            for t in &b {
                let mut factors = s.factors.clone();
                for (b, e) in &t.factors {
                    match factors.iter_mut().find(|f| &f.0 == b) {
                        Some(f) => f.1 += e,
                        None => factors.push((b.clone(), *e)),
                    }
                }
                factors.retain(|f| f.1 != 0.0);
                factors.sort_by(|x, y| x.0.cmp(&y.0));
                out = add(
                    out,
                    vec![Monomial {
                        c: s.c * t.c,
                        factors,
                    }],
                );
            }
        }
        out
    }

    /// aᵉ: exponents multiplied for a single term, else the sum in parentheses to the power e.
    fn power(&self, a: Sum, e: f64) -> Sum {
        match a.as_slice() {
            [t] => vec![Monomial {
                c: t.c.powf(e),
                factors: t.factors.iter().map(|(b, x)| (b.clone(), x * e)).collect(),
            }],
            _ => {
                let mut f = self.as_factor(a);
                f[0].factors[0].1 = e;
                f
            }
        }
    }

    /// A sum of several terms as one factor in parentheses (a single term as it is).
    fn as_factor(&self, a: Sum) -> Sum {
        if a.len() <= 1 {
            return a;
        }
        let inner = self.write(&a);
        base((2, self.parenthesised(&inner)))
    }

    fn parenthesised(&self, s: &str) -> String {
        if self.latex() {
            format!("\\left({s}\\right)")
        } else {
            format!("({s})")
        }
    }

    fn call(&self, f: &str, args: &str) -> String {
        format!("{f}{}", self.parenthesised(args))
    }

    fn function(&self, f: Unary, a: &str) -> String {
        match (f, self.latex()) {
            (Unary::Sqrt, true) => format!("\\sqrt{{{a}}}"),
            (Unary::Cbrt, true) => format!("\\sqrt[3]{{{a}}}"),
            (Unary::Abs, true) => format!("\\left|{a}\\right|"),
            (Unary::Abs, false) => format!("|{a}|"),
            (f, latex) => self.call(function_name(f, latex), a),
        }
    }

    /// A sum as printed: terms joined by + and −.
    fn write(&self, s: &Sum) -> String {
        let minus = if self.latex() { "-" } else { "−" };
        if s.is_empty() {
            return "0".into();
        }
        let mut out = String::new();
        for (k, t) in s.iter().enumerate() {
            let sign = match (k, t.c < 0.0) {
                (0, true) => minus.to_string(),
                (0, false) => String::new(),
                (_, true) => format!(" {minus} "),
                (_, false) => " + ".into(),
            };
            out.push_str(&sign);
            out.push_str(&self.write_term(t.c.abs(), &t.factors));
        }
        out
    }

    /// c·∏ bᵉ (c ≥ 0) as printed: the factors of positive exponent over those of negative.
    fn write_term(&self, c: f64, factors: &[(Base, f64)]) -> String {
        let dot = if self.latex() { " \\, " } else { "·" };
        let part = |positive: bool| -> Vec<String> {
            factors
                .iter()
                .filter(|f| (f.1 > 0.0) == positive)
                .map(|(b, e)| self.write_power(&b.1, e.abs()))
                .collect()
        };
        let (mut top, bottom) = (part(true), part(false));
        if c != 1.0 || top.is_empty() && bottom.is_empty() {
            top.insert(0, number(c));
        }
        let numerator = if top.is_empty() {
            "1".to_string()
        } else {
            top.join(dot)
        };
        if bottom.is_empty() {
            return numerator;
        }
        let denominator = bottom.join(dot);
        if self.latex() {
            return format!("\\frac{{{numerator}}}{{{denominator}}}");
        }
        let denominator = if bottom.len() > 1 {
            self.parenthesised(&denominator)
        } else {
            denominator
        };
        format!("{numerator}/{denominator}")
    }

    fn write_power(&self, b: &str, e: f64) -> String {
        if e == 1.0 {
            return b.to_string();
        }
        let e = number(e);
        if self.latex() {
            return format!("{b}^{{{e}}}");
        }
        match superscript(&e) {
            Some(s) => format!("{b}{s}"),
            None => format!("{b}^{e}"),
        }
    }
}

/// The sum of one term 1·b.
fn base(b: Base) -> Sum {
    vec![Monomial {
        c: 1.0,
        factors: vec![(b, 1.0)],
    }]
}

/// The sum of one constant term (none for zero).
fn constant(c: f64) -> Sum {
    if c == 0.0 {
        Vec::new()
    } else {
        vec![Monomial {
            c,
            factors: Vec::new(),
        }]
    }
}

fn negate(mut a: Sum) -> Sum {
    a.iter_mut().for_each(|t| t.c = -t.c);
    a
}

/// a + b, like terms (the same factors) collected where the first stands, zero terms dropped.
fn add(mut a: Sum, b: Sum) -> Sum {
    for t in b {
        match a
            .iter_mut()
            .find(|s| s.factors.len() == t.factors.len() && s.factors == t.factors)
        {
            Some(s) => s.c += t.c,
            None => a.push(t),
        }
    }
    a.retain(|t| t.c != 0.0);
    a
}

/// A coefficient or exponent as printed: integers exactly, others to ten significant digits.
fn number(c: f64) -> String {
    if c.fract() == 0.0 && c.abs() < 1e15 {
        return format!("{c}");
    }
    if c != 0.0 && (c.abs() < 1e-4 || c.abs() >= 1e10) {
        return format!("{c:.9e}");
    }
    let digits = (9 - c.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{c:.digits$}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `e` in Unicode superscripts, when every character has one.
fn superscript(e: &str) -> Option<String> {
    e.chars()
        .map(|c| match c {
            '-' => Some('⁻'),
            '0'..='9' => "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().nth(c as usize - '0' as usize),
            _ => None,
        })
        .collect()
}

/// The name of a function of one argument, in text or as a LaTeX command.
fn function_name(f: Unary, latex: bool) -> &'static str {
    if !latex {
        return match f {
            Unary::Sqrt => "√",
            Unary::Ln1p => "ln_1p",
            _ => f.name(),
        };
    }
    match f {
        Unary::Exp => "\\exp",
        Unary::Ln => "\\ln",
        Unary::Sin => "\\sin",
        Unary::Cos => "\\cos",
        Unary::Tan => "\\tan",
        Unary::Asin => "\\arcsin",
        Unary::Acos => "\\arccos",
        Unary::Atan => "\\arctan",
        Unary::Sinh => "\\sinh",
        Unary::Cosh => "\\cosh",
        Unary::Tanh => "\\tanh",
        Unary::Sign => "\\operatorname{sgn}",
        Unary::ExpM1 => "\\operatorname{expm1}",
        Unary::Ln1p => "\\operatorname{ln1p}",
        Unary::Asinh => "\\operatorname{arsinh}",
        Unary::Acosh => "\\operatorname{arcosh}",
        Unary::Atanh => "\\operatorname{artanh}",
        Unary::Neg | Unary::Recip | Unary::Sqrt | Unary::Cbrt | Unary::Abs => {
            unreachable!("printed by their own rule")
        }
    }
}

/// What one equation of an [`Equations`] gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Term {
    /// Entry (i, j), i ≥ j, of the mass matrix M of M q̈ = b (M is symmetric).
    Mass(usize, usize),
    /// Entry i of b = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t (+ Q) in M q̈ = b.
    Force(usize),
    /// q̈_i itself (a natural system: q̈ = −M⁻¹∇V(q)).
    Acceleration(usize),
    /// q̇_i = ∂H/∂p_i.
    Velocity(usize),
    /// ṗ_i = −∂H/∂q_i.
    MomentumRate(usize),
}

/// The equations of motion of a compiled system as formulas of its simplified graph: each [`Term`]
/// with the node that gives it. Written out by [`text`](Self::text) and [`latex`](Self::latex)
/// (with the names of the coordinates), or by `Display` (coordinates q₁, q₂, …); evaluated by
/// [`evaluate`](Self::evaluate), to check them against a closed form.
#[derive(Clone, Debug)]
pub struct Equations {
    graph: Graph,
    rows: Vec<(Term, Id)>,
    dof: usize,
    momenta: bool,
}

impl Equations {
    /// The equations `rows` on `graph`, whose inputs are (t, q, then q̇ or — `momenta` — p) for `dof`
    /// coordinates.
    pub(crate) fn new(graph: Graph, rows: Vec<(Term, Id)>, dof: usize, momenta: bool) -> Self {
        Equations {
            graph,
            rows,
            dof,
            momenta,
        }
    }

    /// The terms, in the order they are written and evaluated.
    pub fn terms(&self) -> Vec<Term> {
        self.rows.iter().map(|r| r.0).collect()
    }

    /// The value of each term (in the order of [`terms`](Self::terms)) at `inputs` = (t, q, q̇ or p).
    pub fn evaluate(&self, inputs: &[f64]) -> Vec<f64> {
        let last = self.rows.iter().map(|r| r.1).max().unwrap_or(0);
        let values = self.graph.evaluate(inputs, last);
        self.rows.iter().map(|r| values[r.1 as usize]).collect()
    }

    /// The formula of `term` in `notation`, the coordinates named `coordinates` (empty: q₁, q₂, …).
    pub fn formula(&self, term: Term, coordinates: &[&str], notation: Notation) -> Option<String> {
        let (_, y) = self.rows.iter().find(|r| r.0 == term)?;
        Some(formula(
            &self.graph,
            *y,
            &self.input_names(coordinates, notation),
            notation,
        ))
    }

    /// Every equation on a line of its own, `name = formula`, in Unicode text.
    pub fn text(&self, coordinates: &[&str]) -> String {
        self.write(coordinates, Notation::Text)
    }

    /// Every equation in a LaTeX `aligned` environment.
    pub fn latex(&self, coordinates: &[&str]) -> String {
        self.write(coordinates, Notation::Latex)
    }

    fn write(&self, coordinates: &[&str], notation: Notation) -> String {
        let names = self.input_names(coordinates, notation);
        let coordinate = |i: usize| names[1 + i].as_str();
        let lines: Vec<String> = self
            .rows
            .iter()
            .map(|&(term, y)| {
                let lhs = label(term, notation, coordinate);
                let rhs = formula(&self.graph, y, &names, notation);
                match notation {
                    Notation::Text => format!("{lhs} = {rhs}"),
                    Notation::Latex => format!("{lhs} &= {rhs}"),
                }
            })
            .collect();
        match notation {
            Notation::Text => lines.join("\n"),
            Notation::Latex => format!("\\begin{{aligned}}\n{}\n\\end{{aligned}}", lines.join(" \\\\\n")),
        }
    }

    /// The names of the inputs: t, the coordinates, their velocities (dotted) or momenta p_i, Q_i.
    fn input_names(&self, coordinates: &[&str], notation: Notation) -> Vec<String> {
        let n = self.dof;
        let q: Vec<String> = if coordinates.len() == n {
            coordinates.iter().map(|s| s.to_string()).collect()
        } else {
            (0..n).map(|i| indexed("q", &[i], notation)).collect()
        };
        let mut names = vec!["t".to_string()];
        names.extend(q.iter().cloned());
        names.extend((0..n).map(|i| {
            if self.momenta {
                indexed("p", &[i], notation)
            } else {
                dotted(&q[i], 1, notation)
            }
        }));
        names
    }
}

impl std::fmt::Display for Equations {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text(&[]))
    }
}

/// The left-hand side of a term's equation.
fn label<'a>(term: Term, notation: Notation, coordinate: impl Fn(usize) -> &'a str) -> String {
    match term {
        Term::Mass(i, j) => indexed("M", &[i, j], notation),
        Term::Force(i) => indexed("b", &[i], notation),
        Term::Acceleration(i) => dotted(coordinate(i), 2, notation),
        Term::Velocity(i) => dotted(coordinate(i), 1, notation),
        Term::MomentumRate(i) => dotted(&indexed("p", &[i], notation), 1, notation),
    }
}

/// `base` with the 1-based indices as subscripts: M₁₂ (M₁₀,₁₁ past 9), M_{12} in LaTeX.
fn indexed(base: &str, indices: &[usize], notation: Notation) -> String {
    let wide = indices.iter().any(|&i| i >= 9);
    let parts: Vec<String> = indices.iter().map(|i| (i + 1).to_string()).collect();
    let joined = parts.join(if wide { "," } else { "" });
    match notation {
        Notation::Latex => format!("{base}_{{{joined}}}"),
        Notation::Text => {
            let sub: String = joined
                .chars()
                .map(|c| match c {
                    '0'..='9' => "₀₁₂₃₄₅₆₇₈₉".chars().nth(c as usize - '0' as usize).unwrap_or(c),
                    c => c,
                })
                .collect();
            format!("{base}{sub}")
        }
    }
}

/// `name` with `dots` dots over it (1 or 2): over its first character in text (θ̇₁), over the part
/// before a subscript or superscript in LaTeX (\dot{\theta}_1).
fn dotted(name: &str, dots: usize, notation: Notation) -> String {
    match notation {
        Notation::Text => {
            let mark = if dots == 2 { '\u{308}' } else { '\u{307}' };
            let mut chars = name.chars();
            let first = chars.next().map(String::from).unwrap_or_default();
            format!("{first}{mark}{}", chars.as_str())
        }
        Notation::Latex => {
            let command = if dots == 2 { "\\ddot" } else { "\\dot" };
            let cut = name.find(['_', '^']).unwrap_or(name.len());
            format!("{command}{{{}}}{}", &name[..cut], &name[cut..])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The formulas of a few graphs, in text and LaTeX: signs pulled out of products, like terms
    /// collected, equal factors as powers, divisions as fractions.
    #[test]
    fn formulas_read_as_written() {
        let mut g = Graph::new();
        let (x, y) = (g.input(0), g.input(1));
        let names = ["x".to_string(), "y".to_string()];
        let show = |g: &Graph, id| {
            (
                formula(g, id, &names, Notation::Text),
                formula(g, id, &names, Notation::Latex),
            )
        };
        // x·(−3y) + x·y + (x + 1)/(y·y)
        let m3 = g.scale(-3.0, y);
        let a = g.mul(x, m3);
        let b = g.mul(x, y);
        let s = g.add(a, b);
        let one = g.constant(1.0);
        let x1 = g.add(x, one);
        let yy = g.mul(y, y);
        let d = g.div(x1, yy);
        let e = g.add(s, d);
        assert_eq!(
            show(&g, e),
            (
                "−2·x·y + x/y² + 1/y²".to_string(),
                "-2 \\, x \\, y + \\frac{x}{y^{2}} + \\frac{1}{y^{2}}".to_string()
            )
        );
        // √(x)·sin(y)^3 − 0.1234567890123 (ten significant digits; factors ordered by their text)
        let r = g.unary(Unary::Sqrt, x);
        let sy = g.unary(Unary::Sin, y);
        let p = g.powi(sy, 3);
        let rp = g.mul(r, p);
        let c = g.constant(0.1234567890123);
        let f = g.sub(rp, c);
        assert_eq!(show(&g, f).0, "sin(y)³·√(x) − 0.123456789");
        assert_eq!(
            show(&g, f).1,
            "\\sin\\left(y\\right)^{3} \\, \\sqrt{x} - 0.123456789"
        );
        // x − x is 0 (the graph folds it; a sum whose terms cancel prints 0 as well).
        let z = g.sub(a, a);
        assert_eq!(show(&g, z).0, "0");
    }
}
