//! The classroom server under load: one lecturer sends 20 states a second (a share link of
//! about 300 bytes) to N students (1,000 by default), all on loopback. Prints JSON: the
//! fan-out latency from the lecturer's send to the last student's copy (p50, p99, max per
//! update), the server's CPU (from /proc/PID/stat when it runs the server as a child), its
//! memory per student (RSS before and after the students joined) and the messages a
//! second delivered.
//!
//! ```sh
//! cargo build --release -p armlab-classroom -p armlab-bench --features armlab-bench/classroom
//! target/release/classroomload [--students N] [--seconds S] [--rate R] [--url ws://HOST:PORT/classroom/ws]
//! ```
//!
//! Without `--url` it starts `armlab-classroom` from its own folder on a free port.

use armlab_room::{ClientMessage, ServerMessage, State, decode_server};
use futures_util::{SinkExt, StreamExt};
use std::time::{Duration, Instant};
use tokio::io::AsyncBufReadExt;
use tokio_tungstenite::tungstenite::Message;

struct Args {
    students: usize,
    seconds: f64,
    rate: f64,
    url: Option<String>,
}

fn args() -> Args {
    let mut args = Args {
        students: 1000,
        seconds: 10.0,
        rate: 20.0,
        url: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let value = it.next().unwrap_or_default();
        match arg.as_str() {
            "--students" => args.students = value.parse().unwrap_or(args.students),
            "--seconds" => args.seconds = value.parse().unwrap_or(args.seconds),
            "--rate" => args.rate = value.parse().unwrap_or(args.rate),
            "--url" => args.url = Some(value),
            _ => eprintln!("ignored: {arg}"),
        }
    }
    args
}

/// A share link as the page writes it while the lecturer drags (~300 bytes), numbered.
fn link(seq: u32) -> State {
    let t = f64::from(seq) * 0.01;
    State {
        link: format!(
            "robot=ur10&q={:.4},-1.5708,1.2000,{:.4},0.5000,0.0000&target=0.6123,-0.1734,0.4411,0.0000,3.1416,0.{seq:04}\
             &task=pose&method=dls&lambda=0.05&display=frames,ghost,ellipsoid,path&panels=robot,joints,matrices,jacobian\
             &hidden=t06,j&units=deg&lang=en&overlay=cloud&seq={seq}",
            t.sin(),
            t.cos()
        ),
        camera: Some(format!("cam=0.5,0.3,3.0,0.0,0.0,{:.3}", t.sin())),
    }
}

/// The server's (utime + stime) in clock ticks and RSS in bytes, from /proc.
fn proc_usage(pid: u32) -> Option<(u64, u64)> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let fields: Vec<&str> = stat.rsplit(')').next()?.split_whitespace().collect();
    let ticks = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let rss_kb: u64 = status
        .lines()
        .find(|l| l.starts_with("VmRSS:"))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()?;
    Some((ticks, rss_kb * 1024))
}

/// Starts the server next to this binary on a free port: (child, WebSocket URL).
async fn start_server() -> Result<(tokio::process::Child, String), String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let server = exe.with_file_name("armlab-classroom");
    let mut child = tokio::process::Command::new(&server)
        .args(["--port", "0"])
        .stdout(std::process::Stdio::piped())
        .kill_on_drop(true)
        .spawn()
        .map_err(|e| {
            format!(
                "{}: {e} (build it: cargo build --release -p armlab-classroom)",
                server.display()
            )
        })?;
    let stdout = child.stdout.take().ok_or("no stdout")?;
    let mut lines = tokio::io::BufReader::new(stdout).lines();
    let line = lines
        .next_line()
        .await
        .map_err(|e| e.to_string())?
        .ok_or("the server said nothing")?;
    let http = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .ok_or(line.clone())?;
    let url = format!("{}classroom/ws", http.replacen("http://", "ws://", 1));
    Ok((child, url))
}

type Socket =
    tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

async fn connect(url: &str) -> Socket {
    for _ in 0..50 {
        if let Ok((ws, _)) = tokio_tungstenite::connect_async_with_config(url, None, true).await {
            return ws;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    panic!("cannot connect to {url}");
}

/// A state's number straight from the frame's text: the students' side must not be the
/// bottleneck it measures (decoding 20,000 messages a second on the same 2 cores).
fn state_seq(text: &str) -> Option<u32> {
    if !text.starts_with("\u{7b}\"type\":\"State\"") {
        return None;
    }
    let digits = text.rsplit("seq=").next()?;
    let end = digits
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(digits.len());
    digits[..end].parse().ok()
}

async fn next(ws: &mut Socket) -> Option<ServerMessage> {
    while let Some(Ok(frame)) = ws.next().await {
        if let Message::Text(text) = frame {
            return decode_server(&text).ok();
        }
    }
    None
}

/// A student: joins, then records when each state arrived until `stop`.
async fn student(
    url: String,
    code: String,
    joined: tokio::sync::mpsc::Sender<()>,
) -> Vec<(u32, Instant)> {
    let mut ws = connect(&url).await;
    let join = ClientMessage::Join {
        code,
        nickname: None,
    }
    .to_json();
    if ws.send(Message::text(join)).await.is_err() {
        return Vec::new();
    }
    let mut got = Vec::new();
    while let Some(Ok(frame)) = ws.next().await {
        let Message::Text(text) = frame else { continue };
        if let Some(seq) = state_seq(&text) {
            got.push((seq, Instant::now()));
            continue;
        }
        let Ok(message) = decode_server(&text) else {
            continue;
        };
        match message {
            ServerMessage::Joined { .. } => {
                let _ = joined.send(()).await;
            }
            ServerMessage::Ended {} => break,
            _ => {}
        }
    }
    got
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// Per update: the time from its send until every student had it or a later one.
fn latencies(sent: &[Instant], received: &[Vec<(u32, Instant)>]) -> (Vec<f64>, usize) {
    let mut worst = vec![Duration::ZERO; sent.len()];
    let mut missing = vec![false; sent.len()];
    for got in received {
        let mut next = got.iter().rev().peekable();
        let mut first_at_least: Option<Instant> = None;
        for seq in (0..sent.len()).rev() {
            while let Some(&&(s, at)) = next.peek() {
                if s as usize >= seq {
                    first_at_least = Some(first_at_least.map_or(at, |f: Instant| f.min(at)));
                    next.next();
                } else {
                    break;
                }
            }
            match first_at_least {
                Some(at) => worst[seq] = worst[seq].max(at.saturating_duration_since(sent[seq])),
                None => missing[seq] = true,
            }
        }
    }
    let mut ms: Vec<f64> = worst
        .iter()
        .zip(&missing)
        .filter(|(_, m)| !**m)
        .map(|(d, _)| d.as_secs_f64() * 1e3)
        .collect();
    ms.sort_by(f64::total_cmp);
    (ms, missing.iter().filter(|m| **m).count())
}

#[tokio::main]
async fn main() {
    let args = args();
    let (child, url) = match &args.url {
        Some(url) => (None, url.clone()),
        None => match start_server().await {
            Ok((child, url)) => (Some(child), url),
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        },
    };
    let pid = child.as_ref().and_then(tokio::process::Child::id);
    let mut lecturer = connect(&url).await;
    let _ = lecturer
        .send(Message::text(ClientMessage::Create {}.to_json()))
        .await;
    let code = loop {
        match next(&mut lecturer).await {
            Some(ServerMessage::Created { code, .. }) => break code,
            Some(_) => {}
            None => panic!("the server closed the lecturer's socket"),
        }
    };
    let rss_before = pid.and_then(proc_usage).map(|u| u.1);
    let (joined_tx, mut joined_rx) = tokio::sync::mpsc::channel(args.students.max(1));
    let join_start = Instant::now();
    let students: Vec<_> = (0..args.students)
        .map(|_| tokio::spawn(student(url.clone(), code.clone(), joined_tx.clone())))
        .collect();
    for _ in 0..args.students {
        let _ = joined_rx.recv().await;
    }
    let join_secs = join_start.elapsed().as_secs_f64();
    let usage_before = pid.and_then(proc_usage);
    run_and_report(
        &args,
        lecturer,
        students,
        pid,
        rss_before,
        usage_before,
        join_secs,
    )
    .await;
    drop(child);
}

/// The lecturer's drag: `seconds × rate` states at `rate` a second; when each was sent.
async fn send_states(args: &Args, lecturer: &mut Socket) -> Vec<Instant> {
    let updates = (args.seconds * args.rate) as u32;
    let mut sent = Vec::with_capacity(updates as usize);
    let mut tick = tokio::time::interval(Duration::from_secs_f64(1.0 / args.rate));
    for seq in 0..updates {
        tick.tick().await;
        sent.push(Instant::now());
        let message = ClientMessage::State { state: link(seq) }.to_json();
        let _ = lecturer.send(Message::text(message)).await;
    }
    sent
}

async fn run_and_report(
    args: &Args,
    mut lecturer: Socket,
    students: Vec<tokio::task::JoinHandle<Vec<(u32, Instant)>>>,
    pid: Option<u32>,
    rss_before: Option<u64>,
    usage_before: Option<(u64, u64)>,
    join_secs: f64,
) {
    let start = Instant::now();
    let sent = send_states(args, &mut lecturer).await;
    let updates = sent.len();
    tokio::time::sleep(Duration::from_secs(1)).await;
    let wall = start.elapsed().as_secs_f64();
    let usage_after = pid.and_then(proc_usage);
    let _ = lecturer
        .send(Message::text(ClientMessage::End {}.to_json()))
        .await;
    let mut received = Vec::new();
    for s in students {
        received.push(
            tokio::time::timeout(Duration::from_secs(10), s)
                .await
                .ok()
                .and_then(Result::ok)
                .unwrap_or_default(),
        );
    }
    let delivered: usize = received.iter().map(Vec::len).sum();
    let (ms, missing) = latencies(&sent, &received);
    // /proc counts CPU time in clock ticks of 1/100 s (USER_HZ on Linux).
    let cpu = match (usage_before, usage_after) {
        (Some((t0, _)), Some((t1, _))) => {
            serde_json::json!((t1 - t0) as f64 / 100.0 / wall * 100.0)
        }
        _ => serde_json::Value::Null,
    };
    let per_student = match (rss_before, usage_before) {
        (Some(before), Some((_, after))) => {
            serde_json::json!((after as f64 - before as f64) / args.students.max(1) as f64)
        }
        _ => serde_json::Value::Null,
    };
    let report = serde_json::json!({
        "students": args.students,
        "updates_sent": updates,
        "update_rate_hz": args.rate,
        "link_bytes": link(0).link.len(),
        "join_all_s": join_secs,
        "fanout_ms": { "p50": percentile(&ms, 0.5), "p99": percentile(&ms, 0.99), "max": percentile(&ms, 1.0) },
        "updates_not_reaching_every_student": missing,
        "server_cpu_percent": cpu,
        "server_rss_before_bytes": rss_before,
        "server_rss_after_bytes": usage_before.map(|u| u.1),
        "server_rss_per_student_bytes": per_student,
        "messages_delivered": delivered,
        "messages_per_s": delivered as f64 / wall,
    });
    println!(
        "{}",
        serde_json::to_string_pretty(&report).unwrap_or_default()
    );
}
