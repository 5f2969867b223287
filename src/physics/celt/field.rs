//! The celt's field written once for one state or for [`LANES`]
//! states side by side (issue 84): [`Coefficients`] holds the body in `R`'s lanes, and
//! [`Coefficients::field`] is model.md §5's right-hand side, each operation in the order the
//! scalar field always took (`nalgebra`'s cross and dot products spelt out), so a lane of a
//! batched chart gives the bits a lone run gives.
// Inlined into the caller compiled for the machine's vector unit (`multiversion`): a call
// that is not inlined runs at the baseline's width.
#![allow(clippy::inline_always)]

use super::{DIM, Params};
use crate::physics::numerics::lanes::{F64x4, LANES, Real};

/// The body's constants as the field reads them, one set per lane.
#[derive(Clone, Copy, Debug)]
pub struct Coefficients<R> {
    a: R,
    b: R,
    c: R,
    offset: R,
    ix: R,
    iy: R,
    iz: R,
    product: R,
    gravity: R,
}

impl Coefficients<f64> {
    /// One body's.
    #[must_use]
    pub fn of(p: &Params) -> Self {
        Self {
            a: p.a,
            b: p.b,
            c: p.c,
            offset: p.offset,
            ix: p.ix,
            iy: p.iy,
            iz: p.iz,
            product: p.product,
            gravity: p.gravity,
        }
    }
}

impl Coefficients<F64x4> {
    /// Lane `l` holds `bodies[l]`'s.
    #[must_use]
    pub fn lanes(bodies: [&Params; LANES]) -> Self {
        let pack = |f: fn(&Params) -> f64| F64x4(std::array::from_fn(|l| f(bodies[l])));
        Self {
            a: pack(|p| p.a),
            b: pack(|p| p.b),
            c: pack(|p| p.c),
            offset: pack(|p| p.offset),
            ix: pack(|p| p.ix),
            iy: pack(|p| p.iy),
            iz: pack(|p| p.iz),
            product: pack(|p| p.product),
            gravity: pack(|p| p.gravity),
        }
    }
}

impl<R: Real> Coefficients<R> {
    /// The field `ẏ = f(y)` (model.md §5) in every lane.
    #[inline(always)]
    #[must_use]
    pub fn field(&self, y: &[R; DIM]) -> [R; DIM] {
        let two = R::splat(2.0);
        let w = [y[0], y[1], y[2]];
        let g = [y[3], y[4], y[5]];
        let (a2, b2, c2) = (self.a * self.a, self.b * self.b, self.c * self.c);
        let qq = a2 * g[0] * g[0] + b2 * g[1] * g[1] + c2 * g[2] * g[2];
        let s = qq.sqrt();
        let r = [-a2 * g[0] / s, -b2 * g[1] / s, -c2 * g[2] / s + self.offset];
        let dg = cross(g, w);
        let k = (a2 * g[0] * dg[0] + b2 * g[1] * dg[1] + c2 * g[2] * dg[2]) / (qq * s);
        let dr = [
            -a2 * dg[0] / s + a2 * g[0] * k,
            -b2 * dg[1] / s + b2 * g[1] * k,
            -c2 * dg[2] / s + c2 * g[2] * k,
        ];
        let v = cross(r, w);
        let (wv, drw) = (cross(w, v), cross(dr, w));
        let u: [R; 3] = std::array::from_fn(|i| wv[i] + drw[i] + g[i] * self.gravity);
        let l = [
            self.ix * w[0] + self.product * w[1],
            self.product * w[0] + self.iy * w[1],
            self.iz * w[2],
        ];
        let (wl, ru) = (cross(w, l), cross(r, u));
        let f: [R; 3] = std::array::from_fn(|i| -wl[i] + ru[i]);
        let rr = dot(r, r);
        let m11 = self.ix + rr - r[0] * r[0];
        let m22 = self.iy + rr - r[1] * r[1];
        let m33 = self.iz + rr - r[2] * r[2];
        let m12 = self.product - r[0] * r[1];
        let m13 = -r[0] * r[2];
        let m23 = -r[1] * r[2];
        let c11 = m22 * m33 - m23 * m23;
        let c12 = m13 * m23 - m12 * m33;
        let c13 = m12 * m23 - m13 * m22;
        let c22 = m11 * m33 - m13 * m13;
        let c23 = m12 * m13 - m11 * m23;
        let c33 = m11 * m22 - m12 * m12;
        let det = m11 * c11 + m12 * c12 + m13 * c13;
        let (q0, q1, q2, q3) = (y[6], y[7], y[8], y[9]);
        let half = R::splat(0.5);
        let one = R::splat(1.0);
        [
            (c11 * f[0] + c12 * f[1] + c13 * f[2]) / det,
            (c12 * f[0] + c22 * f[1] + c23 * f[2]) / det,
            (c13 * f[0] + c23 * f[1] + c33 * f[2]) / det,
            dg[0],
            dg[1],
            dg[2],
            half * (-q1 * w[0] - q2 * w[1] - q3 * w[2]),
            half * (q0 * w[0] + q2 * w[2] - q3 * w[1]),
            half * (q0 * w[1] - q1 * w[2] + q3 * w[0]),
            half * (q0 * w[2] + q1 * w[1] - q2 * w[0]),
            (one - two * (q2 * q2 + q3 * q3)) * v[0]
                + two * (q1 * q2 - q0 * q3) * v[1]
                + two * (q1 * q3 + q0 * q2) * v[2],
            two * (q1 * q2 + q0 * q3) * v[0]
                + (one - two * (q1 * q1 + q3 * q3)) * v[1]
                + two * (q2 * q3 - q0 * q1) * v[2],
            dot(w, g),
        ]
    }
}

/// `a × b`, as `nalgebra` computes it.
#[inline(always)]
fn cross<R: Real>(a: [R; 3], b: [R; 3]) -> [R; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a · b`, as `nalgebra` computes it for three components.
#[inline(always)]
fn dot<R: Real>(a: [R; 3], b: [R; 3]) -> R {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::numerics::elementary::Elementary;
    use nalgebra::Vector3;

    /// The field as it was written with `nalgebra` before issue 84 (the reference the scalar
    /// and lane forms are held to, bit for bit).
    fn written_with_nalgebra(p: &Params, y: &super::super::State) -> super::super::State {
        use super::super::State;

        let w = Vector3::new(y[0], y[1], y[2]);
        let g = Vector3::new(y[3], y[4], y[5]);
        let (a2, b2, c2) = (p.a * p.a, p.b * p.b, p.c * p.c);
        let qq = a2 * g.x * g.x + b2 * g.y * g.y + c2 * g.z * g.z;
        let s = qq.sqrt();
        let r = Vector3::new(-a2 * g.x / s, -b2 * g.y / s, -c2 * g.z / s + p.offset);
        let dg = g.cross(&w);
        let k = (a2 * g.x * dg.x + b2 * g.y * dg.y + c2 * g.z * dg.z) / (qq * s);
        let dr = Vector3::new(
            -a2 * dg.x / s + a2 * g.x * k,
            -b2 * dg.y / s + b2 * g.y * k,
            -c2 * dg.z / s + c2 * g.z * k,
        );
        let v = r.cross(&w);
        let u = w.cross(&v) + dr.cross(&w) + g * p.gravity;
        let l = Vector3::new(
            p.ix * w.x + p.product * w.y,
            p.product * w.x + p.iy * w.y,
            p.iz * w.z,
        );
        let f = -w.cross(&l) + r.cross(&u);
        let rr = r.dot(&r);
        let m11 = p.ix + rr - r.x * r.x;
        let m22 = p.iy + rr - r.y * r.y;
        let m33 = p.iz + rr - r.z * r.z;
        let m12 = p.product - r.x * r.y;
        let m13 = -r.x * r.z;
        let m23 = -r.y * r.z;
        let c11 = m22 * m33 - m23 * m23;
        let c12 = m13 * m23 - m12 * m33;
        let c13 = m12 * m23 - m13 * m22;
        let c22 = m11 * m33 - m13 * m13;
        let c23 = m12 * m13 - m11 * m23;
        let c33 = m11 * m22 - m12 * m12;
        let det = m11 * c11 + m12 * c12 + m13 * c13;
        let (q0, q1, q2, q3) = (y[6], y[7], y[8], y[9]);
        let mut out = State::zeros();
        out[0] = (c11 * f.x + c12 * f.y + c13 * f.z) / det;
        out[1] = (c12 * f.x + c22 * f.y + c23 * f.z) / det;
        out[2] = (c13 * f.x + c23 * f.y + c33 * f.z) / det;
        out[3] = dg.x;
        out[4] = dg.y;
        out[5] = dg.z;
        out[6] = 0.5 * (-q1 * w.x - q2 * w.y - q3 * w.z);
        out[7] = 0.5 * (q0 * w.x + q2 * w.z - q3 * w.y);
        out[8] = 0.5 * (q0 * w.y - q1 * w.z + q3 * w.x);
        out[9] = 0.5 * (q0 * w.z + q1 * w.y - q2 * w.x);
        out[10] = (1.0 - 2.0 * (q2 * q2 + q3 * q3)) * v.x
            + 2.0 * (q1 * q2 - q0 * q3) * v.y
            + 2.0 * (q1 * q3 + q0 * q2) * v.z;
        out[11] = 2.0 * (q1 * q2 + q0 * q3) * v.x
            + (1.0 - 2.0 * (q1 * q1 + q3 * q3)) * v.y
            + 2.0 * (q2 * q3 - q0 * q1) * v.z;
        out[12] = w.dot(&g);
        out
    }

    /// On states drawn from a printed seed around every shipped celt body: the scalar form is
    /// the `nalgebra` form's bits, and each lane of the batched form is the scalar form's.
    #[test]
    fn every_form_gives_the_same_bits() {
        let seed: u64 = 8484;
        eprintln!("seed {seed}");
        let mut x = seed;
        let mut uniform = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let bodies: Vec<Params> = crate::scenario::shipped::SHIPPED
            .iter()
            .filter_map(|(name, text)| crate::scenario::Preset::parse(text, name, name, &[]).ok())
            .filter_map(|p| match p.model {
                crate::physics::Model::Celt(c) => Some(*c.params()),
                _ => None,
            })
            .collect();
        assert!(bodies.len() >= 4, "{} celt bodies", bodies.len());
        for round in 0..2_000 {
            let lanes: [Params; LANES] =
                std::array::from_fn(|l| bodies[(round + l) % bodies.len()]);
            let ys: [[f64; DIM]; LANES] = std::array::from_fn(|_| {
                let mut y: [f64; DIM] = std::array::from_fn(|_| 40.0 * uniform() - 20.0);
                // A unit up vector, so the contact is defined.
                let (th, ph) = (3.0 * uniform(), std::f64::consts::TAU * uniform());
                (y[3], y[4], y[5]) = (th.e_sin() * ph.e_cos(), th.e_sin() * ph.e_sin(), th.e_cos());
                y
            });
            let packed = Coefficients::lanes(std::array::from_fn(|l| &lanes[l]));
            let y4: [F64x4; DIM] =
                std::array::from_fn(|i| F64x4(std::array::from_fn(|l| ys[l][i])));
            let out4 = packed.field(&y4);
            for l in 0..LANES {
                let reference = written_with_nalgebra(&lanes[l], &super::super::State::from(ys[l]));
                let scalar = Coefficients::of(&lanes[l]).field(&ys[l]);
                for i in 0..DIM {
                    assert_eq!(
                        scalar[i].to_bits(),
                        reference[i].to_bits(),
                        "seed {seed} round {round} component {i}"
                    );
                    assert_eq!(
                        out4[i].0[l].to_bits(),
                        scalar[i].to_bits(),
                        "seed {seed} round {round} lane {l}"
                    );
                }
            }
        }
    }
}
