//! The registry of named screen points the browser tests and the UI tests read.

/// Named screen points (egui points, window coordinates) for
/// `window.armlab.screenPoint` and the UI tests: every panel writes the points it draws
/// into this one registry, which is emptied at the start of each frame.
#[derive(Debug, Clone, Default)]
pub struct ScreenPoints {
    points: Vec<(String, [f32; 2])>,
}

impl ScreenPoints {
    /// Forgets last frame's points.
    pub fn clear(&mut self) {
        self.points.clear();
    }

    /// Records a point by name.
    pub fn insert(&mut self, name: impl Into<String>, at: egui::Pos2) {
        self.points.push((name.into(), [at.x, at.y]));
    }

    /// A named point drawn this frame, if visible.
    pub fn get(&self, name: &str) -> Option<[f32; 2]> {
        self.points.iter().find(|(n, _)| n == name).map(|(_, p)| *p)
    }

    /// Every point, in the order drawn.
    pub fn all(&self) -> &[(String, [f32; 2])] {
        &self.points
    }
}
