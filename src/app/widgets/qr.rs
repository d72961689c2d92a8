//! A QR code drawn as large as the room allows: light quiet zone, dark modules merged into
//! one rectangle per run in a row (a 29-module code is a few dozen shapes).

/// Modules of light margin around the code, as the QR standard asks.
const QUIET: usize = 4;
/// The largest side drawn, in points: from the back of a lecture hall a projected code
/// needs size more than sharpness.
const MAX_SIDE: f32 = 560.0;

/// Draws the QR code of `text` (made by the platform: at once natively, by the lazy
/// module in the page; a spinner until it is there).
pub fn show(ui: &mut egui::Ui, text: &str) {
    let Some(code) = crate::app::platform::qr::qr_code(text) else {
        ui.spinner();
        return;
    };
    let room = ui.available_size();
    let screen = ui.ctx().content_rect().size();
    let side = room.x.min(screen.y * 0.55).clamp(120.0, MAX_SIDE);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(side, side), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 0.0, egui::Color32::WHITE);
    let modules = code.width + 2 * QUIET;
    let size = side / modules as f32;
    for (y, row) in code.dark.chunks(code.width.max(1)).enumerate() {
        let top = rect.top() + (y + QUIET) as f32 * size;
        let mut x = 0;
        while x < row.len() {
            if !row[x] {
                x += 1;
                continue;
            }
            let start = x;
            while x < row.len() && row[x] {
                x += 1;
            }
            let left = rect.left() + (start + QUIET) as f32 * size;
            let run = egui::Rect::from_min_size(
                egui::pos2(left, top),
                egui::vec2((x - start) as f32 * size, size),
            );
            painter.rect_filled(run.expand(0.25), 0.0, egui::Color32::BLACK);
        }
    }
}
