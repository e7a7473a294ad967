//! Timing and reporting for `bench_peers`.

use std::time::Instant;

/// Collects rows and prints them as a table.
pub struct Report {
    /// Timed runs per row (the median is reported).
    pub runs: usize,
    failures: usize,
    only: Option<String>,
}

/// A peer's figure for the same workload, and the ratio we aim for.
pub struct Peer {
    /// Who measured it (e.g. "pmp-library").
    pub name: &'static str,
    /// Their time in seconds.
    pub seconds: f64,
    /// Target: our time at most `ratio` × theirs.
    pub ratio: f64,
}

impl Report {
    /// A report timing each row `runs` times.
    pub fn new(runs: usize, only: Option<String>) -> Report {
        println!(
            "{:<48} {:>11} {:>11} {:>8} {:>7}  verdict",
            "workload", "meshloom", "peer", "ratio", "target"
        );
        Report {
            runs: runs.max(1),
            failures: 0,
            only,
        }
    }

    /// Time `work` (after one untimed warm-up run) `runs` times; `setup`
    /// runs before each, untimed, and its output is handed to `work`.
    pub fn time<S, R>(
        &mut self,
        name: &str,
        peer: Option<Peer>,
        mut setup: impl FnMut() -> S,
        mut work: impl FnMut(S) -> R,
    ) -> f64 {
        if !self.wanted(name) {
            return f64::NAN;
        }
        std::hint::black_box(work(setup()));
        let mut samples = Vec::with_capacity(self.runs);
        for _ in 0..self.runs {
            let input = setup();
            let t = Instant::now();
            let out = work(input);
            samples.push(t.elapsed().as_secs_f64());
            std::hint::black_box(out);
        }
        samples.sort_by(f64::total_cmp);
        let median = samples[samples.len() / 2];
        self.row(name, median, peer);
        median
    }

    /// Whether the row named `name` is to be run (`--only`).
    pub fn wanted(&self, name: &str) -> bool {
        self.only.as_deref().is_none_or(|o| name.contains(o))
    }

    /// Print one timed row.
    pub fn row(&mut self, name: &str, seconds: f64, peer: Option<Peer>) {
        if !self.wanted(name) || seconds.is_nan() {
            return;
        }
        match peer {
            Some(p) => {
                let ratio = seconds / p.seconds;
                let ok = ratio <= p.ratio;
                if !ok {
                    self.failures += 1;
                }
                println!(
                    "{:<48} {:>9.2}ms {:>9.2}ms {:>8.2} {:>7.2}  {} ({})",
                    name,
                    seconds * 1e3,
                    p.seconds * 1e3,
                    ratio,
                    p.ratio,
                    if ok { "meets" } else { "MISSES" },
                    p.name
                );
            }
            None => println!("{:<48} {:>9.2}ms", name, seconds * 1e3),
        }
    }

    /// Print a non-time figure with an optional bound it should stay under.
    pub fn figure(&mut self, name: &str, value: f64, unit: &str, at_most: Option<(f64, &str)>) {
        if !self.wanted(name) {
            return;
        }
        match at_most {
            Some((bound, who)) => {
                let ok = value <= bound;
                if !ok {
                    self.failures += 1;
                }
                println!(
                    "{:<48} {:>9.1}{unit} {:>9.1}{unit} {:>8.2} {:>7}  {} ({who})",
                    name,
                    value,
                    bound,
                    value / bound,
                    "1.00",
                    if ok { "meets" } else { "MISSES" }
                );
            }
            None => println!("{:<48} {:>9.1}{unit}", name, value),
        }
    }

    /// Print the summary line.
    pub fn finish(self) {
        println!(
            "\n{} of the rows with a target miss it (medians of {} runs)",
            self.failures, self.runs
        );
    }
}
