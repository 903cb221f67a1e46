//! The models that noether's tests, benchmarks and gallery share, each written once, with their
//! closed forms and hand-derived reference equations.
//!
//! A model checked both by a crate's integration tests and by an example of the gallery (or measured
//! by a benchmark) lives here, so the two check the same code. Each item keeps the formula it encodes
//! and where that comes from; the tolerances stay with the tests and examples that use them. Not
//! published: the library crates take it as a dev-dependency only, the gallery as a dependency.
//!
//! Modules that need a crate beyond `noether-core` are behind a feature of that crate's name.
//!
//! | module | the models | used by |
//! |---|---|---|
//! | [`systems`] | core's test systems (double pendulum, heavy top, chains, charge in a field, …) with their hand-derived equations | core's `ad` tests and benchmarks, the gallery's `double_pendulum` and `work_precision` |
//! | [`kepler`], `peer` | Kepler's problem as benchmarked; ode_solvers' DOP853 and Kepler's right-hand side for it (feature `peer`) | core's benchmarks, the gallery's `work_precision` |
//! | [`henon_heiles`] | Hénon-Heiles (and its surface of section), the unit double pendulum as a Hamiltonian | core's tangent tests, analysis' Lyapunov and chaos tests, `symplecticity_check`, `lyapunov_spectrum`, `poincare_henon_heiles`, `megno_map` |
//! | [`three_body`] | the figure-eight (and its shooting problem), the restricted problem, L1 and its continuation | analysis' periodic-orbit tests, discrete's boundary tests, `figure_eight`, `periodic_orbits`, `boundary_value` |
//! | [`top`] | the heavy top in Euler angles, Kepler in polar coordinates | canonical's Routh tests, `heavy_top`, `routh_reduction` |
//! | [`pendulum`] | the pendulum of the ensembles and its quarter period | ensemble's tests and `mpi_scan` |
//! | [`agreement`] | the relative difference of two vectors, reproducible uniform random numbers | noether-compile's tests, `equations_of_motion` |
//! | [`closed_form`] | K, E, sn, cn, dn, Kepler's equation, the free top's Ω(t) | the gallery (`noether_gallery::closed_form`), rigid's tests |
//! | `gibbs_appell` | the four-particle top, the rolling disk and sphere, their closed forms (feature `constraints`) | constraints' tests, `gibbs_appell`, `rolling_sphere` |
//! | `coin` | the coin rolling on a table in dependent coordinates, its steady turns and their stability (feature `constraints`) | analysis' control tests |
//! | `multibody` | the double pendulum from two hinges, a planar arm of three rods with its mass matrix and tip in closed form (feature `multibody`) | multibody's tests, `joints_double_pendulum`, `planar_arm` |
//! | `solar` | the outer solar system of Hairer, Lubich & Wanner (feature `particles`) | the gallery's `work_precision` benchmark and `high_order_orbits` |
//! | `timing` | `min_ns`: the least time per call over rounds | core's benchmarks `rates`, `accelerations_min`, `tangent` |
//! | `boundary` | the boundary-value problems (feature `discrete`) | discrete's tests, `boundary_value` |
//! | `canonical`, `hamilton_jacobi` | canonical maps, generating and phase functions, complete integrals (feature `canonical`) | canonical's tests, `canonical_transformation`, `poisson_brackets`, `action_angle`, `hamilton_jacobi` |

pub mod agreement;
#[cfg(feature = "discrete")]
pub mod boundary;
#[cfg(feature = "canonical")]
pub mod canonical;
pub mod closed_form;
#[cfg(feature = "constraints")]
pub mod coin;
pub mod control;
#[cfg(feature = "constraints")]
pub mod gibbs_appell;
#[cfg(feature = "canonical")]
pub mod hamilton_jacobi;
pub mod henon_heiles;
pub mod kepler;
#[cfg(feature = "multibody")]
pub mod multibody;
#[cfg(feature = "peer")]
pub mod peer;
pub mod pendulum;
#[cfg(feature = "particles")]
pub mod solar;
pub mod systems;
pub mod three_body;
pub mod timing;
pub mod top;
