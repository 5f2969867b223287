//! `rattleback config`: the configuration file, shown, checked, or its path.

use crate::commands::failure::{Failure, Outcome};

/// # Errors
/// The file's first problem, located.
///
/// The configuration for the explorer and replay, with its key bindings checked: an invalid
/// file is an error naming the file, the line and the key.
pub fn load_config() -> Result<
    (
        crate::scenario::config::Config,
        crate::app::user_keys::UserKeys,
    ),
    Vec<String>,
> {
    // The keys that did parse are still checked, so every problem is said at once.
    let (config, problems) = crate::scenario::config::Config::load_all();
    let mut errors: Vec<(usize, String)> = problems
        .iter()
        .map(|e| (e.line().unwrap_or(0), e.to_string()))
        .collect();
    let entries: Vec<(String, Vec<String>)> = config
        .keys
        .iter()
        .map(|k| (k.action.clone(), k.keys.clone()))
        .collect();
    let keys = match crate::app::user_keys::UserKeys::parse(&entries) {
        Ok(k) => k,
        Err(bad) => {
            for (i, message) in bad {
                let entry = &config.keys[i];
                errors.push((
                    entry.line,
                    crate::scenario::PresetError::Invalid {
                        path: config
                            .path
                            .as_ref()
                            .map_or_else(String::new, |p| p.display().to_string()),
                        line: Some(entry.line),
                        key: Some(format!("keys.{}", entry.action)),
                        message,
                    }
                    .to_string(),
                ));
            }
            crate::app::user_keys::UserKeys::default()
        }
    };
    if errors.is_empty() {
        Ok((config, keys))
    } else {
        // In the file's order.
        errors.sort_by_key(|(line, _)| *line);
        Err(errors.into_iter().map(|(_, e)| e).collect())
    }
}

/// `rattleback config path|show`.
pub fn config(command: &crate::commands::cli::ConfigCommand) -> Outcome {
    use crate::commands::cli::ConfigCommand;
    use crate::scenario::config;
    match command {
        ConfigCommand::Path => {
            if let Some(p) = config::path() {
                say!("{}", p.display());
                Ok(())
            } else {
                Err(Failure::input(
                    "no config folder (no home folder); set RATTLEBACK_CONFIG_DIR",
                ))
            }
        }
        ConfigCommand::Show => match load_config() {
            Ok((c, _)) => {
                let origin = c.path.as_ref().map_or_else(
                    || {
                        format!(
                            "# no config file: the defaults ({} would be read)",
                            config::path().map_or_else(String::new, |p| p.display().to_string())
                        )
                    },
                    |p| format!("# from {}", p.display()),
                );
                say_raw!("{origin}\n{}", c.to_toml());
                Ok(())
            }
            Err(errors) => Err(Failure::inputs(errors)),
        },
    }
}
