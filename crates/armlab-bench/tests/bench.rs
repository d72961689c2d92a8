//! The benchmark's statistics and request parsing (the benchmark itself is a binary, not
//! a test): nearest-rank percentiles of known lists, and each bad request field named.

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_bench::ik::{BenchError, MAX_BUDGET, MAX_SAMPLES, config_from_json};
use armlab_bench::stats::{Summary, mean, percentile};

#[test]
fn percentiles_by_nearest_rank_of_known_lists() {
    let four = [1.0, 2.0, 3.0, 4.0];
    assert_eq!(percentile(&four, 0.0), Some(1.0));
    assert_eq!(percentile(&four, 0.5), Some(3.0), "index round(1.5) = 2");
    assert_eq!(percentile(&four, 1.0), Some(4.0));
    let hundred: Vec<f64> = (1..=100).map(f64::from).collect();
    assert_eq!(
        percentile(&hundred, 0.95),
        Some(95.0),
        "index round(94.05) = 94"
    );
    assert_eq!(percentile(&hundred, 0.99), Some(99.0));
    assert_eq!(percentile(&[], 0.5), None);
    assert_eq!(mean(&[]), None);
    assert_eq!(mean(&four), Some(2.5));
    let mut shuffled = vec![5.0, 1.0, 4.0, 2.0, 3.0];
    let s = Summary::of(&mut shuffled).expect("samples");
    assert_eq!((s.count, s.median, s.mean, s.max), (5, 3.0, 3.0, 5.0));
    assert_eq!(shuffled, [1.0, 2.0, 3.0, 4.0, 5.0], "sorted in place");
    assert_eq!(Summary::of(&mut []), None);
}

#[test]
fn bad_benchmark_requests_name_their_field() {
    assert_eq!(config_from_json("").expect("defaults").samples, 10_000);
    let c = config_from_json(r#"{"samples": 500, "budget": 200, "seed": 7}"#).expect("valid");
    assert_eq!((c.samples, c.budget, c.seed), (500, 200, 7));
    let cases = [
        ("{", "not JSON"),
        (r#"{"samples": -1}"#, "\"samples\" must be a whole number"),
        (r#"{"budget": 1.5}"#, "\"budget\" must be a whole number"),
        (
            r#"{"samples": 100000000}"#,
            "\"samples\" must be between 1 and 100000",
        ),
        (
            r#"{"budget": 0}"#,
            "\"budget\" must be between 1 and 100000",
        ),
        (
            r#"{"solver_tolerance": -1}"#,
            "\"solver_tolerance\" must be a positive number",
        ),
        (r#"{"sample": 5}"#, "\"sample\" is not known"),
    ];
    for (request, expected) in cases {
        let e = config_from_json(request).expect_err(request);
        assert!(e.to_string().contains(expected), "{request}: {e}");
    }
    assert_eq!(
        config_from_json(r#"{"samples": 0}"#),
        Err(BenchError::OutOfRange {
            field: "samples",
            max: MAX_SAMPLES
        })
    );
    assert_eq!(MAX_BUDGET, 100_000);
}
