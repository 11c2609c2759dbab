//! `stiction scene --print KIND`: an embedded scene with every accepted key, alternatives
//! commented out with their meaning, to start a scene of one's own from.

use stiction_model::keys::Kind;
use stiction_model::scene;

/// The scene kinds of `scene --print`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SceneKind {
    /// `stiction asperity`.
    Asperity,
    /// `stiction surface`.
    Surface,
    /// `stiction switch`, `design`, `law`.
    Switch,
}

/// Print an embedded scene as TOML, with every accepted key, to start a scene from.
#[derive(Debug, Clone, clap::Args)]
pub struct SceneCommand {
    /// Which scene.
    #[arg(long, value_enum)]
    pub print: SceneKind,
}

impl SceneCommand {
    /// The scene's text.
    pub fn execute(&self) -> String {
        scene_text(match self.print {
            SceneKind::Asperity => Kind::Asperity,
            SceneKind::Surface => Kind::Surface,
            SceneKind::Switch => Kind::Switch,
        })
        .to_string()
    }
}

/// The annotated paper scene of `kind`.
pub fn scene_text(kind: Kind) -> &'static str {
    match kind {
        Kind::Asperity => scene::PAPER_ASPERITY,
        Kind::Surface => scene::PAPER_SURFACE,
        _ => scene::PAPER_SWITCH,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stiction_model::keys as fields;

    /// Every key a scene accepts appears in its printed form, set or commented out.
    #[test]
    fn printed_scenes_show_every_accepted_key() {
        for kind in [Kind::Asperity, Kind::Surface, Kind::Switch] {
            let text = scene_text(kind);
            for f in fields::of(kind) {
                let leaf = f.key.rsplit('.').next().unwrap_or(f.key);
                let present = text.lines().any(|l| {
                    let l = l.trim_start_matches('#').trim_start();
                    l.starts_with(&format!("{leaf} =")) || l.starts_with(&format!("[{}]", f.key))
                });
                assert!(present, "{kind:?}: `{}` is not shown", f.key);
            }
        }
    }
}
