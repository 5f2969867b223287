//! Symmetric compositions of two exactly solvable parts (docs/physics.md §4), for any model that
//! implements [`Split`]: `A(a_0 h) B(b_1 h) A(a_1 h) … B(b_m h) A(a_m h)`. Strang is
//! `a = (½, ½)`, `b = (1)`; a composition of Strang steps of sizes `w_i h` merges adjacent
//! drifts (`yoshida4`, `yoshida6`, `suzuki8`); `blanes-moan4` is Blanes & Moan's 6-stage
//! order-4 splitting (2002, `S6`), whose error constant is far smaller than the triple jump's.
//! Each model says what its two parts are (a drift of the slow coordinate, an exact flow of
//! the fast part or of the forcing) by implementing [`Split`] in its own folder.

use crate::physics::method::Method;

/// A state that can follow each of two parts of its flow exactly.
pub trait Split {
    /// The first part's flow over `c · h` (the "drift").
    fn drift(&mut self, c: f64, h: f64);
    /// The second part's flow over `c · h` (the "kick").
    fn kick(&mut self, c: f64, h: f64);
}

// Published digits are kept as published.
#[allow(clippy::excessive_precision)]
/// Yoshida's 4th-order triple jump, `w1 = 1/(2 − 2^{1/3})`, `w0 = 1 − 2 w1`.
pub const YOSHIDA4: [f64; 3] = [
    1.351_207_191_959_657_8,
    -1.702_414_383_919_315_5,
    1.351_207_191_959_657_8,
];

#[allow(clippy::excessive_precision)]
/// Yoshida's (1990) 6th-order solution A, 7 stages.
pub const YOSHIDA6: [f64; 7] = [
    0.784_513_610_477_557_3,
    0.235_573_213_359_358_1,
    -1.177_679_984_178_871,
    1.315_186_320_683_911_2,
    -1.177_679_984_178_871,
    0.235_573_213_359_358_1,
    0.784_513_610_477_557_3,
];

#[allow(clippy::excessive_precision)]
/// The 15-stage 8th-order symmetric composition (Suzuki and Umeno 1993, `McLachlan` 1995).
pub const SUZUKI8: [f64; 15] = [
    0.741_670_364_350_612_9,
    -0.409_100_825_800_031_6,
    0.190_754_710_296_238_4,
    -0.573_862_471_116_082_3,
    0.299_064_181_303_655_9,
    0.334_624_918_245_298_2,
    0.315_293_092_396_766_6,
    -0.796_887_939_352_916_4,
    0.315_293_092_396_766_6,
    0.334_624_918_245_298_2,
    0.299_064_181_303_655_9,
    -0.573_862_471_116_082_3,
    0.190_754_710_296_238_4,
    -0.409_100_825_800_031_6,
    0.741_670_364_350_612_9,
];

/// Blanes & Moan (2002) `S6`, order 4: drift coefficients `a_1..a_3` (the middle `a_4` and
/// the symmetric half follow) and kick coefficients `b_1, b_2` (`b_3 = ½ − b_1 − b_2`).
const BLANES_MOAN4_A: [f64; 3] = [
    0.079_203_696_431_195_7,
    0.353_172_906_049_774,
    -0.042_065_080_357_719_5,
];
const BLANES_MOAN4_B: [f64; 2] = [0.209_515_106_613_362, -0.143_851_773_179_818];

/// A symmetric splitting `H1(a_0 h) H2(b_1 h) H1(a_1 h) … H2(b_m h) H1(a_m h)`.
#[derive(Clone, Debug)]
pub struct Composition {
    method: Method,
    /// Drift coefficients, one more than the kicks.
    drifts: Vec<f64>,
    /// Kick (exact fast flow) coefficients.
    kicks: Vec<f64>,
}

impl Composition {
    /// The composition of a splitting method.
    ///
    /// # Panics
    /// When `method` is not a splitting method (a programming error).
    #[must_use]
    pub fn of(method: Method) -> Self {
        let weights: &'static [f64] = match method {
            Method::Strang => &[1.0],
            Method::Yoshida4 => &YOSHIDA4,
            Method::Yoshida6 => &YOSHIDA6,
            Method::Suzuki8 => &SUZUKI8,
            Method::BlanesMoan4 => {
                let [a1, a2, a3] = BLANES_MOAN4_A;
                let [b1, b2] = BLANES_MOAN4_B;
                let (a4, b3) = (1.0 - 2.0 * (a1 + a2 + a3), 0.5 - b1 - b2);
                return Self {
                    method,
                    drifts: vec![a1, a2, a3, a4, a3, a2, a1],
                    kicks: vec![b1, b2, b3, b3, b2, b1],
                };
            }
            other => panic!("{other} is not a splitting method"),
        };
        Self::of_strang_steps(method, weights)
    }

    /// Strang steps of sizes `w_i h`, adjacent half drifts merged.
    #[must_use]
    pub fn of_strang_steps(method: Method, weights: &[f64]) -> Self {
        let mut drifts = vec![0.5 * weights[0]];
        for pair in weights.windows(2) {
            drifts.push(0.5 * (pair[0] + pair[1]));
        }
        drifts.push(0.5 * weights[weights.len() - 1]);
        Self {
            method,
            drifts,
            kicks: weights.to_vec(),
        }
    }

    /// The same coefficients under another method's name (a model's own variant, such as
    /// phase-locked Strang steps).
    #[must_use]
    pub fn named(self, method: Method) -> Self {
        Self { method, ..self }
    }

    /// Which method this is.
    #[must_use]
    pub fn method(&self) -> Method {
        self.method
    }

    /// The coefficients `(a_0 … a_m, b_1 … b_m)` of the drifts (the flow of the first part)
    /// and the kicks (the exact flow of the second), as fractions of the step: any model with
    /// two exactly solvable parts composes them the same way.
    #[must_use]
    pub fn coefficients(&self) -> (&[f64], &[f64]) {
        (&self.drifts, &self.kicks)
    }

    /// One step of size `h`: the drifts and kicks in order.
    pub fn apply<S: Split>(&self, state: &mut S, h: f64) {
        state.drift(self.drifts[0], h);
        for (b, a) in self.kicks.iter().zip(&self.drifts[1..]) {
            state.kick(*b, h);
            state.drift(*a, h);
        }
    }

    /// Exact fast flows per step.
    #[must_use]
    pub fn stages(&self) -> usize {
        self.kicks.len()
    }
}
