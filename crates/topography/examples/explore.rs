use topography::*;
fn main() -> Result<()> {
    for &(h, ls_pts, n) in &[(0.8, 16.0, 512usize), (0.8, 8.0, 512), (0.5, 16.0, 512), (0.8, 4.0, 512), (0.8,2.0,512)] {
        let dx = 5e-9;
        let psd = SelfAffinePsd::new(h, n as f64 * dx / 2.0, None, ls_pts * dx, Normalization::RmsHeight(5e-9))?;
        let a = psd.moments();
        let ga = psd.gw_parameters();
        for amp in [Amplitudes::Fixed, Amplitudes::Gaussian] {
            let map = synthesize(&psd, &SynthesisOptions { nx: n, ny: n, dx, dy: dx, seed: 7, amplitudes: amp })?;
            let s = spectral_moments(&map);
            let f = finite_difference_moments(&map);
            let r = analyze(&map, &AnalysisOptions::default())?;
            let su = r.summits.as_ref().unwrap();
            println!("H {h} ls {ls_pts} {:?}: alpha an {:.2} sp {:.2} fd {:.2} | m2 sp/an {:.4} m4 sp/an {:.4} | fd/an m2 {:.4} m4 {:.4}", amp, a.alpha(), s.alpha(), f.alpha(), s.m2/a.m2, s.m4/a.m4, f.m2/a.m2, f.m4/a.m4);
            println!("   analytic: s {:.3e} N {:.3e} R {:.3e} o {:.3e}", ga.sigma_s, ga.asperity_density, ga.radius, ga.offset);
            let g = r.spectral.gw;
            println!("   spectral: s {:.3e} N {:.3e} R {:.3e} o {:.3e}", g.sigma_s, g.asperity_density, g.radius, g.offset);
            let g = su.gw;
            println!("   summits : s {:.3e} N {:.3e} R {:.3e} o {:.3e}  count {} skew {:.2} kurt {:.2} hskew {:.3} hkurt {:.3}", g.sigma_s, g.asperity_density, g.radius, g.offset, su.count, su.skewness, su.kurtosis, r.heights.skewness, r.heights.kurtosis);
            for row in &r.sampling { let s2 = row.summits.unwrap(); println!("     x{} N sp {:.3e} su {:.3e} R sp {:.3e} su {:.3e} s sp {:.3e} su {:.3e}", row.factor, row.spectral.asperity_density, s2.asperity_density, row.spectral.radius, s2.radius, row.spectral.sigma_s, s2.sigma_s); }
            for w in &r.warnings { println!("   warn {}", w.code); }
        }
    }
    Ok(())
}
