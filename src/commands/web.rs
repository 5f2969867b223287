//! `rattleback web DIR` (issue 82): the explorer as a static web site. The module is the
//! workspace's `rattleback-web` package built for `wasm32-unknown-unknown` by cargo, from the
//! source checkout this binary was built in; the page (`web/index.html`) is carried inside the
//! binary. No argument reaches a shell: cargo and rustup are run with their arguments as
//! given, and DIR is a path.

use super::Outcome;
use super::cli::WebArgs;
use super::failure::Failure;
use super::study::not_written;

/// The WebAssembly target the module is built for.
pub const TARGET: &str = "wasm32-unknown-unknown";

/// The page, as shipped: its scripts are put in where it says (`/*WORKER*/`, `/*EXPLORER*/`)
/// by [`page`].
const PAGE: &str = include_str!("../../web/index.html");

/// The module's Web Worker (shared with the served lecture's fork).
pub const WORKER_JS: &str = include_str!("../../web/worker.js");

/// The explorer in a page: draws, keys, buttons, downloads (shared with the served lecture's
/// fork).
pub const EXPLORER_JS: &str = include_str!("../../web/explorer.js");

/// The site's page, its scripts inlined (no outside request).
#[must_use]
pub fn page() -> String {
    PAGE.replace("/*WORKER*/", WORKER_JS)
        .replace("/*EXPLORER*/", EXPLORER_JS)
}

/// The largest module accepted from the build (a sanity bound: it is about 2 MB).
pub const MAX_MODULE: u64 = 64 << 20;

/// The checkout this binary was built from, when it is still there.
fn checkout() -> Option<std::path::PathBuf> {
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    root.join("web")
        .join("Cargo.toml")
        .is_file()
        .then_some(root)
}

/// Whether rustup knows the target installed (`None`: no rustup to ask).
fn target_installed() -> Option<bool> {
    let out = std::process::Command::new("rustup")
        .args(["target", "list", "--installed"])
        .stdin(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .output()
        .ok()?;
    out.status.success().then(|| {
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .any(|l| l.trim() == TARGET)
    })
}

/// `rattleback web DIR`.
pub fn web(args: &WebArgs) -> Outcome {
    let Some(root) = checkout() else {
        return Err(Failure::input(format!(
            "web builds the browser's module from this program's source checkout ({}), which is not there: run it from a clone (`cargo run --release -- web DIR`)",
            env!("CARGO_MANIFEST_DIR")
        )));
    };
    if target_installed() == Some(false) {
        return Err(Failure::input(format!(
            "the WebAssembly target is not installed; add it with one line: rustup target add {TARGET}"
        )));
    }
    // Refused before the build: files of an earlier site are replaced only with --force.
    let page = args.dir.join("index.html");
    let module = args.dir.join("rattleback.wasm");
    if !args.force {
        for path in [&page, &module] {
            if path.exists() {
                return Err(Failure::input(format!(
                    "{} exists; --force replaces it",
                    path.display()
                )));
            }
        }
    }
    crate::scenario::text::warn(&format!(
        "web: building the explorer for {TARGET} (cargo build --release -p rattleback-web)"
    ));
    let status =
        std::process::Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
            .args([
                "build",
                "--release",
                "--quiet",
                "--target",
                TARGET,
                "-p",
                "rattleback-web",
                "--manifest-path",
            ])
            .arg(root.join("Cargo.toml"))
            .stdin(std::process::Stdio::null())
            .status()
            .map_err(|e| Failure::failed(format!("cannot run cargo (is Rust installed?): {e}")))?;
    if !status.success() {
        return Err(Failure::failed(format!(
            "building the module failed (cargo said why above); if the target is missing: rustup target add {TARGET}"
        )));
    }
    let target_dir = std::env::var_os("CARGO_TARGET_DIR")
        .map_or_else(|| root.join("target"), std::path::PathBuf::from);
    let built = target_dir
        .join(TARGET)
        .join("release")
        .join("rattleback_web.wasm");
    let size = std::fs::metadata(&built)
        .map_err(|e| Failure::failed(format!("{}: {e}", built.display())))?
        .len();
    if size > MAX_MODULE {
        return Err(Failure::failed(format!(
            "{}: {size} bytes, more than a module can be",
            built.display()
        )));
    }
    let bytes =
        std::fs::read(&built).map_err(|e| Failure::failed(format!("{}: {e}", built.display())))?;
    let _folder = crate::fault::made_folder(&args.dir)
        .map_err(|e| Failure::input(format!("{}: {e}", args.dir.display())))?;
    crate::scenario::write::write_atomic(&module, &bytes, args.force)
        .map_err(|e| not_written(&module, &e))?;
    crate::scenario::write::write_atomic(&page, self::page().as_bytes(), args.force)
        .map_err(|e| not_written(&page, &e))?;
    crate::scenario::text::warn(&format!(
        "wrote {} and {} ({} KB); serve the folder with any static server, e.g. python3 -m http.server -d {}",
        page.display(),
        module.display(),
        size / 1024,
        crate::scenario::text::shell_word(&args.dir.display().to_string())
    ));
    Ok(())
}
