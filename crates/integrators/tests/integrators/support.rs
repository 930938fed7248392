//! Shared helpers: run any registry method by name on the exact-solution problems.

use nalgebra::SVector;
use tumble_integrators::tables::composition::ALL;
use tumble_integrators::verification::{HarmonicOscillator, Kepler, Pendulum, max_abs_diff};
use tumble_integrators::{
    Composition, Driver, Error, ExplicitRungeKutta, HamiltonianOde, NoObserver,
    SeparableHamiltonian, Stepper, StormerVerlet, SymplecticEuler, gauss2, gauss4, gauss6, gauss8,
    gauss10, gauss12,
};

/// The three problems with exact solutions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Exact {
    /// Harmonic oscillator from (1, 0), t ∈ [0, 10].
    Harmonic,
    /// Kepler e = 0.6 over two and a half periods (ending at apocentre, so that no
    /// periodicity hides the O(h) term of symplectic Euler).
    Kepler,
    /// Pendulum k = 0.999 (near the separatrix), t ∈ [0, 10].
    Pendulum,
}

pub const KEPLER_E: f64 = 0.6;
pub const PENDULUM_K: f64 = 0.999;

impl Exact {
    pub fn t_end(self) -> f64 {
        match self {
            Exact::Harmonic => 10.0,
            Exact::Kepler => 5.0 * std::f64::consts::PI,
            Exact::Pendulum => 10.0,
        }
    }
}

fn run_fixed<H, St, const N: usize>(
    problem: &H,
    stepper: &mut St,
    y0: [f64; N],
    t_end: f64,
    h: f64,
) -> Result<SVector<f64, N>, Error>
where
    H: ?Sized,
    St: Stepper<H, State = SVector<f64, N>>,
{
    let mut y = SVector::<f64, N>::from(y0);
    Driver::new(0.0, t_end)?.run_fixed(stepper, problem, &mut y, h, &mut NoObserver)?;
    Ok(y)
}

/// Final state of method `name` on a separable Hamiltonian from `y0`.
pub fn solve_hamiltonian<H: SeparableHamiltonian, const N: usize>(
    name: &str,
    hamiltonian: H,
    y0: [f64; N],
    t_end: f64,
    h: f64,
) -> Result<SVector<f64, N>, Error> {
    let y = SVector::<f64, N>::from(y0);
    let ode = HamiltonianOde(&hamiltonian);
    match name {
        "rk4" => run_fixed(
            &ode,
            &mut ExplicitRungeKutta::rk4().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "dp5" => run_fixed(
            &ode,
            &mut ExplicitRungeKutta::dp5().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "dop853" => run_fixed(
            &ode,
            &mut ExplicitRungeKutta::dop853().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "tsit5" => run_fixed(
            &ode,
            &mut ExplicitRungeKutta::tsit5().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "vern6" => run_fixed(
            &ode,
            &mut ExplicitRungeKutta::vern6().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "vern7" => run_fixed(
            &ode,
            &mut ExplicitRungeKutta::vern7().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "vern8" => run_fixed(
            &ode,
            &mut ExplicitRungeKutta::vern8().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "vern9" => run_fixed(
            &ode,
            &mut ExplicitRungeKutta::vern9().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "symplectic-euler" => run_fixed(
            &hamiltonian,
            &mut SymplecticEuler::default().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "verlet" => run_fixed(
            &hamiltonian,
            &mut StormerVerlet::default().stepper(&y),
            y0,
            t_end,
            h,
        ),
        "gauss2" => run_fixed(&ode, &mut gauss2().stepper(&y), y0, t_end, h),
        "gauss4" => run_fixed(&ode, &mut gauss4().stepper(&y), y0, t_end, h),
        "gauss6" => run_fixed(&ode, &mut gauss6().stepper(&y), y0, t_end, h),
        "gauss8" => run_fixed(&ode, &mut gauss8().stepper(&y), y0, t_end, h),
        "gauss10" => run_fixed(&ode, &mut gauss10().stepper(&y), y0, t_end, h),
        "gauss12" => run_fixed(&ode, &mut gauss12().stepper(&y), y0, t_end, h),
        other => {
            let table = ALL
                .iter()
                .find(|t| t.name == other)
                .ok_or_else(|| Error::UnknownMethod(other.to_owned()))?;
            let mut stepper = Composition::new(table, StormerVerlet::default().stepper(&y));
            run_fixed(&hamiltonian, &mut stepper, y0, t_end, h)
        }
    }
}

/// Max-norm error at the end of the run of `name` on `problem` with step `h`.
pub fn error_of(name: &str, problem: Exact, h: f64) -> Result<f64, Error> {
    let t_end = problem.t_end();
    Ok(match problem {
        Exact::Harmonic => {
            let y = solve_hamiltonian(name, HarmonicOscillator, [1.0, 0.0], t_end, h)?;
            max_abs_diff(y.as_slice(), &HarmonicOscillator::exact(1.0, 0.0, t_end))
        }
        Exact::Kepler => {
            let y = solve_hamiltonian(name, Kepler, Kepler::initial(KEPLER_E), t_end, h)?;
            max_abs_diff(y.as_slice(), &Kepler::exact(KEPLER_E, t_end))
        }
        Exact::Pendulum => {
            let y = solve_hamiltonian(name, Pendulum, Pendulum::initial(PENDULUM_K), t_end, h)?;
            max_abs_diff(y.as_slice(), &Pendulum::exact(PENDULUM_K, t_end)?)
        }
    })
}
