//! The gallery's shared closed forms and measurements (`noether_gallery::closed_form`, which is
//! crates/testkit/src/closed_form.rs, and src/measure.rs) against tables, identities and hand-worked
//! cases.

// Reference values are quoted with the digits their source gives.
#[allow(clippy::excessive_precision)]
mod closed_form {
    use noether_gallery::closed_form::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn closed_form_elliptic_k() {
        // K(0) = π/2; K(1/√2) = Γ(1/4)² / (4 √π) with Γ(1/4) = 3.625609908221908311930685...
        assert!((elliptic_k(0.0) - PI / 2.0).abs() < 1e-15);
        let gamma_quarter = 3.625_609_908_221_908_f64;
        let expected = gamma_quarter * gamma_quarter / (4.0 * PI.sqrt());
        assert!((elliptic_k(0.5_f64.sqrt()) - expected).abs() < 1e-14 * expected);
        // Series K(k) = π/2 (1 + k²/4 + 9k⁴/64 + 25k⁶/256 + …) for small k.
        let k: f64 = 0.01;
        let series = PI / 2.0 * (1.0 + k * k / 4.0 + 9.0 * k.powi(4) / 64.0 + 25.0 * k.powi(6) / 256.0);
        assert!((elliptic_k(k) - series).abs() < 1e-15);
    }

    #[test]
    fn closed_form_elliptic_k_near_one() {
        // K ≈ ln(4/k′) + (k′²/4)(ln(4/k′) − 1) as k′ → 0 (Abramowitz & Stegun 17.3.26); at
        // k′ = 1e-6 the neglected terms are O(k′⁴ ln k′) ~ 1e-23.
        let kp: f64 = 1e-6;
        let l = (4.0 / kp).ln();
        let expected = l + kp * kp / 4.0 * (l - 1.0);
        assert!((elliptic_k_complementary(kp) - expected).abs() < 4e-15 * expected);
    }

    #[test]
    fn elliptic_k_and_e_against_tables() {
        // (m = k², K, E) from A&S Table 17.1 (DLMF 19.2.8), digits confirmed with mpmath at 30 digits;
        // the last row is k′ = 1e-6 (m₁ = 1e-12), where K = 15.20180491908771517 and
        // E = 1 + O(k′² ln k′) = 1.00000000000735090246 (A&S 17.3.26, 17.3.36).
        // Measured: largest relative error 2.4e-16 for K; for E 2.2e-16, but 1.1e-15 at k′ = 1e-6, where
        // E = K (1 − Σ) cancels a sum Σ ≈ 1 − 1/K (a factor K/E ≈ 15 of rounding): 1e-15 for K, 4e-15
        // for E.
        let rows: [(f64, f64, f64); 4] = [
            (0.5_f64.sqrt(), 1.854_074_677_301_371_9, 1.350_643_881_047_675_5),
            (0.1_f64.sqrt(), 2.578_092_113_348_173_2, 1.104_774_732_704_073_3),
            (0.01_f64.sqrt(), 3.695_637_362_989_874_7, 1.015_993_545_025_223_9),
            (1e-6, 15.201_804_919_087_715, 1.000_000_000_007_350_9),
        ];
        for (kp, k_ref, e_ref) in rows {
            let (k, e) = elliptic_ke_complementary(kp);
            assert!(rel(k, k_ref) < 1e-15, "K(k′={kp}) = {k} vs {k_ref}");
            assert!(rel(e, e_ref) < 4e-15, "E(k′={kp}) = {e} vs {e_ref}");
            assert!(rel(elliptic_k_complementary(kp), k_ref) < 1e-15);
        }
        // k = 0: K = E = π/2; k′ → 0: E → 1.
        let (k0, e0) = elliptic_ke_complementary(1.0);
        assert_eq!((k0, e0), (FRAC_PI_2, FRAC_PI_2));
    }

    #[test]
    fn legendre_relation() {
        // E K′ + E′ K − K K′ = π/2 (DLMF 19.7.1), with K′, E′ the integrals of the complementary
        // modulus: pairs (k, k′) with k² + k′² = 1 (to rounding), down to k′ = 1e-6. Measured 5.6e-16
        // relative, and 3.3e-15 at k′ = 1e-6 (the sum cancels to π/2 from terms up to K K′ ≈ 24, and
        // carries E's error there): 1e-14.
        let pairs = [
            (0.6, 0.8),
            (0.28, 0.96),
            (0.5_f64.sqrt(), 0.5_f64.sqrt()),
            (1.0 - 5e-13, 1e-6),
        ];
        for (k, kp) in pairs {
            let (kk, ee) = elliptic_ke_complementary(kp);
            let (kk1, ee1) = elliptic_ke_complementary(k);
            let lhs = ee * kk1 + ee1 * kk - kk * kk1;
            assert!(rel(lhs, FRAC_PI_2) < 1e-14, "k′={kp}: {lhs}");
        }
    }

    #[test]
    fn jacobi_functions_against_reference_values() {
        // (u, m, m₁, sn, cn, dn) computed with mpmath's ellipfun at 30 digits; the last row is m₁ = 1e-12
        // (k′ = 1e-6). Measured: all exact to the last digit but dn at m₁ = 1e-12 (1.4e-17): 1e-15.
        let rows: [(f64, f64, f64, [f64; 3]); 4] = [
            (
                0.5,
                0.3,
                0.7,
                [
                    0.474_215_622_711_820_6,
                    0.880_408_736_426_462_4,
                    0.965_678_964_745_951_2,
                ],
            ),
            (
                1.2,
                0.7,
                0.3,
                [
                    0.867_183_293_290_238_6,
                    0.497_989_092_087_664_1,
                    0.688_182_530_355_724_2,
                ],
            ),
            (
                2.0,
                0.99,
                0.01,
                [
                    0.966_054_624_849_770_9,
                    0.258_337_883_026_025_55,
                    0.275_809_856_945_513_8,
                ],
            ),
            (
                3.0,
                1.0 - 1e-12,
                1e-12,
                [
                    0.995_054_753_686_971_8,
                    0.099_327_927_417_015_25,
                    0.099_327_927_421_999_42,
                ],
            ),
        ];
        for (u, m, m1, expected) in rows {
            let (sn, cn, dn) = jacobi_sn_cn_dn(u, m, m1);
            for (got, want) in [sn, cn, dn].into_iter().zip(expected) {
                assert!((got - want).abs() < 1e-15, "u={u} m={m}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn jacobi_functions_special_values_and_identities() {
        // DLMF 22.5.1-2: sn(K) = 1, cn(K) = 0, dn(K) = k′; sn(K/2) = 1/sqrt(1 + k′),
        // cn(K/2) = sqrt(k′/(1 + k′)), dn(K/2) = sqrt(k′). m = 0: sin, cos, 1. Down to k′ = 1e-6.
        // Measured: at u = K errors ≤ 6.1e-17 (cn(K) is cos of the double nearest π/2); at u = K/2,
        // ≤ 1.7e-16 down to k′ = 0.3, then 5.1e-16 (k′ = 1e-3) and 2.9e-15 (k′ = 1e-6) absolute in cn
        // and dn: the first descending step takes asin of (c₁/a₁) sin φ₁ with c₁/a₁ ≈ 1 − 2k′, where
        // asin's slope is 1/(2 sqrt k′). That is the method's limit near k → 1: 1e-14 absolute.
        for kp in [0.8, 0.3, 1e-3, 1e-6] {
            let (m, m1) = ((1.0 - kp) * (1.0 + kp), kp * kp);
            let k_big = elliptic_k_complementary(kp);
            let (sn, cn, dn) = jacobi_sn_cn_dn(k_big, m, m1);
            assert!(
                (sn - 1.0).abs() < 1e-15 && cn.abs() < 1e-15,
                "k′={kp}: sn {sn}, cn {cn}"
            );
            assert!((dn - kp).abs() < 1e-15, "k′={kp}: dn(K) {dn}");
            let (sn, cn, dn) = jacobi_sn_cn_dn(0.5 * k_big, m, m1);
            assert!(
                (sn - 1.0 / (1.0 + kp).sqrt()).abs() < 1e-14,
                "k′={kp}: sn(K/2) {sn}"
            );
            assert!(
                (cn - (kp / (1.0 + kp)).sqrt()).abs() < 1e-14,
                "k′={kp}: cn(K/2) {cn}"
            );
            assert!((dn - kp.sqrt()).abs() < 1e-14, "k′={kp}: dn(K/2) {dn}");
        }
        let (sn, cn, dn) = jacobi_sn_cn_dn(0.7, 0.0, 1.0);
        assert_eq!((sn, cn, dn), (0.7_f64.sin(), 0.7_f64.cos(), 1.0));
        // sn² + cn² = 1 and dn² + m sn² = 1 (DLMF 22.6.1) over a grid of u and m, with m near 1.
        // Measured 2.2e-16 and 3.3e-16 at worst: 1e-15.
        for m1 in [0.9, 0.5, 0.1, 1e-6, 1e-12] {
            let m = 1.0 - m1;
            for i in 0..40 {
                let u = -5.0 + 0.37 * i as f64;
                let (sn, cn, dn) = jacobi_sn_cn_dn(u, m, m1);
                assert!(
                    (sn * sn + cn * cn - 1.0).abs() < 1e-15,
                    "sn²+cn² at u={u}, m₁={m1}"
                );
                assert!(
                    (dn * dn + m * sn * sn - 1.0).abs() < 1e-15,
                    "dn²+m sn² at u={u}, m₁={m1}"
                );
            }
        }
    }

    #[test]
    fn kepler_equation() {
        // (e, M, E) from mpmath's findroot at 30 digits. Measured ≤ 1.1e-16 absolute, but 7.5e-16 at
        // e = 0.999, M = 1e-3, where f′ = 1 − e cos E ≈ 0.015 amplifies the residual's rounding: 2e-15.
        let rows = [
            (0.5, 1.0, 1.498_701_133_517_848_3),
            (0.9, 0.1, 0.630_843_527_563_153_4),
            (0.999, 1e-3, 0.170_850_956_323_579_02),
            (0.2, 3.0, 3.023_553_121_752_160_2),
        ];
        for (e, m, expected) in rows {
            let ea = kepler_eccentric_anomaly(m, e);
            assert!((ea - expected).abs() < 2e-15, "e={e} M={m}: {ea} vs {expected}");
        }
        // e = 0: E = M; and the residual E − e sin E − M over a grid of M (including whole turns and
        // M near 0 at e → 1, the hard case): measured ≤ 3.6e-16 relative to max(|M|, 1): 1e-15.
        assert_eq!(kepler_eccentric_anomaly(0.3, 0.0), 0.3);
        for e in [0.0, 0.1, 0.5, 0.9, 0.99, 0.999_999] {
            for i in 0..=200 {
                let m = -20.0 + 0.2 * i as f64;
                let ea = kepler_eccentric_anomaly(m, e);
                let residual = ea - e * ea.sin() - m;
                assert!(
                    residual.abs() < 1e-15 * m.abs().max(1.0),
                    "e={e} M={m}: {residual}"
                );
            }
        }
    }
}

mod measure {
    use noether_gallery::measure::*;

    #[test]
    fn mean_period_of_equally_spaced_times() {
        assert_eq!(mean_period(&[1.0, 3.0, 5.0, 7.0]), Some(2.0));
        assert_eq!(mean_period(&[1.0]), None);
    }

    #[test]
    fn envelope_takes_the_largest_magnitude_per_window() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let y = [1.0, -3.0, 2.0, 0.5, 9.0];
        assert_eq!(envelope(&x, &y, 2), vec![(1.0, 3.0), (3.0, 2.0)]);
    }
}
