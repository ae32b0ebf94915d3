//! Noise identification from a rest recording (issue 36): synthetic 3-axis sensors whose noise densities
//! are known (white noise `N`, bias instability `B`, rate or acceleration random walk `K`), streamed in f64
//! through the core's `noise::AllanVariance` and fitted with `NoiseFit::pooled_from(&avar, 16·period)`,
//! for several record lengths and seeds: how close the fit comes to the truth, how often it identifies each
//! term, how often its own 2-standard-error interval holds the truth, and how that grows with the record;
//! beside each, the information limit (the Cramér–Rao bound any unbiased estimate meets from a record that
//! long), and long records at 1 Hz (30–1000 × τ(B = K)) for the random walk, which needs them.
//!
//! The generator is the one of `tests/noise.rs`: white noise of density `N`; flicker noise of bias
//! instability `B` as a sum of Gauss–Markov processes one octave apart (each of variance `B² ln 2 / π`,
//! correlation times `period · 2^i` from the sample period up, enough octaves to pass the longest record's
//! clusters by 7); a random walk of density `K`; a constant offset. Its expected Allan variance is computed
//! exactly here (each Gauss–Markov process is an AR(1) sequence): it locates the flicker band's lower edge,
//! below the 16 periods where the fit starts, and says how far the generator departs from the model there.
//!
//! Run alone (`noise --out docs`), the study writes its own page, `DIR/noise.md`, with its figures and no
//! CSV; in `report`, a section with its CSV files.

use crate::plot::{plot, Axis, Series};
use crate::report::Ctx;
use crate::rng::Gaussian;
use crate::series::log_slope;
use crate::study::{CsvFile, Study};
use crate::table::{self, Csv, Table};
use quatprop::noise::{AllanVariance, Cluster, NoiseFit, Term, FLICKER_FLOOR};
use quatprop::Vec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The study (sub-command `noise`).
pub struct Noise;

/// Its arguments.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// Seeds (recordings) per sensor. Default 16 (4 with --quick, and in `report`; 16 in `report --full`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub seeds: Option<u32>,
    /// Record lengths in hours, comma-separated (each seed's records are the first hours of one recording
    /// as long as the longest). Default 0.5,1,2,4,8 (2,4,8 minutes with --quick).
    #[arg(long, value_delimiter = ',', value_parser = parse_hours)]
    pub hours: Vec<f64>,
    /// Run alone, the study writes its own page (`DIR/noise.md`, no CSV); in `report`, a section.
    #[arg(skip = true)]
    pub page: bool,
}

fn parse_hours(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v > 0.0 && v <= 1000.0 => Ok(v),
        _ => Err("a record length in hours, above 0 and at most 1000".into()),
    }
}

impl Study for Noise {
    type Args = Args;
    const NAME: &'static str = "noise";
    const ABOUT: &'static str =
        "Noise identification: Allan-variance fit of N, B, K on synthetic sensors against record length";
    const CSV: &'static [CsvFile] = &[
        CsvFile::table::<SensorRow>(),
        CsvFile::table::<BandRow>(),
        CsvFile::table::<ErrorRow>(),
        CsvFile::table::<MinTauRow>(),
        CsvFile::table::<LongRow>(),
        CsvFile::data::<FitRow>(),
        CsvFile::data::<AdevRow>(),
    ];
    fn figures(&self) -> Vec<String> {
        let mut f: Vec<String> = TERMS.iter().map(|t| format!("noise_{}", t.key)).collect();
        f.extend([
            "noise_random_walk_scaled".into(),
            "noise_adev_gyro".into(),
            "noise_adev_accel".into(),
        ]);
        f
    }
    fn report_args(&self, _report: &crate::args::ReportArgs) -> Args {
        Args {
            seeds: None,
            hours: Vec::new(),
            page: false,
        }
    }
    fn run(&self, ctx: &mut Ctx, args: &Args) {
        // Alone (the page of record), the default is the full size.
        let seeds = args.seeds.unwrap_or(if args.page {
            ctx.scale.pick(4, 16, 16)
        } else {
            ctx.scale.pick(4, 4, 16)
        });
        let mut hours = if args.hours.is_empty() {
            ctx.scale.pick(
                vec![2.0 / 60.0, 4.0 / 60.0, 8.0 / 60.0],
                vec![0.5, 1.0, 2.0, 4.0, 8.0],
                vec![0.5, 1.0, 2.0, 4.0, 8.0],
            )
        } else {
            args.hours.clone()
        };
        hours.sort_by(f64::total_cmp);
        hours.dedup();
        if args.page {
            ctx.page("noise.md");
        }
        let page = args.page;
        let ratios = ctx.scale.pick(
            vec![3.0, 10.0],
            vec![30.0, 100.0, 300.0, 1000.0],
            vec![30.0, 100.0, 300.0, 1000.0],
        );
        ctx.section("noise", |c| study(c, seeds, &hours, &ratios, page));
    }
}

// ---------------------------------------------------------------------------------------------------------
// The sensors.

const DEG: f64 = core::f64::consts::PI / 180.0;
/// Standard gravity (m/s²): a datasheet's g.
// The study's parameters: one named constant a line, alike in form only (values, not repeated logic).
const G0: f64 = 9.806_65;
/// The fit's shortest cluster, in sample periods.
const MIN_TAU_PERIODS: f64 = 16.0;
/// The generator's flicker band passes the longest record by this many octaves (its Allan variance is
/// within 1 % of the floor up to 2^(octaves − 7) periods).
const HEADROOM_OCTAVES: u32 = 7;
/// The long records' sample rate (Hz): the random walk shows at clusters of minutes to days, where a 1 Hz
/// sensor's Allan variance is a 100 Hz one's with the same densities (from 16 s on, where the fit starts).
const LONG_RATE_HZ: f64 = 1.0;
/// The interval whose coverage of the truth is counted: the fit's own `Term::interval(2.0)`.
const INTERVAL_SE: f64 = 2.0;
/// The claim: within 10 % of the truth.
const CLAIM: f64 = 0.10;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Gyro,
    Accel,
}

impl Kind {
    /// The datasheet units of N, B, K.
    fn units(self) -> [&'static str; 3] {
        match self {
            Kind::Gyro => ["°/√h", "°/h", "°/h/√h"],
            Kind::Accel => ["m/s/√h", "mg", "m/s²/√h"],
        }
    }

    /// Datasheet values to SI densities: rad/√s, rad/s, rad/s/√s (gyro); m/s/√s, m/s², m/s²/√s (accel).
    fn to_si(self, [n, b, k]: [f64; 3]) -> [f64; 3] {
        match self {
            Kind::Gyro => [n * DEG / 60.0, b * DEG / 3600.0, k * DEG / (3600.0 * 60.0)],
            Kind::Accel => [n / 60.0, b * 1e-3 * G0, k / 60.0],
        }
    }

    /// The Allan deviation's display unit (°/h, mg) per SI unit, and its name.
    fn display(self) -> (f64, &'static str) {
        match self {
            Kind::Gyro => (3600.0 / DEG, "°/h"),
            Kind::Accel => (1e3 / G0, "mg"),
        }
    }
}

/// A sensor class: datasheet-like densities and a sample rate.
#[derive(Clone, Copy, Debug)]
struct Class {
    name: &'static str,
    /// The key in the CSV files.
    key: &'static str,
    kind: Kind,
    rate_hz: f64,
    /// N, B, K in the kind's datasheet units.
    datasheet: [f64; 3],
    /// A constant offset per axis (SI): the turn-on bias, or gravity.
    offset: [f64; 3],
}

impl Class {
    fn truth(&self) -> [f64; 3] {
        self.kind.to_si(self.datasheet)
    }
    fn period(&self) -> f64 {
        1.0 / self.rate_hz
    }
}

/// Three gyroscope grades and an accelerometer, at 100 Hz (typical values of each grade, not one part's).
const CLASSES: [Class; 4] = [
    Class {
        name: "consumer MEMS gyro",
        key: "consumer",
        kind: Kind::Gyro,
        rate_hz: 100.0,
        datasheet: [0.3, 10.0, 30.0],
        offset: [0.5 * DEG, -0.3 * DEG, 0.2 * DEG],
    },
    Class {
        name: "industrial MEMS gyro",
        key: "industrial",
        kind: Kind::Gyro,
        rate_hz: 100.0,
        datasheet: [0.15, 2.0, 3.0],
        offset: [0.05 * DEG, 0.02 * DEG, -0.04 * DEG],
    },
    Class {
        name: "tactical gyro",
        key: "tactical",
        kind: Kind::Gyro,
        rate_hz: 100.0,
        datasheet: [0.03, 0.3, 0.3],
        offset: [1e-3 * DEG, -2e-3 * DEG, 5e-4 * DEG],
    },
    Class {
        name: "MEMS accelerometer",
        key: "accel",
        kind: Kind::Accel,
        rate_hz: 100.0,
        datasheet: [0.04, 0.05, 1e-3],
        offset: [0.05, -0.03, G0],
    },
];

/// The terms, in `NoiseFit`'s order.
struct TermInfo {
    key: &'static str,
    symbol: &'static str,
    what: &'static str,
}

const TERMS: [TermInfo; 3] = [
    TermInfo {
        key: "white",
        symbol: "N",
        what: "white noise N (angle / velocity random walk)",
    },
    TermInfo {
        key: "instability",
        symbol: "B",
        what: "bias instability B",
    },
    TermInfo {
        key: "random_walk",
        symbol: "K",
        what: "random walk K (rate / acceleration random walk)",
    },
];

/// Where the model's terms cross: white = flicker at `N² / (f B²)`, flicker = random walk at `3 f B² / K²`
/// (`f` the flicker floor `2 ln 2 / π`), in seconds.
fn crossovers([n, b, k]: [f64; 3]) -> (f64, f64) {
    let floor = FLICKER_FLOOR * b * b;
    (n * n / floor, 3.0 * floor / (k * k))
}

/// The model's Allan variance at τ.
fn model_avar([n, b, k]: [f64; 3], tau: f64) -> f64 {
    n * n / tau + FLICKER_FLOOR * b * b + k * k * tau / 3.0
}

// ---------------------------------------------------------------------------------------------------------
// The generator (tests/noise.rs's) and its exact expected Allan variance.

/// A 3-axis sensor at rest with the three noises, sampled every `period`.
pub struct Generator {
    /// The white noise's standard deviation per sample.
    white: f64,
    /// The random walk's step per sample.
    walk: f64,
    /// Each Gauss–Markov process's coefficient a = e^(−period/Tc) and innovation σ.
    a: Vec<f64>,
    s: Vec<f64>,
    /// Their states, per axis.
    state: [Vec<f64>; 3],
    /// Innovations of one axis's processes.
    innovations: Vec<f64>,
    bias: [f64; 3],
    rng: Gaussian,
}

impl Generator {
    /// Densities `[n, b, k]` (SI); the flicker band's correlation times run from `period` over `octaves`
    /// octaves. Each process starts in its stationary distribution.
    pub fn new(period: f64, [n, b, k]: [f64; 3], offset: [f64; 3], octaves: u32, seed: u64) -> Self {
        let sigma = markov_sigma(b);
        let a: Vec<f64> = (0..octaves).map(|i| (-1.0 / 2f64.powi(i as i32)).exp()).collect();
        let s = a.iter().map(|a| sigma * (1.0 - a * a).sqrt()).collect();
        let mut rng = Gaussian::new(seed);
        let state = [(); 3].map(|_| a.iter().map(|_| sigma * rng.next()).collect());
        Self {
            white: n / period.sqrt(),
            walk: k * period.sqrt(),
            innovations: vec![0.0; a.len()],
            a,
            s,
            state,
            bias: offset,
            rng,
        }
    }

    pub fn sample(&mut self) -> Vec3<f64> {
        let mut v = [0.0; 3];
        for (axis, out) in v.iter_mut().enumerate() {
            self.bias[axis] += self.walk * self.rng.next();
            for g in self.innovations.iter_mut() {
                *g = self.rng.next();
            }
            let mut flicker = 0.0;
            for (((x, a), s), g) in self.state[axis]
                .iter_mut()
                .zip(&self.a)
                .zip(&self.s)
                .zip(&self.innovations)
            {
                *x = a * *x + s * g;
                flicker += *x;
            }
            *out = self.bias[axis] + flicker + self.white * self.rng.next();
        }
        Vec3::new(v[0], v[1], v[2])
    }
}

/// Each Gauss–Markov process's standard deviation for a bias instability `b`: the one-sided spectrum of
/// processes a factor 2 apart in correlation time is about `σ² / (f ln 2)`, flicker's is `B² / (π f)`.
fn markov_sigma(b: f64) -> f64 {
    b * (core::f64::consts::LN_2 / core::f64::consts::PI).sqrt()
}

/// The generator's octaves for records up to `samples` long: the band passes the longest record's
/// clusters by [`HEADROOM_OCTAVES`].
fn octaves_for(samples: u64) -> u32 {
    (samples.max(2) as f64).log2().ceil() as u32 + HEADROOM_OCTAVES
}

/// The expected non-overlapping Allan variance, at `m` samples per cluster, of a unit-variance AR(1)
/// sequence `xₖ₊₁ = a xₖ + …` with `a = e^(−x)` (a Gauss–Markov process sampled `x` correlation times apart).
///
/// With the cluster weights `w = (−1 ×m, +1 ×m)`, `σ²(m) = Σᵢⱼ wᵢ wⱼ a^|i−j| / (2m²)`; the weights'
/// autocorrelation is `C(d) = 2m − 3d` for `d ≤ m` and `−(2m − d)` beyond, and `Σ C = 0`, so
/// `σ²(m) = Σ_{d=1}^{2m−1} C(d) (a^d − 1) / m²`: a sum of small terms (no cancellation of large ones). For
/// long clusters (over 4096 samples, and `x m ≥ 1e-3` or over 2^16 samples), the closed form
/// `[m (1 + a)/(1 − a) − (2a (1 − a^m) + a (1 − a^m)²)/(1 − a)²] / m²`, whose relative rounding is about
/// `1e-16 / (x m)²` of the result: below 1e-10 for `x m ≥ 1e-3`; past 2^16 samples, a process with
/// `x m < 1e-3` contributes less than a thousandth of its variance, and only that share is rounded so.
pub fn markov_avar(x: f64, m: u64) -> f64 {
    let mf = m as f64;
    if m <= 4096 || (x * mf < 1e-3 && m <= 1 << 16) {
        markov_avar_sum(x, m)
    } else {
        let a = (-x).exp();
        let one_minus_a = -(-x).exp_m1();
        let one_minus_am = -(-x * mf).exp_m1();
        (mf * (1.0 + a) / one_minus_a
            - (2.0 * a * one_minus_am + a * one_minus_am * one_minus_am)
                / (one_minus_a * one_minus_a))
            / (mf * mf)
    }
}

/// [`markov_avar`] as the sum over the lags, `Σ_{d=1}^{2m−1} C(d) (a^d − 1) / m²`.
fn markov_avar_sum(x: f64, m: u64) -> f64 {
    let mf = m as f64;
    let mut s = 0.0;
    for d in 1..2 * m {
        let c = if d <= m {
            2.0 * mf - 3.0 * d as f64
        } else {
            -(2.0 * mf - d as f64)
        };
        s += c * (-x * d as f64).exp_m1();
    }
    s / (mf * mf)
}

/// The generator's flicker band alone: its expected Allan variance over the floor `(2 ln 2/π) B²` at `m`
/// periods (independent of `B`).
pub fn flicker_over_floor(octaves: u32, m: u64) -> f64 {
    // σ² / (f B²) = (ln 2/π) / (2 ln 2/π) = ½.
    0.5 * (0..octaves)
        .map(|i| markov_avar(1.0 / 2f64.powi(i as i32), m))
        .sum::<f64>()
}

/// The generator's expected Allan variance at `m` periods: white `N²/τ` exactly, the flicker band, and the
/// sampled random walk `K² period (2m² + 1)/(6m)` (= `K² τ/3 + K² period² / (6τ)`).
fn generator_avar(truth: [f64; 3], period: f64, octaves: u32, m: u64) -> f64 {
    let [n, b, k] = truth;
    let mf = m as f64;
    n * n / (mf * period)
        + FLICKER_FLOOR * b * b * flicker_over_floor(octaves, m)
        + k * k * period * (2.0 * mf * mf + 1.0) / (6.0 * mf)
}

// ---------------------------------------------------------------------------------------------------------
// The information limit.

/// The smallest relative standard deviation an unbiased estimate of each density `N`, `B`, `K` can have
/// from `samples` samples of a 3-axis sensor at rest: the Cramér–Rao bound with Whittle's approximation of
/// the likelihood. The rate's two-sided spectrum is `S(f) = N² + B²/(2π f) + K²/(2π f)²` (IEEE Std 952's
/// terms, the ones whose Allan variances the fit's model sums), the periodogram's ordinates at the record's
/// frequencies `f_j = j / T`, `j = 1 … n/2`, independent and exponential with mean `S(f_j)`; so the Fisher
/// information of the log-coefficients `ln (N², B², K²)` is `3 Σ_j g gᵀ` over the three axes, with
/// `gᵢ = cᵢ ∂ᵢS / S` each term's share of the spectrum at `f_j`. A density's relative deviation is half its
/// coefficient's. Terms whose density is 0 are left out (known to be absent). The random walk is not
/// stationary; taking its spectrum at the record's own frequencies is the usual approximation, and the
/// fit's own scatter (the study's tables) can be compared with it.
fn information_limit(truth: [f64; 3], period: f64, samples: u64) -> [f64; 3] {
    let active: Vec<usize> = (0..3).filter(|&i| truth[i] > 0.0).collect();
    let record = samples as f64 * period;
    let two_pi_t = 2.0 * core::f64::consts::PI / record;
    let c = truth.map(|d| d * d);
    let mut info = vec![vec![0.0; active.len()]; active.len()];
    for j in 1..=samples / 2 {
        let w = two_pi_t * j as f64;
        let terms = [c[0], c[1] / w, c[2] / (w * w)];
        let s: f64 = terms.iter().sum();
        for (r, &a) in active.iter().enumerate() {
            for (q, &b) in active.iter().enumerate() {
                info[r][q] += 3.0 * terms[a] * terms[b] / (s * s);
            }
        }
    }
    let cov = inverse(info);
    let mut limit = [f64::NAN; 3];
    for (r, &a) in active.iter().enumerate() {
        limit[a] = 0.5 * cov[r][r].sqrt();
    }
    limit
}

/// The inverse of a small symmetric positive definite matrix (Gauss–Jordan; `NaN`s where it is singular).
fn inverse(mut a: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let n = a.len();
    let mut inv: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    for col in 0..n {
        let pivot = a[col][col];
        for j in 0..n {
            a[col][j] /= pivot;
            inv[col][j] /= pivot;
        }
        for row in (0..n).filter(|&r| r != col) {
            let f = a[row][col];
            for j in 0..n {
                a[row][j] -= f * a[col][j];
                inv[row][j] -= f * inv[col][j];
            }
        }
    }
    inv
}

// ---------------------------------------------------------------------------------------------------------
// One recording.

/// One fit: the terms (`None`: too few clusters to fit), the points and the misfit.
#[derive(Clone, Copy, Debug)]
struct Fit {
    terms: Option<[Term; 3]>,
    points: u32,
    misfit: f64,
}

fn fit_of(avar: &AllanVariance<f64, 32>, min_tau: f64) -> Fit {
    match NoiseFit::pooled_from(avar, min_tau) {
        Some(f) => Fit {
            terms: Some([f.white, f.instability, f.random_walk]),
            points: f.points,
            misfit: f.misfit,
        },
        None => Fit {
            terms: None,
            points: 0,
            misfit: f64::NAN,
        },
    }
}

/// The fits of one record: from 16 periods (the study's), and over every cluster (for comparison).
#[derive(Clone, Copy, Debug)]
struct Fits {
    from16: Fit,
    all: Fit,
}

/// One seed of one class: a recording as long as the longest record, fitted at each record length (its
/// first samples); and the clusters at the longest.
/// `experiment` tells the experiments' streams apart (0 for the study's records, 1 for the long ones).
fn record(
    class: &Class,
    experiment: u64,
    seed: u32,
    samples: &[u64],
) -> (Vec<Fits>, Vec<Cluster<f64>>) {
    let period = class.period();
    let longest = *samples.last().expect("a record length");
    let class_index = CLASSES.iter().position(|c| c.key == class.key).unwrap_or(0) as u64;
    let mut generator = Generator::new(
        period,
        class.truth(),
        class.offset,
        octaves_for(longest),
        0x5EED_0000_0000 ^ (experiment << 40) ^ (class_index << 32) ^ u64::from(seed),
    );
    let mut avar = AllanVariance::<f64, 32>::new(period).expect("a positive period");
    let mut fits = Vec::with_capacity(samples.len());
    let mut next = samples.iter().peekable();
    for k in 1..=longest {
        avar.push(generator.sample())
            .expect("finite samples near their first");
        while next.peek() == Some(&&k) {
            next.next();
            fits.push(Fits {
                from16: fit_of(&avar, MIN_TAU_PERIODS * period),
                all: fit_of(&avar, 0.0),
            });
        }
    }
    (fits, avar.clusters().collect())
}

// ---------------------------------------------------------------------------------------------------------
// The CSV files.

/// A sensor class and its generator.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct SensorRow {
    pub sensor: String,
    pub rate_hz: f64,
    /// N, B, K in the datasheet units of `units`.
    pub n: f64,
    pub b: f64,
    pub k: f64,
    pub units: String,
    /// N, B, K in SI (rad or m/s, s).
    pub n_si: f64,
    pub b_si: f64,
    pub k_si: f64,
    /// τ where the white and flicker terms' Allan variances are equal, and where flicker and random walk are
    /// (s).
    pub tau_white_flicker_s: f64,
    pub tau_flicker_walk_s: f64,
    /// The generator's flicker octaves.
    pub octaves: u32,
}

impl Csv for SensorRow {
    const FILE: &'static str = "noise_sensors.csv";
}

// Each table spells out its own line: its columns and their number formats are its own.
impl Table for SensorRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "sensor",
            "rate (Hz)",
            "N",
            "B",
            "K",
            "units",
            "τ where N = B (s)",
            "τ where B = K (s)",
            "flicker octaves",
        ]);
        for r in rows {
            t += &format!(
                "| {} | {} | {} | {} | {} | {} | {:.1} | {:.0} | {} |\n",
                r.sensor,
                r.rate_hz,
                r.n,
                r.b,
                r.k,
                r.units,
                r.tau_white_flicker_s,
                r.tau_flicker_walk_s,
                r.octaves
            );
        }
        t
    }
}

/// The generator against the model at short clusters.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct BandRow {
    pub sensor: String,
    /// τ in sample periods.
    pub tau_periods: u64,
    /// The flicker band's expected Allan variance over the floor `(2 ln 2/π) B²`.
    pub flicker_over_floor: f64,
    /// The generator's expected Allan variance against the model's, relative.
    pub departure: f64,
    /// That departure in standard errors of the pooled point at the longest record (`√(2 / (3 ·
    /// differences))` relative).
    pub departure_se: f64,
}

impl Csv for BandRow {
    const FILE: &'static str = "noise_band.csv";
}

impl Table for BandRow {
    fn render(rows: &[Self]) -> String {
        let sensors = table::distinct(rows, |r| r.sensor.as_str());
        let mut taus: Vec<u64> = rows.iter().map(|r| r.tau_periods).collect();
        taus.sort_unstable();
        taus.dedup();
        let mut cols = vec![
            "τ / period".to_string(),
            "flicker / floor (generator)".to_string(),
        ];
        cols.extend(
            sensors
                .iter()
                .map(|s| format!("{s}: generator / model − 1 (standard errors)")),
        );
        let refs: Vec<&str> = cols.iter().map(String::as_str).collect();
        let mut t = table::header(&refs);
        for tau in taus {
            let at: Vec<&BandRow> = rows.iter().filter(|r| r.tau_periods == tau).collect();
            t += &format!("| {tau} | {:.4} |", at[0].flicker_over_floor);
            for s in &sensors {
                t += &match at.iter().find(|r| r.sensor == *s) {
                    Some(r) => format!(
                        " {:+.3} % ({:+.1}) |",
                        100.0 * r.departure,
                        r.departure_se
                    ),
                    None => " – |".into(),
                };
            }
            t += "\n";
        }
        t
    }
}

/// One sensor at one record length, over the seeds: per term, the median and worst relative error of the
/// seeds that identified it (`NaN` when none did), how many identified it, and how many intervals of
/// ±2 standard errors held the truth.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct ErrorRow {
    pub sensor: String,
    pub hours: f64,
    pub seeds: u32,
    pub white_median: f64,
    pub white_worst: f64,
    pub white_identified: u32,
    pub white_covered: u32,
    pub instability_median: f64,
    pub instability_worst: f64,
    pub instability_identified: u32,
    pub instability_covered: u32,
    pub random_walk_median: f64,
    pub random_walk_worst: f64,
    pub random_walk_identified: u32,
    pub random_walk_covered: u32,
    /// Per term: the rms relative error over the seeds that identified it, and the information limit on
    /// the relative standard deviation at this length ([`information_limit`]).
    pub white_rms: f64,
    pub white_limit: f64,
    pub instability_rms: f64,
    pub instability_limit: f64,
    pub random_walk_rms: f64,
    pub random_walk_limit: f64,
}

/// One term over the seeds: the median, worst and rms |relative error| of the seeds that identified it
/// (`NaN` when none did), how many identified it, and how many ±2 se intervals held the truth.
#[derive(Clone, Copy, Debug)]
struct Summary {
    median: f64,
    worst: f64,
    rms: f64,
    identified: u32,
    covered: u32,
}

impl Summary {
    /// From each seed's (relative error, identified, covered).
    fn of(judged: impl Iterator<Item = (f64, bool, bool)>) -> Self {
        let judged: Vec<(f64, bool, bool)> = judged.collect();
        let mut errors: Vec<f64> = judged.iter().filter(|t| t.1).map(|t| t.0.abs()).collect();
        let worst = errors.iter().copied().fold(f64::NAN, f64::max);
        let rms = if errors.is_empty() {
            f64::NAN
        } else {
            (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt()
        };
        Self {
            median: median(&mut errors),
            worst,
            rms,
            identified: errors.len() as u32,
            covered: judged.iter().filter(|t| t.2).count() as u32,
        }
    }
}

impl ErrorRow {
    /// Per term: the information limit.
    fn limits(&self) -> [f64; 3] {
        [
            self.white_limit,
            self.instability_limit,
            self.random_walk_limit,
        ]
    }

    /// Per term: (median, worst, identified, covered).
    fn terms(&self) -> [(f64, f64, u32, u32); 3] {
        [
            (
                self.white_median,
                self.white_worst,
                self.white_identified,
                self.white_covered,
            ),
            (
                self.instability_median,
                self.instability_worst,
                self.instability_identified,
                self.instability_covered,
            ),
            (
                self.random_walk_median,
                self.random_walk_worst,
                self.random_walk_identified,
                self.random_walk_covered,
            ),
        ]
    }
}

impl Csv for ErrorRow {
    const FILE: &'static str = "noise_errors.csv";
}

/// A record length: minutes below an hour.
fn length(hours: f64) -> String {
    if hours < 1.0 {
        format!("{} min", (hours * 60.0 * 100.0).round() / 100.0)
    } else if hours == hours.round() {
        format!("{hours} h")
    } else {
        format!("{hours:.1} h")
    }
}

/// A percentage with two significant figures below 1 % (the information limits of the white noise).
fn pct_fine(v: f64) -> String {
    if v.is_finite() && v < 0.01 {
        format!("{:.2}", 100.0 * v)
    } else {
        pct(v)
    }
}

fn pct(v: f64) -> String {
    if v.is_nan() {
        "–".into()
    } else {
        format!("{:.1}", 100.0 * v)
    }
}

impl Table for ErrorRow {
    /// One table per sensor.
    fn render(rows: &[Self]) -> String {
        let mut t = String::new();
        let sensors = table::distinct(rows, |r| r.sensor.as_str());
        for (i, s) in sensors.iter().enumerate() {
            if i > 0 {
                t += "\n";
            }
            let of: Vec<&ErrorRow> = rows.iter().filter(|r| r.sensor == *s).collect();
            t += &format!(
                "**{s}** ({} seeds; |relative error| in % over the seeds that identified the term; the \
                 information limit: the smallest relative standard deviation any unbiased estimate can \
                 have from a record this long; identified / truth inside the fit's ±2 se)\n\n",
                of[0].seeds
            );
            let mut cols = vec!["record".to_string()];
            for term in &TERMS {
                let s = term.symbol;
                cols.extend([
                    format!("{s} median"),
                    format!("{s} worst"),
                    format!("{s} limit (1σ)"),
                    format!("{s} id. / in ±2 se"),
                ]);
            }
            let refs: Vec<&str> = cols.iter().map(String::as_str).collect();
            t += &table::header(&refs);
            for r in of {
                t += &format!("| {} |", length(r.hours));
                for ((median, worst, id, cov), limit) in r.terms().into_iter().zip(r.limits()) {
                    t += &format!(
                        " {} | {} | {} | {id} / {cov} |",
                        pct(median),
                        pct(worst),
                        pct_fine(limit)
                    );
                }
                t += "\n";
            }
        }
        t
    }
}

/// A long record (the random walk's experiment), over the seeds: B's and K's median and worst |relative
/// error| over the seeds that identified them, K's rms error, its information limit (1σ) and how many ±2 se
/// intervals held the truth.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct LongRow {
    pub sensor: String,
    pub rate_hz: f64,
    /// The record over τ(B = K).
    pub ratio: f64,
    pub hours: f64,
    pub seeds: u32,
    pub instability_median: f64,
    pub instability_worst: f64,
    pub instability_identified: u32,
    pub random_walk_median: f64,
    pub random_walk_worst: f64,
    pub random_walk_rms: f64,
    pub random_walk_identified: u32,
    pub random_walk_covered: u32,
    pub random_walk_limit: f64,
}

impl LongRow {
    /// Every seed identified K within the 10 %.
    fn k_within_claim(&self) -> bool {
        self.random_walk_identified == self.seeds && self.random_walk_worst <= CLAIM
    }
}

impl Csv for LongRow {
    const FILE: &'static str = "noise_long.csv";
}

impl Table for LongRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "sensor",
            "record / τ(B = K)",
            "record",
            "B median / worst (%)",
            "K median / worst (%)",
            "K rms (%)",
            "K limit (1σ, %)",
            "K identified / in ±2 se",
        ]);
        for r in rows {
            t += &format!(
                "| {} | {} | {} | {} / {} | {} / {} | {} | {} | {} / {} of {} |\n",
                r.sensor,
                r.ratio,
                length(r.hours),
                pct(r.instability_median),
                pct(r.instability_worst),
                pct(r.random_walk_median),
                pct(r.random_walk_worst),
                pct(r.random_walk_rms),
                pct(r.random_walk_limit),
                r.random_walk_identified,
                r.random_walk_covered,
                r.seeds
            );
        }
        t
    }
}

/// Every fit (data).
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct FitRow {
    pub sensor: String,
    pub seed: u32,
    pub hours: f64,
    pub points: u32,
    pub misfit: f64,
    /// Per term: the fitted density (SI), its relative error, the coefficient's standard error relative to
    /// the coefficient, whether identified, whether the ±2 se interval holds the truth.
    pub white: f64,
    pub white_error: f64,
    pub white_se: f64,
    pub white_identified: bool,
    pub white_covered: bool,
    pub instability: f64,
    pub instability_error: f64,
    pub instability_se: f64,
    pub instability_identified: bool,
    pub instability_covered: bool,
    pub random_walk: f64,
    pub random_walk_error: f64,
    pub random_walk_se: f64,
    pub random_walk_identified: bool,
    pub random_walk_covered: bool,
    /// The fit over every cluster (τ ≥ 1 period): each term's relative error and whether identified.
    pub white_error_all: f64,
    pub white_identified_all: bool,
    pub instability_error_all: f64,
    pub instability_identified_all: bool,
    pub random_walk_error_all: f64,
    pub random_walk_identified_all: bool,
}

impl Csv for FitRow {
    const FILE: &'static str = "noise_fits.csv";
}

/// At the longest record, each term fitted from 16 periods (the study's) and over every cluster: median
/// and worst |relative error| over the seeds that identified it, and how many did.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct MinTauRow {
    pub sensor: String,
    pub term: String,
    pub hours: f64,
    pub seeds: u32,
    pub from16_median: f64,
    pub from16_worst: f64,
    pub from16_identified: u32,
    pub all_median: f64,
    pub all_worst: f64,
    pub all_identified: u32,
}

impl Csv for MinTauRow {
    const FILE: &'static str = "noise_min_tau.csv";
}

// Each table spells out its own line: its columns and their number formats are its own.
impl Table for MinTauRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "sensor",
            "term",
            "τ ≥ 16 periods: median / worst (%)",
            "identified",
            "every τ: median / worst (%)",
            "identified",
        ]);
        for r in rows {
            t += &format!(
                "| {} | {} | {} / {} | {} / {} | {} / {} | {} / {} |\n",
                r.sensor,
                r.term,
                pct(r.from16_median),
                pct(r.from16_worst),
                r.from16_identified,
                r.seeds,
                pct(r.all_median),
                pct(r.all_worst),
                r.all_identified,
                r.seeds
            );
        }
        t
    }
}

/// One seed's Allan deviation at the longest record (data; the figures): measured (the axes pooled), the
/// fit, the model at the truth and the generator's expected value, in the sensor's display unit.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct AdevRow {
    pub sensor: String,
    pub unit: String,
    pub tau_s: f64,
    pub differences: u32,
    pub fitted_range: bool,
    pub measured: f64,
    pub fit: f64,
    pub truth: f64,
    pub generator: f64,
}

impl Csv for AdevRow {
    const FILE: &'static str = "noise_adev.csv";
}

// ---------------------------------------------------------------------------------------------------------
// The study.

/// One term of one fit: (relative error, identified, covered); `None` for no fit.
fn judge(term: Option<&Term>, truth: f64) -> (f64, bool, bool) {
    match term {
        Some(t) => {
            let (lo, hi) = t.interval(INTERVAL_SE);
            (
                t.value() / truth - 1.0,
                t.is_identified(),
                lo <= truth && truth <= hi,
            )
        }
        None => (f64::NAN, false, false),
    }
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Writes a table's CSV and returns it (in the report), or renders it directly (on a page of its own).
fn shown<R: Table>(ctx: &mut Ctx, rows: &[R], page: bool) -> String {
    if page {
        format!("{}\n", R::render(rows))
    } else {
        ctx.table(rows)
    }
}

fn study(ctx: &mut Ctx, seeds: u32, hours: &[f64], ratios: &[f64], page: bool) -> String {
    let bar = ctx.progress();
    let samples_of = |c: &Class| -> Vec<u64> {
        hours
            .iter()
            .map(|h| ((h * 3600.0 * c.rate_hz).round() as u64).max(2))
            .collect()
    };
    // Every (class, seed) recording, in parallel; each is seeded, so the result does not depend on the
    // threads.
    let jobs: Vec<(usize, u32)> = (0..CLASSES.len())
        .flat_map(|c| (0..seeds).map(move |s| (c, s)))
        .collect();
    let results: Vec<(Vec<Fits>, Vec<Cluster<f64>>)> = jobs
        .par_iter()
        .map(|&(c, s)| {
            let r = record(&CLASSES[c], 0, s, &samples_of(&CLASSES[c]));
            bar.inc(1);
            r
        })
        .collect();

    // The random walk's long records: each sensor at 1 Hz, records `ratios` × τ(B = K) long.
    let long_class = |c: &Class| Class {
        rate_hz: LONG_RATE_HZ,
        ..*c
    };
    let long_samples = |c: &Class| -> Vec<u64> {
        let tau = crossovers(c.truth()).1;
        ratios
            .iter()
            .map(|r| ((r * tau * c.rate_hz).round() as u64).max(2))
            .collect()
    };
    let long_results: Vec<Vec<Fits>> = jobs
        .par_iter()
        .map(|&(c, s)| {
            let class = long_class(&CLASSES[c]);
            let r = record(&class, 1, s, &long_samples(&class)).0;
            bar.inc(1);
            r
        })
        .collect();
    let mut long_rows = Vec::new();
    for (c, class) in CLASSES.iter().enumerate() {
        let class = long_class(class);
        let truth = class.truth();
        let samples = long_samples(&class);
        for (i, (&ratio, &n)) in ratios.iter().zip(&samples).enumerate() {
            let of = jobs
                .iter()
                .zip(&long_results)
                .filter(|((jc, _), _)| *jc == c)
                .map(|(_, fits)| fits[i].from16);
            let judged: Vec<[(f64, bool, bool); 3]> = of
                .map(|f| [0, 1, 2].map(|t| judge(f.terms.as_ref().map(|x| &x[t]), truth[t])))
                .collect();
            let [_, b, k] = [0, 1, 2].map(|t| Summary::of(judged.iter().map(|j| j[t])));
            let limit = information_limit(truth, class.period(), n);
            long_rows.push(LongRow {
                sensor: class.name.into(),
                rate_hz: class.rate_hz,
                ratio,
                hours: n as f64 * class.period() / 3600.0,
                seeds,
                instability_median: b.median,
                instability_worst: b.worst,
                instability_identified: b.identified,
                random_walk_median: k.median,
                random_walk_worst: k.worst,
                random_walk_rms: k.rms,
                random_walk_identified: k.identified,
                random_walk_covered: k.covered,
                random_walk_limit: limit[2],
            });
        }
    }

    // Every fit, judged.
    let mut fit_rows = Vec::new();
    for (&(c, seed), (fits, _)) in jobs.iter().zip(&results) {
        let class = &CLASSES[c];
        let truth = class.truth();
        for (&h, both) in hours.iter().zip(fits) {
            let fit = &both.from16;
            let j: Vec<(f64, bool, bool)> = (0..3)
                .map(|i| judge(fit.terms.as_ref().map(|t| &t[i]), truth[i]))
                .collect();
            let all: Vec<(f64, bool, bool)> = (0..3)
                .map(|i| judge(both.all.terms.as_ref().map(|t| &t[i]), truth[i]))
                .collect();
            let value = |i: usize| fit.terms.map_or(f64::NAN, |t| t[i].value());
            let se = |i: usize| {
                fit.terms
                    .map_or(f64::NAN, |t| t[i].std_error / t[i].coefficient)
            };
            fit_rows.push(FitRow {
                sensor: class.key.into(),
                seed,
                hours: h,
                points: fit.points,
                misfit: fit.misfit,
                white: value(0),
                white_error: j[0].0,
                white_se: se(0),
                white_identified: j[0].1,
                white_covered: j[0].2,
                instability: value(1),
                instability_error: j[1].0,
                instability_se: se(1),
                instability_identified: j[1].1,
                instability_covered: j[1].2,
                random_walk: value(2),
                random_walk_error: j[2].0,
                random_walk_se: se(2),
                random_walk_identified: j[2].1,
                random_walk_covered: j[2].2,
                white_error_all: all[0].0,
                white_identified_all: all[0].1,
                instability_error_all: all[1].0,
                instability_identified_all: all[1].1,
                random_walk_error_all: all[2].0,
                random_walk_identified_all: all[2].1,
            });
        }
    }
    let term_of = |r: &FitRow, i: usize| match i {
        0 => (r.white_error, r.white_identified, r.white_covered),
        1 => (
            r.instability_error,
            r.instability_identified,
            r.instability_covered,
        ),
        _ => (
            r.random_walk_error,
            r.random_walk_identified,
            r.random_walk_covered,
        ),
    };

    // Per class and length, over the seeds.
    let mut error_rows = Vec::new();
    for class in &CLASSES {
        for &h in hours {
            let of: Vec<&FitRow> = fit_rows
                .iter()
                .filter(|r| r.sensor == class.key && r.hours == h)
                .collect();
            let [w, b, k] = [0, 1, 2].map(|i| Summary::of(of.iter().map(|r| term_of(r, i))));
            let limit = information_limit(
                class.truth(),
                class.period(),
                samples_of(class)[hours.iter().position(|&x| x == h).unwrap_or(0)],
            );
            error_rows.push(ErrorRow {
                sensor: class.name.into(),
                hours: h,
                seeds,
                white_median: w.median,
                white_worst: w.worst,
                white_identified: w.identified,
                white_covered: w.covered,
                white_rms: w.rms,
                white_limit: limit[0],
                instability_median: b.median,
                instability_worst: b.worst,
                instability_identified: b.identified,
                instability_covered: b.covered,
                instability_rms: b.rms,
                instability_limit: limit[1],
                random_walk_median: k.median,
                random_walk_worst: k.worst,
                random_walk_identified: k.identified,
                random_walk_covered: k.covered,
                random_walk_rms: k.rms,
                random_walk_limit: limit[2],
            });
        }
    }

    // The shortest clusters: the study's fit against the fit over every cluster, at the longest record.
    let longest = hours.last().copied().unwrap_or(1.0);
    let all_of = |r: &FitRow, i: usize| match i {
        0 => (r.white_error_all, r.white_identified_all),
        1 => (r.instability_error_all, r.instability_identified_all),
        _ => (r.random_walk_error_all, r.random_walk_identified_all),
    };
    let mut min_tau_rows = Vec::new();
    for class in &CLASSES {
        let of: Vec<&FitRow> = fit_rows
            .iter()
            .filter(|r| r.sensor == class.key && r.hours == longest)
            .collect();
        for (i, term) in TERMS.iter().enumerate() {
            let summary = |errors: Vec<(f64, bool)>| {
                let mut e: Vec<f64> = errors
                    .into_iter()
                    .filter(|t| t.1)
                    .map(|t| t.0.abs())
                    .collect();
                let worst = e.iter().copied().fold(f64::NAN, f64::max);
                let n = e.len() as u32;
                (median(&mut e), worst, n)
            };
            let a = summary(of.iter().map(|r| (term_of(r, i).0, term_of(r, i).1)).collect());
            let b = summary(of.iter().map(|r| all_of(r, i)).collect());
            min_tau_rows.push(MinTauRow {
                sensor: class.name.into(),
                term: term.symbol.into(),
                hours: longest,
                seeds,
                from16_median: a.0,
                from16_worst: a.1,
                from16_identified: a.2,
                all_median: b.0,
                all_worst: b.1,
                all_identified: b.2,
            });
        }
    }

    // The sensors, and the generator against the model at the short clusters.
    let sensor_rows: Vec<SensorRow> = CLASSES
        .iter()
        .map(|c| {
            let si = c.truth();
            let (twb, tbk) = crossovers(si);
            SensorRow {
                sensor: c.name.into(),
                rate_hz: c.rate_hz,
                n: c.datasheet[0],
                b: c.datasheet[1],
                k: c.datasheet[2],
                units: c.kind.units().join(", "),
                n_si: si[0],
                b_si: si[1],
                k_si: si[2],
                tau_white_flicker_s: twb,
                tau_flicker_walk_s: tbk,
                octaves: octaves_for(*samples_of(c).last().unwrap_or(&2)),
            }
        })
        .collect();
    let mut band_rows = Vec::new();
    for (c, s) in CLASSES.iter().zip(&sensor_rows) {
        let n_samples = *samples_of(c).last().unwrap_or(&2);
        for k in 0..=10 {
            let m = 1_u64 << k;
            let generator = generator_avar(c.truth(), c.period(), s.octaves, m);
            let model = model_avar(c.truth(), m as f64 * c.period());
            let differences = (n_samples / m).saturating_sub(1).max(1) as f64;
            let departure = generator / model - 1.0;
            band_rows.push(BandRow {
                sensor: c.key.into(),
                tau_periods: m,
                flicker_over_floor: flicker_over_floor(s.octaves, m),
                departure,
                departure_se: departure / (2.0 / (3.0 * differences)).sqrt(),
            });
        }
    }

    // Seed 0's curves at the longest record.
    let mut adev_rows = Vec::new();
    for (&(c, seed), (fits, clusters)) in jobs.iter().zip(&results) {
        if seed != 0 {
            continue;
        }
        let class = &CLASSES[c];
        let (scale, unit) = class.kind.display();
        let truth = class.truth();
        let octaves = sensor_rows[c].octaves;
        let fit = fits.last().and_then(|f| f.from16.terms);
        for cl in clusters {
            let measured = (cl.variance.x + cl.variance.y + cl.variance.z) / 3.0;
            let fitted = fit.map_or(f64::NAN, |t| {
                model_avar([t[0].value(), t[1].value(), t[2].value()], cl.tau)
            });
            adev_rows.push(AdevRow {
                sensor: class.key.into(),
                unit: unit.into(),
                tau_s: cl.tau,
                differences: cl.differences,
                fitted_range: cl.tau >= MIN_TAU_PERIODS * class.period(),
                measured: scale * measured.sqrt(),
                fit: scale * fitted.sqrt(),
                truth: scale * model_avar(truth, cl.tau).sqrt(),
                generator: scale
                    * generator_avar(truth, class.period(), octaves, u64::from(cl.samples)).sqrt(),
            });
        }
    }

    // The tables (CSV in the report).
    let sensors_table = shown(ctx, &sensor_rows, page);
    let band_table = shown(ctx, &band_rows, page);
    let error_table = shown(ctx, &error_rows, page);
    let min_tau_table = shown(ctx, &min_tau_rows, page);
    let long_table = shown(ctx, &long_rows, page);
    if !page {
        ctx.rows(&fit_rows);
        ctx.rows(&adev_rows);
    }

    // The figures: each term's error against the record length; one seed's Allan deviation.
    for (i, term) in TERMS.iter().enumerate() {
        let mut series = Vec::new();
        for (c, class) in CLASSES.iter().enumerate() {
            let of: Vec<&ErrorRow> = error_rows
                .iter()
                .filter(|r| r.sensor == class.name)
                .collect();
            let med: Vec<(f64, f64)> = of.iter().map(|r| (r.hours, r.terms()[i].0)).collect();
            let worst: Vec<(f64, f64)> = of.iter().map(|r| (r.hours, r.terms()[i].1)).collect();
            series.push(Series::both(format!("{}: median", class.name), med).colour(c));
            series.push(
                Series::both(format!("{}: worst", class.name), worst)
                    .dashed()
                    .colour(c),
            );
        }
        series.push(
            Series::line(
                "10 % (the issue's claim)",
                vec![(hours[0], CLAIM), (longest, CLAIM)],
            )
            .dashed()
            .colour(10),
        );
        let title = format!(
            "{}: |relative error| of the fit ({seeds} seeds, identified ones)",
            term.what
        );
        ctx.plot(|dir| {
            plot(
                dir,
                &format!("noise_{}", term.key),
                &title,
                Axis {
                    label: "record length (h)",
                    log: true,
                },
                Axis {
                    label: "|fitted / true − 1|",
                    log: true,
                },
                &series,
            )
        });
    }
    {
        let mut series = Vec::new();
        for (c, class) in CLASSES.iter().enumerate() {
            let tau = crossovers(class.truth()).1;
            // (record / τ(B = K), rms, worst, limit): the 100 Hz records and the long ones.
            let mut points: Vec<(f64, f64, f64, f64)> = error_rows
                .iter()
                .filter(|r| r.sensor == class.name)
                .map(|r| {
                    let ratio = r.hours * 3600.0 / tau;
                    (ratio, r.random_walk_rms, r.random_walk_worst, r.random_walk_limit)
                })
                .chain(long_rows.iter().filter(|r| r.sensor == class.name).map(|r| {
                    (
                        r.ratio,
                        r.random_walk_rms,
                        r.random_walk_worst,
                        r.random_walk_limit,
                    )
                }))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let at = |f: fn(&(f64, f64, f64, f64)) -> f64| -> Vec<(f64, f64)> {
                points.iter().map(|p| (p.0, f(p))).collect()
            };
            series.push(Series::both(format!("{}: rms", class.name), at(|p| p.1)).colour(c));
            series.push(
                Series::both(format!("{}: worst", class.name), at(|p| p.2))
                    .dashed()
                    .colour(c),
            );
            series.push(
                Series::markers(
                    format!("{}: information limit (1σ)", class.name),
                    at(|p| p.3),
                )
                .colour(c),
            );
        }
        let span: Vec<f64> = series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0))
            .collect();
        let (lo, hi) = span
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(a, b), &x| (a.min(x), b.max(x)));
        series.push(
            Series::line("10 % (the issue's claim)", vec![(lo, CLAIM), (hi, CLAIM)])
                .dashed()
                .colour(10),
        );
        let title = format!(
            "K: |relative error| against record / τ(B = K) ({seeds} seeds; to {} at 100 Hz, then 1 Hz)",
            length(longest)
        );
        ctx.plot(|dir| {
            plot(
                dir,
                "noise_random_walk_scaled",
                &title,
                Axis {
                    label: "record length / τ(B = K)",
                    log: true,
                },
                Axis {
                    label: "|fitted / true − 1|",
                    log: true,
                },
                &series,
            )
        });
    }
    for (kind, name, label) in [
        (Kind::Gyro, "noise_adev_gyro", "Allan deviation (°/h)"),
        (Kind::Accel, "noise_adev_accel", "Allan deviation (mg)"),
    ] {
        let mut series = Vec::new();
        for (c, class) in CLASSES.iter().enumerate().filter(|(_, c)| c.kind == kind) {
            let of: Vec<&AdevRow> = adev_rows.iter().filter(|r| r.sensor == class.key).collect();
            series.push(
                Series::markers(
                    format!("{}: measured (seed 0)", class.name),
                    of.iter().map(|r| (r.tau_s, r.measured)).collect(),
                )
                .colour(c),
            );
            series.push(
                Series::line(
                    format!("{}: fit (τ ≥ 16 periods)", class.name),
                    of.iter()
                        .filter(|r| r.fitted_range)
                        .map(|r| (r.tau_s, r.fit))
                        .collect(),
                )
                .colour(c),
            );
            series.push(
                Series::line(
                    format!("{}: truth (model)", class.name),
                    of.iter().map(|r| (r.tau_s, r.truth)).collect(),
                )
                .dashed()
                .colour(c),
            );
        }
        let title = format!(
            "Allan deviation of one {} recording at rest, its fit and the truth",
            length(longest)
        );
        ctx.plot(|dir| {
            plot(
                dir,
                name,
                &title,
                Axis {
                    label: "cluster time τ (s)",
                    log: true,
                },
                Axis { label, log: true },
                &series,
            )
        });
    }

    markdown(&Page {
        seeds,
        hours,
        page,
        sensors: &sensor_rows,
        band: &band_rows,
        errors: &error_rows,
        min_tau: &min_tau_rows,
        fits: &fit_rows,
        sensors_table: &sensors_table,
        band_table: &band_table,
        error_table: &error_table,
        min_tau_table: &min_tau_table,
        long: &long_rows,
        long_table: &long_table,
        slopes: &slopes(&error_rows),
    })
}

/// Per class and term, the slope of the median error against the record length (log-log).
fn slopes(rows: &[ErrorRow]) -> Vec<[f64; 3]> {
    CLASSES
        .iter()
        .map(|c| {
            let of: Vec<&ErrorRow> = rows.iter().filter(|r| r.sensor == c.name).collect();
            let s = |i: usize| {
                log_slope(
                    &of.iter()
                        .map(|r| (r.hours, r.terms()[i].0))
                        .collect::<Vec<_>>(),
                )
            };
            [s(0), s(1), s(2)]
        })
        .collect()
}

struct Page<'a> {
    seeds: u32,
    hours: &'a [f64],
    page: bool,
    sensors: &'a [SensorRow],
    band: &'a [BandRow],
    errors: &'a [ErrorRow],
    min_tau: &'a [MinTauRow],
    fits: &'a [FitRow],
    sensors_table: &'a str,
    band_table: &'a str,
    error_table: &'a str,
    min_tau_table: &'a str,
    long: &'a [LongRow],
    long_table: &'a str,
    slopes: &'a [[f64; 3]],
}

fn markdown(p: &Page) -> String {
    let h1 = if p.page { "#" } else { "###" };
    let h2 = if p.page { "##" } else { "####" };
    let longest = p.hours.last().copied().unwrap_or(f64::NAN);
    let lengths: Vec<String> = p.hours.iter().map(|&h| length(h)).collect();
    let band0: Vec<&BandRow> = p
        .band
        .iter()
        .filter(|r| r.sensor == CLASSES[0].key)
        .collect();
    let at = |m: u64| {
        band0
            .iter()
            .find(|r| r.tau_periods == m)
            .map_or(f64::NAN, |r| r.flicker_over_floor)
    };
    let within_1pct = band0
        .iter()
        .find(|r| (r.flicker_over_floor - 1.0).abs() < 0.01)
        .map_or(0, |r| r.tau_periods);
    let octaves = p.sensors.first().map_or(0, |s| s.octaves);
    let top = 1_u64 << octaves.saturating_sub(HEADROOM_OCTAVES);
    let top_ratio = flicker_over_floor(octaves, top);
    let short_se = |m_max: u64| {
        p.band
            .iter()
            .filter(|r| r.tau_periods <= m_max)
            .map(|r| r.departure_se.abs())
            .fold(0.0, f64::max)
    };
    let fitted_se = p
        .band
        .iter()
        .filter(|r| r.tau_periods as f64 >= MIN_TAU_PERIODS)
        .map(|r| r.departure_se.abs())
        .fold(0.0, f64::max);

    // The claim, at the longest record.
    let last: Vec<&ErrorRow> = p.errors.iter().filter(|r| r.hours == longest).collect();
    let mut claims = Vec::new();
    let mut all_hold = true;
    for r in &last {
        let t = r.terms();
        let parts: Vec<String> = TERMS
            .iter()
            .zip(t)
            .map(|(term, (_, worst, id, _))| {
                if id == 0 {
                    format!("{} not identified by any seed", term.symbol)
                } else {
                    format!(
                        "{} worst {} % ({id}/{} identified)",
                        term.symbol,
                        pct(worst),
                        r.seeds
                    )
                }
            })
            .collect();
        let holds = t.iter().all(|(_, worst, id, _)| *id == 0 || *worst <= CLAIM);
        all_hold &= holds;
        claims.push(format!(
            "- {}: {}: {}.",
            r.sensor,
            if holds {
                "**every identified term within 10 %**"
            } else {
                "**not every identified term within 10 %**"
            },
            parts.join(", ")
        ));
    }
    // Where each term first comes within 10 % for every seed (identified by all of them).
    let mut first_within = Vec::new();
    for c in &CLASSES {
        let of: Vec<&ErrorRow> = p.errors.iter().filter(|r| r.sensor == c.name).collect();
        let parts: Vec<String> = TERMS
            .iter()
            .enumerate()
            .map(|(i, term)| {
                let first = of.iter().position(|r| {
                    let (_, worst, id, _) = r.terms()[i];
                    id == r.seeds && worst <= CLAIM
                });
                // Holds from there to the longest record.
                let from = first.filter(|&f| {
                    of[f..].iter().all(|r| {
                        let (_, worst, id, _) = r.terms()[i];
                        id == r.seeds && worst <= CLAIM
                    })
                });
                match from {
                    Some(f) => format!("{} from {}", term.symbol, length(of[f].hours)),
                    None => format!("{} not by {}", term.symbol, length(longest)),
                }
            })
            .collect();
        first_within.push(format!("{}: {}", c.name, parts.join(", ")));
    }
    // Coverage of the ±2 se intervals at the longest record, per term over the sensors.
    let coverage: Vec<String> = TERMS
        .iter()
        .enumerate()
        .map(|(i, term)| {
            let (cov, n): (u32, u32) = last
                .iter()
                .map(|r| (r.terms()[i].3, r.seeds))
                .fold((0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
            format!(
                "{} {cov}/{n} ({:.0} %)",
                term.symbol,
                100.0 * f64::from(cov) / f64::from(n.max(1))
            )
        })
        .collect();
    // Over every length: the coverage, and the terms whose coverage is below 95 % by more than 3 binomial
    // standard errors of the count.
    let mut short = Vec::new();
    let coverage_all: Vec<String> = TERMS
        .iter()
        .enumerate()
        .map(|(i, term)| {
            let (cov, n): (u32, u32) = p
                .errors
                .iter()
                .map(|r| (r.terms()[i].3, r.seeds))
                .fold((0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
            let n = f64::from(n.max(1));
            let c = f64::from(cov) / n;
            if c < 0.95 - 3.0 * (0.95 * 0.05 / n).sqrt() {
                short.push(term.symbol);
            }
            format!("{} {:.0} % of {n}", term.symbol, 100.0 * c)
        })
        .collect();
    let short = if short.is_empty() {
        "No term's coverage is below 95 % by more than 3 binomial standard errors of its count.".to_string()
    } else {
        format!(
            "Below 95 % by more than 3 binomial standard errors of the count: {} (the fit's standard errors \
             are smaller than its scatter there).",
            short.join(", ")
        )
    };
    let slopes: Vec<String> = CLASSES
        .iter()
        .zip(p.slopes)
        .map(|(c, s)| {
            let f = |v: f64| {
                if v.is_nan() {
                    "–".to_string()
                } else {
                    format!("{v:+.2}")
                }
            };
            format!(
                "{}: N {}, B {}, K {}",
                c.name,
                f(s[0]),
                f(s[1]),
                f(s[2])
            )
        })
        .collect();
    let misfit = {
        let mut m: Vec<f64> = p
            .fits
            .iter()
            .filter(|r| r.hours == longest)
            .map(|r| r.misfit)
            .filter(|v| v.is_finite())
            .collect();
        median(&mut m)
    };
    // K at the longest 100 Hz record: its information limit, and the fit's rms error over it.
    let k_limit: Vec<String> = last
        .iter()
        .map(|r| {
            if r.random_walk_identified == 0 {
                return format!(
                    "{} {} % (no seed identified K)",
                    r.sensor,
                    pct(r.random_walk_limit)
                );
            }
            format!(
                "{} {} % (the fit's rms error {} %, {:.2} × the limit, over the {} of {} seeds that \
                 identified K)",
                r.sensor,
                pct(r.random_walk_limit),
                pct(r.random_walk_rms),
                r.random_walk_rms / r.random_walk_limit,
                r.random_walk_identified,
                r.seeds
            )
        })
        .collect();
    // The long records: from which length on every seed identified K within 10 %.
    let long_from: Vec<String> = CLASSES
        .iter()
        .map(|c| {
            let of: Vec<&LongRow> = p.long.iter().filter(|r| r.sensor == c.name).collect();
            let from = (0..of.len()).find(|&i| of[i..].iter().all(|r| r.k_within_claim()));
            match from {
                Some(i) => format!(
                    "{}: from {} τ(B = K) ({}; K limit {} %)",
                    c.name,
                    of[i].ratio,
                    length(of[i].hours),
                    pct(of[i].random_walk_limit)
                ),
                None => format!(
                    "{}: not by {} τ(B = K)",
                    c.name,
                    of.last().map_or(f64::NAN, |r| r.ratio)
                ),
            }
        })
        .collect();
    let long_all = CLASSES.iter().all(|c| {
        p.long
            .iter()
            .rfind(|r| r.sensor == c.name)
            .is_some_and(LongRow::k_within_claim)
    });
    let long_verdict = if long_all {
        "**Every sensor's K is within 10 % of the truth on every seed at the longest of these records.**"
    } else {
        "**Not every sensor's K is within 10 % on every seed at the longest of these records.**"
    };
    // The fit over every cluster against the study's: per term, on how many sensors its median error is
    // lower (of those where both fits identified the term).
    let lower: Vec<String> = TERMS
        .iter()
        .map(|term| {
            let both: Vec<&MinTauRow> = p
                .min_tau
                .iter()
                .filter(|r| r.term == term.symbol)
                .filter(|r| r.from16_median.is_finite() && r.all_median.is_finite())
                .collect();
            let lower = both
                .iter()
                .filter(|r| r.all_median < r.from16_median)
                .count();
            format!("{} on {lower} of {}", term.symbol, both.len())
        })
        .collect();
    let lengths_note = if p.hours.len() > 1 {
        format!(
            "Each seed is one recording of {}, and its shorter records are its first {} (a longer record is \
             the same recording continued, as at a bench), so a seed's rows are not independent across \
             lengths.",
            length(longest),
            lengths[..lengths.len() - 1].join(", ")
        )
    } else {
        String::new()
    };
    let command = if p.page {
        "`cargo run --release -p quatprop-lab -- noise --out docs` (the sizes of record; `--quick`, `--seeds N` \
         and `--hours 0.5,1,...` for other sizes)"
            .to_string()
    } else {
        "`cargo run --release -p quatprop-lab -- noise --out docs` writes this study as its own page \
         (docs/noise.md) at the sizes of record"
            .to_string()
    };
    format!(
        "{h1} Noise identification from a rest recording: accuracy against record length\n\n\
         Synthetic 3-axis sensors at rest whose noise densities are known, each sample streamed in f64 through \
         `quatprop::noise::AllanVariance` (the non-overlapping Allan variance at octave cluster times \
         τ = 2^k·period, no buffer) and fitted with `NoiseFit::pooled_from(&avar, 16·period)`: \
         σ²(τ) = N²/τ + (2 ln 2/π) B² + K² τ/3 by weighted least squares on the three axes' pooled variances, \
         every term with its standard error (Python: `quatprop.allan(samples, dt, min_tau=16 * dt)`, the \
         same core). {seeds} seeds per sensor; record lengths {lens}. {lengths_note} A term counts as \
         identified when its coefficient is more than 2 standard errors above zero (`Term::is_identified`); \
         its interval is `Term::interval(2.0)`, the coefficient ±2 standard errors. Regenerate: {command}.\n\n\
         {h2} The sensors\n\n\
         Datasheet-like values of each grade (typical, not one part's). N is the angle (velocity) random walk \
         and B the bias instability (the flat bottom of the Allan deviation is 0.664 B); K the rate \
         (acceleration) random walk. A term shows where it dominates the curve: the white noise below \
         τ(N = B), the flicker floor between τ(N = B) and τ(B = K), the random walk above τ(B = K); a record \
         of length T has clusters up to about T/2, with a handful of differences at the longest.\n\n\
         {sensors_table}\n\
         {h2} The generator's flicker band, and why the fit starts at 16 periods\n\n\
         The generator is the one of `tests/noise.rs`: white noise, a random walk, and flicker noise as the sum \
         of {octaves} Gauss–Markov processes one octave apart, each of variance B² ln 2/π, with correlation \
         times period·2^i, i = 0, 1, …: the band starts at the sample period and ends {HEADROOM_OCTAVES} octaves \
         past the longest record. Its expected Allan variance, computed exactly (each process is an AR(1) \
         sequence), is {r1:.3} of the flicker floor at τ = 1 period, {r16:.3} at 16 periods, and within 1 % of \
         it from {within_1pct} periods on ({top_ratio:.3} at 2^{top_k} periods, past the longest cluster of \
         the longest record). Below about 16 periods the generator is not the model's flicker noise, whatever \
         B; a real sensor's own low-pass filter makes its shortest clusters depart from the model too. What a \
         departure costs depends on the point's own standard error, smallest at the shortest clusters (they \
         average the most differences): the first table gives the generator's expected Allan variance against \
         the model's, and that departure in standard errors of the pooled point at {longest_len} (at most \
         {se_short:.1} of them at τ ≤ 8 periods, {fitted_se:.1} from 16 periods on). The fit starts at 16 \
         periods (`min_tau = 16·period`); the second table fits the same records over every cluster instead, \
         at {longest_len}. Over every cluster the median error is lower for {lower} sensors (those where both \
         fits identified the term): this generator's shortest clusters are close to the model (the first \
         table), so skipping them here mostly gives up data; the skip is for sensors whose shortest clusters \
         are not.\n\n\
         {band_table}\n\
         {min_tau_table}\n\
         {h2} Relative error against record length\n\n\
         {error_table}\n\
         At {longest_len}, the longest record (the issue asks for the truth within 10 %):\n\n{claims}\n\n\
         {verdict}\n\n\
         Every seed identified the term and was within 10 % from that length on: {first}.\n\n\
         The fit's own ±2 standard-error interval held the truth, at {longest_len} over the sensors: {cov}; \
         over every length: {cov_all} (a Gaussian estimate with honest standard errors: about 95 %). {short} \
         The octaves share their samples, so their points are correlated (and consecutive differences within \
         an octave too): the standard errors count that, from the covariance of the octaves' estimates under \
         the fitted model (`NoiseFit`'s sandwich; 0.3's took the points as independent, and its intervals \
         held the truth too rarely: CHANGELOG.md). The fit also inflates them by its misfit per degree \
         of freedom where that exceeds 1 (median at {longest_len}: {misfit:.2}).\n\n\
         How the median error falls with the record (log-log slope over the lengths, −0.5 for an error ∝ 1/√T): \
         {slopes}.\n\n\
         ![N](noise_white.png)\n\n![B](noise_instability.png)\n\n![K](noise_random_walk.png)\n\n\
         {h2} The random walk needs a record many times τ(B = K)\n\n\
         The random walk is the term a record shows last: only the spectrum below about 1/τ(B = K) carries \
         it, a record of length T holds about T/τ(B = K) independent looks at that band, and no estimator \
         does better than the information they hold. The tables' *limit* is that information: the \
         Cramér–Rao bound on each density's relative standard deviation for the record, from the three axes' \
         spectra (Whittle's approximation: the rate's spectrum N² + B²/(2πf) + K²/(2πf)² at the record's \
         frequencies). At {longest_len}, K's limit is {k_limit}. With {seeds} seeds the worst error is about \
         2–2.5 standard deviations, so every seed within 10 % needs a limit near 4 %: no estimator meets the \
         issue's 10 % for K at {longest_len} on these sensors; the fit's rms error is near the limit where \
         most seeds identify K (a seed that does not is left out of the rms, which flatters a sensor where \
         few do).\n\n\
         Long records show where it is met: each sensor at {long_rate} Hz (its densities unchanged: from 16 s \
         on, where the fit starts, its Allan variance is the 100 Hz sensor's), records of \
         {ratios} × τ(B = K), {seeds} seeds each (one recording a seed, its shorter records its beginning), \
         fitted as above.\n\n\
         {long_table}\n\
         Every seed identified K within 10 % from that length on: {long_from}. {long_verdict} The last figure \
         puts every record, 100 Hz and long, on one axis: the record over τ(B = K).\n\n\
         ![K against T / τ(B = K)](noise_random_walk_scaled.png)\n\n\
         {h2} One recording\n\n\
         Seed 0 at {longest_len}: the measured Allan deviation (the three axes' variances pooled), the fit \
         over τ ≥ 16 periods, and the model at the true densities.\n\n\
         ![gyroscopes](noise_adev_gyro.png)\n\n![accelerometer](noise_adev_accel.png)\n",
        seeds = p.seeds,
        lower = lower.join(", "),
        lens = lengths.join(", "),
        r1 = at(1),
        r16 = at(16),
        top_k = octaves.saturating_sub(HEADROOM_OCTAVES),
        longest_len = length(longest),
        se_short = short_se(8),
        claims = claims.join("\n"),
        verdict = if all_hold {
            "Every identified term of every sensor is within 10 % of the truth at this length."
        } else {
            "Not every identified term is within 10 % of the truth at this length (above): the random \
             walk K needs a longer record, and no estimator can do better at this one (the section on the \
             random walk below: its information limit, and the long records where K is within 10 %)."
        },
        first = first_within.join("; "),
        cov = coverage.join(", "),
        cov_all = coverage_all.join(", "),
        slopes = slopes.join("; "),
        k_limit = k_limit.join("; "),
        long_rate = LONG_RATE_HZ,
        ratios = p
            .long
            .iter()
            .map(|r| r.ratio)
            .fold(Vec::<f64>::new(), |mut v, r| {
                if !v.contains(&r) {
                    v.push(r);
                }
                v
            })
            .iter()
            .map(f64::to_string)
            .collect::<Vec<_>>()
            .join(", "),
        long_table = p.long_table,
        long_from = long_from.join("; "),
        sensors_table = p.sensors_table,
        band_table = p.band_table,
        error_table = p.error_table,
        min_tau_table = p.min_tau_table,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fit(class: &Class, seconds: f64, seed: u32) -> Fit {
        let n = (seconds * class.rate_hz) as u64;
        record(class, 0, seed, &[n]).0[0].from16
    }

    /// A white-noise sensor (B = K = 0) over 10 minutes: N within 10 % on every seed, and neither B nor K
    /// identified.
    #[test]
    fn white_noise_is_identified_and_nothing_else() {
        let class = Class {
            datasheet: [0.3, 0.0, 0.0],
            ..CLASSES[0]
        };
        for seed in 0..3 {
            let t = fit(&class, 600.0, seed).terms.expect("a fit");
            let e = t[0].value() / class.truth()[0] - 1.0;
            assert!(e.abs() < 0.10, "seed {seed}: N off by {e}");
            assert!(t[0].is_identified());
            assert!(!t[2].is_identified(), "seed {seed}: K {t:?}");
        }
    }

    /// The consumer gyro over 2 minutes, far shorter than τ(B = K) ≈ 530 s: K is not identified, and its
    /// upper bound holds the truth; over 2 hours it is identified within 25 %.
    #[test]
    fn a_random_walk_needs_a_record_long_enough() {
        let class = CLASSES[0];
        let k = class.truth()[2];
        for seed in 0..3 {
            let t = fit(&class, 120.0, seed).terms.expect("a fit");
            assert!(!t[2].is_identified(), "seed {seed}: {t:?}");
            assert!(t[2].interval(INTERVAL_SE).1 >= k);
        }
        let t = fit(&class, 7200.0, 0).terms.expect("a fit");
        assert!(t[2].is_identified());
        assert!((t[2].value() / k - 1.0).abs() < 0.25, "{t:?}");
    }

    /// The information limit of white noise alone is the sample variance's: `n/2` periodogram ordinates
    /// on each of three axes, each worth one unit of information on `ln N²`, so `N`'s relative deviation is
    /// `½ √(2 / 3n)`; a term known to be absent is left out; adding a term can only lose information on
    /// the others.
    #[test]
    fn the_information_limit_of_white_noise_is_the_sample_variances() {
        let n = 10_000;
        let white = information_limit([1e-3, 0.0, 0.0], 0.01, n);
        let expected = 0.5 * (2.0 / (3.0 * n as f64)).sqrt();
        assert!((white[0] / expected - 1.0).abs() < 1e-12, "{white:?}");
        assert!(white[1].is_nan() && white[2].is_nan());
        let truth = CLASSES[0].truth();
        let all = information_limit(truth, 0.01, n);
        let without_k = information_limit([truth[0], truth[1], 0.0], 0.01, n);
        assert!(all[0] > without_k[0] && all[1] > without_k[1], "{all:?} {without_k:?}");
    }

    /// The exact Allan variance of a Gauss–Markov sequence: the closed form and the sum agree where both
    /// are accurate; one sample per cluster is `1 − a`; a long correlation time is a random walk of the
    /// same driving noise, `2x (2m² + 1)/(6m)`.
    #[test]
    fn markov_allan_variance_is_exact() {
        for (x, m) in [(0.3, 5000_u64), (1.0 / 64.0, 8192), (1e-3, 70_000)] {
            let sum = markov_avar_sum(x, m);
            let closed = markov_avar(x, m);
            assert!((closed / sum - 1.0).abs() < 1e-9, "{x} {m}: {closed} {sum}");
        }
        assert!((markov_avar(0.5, 1) + (-0.5f64).exp_m1()).abs() < 1e-15);
        let x = 1e-9;
        let m = 64;
        let rw = 2.0 * x * (2.0 * 64.0 * 64.0 + 1.0) / (6.0 * 64.0);
        assert!((markov_avar(x, m) / rw - 1.0).abs() < 1e-5);
    }

    /// The flicker band is flat to 1 % from 128 periods to 2^(octaves − 7) periods (tests/noise.rs's
    /// statement), about 5 % low at 16 periods, and a quarter below the floor at one period.
    #[test]
    fn the_flicker_band_starts_at_the_sample_period() {
        let octaves = 24;
        for k in 7..=octaves - 7 {
            let r = flicker_over_floor(octaves, 1 << k);
            assert!((r - 1.0).abs() < 0.01, "2^{k}: {r}");
        }
        let r16 = flicker_over_floor(octaves, 16);
        assert!((0.92..0.96).contains(&r16), "{r16}");
        let r1 = flicker_over_floor(octaves, 1);
        assert!((0.7..0.8).contains(&r1), "{r1}");
    }

    /// The generator's Allan variance, measured over many samples, is its expected one within the
    /// estimate's scatter: the exact expectation describes the generator.
    #[test]
    fn the_generator_has_its_expected_allan_variance() {
        let class = CLASSES[0];
        let period = class.period();
        let samples = 1_u64 << 18;
        let octaves = octaves_for(samples);
        let mut g = Generator::new(period, class.truth(), class.offset, octaves, 42);
        let mut avar = AllanVariance::<f64, 20>::new(period).unwrap();
        for _ in 0..samples {
            avar.push(g.sample()).unwrap();
        }
        for c in avar.clusters().take(8) {
            let measured = (c.variance.x + c.variance.y + c.variance.z) / 3.0;
            let expected = generator_avar(class.truth(), period, octaves, u64::from(c.samples));
            let se = (2.0 / (3.0 * f64::from(c.differences))).sqrt();
            let z = (measured / expected - 1.0) / se;
            assert!(z.abs() < 4.0, "τ = {}: {z:.1} standard errors", c.tau);
        }
    }
}
