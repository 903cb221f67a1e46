//! Equilibria and normal modes: `cargo run --release --example normal_modes`.
//!
//! Coupled pendula, a chain with fixed ends, the bead on a rotating hoop and a triangle of springs;
//! the models and checks live in `src/gallery/normal_modes.rs`.
fn main() {
    noether::gallery::main_for("normal_modes");
}
