//! Pair interactions that are not listed one by one: [`AllPairs`] (every pair i < j, e.g. gravity) and
//! [`ShortRange`] (pairs closer than the potential's cutoff, found with a cell list in O(N)).

use crate::error::{Error, Result};
use crate::interaction::{push_pair_block, Interaction, Triplets};
use crate::particle::{add3, sub3, Particle, Vec3};
use crate::potential::{pair_gradient, pair_hessian, sep, sep64, PairPotential};
use noether_core::Scalar;
use rayon::prelude::*;
use std::sync::Mutex;

/// The potential between every pair i < j of the system's particles: V = Σ_{i<j} U(r_j − r_i).
///
/// Serial: the row loop a hand-written code would use (each pair evaluated once, ±force applied).
/// Parallel: each particle gathers its row in pair order (each pair evaluated twice, the additions in
/// exactly the serial order, so bit-identical); it pays off from three cores on.
pub struct AllPairs<P> {
    potential: P,
}

impl<P: PairPotential> AllPairs<P> {
    /// `potential` between all pairs.
    pub fn new(potential: P) -> Self {
        AllPairs { potential }
    }
}

impl<P: PairPotential> Interaction for AllPairs<P> {
    fn validate(&self, _n: usize) -> Result<()> {
        Ok(())
    }
    fn terms(&self, n: usize) -> usize {
        // The gather path doubles the work: only worth it with more than two threads.
        if rayon::current_num_threads() > 2 {
            n * n.saturating_sub(1) / 2
        } else {
            0
        }
    }
    fn potential<D: Scalar>(&self, _t: f64, x: &[D], ps: &[Particle]) -> D {
        let n = ps.len();
        let mut acc = D::zero();
        for i in 0..n {
            for j in i + 1..n {
                acc += self.potential.energy(sep(x, i, j), &ps[i], &ps[j]);
            }
        }
        acc
    }
    fn add_forces(&self, _t: f64, x: &[f64], ps: &[Particle], f: &mut [f64], parallel: bool) -> f64 {
        let n = ps.len();
        if !parallel {
            let mut total = 0.0;
            for i in 0..n {
                let mut e = 0.0;
                for j in i + 1..n {
                    let (u, g) = pair_gradient(&self.potential, sep64(x, i, j), &ps[i], &ps[j]);
                    e += u;
                    add3(f, i, g);
                    sub3(f, j, g);
                }
                total += e;
            }
            return total;
        }
        let rows: Vec<f64> = f
            .par_chunks_mut(3)
            .enumerate()
            .map(|(i, fi)| {
                let mut acc = [fi[0], fi[1], fi[2]];
                for k in 0..i {
                    let (_, g) = pair_gradient(&self.potential, sep64(x, k, i), &ps[k], &ps[i]);
                    acc = [acc[0] - g[0], acc[1] - g[1], acc[2] - g[2]];
                }
                let mut e = 0.0;
                for j in i + 1..n {
                    let (u, g) = pair_gradient(&self.potential, sep64(x, i, j), &ps[i], &ps[j]);
                    e += u;
                    acc = [acc[0] + g[0], acc[1] + g[1], acc[2] + g[2]];
                }
                fi.copy_from_slice(&acc);
                e
            })
            .collect();
        rows.iter().fold(0.0, |a, e| a + e)
    }
    fn add_hessian(&self, _t: f64, x: &[f64], ps: &[Particle], out: &mut Triplets) {
        for i in 0..ps.len() {
            for j in i + 1..ps.len() {
                let h = pair_hessian(&self.potential, sep64(x, i, j), &ps[i], &ps[j]);
                push_pair_block(out, i, j, h);
            }
        }
    }
    fn find_singular(&self, _t: f64, x: &[f64], ps: &[Particle]) -> Option<Error> {
        for i in 0..ps.len() {
            for j in i + 1..ps.len() {
                let r = sep64(x, i, j);
                let (u, g) = pair_gradient(&self.potential, r, &ps[i], &ps[j]);
                if !(u.is_finite() && g.iter().all(|v| v.is_finite())) {
                    return Some(Error::pair(i, j, r));
                }
            }
        }
        None
    }
}

/// A uniform grid of cubic cells of side ≥ the cutoff over the particles' bounding box; particles
/// sorted by cell (counting sort, O(N)).
#[derive(Debug, Default, Clone)]
pub struct CellList {
    origin: Vec3,
    side: f64,
    dims: [usize; 3],
    start: Vec<u32>,
    order: Vec<u32>,
}

impl CellList {
    /// Builds the list for positions `x` (length 3N, finite) and cutoff `rc` (finite, > 0): cells of
    /// side ≥ rc over the particles' bounding box, no more than about 2N + 8 of them. Errors:
    /// `InvalidParameter` for the cutoff, `Dimension` for a length that is not a multiple of 3,
    /// `NonFinite` for a position (all as [`Error::Core`]); the list is left as it was.
    pub fn build(&mut self, x: &[f64], rc: f64) -> Result<()> {
        if !(rc.is_finite() && rc > 0.0) {
            return Err(Error::Core(noether_core::Error::InvalidParameter {
                name: "cell list cutoff",
                value: rc,
                reason: "the cutoff must be finite and positive",
            }));
        }
        noether_core::error::check_len("positions", x, 3 * (x.len() / 3))?;
        noether_core::error::check_finite("positions", x)?;
        self.fill(x, rc);
        Ok(())
    }

    /// Builds the list for a cutoff `rc` known to be finite and positive; returns whether every
    /// position is finite (when one is not, all particles share one cell and the caller reports it).
    ///
    /// The extents are taken at half scale, (hi − lo)/2 = hi/2 − lo/2, and so is each particle's offset
    /// from the box's corner: the same numbers as at full scale (halving is exact), but finite for
    /// positions out to ±f64::MAX, where hi − lo overflows.
    fn fill(&mut self, x: &[f64], rc: f64) -> bool {
        let n = x.len() / 3;
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        // x·0 is 0 for finite x and NaN otherwise (min and max skip a NaN).
        let mut poison = 0.0;
        for p in x.chunks_exact(3) {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
                poison += p[k] * 0.0;
            }
        }
        let finite = poison == 0.0;
        if n == 0 || !finite {
            lo = [0.0; 3];
            hi = [0.0; 3];
        }
        // Cells no smaller than rc, and no more cells than ~2N (a lone far-away particle must not
        // create a huge empty grid). Counted in f64: at extents like 1e20 the integer counts would
        // overflow.
        let half: [f64; 3] = std::array::from_fn(|k| 0.5 * hi[k] - 0.5 * lo[k]);
        let mut side = rc;
        let limit = (2 * n + 8) as f64;
        let cells = |s: f64| -> [f64; 3] {
            // A flat direction is one cell (0/0 at a subnormal side would be NaN).
            std::array::from_fn(|k| {
                if half[k] > 0.0 {
                    (half[k] / (0.5 * s)).floor() + 1.0
                } else {
                    1.0
                }
            })
        };
        while cells(side).iter().product::<f64>() > limit {
            // ×1.25 would round a subnormal side back to itself.
            side *= if side < f64::MIN_POSITIVE { 2.0 } else { 1.25 };
        }
        let dims: [usize; 3] = cells(side).map(|c| c as usize);
        let ncell = dims.iter().product::<usize>();
        self.origin = lo;
        self.side = side;
        self.dims = dims;
        self.start.clear();
        self.start.resize(ncell + 1, 0);
        let cell_of = |p: &[f64]| -> usize {
            let c: [usize; 3] = std::array::from_fn(|k| {
                // NaN (a non-finite position) casts to 0: cell 0, reported by the caller.
                (((0.5 * p[k] - 0.5 * lo[k]) / (0.5 * side)) as usize).min(dims[k] - 1)
            });
            c[0] + dims[0] * (c[1] + dims[1] * c[2])
        };
        for p in x.chunks_exact(3) {
            self.start[cell_of(p) + 1] += 1;
        }
        for c in 0..ncell {
            self.start[c + 1] += self.start[c];
        }
        self.order.clear();
        self.order.resize(n, 0);
        let mut fill: Vec<u32> = self.start[..ncell].to_vec();
        for (i, p) in x.chunks_exact(3).enumerate() {
            let c = cell_of(p);
            self.order[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        finite
    }

    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    fn members(&self, c: usize) -> &[u32] {
        &self.order[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// Visits every pair closer than `rc` once, cell by cell: (i, j, r_j − r_i).
    fn for_pairs_of_cell(&self, c: usize, x: &[f64], rc2: f64, mut visit: impl FnMut(usize, usize, Vec3)) {
        let [nx, ny, nz] = self.dims;
        let (cx, cy, cz) = (c % nx, (c / nx) % ny, c / (nx * ny));
        let own = self.members(c);
        for (a, &i) in own.iter().enumerate() {
            for &j in &own[a + 1..] {
                let r = sep64(x, i as usize, j as usize);
                if r[0] * r[0] + r[1] * r[1] + r[2] * r[2] < rc2 {
                    visit(i as usize, j as usize, r);
                }
            }
        }
        // Half of the 26 neighbours: each pair of cells is visited once.
        for &(dx, dy, dz) in HALF_STENCIL.iter() {
            let (ox, oy, oz) = (cx as isize + dx, cy as isize + dy, cz as isize + dz);
            if ox < 0 || oy < 0 || oz < 0 || ox >= nx as isize || oy >= ny as isize || oz >= nz as isize {
                continue;
            }
            let other = self.members(ox as usize + nx * (oy as usize + ny * oz as usize));
            for &i in own {
                for &j in other {
                    let r = sep64(x, i as usize, j as usize);
                    if r[0] * r[0] + r[1] * r[1] + r[2] * r[2] < rc2 {
                        visit(i as usize, j as usize, r);
                    }
                }
            }
        }
    }
}

const HALF_STENCIL: [(isize, isize, isize); 13] = [
    (1, 0, 0),
    (-1, 1, 0),
    (0, 1, 0),
    (1, 1, 0),
    (-1, -1, 1),
    (0, -1, 1),
    (1, -1, 1),
    (-1, 0, 1),
    (0, 0, 1),
    (1, 0, 1),
    (-1, 1, 1),
    (0, 1, 1),
    (1, 1, 1),
];

#[derive(Default)]
struct Scratch {
    cells: CellList,
}

/// A raw pointer to the force array shared by the threads of one slab phase.
#[derive(Clone, Copy)]
struct SharedForces(*mut f64, usize);

// SAFETY: threads write through the pointer only to the particles of two adjacent slabs (s, s + 1) of
// cells, and the slabs processed at the same time are two apart (all even, then all odd), so no two
// threads ever touch the same particle; every particle lies in exactly one cell.
unsafe impl Send for SharedForces {}
unsafe impl Sync for SharedForces {}

impl SharedForces {
    #[inline(always)]
    fn add(&self, i: usize, g: Vec3, sign: f64) {
        assert!(3 * i + 2 < self.1, "particle index out of the force array");
        // SAFETY: in bounds (checked above); exclusive per particle within a phase (see the impl).
        unsafe {
            for (k, gk) in g.iter().enumerate() {
                *self.0.add(3 * i + k) += sign * gk;
            }
        }
    }
}

/// A short-range pair potential between all particles closer than its cutoff, V = Σ_{i<j, r<rc} U.
/// Pairs are found with a [`CellList`] rebuilt at each evaluation, so a force evaluation costs O(N) at
/// fixed density. Cells are processed in z-slabs, first the even slabs then the odd ones; a slab's pairs
/// reach only its own and the next slab, so the slabs of one phase run in parallel without conflicts
/// and without extra work. The order of the additions to each particle is the same on one or many
/// threads, so results are bit-identical.
pub struct ShortRange<P> {
    potential: P,
    rc: f64,
    scratch: Mutex<Scratch>,
}

impl<P: PairPotential> ShortRange<P> {
    /// `potential` between all pairs closer than `potential.cutoff()` (which must be finite and > 0).
    pub fn new(potential: P) -> Result<Self> {
        let rc = potential.cutoff().unwrap_or(f64::NAN);
        if !(rc.is_finite() && rc > 0.0) {
            return Err(Error::Core(noether_core::Error::InvalidParameter {
                name: "cutoff",
                value: rc,
                reason: "a short-range potential needs a finite positive cutoff (PairPotential::cutoff)",
            }));
        }
        Ok(ShortRange {
            potential,
            rc,
            scratch: Mutex::new(Scratch::default()),
        })
    }

    fn eval_pair(&self, i: usize, j: usize, r: Vec3, ps: &[Particle]) -> (f64, Vec3) {
        pair_gradient(&self.potential, r, &ps[i], &ps[j])
    }
}

impl<P: PairPotential> Interaction for ShortRange<P> {
    fn validate(&self, _n: usize) -> Result<()> {
        Ok(())
    }
    fn terms(&self, n: usize) -> usize {
        // About 15 neighbours closer than the cutoff per particle at liquid density.
        15 * n
    }
    fn potential<D: Scalar>(&self, _t: f64, x: &[D], ps: &[Particle]) -> D {
        let n = ps.len();
        let rc2 = self.rc * self.rc;
        let mut acc = D::zero();
        for i in 0..n {
            for j in i + 1..n {
                let r = sep(x, i, j);
                if (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).re() < rc2 {
                    acc += self.potential.energy(r, &ps[i], &ps[j]);
                }
            }
        }
        acc
    }
    fn energy(&self, _t: f64, x: &[f64], ps: &[Particle]) -> f64 {
        let mut s = self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        if !s.cells.fill(x, self.rc) {
            return f64::NAN;
        }
        let rc2 = self.rc * self.rc;
        let mut total = 0.0;
        for c in 0..s.cells.cells() {
            s.cells.for_pairs_of_cell(c, x, rc2, |i, j, r| {
                total += self.potential.energy(r, &ps[i], &ps[j]);
            });
        }
        total
    }
    fn add_forces(&self, _t: f64, x: &[f64], ps: &[Particle], f: &mut [f64], parallel: bool) -> f64 {
        let mut guard = self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        let s = &mut *guard;
        if !s.cells.fill(x, self.rc) {
            // A non-finite position has no neighbours in the list: the energy says so, and the caller
            // reports the position (not an Ok(0) from the pairs it could not find).
            return f64::NAN;
        }
        let rc2 = self.rc * self.rc;
        let cells = &s.cells;
        let [nx, ny, nz] = cells.dims;
        let shared = SharedForces(f.as_mut_ptr(), f.len());
        // All pairs of the cells of slab z (pairs reach slabs z and z + 1 only).
        let slab = |z: usize| -> f64 {
            let mut e = 0.0;
            for c in z * nx * ny..(z + 1) * nx * ny {
                cells.for_pairs_of_cell(c, x, rc2, |i, j, r| {
                    let (u, g) = self.eval_pair(i, j, r, ps);
                    e += u;
                    shared.add(i, g, 1.0);
                    shared.add(j, g, -1.0);
                });
            }
            e
        };
        let mut total = 0.0;
        for phase in 0..2 {
            let energies: Vec<f64> = if parallel {
                (phase..nz).into_par_iter().step_by(2).map(slab).collect()
            } else {
                (phase..nz).step_by(2).map(slab).collect()
            };
            total = energies.iter().fold(total, |a, e| a + e);
        }
        total
    }
    fn add_hessian(&self, _t: f64, x: &[f64], ps: &[Particle], out: &mut Triplets) {
        let mut s = self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        // The caller checked that the positions are finite.
        s.cells.fill(x, self.rc);
        for c in 0..s.cells.cells() {
            s.cells.for_pairs_of_cell(c, x, self.rc * self.rc, |i, j, r| {
                push_pair_block(out, i, j, pair_hessian(&self.potential, r, &ps[i], &ps[j]));
            });
        }
    }
    fn find_singular(&self, _t: f64, x: &[f64], ps: &[Particle]) -> Option<Error> {
        let mut s = self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        s.cells.fill(x, self.rc);
        let mut found = None;
        for c in 0..s.cells.cells() {
            s.cells.for_pairs_of_cell(c, x, self.rc * self.rc, |i, j, r| {
                let (u, g) = self.eval_pair(i, j, r, ps);
                if found.is_none() && !(u.is_finite() && g.iter().all(|v| v.is_finite())) {
                    found = Some(Error::pair(i, j, r));
                }
            });
        }
        found
    }
}
