//! The expression graph: nodes interned once (so a common subexpression is one node however often it
//! is built), each built through constructors that fold constants and apply the algebraic
//! identities.
//!
//! A node is an input (t, a coordinate, a velocity, …), a constant, or an operation on earlier nodes:
//! the ids of a node's arguments are always smaller than its own, so the order of the ids is an order
//! of evaluation. The identities applied when a node is built:
//!
//! ```text
//! c₁ ∘ c₂ → the constant (evaluated as at run time)     x + 0 → x     x − 0 → x     0 − x → −x
//! x − x → 0     x·1 → x     x·0 → 0     x·(−1) → −x     x/1 → x     0/x → 0     −(−x) → x
//! x + (−y) → x − y     x − (−y) → x + y     (−x)·(−y) → x·y     xⁿ for n = 0, 1, 2, −1 → 1, x, x·x, 1/x
//! ```
//!
//! and the arguments of + and · are put in one order, so a + b and b + a are one node. `x·0 → 0` and
//! `x − x → 0` hold for every finite x; where x is not finite at run time the other outputs that
//! depend on it are not either, and the compiled model reports it (see [`crate::CompiledEulerLagrange`]).

use std::collections::HashMap;

/// The handle of a node: its index in the graph.
pub type Id = u32;

/// Functions of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Unary {
    /// −x
    Neg,
    /// 1/x
    Recip,
    /// √x
    Sqrt,
    /// ∛x
    Cbrt,
    /// eˣ
    Exp,
    /// eˣ − 1
    ExpM1,
    /// ln x
    Ln,
    /// ln(1 + x)
    Ln1p,
    /// sin x
    Sin,
    /// cos x
    Cos,
    /// tan x
    Tan,
    /// arcsin x
    Asin,
    /// arccos x
    Acos,
    /// arctan x
    Atan,
    /// sinh x
    Sinh,
    /// cosh x
    Cosh,
    /// tanh x
    Tanh,
    /// arsinh x
    Asinh,
    /// arcosh x
    Acosh,
    /// artanh x
    Atanh,
    /// |x|
    Abs,
    /// sign x: 1, 0 or −1 (NaN for NaN)
    Sign,
}

impl Unary {
    /// The value at x: what constant folding and the interpreter both compute.
    #[inline]
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Unary::Neg => -x,
            Unary::Recip => x.recip(),
            Unary::Sqrt => x.sqrt(),
            Unary::Cbrt => x.cbrt(),
            Unary::Exp => x.exp(),
            Unary::ExpM1 => x.exp_m1(),
            Unary::Ln => x.ln(),
            Unary::Ln1p => x.ln_1p(),
            Unary::Sin => x.sin(),
            Unary::Cos => x.cos(),
            Unary::Tan => x.tan(),
            Unary::Asin => x.asin(),
            Unary::Acos => x.acos(),
            Unary::Atan => x.atan(),
            Unary::Sinh => x.sinh(),
            Unary::Cosh => x.cosh(),
            Unary::Tanh => x.tanh(),
            Unary::Asinh => x.asinh(),
            Unary::Acosh => x.acosh(),
            Unary::Atanh => x.atanh(),
            Unary::Abs => x.abs(),
            Unary::Sign => sign(x),
        }
    }

    /// The name printed for it (as the Rust method, and in the text of the equations).
    pub fn name(self) -> &'static str {
        match self {
            Unary::Neg => "neg",
            Unary::Recip => "recip",
            Unary::Sqrt => "sqrt",
            Unary::Cbrt => "cbrt",
            Unary::Exp => "exp",
            Unary::ExpM1 => "exp_m1",
            Unary::Ln => "ln",
            Unary::Ln1p => "ln_1p",
            Unary::Sin => "sin",
            Unary::Cos => "cos",
            Unary::Tan => "tan",
            Unary::Asin => "asin",
            Unary::Acos => "acos",
            Unary::Atan => "atan",
            Unary::Sinh => "sinh",
            Unary::Cosh => "cosh",
            Unary::Tanh => "tanh",
            Unary::Asinh => "asinh",
            Unary::Acosh => "acosh",
            Unary::Atanh => "atanh",
            Unary::Abs => "abs",
            Unary::Sign => "sign",
        }
    }
}

/// sign x as num-dual's `signum` of a dual number: 1 for x > 0, −1 for x < 0, 0 for ±0, NaN for NaN.
#[inline]
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else if x == 0.0 {
        0.0
    } else {
        f64::NAN
    }
}

/// Functions of two arguments.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Binary {
    /// a + b
    Add,
    /// a − b
    Sub,
    /// a·b
    Mul,
    /// a/b
    Div,
    /// atan2(a, b), the angle of the point (b, a)
    Atan2,
}

impl Binary {
    /// The value at (a, b).
    #[inline]
    pub fn apply(self, a: f64, b: f64) -> f64 {
        match self {
            Binary::Add => a + b,
            Binary::Sub => a - b,
            Binary::Mul => a * b,
            Binary::Div => a / b,
            Binary::Atan2 => a.atan2(b),
        }
    }
}

/// One node of the graph. Constants and real exponents are stored by their bits, so that nodes can be
/// compared and hashed exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// The k-th input.
    Input(u32),
    /// A constant (its bits).
    Const(u64),
    /// f(a).
    Unary(Unary, Id),
    /// a ∘ b.
    Binary(Binary, Id, Id),
    /// aⁿ for an integer n.
    Powi(Id, i32),
    /// aᵉ for a real e (its bits).
    Powf(Id, u64),
}

impl Node {
    /// The arguments of the node (none, one or two).
    pub fn args(&self) -> (Option<Id>, Option<Id>) {
        match *self {
            Node::Input(_) | Node::Const(_) => (None, None),
            Node::Unary(_, a) | Node::Powi(a, _) | Node::Powf(a, _) => (Some(a), None),
            Node::Binary(_, a, b) => (Some(a), Some(b)),
        }
    }
}

/// An expression graph under construction: its nodes, the index that makes each one unique, and how
/// many nodes were asked for (before the identities and the sharing reduced them).
#[derive(Debug, Default, Clone)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
    requested: usize,
}

impl Graph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// The number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// `true` when the graph has no node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// How many operations were built: what the graph would hold without folding, identities and
    /// sharing.
    pub fn requested(&self) -> usize {
        self.requested
    }

    /// The node `id`.
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id as usize]
    }

    /// The value of `id` when it is a constant.
    pub fn constant_value(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    fn is_const(&self, id: Id, c: f64) -> bool {
        self.constant_value(id) == Some(c)
    }

    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = Id::try_from(self.nodes.len()).expect("an expression graph of at most 2³² nodes");
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    /// The k-th input.
    pub fn input(&mut self, k: u32) -> Id {
        self.intern(Node::Input(k))
    }

    /// The constant c (−0 and 0 are two constants; every NaN is one).
    pub fn constant(&mut self, c: f64) -> Id {
        let c = if c.is_nan() { f64::NAN } else { c };
        self.intern(Node::Const(c.to_bits()))
    }

    /// f(a), simplified.
    pub fn unary(&mut self, f: Unary, a: Id) -> Id {
        self.requested += 1;
        if let Some(x) = self.constant_value(a) {
            return self.constant(f.apply(x));
        }
        if let (Unary::Neg, Node::Unary(Unary::Neg, x)) = (f, self.node(a)) {
            return x;
        }
        self.intern(Node::Unary(f, a))
    }

    /// a ∘ b, simplified.
    pub fn binary(&mut self, op: Binary, a: Id, b: Id) -> Id {
        self.requested += 1;
        if let (Some(x), Some(y)) = (self.constant_value(a), self.constant_value(b)) {
            return self.constant(op.apply(x, y));
        }
        let simpler = match op {
            Binary::Add => self.simplify_add(a, b),
            Binary::Sub => self.simplify_sub(a, b),
            Binary::Mul => self.simplify_mul(a, b),
            Binary::Div => self.simplify_div(a, b),
            Binary::Atan2 => None,
        };
        if let Some(id) = simpler {
            return id;
        }
        let (a, b) = match op {
            Binary::Add | Binary::Mul if b < a => (b, a),
            _ => (a, b),
        };
        self.intern(Node::Binary(op, a, b))
    }

    /// The negated argument of −x.
    fn negated(&self, id: Id) -> Option<Id> {
        match self.node(id) {
            Node::Unary(Unary::Neg, x) => Some(x),
            _ => None,
        }
    }

    fn simplify_add(&mut self, a: Id, b: Id) -> Option<Id> {
        if self.is_const(a, 0.0) {
            return Some(b);
        }
        if self.is_const(b, 0.0) {
            return Some(a);
        }
        if let Some(y) = self.negated(b) {
            return Some(self.sub(a, y));
        }
        if let Some(x) = self.negated(a) {
            return Some(self.sub(b, x));
        }
        None
    }

    fn simplify_sub(&mut self, a: Id, b: Id) -> Option<Id> {
        if a == b {
            return Some(self.constant(0.0));
        }
        if self.is_const(b, 0.0) {
            return Some(a);
        }
        if self.is_const(a, 0.0) {
            return Some(self.neg(b));
        }
        if let Some(y) = self.negated(b) {
            return Some(self.add(a, y));
        }
        None
    }

    fn simplify_mul(&mut self, a: Id, b: Id) -> Option<Id> {
        for (x, y) in [(a, b), (b, a)] {
            if self.is_const(x, 0.0) {
                return Some(x);
            }
            if self.is_const(x, 1.0) {
                return Some(y);
            }
            if self.is_const(x, -1.0) {
                return Some(self.neg(y));
            }
        }
        if let (Some(x), Some(y)) = (self.negated(a), self.negated(b)) {
            return Some(self.mul(x, y));
        }
        None
    }

    fn simplify_div(&mut self, a: Id, b: Id) -> Option<Id> {
        if self.is_const(b, 1.0) || self.is_const(a, 0.0) {
            return Some(a);
        }
        if self.is_const(b, -1.0) {
            return Some(self.neg(a));
        }
        None
    }

    /// a + b
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        self.binary(Binary::Add, a, b)
    }

    /// a − b
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        self.binary(Binary::Sub, a, b)
    }

    /// a·b
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        self.binary(Binary::Mul, a, b)
    }

    /// a/b
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        self.binary(Binary::Div, a, b)
    }

    /// −a
    pub fn neg(&mut self, a: Id) -> Id {
        self.unary(Unary::Neg, a)
    }

    /// c·a for a real c.
    pub fn scale(&mut self, c: f64, a: Id) -> Id {
        let c = self.constant(c);
        self.mul(c, a)
    }

    /// aⁿ, simplified (n = 0, 1, 2, −1 become 1, a, a·a, 1/a).
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        self.requested += 1;
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.powi(n));
        }
        match n {
            0 => self.constant(1.0),
            1 => a,
            2 => self.mul(a, a),
            -1 => self.unary(Unary::Recip, a),
            _ => self.intern(Node::Powi(a, n)),
        }
    }

    /// aᵉ, simplified (an integer e of magnitude up to 64 is [`powi`](Self::powi)).
    pub fn powf(&mut self, a: Id, e: f64) -> Id {
        if e.fract() == 0.0 && e.abs() <= 64.0 {
            return self.powi(a, e as i32);
        }
        self.requested += 1;
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.powf(e));
        }
        self.intern(Node::Powf(a, e.to_bits()))
    }

    /// Σ terms (0 for none), summed left to right.
    pub fn sum(&mut self, terms: impl IntoIterator<Item = Id>) -> Id {
        let mut acc: Option<Id> = None;
        for t in terms {
            acc = Some(match acc {
                None => t,
                Some(s) => self.add(s, t),
            });
        }
        acc.unwrap_or_else(|| self.constant(0.0))
    }

    /// The `outputs` rebuilt with node `from` replaced by node `to` for each pair of `pairs`, every
    /// node on the way built again through the simplifying constructors (so that, say, setting q̇ = 0
    /// folds away every term that had a factor q̇).
    pub fn substitute(&mut self, outputs: &[Id], pairs: &[(Id, Id)]) -> Vec<Id> {
        let last = outputs.iter().copied().max().map_or(0, |m| m as usize + 1);
        let needed = self.needed(outputs);
        let mut map: Vec<Id> = (0..last as Id).collect();
        for &(from, to) in pairs {
            if (from as usize) < last {
                map[from as usize] = to;
            }
        }
        for v in (0..last as Id).filter(|&v| needed[v as usize]) {
            if pairs.iter().any(|p| p.0 == v) {
                continue;
            }
            let m = |x: Id| map[x as usize];
            map[v as usize] = match self.node(v) {
                Node::Input(_) | Node::Const(_) => v,
                Node::Unary(f, a) => self.unary(f, m(a)),
                Node::Binary(op, a, b) => self.binary(op, m(a), m(b)),
                Node::Powi(a, n) => self.powi(m(a), n),
                Node::Powf(a, e) => self.powf(m(a), f64::from_bits(e)),
            };
        }
        outputs.iter().map(|&y| map[y as usize]).collect()
    }

    /// Which nodes `outputs` need (themselves and everything they are computed from), indexed by id
    /// up to the largest output (empty for no output).
    pub fn needed(&self, outputs: &[Id]) -> Vec<bool> {
        let Some(&last) = outputs.iter().max() else {
            return Vec::new();
        };
        let mut needed = vec![false; last as usize + 1];
        outputs.iter().for_each(|&y| needed[y as usize] = true);
        for v in (0..=last).rev() {
            if needed[v as usize] {
                let (a, b) = self.node(v).args();
                for x in [a, b].into_iter().flatten() {
                    needed[x as usize] = true;
                }
            }
        }
        needed
    }

    /// The value of every node up to and including `last`, given the inputs: the reference
    /// evaluation (the [`Program`](crate::Program) computes the same, faster).
    pub fn evaluate(&self, inputs: &[f64], last: Id) -> Vec<f64> {
        let mut v: Vec<f64> = Vec::with_capacity(last as usize + 1);
        for node in &self.nodes[..=last as usize] {
            let x = match *node {
                Node::Input(k) => inputs[k as usize],
                Node::Const(bits) => f64::from_bits(bits),
                Node::Unary(f, a) => f.apply(v[a as usize]),
                Node::Binary(op, a, b) => op.apply(v[a as usize], v[b as usize]),
                Node::Powi(a, n) => v[a as usize].powi(n),
                Node::Powf(a, e) => v[a as usize].powf(f64::from_bits(e)),
            };
            v.push(x);
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identities_and_sharing() {
        let mut g = Graph::new();
        let (x, y) = (g.input(0), g.input(1));
        let (zero, one) = (g.constant(0.0), g.constant(1.0));
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.mul(one, y), y);
        assert_eq!(g.mul(x, zero), zero);
        assert_eq!(g.sub(x, x), zero);
        let nx = g.neg(x);
        assert_eq!(g.neg(nx), x);
        assert_eq!(g.add(x, y), g.add(y, x));
        let s = g.sin(x);
        assert_eq!(g.sin(x), s);
        let ny = g.neg(y);
        assert_eq!(g.add(x, ny), g.sub(x, y));
        let two = g.constant(2.0);
        let three = g.constant(3.0);
        assert_eq!(g.mul(two, three), g.constant(6.0));
        assert_eq!(g.powi(x, 2), g.mul(x, x));
        // x, y, 0, 1, −x, x + y, sin x, −y, x − y, 2, 3, 6, x·x: nothing twice.
        assert_eq!(g.len(), 13);
    }

    impl Graph {
        fn sin(&mut self, a: Id) -> Id {
            self.unary(Unary::Sin, a)
        }
    }
}
