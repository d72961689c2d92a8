//! The lecture room's protocol: what the lecturer's page, the students' pages and the
//! classroom server say to each other over one WebSocket each, as typed JSON messages
//! (`{"type": "...", ...}`), with the limits every field must keep. No I/O and no clock:
//! the page (wasm) and the server (natively) share this crate.
//!
//! # Messages
//!
//! Client → server ([`ClientMessage`]), decoded by the server with [`decode_client`]:
//!
//! | message | from | the server's answer |
//! |---|---|---|
//! | `Create` | lecturer | `Created {code, token}`: a new class; the token is the control |
//! | `Resume {code, token, state}` | lecturer | `Created {code, token}` again: the class with that code and token (re-created when the server lost it, e.g. after a restart; `Refused {reason: "CodeTaken"}` when another token holds the code) |
//! | `State {state}` | lecturer | `State {state}` to every student (coalesced: a slow student skips to the latest) |
//! | `Ask {question}` | lecturer | `Question {question}` to every student; answers start from zero |
//! | `Reveal {question, truth}` | lecturer | `Revealed {question, truth, values}` to everyone |
//! | `End` | lecturer | `Ended` to everyone; the class is gone |
//! | `Join {code, nickname}` | student | `Joined {state, question}` (the current state at once) or `Refused {reason}` |
//! | `Answer {question, value}` | student | nothing to the student; `Answers {question, values, count}` to the lecturer (coalesced: at most ten a second) |
//!
//! Server → clients ([`ServerMessage`]), decoded by the page with [`decode_server`]:
//! `Created`, `Joined`, `Refused {reason}`, `State {state}`, `Count {students}`,
//! `Question {question}`, `Answers {question, values, count}`, `Revealed {question, truth,
//! values}`, `Ended`, `Dropped {reason}`. Reasons are kinds ([`Refusal`], [`DropReason`]), never
//! English: the page words them in the person's language.
//!
//! A connection is a lecturer after `Create` or `Resume` with the right token, a student
//! after `Join`; anything else it sends before is dropped. Only the lecturer drives
//! (`State`, `Ask`, `Reveal`, `End` from a student are dropped and never forwarded);
//! students send `Answer` only, one per question (the last counts).
//!
//! # Limits
//!
//! A client message is at most [`MAX_CLIENT_BYTES`] (64 KiB), checked before parsing;
//! unknown fields and wrong types are errors; numbers are finite and bounded; texts are
//! cut and cleaned as the app's messages are (`armlab_text::echo`). [`State`] is opaque to
//! the server: the page's share-link fragment and camera, printable ASCII of bounded
//! length. Join codes are [`CODE_LEN`] characters of [`CODE_ALPHABET`]; lecturer tokens are
//! [`TOKEN_LEN`] lowercase hex digits (128 bits), compared with [`tokens_equal`] in
//! constant time.

mod decode;
mod ids;
mod message;
mod page;
mod qr;

pub use decode::{
    DecodeError, Field, MAX_CLIENT_BYTES, MAX_SERVER_BYTES, decode_client, decode_server,
};
pub use ids::{
    CODE_ALPHABET, CODE_LEN, TOKEN_LEN, is_code, is_token, normalize_code, tokens_equal,
};
pub use message::{
    Answer, ClientMessage, DropReason, MAX_CAMERA_BYTES, MAX_CHOICE_CHARS, MAX_LINK_BYTES,
    MAX_NICKNAME_CHARS, MAX_NUMBER, MAX_OPTIONS, MAX_POINT_METRES, MAX_PROMPT_CHARS,
    MAX_UNIT_CHARS, Question, Refusal, ServerMessage, State,
};
pub use page::read_server;
pub use qr::QrModules;
