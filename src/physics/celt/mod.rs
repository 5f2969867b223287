//! The classical rattleback ("celt"): a rigid body whose bottom is part of an ellipsoid, rolling
//! without slipping on a horizontal plane under gravity, with no dissipation (Kane & Levinson
//! 1982; docs/celt/model.md). It is the nonholonomic rattleback the paper argues against: its
//! spin reverses because the rolling constraint couples spin to rocking, not because of a
//! stiff spring.
//!
//! CGS units, per unit mass. Body frame at the mass centre G: x along semi-axis `a`, y along
//! `b`, z along `c`, pointing from the contact to the top. The state vector (this folder's own
//! business; nothing outside indexes it) is
//!
//! ```text
//!     y = (ω_x, ω_y, ω_z,  γ_x, γ_y, γ_z,  q_w, q_x, q_y, q_z,  X_G, Y_G,  φ)
//! ```
//!
//! with ω the body-frame angular velocity, γ the space "up" vector in body coordinates, q the
//! body → space quaternion, `(X_G, Y_G)` G's horizontal position and `φ = ∫ ω·γ dt` the angle
//! turned about the vertical (what the portrait draws against the spin; nothing feeds back
//! from it). The equations (model.md
//! §5): `γ̇ = γ × ω`, `v = r × ω`, `u = ω × v + ṙ × ω + g γ`, `f = −ω × Iω + r × u`,
//! `M ω̇ = f` with `M = I + |r|² 1 − r rᵀ`, where `r(γ)` runs from G to the contact point.
//!
//! The folder: parameters and validation, the field and its invariants (here), the integrators
//! and their events (`flows`), the headless runner (`run`), `auto` (`plan`, verifying by the one
//! loop `physics::verify` as `policy` says), the cost model (`budget`) and what the layers above
//! see (`scene`).
use crate::physics::numerics::elementary::Elementary;

pub mod budget;
pub mod chart;
#[cfg(test)]
pub mod contract;
pub mod field;
pub mod flows;
pub mod linear;
pub mod plan;
pub mod policy;
pub mod report;
pub mod reversal;
pub mod run;
pub mod scene;

use nalgebra::{SVector, Vector3};
use serde::Serialize;

use super::params::{ParamError, check_derived};

/// The state's dimension.
pub const DIM: usize = 13;
/// The state vector.
pub type State = SVector<f64, DIM>;

/// The body: ellipsoid, mass centre, inertia, gravity (per unit mass, CGS).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Params {
    /// Semi-axis along body x (cm).
    pub a: f64,
    /// Semi-axis along body y (cm).
    pub b: f64,
    /// Semi-axis along body z (cm).
    pub c: f64,
    /// `h`: G lies `h` below the ellipsoid's centre, on the c-axis (cm).
    pub offset: f64,
    /// `A`: moment of inertia about body x through G, per unit mass (cm²).
    pub ix: f64,
    /// `B`: about body y.
    pub iy: f64,
    /// `C`: about body z.
    pub iz: f64,
    /// `D`: the inertia tensor's entry `I_xy` (Kane's convention), per unit mass (cm²).
    pub product: f64,
    /// Gravity (cm/s²).
    pub gravity: f64,
}

/// The start: the body's attitude (`R0 = Rz(yaw) Rx(roll) Ry(pitch)`) and angular velocity.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Start {
    /// Roll about body x (rad).
    pub roll: f64,
    /// Pitch about body y (rad).
    pub pitch: f64,
    /// Heading (rad).
    pub yaw: f64,
    /// Body-frame angular velocity (rad/s).
    pub omega: [f64; 3],
}

/// A validated problem: body, start and the reversal band.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Problem {
    params: Params,
    start: Start,
    band: f64,
}

/// Largest tilt of the start (rad): the body must rest on its ellipsoidal bottom.
pub const TILT_MAX: f64 = 1.5;

impl Params {
    /// The Kane–Levinson body.
    pub const KANE_LEVINSON: Self = Self {
        a: 20.0,
        b: 3.0,
        c: 2.0,
        offset: 1.0,
        ix: 2.0,
        iy: 16.0,
        iz: 17.0,
        product: -0.2,
        gravity: 981.0,
    };

    /// Checks what a single field's range cannot: the mass centre above the plane, a positive
    /// definite inertia, finite derived quantities.
    ///
    /// # Errors
    /// The first violated condition.
    pub fn validate(&self) -> Result<(), ParamError> {
        if self.offset >= self.c {
            return Err(ParamError::OutOfRange {
                field: "offset",
                value: self.offset,
                allowed: "a number below the semi-axis c (the mass centre must sit above the plane)",
            });
        }
        if self.ix * self.iy - self.product * self.product <= 0.0 {
            return Err(ParamError::OutOfRange {
                field: "product",
                value: self.product,
                allowed: "|product| < sqrt(ix·iy) (a positive definite inertia)",
            });
        }
        // The principal moments of a real body obey the triangle inequality (each at most the
        // sum of the other two; equal for a flat one): ix = iy = 1, iz = 100 is no body.
        // `hypot`, not the square root of a sum of squares: `ix = 1e155` squared overflows, and
        // an infinite spread made every comparison below false (issue 66, H2).
        let mean = 0.5 * (self.ix + self.iy);
        let spread = (0.5 * (self.ix - self.iy)).e_hypot(self.product);
        let principal = [mean - spread, mean + spread, self.iz];
        let total: f64 = principal.iter().sum();
        check_derived(
            &[
                ("the in-plane principal moments' spread", spread),
                ("the principal moments' sum", total),
            ],
            &[
                ("ix", self.ix),
                ("iy", self.iy),
                ("iz", self.iz),
                ("product", self.product),
            ],
        )?;
        let violated = |principal: [f64; 3], total: f64| {
            (0..3).find(|&i| principal[i] > (total - principal[i]) * (1.0 + 1e-12))
        };
        if let Some(i) = violated(principal, total) {
            // Without the product the moments are ix, iy, iz: if those hold, the product is
            // what breaks it (a chart's corner D = -5 blamed iy = 16, issue 66).
            let plain = [self.ix.min(self.iy), self.ix.max(self.iy), self.iz];
            let (field, value) = if violated(plain, plain.iter().sum()).is_none() {
                ("product", self.product)
            } else if i == 2 {
                ("iz", self.iz)
            } else if self.ix >= self.iy {
                ("ix", self.ix)
            } else {
                ("iy", self.iy)
            };
            return Err(ParamError::OutOfRange {
                field,
                value,
                allowed: "principal moments each at most the sum of the other two (ix + iy ≥ iz and the like: a real body)",
            });
        }
        check_derived(
            &[
                (
                    "the rest height g·(c − h)",
                    self.gravity * (self.c - self.offset),
                ),
                ("a²", self.a * self.a),
                ("1/a²", (self.a * self.a).recip()),
                ("1/b²", (self.b * self.b).recip()),
                ("1/c²", (self.c * self.c).recip()),
                ("ix·iy", self.ix * self.iy),
            ],
            &[
                ("a", self.a),
                ("b", self.b),
                ("c", self.c),
                ("offset", self.offset),
                ("ix", self.ix),
                ("iy", self.iy),
                ("iz", self.iz),
                ("product", self.product),
                ("gravity", self.gravity),
            ],
        )
    }

    /// The inertia matrix about G.
    #[must_use]
    pub fn inertia(&self) -> nalgebra::Matrix3<f64> {
        nalgebra::Matrix3::new(
            self.ix,
            self.product,
            0.0,
            self.product,
            self.iy,
            0.0,
            0.0,
            0.0,
            self.iz,
        )
    }

    /// The skew of the principal axes: the minimum-inertia axis is turned by
    /// `δ = ½ atan2(2D, A − B)` about z from the geometric long axis (rad); the body's only
    /// chirality.
    #[must_use]
    pub fn skew(&self) -> f64 {
        if (self.ix - self.iy).abs() <= f64::EPSILON * self.ix.max(self.iy) {
            std::f64::consts::FRAC_PI_4 * self.product.signum()
        } else {
            0.5 * (2.0 * self.product / (self.ix - self.iy)).e_atan()
        }
    }

    /// `r(γ)`: from G to the contact point, body coordinates.
    #[must_use]
    #[inline]
    pub fn contact(&self, g: &Vector3<f64>) -> Vector3<f64> {
        let (a2, b2, c2) = (self.a * self.a, self.b * self.b, self.c * self.c);
        let s = (a2 * g.x * g.x + b2 * g.y * g.y + c2 * g.z * g.z).sqrt();
        Vector3::new(-a2 * g.x / s, -b2 * g.y / s, -c2 * g.z / s + self.offset)
    }

    /// The rest height of G above the plane, `c − h`.
    #[must_use]
    pub fn rest_height(&self) -> f64 {
        self.c - self.offset
    }

    /// The field `ẏ = f(y)` (model.md §5).
    #[must_use]
    #[inline]
    pub fn field(&self, y: &State) -> State {
        State::from(field::Coefficients::of(self).field(&y.data.0[0]))
    }

    /// The energy per unit mass, `½ ωᵀIω + ½ |r × ω|² − g r·γ` (conserved).
    #[must_use]
    pub fn energy(&self, y: &State) -> f64 {
        let w = omega(y);
        let g = gamma(y);
        let r = self.contact(&g);
        let v = r.cross(&w);
        0.5 * w.dot(&(self.inertia() * w)) + 0.5 * v.dot(&v) - self.gravity * r.dot(&g)
    }
}

/// ω of a state.
#[must_use]
pub fn omega(y: &State) -> Vector3<f64> {
    Vector3::new(y[0], y[1], y[2])
}

/// γ of a state.
#[must_use]
pub fn gamma(y: &State) -> Vector3<f64> {
    Vector3::new(y[3], y[4], y[5])
}

/// The quaternion `(w, x, y, z)` of a state.
#[must_use]
pub fn quaternion(y: &State) -> [f64; 4] {
    [y[6], y[7], y[8], y[9]]
}

/// The spin `σ = ω·γ`: the turning rate about the vertical an observer sees from above.
#[must_use]
#[inline]
pub fn spin(y: &State) -> f64 {
    y[0] * y[3] + y[1] * y[4] + y[2] * y[5]
}

/// The rotation matrix of a quaternion (normalised first).
#[must_use]
pub fn rotation(q: [f64; 4]) -> nalgebra::Matrix3<f64> {
    let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    let (w, x, y, z) = (q[0] / n, q[1] / n, q[2] / n, q[3] / n);
    nalgebra::Matrix3::new(
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}

fn quat_mul(p: [f64; 4], q: [f64; 4]) -> [f64; 4] {
    [
        p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
        p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
        p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
        p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0],
    ]
}

/// The heading of the body's long axis seen from above (rad, in `(−π, π]`).
#[must_use]
pub fn heading(y: &State) -> f64 {
    let r = rotation(quaternion(y));
    r[(1, 0)].e_atan2(r[(0, 0)])
}

/// The body's lean: the angles (rad) by which the `+x` end of its long axis and the `+y` end
/// of its cross axis rise above the horizontal (`asin γ_x`, `asin γ_y`).
#[must_use]
pub fn lean(y: &State) -> [f64; 2] {
    let g = gamma(y);
    let n = g.norm();
    [
        (g.x / n).clamp(-1.0, 1.0).e_asin(),
        (g.y / n).clamp(-1.0, 1.0).e_asin(),
    ]
}

/// The tilt of the body's z axis from the vertical (rad).
#[must_use]
pub fn tilt(y: &State) -> f64 {
    let g = gamma(y);
    (g.x * g.x + g.y * g.y).sqrt().e_atan2(g.z)
}

/// What the body looks like at a state: G and the contact point in space, the rotation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// G in space (cm).
    pub g: [f64; 3],
    /// The contact point in space (its height is 0 up to rounding).
    pub contact: [f64; 3],
    /// Body → space.
    pub rotation: nalgebra::Matrix3<f64>,
}

impl Problem {
    /// A validated problem.
    ///
    /// # Errors
    /// The first field outside its range (the ranges are the table's, `scene::PARAMS`), or a
    /// combination the body cannot have.
    pub fn new(params: Params, start: Start, band: f64) -> Result<Self, ParamError> {
        let values = scene::values_of(&params, &start, band);
        crate::physics::params::ParamSpec::check_all(&scene::PARAMS, &values)?;
        params.validate()?;
        let problem = Self {
            params,
            start,
            band,
        };
        // What the start makes of the body: its energy and its first derivative must be numbers
        // (a semi-axis of 1e100 or an offset of -1e300 overflow there, not in any one field).
        let y0 = problem.initial_state();
        let f0 = params.field(&y0);
        let named: Vec<(&'static str, f64)> =
            scene::PARAMS.iter().map(|s| s.key).zip(values).collect();
        check_derived(
            &[
                ("the energy at the start", params.energy(&y0)),
                (
                    "the motion at the start",
                    // A sum, not a maximum: a NaN anywhere stays a NaN.
                    f0.iter().map(|x| x.abs()).sum::<f64>(),
                ),
            ],
            &named,
        )?;
        Ok(problem)
    }

    crate::physics::params::params_and_start!("The body.", "The start.");

    /// The hysteresis band of macro reversals (rad/s).
    #[must_use]
    pub fn band(&self) -> f64 {
        self.band
    }

    /// The state at `t = 0`: the attitude from the angles, the contact at the space origin
    /// (model.md §7).
    #[must_use]
    pub fn initial_state(&self) -> State {
        let s = &self.start;
        let half = |x: f64| (0.5 * x).e_sin_cos();
        let (sz, cz) = half(s.yaw);
        let (sx, cx) = half(s.roll);
        let (sy, cy) = half(s.pitch);
        let q = quat_mul(
            quat_mul([cz, 0.0, 0.0, sz], [cx, sx, 0.0, 0.0]),
            [cy, 0.0, sy, 0.0],
        );
        let g = Vector3::new(
            -s.pitch.e_sin() * s.roll.e_cos(),
            s.roll.e_sin(),
            s.pitch.e_cos() * s.roll.e_cos(),
        );
        let r = self.params.contact(&g);
        let xg = -(rotation(q) * r);
        let mut y = State::zeros();
        y[0] = s.omega[0];
        y[1] = s.omega[1];
        y[2] = s.omega[2];
        y[3] = g.x;
        y[4] = g.y;
        y[5] = g.z;
        y[6] = q[0];
        y[7] = q[1];
        y[8] = q[2];
        y[9] = q[3];
        y[10] = xg.x;
        y[11] = xg.y;
        y
    }

    /// The pose of a state.
    #[must_use]
    pub fn pose(&self, y: &State) -> Pose {
        let rot = rotation(quaternion(y));
        let g = gamma(y);
        let r = self.params.contact(&g);
        let gpos = Vector3::new(y[10], y[11], -r.dot(&g));
        let contact = gpos + rot * r;
        Pose {
            g: [gpos.x, gpos.y, gpos.z],
            contact: [contact.x, contact.y, contact.z],
            rotation: rot,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kl(omega: [f64; 3]) -> Problem {
        Problem::new(
            Params::KANE_LEVINSON,
            Start {
                roll: 0.005,
                pitch: 0.005,
                yaw: 0.0,
                omega,
            },
            0.5,
        )
        .unwrap()
    }

    #[test]
    fn upright_rest_energy_is_g_times_rest_height() {
        let p = Problem::new(
            Params::KANE_LEVINSON,
            Start {
                roll: 0.0,
                pitch: 0.0,
                yaw: 0.3,
                omega: [0.0; 3],
            },
            0.5,
        )
        .unwrap();
        let y = p.initial_state();
        assert!((p.params().energy(&y) - 981.0).abs() < 1e-12);
        // At rest upright nothing moves.
        assert!(p.params().field(&y).norm() < 1e-12);
    }

    #[test]
    fn contact_starts_at_the_origin_and_gamma_is_the_quaternions_third_row() {
        let p = kl([0.3, -1.0, -5.0]);
        let y = p.initial_state();
        let pose = p.pose(&y);
        for c in pose.contact {
            assert!(c.abs() < 1e-14, "{c}");
        }
        let r = pose.rotation;
        for j in 0..3 {
            assert!((r[(2, j)] - y[3 + j]).abs() < 1e-15);
        }
    }

    #[test]
    fn the_field_keeps_the_energy_and_the_constraints_to_first_order() {
        let p = kl([0.7, -1.3, -5.0]);
        let y = p.initial_state();
        let dy = p.params().field(&y);
        // dE/dt = ∇E · f(y), by central differences.
        let h = 1e-6;
        let de = (p.params().energy(&(y + dy * h)) - p.params().energy(&(y - dy * h))) / (2.0 * h);
        assert!(de.abs() < 1e-6 * p.params().energy(&y), "dE/dt = {de}");
        // |γ|² and |q|² are first integrals of the field.
        assert!(gamma(&y).dot(&gamma(&dy)).abs() < 1e-14);
        let q = quaternion(&y);
        let dq = quaternion(&dy);
        let d: f64 = (0..4).map(|i| q[i] * dq[i]).sum();
        assert!(d.abs() < 1e-14);
    }

    #[test]
    fn the_kane_levinson_skew_is_plus_point_eight_two_degrees() {
        let d = Params::KANE_LEVINSON.skew().to_degrees();
        assert!((d - 0.818).abs() < 0.01, "{d}");
    }
}
