//! # noether-ensemble
//!
//! Many runs of one model — a parameter scan, a Monte Carlo sample of initial conditions — on every
//! core (rayon), and across machines on MPI (feature `mpi`). Like DifferentialEquations.jl's
//! `EnsembleProblem`, in three parts:
//!
//! - **members** ([`Members`]): a list (`Vec<P>`), a [`Grid`] (the Cartesian product of [`Axis`]
//!   values) or a [`Sampler`] of random members, each drawn from its own stream of (seed, index), so
//!   member `i` is the same whichever thread or rank builds it;
//! - **a run per member**: a closure `(index, &params) -> Result<S, E>` that builds a stepper and the
//!   core `Driver` and runs it (events, output times: everything the driver does); with
//!   [`Ensemble::output`] a second closure `(index, &params, S) -> T` keeps only what is needed of the
//!   solution (a deflection angle, a first-event time), so trajectories are dropped as members finish;
//! - **collection**: [`Ensemble::run`] gives every member's result in member order ([`Runs`]);
//!   [`Ensemble::reduce`] folds them into a histogram, a mean, or any [`Reducer`], without keeping them
//!   ([`Reduced`]). A member that fails is reported with its index and error ([`MemberError`]) while
//!   the others complete; a member whose closure panics is one of them too: the panic is caught and
//!   its message kept ([`MemberError::Panicked`]). A closure should still return its failures as
//!   errors (a panic's message is also printed by the panic hook, and a build with
//!   `panic = "abort"` cannot catch it).
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_ensemble::{Axis, Ensemble, Grid, Mean};
//!
//! struct Pendulum;
//! impl Lagrangian for Pendulum {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D { v[0] * v[0] * 0.5 + q[0].cos() }
//! }
//! // The time of the first upward crossing of θ = 0 (a quarter period) for released amplitudes.
//! let amplitudes = Grid::new(vec![Axis::linspace(0.1, 1.0, 10)?])?;
//! let ensemble = Ensemble::new(amplitudes, |_i, p: &Vec<f64>| {
//!     let el = EulerLagrange::new(Pendulum);
//!     Driver::new(Dop853::new(&el).tolerances(1e-10, 1e-10)?, State::new(0.0, [-p[0]], [0.0]))?
//!         .save(Save::End)?
//!         .event(Event::new("θ = 0", |s: &State| s.q[0]).rising().terminal())
//!         .run_until(10.0)
//! })
//! .output(|_i, _p, sol| sol.last().t);
//! let quarter = ensemble.run().values()?; // in member order
//! assert!((quarter[0] - std::f64::consts::FRAC_PI_2 * (1.0 + 0.01 / 16.0)).abs() < 1e-5);
//! let mean = ensemble.reduce(&Mean).into_value()?;
//! assert_eq!(mean.n, 10);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Same bits on any number of threads
//! A reduction folds fixed chunks of consecutive members (the chunk size depends on the number of
//! members only, see [`Ensemble::chunk_size`]), each in member order, and merges the chunks'
//! accumulators in a fixed pairwise tree. Rayon only decides *where* each chunk runs, never how the
//! numbers are combined, so a floating-point mean is bit-identical on 1, 2 or 64 threads, and on any
//! number of MPI ranks. The thread count is rayon's: the global pool (`RAYON_NUM_THREADS`), or a pool of
//! your own with `ThreadPoolBuilder::new().num_threads(k).build()?.install(|| ensemble.reduce(&r))`.
//!
//! # On a cluster (feature `mpi`)
//! With the feature `mpi` (rsmpi; it needs an MPI library and, to generate the bindings, libclang:
//! `apt-get install libopenmpi-dev openmpi-bin libclang-dev` on Debian/Ubuntu, or `module load openmpi`
//! on a cluster), `Ensemble::reduce_mpi` and `Ensemble::run_mpi` split the chunks across the ranks
//! of a communicator in contiguous blocks, each rank runs its block on its own cores with rayon, and
//! rank 0 gathers the accumulators and merges them in the same tree: the result is bit-identical to
//! [`Ensemble::reduce`] on one machine. Accumulators and outputs cross the network as bytes
//! ([`Wire`]).
//!
//! ```text
//! cargo build --release --features noether-ensemble/mpi --example my_scan
//! mpirun -n 64 target/release/examples/my_scan              # OpenMPI / MPICH
//! srun -N 4 --ntasks-per-node=1 -c 32 target/release/examples/my_scan   # Slurm: a rank per node,
//!                                                          # rayon on the node's 32 cores
//! ```
//! Give each rank its cores (`-c`/`--cpus-per-task` under Slurm; `RAYON_NUM_THREADS` if rayon should
//! not take them all). One rank per node with rayon inside is the usual layout; one rank per core with
//! `RAYON_NUM_THREADS=1` works too.
//!
//! # Progress (feature `progress`)
//! [`Ensemble::progress`] draws a progress bar (indicatif) on standard error while members run.

mod error;
mod members;
#[cfg(feature = "mpi")]
mod mpi_run;
mod reduce;
mod wire;

pub use error::{Error, MemberError, Result};
pub use members::{member_rng, Axis, Grid, MemberIter, MemberRng, Members, Sampler};
#[cfg(feature = "mpi")]
pub use mpi;
/// The random-number traits a [`Sampler`]'s closure uses (`rng.random()`, `rng.random_range(a..b)`).
pub use rand;
pub use reduce::{Counts, Fold, Histogram, Map, Max, Mean, Moments, Reducer};
pub use wire::Wire;

use rayon::prelude::*;

/// A failed member: its index and its error (from [`Ensemble::reduce`] a [`MemberError`]: what its
/// run returned, or the message of its panic).
#[derive(Debug, Clone, PartialEq)]
pub struct Failure<E> {
    /// Index of the member.
    pub index: usize,
    /// Why it failed.
    pub error: E,
}

/// The failures of a chunk of members, in member order.
type Failures<E> = Vec<Failure<MemberError<E>>>;

/// Every member's result, in member order.
#[derive(Debug, Clone, PartialEq)]
pub struct Runs<T, E> {
    results: Vec<Result<T, E>>,
}

impl<T, E> Runs<T, E> {
    /// The results, indexed by member.
    pub fn results(&self) -> &[Result<T, E>] {
        &self.results
    }

    /// The results, indexed by member, by value.
    pub fn into_results(self) -> Vec<Result<T, E>> {
        self.results
    }

    /// Number of members.
    pub fn len(&self) -> usize {
        self.results.len()
    }

    /// Whether the ensemble had no member.
    pub fn is_empty(&self) -> bool {
        self.results.is_empty()
    }

    /// The members that failed, in order: (index, error).
    pub fn failures(&self) -> impl Iterator<Item = (usize, &E)> {
        self.results
            .iter()
            .enumerate()
            .filter_map(|(i, r)| r.as_ref().err().map(|e| (i, e)))
    }

    /// The members that succeeded, in order: (index, output).
    pub fn successes(&self) -> impl Iterator<Item = (usize, &T)> {
        self.results
            .iter()
            .enumerate()
            .filter_map(|(i, r)| r.as_ref().ok().map(|t| (i, t)))
    }

    /// Every member's output, or [`Error::MemberFailed`] naming the first failure and counting them.
    pub fn values(self) -> Result<Vec<T>>
    where
        E: std::fmt::Display,
    {
        let failed = self.results.iter().filter(|r| r.is_err()).count();
        let mut out = Vec::with_capacity(self.results.len());
        for (index, r) in self.results.into_iter().enumerate() {
            match r {
                Ok(t) => out.push(t),
                Err(e) => {
                    return Err(Error::MemberFailed {
                        index,
                        failed,
                        message: e.to_string(),
                    })
                }
            }
        }
        Ok(out)
    }
}

/// A reduction of an ensemble: the accumulated value of the members that succeeded, and the failures.
#[derive(Debug, Clone, PartialEq)]
pub struct Reduced<A, E> {
    /// The reduction of the successful members' outputs.
    pub value: A,
    /// The members that failed, in member order.
    pub failures: Vec<Failure<E>>,
    /// Number of members (successes and failures).
    pub members: usize,
}

impl<A, E: std::fmt::Display> Reduced<A, E> {
    /// The value if no member failed, else [`Error::MemberFailed`] naming the first failure.
    pub fn into_value(self) -> Result<A> {
        match self.failures.first() {
            None => Ok(self.value),
            Some(f) => Err(Error::MemberFailed {
                index: f.index,
                failed: self.failures.len(),
                message: f.error.to_string(),
            }),
        }
    }
}

/// Chunks of an ensemble with `n` members when no size is given: about 1024 chunks, so that threads
/// (and ranks) balance their load, and a chunk size that depends on `n` alone.
pub const DEFAULT_CHUNKS: usize = 1024;

/// An ensemble: members and the run of one member (see the [crate] docs).
#[derive(Debug, Clone)]
pub struct Ensemble<M, F> {
    members: M,
    simulate: F,
    chunk: Option<usize>,
    progress: bool,
}

impl<M: Members, F> Ensemble<M, F> {
    /// An ensemble of `members`, member `i` run by `simulate(i, &params)` (which builds the stepper and
    /// the driver and runs them).
    pub fn new<S, E>(members: M, simulate: F) -> Self
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
    {
        Ensemble {
            members,
            simulate,
            chunk: None,
            progress: false,
        }
    }

    /// Keeps `output(i, &params, s)` of each member's result `s` (a solution) instead of `s` itself.
    pub fn output<S, E, T, G>(
        self,
        output: G,
    ) -> Ensemble<M, impl Fn(usize, &M::Param) -> std::result::Result<T, E> + Sync>
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
        G: Fn(usize, &M::Param, S) -> T + Sync,
    {
        let simulate = self.simulate;
        Ensemble {
            members: self.members,
            simulate: move |i: usize, p: &M::Param| simulate(i, p).map(|s| output(i, p, s)),
            chunk: self.chunk,
            progress: self.progress,
        }
    }

    /// Members per chunk of a reduction (≥ 1; default: ⌈n / [`DEFAULT_CHUNKS`]⌉). The result of a
    /// floating-point reduction depends on it (and on nothing else of the schedule).
    pub fn chunk_size(mut self, size: usize) -> Result<Self> {
        if size == 0 {
            return Err(Error::InvalidParameter {
                name: "chunk size",
                value: 0.0,
                reason: "a chunk needs at least one member",
            });
        }
        self.chunk = Some(size);
        Ok(self)
    }

    /// Draws a progress bar on standard error while members run (feature `progress`; without it,
    /// this does nothing).
    pub fn progress(mut self, on: bool) -> Self {
        self.progress = on;
        self
    }

    /// The members.
    pub fn members(&self) -> &M {
        &self.members
    }

    /// Number of members.
    pub fn len(&self) -> usize {
        self.members.len()
    }

    /// Whether there are no members.
    pub fn is_empty(&self) -> bool {
        self.members.is_empty()
    }

    /// Members per chunk of a reduction.
    pub fn chunk(&self) -> usize {
        self.chunk
            .unwrap_or_else(|| self.members.len().div_ceil(DEFAULT_CHUNKS).max(1))
    }

    /// Number of chunks.
    pub fn chunks(&self) -> usize {
        self.members.len().div_ceil(self.chunk())
    }

    /// Runs member `index` alone (to look into one member of a large ensemble): its result, or
    /// [`MemberError::Failed`] with what its run returned, [`MemberError::Panicked`] with the message
    /// of a panic in it (or in the construction of its parameters), [`MemberError::Ensemble`] with
    /// [`Error::NoSuchMember`] for an index out of range.
    pub fn run_member<S, E>(&self, index: usize) -> std::result::Result<S, MemberError<E>>
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
    {
        error::check_member(index, self.members.len())?;
        // The closure is only called: a panic in it leaves nothing of ours half-updated, and the
        // caller's state is the closure's own business (AssertUnwindSafe).
        let run = std::panic::AssertUnwindSafe(|| {
            let params = self.members.member(index)?;
            (self.simulate)(index, &params).map_err(MemberError::Failed)
        });
        std::panic::catch_unwind(run).unwrap_or_else(|payload| {
            Err(MemberError::Panicked {
                message: error::panic_message(payload.as_ref()),
            })
        })
    }

    /// Runs every member (in parallel on rayon's current pool) and returns the results in member
    /// order; a member that failed or panicked has its [`MemberError`].
    pub fn run<S, E>(&self) -> Runs<S, MemberError<E>>
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
        S: Send,
        E: Send,
    {
        Runs {
            results: self.run_range(0..self.members.len()),
        }
    }

    /// The results of members `range`, in order.
    fn run_range<S, E>(&self, range: std::ops::Range<usize>) -> Vec<std::result::Result<S, MemberError<E>>>
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
        S: Send,
        E: Send,
    {
        let bar = Progress::new(self.progress, range.len());
        let out = range
            .into_par_iter()
            .map(|i| {
                let r = self.run_member(i);
                bar.tick();
                r
            })
            .collect();
        bar.finish();
        out
    }

    /// Reduces every member's output with `reducer`, keeping none of them: the chunks run in
    /// parallel on rayon's current pool, and the result is bit-identical for any number of threads
    /// (see the [crate] docs). Members that failed or panicked are left out of the value and listed
    /// with their [`MemberError`].
    pub fn reduce<S, E, R>(&self, reducer: &R) -> Reduced<R::Acc, MemberError<E>>
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
        R: Reducer<S>,
        E: Send,
    {
        let (accs, failures) = self.fold_chunks(reducer, 0..self.chunks());
        Reduced {
            value: reduce::tree(reducer, accs),
            failures,
            members: self.members.len(),
        }
    }

    /// The accumulators of chunks `chunks`, in order, and the failures in them.
    fn fold_chunks<S, E, R>(&self, reducer: &R, chunks: std::ops::Range<usize>) -> (Vec<R::Acc>, Failures<E>)
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
        R: Reducer<S>,
        E: Send,
    {
        let (n, chunk) = (self.members.len(), self.chunk());
        let first = chunks.start * chunk;
        let bar = Progress::new(self.progress, (chunks.end * chunk).min(n).saturating_sub(first));
        let folded: Vec<(R::Acc, Failures<E>)> = chunks
            .into_par_iter()
            .map(|c| {
                let mut acc = reducer.identity();
                let mut failures = Vec::new();
                for i in c * chunk..((c + 1) * chunk).min(n) {
                    match self.run_member(i) {
                        Ok(s) => reducer.fold(&mut acc, i, s),
                        Err(error) => failures.push(Failure { index: i, error }),
                    }
                    bar.tick();
                }
                (acc, failures)
            })
            .collect();
        bar.finish();
        let mut accs = Vec::with_capacity(folded.len());
        let mut failures = Vec::new();
        for (a, f) in folded {
            accs.push(a);
            failures.extend(f);
        }
        (accs, failures)
    }
}

/// A progress bar when the feature `progress` is on and one was asked for; else nothing.
struct Progress {
    #[cfg(feature = "progress")]
    bar: Option<indicatif::ProgressBar>,
}

impl Progress {
    #[cfg_attr(not(feature = "progress"), allow(unused_variables))]
    fn new(on: bool, n: usize) -> Self {
        Progress {
            #[cfg(feature = "progress")]
            bar: on.then(|| {
                let bar = indicatif::ProgressBar::new(n as u64);
                if let Ok(style) = indicatif::ProgressStyle::with_template(
                    "{bar:40} {pos}/{len} members, {elapsed} (eta {eta})",
                ) {
                    bar.set_style(style);
                }
                bar
            }),
        }
    }

    fn tick(&self) {
        #[cfg(feature = "progress")]
        if let Some(bar) = &self.bar {
            bar.inc(1);
        }
    }

    fn finish(&self) {
        #[cfg(feature = "progress")]
        if let Some(bar) = &self.bar {
            bar.finish();
        }
    }
}
