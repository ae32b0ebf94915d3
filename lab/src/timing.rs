//! How long each study of a run took: wall time and this process's CPU time (all threads), so the
//! parallel sweeps' speed-up (CPU / wall) is measured even on a shared machine, where wall time alone
//! also counts the other processes.

use crate::table::{self, Csv, Table};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// One study's run time.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StudyTimeRow {
    pub study: String,
    pub wall_s: f64,
    pub cpu_s: f64,
    /// Rayon's threads for the accuracy sweeps (timing measurements run serially whatever this is).
    pub threads: usize,
}

impl Csv for StudyTimeRow {
    const FILE: &'static str = "run_time.csv";
}

// Each table spells out its own line: its columns and their number formats are its own.
impl Table for StudyTimeRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "study",
            "wall time (s)",
            "CPU time, all threads (s)",
            "CPU / wall",
            "sweep threads",
        ]);
        let (mut wall, mut cpu) = (0.0, 0.0);
        for r in rows {
            t += &format!(
                "| {} | {:.1} | {:.1} | {:.2} | {} |\n",
                r.study,
                r.wall_s,
                r.cpu_s,
                r.cpu_s / r.wall_s.max(1e-9),
                r.threads
            );
            wall += r.wall_s;
            cpu += r.cpu_s;
        }
        t += &format!(
            "| **all studies** | **{wall:.1}** | **{cpu:.1}** | **{:.2}** | |\n",
            cpu / f64::max(wall, 1e-9)
        );
        t
    }
}

/// A running clock: wall time and this process's CPU time (all threads; Linux `/proc`, else wall).
pub struct Clock {
    wall: Instant,
    cpu: Option<cpu_time::ProcessTime>,
}

impl Clock {
    pub fn start() -> Self {
        Self {
            wall: Instant::now(),
            cpu: cpu_time::ProcessTime::try_now().ok(),
        }
    }

    /// The study's row from the time since `start`.
    pub fn row(&self, study: &str) -> StudyTimeRow {
        let wall_s = self.wall.elapsed().as_secs_f64();
        let cpu_s = self
            .cpu
            .and_then(|c| c.try_elapsed().ok())
            .map_or(wall_s, |d| d.as_secs_f64());
        StudyTimeRow {
            study: study.to_string(),
            wall_s,
            cpu_s,
            threads: rayon::current_num_threads(),
        }
    }
}
