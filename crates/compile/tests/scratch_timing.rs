#![allow(missing_docs)]
use noether_compile::Compile;
use noether_core::EulerLagrange;
use noether_testkit::systems::DoublePendulum;
use std::hint::black_box;
use std::time::Instant;

#[test]
fn timing_dp() {
    let c = EulerLagrange::new(DoublePendulum::default()).compile().unwrap();
    println!("{:?}", c.backend());
    let mut a = [0.0; 2];
    for _ in 0..3 {
        let t0 = Instant::now();
        for i in 0..5_000_000 {
            let q = [0.7 + 1e-12 * i as f64, -0.4];
            c.accelerations(0.0, black_box(&q), black_box(&[0.3, 1.1]), &mut a)
                .unwrap();
            black_box(&a);
        }
        let tc = t0.elapsed().as_nanos() as f64 / 5e6;
        let dp = DoublePendulum::default();
        let t0 = Instant::now();
        for i in 0..5_000_000 {
            let q = [0.7 + 1e-12 * i as f64, -0.4];
            black_box(dp.hand_accelerations(black_box(&q), black_box(&[0.3, 1.1])));
        }
        let th = t0.elapsed().as_nanos() as f64 / 5e6;
        println!("acc {tc:.1} hand {th:.1} ratio {:.2}", tc / th);
    }
}
