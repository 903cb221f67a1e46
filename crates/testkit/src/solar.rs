//! The outer solar system of Hairer, Lubich & Wanner (*Geometric Numerical Integration*, §I.2.4,
//! Table I.2.1): the Sun (with the inner planets' mass), Jupiter, Saturn, Uranus, Neptune and Pluto
//! as point masses under Newton's gravity, on 5 September 1994, in AU, days and solar masses.
//!
//! Used by the gallery's `work_precision` benchmark and the `high_order_orbits` example (feature
//! `particles`).

use noether_core::State;
use noether_particles::{AllPairs, Gravity, Parallel, Particle, System, Vec3};

/// G in AU³/(solar mass·day²) (GNI I.2.4).
pub const G: f64 = 2.95912208286e-4;

/// Masses relative to the Sun (the Sun's includes the inner planets), positions (AU) and velocities
/// (AU/day) on 5 September 1994 (GNI Table I.2.1): Sun, Jupiter, Saturn, Uranus, Neptune, Pluto.
pub const BODIES: [(f64, [f64; 3], [f64; 3]); 6] = [
    (1.00000597682, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
    (
        0.000954786104043,
        [-3.5023653, -3.8169847, -1.5507963],
        [0.00565429, -0.00412490, -0.00190589],
    ),
    (
        0.000285583733151,
        [9.0755314, -3.0458353, -1.6483708],
        [0.00168318, 0.00483525, 0.00192462],
    ),
    (
        0.0000437273164546,
        [8.3101420, -16.2901086, -7.2521278],
        [0.00354178, 0.00137102, 0.00055029],
    ),
    (
        0.0000517759138449,
        [11.4707666, -25.7294829, -10.8169456],
        [0.00288930, 0.00114527, 0.00039677],
    ),
    (
        1.0 / 1.3e8,
        [-15.5387357, -25.2225594, -3.1902382],
        [0.00276725, -0.00170702, -0.00136504],
    ),
];

/// The six bodies under pairwise gravity (serial pair sums).
pub type Gravitating = System<((), AllPairs<Gravity>)>;

/// The system and its state on 5 September 1994 (t = 0).
pub fn outer_solar_system() -> (Gravitating, State) {
    let particles = BODIES.iter().map(|(m, _, _)| Particle::new(*m)).collect();
    let sys = System::new(particles)
        .and_then(|s| s.with(AllPairs::new(Gravity { g: G })))
        .expect("solar system");
    let q: Vec<Vec3> = BODIES.iter().map(|b| b.1).collect();
    let v: Vec<Vec3> = BODIES.iter().map(|b| b.2).collect();
    let s0 = sys.state(0.0, &q, &v).expect("state");
    (sys.parallel(Parallel::Serial), s0)
}
