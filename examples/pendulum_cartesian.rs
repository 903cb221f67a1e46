//! A pendulum in Cartesian coordinates with a rod constraint x² + y² = l²: same motion as the angle
//! formulation, and the rod tension from the Lagrange multiplier, T = m g cos θ + m l θ̇².
//! The model and the checks live in `src/gallery/pendulum_cartesian.rs`.
//!
//! Run: `cargo run --release --example pendulum_cartesian`
fn main() {
    noether::gallery::main_for("pendulum_cartesian");
}
