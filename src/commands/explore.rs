//! `rattleback` with no command: the explorer on a preset, and the set-up every explorer
//! command (lesson, compare, follow) shares.

use super::shared::{
    charset, config_or_exit, depth, marker, needs_terminal, no_color, prepare_record, refuse_stdin,
    with_config,
};
use crate::app::user_keys::UserKeys;
use crate::commands;
use crate::commands::cli::{Cli, LookArgs, RecordArgs};
use crate::commands::failure::{Failure, Outcome};
use crate::explorer::{self, ExplorerOptions};
use crate::record;
use crate::scenario::shipped::resolve;
use crate::terminal::Depth;
use crate::ui::UiOptions;

pub fn run_explorer(cli: &Cli) -> Outcome {
    if cli.preset.as_deref() == Some("-") {
        return refuse_stdin("--preset -");
    }
    let opening = Opening {
        look: &cli.look,
        rec: &cli.rec,
        mouse: cli.mouse,
        lesson: None,
        partner: None,
    };
    let preset = cli.preset.as_deref().map(|name| resolve(name, &[]));
    open_explorer(preset, opening)
}

/// How an interactive command opens the explorer.
pub(crate) struct Opening<'a> {
    pub(crate) look: &'a LookArgs,
    pub(crate) rec: &'a RecordArgs,
    pub(crate) mouse: bool,
    pub(crate) lesson: Option<crate::scenario::lesson::Lesson>,
    pub(crate) partner: Option<crate::scenario::Preset>,
}

/// The one way the explorer opens from the command line: the configuration, the preset (`None`:
/// the configured default, else the shipped one), the recording's file, then the loop.
pub(crate) fn open_explorer(
    preset: Option<Result<crate::scenario::Preset, crate::scenario::PresetError>>,
    o: Opening<'_>,
) -> Outcome {
    let (config, keys) = config_or_exit()?;
    let preset = preset.unwrap_or_else(|| {
        let name = config.preset.as_deref();
        resolve(
            name.unwrap_or(crate::scenario::shipped::DEFAULT_PRESET),
            &[],
        )
    });
    let preset = match preset {
        Ok(p) => p,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    prepare_record(o.rec.record.as_deref(), o.rec.force)?;
    let setup = Setup {
        look: with_config(o.look, &config),
        sessions_dir: config.sessions_dir(),
        mouse: o.mouse || config.mouse,
        keys,
        lesson: o.lesson,
        partner: o.partner,
        follow: None,
        sign: o.rec.sign.clone(),
        serve: o.rec.serve,
    };
    explore(&setup, &preset, o.rec.record.clone(), None)
}

/// What the explorer needs from the command line and the configuration.
pub(crate) struct Setup {
    pub(crate) look: LookArgs,
    pub(crate) sessions_dir: Option<std::path::PathBuf>,
    pub(crate) mouse: bool,
    pub(crate) keys: UserKeys,
    pub(crate) lesson: Option<crate::scenario::lesson::Lesson>,
    pub(crate) partner: Option<crate::scenario::Preset>,
    pub(crate) follow: Option<std::path::PathBuf>,
    pub(crate) sign: Option<std::path::PathBuf>,
    /// `--serve`: where the recording is served to browsers as it is written.
    pub(crate) serve: Option<std::net::SocketAddr>,
}

pub(crate) fn explore(
    setup: &Setup,
    preset: &crate::scenario::Preset,
    record: Option<std::path::PathBuf>,
    replay: Option<record::Recording>,
) -> Outcome {
    if let Some(key) = &setup.sign
        && let Err(e) = record::sign::Signer::read(key)
    {
        return Err(Failure::input(format!("--sign: {e}")));
    }
    let look = &setup.look;
    let marker = marker(look.marker);
    let theme = match crate::scenario::theme::theme(look.theme.as_deref().unwrap_or("default")) {
        Ok(t) => t,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let (all, problems) = crate::scenario::theme::themes();
    let all: Vec<_> = all.into_iter().map(|(_, t)| t).collect();
    let depth = depth(look.color);
    let mut options = ExplorerOptions {
        fps: f64::from(look.fps.unwrap_or(30)),
        ui: UiOptions::new(
            marker,
            &theme,
            &all,
            no_color(look.color) || depth == Depth::None,
        )
        .with_charset(charset(look)),
        startup_problems: problems.iter().map(ToString::to_string).collect(),
        record,
        replay,
        sessions_dir: setup.sessions_dir.clone(),
        mouse: setup.mouse,
        keys: setup.keys.clone(),
        lesson: setup.lesson.clone(),
        partner: setup.partner.clone(),
        follow: setup.follow.clone(),
        sign: setup.sign.clone(),
        depth,
        served: None,
    };
    needs_terminal(if setup.follow.is_some() {
        "follow"
    } else if options.replay.is_some() {
        "replay"
    } else if setup.lesson.is_some() {
        "lesson"
    } else if setup.partner.is_some() {
        "compare"
    } else {
        "the explorer"
    })?;
    // Started once the terminal is known to draw; stopped when the explorer ends.
    let beside = match (setup.serve, &options.record) {
        (Some(listen), Some(file)) => Some(commands::serve::Beside::start(file, listen)?),
        _ => None,
    };
    options.served = beside.as_ref().map(|b| b.url.clone());
    match explorer::run(preset, &options) {
        Ok(None) => Ok(()),
        // Ended by a signal: the terminal is restored; exit as the convention says.
        Ok(Some(n)) => Err(Failure::signalled(n)),
        Err(e) => Err(Failure::failed(format!(
            "the explorer needs an interactive terminal ({e}); for headless runs use `rattleback simulate`"
        ))),
    }
}
