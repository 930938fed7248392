//! Inside the driver's loops: events located on dense output, output times delivered, and each
//! step's continuous extension handed to observers that ask for it.

use super::{Action, DenseStep, Direction, Event, EventRecord, Flow, Observer, Report, Status};
use crate::error::Error;
use crate::state::State;
use crate::stepper::{DenseOutput, Stepper};

/// [`DenseStep`] over a stepper with dense output.
pub(super) struct DenseView<'s, P: ?Sized, St: Stepper<P>> {
    stepper: &'s mut St,
    problem: &'s P,
    t0: f64,
    /// End of the span: the step's end, or a terminal event inside the step.
    t1: f64,
    /// The step's end, where `end` is the state.
    step_end: f64,
    end: &'s St::State,
    scratch: &'s mut St::State,
}

impl<P: ?Sized, St: DenseOutput<P>> DenseStep<St::State> for DenseView<'_, P, St> {
    fn span(&self) -> (f64, f64) {
        (self.t0, self.t1)
    }

    fn state_at(&mut self, t: f64) -> &St::State {
        if t == self.step_end {
            return self.end;
        }
        self.stepper.interpolate(self.problem, t, self.scratch);
        self.scratch
    }
}

/// What the loop does after the events and outputs of a step.
pub(super) enum AfterStep {
    /// Go on.
    Go,
    /// A terminal event at this time; the state is set there.
    Terminated(f64),
    /// An observer stopped the run at an output.
    Stopped,
    /// An interpolation failed ([`DenseOutput::take_failure`]).
    Failed(Error),
}

/// Event and output handling inside the loops (a trait so the fixed loop can run without
/// events).
pub(super) trait EventHook<P: ?Sized, St: Stepper<P>> {
    /// At the start: outputs at `t₀`.
    fn start<O: Observer<St::State>>(
        &mut self,
        t: f64,
        state: &St::State,
        observer: &mut O,
    ) -> Flow;
    /// After a step to `t1`: events located, outputs in the step delivered.
    fn after_step<O: Observer<St::State>>(
        &mut self,
        stepper: &mut St,
        problem: &P,
        t1: f64,
        state: &mut St::State,
        report: &mut Report<St::State>,
        observer: &mut O,
    ) -> AfterStep;
}

/// No events.
pub(super) struct NoEvents<'e, S>(std::marker::PhantomData<&'e S>);

impl<P: ?Sized, St: Stepper<P>> EventHook<P, St> for NoEvents<'_, St::State> {
    fn start<O: Observer<St::State>>(
        &mut self,
        _t: f64,
        _state: &St::State,
        _observer: &mut O,
    ) -> Flow {
        Flow::Continue
    }
    fn after_step<O: Observer<St::State>>(
        &mut self,
        _stepper: &mut St,
        _problem: &P,
        _t1: f64,
        _state: &mut St::State,
        _report: &mut Report<St::State>,
        _observer: &mut O,
    ) -> AfterStep {
        AfterStep::Go
    }
}

pub(super) struct EventTracker<'e, 'f, 'o, S> {
    events: &'e mut [Event<'f, S>],
    g_prev: Vec<f64>,
    t_prev: f64,
    scratch: Option<S>,
    found: Vec<(f64, usize)>,
    /// Output times and the index of the next one to deliver.
    outputs: &'o [f64],
    next_output: usize,
    /// The observer wants every step's dense output.
    dense: bool,
}

impl<'e, 'f, 'o, S: State> EventTracker<'e, 'f, 'o, S> {
    pub(super) fn new(events: &'e mut [Event<'f, S>], outputs: &'o [f64]) -> Self {
        let n = events.len();
        Self {
            events,
            g_prev: vec![0.0; n],
            t_prev: 0.0,
            scratch: None,
            found: Vec::with_capacity(n),
            outputs,
            next_output: 0,
            dense: false,
        }
    }
}

fn crosses(direction: Direction, g0: f64, g1: f64) -> bool {
    match direction {
        Direction::Rising => g0 < 0.0 && g1 >= 0.0,
        Direction::Falling => g0 > 0.0 && g1 <= 0.0,
        Direction::Either => (g0 < 0.0 && g1 >= 0.0) || (g0 > 0.0 && g1 <= 0.0),
    }
}

impl<P: ?Sized, St> EventHook<P, St> for EventTracker<'_, '_, '_, St::State>
where
    St: DenseOutput<P>,
{
    fn start<O: Observer<St::State>>(
        &mut self,
        t: f64,
        state: &St::State,
        observer: &mut O,
    ) -> Flow {
        self.t_prev = t;
        for (g, ev) in self.g_prev.iter_mut().zip(self.events.iter()) {
            *g = (ev.function)(t, state);
        }
        self.dense = observer.wants_dense_steps();
        if !self.events.is_empty() || !self.outputs.is_empty() || self.dense {
            self.scratch = Some(state.clone());
        }
        while self.outputs.get(self.next_output) == Some(&t) {
            self.next_output += 1;
            if observer.output(t, state) == Flow::Stop {
                return Flow::Stop;
            }
        }
        Flow::Continue
    }

    fn after_step<O: Observer<St::State>>(
        &mut self,
        stepper: &mut St,
        problem: &P,
        t1: f64,
        state: &mut St::State,
        report: &mut Report<St::State>,
        observer: &mut O,
    ) -> AfterStep {
        let after = self.deliver(stepper, problem, t1, state, report, observer);
        match stepper.take_failure() {
            Some(e) => AfterStep::Failed(e),
            None => after,
        }
    }
}

impl<S: State> EventTracker<'_, '_, '_, S> {
    /// Events, dense steps and outputs of the step that ended at `t1`.
    fn deliver<P: ?Sized, St: DenseOutput<P, State = S>, O: Observer<S>>(
        &mut self,
        stepper: &mut St,
        problem: &P,
        t1: f64,
        state: &mut S,
        report: &mut Report<S>,
        observer: &mut O,
    ) -> AfterStep {
        if self.events.is_empty() && self.outputs.is_empty() && !self.dense {
            return AfterStep::Go;
        }
        let t0 = self.t_prev;
        self.found.clear();
        let Some(scratch) = self.scratch.as_mut() else {
            return AfterStep::Go;
        };
        for (i, ev) in self.events.iter().enumerate() {
            let g0 = self.g_prev[i];
            let g1 = (ev.function)(t1, state);
            if crosses(ev.direction, g0, g1) {
                let root = locate(stepper, problem, &*ev.function, t0, g0, t1, g1, scratch);
                self.found.push((root, i));
            }
            self.g_prev[i] = g1;
        }
        self.t_prev = t1;
        self.found.sort_by(|a, b| a.0.total_cmp(&b.0));
        // The run ends at the first terminal event, if any: outputs after it are not reached.
        let end = self
            .found
            .iter()
            .find(|&&(_, i)| self.events[i].action == Action::Terminate)
            .map_or(t1, |&(root, _)| root);
        if self.dense {
            let mut view = DenseView {
                stepper: &mut *stepper,
                problem,
                t0,
                t1: end,
                step_end: t1,
                end: &*state,
                scratch: &mut *scratch,
            };
            if observer.dense_step(&mut view) == Flow::Stop {
                return AfterStep::Stopped;
            }
        }
        while let Some(&t) = self.outputs.get(self.next_output) {
            if t > end {
                break;
            }
            self.next_output += 1;
            let flow = if t == t1 {
                observer.output(t, state)
            } else {
                stepper.interpolate(problem, t, scratch);
                observer.output(t, scratch)
            };
            if flow == Flow::Stop {
                return AfterStep::Stopped;
            }
        }
        for &(root, i) in &self.found {
            stepper.interpolate(problem, root, scratch);
            report.events.push(EventRecord {
                index: i,
                t: root,
                state: scratch.clone(),
            });
            if self.events[i].action == Action::Terminate {
                state.copy_from(scratch);
                report.status = Status::Terminated(i);
                return AfterStep::Terminated(root);
            }
        }
        AfterStep::Go
    }
}

/// Root of `g(t, u(t))` on `[t0, t1]` (sign change given) by the Illinois method
/// ([`crate::roots::illinois`]) on the dense output `u`.
fn locate<P: ?Sized, St>(
    stepper: &mut St,
    problem: &P,
    g: &dyn Fn(f64, &St::State) -> f64,
    t0: f64,
    g0: f64,
    t1: f64,
    g1: f64,
    scratch: &mut St::State,
) -> f64
where
    St: DenseOutput<P>,
{
    crate::roots::illinois(
        |c| {
            stepper.interpolate(problem, c, scratch);
            g(c, scratch)
        },
        t0,
        g0,
        t1,
        g1,
    )
}
