//! Coulomb scattering: deflection angle and Rutherford's cross section from simulated orbits.
//! `cargo run --release --example rutherford`; model and checks in `src/gallery/rutherford.rs`.
fn main() {
    noether::gallery::main_for("rutherford");
}
