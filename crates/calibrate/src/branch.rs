//! The branch of a loading cycle: shared by the data and their errors.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Which branch of the loading cycle a point belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// The virgin loading from far away to delta_max: at each point the asperity has been
    /// loaded to that point (history delta_max = delta).
    Loading,
    /// The retraction from delta_max.
    Unloading,
}

impl Branch {
    /// The CSV spelling: `loading` or `unloading`.
    pub fn as_str(self) -> &'static str {
        match self {
            Branch::Loading => "loading",
            Branch::Unloading => "unloading",
        }
    }
}

impl fmt::Display for Branch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}
