//! The classroom server: serves the built page and relays the lecturer's page to the
//! students' pages over WebSockets, with questions and their answers (the protocol:
//! `armlab-room`, docs/classroom.md). Standalone it keeps classes in memory; with Redis
//! (`--redis`) several instances share them (docs/deploying.md).
//!
//! Nothing here enters the page: the page uses `armlab-room` alone.

pub mod bus;
pub mod class;
pub mod config;
mod conn;
pub mod http;
pub mod limit;
pub mod server;

pub use config::Config;
pub use server::Server;

use axum::serve::ListenerExt;
use std::net::SocketAddr;
use std::sync::Arc;
use tokio::task::JoinHandle;

/// A running server.
#[derive(Debug)]
pub struct Running {
    /// The address it listens on (with the port picked for port 0).
    pub addr: SocketAddr,
    /// The server (its classes and counters).
    pub server: Arc<Server>,
    tasks: Vec<JoinHandle<()>>,
}

impl Running {
    /// The WebSocket URL.
    pub fn ws_url(&self) -> String {
        format!("ws://{}/classroom/ws", self.addr)
    }

    /// The HTTP URL of `path`.
    pub fn http_url(&self, path: &str) -> String {
        format!("http://{}{path}", self.addr)
    }

    /// Stops the server: the listener closes and every connection with it.
    pub fn stop(self) {
        self.server.shutdown.send_replace(true);
        for task in &self.tasks {
            task.abort();
        }
    }
}

/// Starts a server with `config` (binding its address and port, connecting to Redis when
/// it names one) and returns once it listens.
pub async fn start(mut config: Config) -> std::io::Result<Running> {
    if config.secret.is_none()
        && let Some(path) = &config.secret_file
    {
        config.secret = Some(config::load_or_create_secret(path)?);
    }
    let instance = u64::from_le_bytes(server::random_bytes::<8>());
    let bus = match &config.redis {
        Some(url) => Some(
            bus::Bus::connect(url, instance)
                .await
                .map_err(|e| std::io::Error::other(format!("Redis at {url}: {e}")))?,
        ),
        None => None,
    };
    let listener = tokio::net::TcpListener::bind((config.listen, config.port)).await?;
    let addr = listener.local_addr()?;
    // Each message goes out at once: Nagle's algorithm would hold a state back until the
    // previous one is acknowledged (up to 40 ms of delayed ACK on Linux).
    let listener = listener.tap_io(|tcp| {
        let _ = tcp.set_nodelay(true);
    });
    let sweep = config.sweep;
    let server = Arc::new(Server::new(config, bus.clone(), instance));
    let app = http::router(server.clone()).into_make_service_with_connect_info::<SocketAddr>();
    let mut tasks = vec![tokio::spawn(async move {
        let _ = axum::serve(listener, app).await;
    })];
    if let Some(bus) = bus {
        tasks.push(tokio::spawn(bus.listen(Arc::downgrade(&server))));
    }
    let weak = Arc::downgrade(&server);
    tasks.push(tokio::spawn(async move {
        let mut tick = tokio::time::interval(sweep);
        loop {
            tick.tick().await;
            let Some(server) = weak.upgrade() else { return };
            server.sweep().await;
        }
    }));
    Ok(Running {
        addr,
        server,
        tasks,
    })
}
