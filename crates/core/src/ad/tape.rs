//! Lagrange's terms for many degrees of freedom: one recorded evaluation of L, one scalar reverse
//! sweep, and the curvature of each nonlinear operation pulled back by forward gradients in q̇.
//!
//! L is evaluated once with a [`TapeVar`] (a value and a node handle, two words), which records each
//! operation v = φ(a, b) with its partials; each node also carries forward, on the tape, its
//! derivative ∂ₛ along the flow direction (δt, δq) = (1, q̇) and its gradient ∇_q̇ (stored over the
//! contiguous range of q̇-components it depends on). One reverse sweep then gives every adjoint
//! ā_v = ∂L/∂v, hence ∂L/∂q and the momenta ∂L/∂q̇ as the adjoints of the inputs. The second derivatives follow from the second-order chain rule: the inputs
//! (t + s, q + s·q̇, q̇ + w) are linear in (s, w), so
//!
//! ```text
//! d²L = Σ_v ā_v d²φ_v,   d²φ_v = Σ_ij ∂²φ_v/∂a_i∂a_j da_i da_j
//!
//! M     = ∂²L/∂q̇²  = Σ_v ā_v Σ_ij ∂²φ_v/∂a_i∂a_j ∇_q̇a_i ∇_q̇a_jᵀ
//! mixed = ∂²L/∂s∂q̇ = Σ_v ā_v Σ_ij ∂²φ_v/∂a_i∂a_j ∂ₛa_i ∇_q̇a_j  = (∂²L/∂q̇∂q)·q̇ + ∂²L/∂q̇∂t
//! ```
//!
//! summed over the nonlinear operations with a q̇-dependent argument (a product, a quotient, a
//! function of one argument); linear operations and functions of (t, q) alone add nothing. The cost
//! is the evaluation and one sweep over its operations, plus the length of each gradient in q̇ per
//! operation, plus its square per nonlinear operation: a chain's velocity sums that depend on
//! q̇₁…q̇ₖ cost k and k², where a forward second-order jet carries an N×N Hessian through every
//! operation.
//!
//! The same recording serves the first-order and Hessian-vector kernels of [`ad`](super) for large
//! blocks: with no gradients carried it is plain reverse mode (the whole gradient for a few
//! evaluations' cost), with a direction (δt, δx, δy) it is forward-over-reverse.
//!
//! # References
//! - A. Griewank, A. Walther, *Evaluating Derivatives*, 2nd ed., SIAM 2008: chapters 3–4 (reverse
//!   mode on a tape) and 5 (second-order adjoints).

mod var;

pub use var::TapeVar;

use var::{Arg, Span};

use crate::ad::{Block, Field};
use nalgebra::{DMatrix, DVector};
use std::cell::RefCell;

/// One recorded operation v = φ(a, b): its arguments and the partials ∂φ/∂a, ∂φ/∂b. A missing
/// argument is the sink (node 0), whose adjoint is never read.
#[derive(Debug, Clone, Copy)]
struct Edge {
    a: u32,
    b: u32,
    da: f64,
    db: f64,
}

/// A nonlinear operation with a q̇-dependent argument: its node (whose edge names the arguments, whose
/// flows hold their ∂ₛ and ∇_q̇) and the second partials ∂²φ/∂a², ∂²φ/∂a∂b, ∂²φ/∂b².
#[derive(Debug, Clone, Copy)]
struct Curvature {
    node: u32,
    haa: f64,
    hab: f64,
    hbb: f64,
}

/// What a node carries forward: its derivative ∂ₛ along the seeded direction and where its gradient
/// in the seeded variables lives.
#[derive(Debug, Clone, Copy)]
struct Flow {
    gs: f64,
    w: Span,
}

/// The thread's recording: operations (with their flows, one per node), gradients and curvatures of
/// the evaluation in progress (evaluations may nest: each one truncates back to where it started).
#[derive(Debug)]
struct Tape {
    edges: Vec<Edge>,
    flows: Vec<Flow>,
    grads: Vec<f64>,
    curv: Vec<Curvature>,
    adj: Vec<f64>,
}

/// The node every missing argument and every constant points to.
const SINK: u32 = 0;

thread_local! {
    static TAPE: RefCell<Tape> = const {
        RefCell::new(Tape {
            edges: Vec::new(),
            flows: Vec::new(),
            grads: Vec::new(),
            curv: Vec::new(),
            adj: Vec::new(),
        })
    };
}

impl Tape {
    /// Records v = φ(x, y) with partials `d` and second partials `h` = (∂²φ/∂x², ∂²φ/∂x∂y,
    /// ∂²φ/∂y²); ∂ₛv = d.0 ∂ₛx + d.1 ∂ₛy and ∇_q̇v = d.0 ∇_q̇x + d.1 ∇_q̇y on the union of the
    /// arguments' ranges.
    #[inline]
    fn push(&mut self, x: &Arg, y: &Arg, d: (f64, f64), h: (f64, f64, f64)) -> Arg {
        let id = self.edges.len() as u32;
        self.edges.push(Edge {
            a: x.id,
            b: y.id,
            da: d.0,
            db: d.1,
        });
        let (fx, fy) = (self.flows[x.id as usize], self.flows[y.id as usize]);
        let w = match (fx.w.is_empty(), fy.w.is_empty()) {
            (true, true) => Span::EMPTY,
            (false, true) => self.combine(fx.w, d.0, Span::EMPTY, 0.0),
            (true, false) => self.combine(fy.w, d.1, Span::EMPTY, 0.0),
            (false, false) => self.combine(fx.w, d.0, fy.w, d.1),
        };
        if !w.is_empty() && (h.0 != 0.0 || h.1 != 0.0 || h.2 != 0.0) {
            self.curv.push(Curvature {
                node: id,
                haa: h.0,
                hab: h.1,
                hbb: h.2,
            });
        }
        self.flows.push(Flow {
            gs: d.0 * fx.gs + d.1 * fy.gs,
            w,
        });
        Arg { id }
    }

    /// Appends α ∇a + β ∇b on the union of the two ranges (`b` may be empty) and returns its span.
    #[inline]
    fn combine(&mut self, a: Span, alpha: f64, b: Span, beta: f64) -> Span {
        let (lo, hi) = if b.is_empty() {
            (a.lo, a.hi)
        } else {
            (a.lo.min(b.lo), a.hi.max(b.hi))
        };
        let off = self.grads.len();
        self.grads.resize(off + (hi - lo) as usize, 0.0);
        let (old, new) = self.grads.split_at_mut(off);
        for (n, g) in new[(a.lo - lo) as usize..].iter_mut().zip(a.of(old)) {
            *n = alpha * g;
        }
        if !b.is_empty() {
            for (n, g) in new[(b.lo - lo) as usize..].iter_mut().zip(b.of(old)) {
                *n += beta * g;
            }
        }
        Span {
            off: off as u32,
            lo,
            hi,
        }
    }

    /// An input variable: ∂ₛ = `gs`, and ∇_q̇ = e_k when `k` is given.
    fn input(&mut self, gs: f64, k: Option<usize>) -> Arg {
        let id = self.edges.len() as u32;
        self.edges.push(Edge {
            a: SINK,
            b: SINK,
            da: 0.0,
            db: 0.0,
        });
        let w = match k {
            Some(k) => {
                let off = self.grads.len() as u32;
                self.grads.push(1.0);
                Span {
                    off,
                    lo: k as u32,
                    hi: k as u32 + 1,
                }
            }
            None => Span::EMPTY,
        };
        self.flows.push(Flow { gs, w });
        Arg { id }
    }
}

/// Records v = φ(x, y) on the thread's tape (see [`Tape::push`]); an operation on constants only is a
/// constant and is not recorded.
#[inline]
fn record(x: &Arg, y: &Arg, d: (f64, f64), h: (f64, f64, f64)) -> Arg {
    if x.id == SINK && y.id == SINK {
        return Arg::CONSTANT;
    }
    TAPE.with_borrow_mut(|t| t.push(x, y, d, h))
}

/// Adds c·u_i v_j to h[j + i n] for every j ≤ i (the upper triangle, column-major, of c u vᵀ's lower
/// half), with u, v the gradients on spans `su`, `sv`.
#[inline]
fn add_tri(h: &mut [f64], n: usize, c: f64, (su, u): (Span, &[f64]), (sv, v): (Span, &[f64])) {
    for (i, ui) in (su.lo as usize..).zip(u) {
        let top = (sv.hi as usize).min(i + 1);
        if top <= sv.lo as usize {
            continue;
        }
        let cu = c * ui;
        let col = &mut h[i * n + sv.lo as usize..i * n + top];
        for (hij, vj) in col.iter_mut().zip(v) {
            *hij += cu * vj;
        }
    }
}

/// What [`lagrange_terms_taped`] returns: [`LagrangeTerms`](super::LagrangeTerms) sized at run time.
#[derive(Debug, Clone)]
pub struct LagrangeTermsDyn {
    /// f.
    pub value: f64,
    /// ∇_x f (∂L/∂q).
    pub grad_x: DVector<f64>,
    /// ∇_y f (the momenta ∂L/∂q̇).
    pub grad_y: DVector<f64>,
    /// ∇_y(∂_t f + ∇_x f·y): (∂²L/∂q̇∂q)·q̇ + ∂²L/∂q̇∂t.
    pub mixed: DVector<f64>,
    /// ∂²f/∂y² (the mass matrix ∂²L/∂q̇²).
    pub hess_yy: DMatrix<f64>,
}

/// [`LagrangeTerms`](super::LagrangeTerms) of f at (t, x, y) for any number of variables, from one
/// taped evaluation (module documentation): f, ∇_x f, ∇_y f, the mixed term ∇_y(∂_t f + ∇_x f·y) and
/// the Hessian ∂²f/∂y² (symmetric). For a Lagrangian these are L, ∂L/∂q, the momenta, the term
/// (∂²L/∂q̇∂q)·q̇ + ∂²L/∂q̇∂t of Lagrange's equations and the mass matrix.
///
/// ```
/// use noether_core::ad::{lagrange_terms_taped, Field};
/// use noether_core::Scalar;
///
/// /// L = ½ (q̇₀ + q̇₁)² cosh q₀ − q₁²: M = cosh q₀ [[1, 1], [1, 1]].
/// struct Toy;
/// impl Field for Toy {
///     fn eval<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
///         let s = v[0] + v[1];
///         s * s * q[0].cosh() * 0.5 - q[1] * q[1]
///     }
/// }
/// let terms = lagrange_terms_taped(&Toy, 0.0, &[0.4, 1.0], &[2.0, -0.5]);
/// let c = 0.4_f64.cosh();
/// assert!((terms.hess_yy[(0, 1)] - c).abs() < 1e-15);
/// assert!((terms.grad_x[1] + 2.0).abs() < 1e-15); // ∂L/∂q₁ = −2 q₁
/// // mixed_i = Σ_j ∂²L/∂q̇_i∂q_j q̇_j = (q̇₀ + q̇₁) sinh q₀ · q̇₀
/// assert!((terms.mixed[0] - 1.5 * 0.4_f64.sinh() * 2.0).abs() < 1e-14);
/// ```
pub fn lagrange_terms_taped<F: Field>(f: &F, t: f64, x: &[f64], y: &[f64]) -> LagrangeTermsDyn {
    let n = x.len();
    assert_eq!(y.len(), n, "lagrange_terms_taped: x and y differ in length");
    let (mut grad_x, mut grad_y, mut mixed) = (DVector::zeros(n), DVector::zeros(n), DVector::zeros(n));
    let mut hess_yy = DMatrix::zeros(n, n);
    let value = sweep(
        f,
        (t, x, y),
        Seeds {
            dir: (1.0, y, &[]),
            grad: Grad::Block(Block::Y),
        },
        Outputs {
            grad_x: Some(grad_x.as_mut_slice()),
            grad_y: Some(grad_y.as_mut_slice()),
            mixed: Some(mixed.as_mut_slice()),
            hess: Some(hess_yy.as_mut_slice()),
        },
    );
    LagrangeTermsDyn {
        value,
        grad_x,
        grad_y,
        mixed,
        hess_yy,
    }
}

/// ∇_block f (written into `out`) by one taped evaluation and one reverse sweep, with no second-order
/// bookkeeping: the cost of a few evaluations of f for any number of variables, where
/// [`gradient`](super::gradient)'s forward duals take one evaluation per chunk of 8. Returns f.
///
/// ```
/// use noether_core::ad::{gradient_taped, Block, Field};
/// use noether_core::Scalar;
///
/// /// V = Σ_i ¼ (x_{i+1} − x_i)⁴: ∂V/∂x_0 = −(x_1 − x_0)³.
/// struct Fpu;
/// impl Field for Fpu {
///     fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
///         x.windows(2).fold(D::zero(), |v, w| v + (w[1] - w[0]).powi(4) * 0.25)
///     }
/// }
/// let x: Vec<f64> = (0..100).map(|i| (i as f64 * 0.1).sin()).collect();
/// let mut g = vec![0.0; 100];
/// gradient_taped(&Fpu, 0.0, &x, &[], Block::X, &mut g);
/// assert!((g[0] + (x[1] - x[0]).powi(3)).abs() < 1e-15);
/// ```
pub fn gradient_taped<F: Field>(f: &F, t: f64, x: &[f64], y: &[f64], block: Block, out: &mut [f64]) -> f64 {
    assert_eq!(out.len(), block.pick(x, y).len(), "gradient_taped: output length");
    let outputs = Outputs::default().gradient(block, Some(out));
    let seeds = Seeds {
        dir: (0.0, &[], &[]),
        grad: Grad::None,
    };
    sweep(f, (t, x, y), seeds, outputs)
}

/// [`directional_gradient`](super::directional_gradient) by one taped evaluation:
/// `out_j = ∂/∂b_j [∂_t f·δt + ∇_x f·δx + ∇_y f·δy]` from the curvatures of the nonlinear operations
/// pulled back along the direction (no Hessian formed), and ∇_b f in `grad_b` if given.
#[allow(clippy::too_many_arguments)]
pub fn directional_gradient_taped<F: Field>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    dir: (f64, &[f64], &[f64]),
    b: Block,
    out: &mut [f64],
    grad_b: Option<&mut [f64]>,
) {
    assert_eq!(
        out.len(),
        b.pick(x, y).len(),
        "directional_gradient_taped: output length"
    );
    let outputs = Outputs {
        mixed: Some(out),
        ..Outputs::default()
    }
    .gradient(b, grad_b);
    let seeds = Seeds {
        dir,
        grad: Grad::Block(b),
    };
    sweep(f, (t, x, y), seeds, outputs);
}

/// The Hessian block ∂²f/∂a∂b (rows: block `a`, columns: block `b`, written into `out`) by one taped
/// evaluation: the cost follows the coupling of the model (Σ over nonlinear operations of the squared
/// length of their arguments' gradients), not the ⌈n/8⌉² chunk pairs of
/// [`hessian_forward`](super::hessian_forward). A block across x and y (a ≠ b) is cut out of the
/// Hessian in (x, y) together.
pub fn hessian_taped<F: Field>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    a: Block,
    b: Block,
    out: &mut DMatrix<f64>,
) {
    let (na, nb) = (a.pick(x, y).len(), b.pick(x, y).len());
    assert_eq!(out.shape(), (na, nb), "hessian_taped: output shape");
    let hessian = |grad, h: &mut [f64]| {
        let seeds = Seeds {
            dir: (0.0, &[], &[]),
            grad,
        };
        let outputs = Outputs {
            hess: Some(h),
            ..Outputs::default()
        };
        sweep(f, (t, x, y), seeds, outputs);
    };
    if a == b {
        return hessian(Grad::Block(a), out.as_mut_slice());
    }
    let n = x.len() + y.len();
    let mut joint = DMatrix::zeros(n, n);
    hessian(Grad::Both, joint.as_mut_slice());
    let offset = |blk: Block| if blk == Block::X { 0 } else { x.len() };
    out.copy_from(&joint.view((offset(a), offset(b)), (na, nb)));
}

/// A point or a direction (t, x, y); an empty slice stands for zeros.
type Point<'a> = (f64, &'a [f64], &'a [f64]);

/// How an evaluation is seeded: every node carries its derivative ∂ₛ along `dir` and its gradient
/// with respect to the variables `grad` names.
struct Seeds<'a> {
    dir: Point<'a>,
    grad: Grad,
}

/// The variables whose gradients the nodes carry (for the second-order outputs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Grad {
    /// None: a first-order sweep.
    None,
    /// One block.
    Block(Block),
    /// x and y together, x first.
    Both,
}

/// What a sweep writes (gradients sized for their block; `mixed` for the seeded variables, `hess` their
/// number squared, column-major).
#[derive(Default)]
struct Outputs<'a> {
    grad_x: Option<&'a mut [f64]>,
    grad_y: Option<&'a mut [f64]>,
    /// ∇ ∂ₛf in the seeded variables.
    mixed: Option<&'a mut [f64]>,
    /// The Hessian in the seeded variables.
    hess: Option<&'a mut [f64]>,
}

impl<'a> Outputs<'a> {
    /// These outputs with ∇_block f written into `g`.
    fn gradient(mut self, block: Block, g: Option<&'a mut [f64]>) -> Self {
        match block {
            Block::X => self.grad_x = g,
            Block::Y => self.grad_y = g,
        }
        self
    }
}

/// Records f at `at` with `seeds`, sweeps it backwards and writes `outputs`; returns f.
fn sweep<F: Field>(f: &F, (t, x, y): Point<'_>, seeds: Seeds<'_>, mut outputs: Outputs<'_>) -> f64 {
    let n = match seeds.grad {
        Grad::None => 0,
        Grad::Block(b) => b.pick(x, y).len(),
        Grad::Both => x.len() + y.len(),
    };
    assert!(
        x.len().max(y.len()) < u32::MAX as usize / 2,
        "taped evaluation: too many variables"
    );
    let (marks, tt, xs, ys) = TAPE.with_borrow_mut(|tp| record_inputs(tp, (t, x, y), &seeds));
    let (base, cbase, gbase) = marks;
    let r = f.eval(tt, &xs, &ys);
    TAPE.with_borrow_mut(|tp| {
        reverse(tp, base, r.arg.id);
        let adjoints = |vars: &[TapeVar], out: &mut [f64]| {
            for (o, v) in out.iter_mut().zip(vars) {
                *o = tp.adj[v.arg.id as usize];
            }
        };
        if let Some(g) = outputs.grad_x.as_deref_mut() {
            adjoints(&xs, g);
        }
        if let Some(g) = outputs.grad_y.as_deref_mut() {
            adjoints(&ys, g);
        }
        second_order(tp, cbase, n, outputs.mixed, outputs.hess);
        tp.edges.truncate(base);
        tp.flows.truncate(base);
        tp.grads.truncate(gbase);
        tp.curv.truncate(cbase);
    });
    r.re
}

/// The lengths of a tape's edges, curvatures and gradients before an evaluation (where its nodes
/// start).
type Marks = (usize, usize, usize);

/// Records the inputs of an evaluation at (t, x, y) on the tape, each seeded with its component of
/// the direction and, for the variables `seeds.grad` names, its unit gradient; returns where the
/// evaluation starts on the tape and the variables t, x, y.
fn record_inputs(
    tp: &mut Tape,
    (t, x, y): Point<'_>,
    seeds: &Seeds<'_>,
) -> (Marks, TapeVar, Vec<TapeVar>, Vec<TapeVar>) {
    let (dt, dx, dy) = seeds.dir;
    let dir = |d: &[f64], i: usize| d.get(i).copied().unwrap_or(0.0);
    let span = |b: Block, i: usize| match seeds.grad {
        Grad::Block(g) if g == b => Some(i),
        Grad::Both if b == Block::Y => Some(x.len() + i),
        Grad::Both => Some(i),
        _ => None,
    };
    if tp.edges.is_empty() {
        tp.input(0.0, None); // the sink
    }
    let marks = (tp.edges.len(), tp.curv.len(), tp.grads.len());
    let tt = TapeVar::with(t, tp.input(dt, None));
    let xs: Vec<TapeVar> = (0..x.len())
        .map(|i| TapeVar::with(x[i], tp.input(dir(dx, i), span(Block::X, i))))
        .collect();
    let ys: Vec<TapeVar> = (0..y.len())
        .map(|i| TapeVar::with(y[i], tp.input(dir(dy, i), span(Block::Y, i))))
        .collect();
    (marks, tt, xs, ys)
}

/// The reverse sweep: the adjoint ā_v = ∂f/∂v of every node v of the evaluation that starts at node
/// `base` and ends at `root` (ā_root = 1, ā_a += ∂φ_v/∂a · ā_v back from the root).
fn reverse(tp: &mut Tape, base: usize, root: u32) {
    let end = tp.edges.len();
    tp.adj.clear();
    tp.adj.resize(end, 0.0);
    let Tape { edges, adj, .. } = tp;
    if root != SINK {
        adj[root as usize] = 1.0;
        for v in (base..=root as usize).rev() {
            let (e, g) = (edges[v], adj[v]);
            adj[e.a as usize] += e.da * g;
            adj[e.b as usize] += e.db * g;
        }
    }
}

/// The second-order outputs from the curvatures of the evaluation (from `cbase` on) and the
/// adjoints: Σ_v ā_v d²φ_v pulled back along the seeded direction (`mixed`) and onto the seeded
/// variables' gradients (`hess`, n × n, filled in its lower triangle and then mirrored).
fn second_order(
    tp: &Tape,
    cbase: usize,
    n: usize,
    mut mixed: Option<&mut [f64]>,
    mut hess: Option<&mut [f64]>,
) {
    let Tape {
        edges,
        flows,
        grads,
        curv,
        adj,
    } = tp;
    mixed.iter_mut().for_each(|m| m.fill(0.0));
    hess.iter_mut().for_each(|h| h.fill(0.0));
    for c in &curv[cbase..] {
        let w = adj[c.node as usize];
        if w == 0.0 {
            continue;
        }
        let e = edges[c.node as usize];
        let (fa, fb) = (flows[e.a as usize], flows[e.b as usize]);
        let (ga, gb) = (fa.w.of(grads), fb.w.of(grads));
        if let Some(m) = mixed.as_deref_mut() {
            for (m, g) in m[fa.w.lo as usize..].iter_mut().zip(ga) {
                *m += w * (c.haa * fa.gs + c.hab * fb.gs) * g;
            }
            for (m, g) in m[fb.w.lo as usize..].iter_mut().zip(gb) {
                *m += w * (c.hab * fa.gs + c.hbb * fb.gs) * g;
            }
        }
        if let Some(h) = hess.as_deref_mut() {
            if c.haa != 0.0 {
                add_tri(h, n, w * c.haa, (fa.w, ga), (fa.w, ga));
            }
            if c.hab != 0.0 {
                add_tri(h, n, w * c.hab, (fa.w, ga), (fb.w, gb));
                add_tri(h, n, w * c.hab, (fb.w, gb), (fa.w, ga));
            }
            if c.hbb != 0.0 {
                add_tri(h, n, w * c.hbb, (fb.w, gb), (fb.w, gb));
            }
        }
    }
    if let Some(h) = hess {
        for i in 0..n {
            for j in 0..i {
                h[i + j * n] = h[j + i * n];
            }
        }
    }
}
