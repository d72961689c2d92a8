//! The join link's QR code (`armlab_room::QrModules`): made at once natively; in the page
//! by the lazily loaded module (dist/urdf/), so that the page's own wasm holds no QR
//! encoder.

use std::rc::Rc;

use armlab_room::QrModules;

/// The QR code of `text`: natively at once; in the page the first call for a text asks
/// the module and answers `None` until its answer is there (the frame is woken then).
/// `None` too when the text is too long for a QR code, or the module failed to load.
pub fn qr_code(text: &str) -> Option<Rc<QrModules>> {
    #[cfg(target_arch = "wasm32")]
    {
        super::web::modules::qr_code(text)
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        QrModules::encode(text).map(Rc::new)
    }
}
