//! The controls and the style the panels share: the DH table editor, a number field's
//! draft, a matrix's numbers drawn as one mesh, the hand-drawn plot, colours and text
//! sizes.

pub mod contrast;
pub mod dh_table;
pub mod draft;
pub mod math;
pub mod numbers;
pub mod plot;
pub mod qr;
pub mod style;
pub mod toggles;
