//! The symbolic matrices' tables (`armlab_core::symbolic_tables`): natively made at once;
//! in the page by the lazily loaded module (dist/urdf/), so that the page's own wasm holds
//! none of the symbolic algebra.

use std::rc::Rc;

use armlab_core::Robot;
use armlab_core::symbolic_tables::SymbolicTables;

/// Where a robot's symbolic tables are.
pub type Tables = super::Answer<Rc<SymbolicTables>>;

/// The symbolic tables of `robot`: natively at once; in the page the first call for a
/// robot asks the module and answers [`Tables::Loading`] until its answer is there (the
/// frame is woken then).
pub fn symbolic_tables(robot: &Robot) -> Tables {
    #[cfg(target_arch = "wasm32")]
    {
        super::web::modules::symbolic_tables(robot)
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        Tables::Ready(Rc::new(armlab_core::symbolic_tables::symbolic_tables(
            robot,
        )))
    }
}

/// After a failure: the next call asks the module again.
pub fn retry_symbolic_tables() {
    #[cfg(target_arch = "wasm32")]
    super::web::modules::retry_symbolic_tables();
}

/// For the test hook: `idle`, `loading`, `failed: <the words>`, or `ready: ` and the
/// position column of the last T_0i as plain text, the entries apart by ` | ` (`null`
/// natively, where nothing loads).
pub fn symbolic_state_json() -> serde_json::Value {
    #[cfg(target_arch = "wasm32")]
    {
        serde_json::Value::from(super::web::modules::symbolic_state_text())
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        serde_json::Value::Null
    }
}
