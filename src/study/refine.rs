//! Where a chart's answer changes (issue 70): the cells a chart computes, and those it infers.
//!
//! The grid is cut into blocks by a coarse lattice (every `stride`-th column and row, and the
//! last). A block is settled when every cell of its boundary and a few cells of its interior
//! (chosen at random, seeded by the grid and the block, so the same for every run and every
//! shard) are computed: when they and every other computed cell of the block give one answer
//! and its scene infers regions ([`crate::physics::chart::SceneChart::infers`]), the
//! rest of its interior may be inferred; otherwise it is cut in four at its middle row and
//! column and each quarter is settled the same way, down to blocks without an interior. An
//! undecided or failed cell never agrees, so the blocks around it are computed whole.
//!
//! Agreement is not enough (issue 80: a thin Mathieu tongue inside a block whose edges all said
//! "stable" vanished). A block is inferred only when its scene certifies it: every computed cell
//! of the block carries the continuous quantity behind its answer
//! ([`crate::physics::chart::Certainty`]: the pendulum's Floquet angle or exponent, the full
//! rattleback's distance to the critical curve or the phase of its reversals), and the smallest
//! margin from a change of answer exceeds twice the spread of that quantity over the block. A
//! scene that cannot certify infers nothing and computes every cell. Columns where the scene's
//! theory roots a thin region ([`crate::physics::chart::SceneChart::lines`]) are computed whole
//! in every block that crosses them.
//!
//! Everything here is a function of the cells computed so far: [`Refine::pending`] says which
//! cells to compute next, [`Refine::settle`] the verdict of every cell once none is pending.
//! A block reads only the cells of its own closed rectangle, so the top blocks are independent:
//! a shard takes whole blocks ([`Refine::blocks_of`]) and the parts merge into exactly the
//! cells of one run, whatever the order in which cells were computed or a run was resumed.

use std::collections::BTreeSet;

use super::output::Shard;
use crate::physics::chart::{Answer, Certainty, Verdict};

/// What certifies a computed cell: a chart (its scene's [`SceneChart::certainty`]), or a
/// function in tests.
///
/// [`SceneChart::certainty`]: crate::physics::chart::SceneChart::certainty
pub trait Certifies: Sync {
    /// The certainty of computed cell `n`'s verdict `v` (`None`: it certifies nothing).
    fn certainty(&self, n: usize, v: &Verdict) -> Option<Certainty>;
}

impl<F: Fn(usize, &Verdict) -> Option<Certainty> + Sync> Certifies for F {
    fn certainty(&self, n: usize, v: &Verdict) -> Option<Certainty> {
        self(n, v)
    }
}

/// How a scene certifies a computed cell (`None`: it cannot, and nothing around it is inferred).
pub type Certify<'a> = &'a dyn Certifies;

/// How far inside its answer every computed cell of an inferred block must be: its margin over
/// the spread of the certified quantity across the block.
pub const MARGIN_OVER_SPREAD: f64 = 2.0;

/// The widest a top block is, in cells.
pub const MAX_STRIDE: usize = 16;
/// One interior sample for every this many interior cells (at least one).
pub const SAMPLE_EVERY: usize = 64;

/// A rectangle of cells, its corners on the lattice: columns `x0..=x1`, rows `y0..=y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    /// First column.
    pub x0: usize,
    /// Last column.
    pub x1: usize,
    /// First row.
    pub y0: usize,
    /// Last row.
    pub y1: usize,
}

impl Block {
    fn has_interior(self) -> bool {
        self.x1 - self.x0 >= 2 && self.y1 - self.y0 >= 2
    }
}

/// How a chart of `cols × rows` cells is refined.
#[derive(Clone)]
pub struct Refine<'a> {
    /// Columns.
    pub cols: usize,
    /// Rows.
    pub rows: usize,
    /// The lattice's spacing (a power of two).
    pub stride: usize,
    /// The samples' seed, from the grid.
    seed: u64,
    /// How cells are certified; `None`: nothing is inferred, every cell is computed.
    certify: Option<Certify<'a>>,
    /// Columns every block that crosses them computes whole (sorted).
    lines: Vec<usize>,
}

impl std::fmt::Debug for Refine<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Refine")
            .field("cols", &self.cols)
            .field("rows", &self.rows)
            .field("stride", &self.stride)
            .field("infers", &self.certify.is_some())
            .field("lines", &self.lines)
            .finish_non_exhaustive()
    }
}

/// A well-mixed 64-bit function (`SplitMix64`'s finaliser): the samples' random numbers.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The lattice's points along an axis of `n` cells: every `stride`-th, and the last.
fn lattice(n: usize, stride: usize) -> Vec<usize> {
    let mut points: Vec<usize> = (0..n).step_by(stride).collect();
    if points.last() != Some(&(n - 1)) {
        points.push(n - 1);
    }
    points
}

/// The spans between neighbouring lattice points (one span `(0, 0)` for a single cell).
fn spans(n: usize, stride: usize) -> Vec<(usize, usize)> {
    let points = lattice(n, stride);
    if points.len() == 1 {
        return vec![(0, 0)];
    }
    points.windows(2).map(|w| (w[0], w[1])).collect()
}

impl<'a> Refine<'a> {
    /// The refinement of a `cols × rows` grid: the lattice as wide as a third of the shorter
    /// side allows (a power of two, 2 to [`MAX_STRIDE`]); nothing inferred until it is given a
    /// way to certify ([`Refine::certified_by`]).
    #[must_use]
    pub fn new(cols: usize, rows: usize) -> Self {
        let third = (cols.min(rows) / 3).max(2);
        let stride = (1usize << third.ilog2()).min(MAX_STRIDE);
        Self {
            cols: cols.max(1),
            rows: rows.max(1),
            stride,
            seed: mix(((cols as u64) << 32) ^ rows as u64),
            certify: None,
            lines: Vec::new(),
        }
    }

    /// The same refinement, inferring the blocks `certify` certifies (`None`: computing every
    /// cell).
    #[must_use]
    pub fn certified_by(self, certify: Option<Certify<'a>>) -> Self {
        Self { certify, ..self }
    }

    /// The same refinement, computing the columns `lines` whole in every block that crosses
    /// them (those outside the grid are ignored).
    #[must_use]
    pub fn with_lines(self, mut lines: Vec<usize>) -> Self {
        lines.retain(|&x| x < self.cols);
        lines.sort_unstable();
        lines.dedup();
        Self { lines, ..self }
    }

    /// Whether any block may be inferred.
    #[must_use]
    pub fn infers(&self) -> bool {
        self.certify.is_some()
    }

    /// The top blocks, row by row from the bottom.
    #[must_use]
    pub fn blocks(&self) -> Vec<Block> {
        let (xs, ys) = (spans(self.cols, self.stride), spans(self.rows, self.stride));
        ys.iter()
            .flat_map(|&(y0, y1)| xs.iter().map(move |&(x0, x1)| Block { x0, x1, y0, y1 }))
            .collect()
    }

    /// The top blocks of `shard` (all without one): block `b` goes to shard `b mod N + 1`,
    /// interleaved, so every shard gets a share of every region's boundaries.
    #[must_use]
    pub fn blocks_of(&self, shard: Option<Shard>) -> Vec<Block> {
        let all = self.blocks();
        match shard {
            None => all,
            Some(s) => all
                .into_iter()
                .enumerate()
                .filter(|(b, _)| b % s.count == s.index - 1)
                .map(|(_, block)| block)
                .collect(),
        }
    }

    /// The cells `blocks` own, in grid order: a block owns its columns `x0..x1` and rows
    /// `y0..y1` (its last column and row too at the grid's edge), so every cell has one owner.
    #[must_use]
    pub fn owned(&self, blocks: &[Block]) -> Vec<usize> {
        let mut cells = Vec::new();
        for b in blocks {
            let x_end = if b.x1 + 1 == self.cols {
                b.x1 + 1
            } else {
                b.x1
            };
            let y_end = if b.y1 + 1 == self.rows {
                b.y1 + 1
            } else {
                b.y1
            };
            for y in b.y0..y_end {
                cells.extend((b.x0..x_end).map(|x| y * self.cols + x));
            }
        }
        cells.sort_unstable();
        cells
    }

    /// The cells of `block` that must be computed before it is settled: its boundary and its
    /// interior samples.
    fn required(&self, b: Block) -> Vec<usize> {
        let at = |x: usize, y: usize| y * self.cols + x;
        let mut cells: Vec<usize> = (b.x0..=b.x1)
            .flat_map(|x| [at(x, b.y0), at(x, b.y1)])
            .chain((b.y0..=b.y1).flat_map(|y| [at(b.x0, y), at(b.x1, y)]))
            .collect();
        if b.has_interior() {
            let (w, h) = (b.x1 - b.x0 - 1, b.y1 - b.y0 - 1);
            let area = w * h;
            let key = (b.x0 as u64) << 48 ^ (b.x1 as u64) << 32 ^ (b.y0 as u64) << 16 ^ b.y1 as u64;
            let mut r = mix(self.seed ^ mix(key));
            for _ in 0..area.div_ceil(SAMPLE_EVERY) {
                r = mix(r);
                let p = (r % area as u64) as usize;
                cells.push(at(b.x0 + 1 + p % w, b.y0 + 1 + p / w));
            }
            for &x in self.lines.iter().filter(|&&x| b.x0 < x && x < b.x1) {
                cells.extend((b.y0 + 1..b.y1).map(|y| at(x, y)));
            }
        }
        cells
    }

    /// The answer every computed cell of `block`'s closed rectangle gives, when they give one
    /// and the scene certifies it: each cell's margin from a change of answer exceeds
    /// [`MARGIN_OVER_SPREAD`] times the spread of the certified quantity over the block.
    fn agreed(&self, b: Block, known: &[Option<Verdict>]) -> Option<Answer> {
        let certify = self.certify?;
        let mut agreed = None;
        let (mut lo, mut hi, mut margin) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
        for y in b.y0..=b.y1 {
            let row = y * self.cols;
            for (n, v) in (row + b.x0..=row + b.x1).filter_map(|n| Some((n, known[n].as_ref()?))) {
                let a = v.answer()?;
                if agreed.is_some_and(|b| b != a) {
                    return None;
                }
                agreed = Some(a);
                let c = certify.certainty(n, v)?;
                if !(c.value.is_finite() && c.margin.is_finite() && c.margin > 0.0) {
                    return None;
                }
                lo = lo.min(c.value);
                hi = hi.max(c.value);
                margin = margin.min(c.margin);
            }
        }
        (margin > MARGIN_OVER_SPREAD * (hi - lo))
            .then_some(agreed)
            .flatten()
    }

    /// Walks `block`: its missing cells into `pending`, or its inferred interior into
    /// `inferred`, or its quarters.
    fn walk(
        &self,
        b: Block,
        known: &[Option<Verdict>],
        pending: &mut BTreeSet<usize>,
        inferred: &mut Vec<(Block, Answer)>,
    ) {
        let missing: Vec<usize> = self
            .required(b)
            .into_iter()
            .filter(|&n| known[n].is_none())
            .collect();
        if !missing.is_empty() {
            pending.extend(missing);
            return;
        }
        if !b.has_interior() {
            return;
        }
        if let Some(answer) = self.agreed(b, known) {
            inferred.push((b, answer));
            return;
        }
        let (mx, my) = (b.x0.midpoint(b.x1), b.y0.midpoint(b.y1));
        for (x0, x1) in [(b.x0, mx), (mx, b.x1)] {
            for (y0, y1) in [(b.y0, my), (my, b.y1)] {
                self.walk(Block { x0, x1, y0, y1 }, known, pending, inferred);
            }
        }
    }

    /// Walks every block of `blocks`: the cells still to compute, and the blocks inferred with
    /// their answer.
    fn walk_all(
        &self,
        known: &[Option<Verdict>],
        blocks: &[Block],
    ) -> (BTreeSet<usize>, Vec<(Block, Answer)>) {
        let mut pending = BTreeSet::new();
        let mut inferred = Vec::new();
        for &b in blocks {
            self.walk(b, known, &mut pending, &mut inferred);
        }
        (pending, inferred)
    }

    /// The cells to compute next for `blocks`, in grid order (none: every cell is settled).
    /// `known` holds the computed cells (`None` elsewhere), indexed by cell.
    #[must_use]
    pub fn pending(&self, known: &[Option<Verdict>], blocks: &[Block]) -> Vec<usize> {
        self.walk_all(known, blocks).0.into_iter().collect()
    }

    /// Every cell's verdict as far as the computed ones `known` settle `blocks`: the computed
    /// cells', [`Verdict::Inferred`] inside the blocks whose cells agreed, `None` where cells
    /// are still pending.
    #[must_use]
    pub fn settle(&self, known: &[Option<Verdict>], blocks: &[Block]) -> Vec<Option<Verdict>> {
        self.step(known, blocks).1
    }

    /// [`Refine::pending`] and [`Refine::settle`] from one walk of the blocks (the explorer's
    /// worker asks both after every batch).
    #[must_use]
    pub fn step(
        &self,
        known: &[Option<Verdict>],
        blocks: &[Block],
    ) -> (Vec<usize>, Vec<Option<Verdict>>) {
        let (pending, inferred) = self.walk_all(known, blocks);
        let mut cells = known.to_vec();
        for (b, answer) in inferred {
            for y in b.y0 + 1..b.y1 {
                for x in b.x0 + 1..b.x1 {
                    let cell = &mut cells[y * self.cols + x];
                    if cell.is_none() {
                        *cell = Some(Verdict::Inferred(answer));
                    }
                }
            }
        }
        (pending.into_iter().collect(), cells)
    }

    /// The cells the first pass computes for `blocks` (their boundaries and samples): what
    /// the cost model multiplies by the refinement it expects.
    #[must_use]
    pub fn first_pass(&self, blocks: &[Block]) -> usize {
        let mut cells = BTreeSet::new();
        for &b in blocks {
            cells.extend(self.required(b));
        }
        cells.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scene that certifies every decided cell at once (a quantity that never varies).
    #[allow(clippy::unnecessary_wraps)] // a certificate function's shape
    fn flat(_: usize, _: &Verdict) -> Option<Certainty> {
        Some(Certainty {
            value: 0.0,
            margin: 1.0,
        })
    }

    /// The refinement of a `cols × rows` grid certified by [`flat`].
    fn certified(cols: usize, rows: usize) -> Refine<'static> {
        Refine::new(cols, rows).certified_by(Some(&flat))
    }

    /// Runs the refinement of a chart whose cell `(x, y)` is `f(x, y)` to its end: the
    /// verdicts and the cells computed.
    fn refined(
        r: &Refine,
        blocks: &[Block],
        f: &dyn Fn(usize, usize) -> Verdict,
    ) -> (Vec<Option<Verdict>>, usize) {
        let mut known = vec![None; r.cols * r.rows];
        let mut computed = 0;
        loop {
            let pending = r.pending(&known, blocks);
            if pending.is_empty() {
                break;
            }
            for n in pending {
                assert!(known[n].is_none(), "cell {n} asked twice");
                known[n] = Some(f(n % r.cols, n / r.cols));
                computed += 1;
            }
        }
        (r.settle(&known, blocks), computed)
    }

    #[test]
    fn a_uniform_chart_computes_its_lattice_and_samples_and_infers_the_rest() {
        let r = certified(200, 100);
        assert_eq!(r.stride, 16);
        let (cells, computed) = refined(&r, &r.blocks(), &|_, _| Verdict::counted(0));
        assert!(
            cells
                .iter()
                .all(|c| c.as_ref().and_then(Verdict::count) == Some(0))
        );
        assert_eq!(computed, r.first_pass(&r.blocks()));
        assert!(computed < 20_000 / 5, "{computed}");
        let inferred = cells
            .iter()
            .filter(|c| matches!(c, Some(Verdict::Inferred(_))))
            .count();
        assert_eq!(inferred + computed, 20_000);
    }

    #[test]
    fn a_line_and_a_lone_sampled_cell_are_found_and_the_rest_stays_exact() {
        let r = certified(100, 50);
        // A thin diagonal line of 1s, and an island of 2s of one cell at a sample.
        let blocks = r.blocks();
        let sample = r.required(blocks[1])[4 * 17];
        let (sx, sy) = (sample % 100, sample / 100);
        let f = |x: usize, y: usize| {
            if (x, y) == (sx, sy) {
                Verdict::counted(2)
            } else if x.abs_diff(2 * y) <= 1 {
                Verdict::counted(1)
            } else {
                Verdict::counted(0)
            }
        };
        let (cells, computed) = refined(&r, &blocks, &f);
        for y in 0..50 {
            for x in 0..100 {
                assert_eq!(
                    cells[y * 100 + x].as_ref().and_then(Verdict::count),
                    f(x, y).count(),
                    "cell ({x}, {y})"
                );
            }
        }
        assert!(computed < 5000 / 2, "{computed}");
    }

    #[test]
    fn an_undecided_cell_is_never_inferred_and_is_computed_around() {
        let r = certified(64, 64);
        let undecided = Verdict::found(Answer::Count(3), false, Vec::new());
        let f = |x: usize, y: usize| {
            if (x, y) == (16, 16) {
                undecided.clone()
            } else {
                Verdict::counted(0)
            }
        };
        let (cells, _) = refined(&r, &r.blocks(), &f);
        assert_eq!(cells[16 * 64 + 16], Some(undecided.clone()));
        for (x, y) in [(15, 15), (17, 17), (15, 17)] {
            assert_eq!(
                cells[y * 64 + x],
                Some(Verdict::counted(0)),
                "its neighbour ({x}, {y}) computed"
            );
        }
    }

    #[test]
    fn shards_own_every_cell_once_and_settle_as_one_run() {
        let r = certified(90, 37);
        let f = |x: usize, y: usize| Verdict::counted((x * x + 3 * y * y) / 900);
        let (whole, _) = refined(&r, &r.blocks(), &f);
        let mut owners = vec![0; 90 * 37];
        for i in 1..=4 {
            let blocks = r.blocks_of(Some(Shard { index: i, count: 4 }));
            let (part, _) = refined(&r, &blocks, &f);
            for n in r.owned(&blocks) {
                owners[n] += 1;
                assert_eq!(part[n], whole[n], "cell {n} of shard {i}/4");
            }
        }
        assert!(owners.iter().all(|&o| o == 1));
        for (cols, rows) in [(1, 1), (1, 7), (7, 1), (2, 3), (17, 5)] {
            let r = certified(cols, rows);
            let mut cells = r.owned(&r.blocks());
            cells.dedup();
            assert_eq!(cells, (0..cols * rows).collect::<Vec<_>>(), "{cols}x{rows}");
            let (settled, _) = refined(&r, &r.blocks(), &|_, _| Verdict::counted(1));
            assert!(settled.iter().all(Option::is_some), "{cols}x{rows}");
        }
    }

    #[test]
    fn a_scene_that_infers_nothing_computes_every_cell() {
        let r = Refine::new(64, 32);
        let (cells, computed) = refined(&r, &r.blocks(), &|_, _| Verdict::counted(2));
        assert_eq!(computed, 64 * 32);
        assert!(cells.iter().all(|c| *c == Some(Verdict::counted(2))));
    }

    /// A field whose quantity is `q(x, y)`, its answer `q < 0` (stable) or not, certified by
    /// the margin `|q|`.
    fn field(x: usize, y: usize, q: &dyn Fn(usize, usize) -> f64) -> Verdict {
        let v = q(x, y);
        Verdict::found(
            Answer::Stable(v < 0.0),
            true,
            vec![("trace", crate::physics::chart::Value::Number(Some(v)))],
        )
    }

    #[test]
    fn a_thin_region_inside_agreeing_edges_is_found_by_its_margin() {
        // An island of one stable cell inside a block, on no lattice line and at no sample:
        // every cell the first pass computes agrees ("not stable"), so agreement alone loses
        // it; the quantity's margins near it are small against its spread across the block, so
        // the certified refinement computes around it and finds it.
        let blind = certified(96, 48);
        let first: BTreeSet<usize> = blind
            .blocks()
            .iter()
            .flat_map(|&b| blind.required(b))
            .collect();
        let (ix, iy) = (33..47)
            .flat_map(|x| (17..31).map(move |y| (x, y)))
            .find(|&(x, y)| !first.contains(&(y * 96 + x)))
            .expect("a cell the first pass does not compute");
        let q = |x: usize, y: usize| {
            let (dx, dy) = (x as f64 - ix as f64, y as f64 - iy as f64);
            dx * dx + dy * dy - 0.2
        };
        let certify = |_: usize, v: &Verdict| {
            let trace = match v.computed()?.values.first()? {
                (_, crate::physics::chart::Value::Number(trace)) => (*trace)?,
                _ => return None,
            };
            Some(Certainty {
                value: trace,
                margin: trace.abs(),
            })
        };
        let r = Refine::new(96, 48).certified_by(Some(&certify));
        let (cells, computed) = refined(&r, &r.blocks(), &|x, y| field(x, y, &q));
        for y in 0..48 {
            for x in 0..96 {
                assert_eq!(
                    cells[y * 96 + x].as_ref().and_then(Verdict::answer),
                    field(x, y, &q).answer(),
                    "cell ({x}, {y})"
                );
            }
        }
        assert!(computed < 96 * 48, "nothing was inferred: {computed}");
        // Agreement alone (a flat certificate) loses it: else this test would prove nothing.
        let (lost, _) = refined(&blind, &blind.blocks(), &|x, y| field(x, y, &q));
        assert_eq!(
            lost[iy * 96 + ix].as_ref().and_then(Verdict::answer),
            Some(Answer::Stable(false))
        );
    }

    #[test]
    fn a_line_is_computed_whole_in_every_block_it_crosses() {
        // A region one column wide, rooted at a known column: with the column as a line, every
        // cell of it is computed even where the quantity says nothing (a flat certificate).
        let r = certified(64, 32).with_lines(vec![21, 500]);
        let f = |x: usize, _y: usize| Verdict::counted(usize::from(x == 21));
        let (cells, _) = refined(&r, &r.blocks(), &f);
        for y in 0..32 {
            assert_eq!(cells[y * 64 + 21], Some(Verdict::counted(1)), "row {y}");
        }
    }

    #[test]
    fn a_cell_without_a_certificate_stops_inference_around_it() {
        let none = |n: usize, _: &Verdict| {
            (n != 32 * 64 + 32).then_some(Certainty {
                value: 0.0,
                margin: 1.0,
            })
        };
        let r = Refine::new(64, 64).certified_by(Some(&none));
        let (cells, computed) = refined(&r, &r.blocks(), &|_, _| Verdict::counted(0));
        assert!(
            cells
                .iter()
                .all(|c| c.as_ref().and_then(Verdict::count) == Some(0))
        );
        let full = certified(64, 64);
        let (_, fewer) = refined(&full, &full.blocks(), &|_, _| Verdict::counted(0));
        assert!(computed > fewer, "{computed} against {fewer}");
    }
}
