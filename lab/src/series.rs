//! What the studies share about a measured series: where to sample a long run, and how fast a quantity
//! grows along it.

/// Checkpoints every half decade (a factor √10) from `first` steps to `total`, each rounded to a whole
/// step; `total` last.
pub fn half_decades(first: f64, total: u64) -> Vec<u64> {
    let mut v = Vec::new();
    let mut c = first;
    while (c.round() as u64) < total {
        v.push(c.round() as u64);
        c *= 10f64.sqrt();
    }
    v.push(total);
    v
}

/// Least-squares slope of log(y) against log(x), over the points with x > 0 and a finite y > 0; NaN when
/// fewer than two are left.
pub fn log_slope(points: &[(f64, f64)]) -> f64 {
    let p: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if p.len() < 2 {
        return f64::NAN;
    }
    let n = p.len() as f64;
    let (mx, my) = (
        p.iter().map(|q| q.0).sum::<f64>() / n,
        p.iter().map(|q| q.1).sum::<f64>() / n,
    );
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    let sxx: f64 = p.iter().map(|q| (q.0 - mx) * (q.0 - mx)).sum();
    sxy / sxx
}
