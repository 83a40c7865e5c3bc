//! Prints the transitions of a few full-motion runs (a quick look, not a test).
use eccjump_core::mechanics::{Cylinder, Ramp, Rule};
use eccjump_core::modes::contact::ContactLaw;
use eccjump_core::motion::{simulate, SimOptions};

fn main() {
    for &(alpha, chi, km, mu, e, rule) in &[
        (40.0, 0.15, 0.02, 1.0, 0.0, Rule::Paper),
        (30.0, 0.5, 0.4, 1.0, 0.0, Rule::Paper),
        (30.0, 0.5, 0.4, 1.0, 0.5, Rule::NormalForce),
        (60.0, 0.3, 0.3, 0.1, 0.0, Rule::Paper),
    ] {
        let r = Ramp::new(Cylinder::new(chi, km).unwrap(), f64::to_radians(alpha)).unwrap();
        let o = SimOptions {
            law: ContactLaw { mu_s: mu, mu_k: mu, rule },
            restitution: e,
            t_max: 40.0,
            max_transitions: 12,
            ..SimOptions::default()
        };
        let t = std::time::Instant::now();
        let run = simulate(&r, &o).unwrap();
        let dt = t.elapsed();
        println!("α={alpha} χ={chi} km={km} μ={mu} e={e} {rule:?}: {:?} {} ({} pts, nfev {}, {:?})", run.status, run.message, run.points.len(), run.nfev, dt);
        for tr in &run.transitions {
            let en = r.energy_of(&tr.state);
            println!("  t={:10.6} θ={:10.4}° {:?}→{:?} {:?}  E+diss={:.10}", tr.t, tr.state.theta.to_degrees(), tr.from, tr.to, tr.reason, en);
        }
        let last = run.points.last().unwrap();
        println!("  ledger: E0={:.12} E_end+diss={:.12}", run.energy0, r.energy_of(&last.state) + last.dissipated);
    }
}
