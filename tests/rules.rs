//! quickcheck properties of the stock rules themselves, on random
//! contributor lists (absent values included).

use meshloom::attr::{
    Conserved, Contagion, Dynamic, Incompatible, Interpolate, KeepFirst, Rule, Value,
};
use quickcheck::quickcheck;

/// Contributors from raw numbers: `None` where the flag is false; weights
/// made non-negative and normalised to sum to 1.
fn contributors(raw: &[(bool, i16, u8)]) -> Vec<(Option<f64>, f64)> {
    let total: f64 = raw.iter().map(|&(_, _, w)| f64::from(w)).sum();
    raw.iter()
        .map(|&(present, x, w)| {
            let w = if total > 0.0 {
                f64::from(w) / total
            } else {
                1.0 / raw.len() as f64
            };
            (present.then_some(f64::from(x)), w)
        })
        .collect()
}

fn args(c: &[(Option<f64>, f64)]) -> Vec<(Option<&f64>, f64)> {
    c.iter().map(|(v, w)| (v.as_ref(), *w)).collect()
}

fn present(c: &[(Option<f64>, f64)]) -> Vec<f64> {
    c.iter().filter_map(|(v, _)| *v).collect()
}

quickcheck! {
    fn conserved_split_shares_sum_back(x: i32, raw_shares: Vec<u8>) -> bool {
        let total: f64 = raw_shares.iter().map(|&s| f64::from(s)).sum();
        if total == 0.0 {
            return true;
        }
        let x = f64::from(x);
        let back: f64 = raw_shares
            .iter()
            .map(|&s| <Conserved as Rule<f64>>::split(Some(&x), f64::from(s) / total).unwrap())
            .sum();
        (back - x).abs() <= 1e-9 * x.abs().max(1.0)
    }

    fn conserved_merge_is_the_sum_of_present_values(raw: Vec<(bool, i16, u8)>) -> bool {
        let c = contributors(&raw);
        let p = present(&c);
        let got = <Conserved as Rule<f64>>::merge(&args(&c));
        if p.is_empty() {
            got.is_none()
        } else {
            got == Some(p.iter().sum())
        }
    }

    fn interpolate_stays_between_present_values(raw: Vec<(bool, i16, u8)>) -> bool {
        let c = contributors(&raw);
        let p = present(&c);
        match <Interpolate as Rule<f64>>::merge(&args(&c)) {
            None => p.is_empty(),
            Some(m) => {
                let lo = p.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                m >= lo - 1e-9 && m <= hi + 1e-9
            }
        }
    }

    fn incompatible_never_mixes(raw: Vec<(bool, i16, u8)>) -> bool {
        let c = contributors(&raw);
        match <Incompatible as Rule<f64>>::merge(&args(&c)) {
            // Absent: nobody, someone without a value, or a disagreement.
            None => c.is_empty() || c.iter().any(|(v, _)| v.is_none() || *v != c[0].0),
            Some(m) => c.iter().all(|(v, _)| *v == Some(m)),
        }
    }

    fn contagion_keeps_the_greatest_present_value(raw: Vec<(bool, i16, u8)>) -> bool {
        let c = contributors(&raw);
        let p = present(&c);
        match <Contagion as Rule<f64>>::merge(&args(&c)) {
            None => p.is_empty(),
            Some(m) => p.contains(&m) && p.iter().all(|&x| x <= m),
        }
    }

    fn keep_first_keeps_the_first(raw: Vec<(bool, i16, u8)>) -> bool {
        let c = contributors(&raw);
        <KeepFirst as Rule<f64>>::merge(&args(&c)) == c.first().and_then(|(v, _)| *v)
    }

    fn rules_depend_only_on_their_inputs(raw: Vec<(bool, i16, u8)>) -> bool {
        // Same contributors, same order: same result, every time.
        let c = contributors(&raw);
        let a = args(&c);
        let dynamic: Vec<Option<Value>> = c.iter().map(|(v, _)| v.map(Value::F64)).collect();
        let d: Vec<(Option<&Value>, f64)> = dynamic.iter().zip(&c).map(|(v, (_, w))| (v.as_ref(), *w)).collect();
        <Interpolate as Rule<f64>>::merge(&a) == <Interpolate as Rule<f64>>::merge(&a)
            && Dynamic::merge(&d) == Dynamic::merge(&d)
            && Dynamic::merge(&d).map(|v| v.as_f64())
                == <Interpolate as Rule<f64>>::merge(&a).map(Some)
    }
}
