//! The restricted three-body problem in the rotating frame: `cargo run --release --example three_body`.
//!
//! Jacobi integral, the five Lagrange points as equilibria of the effective potential, and their
//! stability (Routh's criterion for L4/L5). Model and checks: `src/gallery/three_body.rs`.
fn main() {
    noether::gallery::main_for("three_body");
}
