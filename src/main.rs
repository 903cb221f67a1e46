//! The gallery: runs the worked examples and prints their checks against closed forms.
fn main() {
    println!("noether gallery (under construction)");
}
