//! Long runs on Kepler: 10⁶ steps of Gauss–Legendre (s = 2, 3) and of a composition method
//! keep the relative energy error bounded; with compensated summation its round-off part
//! grows like √n (fitted exponent in [0.35, 0.65]); without it, the round-off part is
//! several times larger (printed with its exponent).
//!
//! Setup: eccentricity 0.2, `h = 2π/100` (10⁶ steps = 10⁴ periods). The truncation part of
//! the energy error is bounded and depends only on the phase of the orbit; to isolate the
//! round-off part, the same run is repeated from an initial state perturbed by one ulp: the
//! truncation parts agree to ~1e-20, the round-off sequences decorrelate, and the
//! difference of the two relative energy errors is the round-off part (times √2). Its RMS
//! over the blocks `[2ᵏ, 2ᵏ⁺¹)` steps, `k = 12 … 19`, is fitted against the block's step
//! count. Boundedness: the RMS of the energy error itself shows no drift (exponent ≈ 0).

use nalgebra::SVector;
use tumble_integrators::tables::composition::KAHAN_LI8;
use tumble_integrators::verification::{Kepler, fit_power_law};
use tumble_integrators::{
    Composition, Gauss, HamiltonianOde, SeparableHamiltonian, Stepper, StormerVerlet, gauss4,
    gauss6,
};

type V4 = SVector<f64, 4>;

const STEPS: u64 = 1 << 20; // 1 048 576
const E: f64 = 0.2;
const H: f64 = 2.0 * std::f64::consts::PI / 100.0;

struct LongRun {
    /// Representative step count of each block.
    ns: Vec<f64>,
    /// RMS of the round-off part per block.
    roundoff: Vec<f64>,
    /// RMS of the relative energy error per block.
    energy: Vec<f64>,
    /// Largest relative energy error.
    max: f64,
}

fn long_run<St: Stepper<P, State = V4>, P: ?Sized>(mut a: St, mut b: St, problem: &P) -> LongRun {
    let mut ya = V4::from(Kepler::initial(E));
    let mut yb = ya;
    yb[0] = f64::from_bits(yb[0].to_bits() + 1);
    let ha = Kepler.energy(ya.as_slice());
    let hb = Kepler.energy(yb.as_slice());
    let mut out = LongRun {
        ns: vec![],
        roundoff: vec![],
        energy: vec![],
        max: 0.0,
    };
    let (mut sd, mut se, mut count) = (0.0, 0.0, 0u64);
    let mut block_start = 1u64 << 12;
    let mut t = 0.0;
    for n in 1..=STEPS {
        a.step(problem, t, &mut ya, H).expect("step");
        b.step(problem, t, &mut yb, H).expect("step");
        t = n as f64 * H;
        let ea = (Kepler.energy(ya.as_slice()) - ha) / ha.abs();
        let eb = (Kepler.energy(yb.as_slice()) - hb) / hb.abs();
        out.max = out.max.max(ea.abs());
        if n >= block_start {
            sd += (ea - eb) * (ea - eb);
            se += ea * ea;
            count += 1;
            if n + 1 == 2 * block_start {
                out.ns.push(1.5 * block_start as f64);
                out.roundoff.push((sd / count as f64).sqrt());
                out.energy.push((se / count as f64).sqrt());
                sd = 0.0;
                se = 0.0;
                count = 0;
                block_start *= 2;
            }
        }
    }
    out
}

fn check_gauss<const S: usize>(method: Gauss<S>) {
    let problem = HamiltonianOde(Kepler);
    let y0 = V4::from(Kepler::initial(E));
    let c = long_run(method.stepper(&y0), method.stepper(&y0), &problem);
    let u = long_run(
        method.uncompensated().stepper(&y0),
        method.uncompensated().stepper(&y0),
        &problem,
    );
    let alpha = fit_power_law(&c.ns, &c.roundoff);
    let alpha_u = fit_power_law(&u.ns, &u.roundoff);
    let drift = fit_power_law(&c.ns, &c.energy);
    let (rms, rms_u) = (c.roundoff, u.roundoff);
    eprintln!(
        "gauss s={S}: energy error max {:.2e}, drift exponent {drift:.3}; round-off: compensated \
         exponent {alpha:.3} final RMS {:.2e}; uncompensated exponent {alpha_u:.3} final RMS {:.2e}",
        c.max,
        rms.last().unwrap(),
        rms_u.last().unwrap()
    );
    assert!((0.35..=0.65).contains(&alpha), "Brouwer exponent {alpha}");
    assert!(
        drift.abs() < 0.1,
        "energy error bounded, no drift: exponent {drift}"
    );
    // without compensated summation the round-off part is larger (it is dominated by the
    // rounding of y + δ with |δ| ≪ |y| at every step)
    assert!(
        rms_u.last().unwrap() > &(2.0 * rms.last().unwrap()),
        "uncompensated final RMS {:e} vs {:e}",
        rms_u.last().unwrap(),
        rms.last().unwrap()
    );
}

#[test]
fn gauss4_follows_brouwers_law_over_a_million_steps() {
    check_gauss(gauss4());
}

#[test]
fn gauss6_follows_brouwers_law_over_a_million_steps() {
    check_gauss(gauss6());
}

#[test]
fn kahan_li8_composition_keeps_energy_bounded_over_a_million_steps() {
    let y0 = V4::from(Kepler::initial(E));
    let build = || Composition::new(&KAHAN_LI8, StormerVerlet::default().stepper(&y0));
    let c = long_run(build(), build(), &Kepler);
    let alpha = fit_power_law(&c.ns, &c.roundoff);
    let drift = fit_power_law(&c.ns, &c.energy);
    eprintln!(
        "kahan-li8: energy error max {:.2e}, drift exponent {drift:.3}; round-off exponent {alpha:.3} final RMS {:.2e}",
        c.max,
        c.roundoff.last().unwrap()
    );
    assert!(
        drift.abs() < 0.1,
        "energy error bounded, no drift: exponent {drift}"
    );
    assert!((0.35..=0.65).contains(&alpha), "round-off exponent {alpha}");
}
