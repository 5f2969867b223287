//! The cases of the bit-for-bit check (issue 82), with their native answers: every shipped
//! preset under every method its scene offers, then `N` presets made from them at random
//! (each parameter of the scene's table moved by up to ±10 %, a random method), each run over
//! a shortened horizon. Prints a JSON array of `{name, toml, csv}` for
//! `scripts/web_trajectories.mjs`, which runs each `toml` in the module and compares its CSV
//! with `csv` character by character. The seed is printed (standard error) so a failure can be
//! run again:
//!   cargo run --release -p rattleback-web --example trajectories -- [SEED] [N] > cases.json

use rattleback::physics::method::Method;
use rattleback::scenario::Preset;
use rattleback::scenario::shipped::SHIPPED;
use rattleback_web::trajectory::csv;

/// Samples of each CSV.
const SAMPLES: u32 = 64;

/// The shortened horizon: a fifth of the preset's, at most `cap`.
fn shortened(t_end: f64, cap: f64) -> f64 {
    (t_end / 5.0).min(cap)
}

/// `splitmix64`: enough for choosing cases, the same everywhere.
struct Draw(u64);

impl Draw {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[-1, 1)`.
    fn signed(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn below(&mut self, n: usize) -> usize {
        usize::try_from(self.next() % n as u64).unwrap_or(0)
    }
}

fn case(name: &str, preset: &Preset) -> serde_json::Value {
    let toml = preset.to_toml();
    let csv = csv(&toml, SAMPLES);
    serde_json::json!({ "name": name, "toml": toml, "csv": csv })
}

/// `preset` with `method` over the shortened horizon (the method's default step; a fixed-step
/// method's horizon a tenth of `cap`, its default steps being many).
fn with_method(preset: &Preset, method: Method, cap: f64) -> Preset {
    let cap = if method.is_fixed_step() {
        cap / 10.0
    } else {
        cap
    };
    let mut p = preset.clone();
    p.run.method = Some(method);
    p.run.step = None;
    p.run.t_end = shortened(p.run.t_end, cap);
    p
}

fn main() {
    let mut args = std::env::args().skip(1);
    let seed = args.next().and_then(|s| s.parse().ok()).unwrap_or_else(|| {
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(1, |d| d.as_secs())
    });
    let generated: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(24);
    eprintln!(
        "trajectories: seed {seed}, {generated} generated presets (again: -- {seed} {generated})"
    );
    let shipped: Vec<Preset> = SHIPPED
        .iter()
        .map(|(name, text)| Preset::parse(text, name, name, &[]).expect("a shipped preset parses"))
        .collect();
    let mut cases = Vec::new();
    for (preset, (name, _)) in shipped.iter().zip(SHIPPED) {
        for &method in preset.model.kind().methods() {
            let p = with_method(preset, method, 4.0);
            cases.push(case(&format!("{name} {method}"), &p));
        }
    }
    let mut draw = Draw(seed);
    for i in 0..generated {
        let base = &shipped[draw.below(shipped.len())];
        let mut model = base.model;
        for spec in model.kind().params() {
            let Some(v) = model.value(spec.key) else {
                continue;
            };
            let moved = if v == 0.0 {
                0.05 * draw.signed()
            } else {
                v * (1.0 + 0.1 * draw.signed())
            };
            if let Ok(m) = model.with_value(spec.key, moved) {
                model = m;
            }
        }
        let methods = base.model.kind().methods();
        let method = methods[draw.below(methods.len())];
        let mut p = with_method(base, method, 2.0);
        p.model = model;
        cases.push(case(
            &format!("generated {i} (seed {seed}) from {} {method}", base.name),
            &p,
        ));
    }
    println!("{}", serde_json::Value::Array(cases));
}
