//! The README and the docs are kept true by the program's own output and by checks that fail
//! on drift: key tables generated from the keymaps, the screenshot from the 80×24 snapshot, a
//! README of at most 250 lines, every relative link and every citation resolving in the clone,
//! and the architecture page naming every layering test and only files that exist.

use std::path::{Path, PathBuf};

use rattleback::app::keys::{KEYMAP, REPLAY_KEYMAP, map_markdown, markdown};

fn root() -> &'static Path {
    Path::new(root!())
}

fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn readme() -> String {
    read("README.md")
}

#[test]
fn key_tables_are_generated_from_the_keymaps() {
    let guide = read("docs/guide.md");
    for (what, table) in [
        ("explorer", markdown(&KEYMAP)),
        ("replay", markdown(REPLAY_KEYMAP)),
        ("regime map", map_markdown()),
    ] {
        assert!(
            guide.contains(&table),
            "docs/guide.md's {what} key table differs from `cargo run --example key_tables`:\n{table}"
        );
    }
    // The README's short table: every row is a row of the generated one.
    let full = markdown(&KEYMAP);
    let text = readme();
    let keys = text
        .split("## Keys")
        .nth(1)
        .expect("a Keys section")
        .split("\n## ")
        .next()
        .unwrap();
    let rows: Vec<&str> = keys.lines().filter(|l| l.starts_with("| `")).collect();
    assert!(rows.len() >= 8, "the README's key summary: {rows:?}");
    for row in rows {
        assert!(
            full.contains(row),
            "README key row not in the keymap: {row}"
        );
    }
}

#[test]
fn the_screenshot_is_the_snapshot_of_the_80x24_screen() {
    let snap = read("tests/it/snapshots/it__explorer_ui__screen_80x24.snap");
    let screen = snap.splitn(3, "---\n").nth(2).expect("insta header");
    assert!(
        readme().contains(&format!("```text\n{screen}```")),
        "copy tests/it/snapshots/it__explorer_ui__screen_80x24.snap into the README"
    );
}

#[test]
fn the_readme_is_short() {
    let n = readme().lines().count();
    assert!(
        n <= 250,
        "README.md has {n} lines; the rest belongs in docs/"
    );
}

fn markdown_files() -> Vec<PathBuf> {
    let mut out = vec![root().join("README.md"), root().join("CHANGELOG.md")];
    let mut docs = Vec::new();
    walk_all(&root().join("docs"), &mut docs);
    out.extend(
        docs.into_iter()
            .filter(|p| p.extension().is_some_and(|x| x == "md")),
    );
    out
}

/// GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.push(anchor(line.trim_start_matches('#')));
        }
    }
    out
}

/// Relative links `](target)` outside code blocks.
fn links(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let mut rest = line;
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let end = after.find(')').unwrap_or(after.len());
            let target = &after[..end];
            if !target.contains("://") && !target.starts_with("mailto:") {
                out.push(target.to_owned());
            }
            rest = &after[end..];
        }
    }
    out
}

#[test]
fn every_relative_link_resolves() {
    let mut broken = Vec::new();
    for file in markdown_files() {
        let text = std::fs::read_to_string(&file).unwrap();
        for link in links(&text) {
            let (path, frag) = link.split_once('#').unwrap_or((&link, ""));
            let target = if path.is_empty() {
                file.clone()
            } else {
                file.parent().unwrap().join(path)
            };
            if !target.exists() {
                broken.push(format!("{}: {link} (no such file)", file.display()));
                continue;
            }
            if !frag.is_empty() && target.extension().is_some_and(|x| x == "md") {
                let heads = anchors(&std::fs::read_to_string(&target).unwrap());
                if !heads.iter().any(|h| h == frag) {
                    broken.push(format!("{}: {link} (no such heading)", file.display()));
                }
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

fn walk_all(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            walk_all(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// Every `docs/physics.md §N` (and `second-order.md §N`) the code cites is a section there.
#[test]
fn every_citation_resolves_in_the_clone() {
    let physics = read("docs/physics.md");
    let averaging = read("docs/averaging/second-order.md");
    let section = |doc: &str, s: &str| {
        doc.lines().any(|l| {
            l.starts_with('#')
                && l.trim_start_matches('#')
                    .trim()
                    .starts_with(&format!("{s}."))
        })
    };
    let mut files = Vec::new();
    walk_all(&root().join("src"), &mut files);
    files.extend(markdown_files());
    let mut missing = Vec::new();
    let mut cited = 0;
    for file in files {
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        assert!(
            !text.contains("../shared/"),
            "{} cites a file outside the repository",
            file.display()
        );
        for (doc, name) in [
            (&physics, "physics.md §"),
            (&averaging, "second-order.md §"),
        ] {
            for piece in text.split(name).skip(1) {
                let s: String = piece
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '.')
                    .collect();
                let s = s.trim_end_matches('.');
                cited += 1;
                if !section(doc, s) {
                    missing.push(format!("{}: {name}{s}", file.display()));
                }
            }
        }
    }
    assert!(
        cited > 20,
        "only {cited} citations found: the check reads nothing"
    );
    assert!(
        missing.is_empty(),
        "citations without a section:\n{}",
        missing.join("\n")
    );
}

/// docs/architecture.md names every layering test, and every `src/…` path it names exists.
#[test]
fn the_architecture_page_is_true() {
    let page = read("docs/architecture.md");
    let layering = read("tests/it/layering.rs");
    let mut names = layering.split("#[test]\nfn ").skip(1);
    let mut count = 0;
    for piece in names.by_ref() {
        let name = piece.split('(').next().unwrap();
        count += 1;
        assert!(
            page.contains(name),
            "docs/architecture.md does not name the rule `{name}`"
        );
    }
    assert!(count >= 6, "{count} layering tests found");
    for piece in page.split("`src/").skip(1) {
        let path: String = piece
            .chars()
            .take_while(|c| *c != '`' && *c != ' ')
            .collect();
        let path = path.replace("NAME", "kapitza").replace("PANE", "weak");
        let p = root().join("src").join(&path);
        assert!(
            p.exists(),
            "docs/architecture.md names src/{path}, which does not exist"
        );
    }
}

/// The code map of docs/architecture.md, as entries: a line at the margin opens one (`src/app/`,
/// `src/cast.rs`), a line indented by two opens one inside it (`src/physics/` + `scene.rs`), and
/// deeper lines continue the entry above. Each entry's key and its whole text.
fn code_map() -> Vec<(String, String)> {
    let page = read("docs/architecture.md");
    let section = page
        .split("## Code map")
        .nth(1)
        .and_then(|rest| rest.split("```").nth(1))
        .expect("docs/architecture.md has a code map in a fenced block");
    let mut entries: Vec<(String, String)> = Vec::new();
    let mut parent = String::new();
    for line in section.lines().skip(1) {
        let Some(first) = line.split_whitespace().next() else {
            continue;
        };
        let indent = line.len() - line.trim_start().len();
        if indent == 0 {
            first.clone_into(&mut parent);
            entries.push((parent.clone(), line.to_owned()));
        } else if indent == 2 {
            entries.push((format!("{parent}{first}"), line.to_owned()));
        } else if let Some((_, text)) = entries.last_mut() {
            text.push(' ');
            text.push_str(line.trim());
        }
    }
    entries
}

/// Issue 69: the code map names every source file: by its path, or by its name in the entry
/// of the folder it is in (a folder's `mod.rs` by the folder's entry or `folder/`). A file
/// added without a line on the map fails here, with the files to add.
#[test]
fn the_code_map_names_every_source_file() {
    let entries = code_map();
    let block: String = entries.iter().map(|(_, t)| t.as_str()).collect();
    let mut files = Vec::new();
    walk_all(&root().join("src"), &mut files);
    let mut unnamed = Vec::new();
    for file in files
        .iter()
        .filter(|f| f.extension().is_some_and(|e| e == "rs"))
    {
        let path = file
            .strip_prefix(root())
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let rel = path.trim_start_matches("src/");
        let name = path.rsplit('/').next().unwrap();
        let folder = &path[..path.len() - name.len()];
        let stem = name.trim_end_matches(".rs");
        let named_by_path = block.contains(&path)
            || block.contains(rel)
            || entries.iter().any(|(key, _)| *key == path);
        // The deepest folder above the file that has an entry, and the file's place under it.
        let by_folder = entries
            .iter()
            .filter(|(key, _)| key.ends_with('/') && folder.starts_with(key.as_str()))
            .max_by_key(|(key, _)| key.len())
            .is_some_and(|(key, _)| {
                // The folder's entry with the entries inside it.
                let text = entries
                    .iter()
                    .filter(|(k, _)| k.starts_with(key.as_str()))
                    .map(|(_, t)| t.as_str())
                    .collect::<Vec<_>>()
                    .join(" ");
                let below = &folder[key.len()..];
                let words = |w: &str| {
                    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                        .any(|t| t == w)
                };
                if below.is_empty() {
                    name == "mod.rs" || text.contains(name) || words(stem)
                } else {
                    let sub = below.trim_end_matches('/').rsplit('/').next().unwrap();
                    text.contains(&format!("{sub}/")) && (name == "mod.rs" || text.contains(name))
                }
            });
        if !(named_by_path || by_folder) {
            unnamed.push(path);
        }
    }
    assert!(
        files.len() > 150,
        "the walk found {} files under src/",
        files.len()
    );
    unnamed.sort();
    assert!(
        unnamed.is_empty(),
        "docs/architecture.md's code map does not name {} source files:\n{}",
        unnamed.len(),
        unnamed.join("\n")
    );
}
