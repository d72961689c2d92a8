//! A page that vanishes without closing its socket (a laptop shut mid-class) is let go
//! after two silent heartbeats, and the lecturer's count drops.

use crate::support::{self, WAIT};
use armlab_room::{ClientMessage, ServerMessage};
use std::time::Duration;

#[tokio::test]
async fn a_student_whose_page_went_silent_is_let_go_and_no_longer_counted() {
    let mut config = support::config();
    config.heartbeat = Duration::from_millis(300);
    let running = support::server(config).await;
    let (mut lecturer, code, _) = support::lecturer(&running).await;
    // The silent one is never read again after joining: its client answers no ping.
    let (_silent, _) = support::student(&running.ws_url(), &code).await;
    let (mut awake, _) = support::student(&running.ws_url(), &code).await;
    // The lecturer and the awake student read (and so answer pings) for five beats.
    let span = Duration::from_millis(1500);
    let (heard, _) = tokio::join!(lecturer.listen_for(span), awake.listen_for(span));
    let counts: Vec<u32> = heard
        .iter()
        .filter_map(|m| match m {
            ServerMessage::Count { students } => Some(*students),
            _ => None,
        })
        .collect();
    assert!(counts.contains(&2), "both were counted first: {counts:?}");
    assert_eq!(
        counts.last(),
        Some(&1),
        "the silent one is let go: {counts:?}"
    );
    // The lecturer and the student who answered pings are still in the class.
    lecturer
        .send(&ClientMessage::State {
            state: support::state(7),
        })
        .await;
    let followed = tokio::time::timeout(
        WAIT,
        awake.recv_until(|m| matches!(m, ServerMessage::State { .. }).then_some(())),
    )
    .await;
    assert!(followed.is_ok(), "the awake student follows the lecturer");
}
