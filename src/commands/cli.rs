//! Command-line arguments: parsed raw by clap, with values checked as they are parsed so a bad
//! flag gets a specific message and exit code 2.

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::physics::Method;
use crate::scenario::preset::{Override, TOLERANCE_RANGE};
use crate::scenario::shipped::DEFAULT_PRESET;

/// Explore the holonomic rattleback: spin reversals and the stiff-spring limit.
///
/// The explorer's flags go before nothing else: `rattleback --preset NAME simulate` is refused
/// (each subcommand takes its own `--preset`).
#[derive(Debug, Parser)]
#[command(
    name = "rattleback",
    version,
    about = "Explore the holonomic rattleback, Kapitza's pendulum and the celt",
    long_about = None,
    args_conflicts_with_subcommands = true,
    // One line: the explorer's flags, or a command (they do not mix).
    override_usage = "rattleback [OPTIONS] | rattleback <COMMAND>",
    after_help = crate::commands::manual::after_help()
)]
pub struct Cli {
    /// What to do; without a command, the explorer opens.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Preset: a name (`rattleback presets`) or a file
    #[arg(long, value_name = "NAME|PATH")]
    pub preset: Option<String>,
    /// How the explorer draws.
    #[command(flatten)]
    pub look: LookArgs,
    /// Mouse on: a click sets the start, the wheel zooms
    #[arg(long)]
    pub mouse: bool,
    /// Recording.
    #[command(flatten)]
    pub rec: RecordArgs,
    /// Use FILE as config.toml (before or after a command)
    #[arg(long, global = true, value_name = "FILE")]
    pub config: Option<std::path::PathBuf>,
}

/// The command line's grammar: [`Cli`] with each subcommand's examples at the end of its help
/// (as ripgrep and fd show theirs); the parser, the manual and the completions all read it.
#[must_use]
pub fn command() -> clap::Command {
    use clap::CommandFactory as _;
    let mut cmd = Cli::command();
    for (name, examples) in crate::commands::manual::SUBCOMMAND_EXAMPLES {
        cmd = cmd.mut_subcommand(*name, |sub| {
            sub.after_help(crate::commands::manual::examples_text(examples))
        });
    }
    cmd
}

/// Parses `args` (the program's name first) with [`command`].
pub fn parse_from<I, T>(args: I) -> Result<Cli, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    use clap::FromArgMatches as _;
    let mut cmd = command();
    let matches = cmd.try_get_matches_from_mut(args)?;
    Cli::from_arg_matches(&matches).map_err(|e| e.format(&mut cmd))
}

/// For `rattleback --preset X simulate …`, refused because a subcommand takes its own flags:
/// the same words with the flags moved after the command's name
/// (`rattleback simulate --preset X …`). `None` when no flag comes before a command.
#[must_use]
pub fn flags_after_command(args: &[std::ffi::OsString]) -> Option<String> {
    let words: Vec<String> = args
        .iter()
        .skip(1)
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let cmd = command();
    let at = words
        .iter()
        .position(|w| cmd.get_subcommands().any(|s| s.get_name() == w))?;
    if at == 0 || !words[0].starts_with('-') {
        return None;
    }
    let mut out = vec!["rattleback".to_owned(), words[at].clone()];
    out.extend(words[..at].iter().cloned());
    out.extend(words[at + 1..].iter().cloned());
    Some(
        out.iter()
            .map(|w| crate::scenario::text::shell_word(w))
            .collect::<Vec<_>>()
            .join(" "),
    )
}

/// How the explorer records: `--record FILE [--force] [--sign KEYFILE]`.
#[derive(Debug, Args, Clone)]
pub struct RecordArgs {
    /// Record the session into FILE (R in the explorer too)
    #[arg(long, value_name = "FILE")]
    pub record: Option<std::path::PathBuf>,
    /// Replace an existing --record file
    #[arg(long)]
    pub force: bool,
    /// Sign recordings with KEYFILE (`rattleback keygen`)
    #[arg(long, value_name = "KEYFILE")]
    pub sign: Option<std::path::PathBuf>,
    /// Serve it to browsers as it is recorded (`serve`)
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = "127.0.0.1:0", requires = "record")]
    pub serve: Option<std::net::SocketAddr>,
}

/// How the explorer (and a replay) draws: frame rate, theme, marker.
#[derive(Debug, Args, Clone)]
pub struct LookArgs {
    /// Frame rate cap [default: 30; serve, cast: 10]
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=240))]
    pub fps: Option<u32>,
    /// Colour theme: a name (`rattleback themes`) or a file
    #[arg(long, value_name = "NAME|PATH")]
    pub theme: Option<String>,
    /// Curves: braille, halfblock or dot (no Braille font)
    #[arg(long, value_enum, hide_possible_values = true)]
    pub marker: Option<MarkerChoice>,
    /// Colours: auto (see `NO_COLOR`), always or never
    #[arg(long, value_enum, default_value_t = ColorChoice::Auto, hide_possible_values = true, hide_default_value = true)]
    pub color: ColorChoice,
    /// ASCII only (chosen under a locale that is not UTF-8)
    #[arg(long)]
    pub ascii: bool,
}

/// `--color`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ColorChoice {
    /// As the environment says (`NO_COLOR`, `CLICOLOR`, `CLICOLOR_FORCE`).
    Auto,
    /// Colours, whatever the environment says.
    Always,
    /// No colours: the selection and the status bar in reverse video.
    Never,
}

impl ColorChoice {
    /// Whether colours are off, given the environment's `NO_COLOR`, `CLICOLOR` and
    /// `CLICOLOR_FORCE` (<https://no-color.org>, <https://bixense.com/clicolors/>): a flag wins;
    /// then `NO_COLOR` (non-empty) turns them off; then `CLICOLOR_FORCE` (non-empty, not `0`)
    /// keeps them on; then `CLICOLOR=0` turns them off.
    #[must_use]
    pub fn colours_off(
        self,
        no_color: Option<&str>,
        clicolor: Option<&str>,
        clicolor_force: Option<&str>,
    ) -> bool {
        match self {
            Self::Always => false,
            Self::Never => true,
            Self::Auto => {
                if no_color.is_some_and(|v| !v.is_empty()) {
                    true
                } else if clicolor_force.is_some_and(|v| !v.is_empty() && v != "0") {
                    false
                } else {
                    clicolor == Some("0")
                }
            }
        }
    }
}

impl ColorChoice {
    /// [`ColorChoice::colours_off`] with this process's `NO_COLOR`, `CLICOLOR` and
    /// `CLICOLOR_FORCE`.
    #[must_use]
    pub fn colours_off_here(self) -> bool {
        let var = |name: &str| std::env::var(name).ok();
        self.colours_off(
            var("NO_COLOR").as_deref(),
            var("CLICOLOR").as_deref(),
            var("CLICOLOR_FORCE").as_deref(),
        )
    }

    /// The value as written on the command line (`auto`, `always`, `never`).
    #[must_use]
    pub fn name(self) -> String {
        value_name(&self)
    }
}

/// A value of a `ValueEnum` flag as written on the command line.
fn value_name(v: &impl ValueEnum) -> String {
    v.to_possible_value()
        .map_or_else(String::new, |p| p.get_name().to_owned())
}

impl MarkerChoice {
    /// The value as written on the command line (`braille`, `halfblock`, `dot`).
    #[must_use]
    pub fn name(self) -> String {
        value_name(&self)
    }
}

/// `--marker`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MarkerChoice {
    /// Braille dots: 2×4 per cell (finest).
    Braille,
    /// Half blocks: 1×2 per cell.
    Halfblock,
    /// Dots: 1 per cell.
    Dot,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run one trajectory headless and print the result.
    Simulate(SimulateArgs),
    /// List the presets, or print one (`presets show NAME`).
    ///
    /// Every preset, shipped and the user's, with its scene, source and description.
    Presets(PresetsArgs),
    /// List the colour themes, or print one (`themes show NAME`).
    Themes(ThemesArgs),
    /// Open a lesson in the explorer, or write one (`lesson new NAME`).
    ///
    /// A lesson's steps, questions and conditions in the explorer (`lessons` lists them);
    /// `lesson new NAME` writes a commented lesson to edit into your lessons folder.
    #[command(subcommand_negates_reqs = true, args_conflicts_with_subcommands = true)]
    Lesson(LessonArgs),
    /// List the lessons, or print one (`lessons show NAME`).
    Lessons(LessonsArgs),
    /// Two presets on one time axis, in the explorer.
    ///
    /// The explorer on preset A with preset B beside it on one time axis (the compare pane,
    /// key C): e.g. `compare subcritical celt-clockwise`, the holonomic rattleback beside the
    /// rolling celt. B runs over A's window.
    Compare(CompareArgs),
    /// Follow a recording live, read-only, as the lecturer sees it.
    ///
    /// Follows a session that is still being recorded: what the lecturer sees, paced to the
    /// lecturer's clock; `f` forks and explores on its own from there.
    Follow(FollowArgs),
    /// Serve a recording to web browsers, live and read-only.
    ///
    /// Serves a session, while it is recorded or after, to browsers: the page shows the
    /// lecturer's screen as it is drawn (a reader who joins late sees the current screen at
    /// once), then the whole session with its chapters. The first line on standard output is
    /// the address to open. On an address other than loopback a random token is required (in
    /// the address printed); a wrong or missing one gets 403.
    Serve(ServeArgs),
    /// Report every problem of preset, theme or lesson files.
    ///
    /// Every problem with its file, line and key (exit 2 if any); a lesson is also read step
    /// by step as a student meets it at 80×24.
    Check(CheckArgs),
    /// Replay a recording, verify it, or export it (cast, page).
    Replay(ReplayArgs),
    /// Run time against error of every method, and a stability report.
    ///
    /// The work–precision study of every method over k = 1e2 … 1e12, each scene's own, and a
    /// stability report.
    Bench(BenchArgs),
    /// The sweep towards the limit, and each scene's chart (map).
    #[command(subcommand)]
    Study(StudyCommand),
    /// Print a shell completion script.
    ///
    /// Sourced once, it asks the program for the preset, theme and lesson names each time, so
    /// a preset saved later completes too.
    Completions(CompletionsArgs),
    /// Print the manual page: `rattleback man > rattleback.1`.
    Man,
    /// Make a key that signs recordings.
    ///
    /// Writes `NAME.key` (private, mode 0600) and `NAME.pub` (give it to whoever verifies);
    /// never replaces a file.
    Keygen(KeygenArgs),
    /// Where the configuration is, and what it sets.
    #[command(subcommand)]
    Config(ConfigCommand),
    /// What the program sees here and would choose, with why.
    ///
    /// What this terminal and machine look like to the program and what the explorer would
    /// choose here (characters, colours, marker, preset, theme, folders), each with why: paste
    /// it into a bug report. Takes the explorer's look flags to show their effect.
    Doctor(DoctorArgs),
    /// Write the explorer as a static web site (WebAssembly).
    ///
    /// Builds the explorer for the browser (`wasm32-unknown-unknown`, from this program's
    /// source checkout) and writes `index.html` and `rattleback.wasm` into DIR: any static
    /// server hosts it (`python3 -m http.server -d DIR`); it asks for nothing else. It opens
    /// on the default preset; `?preset=NAME` opens another.
    Web(WebArgs),
}

/// Arguments of `web`.
#[derive(Debug, Args)]
pub struct WebArgs {
    /// The folder to write the site into (created if missing).
    #[arg(value_name = "DIR")]
    pub dir: std::path::PathBuf,
    /// Replace an existing `index.html` or `rattleback.wasm` there.
    #[arg(long)]
    pub force: bool,
}

/// Arguments of `doctor`.
#[derive(Debug, Args)]
pub struct DoctorArgs {
    /// As the explorer would take them.
    #[command(flatten)]
    pub look: LookArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ListFormat::Table)]
    pub format: ListFormat,
}

/// Arguments of `keygen`.
#[derive(Debug, Args)]
pub struct KeygenArgs {
    /// The key's name and file stem (a path may go before it): `NAME.key` and `NAME.pub`.
    #[arg(value_name = "NAME")]
    pub name: std::path::PathBuf,
}

/// `config` subcommands.
#[derive(Debug, Subcommand)]
pub enum ConfigCommand {
    /// Print the path of config.toml (it need not exist).
    Path,
    /// Print the configuration in effect as TOML (defaults commented), to copy into config.toml.
    Show,
}

/// Arguments of `lesson`.
#[derive(Debug, Args)]
pub struct LessonArgs {
    /// Write a new lesson instead of opening one.
    #[command(subcommand)]
    pub new: Option<LessonCommand>,
    /// A lesson: a shipped name (`rattleback lessons` lists them), a user lesson or a path.
    #[arg(value_name = "NAME|PATH", required = true)]
    pub lesson: Option<String>,
    /// How the explorer draws.
    #[command(flatten)]
    pub look: LookArgs,
    /// Recording.
    #[command(flatten)]
    pub rec: RecordArgs,
}

/// What `lesson` does besides opening one.
#[derive(Debug, Subcommand)]
pub enum LessonCommand {
    /// Write a commented lesson skeleton, every key in use, to `<config>/lessons/NAME.toml`
    /// (or elsewhere); it passes `rattleback check` as written.
    New(LessonNewArgs),
}

/// Arguments of `lesson new`.
#[derive(Debug, Args)]
pub struct LessonNewArgs {
    /// The lesson's name (`rattleback lesson NAME` opens it): letters, digits, `-` and `_`.
    #[arg(value_name = "NAME")]
    pub name: String,
    /// Write here instead of the user's lessons folder.
    #[arg(long, value_name = "PATH")]
    pub out: Option<std::path::PathBuf>,
    /// Replace an existing file.
    #[arg(long)]
    pub force: bool,
}

/// Arguments of `compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The preset the explorer opens (a shipped name or a path).
    #[arg(value_name = "A")]
    pub a: String,
    /// The partner drawn beside it (a shipped name or a path).
    #[arg(value_name = "B")]
    pub b: String,
    /// How the explorer draws.
    #[command(flatten)]
    pub look: LookArgs,
    /// Recording.
    #[command(flatten)]
    pub rec: RecordArgs,
}

/// Arguments of `follow`.
#[derive(Debug, Args)]
pub struct FollowArgs {
    /// The session file being written by `rattleback --record` (or `R`).
    pub file: std::path::PathBuf,
    /// How the follower draws.
    #[command(flatten)]
    pub look: LookArgs,
}

/// Arguments of `serve`.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// The session file (being recorded by `rattleback --record`, or finished; the page waits
    /// for it to appear).
    pub file: std::path::PathBuf,
    /// Where to listen [default: 127.0.0.1 and a free port]; 0.0.0.0:PORT for a hall's network
    #[arg(long, value_name = "ADDR:PORT")]
    pub listen: Option<std::net::SocketAddr>,
    /// No token: allowed on loopback only (refused elsewhere, exit 2)
    #[arg(long)]
    pub no_token: bool,
    /// A token even on loopback (behind a reverse proxy that has no login of its own)
    #[arg(long, conflicts_with = "no_token")]
    pub token: bool,
    /// Readers of the live stream at most [default: 500]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub max_readers: Option<u32>,
    /// Readers of the live stream from one address at most [default: 20; loopback, where a
    /// tunnel's or a proxy's readers all come from, only when given] (a hall behind one NAT
    /// address raises it).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub max_per_address: Option<u32>,
    /// A site `rattleback web DIR` wrote: its module is served too, and `f` on the page forks
    /// the lecture into the reader's browser (computed there, not here)
    #[arg(long, value_name = "DIR")]
    pub site: Option<std::path::PathBuf>,
    /// How the frames are drawn (`--fps`: frames a second, default 10).
    #[command(flatten)]
    pub look: LookArgs,
    /// Started by the explorer's `--serve`: stop when standard input closes (the explorer
    /// ended, however it ended).
    #[arg(long, hide = true)]
    pub with_parent: bool,
}

/// Arguments of `completions`.
#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// The shell.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
    /// The program the script asks for completions [default: `rattleback`, found on PATH
    /// each time]; give a path to complete with a binary that is not on PATH.
    #[arg(long, value_name = "PATH")]
    pub binary: Option<std::path::PathBuf>,
}

/// `study` subcommands.
#[derive(Debug, Subcommand)]
pub enum StudyCommand {
    /// The full motion at a ladder of stiffnesses against the limit: the largest distance of
    /// its α from the limit's over [0, T], against k, with the fitted log–log slope.
    Sweep(SweepArgs),
    /// The preset's scene charted: the rattleback's reversals over (α̇0²/γ̇0², iy/ix) with the
    /// critical curve (from the limit, or the full model at `--k`); the pendulum's stability
    /// over (a, b) at its ε by Floquet theory, with Kapitza's b² = 2a; the celt's reversals over
    /// (initial `ω_z`, product of inertia) with its linear-stability boundary.
    Map(MapArgs),
    /// Put the part files of `study map --shard I/N` back together: the same output as the
    /// unsharded run (refusing parts of different charts, repeated or missing slices).
    Merge(MergeArgs),
}

/// What both studies take.
#[derive(Debug, Args)]
pub struct StudyCommon {
    /// Preset: a shipped name or a path to a TOML file.
    #[arg(long, value_name = "NAME|PATH", default_value = DEFAULT_PRESET)]
    pub preset: String,
    /// Override a preset value, e.g. `--set body.iz=2` (repeatable).
    #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
    pub set: Vec<Override>,
    /// Final time (overrides the preset's `run.t_end`).
    #[arg(long = "t-end", value_parser = parse_positive, allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// `auto`'s tolerance for the full-model runs (overrides the preset's).
    #[arg(long, value_parser = parse_tolerance, allow_negative_numbers = true)]
    pub tolerance: Option<f64>,
    /// Also write CSV files and an SVG plot into this folder (created if missing; existing
    /// files of the same names are refused unless `--force`).
    #[arg(long, value_name = "DIR")]
    pub out: Option<std::path::PathBuf>,
    /// Replace existing files in `--out`.
    #[arg(long)]
    pub force: bool,
    /// Output format on stdout.
    #[arg(long, value_enum, default_value_t = StudyFormat::Table)]
    pub format: StudyFormat,
}

/// Arguments of `study sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    #[command(flatten)]
    pub common: StudyCommon,
    /// The stiffnesses, comma-separated (default: one per decade from 1e1 to 1e8).
    #[arg(long, value_delimiter = ',', value_parser = parse_positive, allow_negative_numbers = true)]
    pub ladder: Vec<f64>,
}

/// Arguments of `study map`.
#[derive(Debug, Args)]
pub struct MapArgs {
    #[command(flatten)]
    pub common: StudyCommon,
    /// Cells: columns x rows.
    #[arg(long, value_name = "COLSxROWS", default_value = "200x100", value_parser = parse_grid)]
    pub grid: (usize, usize),
    /// The rattleback's largest α̇0²/γ̇0² (columns span (0, max]; default 2).
    #[arg(long = "ratio-max", value_parser = parse_positive, allow_negative_numbers = true)]
    pub ratio_max: Option<f64>,
    /// The rattleback's smallest iy/ix (rows are log-spaced; default 0.1).
    #[arg(long = "inertia-min", value_parser = parse_positive, allow_negative_numbers = true)]
    pub inertia_min: Option<f64>,
    /// The rattleback's largest iy/ix (default 10).
    #[arg(long = "inertia-max", value_parser = parse_positive, allow_negative_numbers = true)]
    pub inertia_max: Option<f64>,
    /// The rattleback: compute every cell from the full model at this Hooke constant (through
    /// `auto`) instead of the limit; refused when predicted over the work budget unless `--force`.
    #[arg(long, value_parser = parse_positive, allow_negative_numbers = true)]
    pub k: Option<f64>,
    /// The pendulum and the celt: the range across, `MIN,MAX` (the pendulum's `a`, the celt's
    /// initial `ω_z`).
    #[arg(long, value_name = "MIN,MAX", value_parser = parse_range, allow_hyphen_values = true)]
    pub columns: Option<(f64, f64)>,
    /// The pendulum and the celt: the range up, `MIN,MAX` (the pendulum's `b`, log-spaced, both
    /// positive; the celt's product of inertia `D`).
    #[arg(long, value_name = "MIN,MAX", value_parser = parse_range, allow_hyphen_values = true)]
    pub rows: Option<(f64, f64)>,
    /// The pendulum: which equilibrium's stability (default: upright).
    #[arg(long, value_enum)]
    pub position: Option<Position>,
    /// Compute every cell instead of refining (by default a chart computes a coarse lattice,
    /// then only where neighbouring cells disagree, and infers the rest: each cell's `mark`
    /// says which).
    #[arg(long)]
    pub exhaustive: bool,
    /// Compute one slice of the cells, `I/N` (1-based: whole blocks of the refinement, block
    /// `b` in slice `b mod N + 1`; with `--exhaustive`, the cells whose index is `I − 1` modulo
    /// `N`), and print it as a JSON part file for `study merge`.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<crate::study::chart::Shard>,
}

/// The pendulum's equilibrium of `study map --position`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Position {
    /// θ = 0.
    Upright,
    /// θ = π.
    Hanging,
}

/// Arguments of `study merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The part files `study map --shard I/N` wrote, in any order (`-` reads one from stdin).
    #[arg(required = true, value_name = "PART.json")]
    pub parts: Vec<std::path::PathBuf>,
    /// Cells of each part recomputed, chosen at random, to catch a part whose values were
    /// edited (0: none; every part's header and coordinates are checked regardless).
    #[arg(long, value_name = "N", default_value_t = 3)]
    pub check: usize,
    /// Output format on stdout.
    #[arg(long, value_enum, default_value_t = StudyFormat::Json)]
    pub format: StudyFormat,
    /// Also write `map.csv` and `map.svg` into this folder.
    #[arg(long, value_name = "DIR")]
    pub out: Option<std::path::PathBuf>,
    /// Replace existing files in `--out`.
    #[arg(long)]
    pub force: bool,
}

/// Why a flag's value was refused (clap shows it after the flag's name).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FlagValue {
    /// Not of the flag's shape.
    #[error("expected {0}")]
    Shape(&'static str),
    /// An end of a range that is not a finite number of magnitude at most 1e12.
    #[error("`{0}`: a finite number of magnitude at most 1e12")]
    RangeEnd(String),
    /// A range whose ends are out of order.
    #[error("MIN ({0}) must be below MAX ({1})")]
    Order(f64, f64),
    /// A shard out of its bounds.
    #[error("`{0}`: I/N with N from 1 to 10000 and I from 1 to N (1-based)")]
    Shard(String),
    /// A side of the grid out of its bounds.
    #[error("`{0}`: a whole number from 1 to 2000")]
    GridSide(String),
    /// Not a number.
    #[error("not a number")]
    NotANumber,
    /// Infinite or NaN.
    #[error("not a finite number")]
    NotFinite,
    /// Zero or negative.
    #[error("allowed: a finite number > 0")]
    NotPositive,
    /// A tolerance out of its range.
    #[error("allowed: a number in [{0:e}, {1:e}]")]
    Tolerance(f64, f64),
}

fn parse_range(s: &str) -> Result<(f64, f64), FlagValue> {
    let (a, b) = s
        .split_once(',')
        .ok_or(FlagValue::Shape("MIN,MAX, e.g. 0,2"))?;
    let n = |v: &str| {
        v.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && x.abs() <= 1e12)
            .ok_or_else(|| FlagValue::RangeEnd(v.to_owned()))
    };
    let (a, b) = (n(a)?, n(b)?);
    if a >= b {
        return Err(FlagValue::Order(a, b));
    }
    Ok((a, b))
}

fn parse_shard(s: &str) -> Result<crate::study::chart::Shard, FlagValue> {
    let (i, n) = s.split_once('/').ok_or(FlagValue::Shape(
        "I/N, e.g. 2/3 (the second of three slices)",
    ))?;
    let n_of = |v: &str| v.trim().parse::<usize>().ok();
    match (n_of(i), n_of(n)) {
        (Some(index), Some(count))
            if (1..=10_000).contains(&count) && (1..=count).contains(&index) =>
        {
            Ok(crate::study::chart::Shard { index, count })
        }
        _ => Err(FlagValue::Shard(s.to_owned())),
    }
}

fn parse_grid(s: &str) -> Result<(usize, usize), FlagValue> {
    let (c, r) = s
        .split_once(['x', 'X'])
        .ok_or(FlagValue::Shape("COLSxROWS, e.g. 200x100"))?;
    let n = |v: &str| {
        v.trim()
            .parse::<usize>()
            .ok()
            .filter(|n| (1..=2000).contains(n))
            .ok_or_else(|| FlagValue::GridSide(v.to_owned()))
    };
    Ok((n(c)?, n(r)?))
}

/// Arguments of `bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// The short version (under a minute here): fewer settings, T = 5, no repeats.
    #[arg(long)]
    pub quick: bool,
    /// Folder for `work_precision.csv`, `work_precision.svg`, `auto_profile.csv`,
    /// `kapitza.csv`, `celt.csv` and `stability.csv`.
    #[arg(long, value_name = "DIR", default_value = "bench-results")]
    pub out: std::path::PathBuf,
    /// Run one part only.
    #[arg(long, value_enum, value_name = "PART")]
    pub only: Option<BenchPart>,
    /// Replace the files of an earlier run in `--out` (refused otherwise, before anything runs).
    #[arg(long)]
    pub force: bool,
}

/// A part of `rattleback bench`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchPart {
    /// Every method over k = 1e2 … 1e12 (`work_precision.csv`, `.svg`).
    WorkPrecision,
    /// `auto` at every stiffness (`auto_profile.csv`).
    Auto,
    /// Kapitza's pendulum: cost against ε (`kapitza.csv`).
    Kapitza,
    /// The celt: run time against error on its presets (`celt.csv`).
    Celt,
    /// The stability report (`stability.csv`).
    Stability,
    /// Long runs verified in segments: the wait before the first frame against the whole
    /// verification (`segments.csv`).
    Segments,
}

/// Arguments of `replay`.
#[derive(Debug, Args)]
#[command(group(clap::ArgGroup::new("export").multiple(true).args(["export_cast", "export_html"])))]
pub struct ReplayArgs {
    /// The session file.
    pub file: std::path::PathBuf,
    /// Check the file's integrity by its format's rules, then re-run it headless and check
    /// every checkpoint bit for bit and every recorded screen (exit 1 on a divergence, a
    /// tampered line or a file cut short).
    #[arg(long)]
    pub verify: bool,
    /// With `--verify`: the lecturer's public key (`NAME.pub`); the session must be signed
    /// with its private half.
    #[arg(long, value_name = "PUBFILE", requires = "verify")]
    pub key: Option<std::path::PathBuf>,
    /// Print the chapters with their times (wall clock of the recording and simulated time),
    /// then exit.
    #[arg(long)]
    pub chapters: bool,
    /// Output of `--chapters` or `--verify` (one of them with `json`): text, or one JSON
    /// object on stdout (`docs/schemas/chapters.schema.json`, `verify.schema.json`).
    #[arg(long, value_enum, default_value_t = ListFormat::Table)]
    pub format: ListFormat,
    /// Write an asciicast v2 file (asciinema-player plays it), chapters as markers. With
    /// `--verify`, the session is checked first and exported only if it verifies. An existing
    /// file is refused (exit 2) unless `--force`.
    #[arg(long, value_name = "OUT.cast")]
    pub export_cast: Option<std::path::PathBuf>,
    /// Write one self-contained HTML page that plays the session (asciinema-player, inlined:
    /// no network needed), with the chapters as links and the chapters and notes as markers.
    /// With `--verify`, written only if the session verifies. An existing file is refused
    /// (exit 2) unless `--force`.
    #[arg(long, value_name = "OUT.html")]
    pub export_html: Option<std::path::PathBuf>,
    /// Replace an existing `--export-cast` or `--export-html` file (never the session itself).
    #[arg(long)]
    pub force: bool,
    /// How the replay (and the exported cast) draws.
    #[command(flatten)]
    pub look: LookArgs,
    /// Columns of the exported cast or page (default: the recorded terminal's).
    #[arg(long, value_parser = clap::value_parser!(u16).range(80..=1000), requires = "export")]
    pub cols: Option<u16>,
    /// Rows of the exported cast or page (default: the recorded terminal's).
    #[arg(long, value_parser = clap::value_parser!(u16).range(24..=1000), requires = "export")]
    pub rows: Option<u16>,
}

/// Arguments of `presets`.
#[derive(Debug, Args)]
pub struct PresetsArgs {
    /// Print one preset instead of the list.
    #[command(subcommand)]
    pub action: Option<PresetsAction>,
    /// Output format of the list.
    #[arg(long, value_enum, default_value_t = ListFormat::Table)]
    pub format: ListFormat,
}

/// `presets` subcommands.
#[derive(Debug, Subcommand)]
pub enum PresetsAction {
    /// Print a preset's TOML (a shipped name, a user preset or a path), to copy and edit.
    Show {
        /// The preset.
        #[arg(value_name = "NAME|PATH")]
        name: String,
    },
}

/// Arguments of `themes`.
#[derive(Debug, Args)]
pub struct ThemesArgs {
    /// Print one theme instead of the list.
    #[command(subcommand)]
    pub action: Option<ShowAction>,
    /// Output format of the list.
    #[arg(long, value_enum, default_value_t = ListFormat::Table)]
    pub format: ListFormat,
}

/// Arguments of `lessons`.
#[derive(Debug, Args)]
pub struct LessonsArgs {
    /// Print one lesson instead of the list.
    #[command(subcommand)]
    pub action: Option<ShowAction>,
    /// Output format of the list.
    #[arg(long, value_enum, default_value_t = ListFormat::Table)]
    pub format: ListFormat,
}

/// `themes` and `lessons` subcommands.
#[derive(Debug, Subcommand)]
pub enum ShowAction {
    /// Print its TOML (a shipped name, the user's or a path), to copy and edit.
    Show {
        /// The theme or lesson.
        #[arg(value_name = "NAME|PATH")]
        name: String,
    },
}

/// Output format of the lists, `check`, `doctor` and `replay --chapters`/`--verify`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ListFormat {
    /// One JSON object on stdout: `schema_version`, `model` (`null` where it is about no
    /// scene), then the command's own fields (each output's schema is in `docs/schemas/`).
    Json,
    /// Text for people.
    Table,
}

/// Arguments of `check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Files to check: presets, themes (files with a `[theme]` or `[colors]` table) or lessons
    /// (files with a `[lesson]` table); `-` is standard input.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<std::path::PathBuf>,
    /// Output format: every problem as text on stderr, or one JSON object on stdout.
    #[arg(long, value_enum, default_value_t = ListFormat::Table)]
    pub format: ListFormat,
}

/// Output format of a study.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum StudyFormat {
    /// One JSON object (`docs/schemas/sweep.schema.json`, `map.schema.json`).
    Json,
    /// One row per rung (the sweep) or per cell (the map), with a header line.
    Csv,
    /// A summary for people.
    Table,
}

/// Output format of `simulate`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One JSON object.
    Json,
    /// The sampled trajectory as CSV (see `--samples`).
    Csv,
    /// A summary for people.
    Table,
}

impl From<Format> for crate::simulate::Format {
    fn from(f: Format) -> Self {
        match f {
            Format::Json => Self::Json,
            Format::Csv => Self::Csv,
            Format::Table => Self::Table,
        }
    }
}

impl SimulateArgs {
    /// The run this asks for, in the library's terms.
    #[must_use]
    pub fn request(&self) -> crate::simulate::Request {
        crate::simulate::Request {
            method: self.method,
            tolerance: self.tolerance,
            step: self.step,
            t_end: self.t_end,
            format: self.format.into(),
            samples: self.samples,
            force: self.force,
        }
    }
}

/// Arguments of `simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Preset: a shipped name or a path to a TOML file.
    #[arg(long, value_name = "NAME|PATH", default_value = DEFAULT_PRESET)]
    pub preset: String,
    /// Override a preset value, e.g. `--set spring.k=1e6` (repeatable).
    #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
    pub set: Vec<Override>,
    /// Integrator (overrides the preset's `run.method`); any case.
    #[arg(long, value_parser = method_parser(), ignore_case = true)]
    pub method: Option<Method>,
    /// Tolerance: relative and absolute for adaptive methods; picks the step of fixed-step ones.
    #[arg(long, value_parser = parse_tolerance, allow_negative_numbers = true)]
    pub tolerance: Option<f64>,
    /// Fixed step size for fixed-step methods (overrides the one derived from the tolerance).
    #[arg(long, value_parser = parse_positive, allow_negative_numbers = true)]
    pub step: Option<f64>,
    /// Final time (overrides the preset's `run.t_end`).
    #[arg(long = "t-end", value_parser = parse_positive, allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Number of evenly spaced samples for `--format csv`.
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u32).range(2..=10_000_000))]
    pub samples: u32,
    /// Run even when the work is predicted to exceed the budget (60 s on the calibration
    /// machine); without it such a run is refused before it starts, with the prediction.
    #[arg(long)]
    pub force: bool,
    /// Exit 1 when `auto` cannot meet the tolerance (its estimate is above it: `auto.met` is
    /// false). Without it the output is written and a warning goes to stderr.
    #[arg(long)]
    pub strict: bool,
}

/// `--method`: the names listed in `--help` and in the error, matched in any case.
fn method_parser() -> impl clap::builder::TypedValueParser<Value = Method> {
    use clap::builder::TypedValueParser as _;
    clap::builder::PossibleValuesParser::new(Method::ALL.map(Method::name))
        .map(|name: String| Method::from_name(&name).unwrap_or(Method::Auto))
}

fn parse_finite(s: &str) -> Result<f64, FlagValue> {
    let v: f64 = s.parse().map_err(|_| FlagValue::NotANumber)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(FlagValue::NotFinite)
    }
}

fn parse_positive(s: &str) -> Result<f64, FlagValue> {
    let v = parse_finite(s)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(FlagValue::NotPositive)
    }
}

fn parse_tolerance(s: &str) -> Result<f64, FlagValue> {
    let v = parse_finite(s)?;
    let (lo, hi) = TOLERANCE_RANGE;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(FlagValue::Tolerance(lo, hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_flag_values_are_refused_with_the_allowed_range() {
        let err = Cli::try_parse_from(["rattleback", "simulate", "--tolerance", "0"]).unwrap_err();
        assert!(err.to_string().contains("allowed: a number in"), "{err}");
        let err = Cli::try_parse_from(["rattleback", "simulate", "--method", "euler"]).unwrap_err();
        assert!(err.to_string().contains("dop853"), "{err}");
        let err = Cli::try_parse_from(["rattleback", "simulate", "--t-end", "NaN"]).unwrap_err();
        assert!(err.to_string().contains("finite"), "{err}");
        let ok = Cli::try_parse_from(["rattleback", "simulate", "--set", "spring.k=1e6"]).unwrap();
        let Some(Command::Simulate(args)) = ok.command else {
            panic!("simulate expected")
        };
        assert_eq!(args.set[0].key, "spring.k");
    }
}
