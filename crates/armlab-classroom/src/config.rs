//! The server's settings: from the command line, with the durations and limits a test
//! shortens.

use std::net::{IpAddr, Ipv4Addr};
use std::path::PathBuf;
use std::time::Duration;

/// How the server runs.
#[derive(Clone)]
pub struct Config {
    /// The address to listen on (`127.0.0.1` unless `--listen`; `0.0.0.0` behind a proxy).
    pub listen: IpAddr,
    /// The port (`--port`, 8080 by default; 0 picks a free one).
    pub port: u16,
    /// The built page to serve at `/` (`--dist`), if any.
    pub dist: Option<PathBuf>,
    /// Redis to share classes with other instances (`--redis redis://HOST:PORT`).
    pub redis: Option<String>,
    /// A class without a lecturer connected for this long ends (1 h).
    pub expiry: Duration,
    /// How often expired classes are looked for (and Redis keys of live ones renewed).
    pub sweep: Duration,
    /// How often a connection is pinged (20 s); one that has answered nothing for two of
    /// these is let go, so that a laptop shut mid-class (its socket never closed) stops
    /// counting as a student within a minute.
    pub heartbeat: Duration,
    /// Messages a second a lecturer may send (the burst is one second's worth).
    pub lecturer_rate: f64,
    /// Messages a second a student (or a connection not yet in a class) may send.
    pub student_rate: f64,
    /// Failed joins (unknown code, wrong token) one address may make in a burst…
    pub join_failures: f64,
    /// …and how many more it earns a second.
    pub join_refill: f64,
    /// The most classes one instance holds.
    pub max_classes: usize,
    /// Whether to take the client's address from `X-Forwarded-For` (`--behind-proxy`:
    /// only when a reverse proxy that sets it is the only way in).
    pub behind_proxy: bool,
    /// The key lecturer tokens are derived from (`--secret-file`: read, or made and kept
    /// there). With one, a token is the HMAC of its class's code, so after a restart only
    /// the class's own lecturer can re-create it; without one, tokens are random and the
    /// first `Resume` of a code lost in a restart takes it.
    pub secret: Option<[u8; 32]>,
    /// Where the secret is kept (loaded by [`start`](crate::start)).
    pub secret_file: Option<PathBuf>,
}

impl std::fmt::Debug for Config {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // Every setting but the secret's bytes.
        f.debug_struct("Config")
            .field("listen", &self.listen)
            .field("port", &self.port)
            .field("dist", &self.dist)
            .field("redis", &self.redis)
            .field("expiry", &self.expiry)
            .field("secret", &self.secret.map(|_| "set"))
            .field("secret_file", &self.secret_file)
            .finish_non_exhaustive()
    }
}

impl Default for Config {
    fn default() -> Self {
        Self {
            listen: IpAddr::V4(Ipv4Addr::LOCALHOST),
            port: 8080,
            dist: None,
            redis: None,
            expiry: Duration::from_secs(3600),
            sweep: Duration::from_secs(30),
            heartbeat: Duration::from_secs(20),
            lecturer_rate: 30.0,
            student_rate: 5.0,
            join_failures: 20.0,
            join_refill: 0.5,
            max_classes: 10_000,
            behind_proxy: false,
            secret: None,
            secret_file: None,
        }
    }
}

/// The command line's usage line.
pub const USAGE: &str = "usage: armlab-classroom [--listen ADDR] [--port P] [--dist DIR] [--redis redis://HOST:PORT] [--behind-proxy] [--secret-file PATH] [--expiry-secs S] [--heartbeat-secs S]";

/// The secret in `path`, or a new one written there (readable by its owner only).
pub fn load_or_create_secret(path: &std::path::Path) -> std::io::Result<[u8; 32]> {
    match std::fs::read(path) {
        Ok(bytes) => bytes
            .get(..32)
            .and_then(|b| b.try_into().ok())
            .ok_or_else(|| {
                std::io::Error::other(format!(
                    "{}: a secret file holds 32 bytes or more",
                    path.display()
                ))
            }),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let secret = crate::server::random_bytes::<32>();
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir)?;
            }
            let mut options = std::fs::OpenOptions::new();
            options.write(true).create_new(true);
            #[cfg(unix)]
            std::os::unix::fs::OpenOptionsExt::mode(&mut options, 0o600);
            std::io::Write::write_all(&mut options.open(path)?, &secret)?;
            Ok(secret)
        }
        Err(e) => Err(e),
    }
}

impl Config {
    /// The settings from command-line arguments (without the program's name).
    pub fn from_args(args: impl IntoIterator<Item = String>) -> Result<Self, String> {
        let mut config = Self::default();
        let mut args = args.into_iter();
        while let Some(arg) = args.next() {
            let mut value = |name: &str| args.next().ok_or_else(|| format!("{name} needs a value"));
            match arg.as_str() {
                "--listen" => {
                    let v = value("--listen")?;
                    config.listen = v
                        .parse()
                        .map_err(|_| format!("--listen {v}: not an IP address"))?;
                }
                "--port" => {
                    let v = value("--port")?;
                    config.port = v.parse().map_err(|_| format!("--port {v}: not a port"))?;
                }
                "--dist" => config.dist = Some(PathBuf::from(value("--dist")?)),
                "--redis" => config.redis = Some(value("--redis")?),
                "--expiry-secs" => {
                    config.expiry = seconds("--expiry-secs", &value("--expiry-secs")?)?
                }
                "--heartbeat-secs" => {
                    config.heartbeat = seconds("--heartbeat-secs", &value("--heartbeat-secs")?)?
                        .max(Duration::from_secs(1));
                }
                "--behind-proxy" => config.behind_proxy = true,
                "--secret-file" => {
                    config.secret_file = Some(PathBuf::from(value("--secret-file")?))
                }
                other => return Err(format!("unknown argument {other}\n{USAGE}")),
            }
        }
        Ok(config)
    }
}

/// A whole number of seconds given to option `name`.
fn seconds(name: &str, v: &str) -> Result<Duration, String> {
    v.parse()
        .map(Duration::from_secs)
        .map_err(|_| format!("{name} {v}: not a number"))
}
