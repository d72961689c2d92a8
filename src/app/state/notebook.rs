//! The lecture notebook's two runs as one-click demos (docs/kinematics.md §8.7): on the
//! planar 2R from θ = (0.1, 0.1), Newton–Raphson to (1.5, 1.5) never wrapping θ, and
//! gradient descent on F = ‖e‖² with α = 0.01 to (1.0, 1.5). The panel shows the raw
//! answer (the notebook's printed digits) beside the wrapped one, and the error per
//! iteration.

use nalgebra::{Matrix3, Vector3};

use armlab_core::ik::target_pose;
use armlab_core::{IkMethod, IkResult, IkSettings, Objective, Task, preset};

use crate::app::state::model::Model;
use armlab_session::session::RobotSource;

/// One of the notebook's runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NotebookDemo {
    /// `θ += solve(J, e)` until ‖e‖ < 1e−10, never wrapping θ.
    Newton,
    /// `θ −= α·2Jᵀ(f − t)`, α = 0.01, until ‖∇F‖ < 1e−10 or 1000 iterations.
    Gradient,
}

impl NotebookDemo {
    /// The target position (the planar 2R's plane, metres).
    pub fn target(self) -> [f64; 2] {
        match self {
            NotebookDemo::Newton => [1.5, 1.5],
            NotebookDemo::Gradient => [1.0, 1.5],
        }
    }

    /// The method as ArmLab names it.
    pub fn method(self) -> IkMethod {
        match self {
            NotebookDemo::Newton => IkMethod::PseudoInverse,
            NotebookDemo::Gradient => IkMethod::JacobianTranspose { alpha: Some(0.01) },
        }
    }

    /// The settings that reproduce the notebook: no restarts, its tolerance, its
    /// iteration count; Newton never wraps, the gradient is of ‖e‖² (not ½‖e‖²).
    pub fn settings(self) -> IkSettings {
        let base = IkSettings {
            position_tolerance: 1e-10,
            max_iterations: 1000,
            budget: 1000,
            restarts: 0,
            record_trace: true,
            ..IkSettings::default()
        };
        match self {
            NotebookDemo::Newton => IkSettings {
                wrap: false,
                ..base
            },
            NotebookDemo::Gradient => IkSettings {
                objective: Objective::Squared,
                ..base
            },
        }
    }

    /// What the notebook printed.
    pub fn printed(self) -> &'static str {
        match self {
            NotebookDemo::Newton => "[-5.9844821 20.54568008]",
            NotebookDemo::Gradient => "[0.46058393 2.0236129]",
        }
    }

    /// Sets the model up as the notebook starts (planar 2R, θ = (0.1, 0.1), the target,
    /// position task, the method) and runs it; `None` if the preset could not be loaded.
    pub fn run(self, model: &mut Model) -> Option<IkResult> {
        let robot = preset("planar-2r").ok()?;
        model.load_robot(robot, RobotSource::Preset("planar-2r".to_string()));
        model.set_q_exact(vec![0.1, 0.1]);
        model.set_task(Task::Position);
        model.set_method(self.method());
        let [x, y] = self.target();
        model.set_target(target_pose(Vector3::new(x, y, 0.0), Matrix3::identity()));
        model.solve_with_settings(&self.settings())
    }
}
