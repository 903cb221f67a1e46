//! The LGVI's observed order on a second problem: an asymmetric heavy top (a torque that depends on
//! the orientation), where no closed form exists. The order comes from three successive halvings:
//! with x_h the state at t = 1 after 1/h steps, e(h) = |x_h − x_{h/2}| = C h² (1 − 1/4) + O(h³), so
//! log₂ e(h)/e(h/2) → 2 without a reference solution.

use nalgebra::{UnitQuaternion, Vector3};
use noether_core::{Momenta, State, Stepper};
use noether_rigid::{Inertia, Lgvi, RigidBody, UniformGravity};

/// The state (quaternion and body angular momentum) at t = 1 after 1/h steps of size h.
fn end_state(h: f64) -> Vec<f64> {
    let gravity = UniformGravity {
        mass: 1.0,
        g: 9.81,
        center: Vector3::new(0.05, -0.02, 0.3),
    };
    let body = RigidBody::new(Inertia::principal(0.9, 1.1, 0.4).unwrap(), gravity).unwrap();
    let mut s: State<Momenta> = body.state(
        0.0,
        &UnitQuaternion::from_euler_angles(0.7, -0.2, 0.3),
        &Vector3::new(0.5, -1.0, 6.0),
    );
    let mut lgvi = Lgvi::new(body).unwrap();
    for _ in 0..(1.0 / h).round() as usize {
        lgvi.step(&mut s, h).unwrap();
    }
    s.q.iter().chain(s.v.iter()).copied().collect()
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// h = 0.02 … 0.0025: measured orders 2.0036 and 2.0009 (the O(h³) remainder shrinking); tolerance
/// ±0.01.
#[test]
fn order_heavy_top() {
    let x: Vec<Vec<f64>> = [0.02, 0.01, 0.005, 0.0025]
        .iter()
        .map(|&h| end_state(h))
        .collect();
    let e: Vec<f64> = x.windows(2).map(|w| distance(&w[0], &w[1])).collect();
    for w in e.windows(2) {
        let p = (w[0] / w[1]).log2();
        eprintln!("heavy top order {p} ({e:?})");
        assert!((p - 2.0).abs() < 0.01, "{e:?}");
    }
}
