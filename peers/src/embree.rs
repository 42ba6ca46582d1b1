//! Embree's own figures from `embree_anchor.py --json FILE` (run in the same session): its
//! median Mrays/s per mesh, ray set and thread count, and its median build time on 2 CPUs,
//! with the scene's default (non-robust) flags.

use std::path::Path;

use serde_json::Value;

pub struct EmbreeFigures {
    json: Value,
}

impl EmbreeFigures {
    pub fn load(path: &Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        // Python writes NaN for a figure it could not measure (no quiet moment for a build);
        // JSON has no NaN, so it becomes null here: "not measured".
        let text = text.replace("NaN", "null");
        let json = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(EmbreeFigures { json })
    }

    /// The results of the run restricted to `cpus` CPUs, for `mesh`.
    fn mesh(&self, cpus: usize, mesh: &str) -> &Value {
        &self.json["results"][cpus.to_string()]["meshes"][mesh]["by_robust"]["0"]
    }

    /// Median Mrays/s of `set` on `mesh` with `threads` threads.
    pub fn mrays(&self, mesh: &str, set: &str, threads: usize) -> Option<f64> {
        self.mesh(threads, mesh)[format!("{set}@{threads}t")]["median_mrays"].as_f64()
    }

    /// Median build milliseconds on `cpus` CPUs.
    pub fn build_ms(&self, mesh: &str, cpus: usize) -> Option<f64> {
        self.mesh(cpus, mesh)["build"]["median_s"]
            .as_f64()
            .map(|s| s * 1e3)
    }
}
