//! The registry: every study of the lab, one line each, in the report's order. A line `file::Type` declares
//! the module `studies/file.rs` and registers its [`Study`](crate::study::Study) `Type`: its sub-command,
//! its place in `report`, and its CSV files and figures in the tests' checks all come from here.

use crate::study::AnyStudy;

macro_rules! registry {
    ($($module:ident :: $study:ident),* $(,)?) => {
        $(pub mod $module;)*

        /// Every study, in the report's order.
        pub const ALL: &[&dyn AnyStudy] = &[$(&$module::$study),*];

        /// The registered modules (files under `studies/`).
        #[cfg(test)]
        pub const MODULES: &[&str] = &[$(stringify!($module)),*];
    };
}

registry! {
    geiger::Geiger,
    baumgarte_sweep::BaumgarteSweep,
    atlas::Atlas,
    work_precision::WorkPrecision,
    config_cost::ConfigCost,
    scene_table::Scenes,
    sensor::Sensor,
    coning_drift::ConingDrift,
    time_base::TimeBaseStudy,
    long_horizon::LongHorizon,
    covariance::Covariance,
}
