//! A chart's cell, in the words of its scene (issue 83): what a scene's cell found
//! ([`Verdict`]: an [`Answer`], whether it is decided, and the scene's own named values), the
//! fields it writes ([`Column`]s the scene lists in its folder, each of its own [`Field`]s a
//! name, a [`Kind`] and a meaning), and the written cell ([`CellOutput`]) read back.
//!
//! Nothing here names a scene's field: `reversals`, `first_reversal`, `stable` or `trace` are
//! declared in the folders that write them (`rattleback/scene.rs`, `celt/scene.rs`, …). A new
//! scene with a new kind of value (a mean energy, a period) declares it there too, and its JSON,
//! CSV, schema (`docs/schemas/map-NAME.schema.json`), merge and read-back follow, with no edit
//! here. What is shared is what every chart's machinery needs of any cell: its answer, the one
//! discrete thing regions are inferred from and the pane draws (a count, or a yes/no), whether
//! it is decided, and how it was found.

use std::collections::BTreeMap;

use serde::de::{Error as _, MapAccess, Visitor};
use serde::ser::SerializeMap as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::json::Number;

/// What a field of a scene's cells holds: its JSON type and its CSV text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A whole number (`0` in the CSV when absent).
    Count,
    /// A time in seconds, `null` when there is none (empty in the CSV).
    Time,
    /// A number that need not be finite (`"inf"`, `"-inf"`, `"nan"`), absent when the cell has
    /// none (empty in the CSV).
    Number,
    /// Yes or no (`false` in the CSV when absent).
    Flag,
}

/// One field a scene's cells carry, declared in its folder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// Its name in the JSON and the CSV's heading (a contract once shipped).
    pub name: &'static str,
    /// What it holds.
    pub kind: Kind,
    /// What it means (the schema's description).
    pub doc: &'static str,
}

impl Field {
    /// A field named `name` holding a `kind`, meaning `doc`.
    #[must_use]
    pub const fn new(name: &'static str, kind: Kind, doc: &'static str) -> Self {
        Self { name, kind, doc }
    }
}

/// A whole number as written (`None`: not one, or too large for this machine).
fn count(v: &serde_json::Value) -> Option<usize> {
    usize::try_from(v.as_u64()?).ok()
}

/// One of a scene's values in a computed cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A whole number.
    Count(usize),
    /// A time, or none.
    Time(Option<f64>),
    /// A number, or none (then absent from the cell).
    Number(Option<f64>),
    /// Yes or no.
    Flag(bool),
}

impl Value {
    /// The value as written (`None`: absent).
    fn json(self) -> Option<serde_json::Value> {
        Some(match self {
            Self::Count(n) => serde_json::Value::from(n),
            Self::Time(t) => t.map_or(serde_json::Value::Null, serde_json::Value::from),
            Self::Number(x) => serde_json::to_value(Number::from(x?)).ok()?,
            Self::Flag(b) => serde_json::Value::Bool(b),
        })
    }

    /// A value of `kind` read back from its JSON (`None`: absent where the kind may be; an
    /// outer `None`: not a value of that kind).
    fn read(kind: Kind, v: Option<&serde_json::Value>) -> Option<Self> {
        match (kind, v) {
            (Kind::Count, Some(v)) => Some(Self::Count(count(v)?)),
            (Kind::Time, Some(serde_json::Value::Null)) => Some(Self::Time(None)),
            (Kind::Time, Some(serde_json::Value::Number(x))) => Some(Self::Time(Some(x.as_f64()?))),
            (Kind::Number, None | Some(serde_json::Value::Null)) => Some(Self::Number(None)),
            (Kind::Number, Some(v)) => {
                Some(Self::Number(Some(f64::from(Number::deserialize(v).ok()?))))
            }
            (Kind::Flag, Some(v)) => Some(Self::Flag(v.as_bool()?)),
            (Kind::Count | Kind::Time | Kind::Flag, _) => None,
        }
    }

    /// The CSV text of a field of `kind` written as `v` (absent: `0`, `false` or empty).
    fn csv(kind: Kind, v: Option<&serde_json::Value>) -> String {
        match kind {
            Kind::Count => v
                .and_then(serde_json::Value::as_u64)
                .unwrap_or(0)
                .to_string(),
            Kind::Flag => v
                .and_then(serde_json::Value::as_bool)
                .unwrap_or(false)
                .to_string(),
            Kind::Time | Kind::Number => v
                .and_then(|v| Number::deserialize(v).ok())
                .map_or_else(String::new, |x| f64::from(x).to_string()),
        }
    }
}

/// What a computed cell found: its answer, whether the chart's tolerance decides it, and the
/// scene's own values by name (the fields its [`Column::Value`]s write).
#[derive(Clone, Debug, PartialEq)]
pub struct Findings {
    /// The answer.
    pub answer: Answer,
    /// Whether it is certain at the chart's tolerance.
    pub decided: bool,
    /// The scene's values, by their fields' names.
    pub values: Vec<(&'static str, Value)>,
}

impl Findings {
    /// The value of `field`, if the cell has one.
    #[must_use]
    pub fn value(&self, field: Field) -> Option<Value> {
        self.values
            .iter()
            .find(|(name, _)| *name == field.name)
            .map(|&(_, v)| v)
    }

    /// The time `field` holds (`None`: no such field; `Some(None)`: none in the window).
    #[must_use]
    pub fn time(&self, field: Field) -> Option<Option<f64>> {
        match self.value(field)? {
            Value::Time(t) => Some(t),
            Value::Count(_) | Value::Number(_) | Value::Flag(_) => None,
        }
    }

    /// The number `field` holds.
    #[must_use]
    pub fn number(&self, field: Field) -> Option<f64> {
        match self.value(field)? {
            Value::Number(x) => x,
            Value::Count(_) | Value::Time(_) | Value::Flag(_) => None,
        }
    }
}

/// What one cell found.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// The scene's routine ran at the cell: its answer and values.
    Computed(Findings),
    /// The cell's integration failed (a step size that underflowed, a state no longer finite):
    /// the chart marks it undecided and says why, instead of failing whole (issue 66, H8).
    Failed {
        /// What went wrong, as the run said it.
        error: String,
    },
    /// Not computed: its region's corners, edges and samples all gave this answer (issue 70,
    /// `study::refine`).
    Inferred(Answer),
}

/// The continuous quantity behind a decided cell's answer (issue 80): where the cell lies along
/// it (`value`) and how far it is from changing the answer (`margin`, in the same units). A
/// region is inferred only where every computed cell's margin exceeds twice the spread of the
/// values across the region: the answer cannot change between cells that far from its boundary
/// unless the quantity varies much faster inside than along the edges and samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Certainty {
    /// The quantity at the cell.
    pub value: f64,
    /// Its distance from the nearest value where the answer changes (positive).
    pub margin: f64,
}

/// A cell's answer, the one thing compared between neighbours (regions are inferred from it)
/// and drawn: a count (of reversals, of crossings), or a yes/no (a stability verdict).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    /// How many in the window.
    Count(usize),
    /// Whether the equilibrium is stable.
    Stable(bool),
}

impl Answer {
    fn json(self) -> serde_json::Value {
        match self {
            Self::Count(n) => serde_json::Value::from(n),
            Self::Stable(b) => serde_json::Value::Bool(b),
        }
    }

    /// The answer written in a field of `kind` (a count, or a flag).
    fn read(kind: Kind, v: &serde_json::Value) -> Option<Self> {
        match kind {
            Kind::Count => Some(Self::Count(count(v)?)),
            Kind::Flag => Some(Self::Stable(v.as_bool()?)),
            Kind::Time | Kind::Number => None,
        }
    }
}

/// Whether a cell of a chart's output was computed or inferred from its region (issue 70).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Mark {
    /// The scene's verified routine ran at this cell.
    Computed,
    /// Its region's corners, edges and seeded interior samples all agreed on this answer.
    Inferred,
}

impl Verdict {
    /// A computed cell with `answer`, `decided`, and the scene's `values`.
    #[must_use]
    pub fn found(answer: Answer, decided: bool, values: Vec<(&'static str, Value)>) -> Self {
        Self::Computed(Findings {
            answer,
            decided,
            values,
        })
    }

    /// A count alone, decided (a cell whose count is exact or verified by its run: the
    /// rattleback's limit, the oscillator's).
    #[must_use]
    pub const fn counted(count: usize) -> Self {
        Self::Computed(Findings {
            answer: Answer::Count(count),
            decided: true,
            values: Vec::new(),
        })
    }

    /// What the scene's routine found (`None`: failed or inferred).
    #[must_use]
    pub fn computed(&self) -> Option<&Findings> {
        match self {
            Self::Computed(found) => Some(found),
            Self::Failed { .. } | Self::Inferred(_) => None,
        }
    }

    /// The count (`None` for a yes/no answer or a failed cell), decided or not.
    #[must_use]
    pub fn count(&self) -> Option<usize> {
        match *self {
            Self::Computed(Findings {
                answer: Answer::Count(count),
                ..
            })
            | Self::Inferred(Answer::Count(count)) => Some(count),
            Self::Computed(_) | Self::Failed { .. } | Self::Inferred(Answer::Stable(_)) => None,
        }
    }

    /// The answer a decided cell gives (`None`: undecided or failed), computed or inferred.
    #[must_use]
    pub fn answer(&self) -> Option<Answer> {
        match *self {
            Self::Computed(Findings {
                answer,
                decided: true,
                ..
            })
            | Self::Inferred(answer) => Some(answer),
            Self::Computed(_) | Self::Failed { .. } => None,
        }
    }

    /// How the cell's verdict was found.
    #[must_use]
    pub fn mark(&self) -> Mark {
        match self {
            Self::Inferred(_) => Mark::Inferred,
            Self::Computed(_) | Self::Failed { .. } => Mark::Computed,
        }
    }

    /// Whether the cell's verdict is certain at the chart's tolerance.
    #[must_use]
    pub fn decided(&self) -> bool {
        match self {
            Self::Computed(found) => found.decided,
            Self::Failed { .. } => false,
            Self::Inferred(_) => true,
        }
    }
}

/// One cell of `study map`'s JSON: its index and coordinates, the fields its scene's columns
/// write (in their order), whether decided, a failed run's error, and how it was found. Read
/// back, the scene's fields are kept as written and checked against the scene's columns
/// ([`read_cell`]: a field not the scene's is refused there).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CellOutput {
    /// The cell's place in the grid, row by row from the bottom-left (`row · columns + column`).
    pub index: usize,
    /// The preset keys the cell sets, and their values.
    pub coords: BTreeMap<String, f64>,
    /// The scene's fields, by name, as written (its [`Column`]s' order).
    pub fields: Vec<(String, serde_json::Value)>,
    /// Whether the verdict is certain at the chart's tolerance (where the scene writes it);
    /// `false` on a failed cell.
    pub decided: Option<bool>,
    /// Why the cell's integration failed (a failed cell has this, `decided: false` and no
    /// verdict).
    pub error: Option<String>,
    /// `computed` (the scene's routine ran here) or `inferred` (its region agreed: the cell
    /// carries the answer alone, without the computed cell's times, rates or traces).
    pub mark: Option<Mark>,
}

impl CellOutput {
    /// The field `name` as written.
    #[must_use]
    pub fn field(&self, name: &str) -> Option<&serde_json::Value> {
        self.fields.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// The answer written in the answer field of a scene whose cells carry `columns`, decided
    /// or not (`None`: none written, a failed cell's).
    #[must_use]
    pub fn answer(&self, columns: &[Column]) -> Option<Answer> {
        let f = answer_field(columns)?;
        Answer::read(f.kind, self.field(f.name)?)
    }

    fn set(&mut self, name: &str, v: serde_json::Value) {
        self.fields.push((name.to_owned(), v));
    }
}

impl Serialize for CellOutput {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(None)?;
        m.serialize_entry("index", &self.index)?;
        m.serialize_entry("coords", &self.coords)?;
        for (name, v) in &self.fields {
            m.serialize_entry(name, v)?;
        }
        if let Some(decided) = self.decided {
            m.serialize_entry("decided", &decided)?;
        }
        if let Some(error) = &self.error {
            m.serialize_entry("error", error)?;
        }
        if let Some(mark) = self.mark {
            m.serialize_entry("mark", &mark)?;
        }
        m.end()
    }
}

impl<'de> Deserialize<'de> for CellOutput {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct CellVisitor;
        impl<'de> Visitor<'de> for CellVisitor {
            type Value = CellOutput;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a chart's cell: an object with `index` and `coords`")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<CellOutput, A::Error> {
                let mut index = None;
                let mut coords = None;
                let (mut decided, mut error, mut mark) = (None, None, None);
                let mut out = CellOutput::default();
                while let Some(key) = map.next_key::<String>()? {
                    let twice = |key: &str| A::Error::custom(format!("the field `{key}` twice"));
                    // Each field once: the shared ones by their slot, the scene's by name.
                    let again = match key.as_str() {
                        "index" => index.replace(map.next_value::<usize>()?).is_some(),
                        "coords" => coords.replace(map.next_value()?).is_some(),
                        "decided" => decided.replace(map.next_value()?).is_some(),
                        "error" => error.replace(map.next_value()?).is_some(),
                        "mark" => mark.replace(map.next_value()?).is_some(),
                        _ if out.field(&key).is_some() => true,
                        _ => {
                            let v = map.next_value()?;
                            out.fields.push((key, v));
                            continue;
                        }
                    };
                    if again {
                        return Err(twice(&key));
                    }
                }
                (out.decided, out.error, out.mark) =
                    (decided.flatten(), error.flatten(), mark.flatten());
                out.index = index.ok_or_else(|| A::Error::missing_field("index"))?;
                out.coords = coords.ok_or_else(|| A::Error::missing_field("coords"))?;
                Ok(out)
            }
        }
        d.deserialize_map(CellVisitor)
    }
}

// The part of a cell's schema every scene shares; the scene's own fields are added from its
// columns where the schemas are written (`commands/outputs.rs`).
/// One cell of `study map`'s JSON. Every cell has `index` and `coords`; its other fields are
/// its scene's (`map-NAME.schema.json` lists each scene's).
#[derive(schemars::JsonSchema)]
#[schemars(rename = "CellOutput")]
#[allow(dead_code)] // only its schema is used
struct SharedCell {
    /// The cell's place in the grid, row by row from the bottom-left (`row · columns + column`).
    index: usize,
    /// The preset keys the cell sets, and their values.
    coords: BTreeMap<String, f64>,
    /// Whether the verdict is certain at the chart's tolerance (where the scene writes it).
    /// `false` on a failed cell.
    decided: Option<bool>,
    /// Why the cell's integration failed (a failed cell has this, `decided: false` and no
    /// verdict).
    error: Option<String>,
    /// `computed` (the scene's routine ran here) or `inferred` (its region agreed: the cell
    /// carries the answer alone, without the computed cell's times, rates or traces).
    mark: Option<Mark>,
}

impl schemars::JsonSchema for CellOutput {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        SharedCell::schema_name()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        // The number's words, for the scenes' `Number` fields.
        let _ = generator.subschema_for::<Number>();
        SharedCell::json_schema(generator)
    }
}

/// A cell read back whose fields are not its scene's (`study merge`): which cell, which field
/// and what is wrong with it.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("cell {index}: `{field}` {fault} a {scene} chart's cell")]
pub struct NotItsFields {
    /// The cell's index.
    pub index: usize,
    /// The scene's name.
    pub scene: &'static str,
    /// The field.
    pub field: String,
    /// What is wrong with it.
    pub fault: FieldFault,
}

/// What is wrong with a field of a cell read back.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FieldFault {
    /// The scene's cells have no such field.
    #[error("is not a field of")]
    NotIts,
    /// A field the scene's cells must have.
    #[error("is missing from")]
    Missing,
    /// Not the kind of value the scene's field holds.
    #[error("is not of its kind in")]
    OtherKind,
}

/// A column of a chart's cells (a scene lists its own, in order: `ChartWords::csv`; the JSON
/// cell holds the same fields).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// The cell's index (the CSV's; every JSON cell has it).
    Index,
    /// The value across, named after the axis (the CSV's; the JSON's `coords`).
    X,
    /// The value up, named after the axis (the CSV's; the JSON's `coords`).
    Y,
    /// The cell's centre across, under a name of the scene's (the rattleback's `ratio`).
    Across(Field),
    /// The cell's centre up, under a name of the scene's (the rattleback's `inertia_ratio`).
    Up(Field),
    /// The cell's answer under the scene's name: a [`Kind::Count`] field for a count, a
    /// [`Kind::Flag`] for a yes/no.
    Answer(Field),
    /// One of the scene's values ([`Findings::values`]).
    Value(Field),
    /// Whether decided (`false` when absent).
    Decided,
    /// `computed` or `inferred` (issue 70).
    Mark,
}

impl Column {
    /// The column's heading on a chart whose axes are named `x` and `y`.
    #[must_use]
    pub fn heading<'a>(self, x: &'a str, y: &'a str) -> &'a str {
        match self {
            Self::Index => "index",
            Self::X => x,
            Self::Y => y,
            Self::Across(f) | Self::Up(f) | Self::Answer(f) | Self::Value(f) => f.name,
            Self::Decided => "decided",
            Self::Mark => "mark",
        }
    }

    /// The scene's own field the column writes (`None`: a column every chart has).
    #[must_use]
    pub fn field(self) -> Option<Field> {
        match self {
            Self::Across(f) | Self::Up(f) | Self::Answer(f) | Self::Value(f) => Some(f),
            Self::Index | Self::X | Self::Y | Self::Decided | Self::Mark => None,
        }
    }

    /// The answer's field, if this column is the answer.
    fn answer(&self) -> Option<Field> {
        match *self {
            Self::Answer(f) => Some(f),
            _ => None,
        }
    }

    /// The column's value in cell `c` of a chart whose axes are named `x` and `y`.
    #[must_use]
    pub fn value(self, c: &CellOutput, x: &str, y: &str) -> String {
        let coord = |name: &str| c.coords.get(name).copied().unwrap_or(f64::NAN).to_string();
        match self {
            Self::Index => c.index.to_string(),
            Self::X => coord(x),
            Self::Y => coord(y),
            Self::Across(f) | Self::Up(f) | Self::Answer(f) | Self::Value(f) => {
                Value::csv(f.kind, c.field(f.name))
            }
            Self::Decided => c.decided.unwrap_or(false).to_string(),
            Self::Mark => match c.mark {
                Some(Mark::Computed) => "computed".to_owned(),
                Some(Mark::Inferred) => "inferred".to_owned(),
                None => String::new(),
            },
        }
    }
}

/// Why a scene's columns would not make cells that read back as written.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ColumnsError {
    /// No answer, or more than one.
    #[error("{0} answer columns: a chart's cells have one (a count or a yes/no)")]
    Answers(usize),
    /// An answer of a kind that is neither a count nor a yes/no.
    #[error("the answer `{0}` is neither a count nor a flag")]
    AnswerKind(&'static str),
    /// A field named twice, or named as a field every cell has.
    #[error(
        "the field `{0}` is named twice, or as one every cell has (index, coords, decided, error, mark)"
    )]
    Name(&'static str),
}

/// Whether a scene's `columns` make cells that read back as written: one answer, a count or a
/// flag; every field of its own named once, and none named as a field every cell has (the
/// scene contract holds every registered scene to it).
///
/// # Errors
/// The first thing wrong.
pub fn check_columns(columns: &[Column]) -> Result<(), ColumnsError> {
    let answers: Vec<Field> = columns.iter().filter_map(Column::answer).collect();
    match answers.as_slice() {
        [f] if matches!(f.kind, Kind::Count | Kind::Flag) => {}
        [f] => return Err(ColumnsError::AnswerKind(f.name)),
        _ => return Err(ColumnsError::Answers(answers.len())),
    }
    let mut seen = vec!["index", "coords", "decided", "error", "mark"];
    for f in columns.iter().filter_map(|c| c.field()) {
        if seen.contains(&f.name) {
            return Err(ColumnsError::Name(f.name));
        }
        seen.push(f.name);
    }
    Ok(())
}

/// The answer column among a scene's `columns`.
#[must_use]
pub fn answer_field(columns: &[Column]) -> Option<Field> {
    columns.iter().find_map(Column::answer)
}

/// Writes into `out` the fields of verdict `v` that a scene's cells carry, its `columns`
/// (`ChartWords::csv`: the JSON cell and the CSV row hold the same fields), the cell's centre
/// being `at`.
pub fn fill_cell(columns: &[Column], v: &Verdict, at: (f64, f64), out: &mut CellOutput) {
    let number = |x: f64| Value::Number(Some(x)).json().unwrap_or_default();
    for &column in columns {
        match (column, v) {
            (Column::Across(f), _) => out.set(f.name, number(at.0)),
            (Column::Up(f), _) => out.set(f.name, number(at.1)),
            (
                Column::Answer(f),
                Verdict::Computed(Findings { answer, .. }) | Verdict::Inferred(answer),
            ) => {
                out.set(f.name, answer.json());
            }
            (Column::Value(f), Verdict::Computed(found)) => {
                if let Some(v) = found.value(f).and_then(Value::json) {
                    out.set(f.name, v);
                }
            }
            (Column::Decided, Verdict::Computed(found)) => out.decided = Some(found.decided),
            (Column::Decided, Verdict::Inferred(_)) => out.decided = Some(true),
            (Column::Mark, v) => out.mark = Some(v.mark()),
            // The index and coordinates every cell has; what a failed cell or an inferred one
            // does not carry: nothing (every column named, so a new one must say).
            (
                Column::Index
                | Column::X
                | Column::Y
                | Column::Answer(_)
                | Column::Value(_)
                | Column::Decided,
                _,
            ) => {}
        }
    }
}

/// The verdict a (not failed) cell of a scene whose cells carry `columns` says, read back.
///
/// # Errors
/// The first field the cell has that is not the scene's, or that it must have and lacks, or
/// that holds another kind of value.
pub fn read_cell(columns: &[Column], c: &CellOutput) -> Result<Verdict, (String, FieldFault)> {
    let own: Vec<Field> = columns.iter().filter_map(|c| c.field()).collect();
    if let Some((name, _)) = c
        .fields
        .iter()
        .find(|(n, _)| !own.iter().any(|f| f.name == n))
    {
        return Err((name.clone(), FieldFault::NotIts));
    }
    let fault = |f: Field| {
        let why = if c.field(f.name).is_some() {
            FieldFault::OtherKind
        } else {
            FieldFault::Missing
        };
        (f.name.to_owned(), why)
    };
    let Some(f) = answer_field(columns) else {
        return Err(("the answer".to_owned(), FieldFault::Missing));
    };
    let answer = c
        .field(f.name)
        .and_then(|v| Answer::read(f.kind, v))
        .ok_or_else(|| fault(f))?;
    if c.mark == Some(Mark::Inferred) {
        return Ok(Verdict::Inferred(answer));
    }
    let mut values = Vec::new();
    for column in columns {
        if let Column::Value(f) = *column {
            let v = Value::read(f.kind, c.field(f.name)).ok_or_else(|| fault(f))?;
            // A number a cell does not have is absent, not a value.
            if v != Value::Number(None) {
                values.push((f.name, v));
            }
        }
    }
    let decided = if columns.contains(&Column::Decided) {
        c.decided
            .ok_or_else(|| ("decided".to_owned(), FieldFault::Missing))?
    } else {
        true
    };
    Ok(Verdict::found(answer, decided, values))
}

#[cfg(test)]
mod tests {
    use super::*;

    const COUNT: Field = Field::new("count", Kind::Count, "how many");
    const WHEN: Field = Field::new("when", Kind::Time, "the first");
    const RATE: Field = Field::new("rate", Kind::Number, "a rate");
    const FLAG: Field = Field::new("flag", Kind::Flag, "a flag");
    const COLUMNS: &[Column] = &[
        Column::Index,
        Column::X,
        Column::Y,
        Column::Answer(COUNT),
        Column::Value(WHEN),
        Column::Value(RATE),
        Column::Value(FLAG),
        Column::Decided,
        Column::Mark,
    ];

    fn written(v: &Verdict) -> CellOutput {
        let mut out = CellOutput {
            index: 7,
            coords: BTreeMap::from([("a".to_owned(), 0.5)]),
            ..CellOutput::default()
        };
        fill_cell(COLUMNS, v, (0.5, 2.0), &mut out);
        out
    }

    /// A scene's own fields, of every kind, go out and come back as they were, through the
    /// JSON text; a field not the scene's, or of another kind, is refused.
    #[test]
    fn a_scenes_own_fields_read_back_as_written() {
        for v in [
            Verdict::found(
                Answer::Count(3),
                false,
                vec![
                    ("when", Value::Time(Some(1.25))),
                    ("rate", Value::Number(Some(f64::INFINITY))),
                    ("flag", Value::Flag(true)),
                ],
            ),
            Verdict::found(
                Answer::Count(0),
                true,
                vec![("when", Value::Time(None)), ("flag", Value::Flag(false))],
            ),
            Verdict::Inferred(Answer::Count(2)),
        ] {
            let text = serde_json::to_string(&written(&v)).unwrap();
            let back: CellOutput = serde_json::from_str(&text).unwrap();
            assert_eq!(back, written(&v), "{text}");
            assert_eq!(read_cell(COLUMNS, &back), Ok(v), "{text}");
        }
        let good = serde_json::to_value(written(&Verdict::found(
            Answer::Count(1),
            true,
            vec![("when", Value::Time(None)), ("flag", Value::Flag(false))],
        )))
        .unwrap();
        for (key, bad, fault) in [
            ("stable", serde_json::json!(true), FieldFault::NotIts),
            ("count", serde_json::json!(1.5), FieldFault::OtherKind),
            ("when", serde_json::json!("soon"), FieldFault::OtherKind),
            ("flag", serde_json::json!(1), FieldFault::OtherKind),
        ] {
            let mut v = good.clone();
            v[key] = bad;
            let cell: CellOutput = serde_json::from_value(v).unwrap();
            assert_eq!(read_cell(COLUMNS, &cell), Err((key.to_owned(), fault)));
        }
        // A field twice, shared or the scene's, is refused as it is read.
        for text in [
            r#"{"index":1,"coords":{},"index":2}"#,
            r#"{"index":1,"coords":{},"count":1,"count":2}"#,
            r#"{"index":1,"coords":{},"mark":"computed","mark":"inferred"}"#,
        ] {
            let e = serde_json::from_str::<CellOutput>(text).unwrap_err();
            assert!(e.to_string().contains("twice"), "{text}: {e}");
        }
        let mut v = good.clone();
        v.as_object_mut().unwrap().remove("when");
        let cell: CellOutput = serde_json::from_value(v).unwrap();
        assert_eq!(
            read_cell(COLUMNS, &cell),
            Err(("when".to_owned(), FieldFault::Missing))
        );
    }

    /// A scene's columns with no answer, two, an answer that is a time, a field named twice or
    /// as a shared one are refused; the test scene's are taken.
    #[test]
    fn columns_that_would_not_read_back_are_refused() {
        check_columns(COLUMNS).unwrap();
        let time = Field::new("t", Kind::Time, "");
        for (bad, want) in [
            (vec![Column::Value(WHEN)], ColumnsError::Answers(0)),
            (
                vec![Column::Answer(COUNT), Column::Answer(FLAG)],
                ColumnsError::Answers(2),
            ),
            (vec![Column::Answer(time)], ColumnsError::AnswerKind("t")),
            (
                vec![Column::Answer(COUNT), Column::Value(COUNT)],
                ColumnsError::Name("count"),
            ),
            (
                vec![
                    Column::Answer(COUNT),
                    Column::Value(Field::new("mark", Kind::Flag, "")),
                ],
                ColumnsError::Name("mark"),
            ),
        ] {
            assert_eq!(check_columns(&bad), Err(want));
        }
    }

    fn any_f64() -> impl proptest::strategy::Strategy<Value = f64> {
        use proptest::prelude::*;
        prop_oneof![
            any::<f64>(),
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(-0.0),
            Just(f64::MIN_POSITIVE / 8.0),
        ]
    }

    proptest::proptest! {
    /// Every cell a scene can write reads back as it was (`study merge` rests on it), through
    /// the JSON text, on generated cells: counts, times (finite or none), numbers of every
    /// kind (NaN, infinities, subnormals, −0 included, or none), flags, decided or not,
    /// computed or inferred. Compared as written again, so a NaN equals itself.
    #[test]
    fn every_generated_cell_reads_back_as_written(
        count in 0usize..10_000_000,
        when in proptest::option::of(-1e300f64..1e300),
        rate in proptest::option::of(any_f64()),
        flag in proptest::bool::ANY,
        decided in proptest::bool::ANY,
        inferred in proptest::bool::ANY,
    ) {
        let v = if inferred {
            Verdict::Inferred(Answer::Count(count))
        } else {
            let mut values = vec![("when", Value::Time(when)), ("flag", Value::Flag(flag))];
            if rate.is_some() {
                values.insert(1, ("rate", Value::Number(rate)));
            }
            Verdict::found(Answer::Count(count), decided, values)
        };
        let text = serde_json::to_string(&written(&v)).unwrap();
        let back: CellOutput = serde_json::from_str(&text).unwrap();
        let read = read_cell(COLUMNS, &back).unwrap();
        proptest::prop_assert_eq!(serde_json::to_string(&written(&read)).unwrap(), text);
        if let (Some(rate), Verdict::Computed(found)) = (rate, &read) {
            let got = found.number(RATE).unwrap();
            proptest::prop_assert_eq!(
                crate::physics::json::bits(got),
                crate::physics::json::bits(rate)
            );
        }
    }
    }

    /// The JSON's order is the columns': index, coords, the scene's fields, then decided,
    /// error and mark; the CSV's absent values are `0`, empty, `false`.
    #[test]
    fn a_cell_is_written_in_its_columns_order() {
        let v = Verdict::found(
            Answer::Count(1),
            true,
            vec![("flag", Value::Flag(true)), ("when", Value::Time(None))],
        );
        assert_eq!(
            serde_json::to_string(&written(&v)).unwrap(),
            r#"{"index":7,"coords":{"a":0.5},"count":1,"when":null,"flag":true,"decided":true,"mark":"computed"}"#
        );
        let failed = written(&Verdict::Failed {
            error: "x".to_owned(),
        });
        let row: Vec<String> = COLUMNS.iter().map(|c| c.value(&failed, "a", "b")).collect();
        assert_eq!(
            row,
            ["7", "0.5", "NaN", "0", "", "", "false", "false", "computed"]
        );
    }
}
