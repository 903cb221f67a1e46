//! The native backend (feature `jit`): a [`Program`](crate::Program)'s instructions compiled by
//! Cranelift to one machine-code function, `extern "C" fn(inputs: *const f64, outputs: *mut f64)`.
//!
//! The instructions are translated in order, each result a new SSA value (a register of the
//! interpreter names the value last written to it), so Cranelift allocates the machine registers.
//! Each input is loaded from memory where it is first read, each output stored at the end.
//!
//! **Bit for bit the interpreter's results.** Only the correctly rounded IEEE operations are emitted
//! as instructions: `fadd`, `fsub`, `fmul`, `fdiv` (also 1/x, as `recip` computes it), `fsqrt`, and
//! the sign-bit operations `fneg`, `fabs`; Cranelift contracts nothing into a fused multiply-add.
//! Every other function (sin, exp, atan2, powi, powf, cbrt, …) is a call to a Rust wrapper of the very
//! function the interpreter calls ([`Unary::apply`], `f64::atan2`, `f64::powi`, `f64::powf`),
//! registered with the JIT by name.

use crate::graph::Unary;
use crate::program::Instr;
use cranelift_codegen::ir::{
    types, AbiParam, FuncRef, InstBuilder, MemFlags, Signature, UserFuncName, Value,
};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_codegen::Context;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, FuncId, Linkage, Module};
use std::collections::HashMap;
use std::fmt;

/// The signature of a compiled program.
type Entry = unsafe extern "C" fn(*const f64, *mut f64);

/// A program compiled to machine code: the JIT module that owns the code (freed on drop) and the
/// function's address.
pub(crate) struct Code {
    module: Option<JITModule>,
    entry: Entry,
}

// SAFETY: after `finalize_definitions` the module is never used again until it is freed on drop (which
// needs `&mut self`, so no call can be running); the code it owns is immutable and reentrant: it reads
// the inputs and writes the outputs it is given, and calls only the pure functions of `wrappers`.
unsafe impl Send for Code {}
// SAFETY: as above: `&Code` only gives calls of the immutable, reentrant function.
unsafe impl Sync for Code {}

impl Drop for Code {
    fn drop(&mut self) {
        if let Some(module) = self.module.take() {
            // SAFETY: the code is not running (we hold `&mut self`) and the entry point dies with `self`.
            unsafe { module.free_memory() }
        }
    }
}

impl fmt::Debug for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Code")
            .field("entry", &(self.entry as *const u8))
            .finish()
    }
}

impl Code {
    /// Runs the function: reads `inputs` values at `inputs_at`, writes the outputs at `outputs_at`.
    ///
    /// # Safety
    /// `inputs_at` must be valid for reads of the program's number of inputs, `outputs_at` for writes
    /// of its number of outputs.
    #[inline]
    pub(crate) unsafe fn call(&self, inputs_at: *const f64, outputs_at: *mut f64) {
        // SAFETY: the caller's contract; the function was compiled with this signature.
        unsafe { (self.entry)(inputs_at, outputs_at) }
    }
}

/// The Rust functions that the compiled code calls: each computes exactly what the interpreter does.
mod wrappers {
    use crate::graph::Unary;

    macro_rules! unary {
        ($($v:ident),* $(,)?) => {
            /// The symbol and the function of `f`.
            pub(super) fn unary(f: Unary) -> (&'static str, extern "C" fn(f64) -> f64) {
                match f {
                    $(Unary::$v => {
                        extern "C" fn w(x: f64) -> f64 {
                            Unary::$v.apply(x)
                        }
                        (concat!("noether_", stringify!($v)), w)
                    })*
                }
            }
        };
    }
    unary!(
        Neg, Recip, Sqrt, Cbrt, Exp, ExpM1, Ln, Ln1p, Sin, Cos, Tan, Asin, Acos, Atan, Sinh, Cosh, Tanh,
        Asinh, Acosh, Atanh, Abs, Sign
    );

    /// atan2(a, b)
    pub(super) extern "C" fn atan2(a: f64, b: f64) -> f64 {
        a.atan2(b)
    }

    /// aⁿ
    pub(super) extern "C" fn powi(a: f64, n: i32) -> f64 {
        a.powi(n)
    }

    /// aᵉ
    pub(super) extern "C" fn powf(a: f64, e: f64) -> f64 {
        a.powf(e)
    }
}

/// The functions a program calls: a symbol each, with its parameter types.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Callee {
    Unary(Unary),
    Atan2,
    Powi,
    Powf,
}

impl Callee {
    /// The symbol, the address and the parameter types (the result is one f64).
    fn symbol(self) -> (&'static str, *const u8, &'static [types::Type]) {
        match self {
            Callee::Unary(f) => {
                let (name, w) = wrappers::unary(f);
                (name, w as *const u8, &[types::F64])
            }
            Callee::Atan2 => (
                "noether_atan2",
                wrappers::atan2 as *const u8,
                &[types::F64, types::F64],
            ),
            Callee::Powi => (
                "noether_powi",
                wrappers::powi as *const u8,
                &[types::F64, types::I32],
            ),
            Callee::Powf => (
                "noether_powf",
                wrappers::powf as *const u8,
                &[types::F64, types::F64],
            ),
        }
    }

    /// The function an instruction calls, if it is not one of the native operations.
    fn of(ins: &Instr) -> Option<Callee> {
        match *ins {
            Instr::Atan2 { .. } => Some(Callee::Atan2),
            Instr::Powi { .. } => Some(Callee::Powi),
            Instr::Powf { .. } => Some(Callee::Powf),
            Instr::Unary { f, .. } if !is_native(f) => Some(Callee::Unary(f)),
            _ => None,
        }
    }
}

/// The functions of one argument emitted as instructions (correctly rounded, or exact).
fn is_native(f: Unary) -> bool {
    matches!(f, Unary::Neg | Unary::Recip | Unary::Sqrt | Unary::Abs)
}

/// Cranelift's settings: optimised for speed; calls by absolute address (cranelift-jit's
/// requirement); stack probes inline (the frame of a large program, its spilled values, may pass a
/// guard page); the IR verifier only in debug builds (it costs time at each compilation).
const SETTINGS: [(&str, &str); 6] = [
    ("opt_level", "speed"),
    ("use_colocated_libcalls", "false"),
    ("is_pic", "false"),
    ("enable_probestack", "true"),
    ("probestack_strategy", "inline"),
    (
        "enable_verifier",
        if cfg!(debug_assertions) { "true" } else { "false" },
    ),
];

/// Compiles `instrs` (the interpreter's program: `inputs` input registers, the outputs in the
/// registers `outputs`) to machine code, with Cranelift's settings of [`SETTINGS`] and then
/// `overrides`.
pub(crate) fn compile(
    instrs: &[Instr],
    inputs: usize,
    outputs: &[u32],
    overrides: &[(&str, &str)],
) -> Result<Code, String> {
    let err = |e: &dyn fmt::Display| e.to_string();
    let mut flags = settings::builder();
    for &(name, value) in SETTINGS.iter().chain(overrides) {
        flags.set(name, value).map_err(|e| err(&e))?;
    }
    let isa = cranelift_native::builder()
        .map_err(|e| err(&e))?
        .finish(settings::Flags::new(flags))
        .map_err(|e| err(&e))?;
    let mut callees: Vec<Callee> = Vec::new();
    for c in instrs.iter().filter_map(Callee::of) {
        if !callees.contains(&c) {
            callees.push(c);
        }
    }
    let mut builder = JITBuilder::with_isa(isa, default_libcall_names());
    for c in &callees {
        let (name, address, _) = c.symbol();
        builder.symbol(name, address);
    }
    let mut module = JITModule::new(builder);
    let entry = match define(&mut module, &callees, (instrs, inputs, outputs)) {
        Ok(id) => module.get_finalized_function(id),
        Err(e) => {
            // SAFETY: no code of the module has been handed out.
            unsafe { module.free_memory() };
            return Err(e);
        }
    };
    // SAFETY: the function was defined with the signature `Entry` (two pointers, no result).
    let entry = unsafe { std::mem::transmute::<*const u8, Entry>(entry) };
    Ok(Code {
        module: Some(module),
        entry,
    })
}

/// Declares, defines and finalizes the function of the program in `module`.
fn define(
    module: &mut JITModule,
    callees: &[Callee],
    program: (&[Instr], usize, &[u32]),
) -> Result<FuncId, String> {
    let err = |e: &dyn fmt::Display| e.to_string();
    let pointer = module.target_config().pointer_type();
    let mut sig = module.make_signature();
    sig.params
        .extend([AbiParam::new(pointer), AbiParam::new(pointer)]);
    let id = module
        .declare_function("program", Linkage::Local, &sig)
        .map_err(|e| err(&e))?;
    let mut imports: Vec<(Callee, FuncId)> = Vec::with_capacity(callees.len());
    for &c in callees {
        let (name, _, params) = c.symbol();
        let mut s: Signature = module.make_signature();
        s.params.extend(params.iter().map(|&t| AbiParam::new(t)));
        s.returns.push(AbiParam::new(types::F64));
        let f = module
            .declare_function(name, Linkage::Import, &s)
            .map_err(|e| err(&e))?;
        imports.push((c, f));
    }
    let mut ctx: Context = module.make_context();
    ctx.func.signature = sig;
    ctx.func.name = UserFuncName::user(0, id.as_u32());
    let mut fctx = FunctionBuilderContext::new();
    let mut b = FunctionBuilder::new(&mut ctx.func, &mut fctx);
    let refs: HashMap<Callee, FuncRef> = imports
        .iter()
        .map(|&(c, f)| (c, module.declare_func_in_func(f, b.func)))
        .collect();
    translate(&mut b, &refs, program);
    b.finalize();
    module.define_function(id, &mut ctx).map_err(|e| err(&e))?;
    module.finalize_definitions().map_err(|e| err(&e))?;
    Ok(id)
}

/// The value each register holds while the instructions are translated: an input's is loaded from
/// the inputs' pointer where it is first read.
struct Registers {
    values: Vec<Option<Value>>,
    inputs_at: Value,
}

impl Registers {
    /// The value of register r.
    fn get(&mut self, b: &mut FunctionBuilder<'_>, r: u32) -> Value {
        let at = self.inputs_at;
        *self.values[r as usize]
            .get_or_insert_with(|| b.ins().load(types::F64, MemFlags::trusted(), at, 8 * r as i32))
    }

    /// The values of registers a and c.
    fn pair(&mut self, b: &mut FunctionBuilder<'_>, a: u32, c: u32) -> (Value, Value) {
        (self.get(b, a), self.get(b, c))
    }
}

/// The body of the function: one block, the instructions in order, the outputs stored, return.
fn translate(
    b: &mut FunctionBuilder<'_>,
    refs: &HashMap<Callee, FuncRef>,
    (instrs, inputs, outputs): (&[Instr], usize, &[u32]),
) {
    let block = b.create_block();
    b.append_block_params_for_function_params(block);
    b.switch_to_block(block);
    b.seal_block(block);
    let (x, y) = (b.block_params(block)[0], b.block_params(block)[1]);
    let size = instrs
        .iter()
        .map(|i| dest(i) as usize + 1)
        .chain(outputs.iter().map(|&o| o as usize + 1))
        .max()
        .unwrap_or(0)
        .max(inputs);
    let mut r = Registers {
        values: vec![None; size],
        inputs_at: x,
    };
    for ins in instrs {
        let value = match *ins {
            Instr::Const { c, .. } => b.ins().f64const(c),
            Instr::Add { a, b: c, .. } => {
                let (p, q) = r.pair(b, a, c);
                b.ins().fadd(p, q)
            }
            Instr::Sub { a, b: c, .. } => {
                let (p, q) = r.pair(b, a, c);
                b.ins().fsub(p, q)
            }
            Instr::Mul { a, b: c, .. } => {
                let (p, q) = r.pair(b, a, c);
                b.ins().fmul(p, q)
            }
            Instr::Div { a, b: c, .. } => {
                let (p, q) = r.pair(b, a, c);
                b.ins().fdiv(p, q)
            }
            Instr::Neg { a, .. } => {
                let p = r.get(b, a);
                b.ins().fneg(p)
            }
            Instr::Unary { f, a, .. } => {
                let p = r.get(b, a);
                unary(b, refs, f, p)
            }
            Instr::Atan2 { a, b: c, .. } => {
                let (p, q) = r.pair(b, a, c);
                call(b, refs[&Callee::Atan2], &[p, q])
            }
            Instr::Powi { a, n, .. } => {
                let p = r.get(b, a);
                let n = b.ins().iconst(types::I32, i64::from(n));
                call(b, refs[&Callee::Powi], &[p, n])
            }
            Instr::Powf { a, e, .. } => {
                let p = r.get(b, a);
                let e = b.ins().f64const(e);
                call(b, refs[&Callee::Powf], &[p, e])
            }
        };
        r.values[dest(ins) as usize] = Some(value);
    }
    for (i, &o) in outputs.iter().enumerate() {
        let value = r.get(b, o);
        b.ins().store(MemFlags::trusted(), value, y, 8 * i as i32);
    }
    b.ins().return_(&[]);
}

/// f(p): an instruction for the native operations, else a call.
fn unary(b: &mut FunctionBuilder<'_>, refs: &HashMap<Callee, FuncRef>, f: Unary, p: Value) -> Value {
    match f {
        Unary::Neg => b.ins().fneg(p),
        Unary::Abs => b.ins().fabs(p),
        Unary::Sqrt => b.ins().sqrt(p),
        Unary::Recip => {
            let one = b.ins().f64const(1.0);
            b.ins().fdiv(one, p)
        }
        _ => call(b, refs[&Callee::Unary(f)], &[p]),
    }
}

/// The result of a call of `f` with `args`.
fn call(b: &mut FunctionBuilder<'_>, f: FuncRef, args: &[Value]) -> Value {
    let inst = b.ins().call(f, args);
    b.inst_results(inst)[0]
}

/// The register an instruction writes.
fn dest(ins: &Instr) -> u32 {
    match *ins {
        Instr::Const { d, .. }
        | Instr::Add { d, .. }
        | Instr::Sub { d, .. }
        | Instr::Mul { d, .. }
        | Instr::Div { d, .. }
        | Instr::Neg { d, .. }
        | Instr::Atan2 { d, .. }
        | Instr::Unary { d, .. }
        | Instr::Powi { d, .. }
        | Instr::Powf { d, .. } => d,
    }
}

#[cfg(test)]
mod tests {
    use crate::Compile;
    use noether_core::EulerLagrange;
    use noether_testkit::systems::{Chain, DoublePendulum};
    use std::time::Instant;

    /// Cranelift's optimisations on ("speed") and off ("none"), with its two register allocators
    /// ("backtracking", the default, and "single_pass"): the time to compile the program of q̈ of four
    /// models and the time per run, printed (not asserted: the machine is shared). `cargo test -p noether-compile --release --features jit --lib --
    /// --ignored --nocapture opt_levels`.
    #[test]
    #[ignore]
    fn opt_levels() {
        const SETTINGS: [&[(&str, &str)]; 4] = [
            &[("opt_level", "none")],
            &[("opt_level", "speed")],
            &[("opt_level", "none"), ("regalloc_algorithm", "single_pass")],
            &[("opt_level", "speed"), ("regalloc_algorithm", "single_pass")],
        ];
        fn measure<L: noether_core::Lagrangian>(name: &str, l: L, runs: usize) {
            let c = EulerLagrange::new(l).compile().unwrap();
            let p = c.accelerations_program();
            let n = p.inputs();
            let x: Vec<f64> = (0..n).map(|i| 0.1 + 0.37 * (i as f64).sin()).collect();
            let mut out = vec![0.0; p.outputs()];
            for settings in SETTINGS {
                let t0 = Instant::now();
                let q = p.with_settings(settings);
                let build = t0.elapsed().as_secs_f64() * 1e3;
                let best = (0..15)
                    .map(|_| {
                        let t0 = Instant::now();
                        for _ in 0..runs {
                            q.run(std::hint::black_box(&x), &mut out).unwrap();
                        }
                        t0.elapsed().as_secs_f64() * 1e9 / runs as f64
                    })
                    .fold(f64::INFINITY, f64::min);
                println!(
                    "{name} ({} operations), {settings:?}: compiled in {build:.1} ms, {best:.0} ns per run",
                    p.operations()
                );
            }
        }
        measure("double pendulum", DoublePendulum::default(), 200_000);
        measure(
            "heavy top",
            noether_testkit::systems::HeavyTop::default(),
            200_000,
        );
        measure("10-link chain", Chain::<10>::default(), 5_000);
        measure("40-link chain", Chain::<40>::default(), 200);
    }
}
