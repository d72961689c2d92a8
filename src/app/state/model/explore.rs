//! The model's explorations around the target: the workspace cloud filled a few
//! milliseconds per frame, and the sphere of tool directions reached at the target's
//! position (docs/kinematics.md §12).

use nalgebra::Vector3;

use armlab_core::ik::IkSettings;
use armlab_core::workspace::{
    DirectionReach, WorkspaceCloud, WorkspaceMeasure, direction_reachability, sphere_directions,
};
use armlab_core::{IkMethod, SplitMix64, Task, ToolAxis, tool_pose};

use super::Model;

/// Which tool directions the arm reaches at one position (docs/kinematics.md §12).
#[derive(Debug, Clone, PartialEq)]
pub struct DirectionSphere {
    robot_changes: u64,
    task: Task,
    /// The position the directions were tested at.
    pub position: Vector3<f64>,
    /// Each direction and whether the 5D task reaches it.
    pub directions: Vec<DirectionReach>,
    /// For each direction, whether the arm reaches the position with its tool axis
    /// within [`DirectionSphere::tolerance`] of it: a 5-axis arm points an axis along a
    /// curve of directions, which a finite lattice never hits exactly; the lattice points
    /// within half their spacing of it draw that curve.
    pub near: Vec<bool>,
    /// Half the lattice's spacing, √(4π/n)/2 (radians).
    pub tolerance: f64,
    /// The axis's directions in position-only solves from random starts that put the
    /// tool at the position: samples of every direction the arm can point the axis at
    /// there (a curve for a 5-axis arm).
    pub samples: Vec<Vector3<f64>>,
}

/// Directions tested on the sphere of [`Model::fill_directions`].
pub const DIRECTION_SAMPLES: usize = 64;

/// The iteration budget of each direction's 5D solve.
const DIRECTION_BUDGET: usize = 300;

impl Model {
    /// Adds workspace samples for at most `budget_ms` (measured with `clock`, the app's
    /// milliseconds), starting a new cloud of `samples` points when the robot or the
    /// measure changed; returns the milliseconds spent.
    pub fn fill_workspace(
        &mut self,
        measure: WorkspaceMeasure,
        samples: usize,
        budget_ms: f64,
        clock: impl Fn() -> f64,
    ) -> f64 {
        let fresh = self
            .workspace
            .as_ref()
            .is_some_and(|(made_for, c)| *made_for == self.robot_changes && c.measure() == measure);
        if !fresh {
            let cloud = WorkspaceCloud::new(&self.robot, measure, samples, 0x5eed);
            self.workspace = Some((self.robot_changes, cloud));
        }
        let start = clock();
        if let Some((_, cloud)) = self.workspace.as_mut() {
            // Slices of 256 samples (about 0.1–0.3 ms each natively) until the budget.
            while !cloud.is_full() && clock() - start < budget_ms {
                cloud.fill(256);
            }
        }
        clock() - start
    }

    /// The tool directions reached at the target's position, as last filled.
    pub fn directions(&self) -> Option<&DirectionSphere> {
        self.directions.as_ref()
    }

    /// Tests [`DIRECTION_SAMPLES`] tool directions at the target's position (the task's
    /// tool axis, else the one nearest the last joint's axis) by a 5D solve each from q,
    /// and samples the axis's direction in as many position-only solves from random
    /// starts, unless the last test was for this robot and task and a position within 1 %
    /// of the reach. Returns the milliseconds spent (`clock` in ms).
    pub fn fill_directions(&mut self, clock: impl Fn() -> f64) -> f64 {
        let start = clock();
        let position = self.target.translation.vector;
        let near = 0.01 * self.robot.reach();
        let fresh = self.directions.as_ref().is_some_and(|d| {
            d.robot_changes == self.robot_changes
                && d.task == self.task
                && (d.position - position).norm() <= near
        });
        if fresh {
            return clock() - start;
        }
        let axis = match self.task {
            Task::PositionAndAxis(axis) => axis,
            _ => self.last_joint_tool_axis(),
        };
        let settings = IkSettings {
            budget: DIRECTION_BUDGET,
            max_iterations: DIRECTION_BUDGET,
            restarts: 0,
            ..IkSettings::default()
        };
        let sphere = sphere_directions(DIRECTION_SAMPLES);
        let directions =
            direction_reachability(&self.robot, &position, axis, &sphere, &self.q, &settings)
                .unwrap_or_default();
        let tolerance = 0.5 * (4.0 * std::f64::consts::PI / DIRECTION_SAMPLES as f64).sqrt();
        let pointing = |q: &[f64]| {
            tool_pose(&self.robot, q)
                .rotation
                .matrix()
                .column(axis.index())
                .into_owned()
        };
        let mut rng = SplitMix64::new(0xd1ec7);
        let mut samples = Vec::with_capacity(DIRECTION_SAMPLES);
        for _ in 0..DIRECTION_SAMPLES {
            let seed = rng.joint_vector(&self.robot);
            let solved = self.solver.solve(
                &self.robot,
                &self.target,
                Task::Position,
                &seed,
                IkMethod::DampedLeastSquares,
                &settings,
            );
            if let Ok(r) = solved
                && r.success
                && r.within_limits
            {
                samples.push(pointing(&r.q));
            }
        }
        let near = directions
            .iter()
            .map(|d| d.reachable || samples.iter().any(|s| s.angle(&d.direction) <= tolerance))
            .collect();
        self.directions = Some(DirectionSphere {
            robot_changes: self.robot_changes,
            task: self.task,
            position,
            directions,
            near,
            tolerance,
            samples,
        });
        clock() - start
    }

    /// The tool axis most nearly along the last joint's axis: the one direction the last
    /// joint cannot turn, so the one whose reachable directions show what the other joints
    /// can do (the Metrover's y). The last column of J's angular rows is that axis in the
    /// base frame (zero for a prismatic joint: then z).
    pub(super) fn last_joint_tool_axis(&self) -> ToolAxis {
        let n = self.robot.dof();
        if n == 0 {
            return ToolAxis::Z;
        }
        let w = Vector3::new(
            self.jacobian[(3, n - 1)],
            self.jacobian[(4, n - 1)],
            self.jacobian[(5, n - 1)],
        );
        let in_tool = self.fk.tool_rotation().transpose() * w;
        let [x, y, z] = [in_tool.x.abs(), in_tool.y.abs(), in_tool.z.abs()];
        if x > y && x > z {
            ToolAxis::X
        } else if y > z {
            ToolAxis::Y
        } else {
            ToolAxis::Z
        }
    }
}
