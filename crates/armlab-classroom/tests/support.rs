//! A test client and servers with short durations.

use armlab_classroom::{Config, Running, start};
use armlab_room::{ClientMessage, ServerMessage, State, decode_server};
use futures_util::{SinkExt, StreamExt};
use std::time::Duration;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

/// How long a test waits for a message it expects.
pub const WAIT: Duration = Duration::from_secs(5);

/// A config for tests: a free port, a lecturer limit that lets a burst of 100 states
/// through (the rules' tests use the defaults), quick sweeps.
pub fn config() -> Config {
    Config {
        port: 0,
        lecturer_rate: 1000.0,
        sweep: Duration::from_millis(50),
        ..Config::default()
    }
}

/// A server with `config`.
pub async fn server(config: Config) -> Running {
    start(config).await.expect("the server starts")
}

/// A link fragment as the page writes it, numbered.
pub fn state(n: u32) -> State {
    State {
        link: format!(
            "robot=ur10&q=0,-1.5708,1.2,{n},0.5,0&task=pose&method=dls&display=frames,ghost&seq={n}"
        ),
        camera: Some(format!("cam=0.5,0.3,3,0,0,{n}")),
    }
}

/// One page's WebSocket.
pub struct Client {
    ws: WebSocketStream<MaybeTlsStream<TcpStream>>,
}

impl Client {
    /// Connects to `url`.
    pub async fn connect(url: &str) -> Self {
        let (ws, _) = tokio_tungstenite::connect_async(url)
            .await
            .expect("the WebSocket connects");
        Self { ws }
    }

    /// Sends `message`.
    pub async fn send(&mut self, message: &ClientMessage) {
        self.send_raw(message.to_json()).await;
    }

    /// Sends `text` as it is.
    pub async fn send_raw(&mut self, text: String) {
        self.ws
            .send(Message::text(text))
            .await
            .expect("the message is sent");
    }

    /// The next message (within [`WAIT`]).
    pub async fn recv(&mut self) -> ServerMessage {
        self.try_recv(WAIT)
            .await
            .expect("a message within the wait")
    }

    /// The next message within `wait`, None when none came (or the socket closed).
    pub async fn try_recv(&mut self, wait: Duration) -> Option<ServerMessage> {
        loop {
            let frame = tokio::time::timeout(wait, self.ws.next()).await.ok()??;
            match frame.ok()? {
                Message::Text(text) => {
                    return Some(decode_server(&text).expect("the server's message decodes"));
                }
                Message::Close(_) => return None,
                _ => {}
            }
        }
    }

    /// Skips messages until one `pick` accepts (within [`WAIT`]).
    pub async fn recv_until<T>(&mut self, mut pick: impl FnMut(&ServerMessage) -> Option<T>) -> T {
        let deadline = tokio::time::Instant::now() + WAIT;
        loop {
            let left = deadline.saturating_duration_since(tokio::time::Instant::now());
            let message = self
                .try_recv(left)
                .await
                .expect("the awaited message within the wait");
            if let Some(t) = pick(&message) {
                return t;
            }
        }
    }

    /// Every message within `wait`.
    pub async fn drain(&mut self, wait: Duration) -> Vec<ServerMessage> {
        let mut out = Vec::new();
        while let Some(m) = self.try_recv(wait).await {
            out.push(m);
        }
        out
    }

    /// Every message for `span`, reading (and so answering the server's pings) until then.
    pub async fn listen_for(&mut self, span: Duration) -> Vec<ServerMessage> {
        let end = tokio::time::Instant::now() + span;
        let mut out = Vec::new();
        while let Ok(Some(Ok(frame))) = tokio::time::timeout_at(end, self.ws.next()).await {
            if let Message::Text(text) = frame {
                out.push(decode_server(&text).expect("the server's message decodes"));
            }
        }
        out
    }

    /// Whether the server closed the socket (within [`WAIT`]).
    pub async fn closed(&mut self) -> bool {
        loop {
            match tokio::time::timeout(WAIT, self.ws.next()).await {
                Ok(None | Some(Err(_)) | Some(Ok(Message::Close(_)))) => return true,
                Ok(Some(Ok(_))) => {}
                Err(_) => return false,
            }
        }
    }
}

/// A lecturer's client with a new class: (client, code, token).
pub async fn lecturer(running: &Running) -> (Client, String, String) {
    let mut client = Client::connect(&running.ws_url()).await;
    client.send(&ClientMessage::Create {}).await;
    match client.recv().await {
        ServerMessage::Created { code, token } => (client, code, token),
        other => panic!("Created expected, got {other:?}"),
    }
}

/// A student's client in class `code`, with its `Joined` message.
pub async fn student(url: &str, code: &str) -> (Client, ServerMessage) {
    let mut client = Client::connect(url).await;
    client
        .send(&ClientMessage::Join {
            code: code.into(),
            nickname: None,
        })
        .await;
    let joined = client.recv().await;
    (client, joined)
}

/// The lecturer's next `Count`.
pub async fn count(lecturer: &mut Client) -> u32 {
    lecturer
        .recv_until(|m| match m {
            ServerMessage::Count { students } => Some(*students),
            _ => None,
        })
        .await
}

/// GET `path` from the server: (status, body).
pub async fn get(running: &Running, path: &str) -> (u16, String) {
    let (status, _, body) = get_with(running, path, "").await;
    (status, body)
}

/// GET `path` with the extra header lines `headers` (each ending in CRLF): (status, the
/// response's header lines in lower case, body).
pub async fn get_with(running: &Running, path: &str, headers: &str) -> (u16, String, String) {
    let mut stream = TcpStream::connect(running.addr).await.expect("connects");
    let request = format!(
        "GET {path} HTTP/1.1\r\nHost: {}\r\n{headers}Connection: close\r\n\r\n",
        running.addr
    );
    stream
        .write_all(request.as_bytes())
        .await
        .expect("request sent");
    let mut response = String::new();
    stream
        .read_to_string(&mut response)
        .await
        .expect("response read");
    let status = response
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let (head, body) = response.split_once("\r\n\r\n").unwrap_or_default();
    (status, head.to_lowercase(), body.to_owned())
}
