//! A program of one's own: the `stiction` command line with one more plasticity law, which
//! any scene can then name (`plasticity_law = "flat_top"`) in every command: `switch`,
//! `design`, `law`, `surface`, `asperity`.
//!
//! The law: a tip that flattens fully plastically beyond its yield onset (Chang, Etsion &
//! Bogy 1987 in spirit): it loses delta_max - delta_CP of height, keeps the elastic
//! recovery delta_CP, and unloads as a sphere of residual radius
//! R_res = R (1 + hardening (delta_max/delta_CP - 1)). Its two parameters live in the
//! scene's `[contact.plasticity]` table.
//!
//! Run: `cargo run --example user_law -- switch --scene my_scene.toml`.

use std::sync::Arc;
use stiction::contact_core::{PlasticState, PlasticityLaw};
use stiction::model::keys::{Default, Domain};
use stiction::model::laws::{LawRegistry, Param, PlasticityEntry};

/// The flat-top law.
#[derive(Debug, Clone, Copy)]
pub struct FlatTop {
    radius: f64,
    delta_cp: f64,
    hardening: f64,
}

impl PlasticityLaw for FlatTop {
    fn radius(&self) -> f64 {
        self.radius
    }
    fn delta_cp(&self) -> f64 {
        self.delta_cp
    }
    fn state(&self, delta_max: f64) -> PlasticState {
        let omega = delta_max / self.delta_cp;
        if !(omega > 1.0) {
            return PlasticState::new(delta_max.max(0.0), 0.0, self.radius, false);
        }
        PlasticState::new(
            delta_max,
            delta_max - self.delta_cp,
            self.radius * (1.0 + self.hardening * (omega - 1.0)),
            false,
        )
    }
    fn effective_radius(&self, state: &PlasticState, _delta: f64) -> f64 {
        state.r_res
    }
}

/// The registry of the built-in laws with `flat_top` added.
pub fn registry() -> LawRegistry {
    let mut r = LawRegistry::builtin();
    let params = vec![
        Param {
            name: "delta_cp",
            unit: "m",
            domain: Domain::range(1e-12, 1e-6),
            default: Default::Required,
            help: "yield onset interference",
        },
        Param {
            name: "hardening",
            unit: "-",
            domain: Domain::range(0.0, 10.0),
            default: Default::Number(0.5),
            help: "growth of the residual radius per delta_max/delta_CP",
        },
    ];
    let entry = PlasticityEntry::new(
        "flat_top",
        "fully plastic flat top (example)",
        params,
        |ctx| {
            Ok(Arc::new(FlatTop {
                radius: ctx.pair.radius(),
                delta_cp: ctx.params.number("delta_cp").unwrap_or(f64::NAN),
                hardening: ctx.params.number("hardening").unwrap_or(0.5),
            }))
        },
    );
    r.register_plasticity(entry).expect("a new name");
    r
}

#[allow(dead_code)]
fn main() {
    std::process::exit(stiction::cli::main_with(std::env::args_os(), &registry()));
}
