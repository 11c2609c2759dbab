//! The Maugis-Kim curve's result (`stiction md`): its table and CSV.

use crate::render::{csv_num, Render};
use std::fmt::Write as _;
use stiction_model::maugis_kim;
use stiction_model::md::{MdPointResult, MdResult};

impl Render for MdResult {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Maugis-Kim, lambda = {} (nondimensional, eq 7)",
            self.lambda
        );
        let _ = writeln!(s, "  jump-in      Delta_in = {:.10}", self.jump_in_delta);
        let _ = writeln!(
            s,
            "  turning pt.  Delta_t  = {:.10}   Fbar_t = {:.10}",
            self.turning_delta, self.turning_force
        );
        let _ = writeln!(
            s,
            "  pull-off, load control         Fbar = {:.10}",
            self.pull_off_load_control
        );
        let _ = writeln!(
            s,
            "  pull-off, displacement control Fbar = {:.10}",
            self.pull_off_displacement_control
        );
        let _ = writeln!(
            s,
            "{:>14} {:>14} {:>12} {:>12} {:>7}",
            "Delta", "Fbar", "A", "C", "stable"
        );
        for p in &self.curve {
            let _ = writeln!(
                s,
                "{:>14.6e} {:>14.6e} {:>12.5e} {:>12.5e} {:>7}",
                p.delta, p.force, p.a, p.c, p.stable
            );
        }
        s
    }
    fn csv(&self) -> String {
        let mut s = String::from("delta,force,a,c,branch,stable\n");
        for p in &self.curve {
            let branch = match p.branch {
                maugis_kim::Branch::Contact => "contact",
                maugis_kim::Branch::NonContact => "non_contact",
            };
            let _ = writeln!(
                s,
                "{},{},{},{},{},{}",
                csv_num(p.delta),
                csv_num(p.force),
                csv_num(p.a),
                csv_num(p.c),
                branch,
                p.stable
            );
        }
        s
    }
}

impl Render for MdPointResult {
    fn table(&self) -> String {
        format!(
            "lambda = {}, Delta = {}, path = {}: Fbar = {}\n",
            self.lambda, self.delta, self.path, self.force
        )
    }
    fn csv(&self) -> String {
        format!(
            "lambda,delta,path,force\n{},{},{},{}\n",
            csv_num(self.lambda),
            csv_num(self.delta),
            self.path,
            csv_num(self.force)
        )
    }
}
