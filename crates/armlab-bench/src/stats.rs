//! The statistics of a benchmark's samples: percentiles by nearest rank, the mean, and a
//! summary. One helper for the IK benchmark, the native frame benchmark and the JS API's
//! benchmark.

/// The `p`-quantile (0 ≤ p ≤ 1) of `sorted` (ascending) by nearest rank: the sample at
/// index `round((n − 1)·p)`. `None` for no samples. `p = 0.5` of `[1, 2, 3, 4]` is 3 (index
/// round(1.5) = 2); `p = 1` is the largest sample.
pub fn percentile(sorted: &[f64], p: f64) -> Option<f64> {
    let last = sorted.len().checked_sub(1)?;
    let k = (last as f64 * p.clamp(0.0, 1.0)).round() as usize;
    sorted.get(k.min(last)).copied()
}

/// The arithmetic mean, `None` for no samples.
pub fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

/// Median, mean, 95th and 99th percentile and maximum of a set of samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// How many samples.
    pub count: usize,
    /// The 0.5-quantile.
    pub median: f64,
    /// The mean.
    pub mean: f64,
    /// The 0.95-quantile.
    pub p95: f64,
    /// The 0.99-quantile.
    pub p99: f64,
    /// The largest sample.
    pub max: f64,
}

impl Summary {
    /// The summary of `samples` (sorted in place); `None` when there are none.
    pub fn of(samples: &mut [f64]) -> Option<Summary> {
        samples.sort_by(f64::total_cmp);
        Some(Summary {
            count: samples.len(),
            median: percentile(samples, 0.5)?,
            mean: mean(samples)?,
            p95: percentile(samples, 0.95)?,
            p99: percentile(samples, 0.99)?,
            max: percentile(samples, 1.0)?,
        })
    }
}
