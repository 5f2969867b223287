//! The small headless commands: `presets` (the catalogue) and `check` (validate files).
//! Output goes to stdout, problems to stderr; exit 2 on any problem.

use std::fmt::Write as _;
use std::process::ExitCode;

use crate::cli::{CheckArgs, ListFormat, PresetsArgs};
use crate::scenario::PresetError;
use crate::scenario::preset;
use crate::scenario::shipped::catalogue;
use crate::scenario::theme::ThemeSpec;

/// Untrusted text (names, descriptions, echoed values) never reaches a terminal raw: every line
/// printed goes through `clean`.
macro_rules! say {
    ($($t:tt)*) => { println!("{}", crate::scenario::text::clean(&format!($($t)*))) };
}
macro_rules! say_err {
    ($($t:tt)*) => { eprintln!("{}", crate::scenario::text::clean(&format!($($t)*))) };
}
macro_rules! say_raw {
    ($($t:tt)*) => { print!("{}", crate::scenario::text::clean(&format!($($t)*))) };
}

/// `rattleback presets`.
#[must_use]
pub fn presets(args: &PresetsArgs) -> ExitCode {
    let (entries, problems) = catalogue();
    let out = match args.format {
        ListFormat::Json => {
            let mut s = serde_json::to_string_pretty(&entries).unwrap_or_else(|_| "[]".to_owned());
            s.push('\n');
            s
        }
        ListFormat::Table => {
            let mut s = String::new();
            for e in &entries {
                let _ = writeln!(
                    s,
                    "{:<16} {:<8} {}\n                 {}\n                 {}\n",
                    e.name,
                    format!("{:?}", e.source).to_lowercase(),
                    e.title,
                    e.path,
                    e.description
                );
            }
            s
        }
    };
    say_raw!("{out}");
    report(&problems)
}

fn report(problems: &[PresetError]) -> ExitCode {
    for p in problems {
        say_err!("rattleback: {p}");
    }
    if problems.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    }
}

/// Whether a file is a theme rather than a preset.
fn is_theme(src: &str) -> bool {
    src.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("theme") || t.contains_key("colors"))
}

/// `rattleback bench`.
#[must_use]
pub fn bench(args: &crate::cli::BenchArgs) -> ExitCode {
    use crate::bench;
    let config = bench::Config { quick: args.quick };
    if let Err(e) = std::fs::create_dir_all(&args.out) {
        say_err!("rattleback: error: {}: {e}", args.out.display());
        return ExitCode::from(2);
    }
    let rows = bench::work_precision(config, &mut |line| say_err!("{line}"));
    say_raw!("{}", bench::table(&rows));
    say!("");
    if rows.iter().any(|r| r.method.starts_with("peer-")) {
        say!("{}", bench::peer_summary(&rows, 1e-8));
    }
    for k in [1e4, 1e8] {
        say_raw!("{}", bench::terminal_diagram(&rows, k, 72, 16));
    }
    let csv = args.out.join("work_precision.csv");
    let svg = args.out.join("work_precision.svg");
    if let Err(e) = bench::write_csv(&rows, &csv) {
        say_err!("rattleback: error: {}: {e}", csv.display());
        return ExitCode::from(1);
    }
    if let Err(e) = bench::write_svg(&rows, &svg) {
        say_err!("rattleback: error: {}: {e}", svg.display());
        return ExitCode::from(1);
    }
    say!(
        "\nauto at every stiffness (T = 30, tolerance 1e-8; errors against tests/fixtures/reference/averaged.toml)"
    );
    let profile = bench::profile(config.quick, &mut |line| say_err!("{line}"));
    say_raw!("{}", bench::profile_table(&profile));
    let profile_csv = args.out.join("auto_profile.csv");
    if let Err(e) = bench::write_profile_csv(&profile, &profile_csv) {
        say_err!("rattleback: error: {}: {e}", profile_csv.display());
        return ExitCode::from(1);
    }
    let stability = bench::stability(config);
    say!("\nStability\n{}", bench::stability_table(&stability));
    let path = args.out.join("stability.csv");
    if let Err(e) = bench::write_stability_csv(&stability, &path) {
        say_err!("rattleback: error: {}: {e}", path.display());
        return ExitCode::from(1);
    }
    say!(
        "wrote {}, {}, {}, {}",
        csv.display(),
        svg.display(),
        profile_csv.display(),
        path.display()
    );
    ExitCode::SUCCESS
}

/// `rattleback check FILE...`.
#[must_use]
pub fn check(args: &CheckArgs) -> ExitCode {
    let mut problems = Vec::new();
    for path in &args.files {
        let label = path.display().to_string();
        // Bounded, regular files only (a FIFO or /dev/zero is refused, not read), and an
        // encoding error names its line.
        match PresetError::read(path) {
            Err(e) => problems.push(e),
            Ok(src) if is_theme(&src) => {
                if let Err(mut e) = ThemeSpec::parse(&src, &label, &label) {
                    problems.append(&mut e);
                }
            }
            Ok(src) => problems.extend(preset::check(&src, &label)),
        }
    }
    if problems.is_empty() {
        say!("{} file(s) ok", args.files.len());
    }
    report(&problems)
}
