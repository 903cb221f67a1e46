//! Relativistic cyclotron motion: `cargo run --release --example cyclotron`. The Lagrangian
//! −mc² sqrt(1 − v²/c²) + e v·A gives circles at ω = eB/(γm). Model and checks in
//! `src/gallery/cyclotron.rs`.
fn main() {
    noether::gallery::main_for("cyclotron");
}
