//! The server's decoding, fuzzed: 1,000,000 generated messages (valid messages mutated —
//! flipped bytes, cuts, huge and NaN-ish numbers, deep nesting, long strings, unknown
//! fields, wrong types, splices — and random bytes) through `decode_client`: none panics.
//! Prints the count, the time and the slowest decode with its first bytes. Seeded, so a
//! failure repeats.

use armlab_room::{Answer, ClientMessage, MAX_CLIENT_BYTES, Question, State, decode_client};
use std::time::{Duration, Instant};

/// Messages generated.
const MESSAGES: usize = 1_000_000;

/// xorshift64* (Vigna): small and seeded.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn seeds() -> Vec<Vec<u8>> {
    let state = State {
        link: "robot=ur10&q=0,-1.57,1.2,0,0.5,0&task=pose".into(),
        camera: Some("cam=1,2,3".into()),
    };
    let choice = Question::Choice {
        id: 3,
        prompt: "Which branch?".into(),
        options: vec!["up".into(), "down".into()],
    };
    [
        ClientMessage::Create {},
        ClientMessage::End {},
        ClientMessage::Resume {
            code: "ABCD2345".into(),
            token: "0123456789abcdef0123456789abcdef".into(),
            state: state.clone(),
        },
        ClientMessage::State { state },
        ClientMessage::Ask {
            question: Question::Point {
                id: 1,
                prompt: "Where?".into(),
            },
        },
        ClientMessage::Ask {
            question: Question::Number {
                id: 2,
                prompt: "det J".into(),
                unit: Some("m".into()),
            },
        },
        ClientMessage::Ask { question: choice },
        ClientMessage::Reveal {
            question: 1,
            truth: Answer::Point {
                at: [0.5, -0.25, 1.0],
            },
        },
        ClientMessage::Join {
            code: "ABCD2345".into(),
            nickname: Some("Aino".into()),
        },
        ClientMessage::Answer {
            question: 2,
            value: Answer::Number { value: -0.125 },
        },
        ClientMessage::Answer {
            question: 3,
            value: Answer::Choice { index: 1 },
        },
    ]
    .iter()
    .map(|m| m.to_json().into_bytes())
    .collect()
}

const NUMBERS: [&str; 12] = [
    "1e309",
    "-1e308",
    "NaN",
    "Infinity",
    "-0",
    "1e-400",
    "0x10",
    "18446744073709551616",
    "4294967296",
    "-1",
    "1.5",
    "00001",
];
const VALUES: [&str; 8] = [
    "null",
    "true",
    "[]",
    "{}",
    "\"s\"",
    "[1,2,3]",
    "{\"type\":\"End\"}",
    "\"\\ud800\"",
];

/// `with` inserted into `message` at `at` (slices copied whole: fast in a debug build too).
fn splice(message: &mut Vec<u8>, at: usize, with: &[u8]) {
    let at = at.min(message.len());
    let mut out = Vec::with_capacity(message.len() + with.len());
    out.extend_from_slice(&message[..at]);
    out.extend_from_slice(with);
    out.extend_from_slice(&message[at..]);
    *message = out;
}

/// The long pieces, made once: brackets to nest in and bytes of a long string.
struct Pieces {
    open: Vec<u8>,
    close: Vec<u8>,
    long: Vec<Vec<u8>>,
}

impl Pieces {
    fn new() -> Self {
        let long = b"a\\u00e4\"x"
            .iter()
            .map(|&b| vec![b; 2 * MAX_CLIENT_BYTES])
            .collect();
        Self {
            open: vec![b'['; 40_000],
            close: vec![b']'; 40_000],
            long,
        }
    }
}

/// One mutation of `message`.
fn mutate(rng: &mut Rng, message: &mut Vec<u8>, seeds: &[Vec<u8>], pieces: &Pieces) {
    let at = rng.below(message.len() + 1);
    match rng.below(9) {
        0 => {
            if let Some(b) = message.get_mut(at) {
                *b ^= 1 << rng.below(8);
            }
        }
        1 => message.truncate(at),
        2 => splice(message, at, NUMBERS[rng.below(NUMBERS.len())].as_bytes()),
        3 => {
            let most = if rng.below(10) == 0 { 40_000 } else { 200 };
            let depth = 1 + rng.below(most);
            let mut nested = Vec::with_capacity(message.len() + 2 * depth);
            nested.extend_from_slice(&pieces.open[..depth]);
            nested.extend_from_slice(message);
            nested.extend_from_slice(&pieces.close[..depth]);
            *message = nested;
        }
        4 => {
            let most = if rng.below(10) == 0 {
                2 * MAX_CLIENT_BYTES
            } else {
                300
            };
            let len = rng.below(most);
            let long = &pieces.long[rng.below(pieces.long.len())];
            splice(message, at, &long[..len]);
        }
        5 => splice(message, 1, b"\"zz\":1,"),
        6 => splice(message, at, VALUES[rng.below(VALUES.len())].as_bytes()),
        7 => {
            let other = &seeds[rng.below(seeds.len())];
            let from = rng.below(other.len());
            splice(message, at, &other[from..]);
        }
        _ => {
            let len = rng.below(64);
            *message = (0..len).map(|_| rng.next() as u8).collect();
        }
    }
}

#[test]
fn a_million_generated_messages_decode_without_a_panic() {
    let seeds = seeds();
    let pieces = Pieces::new();
    let mut rng = Rng(0x5eed_c1a5_5700_0001);
    let (mut decoded, mut panics) = (0usize, 0usize);
    let mut slowest = (Duration::ZERO, 0, Vec::new());
    let start = Instant::now();
    let mut decoding = Duration::ZERO;
    for _ in 0..MESSAGES {
        let mut message = seeds[rng.below(seeds.len())].clone();
        for _ in 0..1 + rng.below(3) {
            mutate(&mut rng, &mut message, &seeds, &pieces);
        }
        let t = Instant::now();
        let result = std::panic::catch_unwind(|| decode_client(&message));
        let took = t.elapsed();
        decoding += took;
        match result {
            Ok(Ok(_)) => decoded += 1,
            Ok(Err(_)) => {}
            Err(_) => panics += 1,
        }
        if took > slowest.0 {
            slowest = (
                took,
                message.len(),
                message.iter().take(60).copied().collect::<Vec<u8>>(),
            );
        }
    }
    println!(
        "fuzz: {MESSAGES} messages in {:.1} s ({:.1} s decoding), {decoded} decoded, {panics} panics; slowest {:.3} ms, {} bytes: {:?}",
        start.elapsed().as_secs_f64(),
        decoding.as_secs_f64(),
        slowest.0.as_secs_f64() * 1e3,
        slowest.1,
        String::from_utf8_lossy(&slowest.2)
    );
    assert_eq!(panics, 0);
    assert!(
        decoded > MESSAGES / 100,
        "the mutations leave some messages valid: {decoded}"
    );
}
