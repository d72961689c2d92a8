//! `armlab-classroom [--listen ADDR] [--port P] [--dist DIR] [--redis URL]`: serves the
//! page and the lecture room's relay.

use armlab_classroom::{Config, start};

#[tokio::main]
async fn main() -> std::process::ExitCode {
    let config = match Config::from_args(std::env::args().skip(1)) {
        Ok(config) => config,
        Err(e) => {
            eprintln!("{e}");
            return std::process::ExitCode::from(2);
        }
    };
    let redis = config.redis.clone();
    match start(config).await {
        Ok(running) => {
            let shared = redis
                .map(|r| format!(", classes shared through {r}"))
                .unwrap_or_default();
            println!("ArmLab classroom on {}{shared}", running.http_url("/"));
            std::future::pending::<()>().await;
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("cannot start: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
