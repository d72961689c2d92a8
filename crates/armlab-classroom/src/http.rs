//! The HTTP side: the page (the built `dist/`, its `index.html` marked as a classroom
//! server's), `/classroom/hello`, `/classroom/stats`, `/classroom/ws` and
//! `/classroom/{code}/answers.csv`.

use crate::conn::Connection;
use crate::server::Server;
use armlab_room::{Answer, MAX_CLIENT_BYTES};
use axum::Router;
use axum::extract::ws::WebSocketUpgrade;
use axum::extract::{ConnectInfo, Path, Query, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;
use tower_http::services::ServeDir;

/// The largest WebSocket message read at all: beyond it the connection closes. Between
/// the protocol's limit and this one a message is read, dropped and counted.
pub const MAX_FRAME_BYTES: usize = 1024 * 1024;

/// The read buffer of a WebSocket.
const SOCKET_BUFFER_BYTES: usize = 4096;

/// The routes, with the page served from `dist` when the server has one: a file's copy
/// compressed ahead (`NAME.br`, `NAME.gz`, which the page's release build writes beside
/// each file) goes to a browser that accepts its encoding, brotli first (about a fifth
/// smaller than gzip for the wasm).
pub fn router(server: Arc<Server>) -> Router {
    let dist = server.config.dist.clone();
    let router = Router::new()
        .route("/", get(page))
        .route("/index.html", get(page))
        .route("/classroom/hello", get(hello))
        .route("/classroom/stats", get(stats))
        .route("/classroom/ws", get(ws))
        .route("/classroom/{code}/answers.csv", get(csv))
        .with_state(server);
    match dist {
        Some(dist) => {
            router.fallback_service(ServeDir::new(dist).precompressed_br().precompressed_gzip())
        }
        None => router,
    }
}

fn json(body: String) -> Response {
    (
        [
            (header::CONTENT_TYPE, "application/json"),
            (header::CACHE_CONTROL, "no-store"),
        ],
        body,
    )
        .into_response()
}

/// The mark a classroom server's page carries in its `<head>`: the page shows the lecture
/// room only where it finds it. A static host's page has none and asks nothing (a
/// request it answered with "not found" would be a console error on every visit).
pub const PAGE_MARK: &str = r#"<meta name="armlab-classroom" content="1">"#;

/// The page's `index.html` with [`PAGE_MARK`] before its `<title>` (the built page is
/// minified: its `<head>` tag is left out, as HTML allows), or at its end.
pub fn marked_page(html: &str) -> String {
    match html.find("<title") {
        Some(at) => format!("{}{PAGE_MARK}{}", &html[..at], &html[at..]),
        None => format!("{html}{PAGE_MARK}"),
    }
}

async fn page(State(server): State<Arc<Server>>) -> Response {
    let Some(dist) = &server.config.dist else {
        return StatusCode::NOT_FOUND.into_response();
    };
    match tokio::fs::read_to_string(dist.join("index.html")).await {
        Ok(html) => (
            [
                (header::CONTENT_TYPE, "text/html; charset=utf-8"),
                (header::CACHE_CONTROL, "no-cache"),
            ],
            marked_page(&html),
        )
            .into_response(),
        Err(_) => StatusCode::NOT_FOUND.into_response(),
    }
}

async fn hello() -> Response {
    json(serde_json::json!({ "classroom": true, "protocol": 1, "ws": "/classroom/ws" }).to_string())
}

async fn stats(State(server): State<Arc<Server>>) -> Response {
    json(server.stats.to_json(server.class_count()))
}

/// The client's address: the socket's, or behind a trusted proxy the last hop of
/// `X-Forwarded-For` (the one the proxy added).
fn client_ip(server: &Server, addr: SocketAddr, headers: &HeaderMap) -> IpAddr {
    if server.config.behind_proxy
        && let Some(ip) = headers
            .get("x-forwarded-for")
            .and_then(|v| v.to_str().ok())
            .and_then(|v| v.rsplit(',').next())
            .and_then(|v| v.trim().parse().ok())
    {
        return ip;
    }
    addr.ip()
}

async fn ws(
    upgrade: WebSocketUpgrade,
    ConnectInfo(addr): ConnectInfo<SocketAddr>,
    headers: HeaderMap,
    State(server): State<Arc<Server>>,
) -> Response {
    let ip = client_ip(&server, addr, &headers);
    // Small buffers: tungstenite's defaults (128 KiB each way) would cost a lecture of
    // 1,000 students a quarter of a gigabyte; its messages are a few hundred bytes, and
    // each is flushed as it is sent.
    upgrade
        .read_buffer_size(SOCKET_BUFFER_BYTES)
        .write_buffer_size(0)
        .max_message_size(MAX_FRAME_BYTES)
        .max_frame_size(MAX_FRAME_BYTES.max(MAX_CLIENT_BYTES))
        .on_upgrade(move |socket| Connection::new(server, ip).run(socket))
}

async fn csv(
    Path(code): Path<String>,
    Query(query): Query<HashMap<String, String>>,
    ConnectInfo(addr): ConnectInfo<SocketAddr>,
    headers: HeaderMap,
    State(server): State<Arc<Server>>,
) -> Response {
    let ip = client_ip(&server, addr, &headers);
    if !server.joins.allowed(ip) {
        return StatusCode::TOO_MANY_REQUESTS.into_response();
    }
    let bearer = headers
        .get(header::AUTHORIZATION)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.strip_prefix("Bearer "));
    let token = bearer
        .or(query.get("token").map(String::as_str))
        .unwrap_or_default();
    let class = server.class(&code).filter(|c| c.token_is(token));
    let Some(class) = class else {
        server.joins.failed(ip);
        return StatusCode::FORBIDDEN.into_response();
    };
    let body = answers_csv(&class.asked());
    let disposition = format!("attachment; filename=\"armlab-{}.csv\"", class.code);
    (
        [
            (header::CONTENT_TYPE, "text/csv; charset=utf-8".to_owned()),
            (header::CONTENT_DISPOSITION, disposition),
        ],
        body,
    )
        .into_response()
}

/// The answers as CSV: one row per answer (no student, no name, no time), and the truth
/// in a row of its own once revealed. Columns: question, kind, truth (1 on the truth's
/// row), x, y, z (points, metres), number, choice (an option's index).
pub fn answers_csv(asked: &[crate::class::Asked]) -> String {
    let mut out = String::from("question,kind,truth,x,y,z,number,choice\n");
    for a in asked {
        let (id, kind) = (a.question.id(), a.question.kind_name());
        let rows = a
            .answers
            .values()
            .map(|v| (0, v))
            .chain(a.truth.iter().map(|t| (1, t)));
        for (truth, value) in rows {
            let cells = match value {
                Answer::Point { at: [x, y, z] } => format!("{x},{y},{z},,"),
                Answer::Number { value } => format!(",,,{value},"),
                Answer::Choice { index } => format!(",,,,{index}"),
            };
            let _ = writeln!(out, "{id},{kind},{truth},{cells}");
        }
    }
    out
}
