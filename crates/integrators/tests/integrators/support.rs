//! Shared helpers: run any registry method by name on the exact-solution problems.

use nalgebra::SVector;
use tumble_integrators::registry::build::{self, Receive, ReceiveOde};
use tumble_integrators::registry::find;
use tumble_integrators::verification::{HarmonicOscillator, Kepler, Pendulum, max_abs_diff};
use tumble_integrators::{
    AdaptiveStepper, DenseOutput, Driver, Error, HamiltonianOde, NoObserver, Ode, ProblemKind,
    SeparableHamiltonian, Stepper,
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

/// Runs the stepper it receives with fixed steps `h` from `y0` over `[0, t_end]`; the final
/// state.
struct Fixed<'a, P, const N: usize> {
    problem: &'a P,
    y0: [f64; N],
    t_end: f64,
    h: f64,
}

impl<P, const N: usize> Fixed<'_, P, N> {
    fn run<St: Stepper<P, State = SVector<f64, N>>>(
        self,
        mut stepper: St,
    ) -> Result<SVector<f64, N>, Error> {
        let mut y = SVector::<f64, N>::from(self.y0);
        Driver::new(0.0, self.t_end)?.run_fixed(
            &mut stepper,
            self.problem,
            &mut y,
            self.h,
            &mut NoObserver,
        )?;
        Ok(y)
    }
}

impl<P, const N: usize> Receive<P, SVector<f64, N>> for Fixed<'_, P, N> {
    type Output = Result<SVector<f64, N>, Error>;
    fn receive<St: Stepper<P, State = SVector<f64, N>> + Clone>(self, stepper: St) -> Self::Output {
        self.run(stepper)
    }
}

impl<P: Ode<SVector<f64, N>>, const N: usize> ReceiveOde<P, SVector<f64, N>> for Fixed<'_, P, N> {
    type Output = Result<SVector<f64, N>, Error>;
    fn adaptive<St: AdaptiveStepper<P, State = SVector<f64, N>> + DenseOutput<P>>(
        self,
        stepper: St,
    ) -> Self::Output {
        self.run(stepper)
    }
    fn interpolating<St: DenseOutput<P, State = SVector<f64, N>>>(
        self,
        stepper: St,
    ) -> Self::Output {
        self.run(stepper)
    }
    fn plain<St: Stepper<P, State = SVector<f64, N>> + Clone>(self, stepper: St) -> Self::Output {
        self.run(stepper)
    }
}

/// Final state of the registry method `name` on a separable Hamiltonian from `y0`, with fixed
/// steps: as a first-order ODE `y' = (∂H/∂p, −∂H/∂q)` for the methods that integrate one, as
/// the Hamiltonian itself for the others (the registry builds either stepper).
pub fn solve_hamiltonian<H: SeparableHamiltonian, const N: usize>(
    name: &str,
    hamiltonian: H,
    y0: [f64; N],
    t_end: f64,
    h: f64,
) -> Result<SVector<f64, N>, Error> {
    let method = find(name)?;
    let y = SVector::<f64, N>::from(y0);
    if method.problems.contains(&ProblemKind::Ode) {
        let ode = HamiltonianOde(&hamiltonian);
        let run = Fixed {
            problem: &ode,
            y0,
            t_end,
            h,
        };
        build::ode(method, &y, run)?
    } else {
        let run = Fixed {
            problem: &hamiltonian,
            y0,
            t_end,
            h,
        };
        build::separable(method, &y, run)?
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
