//! Structure-aware fuzzing on stable Rust: a seeded generator of hostile inputs for the
//! robot-file parser, the link-hash parser and the JSON API, and the one function that
//! feeds an input to its parser ([`Case::run`]). The `fuzz` binary runs millions of cases
//! with a clock and `catch_unwind`; `tests/fuzz.rs` replays the saved corpus
//! (`tests/fuzz_corpus.json`) and a few thousand seeded cases, natively and as wasm.
//!
//! An input starts from something valid (a preset's file, a real request, a real link)
//! and is then mutated at the level of its structure — a node replaced by nested junk, a
//! huge or tiny number, NaN or infinity spelled one of many ways, a value of the wrong
//! type, 64 or more joints, a duplicated key, a very long string — and at the level of
//! its text (cut short, a byte flipped, a stray quote or brace).

use serde_json::{Map, Value, json};

use armlab_core::presets::{preset, preset_ids};
use armlab_core::rng::SplitMix64;
use armlab_session::session::{Session, percent_encode};
use armlab_text::{Lang, Sentence};

/// Which parser a case goes to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Target {
    /// `robot_from_json`: a robot file.
    RobotFile,
    /// `Session::from_hash`: a link's hash.
    Link,
    /// `api::fk`.
    Fk,
    /// `api::jacobian`.
    Jacobian,
    /// `api::ik`.
    Ik,
    /// `api::robot`.
    Robot,
}

impl Target {
    /// Every target.
    pub const ALL: [Target; 6] = [
        Target::RobotFile,
        Target::Link,
        Target::Fk,
        Target::Jacobian,
        Target::Ik,
        Target::Robot,
    ];

    /// The target's name in reports and in the corpus.
    pub fn name(self) -> &'static str {
        match self {
            Target::RobotFile => "robot_file",
            Target::Link => "link",
            Target::Fk => "fk",
            Target::Jacobian => "jacobian",
            Target::Ik => "ik",
            Target::Robot => "robot",
        }
    }

    /// The target of a name.
    pub fn from_name(name: &str) -> Option<Target> {
        Target::ALL.into_iter().find(|t| t.name() == name)
    }
}

/// One input for one parser.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The parser.
    pub target: Target,
    /// The text it gets.
    pub input: String,
}

/// What a case gave: `Ok` with the response's size, or the error's sentence.
pub type Outcome = Result<usize, String>;

impl Case {
    /// Feeds the input to its parser: the response's length, or the error's English
    /// sentence. A panic propagates (the binary catches it; a test fails on it).
    pub fn run(&self) -> Outcome {
        let text = self.input.as_str();
        match self.target {
            Target::RobotFile => armlab_core::robot_from_json(text)
                .map(|r| r.dof())
                .map_err(|e| e.sentence(Lang::En)),
            Target::Link => Session::from_hash(text)
                .map(|s| s.map_or(0, |s| s.q.len()))
                .map_err(|e| e.to_string()),
            Target::Fk => armlab_api::fk(text)
                .map(|s| s.len())
                .map_err(|e| e.to_string()),
            Target::Jacobian => armlab_api::jacobian(text)
                .map(|s| s.len())
                .map_err(|e| e.to_string()),
            Target::Ik => armlab_api::ik(text)
                .map(|s| s.len())
                .map_err(|e| e.to_string()),
            Target::Robot => armlab_api::robot(text)
                .map(|s| s.len())
                .map_err(|e| e.to_string()),
        }
    }
}

/// What is wrong with a message by the readability rules every message keeps, if anything: more
/// than 60 characters of one repeated character (a person's long text repeated whole),
/// a control character, a run of more than 40 digits (a number written out in full, or
/// more of the person's text than the 40 characters a message may echo), or more than
/// 600 characters in all.
pub fn unreadable(message: &str) -> Option<String> {
    if message.chars().any(char::is_control) {
        return Some("a control character".into());
    }
    if message.chars().count() > 600 {
        return Some(format!("{} characters", message.chars().count()));
    }
    let digits = message
        .split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0);
    if digits > 40 {
        return Some(format!("a number of {digits} digits"));
    }
    let mut run = 0;
    let mut last = None;
    for c in message.chars() {
        run = if Some(c) == last { run + 1 } else { 1 };
        last = Some(c);
        if run > 60 {
            return Some(format!("{c:?} repeated over 60 times"));
        }
    }
    None
}

/// The numbers a fuzzer tries: huge, tiny, negative zero, and just past the limits.
const NUMBERS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    1e-300,
    5e-324,
    -5e-324,
    1e300,
    -1e300,
    1.7e308,
    -1.7e308,
    f64::MAX,
    f64::MIN,
    1e6,
    1_000_000.000_001,
    -1e6,
    3600.0,
    3_600.000_001,
    1e9,
    1_000_000_001.0,
    1e15,
    9_007_199_254_740_993.0,
    std::f64::consts::PI,
    -std::f64::consts::PI,
    180.0,
    1e-7,
    64.0,
    65.0,
];

/// NaN and infinity spelled every way a person or a program writes them.
const SPELLINGS: &[&str] = &[
    "NaN",
    "nan",
    "-NaN",
    "Infinity",
    "-Infinity",
    "+Infinity",
    "inf",
    "-inf",
    "INF",
    "1e999",
    "-1e999",
    "1e309",
    "∞",
    "-∞",
    "1/0",
    "0x7ff8000000000000",
    "1.#INF",
    "1.#QNAN",
    "null",
    "undefined",
    "1e-999",
    "00",
    "-",
    ".",
    "1e",
    "1.2.3",
    "+1",
    "１",
];

/// Junk strings: control characters, escapes, bidi overrides, long runs.
const STRINGS: &[&str] = &[
    "",
    " ",
    "\u{0}",
    "\u{7}\u{1b}[2J",
    "a\nb\rc\td",
    "\u{202E}gnp.exe",
    "\u{FEFF}",
    "\"",
    "\\",
    "%",
    "%zz",
    "%C3%28",
    "%00",
    "&",
    "=",
    "#",
    "standard",
    "modified",
    "revolute",
    "prismatic",
    "mm",
    "m",
    "ur10",
    "custom",
    "full",
    "closed",
    "position",
    "axis-z",
    "gradient",
    "numerical",
    "𝕦𝕣𝟙𝟘",
    "é",
];

/// The generator: a seeded source of cases.
#[derive(Debug, Clone)]
pub struct Generator {
    rng: SplitMix64,
    presets: Vec<(String, Value)>,
    /// IK iteration counts up to `u64::MAX` (capped by the API at 100 000); off for the
    /// test command's seeded cases (at most 100), whose IK must stay fast in debug builds.
    large_counts: bool,
}

impl Generator {
    /// A generator drawing from `seed`.
    pub fn new(seed: u64) -> Self {
        let presets = preset_ids()
            .filter_map(|id| {
                let robot = preset(id).ok()?;
                let file = serde_json::from_str(&armlab_core::robot_to_json(&robot)).ok()?;
                Some((id.to_string(), file))
            })
            .collect();
        Generator {
            rng: SplitMix64::new(seed),
            presets,
            large_counts: true,
        }
    }

    /// [`Generator::new`] with IK iteration counts of at most 100 (the test command's
    /// seeded cases: fast in a debug build and as wasm).
    pub fn with_small_counts(seed: u64) -> Self {
        Generator {
            large_counts: false,
            ..Generator::new(seed)
        }
    }

    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.rng.next_u64() % n as u64) as usize
        }
    }

    fn chance(&mut self, p: f64) -> bool {
        self.rng.next_f64() < p
    }

    fn pick<'a, T>(&mut self, list: &'a [T]) -> &'a T {
        &list[self.below(list.len())]
    }

    /// The next case: a target (IK a little rarer, it is the slowest) and its input.
    pub fn case(&mut self) -> Case {
        // IK (up to 100 000 iterations a call) is 1 case in 25, so that millions of cases
        // fit in minutes.
        let target = match self.below(100) {
            0..=22 => Target::RobotFile,
            23..=45 => Target::Link,
            46..=64 => Target::Fk,
            65..=83 => Target::Jacobian,
            84..=95 => Target::Robot,
            _ => Target::Ik,
        };
        let input = match target {
            Target::RobotFile => {
                let file = self.robot_file();
                self.finish(file)
            }
            Target::Link => self.link(),
            Target::Fk | Target::Jacobian | Target::Robot | Target::Ik => {
                let request = self.request(target);
                self.finish(request)
            }
        };
        Case { target, input }
    }

    /// A number: mostly from [`NUMBERS`], sometimes random over many magnitudes.
    fn number(&mut self) -> f64 {
        if self.chance(0.6) {
            *self.pick(NUMBERS)
        } else {
            let exponent = self.rng.uniform(-320.0, 308.0);
            let sign = if self.chance(0.5) { -1.0 } else { 1.0 };
            sign * self.rng.next_f64() * 10f64.powf(exponent)
        }
    }

    /// A JSON value of the wrong kind, or nested junk of depth up to `depth`.
    fn junk(&mut self, depth: usize) -> Value {
        match self.below(if depth == 0 { 6 } else { 9 }) {
            0 => Value::Null,
            1 => json!(self.chance(0.5)),
            2 => json!(self.number()),
            3 => json!(*self.pick(STRINGS)),
            4 => json!(self.rng.next_u64()),
            5 => {
                let len = *self.pick(&[100, 1000, 1000, 10_000, 10_000, 100_000]);
                // The opening brace as an escape: the same text.
                json!(self.pick(&["x", "é", "\u{0}", "9", "\u{7b}"]).repeat(len))
            }
            6 => {
                let n = self.below(5);
                Value::Array((0..n).map(|_| self.junk(depth - 1)).collect())
            }
            7 => {
                let mut map = Map::new();
                for _ in 0..self.below(4) {
                    let key = self.pick(STRINGS).to_string();
                    map.insert(key, self.junk(depth - 1));
                }
                Value::Object(map)
            }
            _ => {
                // Deep nesting: 10 to 200 levels of arrays.
                let levels = 10 + self.below(190);
                let mut v = json!(self.number());
                for _ in 0..levels {
                    v = json!([v]);
                }
                v
            }
        }
    }

    /// A preset's robot file, mutated; sometimes with 64 or more joints.
    fn robot_file(&mut self) -> Value {
        let k = self.below(self.presets.len());
        let mut file = self.presets[k].1.clone();
        if self.chance(0.15)
            && let Some(joints) = file.get_mut("joints").and_then(Value::as_array_mut)
            && !joints.is_empty()
        {
            let count = *self.pick(&[63, 64, 65, 100, 1000]);
            let mut grown = Vec::with_capacity(count);
            for i in 0..count {
                grown.push(joints[i % joints.len()].clone());
            }
            *joints = grown;
        }
        let mutations = self.below(4);
        for _ in 0..mutations {
            self.mutate(&mut file, 0);
        }
        file
    }

    /// Replaces one node somewhere below `value` (depth-first, random path).
    fn mutate(&mut self, value: &mut Value, depth: usize) {
        let descend = depth < 6 && self.chance(0.7);
        match value {
            Value::Object(map) if descend && !map.is_empty() => {
                let keys: Vec<String> = map.keys().cloned().collect();
                let key = self.pick(&keys).clone();
                if self.chance(0.1) {
                    map.remove(&key);
                } else if let Some(child) = map.get_mut(&key) {
                    self.mutate(child, depth + 1);
                }
            }
            Value::Array(list) if descend && !list.is_empty() => {
                let i = self.below(list.len());
                match self.below(10) {
                    0 => {
                        list.remove(i);
                    }
                    1 => {
                        let copy = list[i].clone();
                        list.push(copy);
                    }
                    _ => self.mutate(&mut list[i], depth + 1),
                }
            }
            _ => {
                *value = match self.below(4) {
                    0 => json!(self.number()),
                    1 => json!(*self.pick(SPELLINGS)),
                    _ => self.junk(3),
                };
            }
        }
    }

    /// A request for one of the JSON API's functions, mutated.
    fn request(&mut self, target: Target) -> Value {
        let k = self.below(self.presets.len());
        let (id, file) = self.presets[k].clone();
        let dof = file["joints"].as_array().map_or(6, Vec::len);
        let robot = if self.chance(0.7) { json!(id) } else { file };
        let q: Vec<f64> = (0..dof)
            .map(|_| {
                if self.chance(0.8) {
                    self.rng.uniform(-3.0, 3.0)
                } else {
                    self.number()
                }
            })
            .collect();
        let mut request = json!({"robot": robot});
        if self.chance(0.9) {
            request["q"] = json!(q);
        }
        if matches!(target, Target::Jacobian | Target::Ik) && self.chance(0.8) {
            request["task"] =
                json!(*self.pick(&["position", "axis-x", "axis-y", "axis-z", "full", "FULL"]));
        }
        if target == Target::Ik {
            request["target"] = self.ik_target(dof);
            request["method"] =
                json!(*self.pick(&["dls", "pinv", "gradient", "closed", "closed-form", "newton"]));
            if self.chance(0.2) {
                request["drag"] = json!(true);
            }
            if self.chance(0.1) {
                request["alpha"] = json!(self.number());
            }
            if self.chance(0.2) {
                request["jacobian"] = json!("numerical");
            }
            if self.chance(0.5) {
                request["settings"] = self.settings();
            }
        }
        let mutations = self.below(3);
        for _ in 0..mutations {
            self.mutate(&mut request, 0);
        }
        request
    }

    fn ik_target(&mut self, dof: usize) -> Value {
        match self.below(4) {
            0 => json!({"q": (0..dof).map(|_| self.rng.uniform(-2.0, 2.0)).collect::<Vec<_>>()}),
            1 => json!({"position": [self.number(), self.number(), self.number()]}),
            2 => {
                let p = [
                    self.rng.uniform(-1500.0, 1500.0),
                    self.rng.uniform(-1500.0, 1500.0),
                    self.rng.uniform(-1500.0, 1500.0),
                ];
                json!({"position": p, "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]})
            }
            _ => json!([
                [1, 0, 0, self.number()],
                [0, 0, -1, 200],
                [0, 1, 0, 300],
                [0, 0, 0, 1]
            ]),
        }
    }

    fn settings(&mut self) -> Value {
        let mut s = Map::new();
        let counts: &[u64] = if self.large_counts {
            &[0, 1, 5, 100, 10_000, 10_000_000, u64::MAX]
        } else {
            &[0, 1, 5, 100]
        };
        for key in ["max_iterations", "budget", "restarts", "seed"] {
            if self.chance(0.3) {
                s.insert(key.into(), json!(*self.pick(counts)));
            }
        }
        for key in [
            "position_tolerance",
            "orientation_tolerance",
            "max_joint_change",
        ] {
            if self.chance(0.2) {
                s.insert(key.into(), json!(self.number()));
            }
        }
        if self.chance(0.1) {
            s.insert("trace".into(), json!(true));
        }
        Value::Object(s)
    }

    /// A link hash: real parts with hostile values, sometimes a custom robot's table.
    fn link(&mut self) -> String {
        let mut parts: Vec<String> = Vec::new();
        let k = self.below(self.presets.len());
        let (id, file) = self.presets[k].clone();
        if self.chance(0.2) {
            parts.push("robot=custom".into());
            let mut file = file.clone();
            if self.chance(0.5) {
                self.mutate(&mut file, 0);
            }
            parts.push(format!("dh={}", percent_encode(&file.to_string())));
        } else if self.chance(0.95) {
            parts.push(format!("robot={id}"));
        }
        let dof = file["joints"].as_array().map_or(6, Vec::len);
        for _ in 0..self.below(8) {
            let part = match self.below(13) {
                0 | 1 => format!("q={}", self.numbers_text(dof)),
                2 => format!("target={}", self.numbers_text(6)),
                3 => format!("camera={}", self.numbers_text(6)),
                4 => format!("task={}", self.word()),
                5 => format!("method={}", self.word()),
                6 => format!(
                    "{}={}",
                    self.pick(&[
                        "units", "frames", "decimals", "present", "lang", "panels", "ppanels"
                    ]),
                    self.word()
                ),
                7 => self.word(),
                8 => format!("dh={}", self.word()),
                9 => format!("{}={}", self.word(), self.word()),
                10 => "&&&".into(),
                11 => format!("q={}", "9".repeat(1 + self.below(5000))),
                _ => format!("robot={}", self.word()),
            };
            parts.push(part);
        }
        let mut hash = format!("#{}", parts.join("&"));
        self.text_mutation(&mut hash);
        hash
    }

    fn numbers_text(&mut self, n: usize) -> String {
        let n = if self.chance(0.2) { self.below(70) } else { n };
        (0..n)
            .map(|_| {
                if self.chance(0.2) {
                    self.pick(SPELLINGS).to_string()
                } else {
                    format!("{}", self.number())
                }
            })
            .collect::<Vec<_>>()
            .join(",")
    }

    fn word(&mut self) -> String {
        match self.below(4) {
            0 => self.pick(SPELLINGS).to_string(),
            1 => "w".repeat(1 + self.below(2000)),
            _ => self.pick(STRINGS).to_string(),
        }
    }

    /// The JSON text of `value`, sometimes with a duplicated key, and mutated as text.
    fn finish(&mut self, value: Value) -> String {
        let mut text = value.to_string();
        if self.chance(0.15) {
            // A duplicate key: repeat the first `"key":value` pair of the top object.
            if let Some(obj) = value.as_object()
                && let Some((key, v)) = obj.iter().next()
            {
                let pair = format!("{}:{},", Value::String(key.clone()), self.junk(1));
                let _ = v;
                text.insert_str(1, &pair);
            }
        }
        self.text_mutation(&mut text);
        text
    }

    /// Sometimes cuts the text short, flips a byte, or inserts a stray character.
    fn text_mutation(&mut self, text: &mut String) {
        match self.below(10) {
            0 => {
                let cut = self.below(text.len() + 1);
                let mut cut = cut;
                while !text.is_char_boundary(cut) {
                    cut -= 1;
                }
                text.truncate(cut);
            }
            1 => {
                let at = self.below(text.len() + 1);
                let mut at = at;
                while !text.is_char_boundary(at) {
                    at -= 1;
                }
                let stray = *self.pick(&[
                    "\"", "{", "}", "[", "]", ",", ":", "\\", "\u{0}", "%", "&", "=",
                ]);
                text.insert_str(at, stray);
            }
            2 => {
                // Replace one number in the text by a spelling of NaN or infinity.
                if let Some(at) = text.find(|c: char| c.is_ascii_digit()) {
                    let end = text[at..]
                        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
                        .map_or(text.len(), |e| at + e);
                    let spelling = *self.pick(SPELLINGS);
                    text.replace_range(at..end, spelling);
                }
            }
            _ => {}
        }
    }
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    #[test]
    fn the_generator_is_seeded_and_reaches_every_target() {
        let a: Vec<Case> = {
            let mut g = Generator::new(7);
            (0..200).map(|_| g.case()).collect()
        };
        let b: Vec<Case> = {
            let mut g = Generator::new(7);
            (0..200).map(|_| g.case()).collect()
        };
        assert_eq!(a, b);
        for target in Target::ALL {
            assert!(a.iter().any(|c| c.target == target), "{target:?}");
            assert_eq!(Target::from_name(target.name()), Some(target));
        }
    }

    #[test]
    fn unreadable_names_what_is_wrong() {
        assert_eq!(unreadable("The value 5 of joint 1 lies outside."), None);
        assert_eq!(
            unreadable("a\u{7}b").as_deref(),
            Some("a control character")
        );
        assert_eq!(
            unreadable(&format!("is {}", "9".repeat(301))).as_deref(),
            Some("a number of 301 digits")
        );
        assert!(unreadable(&"x".repeat(61)).is_some());
    }
}
