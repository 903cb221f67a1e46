//! Bertrand's theorem: `cargo run --release --example bertrand`. Kepler and harmonic orbits close,
//! r^(−1.1) precesses at the near-circular rate. Model and checks in `src/gallery/bertrand.rs`.
fn main() {
    noether::gallery::main_for("bertrand");
}
