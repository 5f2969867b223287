//! `rattleback follow`: a lecture followed live from its growing session file.

use super::explore::{Setup, explore};
use super::replay::replay_theme;
use super::shared::{config_or_exit, needs_terminal, refuse_stdin, with_config};
use crate::commands::cli::LookArgs;
use crate::commands::failure::{Failure, Outcome};
use crate::record;

pub fn run_follow(args: &crate::commands::cli::FollowArgs) -> Outcome {
    if args.file.as_os_str() == "-" {
        return refuse_stdin("follow -");
    }
    // Before waiting for the lecturer's file: a follower with nowhere to draw would wait for
    // nothing.
    needs_terminal("follow")?;
    // Students often start first: wait for the file (and its header) to appear, saying so.
    let mut said = false;
    while !args
        .file
        .metadata()
        .is_ok_and(|m| m.is_file() && m.len() > 0)
    {
        if !said {
            say_err!(
                "rattleback: note: waiting for {} to appear (the lecturer has not started recording yet; Ctrl-C stops)",
                args.file.display()
            );
            said = true;
        }
        std::thread::sleep(std::time::Duration::from_millis(200));
    }
    // Read once here: a file that is not a session is refused before the terminal is touched.
    let rec = match crate::record::tail::Tail::open(&args.file) {
        Ok((_, rec)) => rec,
        Err(record::RecordError::Io { path, source })
            if source.kind() == std::io::ErrorKind::PermissionDenied =>
        {
            return Err(Failure::input(format!(
                "{path}: permission denied: the lecturer's file is not readable by you (recorded under umask 077?); the lecturer can run `chmod a+r {path}`, or record with `umask 022`"
            )));
        }
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let (config, keys) = config_or_exit()?;
    let preset = match crate::scenario::Preset::parse(
        &rec.header.preset,
        &format!("{} (header)", args.file.display()),
        "recorded",
        &[],
    ) {
        Ok(p) => p,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let asked = with_config(&args.look, &config);
    let setup = Setup {
        look: LookArgs {
            theme: Some(replay_theme(args.look.theme.as_deref(), &rec.header.theme)),
            ..asked
        },
        sessions_dir: config.sessions_dir(),
        mouse: false,
        keys,
        lesson: None,
        partner: None,
        follow: Some(args.file.clone()),
        sign: None,
        serve: None,
    };
    explore(&setup, &preset, None, Some(rec))
}
