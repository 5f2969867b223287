//! The lesson `rattleback lesson new NAME` writes: every key in use, each commented, so a
//! lecturer edits rather than starts from nothing. It passes `rattleback check` as written (a
//! test checks it, the student's-eye reading included).

/// The skeleton; `@NAME@` is replaced by the lesson's name, `@TITLE@` by it in words and
/// `@PATH@` by the file's path.
pub const SKELETON: &str = r#"# A lesson for `rattleback lesson @NAME@` (docs/guide.md, "Writing a lesson", lists every key).
# Check it as you edit: `rattleback check @PATH@` reads it as the program does and as a
# student meets it (each step drawn at 80x24: the pane a step is about has room, nothing on
# screen gives a question's answer away).

[lesson]
title = "@TITLE@"
# Shown above the first step, in `rattleback lessons` and as the title of an exported page.
description = "What the student finds out, in a sentence or two."

# ---------------------------------------------------------------------------------------------
[[step]]
title = "Predict, then watch"
# Placeholders are written by the program: {time} {reversals} {at_least} {at_most} from the
# step's [step.until], {section.key} (any parameter, as --set names it) from its scenario.
text = "The rattleback spins with alpha_dot = {initial.alpha_dot} and rocks with gamma_dot = {initial.gamma_dot}. Answer with a number key, then press space and watch alpha_dot in the time series."
preset = "subcritical"          # a preset name (`rattleback presets`) or a file
set = ["run.t_end=10"]          # changes after the preset, as --set takes them: here the run
                                # ends at the question's time (played on, it would show step
                                # 2's answer)
pane = "series"                 # portrait, series, sweep, weak, map, body or compare

[step.question]                 # asked before the run; the answer shows after it
prompt = "Will the spin reverse before t = {time}?"
choices = ["yes", "no"]
answer = "yes"

[step.until]                    # what `n` waits for: every condition given
time = 10.0

# ---------------------------------------------------------------------------------------------
[[step]]
title = "Find the threshold yourself"
text = "Select alpha_dot (arrows up and down), raise it (right arrow, or Enter to type a value) and play each time to t = {time}. Where do the reversals stop?"
preset = "subcritical"

[step.question]                 # a number: right within `tolerance`
prompt = "From which alpha_dot on does the spin keep its sense?"
answer = 0.9102
tolerance = 0.02

[step.until]
parameter = "initial.alpha_dot" # any parameter of the step's scene
at_least = 0.92                 # and/or at_most; the student does not see it before answering
time = 30.0
"#;
