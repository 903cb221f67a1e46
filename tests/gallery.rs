//! Every gallery example's checks against closed forms must pass (each check states its formula and
//! tolerance in the example module that makes it).

use noether_gallery::{self as gallery, Options, Report};

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
fn closed_form_pendulum_cartesian() {
    assert_example_passes("pendulum_cartesian");
}

#[test]
fn closed_form_bead_rotating_hoop() {
    assert_example_passes("bead_rotating_hoop");
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
