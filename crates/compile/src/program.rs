//! The program of a list of outputs: the nodes that the outputs need (dead code eliminated), in
//! order, as a flat program over a file of f64 registers, with registers reused once a value is dead;
//! run by one of two backends ([`Backend`]).
//!
//! - **The interpreter** (always available; the fallback): one pass over the instructions — no dual
//!   parts, no allocation (the register file is a per-thread scratch buffer). The inputs occupy the
//!   first registers; each instruction reads its arguments before it writes its result, so a result
//!   may take the register of an argument that dies with it.
//! - **Native code** (feature `jit`: `noether-compile = { features = ["jit"] }`, or the facade's
//!   `noether = { features = ["jit"] }`): the same instructions compiled once, when the program is
//!   built, to one machine-code function by Cranelift (`native`), which gives the interpreter's
//!   results bit for bit. [`Program::new`] builds it (the interpreter where Cranelift fails, e.g. on a
//!   host it does not support); [`Program::interpreted`] builds the interpreter in any case.

use crate::graph::{Binary, Graph, Id, Node, Unary};
use noether_core::error::check_len;
use noether_core::{Error, Result};
use std::cell::RefCell;
#[cfg(feature = "jit")]
use std::sync::Arc;

/// One instruction: `d` is the register written, `a`, `b` the registers read.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Instr {
    Const { d: u32, c: f64 },
    Add { d: u32, a: u32, b: u32 },
    Sub { d: u32, a: u32, b: u32 },
    Mul { d: u32, a: u32, b: u32 },
    Div { d: u32, a: u32, b: u32 },
    Neg { d: u32, a: u32 },
    Atan2 { d: u32, a: u32, b: u32 },
    Unary { f: Unary, d: u32, a: u32 },
    Powi { d: u32, a: u32, n: i32 },
    Powf { d: u32, a: u32, e: f64 },
}

/// What runs a [`Program`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// The interpreter of the instructions.
    Interpreter,
    /// Machine code compiled by Cranelift (feature `jit`).
    Native,
}

/// A compiled list of outputs of a graph: the nodes that the outputs need (dead code eliminated), in
/// order, as a flat program over a file of f64 registers (reused once a value is dead), the register
/// of each output, and with the feature `jit` the native code.
///
/// - **The interpreter** (always available; the fallback): one pass over the instructions, no
///   allocation (the register file is a per-thread scratch buffer).
/// - **Native code** (feature `jit` of noether-compile, or of the facade `noether`): the same
///   instructions compiled once, when the program is built, to one machine-code function by
///   Cranelift, which gives the interpreter's results bit for bit: only correctly rounded IEEE
///   operations (+, −, ·, /, √) and sign-bit operations (−x, |x|) as instructions, every other
///   function a call of the Rust function the interpreter calls. [`new`](Self::new) builds it (the
///   interpreter where Cranelift fails, e.g. on a host it does not support);
///   [`interpreted`](Self::interpreted) builds the interpreter in any case; [`backend`](Self::backend)
///   tells which runs.
///
/// Cloning shares the native code. A program is `Send` and `Sync`: threads run it at once, each with
/// its own scratch buffer.
#[derive(Clone, Debug)]
pub struct Program {
    instrs: Vec<Instr>,
    inputs: usize,
    registers: usize,
    outputs: Vec<u32>,
    /// The native code, where it is built: it reads the inputs from the scratch buffer and writes
    /// output i to its slot `inputs + i`.
    #[cfg(feature = "jit")]
    native: Option<(Arc<crate::native::Code>, Vec<u32>)>,
}

/// Inputs and outputs of native code up to this many together run in a buffer on the stack (a
/// double pendulum's q̈ takes 11, a heavy top's 16).
#[cfg(feature = "jit")]
const STACK: usize = 16;

/// The inputs `parts`, one after the other, into the first values of `r` (an element loop: a few
/// values each, no call of `memcpy`).
#[inline]
#[allow(clippy::needless_range_loop, clippy::manual_memcpy)] // a few values: no call of memcpy
fn gather(r: &mut [f64], parts: &[&[f64]]) {
    let mut at = 0;
    for p in parts {
        for i in 0..p.len() {
            r[at + i] = p[i];
        }
        at += p.len();
    }
}

thread_local! {
    static REGISTERS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

impl Program {
    /// The program that computes `outputs` of `graph` from its first `inputs` inputs (every
    /// [`Node::Input`] k of the graph must have k < `inputs`): native code with the feature `jit` (the
    /// interpreter where Cranelift cannot compile it), else the interpreter.
    pub fn new(graph: &Graph, inputs: usize, outputs: &[Id]) -> Self {
        Self::with_backend(graph, inputs, outputs, Backend::Native)
    }

    /// The program of [`new`](Self::new) run by `backend` where it is available: [`Backend::Native`]
    /// is the interpreter without the feature `jit` or where Cranelift fails.
    pub fn with_backend(graph: &Graph, inputs: usize, outputs: &[Id], backend: Backend) -> Self {
        #[allow(unused_mut)]
        let mut program = Self::interpreted(graph, inputs, outputs);
        #[cfg(feature = "jit")]
        if backend == Backend::Native {
            program.compile_native(&[]);
        }
        #[cfg(not(feature = "jit"))]
        let _ = backend;
        program
    }

    /// The native code of the program, compiled by Cranelift (with `settings` in place of the
    /// defaults of [`native`](crate::native)), where it compiles; the program stays with the
    /// interpreter otherwise.
    #[cfg(feature = "jit")]
    fn compile_native(&mut self, settings: &[(&str, &str)]) {
        if let Ok(code) = crate::native::compile(&self.instrs, self.inputs, &self.outputs, settings) {
            let slots = (self.inputs..self.inputs + self.outputs.len())
                .map(|k| k as u32)
                .collect();
            self.native = Some((Arc::new(code), slots));
        }
    }

    /// The program compiled again by Cranelift with `settings` (for the measurements of the tests).
    #[cfg(all(test, feature = "jit"))]
    pub(crate) fn with_settings(&self, settings: &[(&str, &str)]) -> Program {
        let mut program = self.clone();
        program.native = None;
        program.compile_native(settings);
        program
    }

    /// The program of [`new`](Self::new) run by the interpreter, with or without the feature `jit`.
    pub fn interpreted(graph: &Graph, inputs: usize, outputs: &[Id]) -> Self {
        let (needed, last_use) = liveness(graph, outputs);
        let mut is_output = vec![false; needed.len()];
        outputs.iter().for_each(|&y| is_output[y as usize] = true);
        let mut reg: Vec<u32> = vec![u32::MAX; needed.len()];
        let mut free: Vec<u32> = Vec::new();
        let mut registers = inputs;
        let mut instrs = Vec::new();
        for v in (0..needed.len() as Id).filter(|&v| needed[v as usize]) {
            let node = graph.node(v);
            if let Node::Input(k) = node {
                reg[v as usize] = k;
                continue;
            }
            // Free the registers of arguments that die here (never an input's or an output's).
            let (a, b) = node.args();
            for x in [a, b].into_iter().flatten() {
                let dies = last_use[x as usize] == v && !is_output[x as usize];
                if dies && !matches!(graph.node(x), Node::Input(_)) && !free.contains(&reg[x as usize]) {
                    free.push(reg[x as usize]);
                }
            }
            let d = free.pop().unwrap_or_else(|| {
                registers += 1;
                (registers - 1) as u32
            });
            reg[v as usize] = d;
            instrs.push(lower(node, d, &reg));
        }
        Program {
            instrs,
            inputs,
            registers,
            outputs: outputs.iter().map(|&y| reg[y as usize]).collect(),
            #[cfg(feature = "jit")]
            native: None,
        }
    }

    /// What runs the program.
    pub fn backend(&self) -> Backend {
        #[cfg(feature = "jit")]
        if self.native.is_some() {
            return Backend::Native;
        }
        Backend::Interpreter
    }

    /// The number of instructions (constants included).
    pub fn len(&self) -> usize {
        self.instrs.len()
    }

    /// `true` for a program with no instruction.
    pub fn is_empty(&self) -> bool {
        self.instrs.is_empty()
    }

    /// The number of arithmetic operations and function calls (the instructions that are not
    /// constants).
    pub fn operations(&self) -> usize {
        self.instrs
            .iter()
            .filter(|i| !matches!(i, Instr::Const { .. }))
            .count()
    }

    /// The number of inputs.
    pub fn inputs(&self) -> usize {
        self.inputs
    }

    /// The number of outputs.
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// The size of the interpreter's register file.
    pub fn registers(&self) -> usize {
        self.registers
    }

    /// Runs the program on the inputs given as consecutive `parts` (together exactly
    /// [`inputs`](Self::inputs) values) and hands the outputs to `f`.
    #[inline]
    pub fn run_with<R>(&self, parts: &[&[f64]], f: impl FnOnce(Outputs<'_>) -> R) -> Result<R> {
        let given: usize = parts.iter().map(|p| p.len()).sum();
        if given != self.inputs {
            return Err(Error::Dimension {
                what: "inputs of a compiled program",
                expected: self.inputs,
                got: given,
            });
        }
        // Native code of a small model: inputs and outputs in a buffer on the stack (no thread-local
        // look-up, no borrow flag), the common case of a few degrees of freedom.
        #[cfg(feature = "jit")]
        if let Some((code, slots)) = &self.native {
            if self.inputs + slots.len() <= STACK {
                let mut r = [0.0; STACK];
                gather(&mut r, parts);
                // SAFETY: `r` holds the inputs in its first `inputs` values and room for the outputs
                // after them (checked just above); the two ranges do not overlap.
                unsafe { code.call(r.as_mut_ptr(), r.as_mut_ptr().add(self.inputs)) };
                return Ok(f(Outputs {
                    registers: &r,
                    map: slots,
                }));
            }
        }
        // The thread's register file, or a fresh one when it is in use (`f` running a program).
        REGISTERS.with(|cell| match cell.try_borrow_mut() {
            Ok(mut r) => Ok(self.execute(&mut r, parts, f)),
            Err(_) => Ok(self.execute(&mut Vec::new(), parts, f)),
        })
    }

    #[inline]
    fn execute<R>(&self, r: &mut Vec<f64>, parts: &[&[f64]], f: impl FnOnce(Outputs<'_>) -> R) -> R {
        #[cfg(feature = "jit")]
        let size = match &self.native {
            Some(_) => self.inputs + self.outputs.len(),
            None => self.registers,
        };
        #[cfg(not(feature = "jit"))]
        let size = self.registers;
        if r.len() < size {
            r.resize(size, 0.0);
        }
        gather(r, parts);
        #[cfg(feature = "jit")]
        if let Some((code, slots)) = &self.native {
            let base = r.as_mut_ptr();
            // SAFETY: `r` holds the inputs in its first `inputs` values and room for the outputs after
            // them (resized above); the two ranges do not overlap.
            unsafe { code.call(base, base.add(self.inputs)) };
            return f(Outputs {
                registers: r,
                map: slots,
            });
        }
        execute(&self.instrs, r);
        f(Outputs {
            registers: r,
            map: &self.outputs,
        })
    }

    /// Runs the native code on `inputs` into `outputs` directly (no scratch buffer, no copy): the
    /// fast path of small compiled models, which gather their inputs on the stack. `false`, with
    /// `outputs` untouched, where the program has no native code or the lengths are not the
    /// program's.
    #[inline]
    pub fn call(&self, inputs: &[f64], outputs: &mut [f64]) -> bool {
        #[cfg(feature = "jit")]
        if let Some((code, slots)) = &self.native {
            if inputs.len() != self.inputs || outputs.len() != slots.len() {
                return false;
            }
            // SAFETY: `inputs` holds the program's number of inputs and `outputs` room for its
            // outputs (checked just above); the native code reads and writes only those.
            unsafe { code.call(inputs.as_ptr(), outputs.as_mut_ptr()) };
            return true;
        }
        let _ = (inputs, outputs);
        false
    }

    /// Runs the program: `inputs` in, the outputs written into `out` (both of the program's lengths,
    /// else [`Error::Dimension`]).
    pub fn run(&self, inputs: &[f64], out: &mut [f64]) -> Result<()> {
        check_len("outputs of a compiled program", out, self.outputs.len())?;
        self.run_with(&[inputs], |o| {
            for (i, x) in out.iter_mut().enumerate() {
                *x = o.get(i);
            }
        })
    }
}

/// The outputs of one run of a [`Program`], read in place from its registers.
#[derive(Clone, Copy)]
pub struct Outputs<'a> {
    registers: &'a [f64],
    map: &'a [u32],
}

impl Outputs<'_> {
    /// Output i.
    #[inline]
    pub fn get(&self, i: usize) -> f64 {
        self.registers[self.map[i] as usize]
    }

    /// The number of outputs.
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// `true` when there are none.
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }
}

/// The nodes the outputs need, and for each the last node that reads it (0 for none).
fn liveness(graph: &Graph, outputs: &[Id]) -> (Vec<bool>, Vec<Id>) {
    let needed = graph.needed(outputs);
    let mut last_use = vec![0 as Id; needed.len()];
    for v in (0..needed.len() as Id).filter(|&v| needed[v as usize]) {
        let (a, b) = graph.node(v).args();
        for x in [a, b].into_iter().flatten() {
            last_use[x as usize] = last_use[x as usize].max(v);
        }
    }
    (needed, last_use)
}

/// The instruction that computes `node` into register `d`, its arguments in the registers `reg`.
fn lower(node: Node, d: u32, reg: &[u32]) -> Instr {
    let r = |x: Id| reg[x as usize];
    match node {
        Node::Input(_) => unreachable!("inputs take no instruction"),
        Node::Const(bits) => Instr::Const {
            d,
            c: f64::from_bits(bits),
        },
        Node::Binary(op, a, b) => {
            let (a, b) = (r(a), r(b));
            match op {
                Binary::Add => Instr::Add { d, a, b },
                Binary::Sub => Instr::Sub { d, a, b },
                Binary::Mul => Instr::Mul { d, a, b },
                Binary::Div => Instr::Div { d, a, b },
                Binary::Atan2 => Instr::Atan2 { d, a, b },
            }
        }
        Node::Unary(Unary::Neg, a) => Instr::Neg { d, a: r(a) },
        Node::Unary(f, a) => Instr::Unary { f, d, a: r(a) },
        Node::Powi(a, n) => Instr::Powi { d, a: r(a), n },
        Node::Powf(a, e) => Instr::Powf {
            d,
            a: r(a),
            e: f64::from_bits(e),
        },
    }
}

/// The instruction loop.
#[inline(never)]
fn execute(instrs: &[Instr], r: &mut [f64]) {
    for ins in instrs {
        match *ins {
            Instr::Const { d, c } => r[d as usize] = c,
            Instr::Add { d, a, b } => r[d as usize] = r[a as usize] + r[b as usize],
            Instr::Sub { d, a, b } => r[d as usize] = r[a as usize] - r[b as usize],
            Instr::Mul { d, a, b } => r[d as usize] = r[a as usize] * r[b as usize],
            Instr::Div { d, a, b } => r[d as usize] = r[a as usize] / r[b as usize],
            Instr::Neg { d, a } => r[d as usize] = -r[a as usize],
            Instr::Atan2 { d, a, b } => r[d as usize] = r[a as usize].atan2(r[b as usize]),
            Instr::Unary { f, d, a } => r[d as usize] = f.apply(r[a as usize]),
            Instr::Powi { d, a, n } => r[d as usize] = r[a as usize].powi(n),
            Instr::Powf { d, a, e } => r[d as usize] = r[a as usize].powf(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The program gives the graph's own evaluation bit for bit (both backends), and reuses registers.
    #[test]
    fn matches_the_graph_and_reuses_registers() {
        let mut g = Graph::new();
        let (x, y) = (g.input(0), g.input(1));
        let mut acc = x;
        for k in 0..20 {
            let s = g.unary(Unary::Sin, acc);
            let c = g.scale(1.0 + f64::from(k), y);
            acc = g.add(s, c);
        }
        let outputs = [acc, g.mul(acc, x)];
        let p = Program::interpreted(&g, 2, &outputs);
        assert_eq!(p.backend(), Backend::Interpreter);
        let v = g.evaluate(&[0.3, -0.8], outputs[1]);
        // Both backends where the feature `jit` is on (the first is native then).
        for p in [Program::new(&g, 2, &outputs), p.clone()] {
            let mut out = [0.0; 2];
            p.run(&[0.3, -0.8], &mut out).unwrap();
            assert_eq!(out[0].to_bits(), v[outputs[0] as usize].to_bits());
            assert_eq!(out[1].to_bits(), v[outputs[1] as usize].to_bits());
        }
        assert!(
            p.registers() < 8,
            "{} registers for a chain of 80 nodes",
            p.registers()
        );
    }
}
