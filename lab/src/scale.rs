//! How big a run makes its work: [`Scale`] (`--quick`, the default, `--full`), which every study reads
//! from its `Ctx`.

/// How big every study makes its grids and horizons.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scale {
    /// `--quick`: seconds per study; CI checks that every study runs and writes every file.
    Quick,
    /// No flag: every figure at a resolution that shows its point; the whole report, build included, in
    /// minutes (lab/README.md has the measured times).
    #[default]
    Default,
    /// `--full`: the sizes of record (docs/report).
    Full,
}

impl Scale {
    /// The value for this scale.
    pub fn pick<T>(self, quick: T, default: T, full: T) -> T {
        match self {
            Scale::Quick => quick,
            Scale::Default => default,
            Scale::Full => full,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_picks_its_value() {
        assert_eq!(Scale::Quick.pick(1, 2, 3), 1);
        assert_eq!(Scale::Default.pick(1, 2, 3), 2);
        assert_eq!(Scale::Full.pick(1, 2, 3), 3);
        assert_eq!(Scale::default(), Scale::Default);
    }
}
