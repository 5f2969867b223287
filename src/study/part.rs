//! A chart in parts that prove where they came from (issue 66).
//!
//! `study map --shard I/N` writes, before its cells, the chart's whole [`Description`]: the
//! preset's values (as TOML), every flag that shapes the chart, the program's version. After the
//! cells comes a SHA-256 [digest](digest_of) over everything else. `study merge`:
//!
//! - reads each part with a size cap that the description sets before any cell is read
//!   ([`read`]): a part can be no larger than its slice's cells can print;
//! - rebuilds the chart from the description (the caller parses the preset with the same
//!   validator as a preset file) and refuses a part whose header, cells' coordinates or cells'
//!   fields are not what that chart writes ([`merge`]);
//! - recomputes a random sample of each part's cells and refuses a part whose verdicts differ
//!   ([`sample`]), which catches a part edited and re-digested.
//!
//! The digest catches accidents (a part cut short, a changed byte); anyone can recompute it, so
//! against a forger only the recomputation counts, and it is a sample: a part edited in one cell
//! of many passes with the probability that the sample misses that cell. `--check` sets its size.

use std::cell::Cell;
use std::io::Read;

use serde::Serialize;
use serde::de::{DeserializeSeed, Error as _, MapAccess, SeqAccess, Visitor};

pub use super::ask::Description;
use super::ask::{MAX_CELLS, printable};
#[cfg(test)]
use super::chart::shard_cells;
use super::chart::{CellOutput, Chart, ChartOutput, Mark, Shard};

/// Bytes a part may have before its description is read (the header, the description with its
/// preset, the axes).
pub const HEADER_BYTES: u64 = 256 * 1024;

/// A SHA-256 that JSON is written into.
struct Hasher(sha2::Sha256);

impl std::io::Write for Hasher {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        sha2::Digest::update(&mut self.0, buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The digest of `part`: SHA-256 (hex) of its compact JSON without the `digest` field.
#[must_use]
pub fn digest_of(part: &mut ChartOutput) -> String {
    let kept = part.digest.take();
    let mut h = Hasher(sha2::Sha256::default());
    // Plain data: serialising it cannot fail.
    let _ = serde_json::to_writer(&mut h, &*part);
    part.digest = kept;
    hex::encode(sha2::Digest::finalize(h.0))
}

/// `part` with its digest set.
#[must_use]
pub fn sealed(mut part: ChartOutput) -> ChartOutput {
    part.digest = Some(digest_of(&mut part));
    part
}

/// The most bytes a part of a `cols`×`rows` chart holding `slice` cells can take as this program
/// prints it (pretty JSON; a generous bound: a cell prints in under 700 bytes, a curve point in
/// under 100).
#[must_use]
pub fn part_bytes_cap(cols: usize, rows: usize, slice: usize) -> u64 {
    let points = 4 * cols as u64 + 4 * rows as u64 + 8;
    HEADER_BYTES + 2048 * slice as u64 + 512 * points
}

/// A reader that gives end of file past `cap` bytes (a cap that may be raised while reading).
struct Capped<'a, R> {
    inner: R,
    cap: &'a Cell<u64>,
    read: u64,
    hit: bool,
}

impl<R: Read> Read for Capped<'_, R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let left = self.cap.get().saturating_sub(self.read);
        if left == 0 {
            self.hit = true;
            return Ok(0);
        }
        let want = buf.len().min(usize::try_from(left).unwrap_or(usize::MAX));
        let n = self.inner.read(&mut buf[..want])?;
        self.read += n as u64;
        Ok(n)
    }
}

/// Reads one part from `source`, streamed: at most [`HEADER_BYTES`] until its description and
/// shard are read, then at most what its slice can print ([`part_bytes_cap`]); the cells are
/// refused past the slice's count. Stdin is read the same way.
///
/// # Errors
/// What is wrong, in words (the caller names the file).
pub fn read(source: impl Read) -> Result<ChartOutput, String> {
    let cap = Cell::new(HEADER_BYTES);
    let mut capped = Capped {
        inner: std::io::BufReader::new(source),
        cap: &cap,
        read: 0,
        hit: false,
    };
    let parsed = {
        let mut de = serde_json::Deserializer::from_reader(&mut capped);
        let part = serde::Deserializer::deserialize_map(&mut de, PartVisitor { cap: &cap });
        part.and_then(|p| de.end().map(|()| p))
    };
    let over = || {
        format!(
            "larger than a part of this chart can be (read {} bytes, at most {} for its description and slice)",
            capped.read,
            cap.get()
        )
    };
    match parsed {
        Err(e) if capped.hit => Err(format!("{}; {}", over(), printable(&e.to_string()))),
        Err(e) => Err(format!(
            "not a part file of `study map --shard` ({})",
            printable(&e.to_string())
        )),
        Ok(part) => {
            // Valid JSON up to the cap with more behind it is still too large.
            if capped.hit && capped.inner.read(&mut [0u8; 1]).map_or(true, |n| n > 0) {
                return Err(over());
            }
            Ok(part)
        }
    }
}

struct PartVisitor<'a> {
    cap: &'a Cell<u64>,
}

impl<'de> Visitor<'de> for PartVisitor<'_> {
    type Value = ChartOutput;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a part file: a JSON object")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<ChartOutput, A::Error> {
        let mut rest = serde_json::Map::new();
        let mut description: Option<Description> = None;
        let mut shard: Option<Shard> = None;
        let mut cells: Option<Vec<CellOutput>> = None;
        while let Some(key) = map.next_key::<String>()? {
            let twice = || A::Error::custom(format!("the field `{key}` twice"));
            match key.as_str() {
                "description" => {
                    if description.is_some() {
                        return Err(twice());
                    }
                    description = Some(map.next_value()?);
                }
                "shard" => {
                    if shard.is_some() {
                        return Err(twice());
                    }
                    shard = Some(map.next_value()?);
                }
                "cells" => {
                    if cells.is_some() {
                        return Err(twice());
                    }
                    let (Some(d), Some(s)) = (&description, shard) else {
                        return Err(A::Error::custom(
                            "cells before a `description` and a `shard`: a whole chart, a part written by an older build (re-run that shard with this one), or an edited file",
                        ));
                    };
                    let [cols, rows] = d.grid;
                    if !(1..=MAX_CELLS).contains(&cols) || !(1..=MAX_CELLS).contains(&rows) {
                        return Err(A::Error::custom(format!(
                            "grid {cols}x{rows}: each side from 1 to {MAX_CELLS}"
                        )));
                    }
                    if s.index == 0 || s.index > s.count {
                        return Err(A::Error::custom(format!(
                            "shard {}/{}: I from 1 to N",
                            s.index, s.count
                        )));
                    }
                    let total = cols * rows;
                    let slice = if d.exhaustive {
                        total / s.count + usize::from(s.index <= total % s.count)
                    } else {
                        let refine = super::refine::Refine::new(cols, rows);
                        refine.owned(&refine.blocks_of(Some(s))).len()
                    };
                    self.cap.set(part_bytes_cap(cols, rows, slice));
                    cells = Some(map.next_value_seed(Cells { max: slice })?);
                }
                _ => {
                    if rest.contains_key(&key) {
                        return Err(twice());
                    }
                    let value: serde_json::Value = map.next_value()?;
                    rest.insert(key, value);
                }
            }
        }
        let Some(cells) = cells else {
            return Err(A::Error::custom("no `cells`"));
        };
        rest.insert("cells".to_owned(), serde_json::Value::Array(Vec::new()));
        let mut out: ChartOutput =
            serde_json::from_value(serde_json::Value::Object(rest)).map_err(A::Error::custom)?;
        out.description = description;
        out.shard = shard;
        out.cells = cells;
        Ok(out)
    }
}

/// A part's cells, at most `max` of them.
struct Cells {
    max: usize,
}

impl<'de> DeserializeSeed<'de> for Cells {
    type Value = Vec<CellOutput>;
    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for Cells {
    type Value = Vec<CellOutput>;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "at most {} cells", self.max)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut out = Vec::with_capacity(self.max.min(4096));
        while let Some(cell) = seq.next_element::<CellOutput>()? {
            if out.len() == self.max {
                return Err(A::Error::custom(format!(
                    "more cells than its shard has ({})",
                    self.max
                )));
            }
            out.push(cell);
        }
        Ok(out)
    }
}

/// The first field where two outputs (a part, a cell) differ, for a refusal that names it.
fn first_difference<T: Serialize>(a: &T, b: &T) -> String {
    let (Ok(serde_json::Value::Object(a)), Ok(serde_json::Value::Object(b))) =
        (serde_json::to_value(a), serde_json::to_value(b))
    else {
        return "?".to_owned();
    };
    a.keys()
        .chain(b.keys())
        .find(|k| a.get(*k) != b.get(*k))
        .cloned()
        .unwrap_or_else(|| "?".to_owned())
}

/// Why parts do not merge, or a part's cell does not recompute (`study merge`): each refusal
/// its own variant, so a caller (a script through the exit's words, a test) tells them apart;
/// the words name the part and the field.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MergeError {
    /// Nothing to merge.
    #[error("no parts given")]
    NoParts,
    /// A file without a description or a shard.
    #[error("{part}: not a part (no `description` or `shard`)")]
    NotAPart {
        /// The part's name.
        part: String,
    },
    /// Parts of two charts.
    #[error("{part}: another chart than {first}'s (their descriptions differ)")]
    OtherChart {
        /// The part's name.
        part: String,
        /// The first part's.
        first: String,
    },
    /// A part cut short or edited by accident.
    #[error("{part}: its digest does not match its content (cut short or edited)")]
    Digest {
        /// The part's name.
        part: String,
    },
    /// A part of another split.
    #[error(
        "{part}: shard {index}/{of} among shards of {count} ({first} is {first_index}/{count})"
    )]
    OtherSplit {
        /// The part's name.
        part: String,
        /// Its slice.
        index: usize,
        /// Its count.
        of: usize,
        /// The first part's count.
        count: usize,
        /// The first part's name.
        first: String,
        /// The first part's slice.
        first_index: usize,
    },
    /// A slice outside `1..=count`.
    #[error("{part}: shard {index}/{count}")]
    OutOfRange {
        /// The part's name.
        part: String,
        /// Its slice.
        index: usize,
        /// The count.
        count: usize,
    },
    /// A slice given twice.
    #[error("{part}: shard {index}/{count} given twice (also {other})")]
    Twice {
        /// The part's name.
        part: String,
        /// Its slice.
        index: usize,
        /// The count.
        count: usize,
        /// The other part with this slice.
        other: String,
    },
    /// Slices not given, as `I/N`.
    #[error("missing shards: {}", .0.join(", "))]
    Missing(Vec<String>),
    /// A part's cells not its slice's.
    #[error(
        "{part}: its cells are not those of shard {index}/{count} ({got} of {expected} expected; truncated or edited?)"
    )]
    NotItsSlice {
        /// The part's name.
        part: String,
        /// Its slice.
        index: usize,
        /// The count.
        count: usize,
        /// Cells it holds.
        got: usize,
        /// Cells of its slice.
        expected: usize,
    },
    /// A cell without its scene's fields.
    #[error("{part}: {fields}")]
    Fields {
        /// The part's name.
        part: String,
        /// Which cell, which scene.
        fields: super::chart::NotItsFields,
    },
    /// A wall time that is not one.
    #[error("{part}: wall_seconds {wall}: a time")]
    Wall {
        /// The part's name.
        part: String,
        /// What it says.
        wall: f64,
    },
    /// A cell that its chart does not write.
    #[error(
        "{part}: cell {index} is not one this chart writes (its `{field}` differs from the description's grid and scene)"
    )]
    Cell {
        /// The part's name.
        part: String,
        /// The cell.
        index: usize,
        /// The first field that differs.
        field: String,
    },
    /// A header field that the description does not give.
    #[error("{part}: its `{field}` is not what its description gives")]
    Header {
        /// The part's name.
        part: String,
        /// The first field that differs.
        field: String,
    },
    /// Computed cells that do not settle the chart as its parts say: a cell still to compute,
    /// or an inferred one its region's computed cells do not give.
    #[error(
        "{part}: cell {index} is {what} (a computed cell edited, or an inferred one its region's cells do not give)"
    )]
    Unsettled {
        /// The part's name.
        part: String,
        /// The cell.
        index: usize,
        /// What is wrong with it.
        what: &'static str,
    },
    /// A recomputation that failed or was cancelled.
    #[error("recomputing cells: {0}")]
    Recomputing(crate::physics::StepError),
    /// A cell recomputed to another value.
    #[error(
        "{part}: cell {index} recomputed gives another `{field}` than the part holds (edited, or written by another build)"
    )]
    Recomputed {
        /// The part's name.
        part: String,
        /// The cell.
        index: usize,
        /// The first field that differs.
        field: String,
    },
}

/// Puts the parts of `chart` (rebuilt from their common `description`) back together: the same
/// output as the unsharded run, but `wall_seconds` (the parts' sum).
///
/// # Errors
/// A part of another description, a digest that does not match, a slice given twice or
/// missing, a header or a cell that is not what the chart writes.
pub fn merge(
    chart: &Chart,
    schema_version: u32,
    parts: &[(String, ChartOutput)],
) -> Result<ChartOutput, MergeError> {
    let Some((first_name, first)) = parts.first() else {
        return Err(MergeError::NoParts);
    };
    let (Some(description), Some(first_shard)) = (&first.description, first.shard) else {
        return Err(MergeError::NotAPart {
            part: first_name.clone(),
        });
    };
    let count = first_shard.count;
    let total = chart.len();
    let exhaustive = description.exhaustive;
    let mut from = vec![0; total];
    let mut seen: Vec<Option<&str>> = vec![None; count];
    let mut verdicts = vec![None; total];
    let mut wall = 0.0;
    for (p, (name, part)) in parts.iter().enumerate() {
        let (Some(d), Some(shard)) = (&part.description, part.shard) else {
            return Err(MergeError::NotAPart { part: name.clone() });
        };
        if d != description {
            return Err(MergeError::OtherChart {
                part: name.clone(),
                first: first_name.clone(),
            });
        }
        let mut copy = part.clone();
        if part.digest.as_deref() != Some(digest_of(&mut copy).as_str()) {
            return Err(MergeError::Digest { part: name.clone() });
        }
        if shard.count != count {
            return Err(MergeError::OtherSplit {
                part: name.clone(),
                index: shard.index,
                of: shard.count,
                count,
                first: first_name.clone(),
                first_index: first_shard.index,
            });
        }
        if shard.index == 0 || shard.index > count {
            return Err(MergeError::OutOfRange {
                part: name.clone(),
                index: shard.index,
                count,
            });
        }
        if let Some(other) = seen[shard.index - 1] {
            return Err(MergeError::Twice {
                part: name.clone(),
                index: shard.index,
                count,
                other: other.to_owned(),
            });
        }
        seen[shard.index - 1] = Some(name);
        let (expected, read) = check_part(chart, schema_version, name, part, shard, exhaustive)?;
        for (&n, v) in expected.iter().zip(read) {
            verdicts[n] = Some(v);
            from[n] = p;
        }
        wall += part.wall_seconds;
    }
    let missing: Vec<String> = seen
        .iter()
        .enumerate()
        .filter(|(_, s)| s.is_none())
        .map(|(i, _)| format!("{}/{count}", i + 1))
        .collect();
    if !missing.is_empty() {
        return Err(MergeError::Missing(missing));
    }
    if !exhaustive {
        settles(chart, &verdicts, &|n| parts[from[n]].0.clone())?;
    }
    let all: Vec<usize> = (0..total).collect();
    let verdicts: Vec<_> = verdicts.into_iter().flatten().collect();
    let mut out = chart.output(
        schema_version,
        &first.preset,
        &all,
        &verdicts,
        None,
        exhaustive,
    );
    out.wall_seconds = wall;
    Ok(out)
}

/// The refinement run again over the parts' computed cells: nothing left to compute, and every
/// inferred cell what their regions give (`part_of` names a cell's part).
fn settles(
    chart: &Chart,
    verdicts: &[Option<super::chart::Verdict>],
    part_of: &dyn Fn(usize) -> String,
) -> Result<(), MergeError> {
    let known: Vec<_> = verdicts
        .iter()
        .map(|v| v.clone().filter(|v| v.mark() == Mark::Computed))
        .collect();
    let refine = chart.refine();
    let blocks = refine.blocks();
    if let Some(&index) = refine.pending(&known, &blocks).first() {
        return Err(MergeError::Unsettled {
            part: part_of(index),
            index,
            what: "one the refinement computes, but inferred",
        });
    }
    let settled = refine.settle(&known, &blocks);
    if let Some(index) = (0..verdicts.len()).find(|&n| settled[n] != verdicts[n]) {
        return Err(MergeError::Unsettled {
            part: part_of(index),
            index,
            what: "inferred where its region's cells disagree, or with another answer",
        });
    }
    Ok(())
}

/// One part against the chart its description gives: its cells those of its slice, each read
/// back into its verdict, and the header and cells exactly what the chart writes with them.
fn check_part(
    chart: &Chart,
    schema_version: u32,
    name: &str,
    part: &ChartOutput,
    shard: Shard,
    exhaustive: bool,
) -> Result<(Vec<usize>, Vec<super::chart::Verdict>), MergeError> {
    let expected = chart.shard_indices(exhaustive, shard);
    let got: Vec<usize> = part.cells.iter().map(|c| c.index).collect();
    if got != expected {
        return Err(MergeError::NotItsSlice {
            part: name.to_owned(),
            index: shard.index,
            count: shard.count,
            got: got.len(),
            expected: expected.len(),
        });
    }
    let read: Vec<_> = part
        .cells
        .iter()
        .map(|c| chart.verdict_of(c))
        .collect::<Result<_, _>>()
        .map_err(|fields| MergeError::Fields {
            part: name.to_owned(),
            fields,
        })?;
    if !(part.wall_seconds.is_finite() && part.wall_seconds >= 0.0) {
        return Err(MergeError::Wall {
            part: name.to_owned(),
            wall: part.wall_seconds,
        });
    }
    let mut written = chart.output(
        schema_version,
        &part.preset,
        &expected,
        &read,
        Some(shard),
        exhaustive,
    );
    written.description.clone_from(&part.description);
    written.wall_seconds = part.wall_seconds;
    written.digest.clone_from(&part.digest);
    if written.cells != part.cells {
        let (w, p) = written
            .cells
            .iter()
            .zip(&part.cells)
            .find(|(w, p)| w != p)
            .unwrap_or((&written.cells[0], &part.cells[0]));
        return Err(MergeError::Cell {
            part: name.to_owned(),
            index: p.index,
            field: first_difference(w, p),
        });
    }
    if written != *part {
        return Err(MergeError::Header {
            part: name.to_owned(),
            field: first_difference(&written, part),
        });
    }
    Ok((expected, read))
}

/// The cells' indices of the parts' cells `chosen` (by part and position, as [`choose`] gives).
#[must_use]
pub fn indices(parts: &[(String, ChartOutput)], chosen: &[(usize, usize)]) -> Vec<usize> {
    chosen
        .iter()
        .map(|&(p, k)| parts[p].1.cells[k].index)
        .collect()
}

/// Which cells of each part [`sample`] recomputes: `n` of each (all when fewer), chosen by
/// `random` (a source the forger cannot predict; tests pass a fixed one).
#[must_use]
pub fn choose(
    parts: &[(String, ChartOutput)],
    n: usize,
    random: &mut dyn FnMut() -> u64,
) -> Vec<(usize, usize)> {
    let mut chosen = Vec::new();
    for (p, (_, part)) in parts.iter().enumerate() {
        // The computed cells: an inferred one is checked against its region (`settles`).
        let mut picks: Vec<usize> = (0..part.cells.len())
            .filter(|&k| part.cells[k].mark != Some(Mark::Inferred))
            .collect();
        let len = picks.len();
        // A partial Fisher–Yates shuffle: the first `n` are a uniform sample.
        for k in 0..n.min(len) {
            let j = k + (random() % (len - k) as u64) as usize;
            picks.swap(k, j);
            chosen.push((p, picks[k]));
        }
    }
    chosen
}

/// Recomputes the cells `chosen` (part, position in its cells) and compares them with what the
/// parts hold, bit for bit.
///
/// # Errors
/// The first cell that differs (named by part and index), or a cancelled run.
pub fn sample(
    chart: &Chart,
    parts: &[(String, ChartOutput)],
    chosen: &[(usize, usize)],
    go_on: &(dyn Fn(f64) -> bool + Sync),
) -> Result<(), MergeError> {
    let indices: Vec<usize> = chosen
        .iter()
        .map(|&(p, k)| parts[p].1.cells[k].index)
        .collect();
    let verdicts = chart
        .cells(&indices, go_on, &|| ())
        .map_err(MergeError::Recomputing)?;
    for (&(p, k), v) in chosen.iter().zip(&verdicts) {
        let (name, part) = &parts[p];
        let given = &part.cells[k];
        let fresh = chart.cell_output(given.index, v);
        if fresh != *given {
            return Err(MergeError::Recomputed {
                part: name.clone(),
                index: given.index,
                field: first_difference(&fresh, given),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::study::ask::StudyAsk;
    use crate::study::chart::{Answer, Tally, Verdict};

    /// A pendulum cell given the other verdict (its `stable` negated).
    fn flip(cell: &mut CellOutput) {
        for (name, v) in &mut cell.fields {
            if name == "stable" {
                *v = serde_json::Value::Bool(!v.as_bool().unwrap());
            }
        }
    }

    /// A pendulum chart for tests.
    fn pendulum(cols: usize, rows: usize) -> Chart {
        crate::physics::kapitza::chart::tests::pendulum(cols, rows).into()
    }

    /// The description of an exhaustive chart (its parts' cells interleaved, `n mod N`).
    fn description(cols: usize, rows: usize) -> Description {
        Description::new(
            "[preset]\nname = \"p\"\n".to_owned(),
            &StudyAsk {
                grid: (cols, rows),
                t_end: 1.0,
                tolerance: 1e-8,
                exhaustive: true,
                ..StudyAsk::default()
            },
        )
    }

    fn part(chart: &Chart, d: &Description, i: usize, n: usize) -> (String, ChartOutput) {
        let s = Shard { index: i, count: n };
        let c = chart
            .compute(d.exhaustive, Some(s), &|_| true, &Tally::QUIET)
            .unwrap();
        if d.exhaustive {
            assert_eq!(c.indices, shard_cells(chart.len(), s));
        }
        let mut out = chart.output(1, "p", &c.indices, &c.verdicts, Some(s), d.exhaustive);
        out.description = Some(d.clone());
        (format!("part{i}"), sealed(out))
    }

    fn whole(chart: &Chart, exhaustive: bool) -> ChartOutput {
        let c = chart
            .compute(exhaustive, None, &|_| true, &Tally::QUIET)
            .unwrap();
        chart.output(1, "p", &c.indices, &c.verdicts, None, exhaustive)
    }

    fn printed(p: &ChartOutput) -> Vec<u8> {
        serde_json::to_vec_pretty(p).unwrap()
    }

    #[test]
    fn shards_merge_into_the_whole_and_refuse_what_is_not_a_partition() {
        let chart = pendulum(7, 5);
        let d = description(7, 5);
        let whole = whole(&chart, true);
        for n in 1..=4 {
            let parts: Vec<_> = (1..=n).rev().map(|i| part(&chart, &d, i, n)).collect();
            let mut merged = merge(&chart, 1, &parts).unwrap();
            merged.wall_seconds = 0.0;
            assert_eq!(merged, whole, "{n} shards");
        }
        let e = merge(&chart, 1, &[part(&chart, &d, 1, 3), part(&chart, &d, 3, 3)]).unwrap_err();
        assert_eq!(e, MergeError::Missing(vec!["2/3".to_owned()]));
        assert_eq!(e.to_string(), "missing shards: 2/3");
        let e = merge(
            &chart,
            1,
            &[
                part(&chart, &d, 1, 2),
                part(&chart, &d, 1, 2),
                part(&chart, &d, 2, 2),
            ],
        )
        .unwrap_err();
        assert!(matches!(e, MergeError::Twice { index: 1, .. }), "{e}");
        assert!(e.to_string().contains("given twice"), "{e}");
        let e = merge(&chart, 1, &[part(&chart, &d, 1, 2), part(&chart, &d, 2, 3)]).unwrap_err();
        assert!(
            matches!(
                e,
                MergeError::OtherSplit {
                    of: 3,
                    count: 2,
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("among shards of 2"), "{e}");
        let other = pendulum(7, 6);
        let e = merge(
            &chart,
            1,
            &[
                part(&chart, &d, 1, 2),
                part(&other, &description(7, 6), 2, 2),
            ],
        )
        .unwrap_err();
        assert!(matches!(e, MergeError::OtherChart { .. }), "{e}");
        let (name, mut cut) = part(&chart, &d, 2, 2);
        cut.cells.pop();
        let e = merge(
            &chart,
            1,
            &[part(&chart, &d, 1, 2), (name.clone(), cut.clone())],
        )
        .unwrap_err();
        assert!(matches!(e, MergeError::Digest { .. }), "{e}");
        let e = merge(&chart, 1, &[part(&chart, &d, 1, 2), (name, sealed(cut))]).unwrap_err();
        assert!(
            matches!(
                e,
                MergeError::NotItsSlice {
                    index: 2,
                    count: 2,
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("not those of shard 2/2"), "{e}");
    }

    #[test]
    fn an_edited_part_is_refused_even_when_re_digested() {
        let chart = pendulum(6, 4);
        let d = description(6, 4);
        let good = || vec![part(&chart, &d, 1, 2), part(&chart, &d, 2, 2)];
        // Part `i` edited by `edit`, its digest recomputed: the merge's refusal.
        let forged = |i: usize, edit: &dyn Fn(&mut ChartOutput)| {
            let mut parts = good();
            edit(&mut parts[i].1);
            parts[i].1 = sealed(parts[i].1.clone());
            merge(&chart, 1, &parts).unwrap_err()
        };
        // A coordinate moved: the grid says otherwise.
        let e = forged(0, &|p| {
            p.cells[0].coords.insert("pendulum.a".into(), 123.0);
        });
        assert!(
            matches!(e, MergeError::Cell { index: 0, ref field, .. } if field == "coords"),
            "{e}"
        );
        assert!(
            e.to_string()
                .contains("cell 0 is not one this chart writes"),
            "{e}"
        );
        // Relabelled as another scene.
        let other = crate::physics::ModelKind::ALL
            .into_iter()
            .find(|k| *k != chart.model())
            .unwrap();
        let e = forged(1, &|p| p.model = other);
        assert!(
            matches!(e, MergeError::Header { ref field, .. } if field == "model"),
            "{e}"
        );
        // A reversed axis.
        let e = forged(0, &|p| {
            (p.columns.min, p.columns.max) = (p.columns.max, p.columns.min);
        });
        assert!(
            matches!(e, MergeError::Header { ref field, .. } if field == "columns"),
            "{e}"
        );
        // A field of another scene's cells.
        let e = forged(0, &|p| {
            p.cells[1]
                .fields
                .push(("reversals".to_owned(), serde_json::json!(3)));
        });
        assert!(
            matches!(e, MergeError::Fields { ref fields, .. } if fields.field == "reversals"
                && fields.index == 2 && fields.fault == crate::physics::chart::FieldFault::NotIts),
            "{e}"
        );
        assert!(
            e.to_string()
                .contains("cell 2: `reversals` is not a field of a kapitza chart's cell"),
            "{e}"
        );
        // A flipped verdict passes the structure but not the recomputation of that cell.
        let mut parts = good();
        flip(&mut parts[1].1.cells[2]);
        parts[1].1 = sealed(parts[1].1.clone());
        merge(&chart, 1, &parts).unwrap();
        let every = choose(&parts, usize::MAX, &mut || 7);
        let e = sample(&chart, &parts, &every, &|_| true).unwrap_err();
        assert!(
            matches!(e, MergeError::Recomputed { index: 5, ref part, ref field } if part == "part2" && field == "stable"),
            "{e}"
        );
        sample(&chart, &good(), &every, &|_| true).unwrap();
    }

    #[test]
    fn a_part_is_read_within_its_slices_size() {
        let chart = pendulum(6, 4);
        let d = description(6, 4);
        let (_, p) = part(&chart, &d, 1, 3);
        let bytes = printed(&p);
        assert_eq!(read(&bytes[..]).unwrap(), p);
        // Whitespace without end, before and after the description.
        let e = read(std::io::repeat(b' ')).unwrap_err();
        assert!(e.contains("larger than a part"), "{e}");
        let mut padded = bytes.clone();
        padded.extend(std::iter::repeat_n(b' ', 3 << 20));
        let e = read(&padded[..]).unwrap_err();
        assert!(e.contains("larger than a part"), "{e}");
        // More cells than the slice has.
        let mut big = p.clone();
        big.cells.extend(p.cells.iter().cloned());
        let e = read(&printed(&big)[..]).unwrap_err();
        assert!(e.contains("more cells than its shard has"), "{e}");
        // A whole chart is not a part.
        let whole = whole(&chart, true);
        let e = read(&printed(&whole)[..]).unwrap_err();
        assert!(e.contains("not a part"), "{e}");
    }

    #[test]
    fn refined_parts_merge_into_one_runs_bytes_and_a_forged_inference_is_refused() {
        // 40×24 cells of the pendulum: a lattice of 8, regions inferred inside it.
        let chart = pendulum(40, 24);
        let d = Description {
            exhaustive: false,
            ..description(40, 24)
        };
        let one = whole(&chart, false);
        let marks = |o: &ChartOutput, m: Mark| o.cells.iter().filter(|c| c.mark == Some(m)).count();
        assert!(
            marks(&one, Mark::Inferred) > 100,
            "{}",
            marks(&one, Mark::Inferred)
        );
        // The answers are the exhaustive chart's, cell for cell.
        let every = whole(&chart, true);
        for (r, e) in one.cells.iter().zip(&every.cells) {
            assert_eq!(
                (r.field("stable"), r.decided),
                (e.field("stable"), e.decided),
                "cell {}",
                r.index
            );
        }
        for n in [1, 2, 3, 7] {
            let parts: Vec<_> = (1..=n).map(|i| part(&chart, &d, i, n)).collect();
            let mut merged = merge(&chart, 1, &parts).unwrap();
            merged.wall_seconds = one.wall_seconds;
            assert_eq!(printed(&merged), printed(&one), "{n} shards");
        }
        let good = || vec![part(&chart, &d, 1, 2), part(&chart, &d, 2, 2)];
        // An inferred cell given another answer, re-digested: its region's cells say otherwise.
        let mut parts = good();
        let k = parts[1]
            .1
            .cells
            .iter()
            .position(|c| c.mark == Some(Mark::Inferred))
            .unwrap();
        flip(&mut parts[1].1.cells[k]);
        parts[1].1 = sealed(parts[1].1.clone());
        let e = merge(&chart, 1, &parts).unwrap_err();
        assert!(
            matches!(e, MergeError::Unsettled { ref part, .. } if part == "part2"),
            "{e}"
        );
        // A computed cell claimed inferred: the refinement computes it.
        let mut parts = good();
        let k = parts[0]
            .1
            .cells
            .iter()
            .position(|c| c.mark == Some(Mark::Computed) && c.decided == Some(true))
            .unwrap();
        let cell = &mut parts[0].1.cells[k];
        let stable = cell.field("stable").and_then(serde_json::Value::as_bool);
        let verdict = Verdict::Inferred(Answer::Stable(stable.unwrap()));
        *cell = chart.cell_output(cell.index, &verdict);
        parts[0].1 = sealed(parts[0].1.clone());
        let e = merge(&chart, 1, &parts).unwrap_err();
        assert!(matches!(e, MergeError::Unsettled { .. }), "{e}");
        assert!(e.to_string().contains("the refinement computes"), "{e}");
        // The recomputation samples computed cells only.
        let parts = good();
        for &(p, k) in &choose(&parts, usize::MAX, &mut || 3) {
            assert_eq!(parts[p].1.cells[k].mark, Some(Mark::Computed));
        }
    }
}
