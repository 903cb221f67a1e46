//! The spherical pendulum in Cartesian coordinates vs spherical angles: same motion, conserved E and L_z.
//! The model and the checks live in `src/gallery/spherical_pendulum.rs`.
//!
//! Run: `cargo run --release --example spherical_pendulum`
fn main() {
    noether::gallery::main_for("spherical_pendulum");
}
