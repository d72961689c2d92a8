//! The DH exercise's check (`armlab_core::exercise::check_table`): natively at once; in the
//! page by the lazily loaded module (dist/urdf/), so that the page's own wasm holds none of
//! the check and its diagnosis.

use armlab_core::Robot;
use armlab_core::exercise::Verdict;

/// Where a check is: its verdict once made.
pub type Checked = super::Answer<Verdict>;

/// The verdict on `student`'s table against `reference`: natively at once; in the page the
/// first call for the pair asks the module and answers [`Checked::Loading`] until its
/// answer is there (the frame is woken then).
pub fn check_table(reference: &Robot, student: &Robot) -> Checked {
    #[cfg(target_arch = "wasm32")]
    {
        super::web::modules::check_table(reference, student)
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        Checked::Ready(armlab_core::exercise::check_table(reference, student))
    }
}

/// After a failure: the next call asks the module again.
pub fn retry_check() {
    #[cfg(target_arch = "wasm32")]
    super::web::modules::retry_check();
}
