//! Derivatives on the graph: the chain rule applied once to the recorded operations, building the
//! derivative as new nodes of the same graph (so that it shares every subexpression with the value).
//!
//! Each operation v = φ(a, b) contributes its partials ∂φ/∂a, ∂φ/∂b, themselves nodes
//! ([`partials`]). Reverse accumulation ([`gradient`]) gives the whole gradient of one output,
//!
//! ```text
//! v̄ = ∂y/∂v:   ȳ = 1,   ā += v̄ ∂φ/∂a,   b̄ += v̄ ∂φ/∂b   over the nodes from y down,
//! ```
//!
//! and forward accumulation ([`directional`]) the derivative of many outputs along one direction,
//!
//! ```text
//! v̇ = ∂φ/∂a ȧ + ∂φ/∂b ḃ   over the nodes from the inputs up, from the seeds ẋ of the inputs:
//! ```
//!
//! one pass each, whichever needs fewer for the outputs wanted. Only nodes that depend on the
//! variables of the derivative take part, so a term free of them adds no node.

use crate::graph::{Binary, Graph, Id, Node, Unary};

/// (∂φ/∂a, ∂φ/∂b) of node `v` = φ(a, b), as nodes (`None` where φ has no such argument):
///
/// ```text
/// a ± b: 1, ±1      a·b: b, a      a/b: 1/b, −v/b      atan2(a, b): b/(a² + b²), −a/(a² + b²)
/// −a: −1   1/a: −v²   √a: 1/(2v)   ∛a: v/(3a)   eᵃ: v   eᵃ − 1: v + 1   ln a: 1/a   ln(1 + a): 1/(1 + a)
/// sin: cos a   cos: −sin a   tan: 1 + v²   asin: 1/√(1 − a²)   acos: −1/√(1 − a²)   atan: 1/(1 + a²)
/// sinh: cosh a   cosh: sinh a   tanh: 1 − v²   asinh: 1/√(a² + 1)   acosh: 1/√(a² − 1)
/// atanh: 1/(1 − a²)   |a|: sign a   sign a: 0   aⁿ: n aⁿ⁻¹   aᵉ: e aᵉ⁻¹
/// ```
pub fn partials(g: &mut Graph, v: Id) -> (Option<Id>, Option<Id>) {
    match g.node(v) {
        Node::Input(_) | Node::Const(_) => (None, None),
        Node::Binary(op, a, b) => {
            let (da, db) = binary_partials(g, op, v, a, b);
            (Some(da), Some(db))
        }
        Node::Unary(f, a) => (Some(unary_partial(g, f, v, a)), None),
        Node::Powi(a, n) => {
            let p = g.powi(a, n - 1);
            (Some(g.scale(f64::from(n), p)), None)
        }
        Node::Powf(a, bits) => {
            let e = f64::from_bits(bits);
            let p = g.powf(a, e - 1.0);
            (Some(g.scale(e, p)), None)
        }
    }
}

fn binary_partials(g: &mut Graph, op: Binary, v: Id, a: Id, b: Id) -> (Id, Id) {
    match op {
        Binary::Add => {
            let one = g.constant(1.0);
            (one, one)
        }
        Binary::Sub => (g.constant(1.0), g.constant(-1.0)),
        Binary::Mul => (b, a),
        Binary::Div => {
            let one = g.constant(1.0);
            let r = g.div(one, b);
            let q = g.div(v, b);
            (r, g.neg(q))
        }
        Binary::Atan2 => {
            let (aa, bb) = (g.mul(a, a), g.mul(b, b));
            let r2 = g.add(aa, bb);
            let da = g.div(b, r2);
            let q = g.div(a, r2);
            (da, g.neg(q))
        }
    }
}

fn unary_partial(g: &mut Graph, f: Unary, v: Id, a: Id) -> Id {
    let one = g.constant(1.0);
    match f {
        Unary::Neg => g.constant(-1.0),
        Unary::Recip => {
            let vv = g.mul(v, v);
            g.neg(vv)
        }
        Unary::Sqrt => {
            let two_v = g.scale(2.0, v);
            g.div(one, two_v)
        }
        Unary::Cbrt => {
            let three_a = g.scale(3.0, a);
            g.div(v, three_a)
        }
        Unary::Exp => v,
        Unary::ExpM1 => g.add(v, one),
        Unary::Ln => g.div(one, a),
        Unary::Ln1p => {
            let s = g.add(one, a);
            g.div(one, s)
        }
        Unary::Sin => g.unary(Unary::Cos, a),
        Unary::Cos => {
            let s = g.unary(Unary::Sin, a);
            g.neg(s)
        }
        Unary::Tan => {
            let vv = g.mul(v, v);
            g.add(one, vv)
        }
        Unary::Asin | Unary::Acos => {
            let aa = g.mul(a, a);
            let d = g.sub(one, aa);
            let r = g.unary(Unary::Sqrt, d);
            let p = g.div(one, r);
            if f == Unary::Asin {
                p
            } else {
                g.neg(p)
            }
        }
        Unary::Atan => {
            let aa = g.mul(a, a);
            let d = g.add(one, aa);
            g.div(one, d)
        }
        Unary::Sinh => g.unary(Unary::Cosh, a),
        Unary::Cosh => g.unary(Unary::Sinh, a),
        Unary::Tanh => {
            let vv = g.mul(v, v);
            g.sub(one, vv)
        }
        Unary::Asinh | Unary::Acosh => {
            let aa = g.mul(a, a);
            let d = if f == Unary::Asinh {
                g.add(aa, one)
            } else {
                g.sub(aa, one)
            };
            let r = g.unary(Unary::Sqrt, d);
            g.div(one, r)
        }
        Unary::Atanh => {
            let aa = g.mul(a, a);
            let d = g.sub(one, aa);
            g.div(one, d)
        }
        Unary::Abs => g.unary(Unary::Sign, a),
        Unary::Sign => g.constant(0.0),
    }
}

/// Which nodes up to `last` depend on one of `vars`.
pub(crate) fn dependents(g: &Graph, last: Id, vars: &[Id]) -> Vec<bool> {
    let mut dep = vec![false; last as usize + 1];
    for &x in vars {
        if x <= last {
            dep[x as usize] = true;
        }
    }
    for id in 0..=last {
        let (a, b) = g.node(id).args();
        if a.is_some_and(|a| dep[a as usize]) || b.is_some_and(|b| dep[b as usize]) {
            dep[id as usize] = true;
        }
    }
    dep
}

/// ∂y/∂x for each x of `vars`, by reverse accumulation from y (see the [module docs](self)).
pub fn gradient(g: &mut Graph, y: Id, vars: &[Id]) -> Vec<Id> {
    let dep = dependents(g, y, vars);
    let mut adj: Vec<Option<Id>> = vec![None; y as usize + 1];
    if dep[y as usize] {
        adj[y as usize] = Some(g.constant(1.0));
    }
    for v in (0..=y).rev() {
        let Some(bar) = adj[v as usize] else { continue };
        let node = g.node(v);
        if matches!(node, Node::Input(_)) {
            continue;
        }
        let (a, b) = node.args();
        let wanted = |x: Option<Id>| x.filter(|&x| dep[x as usize]);
        let (a, b) = (wanted(a), wanted(b));
        if a.is_none() && b.is_none() {
            continue;
        }
        let (da, db) = partials(g, v);
        for (x, dx) in [(a, da), (b, db)] {
            if let (Some(x), Some(dx)) = (x, dx) {
                let c = g.mul(bar, dx);
                let acc = &mut adj[x as usize];
                *acc = Some(match *acc {
                    None => c,
                    Some(s) => g.add(s, c),
                });
            }
        }
    }
    vars.iter()
        .map(|&x| {
            adj.get(x as usize)
                .copied()
                .flatten()
                .unwrap_or_else(|| g.constant(0.0))
        })
        .collect()
}

/// The derivatives of `outputs` along the direction that moves input node `x` at rate `ẋ`, for each
/// `(x, ẋ)` of `seeds` (ẋ a node), by forward accumulation (see the [module docs](self)).
pub fn directional(g: &mut Graph, outputs: &[Id], seeds: &[(Id, Id)]) -> Vec<Id> {
    let Some(&last) = outputs.iter().max() else {
        return Vec::new();
    };
    let vars: Vec<Id> = seeds.iter().map(|s| s.0).collect();
    let dep = dependents(g, last, &vars);
    let mut dot: Vec<Option<Id>> = vec![None; last as usize + 1];
    for &(x, xd) in seeds {
        if x <= last {
            dot[x as usize] = Some(xd);
        }
    }
    for v in 0..=last {
        if !dep[v as usize] || dot[v as usize].is_some() {
            continue;
        }
        let (a, b) = g.node(v).args();
        let (da, db) = partials(g, v);
        let mut terms = Vec::with_capacity(2);
        for (x, dx) in [(a, da), (b, db)] {
            if let (Some(x), Some(dx)) = (x, dx) {
                if let Some(xd) = dot[x as usize] {
                    terms.push(g.mul(dx, xd));
                }
            }
        }
        dot[v as usize] = Some(g.sum(terms));
    }
    outputs
        .iter()
        .map(|&y| dot[y as usize].unwrap_or_else(|| g.constant(0.0)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// d/dx of f(x) = x² sin x + eˣ/x at x = 0.7 against f′(x) = 2x sin x + x² cos x + eˣ(x − 1)/x².
    #[test]
    fn gradient_and_directional_of_a_scalar_function() {
        let mut g = Graph::new();
        let x = g.input(0);
        let xx = g.mul(x, x);
        let s = g.unary(Unary::Sin, x);
        let e = g.unary(Unary::Exp, x);
        let p = g.mul(xx, s);
        let q = g.div(e, x);
        let f = g.add(p, q);
        let df = gradient(&mut g, f, &[x])[0];
        let one = g.constant(1.0);
        let df_fwd = directional(&mut g, &[f], &[(x, one)])[0];
        let x0: f64 = 0.7;
        let exact = 2.0 * x0 * x0.sin() + x0 * x0 * x0.cos() + x0.exp() * (x0 - 1.0) / (x0 * x0);
        for d in [df, df_fwd] {
            let v = g.evaluate(&[x0], d)[d as usize];
            // A few roundings of terms of size ~1: within 4 ulps of the closed form.
            assert!(
                (v - exact).abs() <= 4.0 * f64::EPSILON * exact.abs(),
                "{v} vs {exact}"
            );
        }
    }
}
