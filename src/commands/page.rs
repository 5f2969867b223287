//! `replay FILE --export-html OUT`: a lecture as one self-contained web page. The session is
//! rendered into an asciicast (as `--export-cast` does: no key footer, no frame that changes
//! nothing), which the page inlines beside asciinema-player 3.18.0 (vendored from its npm
//! release with its licence, `assets/asciinema-player/`), so the page needs no network. Chapters
//! (and a lesson's steps) are links that seek to them, each with its time; chapters, steps and
//! notes are the player's markers. The page opens on the session's last frame (its poster) and
//! plays from the start when clicked.

use std::fmt::Write as _;

use crate::record::Recording;

/// The player's script, inlined.
const PLAYER_JS: &str = include_str!("../../assets/asciinema-player/asciinema-player.min.js");
/// The player's style sheet, inlined.
const PLAYER_CSS: &str = include_str!("../../assets/asciinema-player/asciinema-player.css");
/// The player's licence, inlined as a comment.
const PLAYER_LICENSE: &str = include_str!("../../assets/asciinema-player/LICENSE");

/// Text for HTML content and attributes.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
    out
}

/// JSON that is safe inside a `<script>` element: `<` written as `\u003c`, so no `</script>`
/// (or `<!--`) can end it.
fn script_json(value: &serde_json::Value) -> String {
    serde_json::to_string(value)
        .unwrap_or_else(|_| "null".to_owned())
        .replace('<', "\\u003c")
}

/// One chapter link (a lecturer's chapter, or a lesson's step): its number among the cast's
/// markers (chapters, steps and notes, in order) and its title.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Link {
    /// Index of the marker the link seeks to.
    pub marker: usize,
    /// The chapter's title (cleaned of control characters).
    pub title: String,
}

/// The chapter links of `rec` (its chapters and lesson steps), indexed as the cast's markers
/// are (a note is a marker too).
#[must_use]
pub fn links(rec: &Recording) -> Vec<Link> {
    rec.lines
        .iter()
        .filter_map(|(_, line)| {
            crate::cast::marker_label(&line.event).map(|label| (&line.event, label))
        })
        .enumerate()
        .filter(|(_, (event, _))| event.starts_chapter())
        .map(|(marker, (_, title))| Link {
            marker,
            title: title.replace(['\n', '\t'], " "),
        })
        .collect()
}

/// The page's poster: the player's frame just after the cast's last output (asciinema-player
/// draws a poster from the events strictly before its time, so at the last frame's own time it
/// showed the frame before it), which is the session's last screen.
#[must_use]
pub fn poster_time(cast: &str) -> f64 {
    crate::cast::last_frame_time(cast) + 0.001
}

/// A time on the player's seek bar, as it shows it: `m:ss`.
fn clock(seconds: f64) -> String {
    // Whole seconds of a page's length: far below u64's range.
    let s = seconds.max(0.0).floor() as u64;
    format!("{}:{:02}", s / 60, s % 60)
}

/// Writes the page of `rec` at `out` (replacing an existing file only when `replace`), telling
/// `seen` how many of the file's lines have been drawn; returns the cast's number of frames.
///
/// # Errors
/// As [`crate::cast::export_cast`].
pub fn export_html(
    rec: &Recording,
    path: &str,
    out: &std::path::Path,
    options: &crate::ui::UiOptions,
    size: crate::cast::CastSize,
    replace: bool,
    seen: &mut dyn FnMut(usize),
) -> Result<usize, crate::record::RecordError> {
    let (cast, frames) = crate::cast::cast_text(rec, path, options, size, seen)?;
    let name =
        crate::commands::outputs::recorded_preset(rec).map_or_else(|| path.to_owned(), |p| p.name);
    let page = lecture_page(rec, &crate::record::title(rec, &name), &cast);
    crate::scenario::write::write_atomic(out, page.as_bytes(), replace).map_err(|source| {
        crate::record::RecordError::Io {
            path: out.display().to_string(),
            source,
        }
    })?;
    Ok(frames)
}

/// The page: `title`, the player with `cast` inlined, and the chapter links of `rec`.
#[must_use]
pub fn lecture_page(rec: &Recording, title: &str, cast: &str) -> String {
    recorded_page(rec, title, cast, false, None)
}

/// The page `rattleback serve` gives once the lecture ended: [`lecture_page`], saying so, with
/// a link to the session file (every link carries `token`, when there is one).
#[must_use]
pub fn served_page(rec: &Recording, title: &str, cast: &str, token: Option<&str>) -> String {
    recorded_page(rec, title, cast, true, token)
}

/// The query every link of a served page carries: the token, if any.
fn query(token: Option<&str>) -> String {
    token.map_or_else(String::new, |t| format!("?token={}", escape(t)))
}

/// The line under a served page's player: the session file so far, to replay or fork.
fn session_link(token: Option<&str>) -> String {
    format!(
        "<p><a href=\"session.jsonl{}\" download=\"session.jsonl\">The session file</a>: \
         <code>rattleback replay session.jsonl</code> plays it again, <code>--verify</code> \
         checks it, and <code>f</code> in the replay forks it.</p>\n",
        query(token)
    )
}

/// The page of a whole session; `served` by `rattleback serve` (its links carrying `token`).
fn recorded_page(
    rec: &Recording,
    title: &str,
    cast: &str,
    served: bool,
    token: Option<&str>,
) -> String {
    let title = escape(&crate::scenario::text::clean(title));
    // Where each marker is on the player's clock (its seek bar), shown beside its chapter.
    let markers: Vec<f64> = crate::cast::player_clock(cast)
        .into_iter()
        .filter(|(_, kind)| kind == "m")
        .map(|(t, _)| t)
        .collect();
    let mut chapters = String::new();
    for l in links(rec) {
        let at = markers.get(l.marker).copied().unwrap_or(0.0);
        let _ = writeln!(
            chapters,
            "<li><a href=\"#\" data-marker=\"{}\" data-time=\"{at:.6}\">{}</a> <small>{}</small></li>",
            l.marker,
            escape(&l.title),
            clock(at)
        );
    }
    let chapters = if chapters.is_empty() {
        String::new()
    } else {
        format!("<nav><h2>Chapters</h2>\n<ol id=\"chapters\">\n{chapters}</ol></nav>\n")
    };
    // A lesson's description under its title, as `lessons` and its first step show it.
    let description = rec
        .header
        .lesson
        .as_ref()
        .filter(|l| !l.description.is_empty())
        .map_or_else(String::new, |l| {
            format!(
                "<p class=\"description\">{}</p>\n",
                escape(&crate::scenario::text::clean(&l.description))
            )
        });
    let (state, file) = if served {
        (
            "<p id=\"state\">The lecture has ended: this is its recording, to play again chapter by chapter.</p>\n"
                .to_owned(),
            session_link(token),
        )
    } else {
        (String::new(), String::new())
    };
    let cast_json = script_json(&serde_json::Value::String(cast.to_owned()));
    let body = format!(
        "<h1>{title}</h1>\n{description}{state}<div id=\"player\"></div>\n{chapters}{file}\
         <script type=\"application/json\" id=\"cast\">{cast_json}</script>\n"
    );
    let script = format!(
        r##"(function () {{
  var cast = JSON.parse(document.getElementById("cast").textContent);
  var player = AsciinemaPlayer.create({{ data: cast }}, document.getElementById("player"), Object.assign({{
    idleTimeLimit: {idle},
    preload: true,
    poster: "npt:{poster:.6}"
  }}, {narrow}));
  window.rattlebackPlayer = player;
  var links = document.querySelectorAll("#chapters a");
  for (var i = 0; i < links.length; i++) {{
    links[i].addEventListener("click", function (e) {{
      e.preventDefault();
      player.seek({{ marker: Number(this.dataset.marker) }});
      player.play();
    }});
  }}
}})();"##,
        idle = crate::cast::IDLE_TIME_LIMIT,
        poster = poster_time(cast),
        narrow = NARROW_FIT,
    );
    shell(&title, &body, &script)
}

/// How the player fits its screen: to the page's width, but on a narrow screen (a phone) at a
/// 12 px font that scrolls sideways (issue 82: fitted, a phone's 400 px made the text 5 px).
const NARROW_FIT: &str =
    r#"(window.innerWidth < 700 ? { fit: false, terminalFontSize: "12px" } : { fit: "width" })"#;

/// The served page's fork (issue 82): `f`, the button, the line that says how far the lecture
/// has moved on, `Esc` back.
const FORK_JS: &str = include_str!("../../web/fork.js");

/// The page `rattleback serve` gives while the lecture is recorded: the player reads the
/// frames from `events` (Server-Sent Events, asciinema-player's eventsource driver, no
/// buffering) as they are drawn; when the stream says the recording ended, the page loads
/// again and is then [`served_page`]. `f` (or the fork button) forks the lecture into the
/// reader's browser (issue 82): the page fetches the session so far and the explorer's module
/// (`serve --site`), replays the lecture to its last line in a Web Worker and hands it over;
/// `Esc` comes back to the live view, which played on meanwhile.
#[must_use]
pub fn live_page(title: &str, token: Option<&str>) -> String {
    let title = escape(&crate::scenario::text::clean(title));
    let body = format!(
        "<h1>{title}</h1>\n<p id=\"state\">Live: this page shows the lecturer's screen as it is \
         recorded. <b>f</b> forks it into your browser, to explore on your own.</p>\n\
         <div id=\"bar\"><button id=\"fork-button\">fork (f)</button>\
         <button id=\"live-button\" hidden>back to the live view (Esc)</button></div>\n\
         <div id=\"live\"><div id=\"player\"></div></div>\n\
         <div id=\"fork\" hidden><div id=\"buttons\">\
         <button data-key=\" \">play / pause</button><button data-key=\".\">step</button>\
         <button data-key=\"-\">slower</button><button data-key=\"+\">faster</button>\
         <button data-key=\"r\">reset</button><button data-key=\"R\">record</button>\
         <button data-key=\"?\">help</button></div>\
         <div id=\"wrap\"><pre id=\"screen\" tabindex=\"0\" aria-live=\"off\" \
         aria-label=\"your fork of the lecture\"></pre></div></div>\n\
         <script id=\"worker\" type=\"text/plain\">\n{worker}</script>\n{}",
        session_link(token),
        worker = crate::commands::web::WORKER_JS.replace("</script", "<\\/script"),
    );
    let events = script_json(&serde_json::Value::String(format!(
        "events{}",
        query(token)
    )));
    let session = script_json(&serde_json::Value::String(format!(
        "session.jsonl{}",
        query(token)
    )));
    let module = script_json(&serde_json::Value::String(format!(
        "rattleback.wasm{}",
        query(token)
    )));
    let script = format!(
        r#"{explorer}
{fork}
(function () {{
  var player = AsciinemaPlayer.create(
    {{ driver: "eventsource", url: {events}, bufferTime: 0 }},
    document.getElementById("player"),
    Object.assign({{ autoPlay: true }}, {narrow})
  );
  window.rattlebackPlayer = player;
  var fork = rattlebackFork({{ session: {session}, module: {module} }});
  player.addEventListener("ended", function () {{
    if (fork.ended()) return;
    document.getElementById("state").textContent =
      "The lecture has ended: loading its recording, to play again chapter by chapter.";
    setTimeout(function () {{ location.reload(); }}, 500);
  }});
}})();"#,
        explorer = crate::commands::web::EXPLORER_JS,
        fork = FORK_JS,
        narrow = NARROW_FIT,
    );
    shell(&title, &body, &script)
}

/// A page around `body`, with the player's style and script inlined (no outside request),
/// then `script`.
fn shell(title: &str, body: &str, script: &str) -> String {
    format!(
        r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="rattleback {version}">
<title>{title}</title>
<style>
{css}
body {{ font-family: sans-serif; max-width: 1100px; margin: 1em auto; padding: 0 1em; }}
nav ol {{ columns: 2; }}
#screen {{ font-family: "DejaVu Sans Mono", "Menlo", "Consolas", monospace; font-size: 14px;
          line-height: 1.2; margin: 0; white-space: pre; outline: none; display: inline-block;
          background: #1e1e1e; color: #d4d4d4; }}
#screen .cell {{ display: inline-block; width: 1ch; overflow: hidden; vertical-align: top; }}
#wrap, #player {{ overflow-x: auto; }}
#buttons button, #bar button {{ font-size: 15px; margin: 2px; padding: 6px 10px; }}
</style>
</head>
<body>
{body}<p><small>Recorded with rattleback {version}; played by asciinema-player 3.18.0
(Apache License 2.0, inlined below).</small></p>
<script>
/*
{license}
*/
{js}
</script>
<script>
{script}
</script>
</body>
</html>
"#,
        version = env!("CARGO_PKG_VERSION"),
        css = PLAYER_CSS,
        license = PLAYER_LICENSE.replace("*/", "* /"),
        js = PLAYER_JS,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_cannot_end_a_script_or_open_a_tag() {
        assert_eq!(
            escape("<b>\"x\" & 'y'\u{1b}"),
            "&lt;b&gt;&quot;x&quot; &amp; &#39;y&#39;"
        );
        let j = script_json(&serde_json::Value::String("</script><!--".to_owned()));
        assert!(!j.contains('<'), "{j}");
        assert_eq!(
            serde_json::from_str::<String>(&j).unwrap(),
            "</script><!--",
            "the same text once parsed"
        );
    }
}
