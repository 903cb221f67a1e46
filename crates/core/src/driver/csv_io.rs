//! Saved runs as CSV: one header naming the columns, `t, q0 … q(n−1), v0 … v(n−1)` (`p0 …` for a
//! momentum solution) and then the observed quantities by name, and one row per saved state. Numbers
//! are written in Rust's shortest round-trip form, so reading a file back gives the same `f64`s bit for
//! bit. Events, statistics and dense output are not part of the file.

use super::Solution;
use crate::{Error, Partner, Result, State};
use std::io::{Read, Write};
use std::path::Path;

fn saved_run(line: Option<u64>, reason: impl std::fmt::Display) -> Error {
    Error::SavedRun {
        line,
        reason: reason.to_string(),
    }
}

/// The state's columns: `t`, `q0` … `q(n−1)`, then the partner's (`v0` … or `p0` …).
fn state_columns<K: Partner>(dof: usize) -> impl Iterator<Item = String> {
    std::iter::once("t".to_string())
        .chain((0..dof).map(|i| format!("q{i}")))
        .chain((0..dof).map(|i| format!("{}{i}", K::SYMBOL)))
}

fn csv_error(e: csv::Error) -> Error {
    saved_run(e.position().map(|p| p.line()), e)
}

impl<K: Partner> Solution<K> {
    /// The CSV header: `t`, `q0` … , `v0` … (or `p0` …), then the observer names.
    pub fn csv_header(&self) -> Vec<String> {
        state_columns::<K>(self.dof)
            .chain(self.observer_names.iter().cloned())
            .collect()
    }

    /// Writes the solution as CSV to `w`: a header `t,q0,…,v0,…` (`p0,…` for momenta) and the observer
    /// names, then one row per saved state in the shortest form that reads back to the same `f64`.
    pub fn write_csv<W: Write>(&self, w: W) -> Result<()> {
        let mut out = csv::Writer::from_writer(w);
        out.write_record(self.csv_header()).map_err(csv_error)?;
        let (n, m) = (self.dof, self.observer_names.len());
        let mut row: Vec<String> = Vec::with_capacity(1 + 2 * n + m);
        for (i, t) in self.t.iter().enumerate() {
            row.clear();
            row.push(format!("{t:?}"));
            let values = self.q[i * n..(i + 1) * n]
                .iter()
                .chain(&self.v[i * n..(i + 1) * n])
                .chain(&self.observed[i * m..(i + 1) * m]);
            row.extend(values.map(|x| format!("{x:?}")));
            out.write_record(&row).map_err(csv_error)?;
        }
        out.flush().map_err(|e| saved_run(None, e))
    }

    /// Writes the solution to the CSV file at `path` (created or truncated).
    pub fn save_csv(&self, path: impl AsRef<Path>) -> Result<()> {
        let path = path.as_ref();
        let file =
            std::fs::File::create(path).map_err(|e| saved_run(None, format!("{}: {e}", path.display())))?;
        self.write_csv(std::io::BufWriter::new(file))
    }

    /// Reads a solution written by [`write_csv`](Self::write_csv): times, states and observed quantities
    /// (the method is recorded as `"csv"`; events and statistics are empty). A header that does not name
    /// `t`, equally many `q` and partner columns (`v` for velocities, `p` for momenta), a row of the
    /// wrong length, a value that is not a finite number (NaN, inf, 1e400), or a file with no row is an
    /// [`Error::SavedRun`].
    pub fn read_csv<R: Read>(r: R) -> Result<Self> {
        let mut input = csv::ReaderBuilder::new().has_headers(true).from_reader(r);
        let header: Vec<String> = input
            .headers()
            .map_err(csv_error)?
            .iter()
            .map(str::to_string)
            .collect();
        let dof = header.iter().skip(1).take_while(|h| h.starts_with('q')).count();
        let expected: Vec<String> = state_columns::<K>(dof).collect();
        if dof == 0 || header.len() < expected.len() || header[..expected.len()] != expected[..] {
            return Err(saved_run(
                Some(1),
                format!(
                    "header {:?} does not start with t, q0…, {}0… (a {} solution)",
                    header,
                    K::SYMBOL,
                    K::NAME
                ),
            ));
        }
        let observer_names = header[expected.len()..].to_vec();
        let mut sol = Solution::new(dof, "csv", observer_names, Vec::new(), State::zeros(0.0, dof));
        let mut state = State::zeros(0.0, dof);
        let mut observed = Vec::with_capacity(header.len() - expected.len());
        for record in input.records() {
            let record = record.map_err(csv_error)?;
            let line = record.position().map(|p| p.line());
            let values = record
                .iter()
                .map(|x| match x.trim().parse::<f64>() {
                    Ok(v) if v.is_finite() => Ok(v),
                    Ok(_) => Err(saved_run(line, format!("'{x}' is not a finite number"))),
                    Err(e) => Err(saved_run(line, format!("'{x}': {e}"))),
                })
                .collect::<Result<Vec<f64>>>()?;
            state.t = values[0];
            state.q.copy_from_slice(&values[1..=dof]);
            state.v.copy_from_slice(&values[dof + 1..=2 * dof]);
            observed.clear();
            observed.extend_from_slice(&values[2 * dof + 1..]);
            sol.push(&state, &observed);
        }
        if sol.is_empty() {
            return Err(saved_run(None, "the file has a header but no row"));
        }
        sol.last = state;
        Ok(sol)
    }

    /// Reads a solution from the CSV file at `path` (see [`read_csv`](Self::read_csv)).
    pub fn load_csv(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let file =
            std::fs::File::open(path).map_err(|e| saved_run(None, format!("{}: {e}", path.display())))?;
        Self::read_csv(std::io::BufReader::new(file))
    }
}

#[cfg(test)]
mod tests {
    use crate::prelude::*;

    struct Oscillator;
    impl Lagrangian for Oscillator {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            (v[0] * v[0] + v[1] * v[1] - q[0] * q[0] - q[1] * q[1] * 4.0) * 0.5
        }
    }

    fn run() -> Solution {
        let el = EulerLagrange::new(Oscillator);
        let start = State::new(0.0, [1.0, 0.5], [0.0, 0.3]);
        let mut driver = Driver::with_step(Rk4::new(&el), start, 0.01)
            .and_then(|d| d.save(Save::Every(7)))
            .unwrap()
            .observe("energy", |s: &State| {
                el.energy(s.t, s.q.as_slice(), s.v.as_slice())
            });
        driver.run_until(1.0).unwrap()
    }

    #[test]
    fn csv_round_trip_is_bit_exact() {
        let sol = run();
        let mut buf = Vec::new();
        sol.write_csv(&mut buf).unwrap();
        let text = String::from_utf8(buf.clone()).unwrap();
        assert!(text.starts_with("t,q0,q1,v0,v1,energy\n"), "{text}");
        let back = Solution::<Velocities>::read_csv(buf.as_slice()).unwrap();
        assert_eq!(back.times(), sol.times());
        assert_eq!(back.observed("energy"), sol.observed("energy"));
        for i in 0..sol.len() {
            assert_eq!(back.q(i), sol.q(i));
            assert_eq!(back.v(i), sol.v(i));
        }
        assert_eq!(back.last(), sol.last());
    }

    #[test]
    fn csv_of_the_wrong_partner_is_a_typed_error() {
        let mut buf = Vec::new();
        run().write_csv(&mut buf).unwrap();
        let err = Solution::<Momenta>::read_csv(buf.as_slice()).unwrap_err();
        assert!(matches!(err, Error::SavedRun { line: Some(1), .. }), "{err}");
    }

    #[test]
    fn csv_with_a_bad_value_or_row_is_a_typed_error() {
        let bad_value = "t,q0,v0\n0.0,1.0,0.0\n0.1,oops,0.0\n";
        let err = Solution::<Velocities>::read_csv(bad_value.as_bytes()).unwrap_err();
        assert!(matches!(err, Error::SavedRun { line: Some(3), .. }), "{err}");
        let short_row = "t,q0,v0\n0.0,1.0\n";
        let err = Solution::<Velocities>::read_csv(short_row.as_bytes()).unwrap_err();
        assert!(matches!(err, Error::SavedRun { .. }), "{err}");
        let no_rows = "t,q0,v0\n";
        assert!(Solution::<Velocities>::read_csv(no_rows.as_bytes()).is_err());
    }

    #[test]
    fn regress_csv_with_non_finite_values_is_refused() {
        // Issue 29 item 12: NaN, inf and 1e400 (which parses to inf) were read as values.
        for bad in ["NaN", "inf", "-inf", "1e400"] {
            let text = format!("t,q0,v0\n0,1,0\n0.1,{bad},0\n");
            let err = Solution::<Velocities>::read_csv(text.as_bytes()).unwrap_err();
            assert!(
                matches!(err, Error::SavedRun { line: Some(3), .. }),
                "{bad}: {err}"
            );
        }
    }

    #[cfg(feature = "serde")]
    #[test]
    fn serde_round_trip_keeps_rows_observers_and_stats() {
        let sol = run();
        let json = serde_json::to_string(&sol).unwrap();
        let back: Solution = serde_json::from_str(&json).unwrap();
        assert_eq!(back.times(), sol.times());
        assert_eq!(back.q_matrix(), sol.q_matrix());
        assert_eq!(back.observed("energy"), sol.observed("energy"));
        assert_eq!(back.stats(), sol.stats());
        assert_eq!(back.method(), sol.method());
    }

    #[cfg(feature = "serde")]
    #[test]
    fn regress_deserialized_solution_is_checked() {
        // Issue 29 items 6 and 11: a saved run whose arrays disagree (fewer times than rows, a dof that
        // does not divide the rows) was accepted, and q_matrix or write_csv then panicked.
        let sol = run();
        let mut value: serde_json::Value = serde_json::to_value(&sol).unwrap();
        let good = value.clone();
        value["t"].as_array_mut().unwrap().pop();
        let err = serde_json::from_value::<Solution>(value).unwrap_err();
        assert!(err.to_string().contains("times"), "{err}");
        let mut value = good.clone();
        value["dof"] = serde_json::json!(3);
        assert!(serde_json::from_value::<Solution>(value).is_err());
        let mut value = good.clone();
        value["observed"].as_array_mut().unwrap().pop();
        assert!(serde_json::from_value::<Solution>(value).is_err());
        let mut value = good.clone();
        value["q"][0] = serde_json::json!(null);
        assert!(serde_json::from_value::<Solution>(value).is_err());
        assert!(serde_json::from_value::<Solution>(good).is_ok());
    }
}
