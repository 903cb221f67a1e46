//! Runs the `charged_particle` example of the gallery and prints its checks against closed forms.
//!
//! The model and the checks are in `src/gallery/charged_particle.rs` (open it to read or copy the model).
//! Run: `cargo run --release --example charged_particle` (pictures go to `gallery-out/`).

fn main() {
    noether::gallery::main_for("charged_particle");
}
