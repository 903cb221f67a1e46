//! Every gallery example's checks against closed forms must pass (each check states its formula and
//! tolerance in the example module that makes it).

use noether_gallery::{self as gallery, Check, Example, Options, Outcome, Report};

/// Runs the example `name` without pictures and asserts that all its checks pass.
fn assert_example_passes(name: &str) {
    let ex = gallery::all()
        .into_iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("no example {name}"));
    let report = (ex.run)(&Options::default()).unwrap_or_else(|e| panic!("{name} failed: {e}"));
    assert_report_passes(name, &report);
}

/// Asserts that `report` made checks and that all of them pass.
fn assert_report_passes(name: &str, report: &Report) {
    assert!(!report.checks.is_empty(), "{name} made no checks");
    let failed: Vec<String> = report
        .checks
        .iter()
        .filter(|c| !c.passed())
        .map(|c| c.to_string())
        .collect();
    assert!(failed.is_empty(), "failed checks:\n{}", failed.join("\n"));
}

/// The page `cargo run --release` writes (issue 30 item 13), for every example of the registry: each
/// has its section and its entry in the contents, and every picture the page shows exists in the
/// folder beside it. The outcomes are stand-ins (one check and one picture each, every fifth example
/// failed) so that the test does not draw the whole gallery a second time; the real pictures of two
/// examples are checked by the next test.
#[test]
fn gallery_page_names_every_example_and_every_picture_exists() {
    let dir = scratch("names");
    let runs: Vec<(Example, Outcome)> = gallery::all()
        .into_iter()
        .enumerate()
        .map(|(i, ex)| {
            let outcome = if i % 5 == 4 {
                Err(format!("{} <failed> & said so", ex.name))
            } else {
                let svg = dir.join(format!("{}.svg", ex.name));
                std::fs::write(&svg, "<svg xmlns=\"http://www.w3.org/2000/svg\"/>").unwrap();
                Ok(Report {
                    checks: vec![Check::rel(ex.name, "x", 1.0, 1.0, 1e-15)],
                    figures: vec![svg],
                    notes: vec![],
                })
            };
            (ex, outcome)
        })
        .collect();
    let html = page_of(&dir, &runs);
    for (ex, _) in &runs {
        assert!(
            html.contains(&format!("<section id=\"{}\">", ex.name)),
            "no section for {}",
            ex.name
        );
        assert!(
            html.contains(&format!("<a href=\"#{0}\">{0}</a>", ex.name)),
            "{} not in the contents",
            ex.name
        );
    }
    assert!(
        html.contains("&lt;failed&gt; &amp; said so"),
        "an example's error is shown, escaped"
    );
    let expected = runs.iter().filter(|(_, o)| o.is_ok()).count();
    assert_eq!(pictures_shown(&dir, &html), expected);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The page of two real examples with their pictures: every picture they drew is on the page, and
/// every picture on the page is in the folder.
#[test]
fn gallery_page_shows_the_pictures_examples_draw() {
    let dir = scratch("real");
    let opts = Options {
        out_dir: Some(dir.clone()),
    };
    let runs: Vec<(Example, Outcome)> = gallery::all()
        .into_iter()
        .filter(|e| e.name == "pendulum" || e.name == "bouncing_ball")
        .map(|ex| {
            let outcome = gallery::run_caught(&ex, &opts);
            (ex, outcome)
        })
        .collect();
    assert_eq!(runs.len(), 2);
    let html = page_of(&dir, &runs);
    let mut drawn = 0;
    for (ex, outcome) in &runs {
        let report = outcome
            .as_ref()
            .unwrap_or_else(|e| panic!("{} failed: {e}", ex.name));
        for f in &report.figures {
            let rel = f.strip_prefix(&dir).unwrap().to_string_lossy().into_owned();
            assert!(
                html.contains(&format!("<img src=\"{rel}\"")),
                "picture {rel} not on the page"
            );
            drawn += 1;
        }
    }
    assert!(drawn >= 2, "the two examples draw {drawn} pictures");
    assert_eq!(pictures_shown(&dir, &html), drawn);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An empty folder of this test process's own.
fn scratch(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("noether-gallery-page-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes the page into `dir` and reads it back.
fn page_of(dir: &std::path::Path, runs: &[(Example, Outcome)]) -> String {
    let page = gallery::page::write_index(dir, runs).unwrap();
    assert_eq!(page, dir.join(gallery::page::INDEX));
    std::fs::read_to_string(page).unwrap()
}

/// The number of pictures the page shows, each checked to exist in `dir`.
fn pictures_shown(dir: &std::path::Path, html: &str) -> usize {
    let shown: Vec<&str> = html
        .split("<img src=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    for src in &shown {
        assert!(
            dir.join(src).is_file(),
            "the page shows {src}, which is not in {}",
            dir.display()
        );
    }
    shown.len()
}

#[test]
fn gallery_names_are_unique() {
    let mut names: Vec<_> = gallery::all().iter().map(|e| e.name).collect();
    let n = names.len();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), n);
}

// One test per example; each example module states its closed forms and why each tolerance is what it is.
#[test]
fn closed_form_pendulum() {
    assert_example_passes("pendulum");
}

#[test]
fn closed_form_bouncing_ball() {
    assert_example_passes("bouncing_ball");
}

#[test]
fn closed_form_export_trajectory() {
    assert_example_passes("export_trajectory");
}

#[test]
fn closed_form_two_springs() {
    assert_example_passes("two_springs");
}

#[test]
fn closed_form_binary_star() {
    assert_example_passes("binary_star");
}

#[test]
fn closed_form_billiard() {
    assert_example_passes("billiard");
}

#[test]
fn closed_form_third_law() {
    assert_example_passes("third_law");
}

/// The gallery example runs the full 10⁵ steps (`cargo run --release --example lj_cluster`, ~4 s on
/// an idle core); the test runs the same cluster for 2·10⁴ steps to keep the suite fast. Same checks.
#[test]
fn conserves_energy_lj_cluster() {
    let report = gallery::examples::lj_cluster::run_steps(20_000).expect("lj_cluster runs");
    assert_report_passes("lj_cluster", &report);
}

#[test]
fn closed_form_coupled_chains() {
    assert_example_passes("coupled_chains");
}

#[test]
fn closed_form_coupled_chains_momentum() {
    assert_example_passes("coupled_chains_momentum");
}

#[test]
fn closed_form_coupled_chains_transfer() {
    assert_example_passes("coupled_chains_transfer");
}

#[test]
fn closed_form_coupled_chains_heat() {
    assert_example_passes("coupled_chains_heat");
}

#[test]
fn closed_form_heavy_top() {
    assert_example_passes("heavy_top");
}

#[test]
fn closed_form_top_nutation() {
    assert_example_passes("top_nutation");
}

#[test]
fn closed_form_joints_double_pendulum() {
    assert_example_passes("joints_double_pendulum");
}

#[test]
fn closed_form_reaction_wheel_pendulum() {
    assert_example_passes("reaction_wheel_pendulum");
}

#[test]
fn closed_form_slider_crank() {
    assert_example_passes("slider_crank");
}

#[test]
fn closed_form_spherical_joint() {
    assert_example_passes("spherical_joint");
}

#[test]
fn closed_form_rolling_coin() {
    assert_example_passes("rolling_coin");
}

#[test]
fn closed_form_four_bar() {
    assert_example_passes("four_bar");
}

#[test]
fn closed_form_planar_arm() {
    assert_example_passes("planar_arm");
}

#[test]
fn closed_form_fast_top() {
    assert_example_passes("fast_top");
}

#[test]
fn closed_form_sleeping_top() {
    assert_example_passes("sleeping_top");
}

#[test]
fn closed_form_harmonic_oscillator() {
    assert_example_passes("harmonic_oscillator");
}

#[test]
fn closed_form_kepler() {
    assert_example_passes("kepler");
}

#[test]
fn closed_form_high_order_orbits() {
    assert_example_passes("high_order_orbits");
}

#[test]
fn closed_form_mercury_perihelion() {
    assert_example_passes("mercury_perihelion");
}

#[test]
fn conserves_energy_double_pendulum() {
    assert_example_passes("double_pendulum");
}

#[test]
fn textbook_equations_of_motion() {
    assert_example_passes("equations_of_motion");
}

#[test]
fn compiled_and_dual_agree_compiled_chain() {
    assert_example_passes("compiled_chain");
}

#[test]
fn closed_form_charged_particle() {
    assert_example_passes("charged_particle");
}

#[test]
fn closed_form_exb_drift() {
    assert_example_passes("exb_drift");
}

#[test]
fn closed_form_three_body() {
    assert_example_passes("three_body");
}

#[test]
fn closed_form_trojan_orbits() {
    assert_example_passes("trojan_orbits");
}

#[test]
fn closed_form_rutherford() {
    assert_example_passes("rutherford");
}

#[test]
fn closed_form_bertrand() {
    assert_example_passes("bertrand");
}

#[test]
fn closed_form_driven_pendulum() {
    assert_example_passes("driven_pendulum");
}

#[test]
fn closed_form_galerkin_orders() {
    assert_example_passes("galerkin_orders");
}

#[test]
fn closed_form_cart_pole_lqr() {
    assert_example_passes("cart_pole_lqr");
}

#[test]
fn closed_form_satellite_slew() {
    assert_example_passes("satellite_slew");
}

#[test]
fn closed_form_swing_up() {
    assert_example_passes("swing_up");
}

#[test]
fn closed_form_cyclotron() {
    assert_example_passes("cyclotron");
}

#[test]
fn closed_form_pendulum_cartesian() {
    assert_example_passes("pendulum_cartesian");
}

#[test]
fn closed_form_bead_rotating_hoop() {
    assert_example_passes("bead_rotating_hoop");
}

#[test]
fn closed_form_hoop_equilibria() {
    assert_example_passes("hoop_equilibria");
}

#[test]
fn closed_form_spherical_pendulum() {
    assert_example_passes("spherical_pendulum");
}

#[test]
fn closed_form_bead_helix() {
    assert_example_passes("bead_helix");
}

#[test]
fn closed_form_bead_cycloid() {
    assert_example_passes("bead_cycloid");
}

#[test]
fn closed_form_rolling_disk() {
    assert_example_passes("rolling_disk");
}

#[test]
fn closed_form_normal_modes() {
    assert_example_passes("normal_modes");
}

#[test]
fn closed_form_struck_rod() {
    assert_example_passes("struck_rod");
}

#[test]
fn closed_form_collision_lab_cm() {
    assert_example_passes("collision_lab_cm");
}

#[test]
fn closed_form_action_angle() {
    assert_example_passes("action_angle");
}

#[test]
fn closed_form_poisson_brackets() {
    assert_example_passes("poisson_brackets");
}

#[test]
fn closed_form_canonical_transformation() {
    assert_example_passes("canonical_transformation");
}

#[test]
fn closed_form_hamilton_jacobi() {
    assert_example_passes("hamilton_jacobi");
}

#[test]
fn closed_form_poincare_henon_heiles() {
    assert_example_passes("poincare_henon_heiles");
}

#[test]
fn closed_form_routh_reduction() {
    assert_example_passes("routh_reduction");
}

#[test]
fn closed_form_adiabatic_invariant() {
    assert_example_passes("adiabatic_invariant");
}

#[test]
fn closed_form_free_rigid_body() {
    assert_example_passes("free_rigid_body");
}

#[test]
fn closed_form_intermediate_axis() {
    assert_example_passes("intermediate_axis");
}

#[test]
fn closed_form_top_quaternion() {
    assert_example_passes("top_quaternion");
}

#[test]
fn closed_form_gibbs_appell() {
    assert_example_passes("gibbs_appell");
}

#[test]
fn closed_form_rolling_sphere() {
    assert_example_passes("rolling_sphere");
}

#[test]
fn closed_form_periodic_orbits() {
    assert_example_passes("periodic_orbits");
}

#[test]
fn closed_form_figure_eight() {
    assert_example_passes("figure_eight");
}

#[test]
fn closed_form_lyapunov_spectrum() {
    assert_example_passes("lyapunov_spectrum");
}

#[test]
fn continuation_lyapunov_family() {
    assert_example_passes("lyapunov_family");
}

#[test]
fn bifurcation_halo_orbits() {
    assert_example_passes("halo_orbits");
}

/// The gallery example maps 32 × 32 to t = 1000, its sea orbit to t = 10⁵ (`cargo run --release
/// --example megno_map`); the test maps 24 × 24, the sea orbit to 5·10⁴ (as many crossings per cell),
/// the same checks.
#[test]
fn chaos_map_megno() {
    let report =
        gallery::examples::megno_map::run_grid(24, 1000.0, 5e4, &Options::default()).expect("megno_map runs");
    for c in &report.checks {
        eprintln!("{c}");
    }
    for n in &report.notes {
        eprintln!("{n}");
    }
    assert_report_passes("megno_map", &report);
}

#[test]
fn closed_form_sensitivity() {
    assert_example_passes("sensitivity");
}

#[test]
fn closed_form_symplecticity_check() {
    assert_example_passes("symplecticity_check");
}

#[test]
fn closed_form_boundary_value() {
    assert_example_passes("boundary_value");
}

/// The gallery example counts 10⁵ particles (`cargo run --release --example scattering_monte_carlo`);
/// the test counts 5·10⁴, the same checks (their statistical bounds scale with the counts).
#[test]
fn closed_form_scattering_monte_carlo() {
    let report = gallery::examples::scattering_monte_carlo::run_members(50_000, &Options::default())
        .expect("scattering_monte_carlo runs");
    for c in &report.checks {
        eprintln!("{c}");
    }
    assert_report_passes("scattering_monte_carlo", &report);
}

/// The gallery example maps a 90 × 90 grid to t = 30 (`cargo run --release --example flip_map`); the
/// test maps 40 × 40 to t = 20, the same checks.
#[test]
fn energy_bound_flip_map() {
    let report = gallery::examples::flip_map::run_grid(40, 20.0, &Options::default()).expect("flip_map runs");
    for c in &report.checks {
        eprintln!("{c}");
    }
    assert_report_passes("flip_map", &report);
}
