//! The elementary functions (sine, logarithm, power, …) every computation of the core takes,
//! one implementation on every platform: the `libm` crate (a port of musl's), so a native
//! build and the WebAssembly module (issue 82) compute the same bits. The platform's own
//! library (glibc's on Linux, the standard library's elsewhere) rounds some results otherwise
//! in the last place, which is enough for two trajectories to part.
//!
//! Session files of format 14 and older were recorded with the platform's functions; their
//! replay follows them ([`Functions::Platform`], set for the thread that computes by
//! [`following`]), so every existing recording still verifies on the platform it was made on.
//! Everything else (and every thread that never asks) takes the portable ones.
//!
//! The rest of `src/` calls these methods, never `f64::sin` and its kin (a hygiene test reads
//! the sources).

use std::cell::Cell;

/// Which implementation of the elementary functions a computation follows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Functions {
    /// The platform's (session files of format 14 and older).
    Platform,
    /// The `libm` crate's, the same on every platform.
    #[default]
    Portable,
}

thread_local! {
    static PLATFORM: Cell<bool> = const { Cell::new(false) };
}

/// Puts the thread's choice back, even when `body` panics.
struct Restore(bool);

impl Drop for Restore {
    fn drop(&mut self) {
        PLATFORM.with(|p| p.set(self.0));
    }
}

/// Runs `body` with `functions` on this thread, then the choice before.
pub fn following<R>(functions: Functions, body: impl FnOnce() -> R) -> R {
    let before = PLATFORM.with(|p| p.replace(functions == Functions::Platform));
    let _restore = Restore(before);
    body()
}

/// The functions this thread follows now.
pub(super) fn current() -> Functions {
    if platform() {
        Functions::Platform
    } else {
        Functions::Portable
    }
}

#[inline]
fn platform() -> bool {
    PLATFORM.with(Cell::get)
}

/// The elementary functions of a double, as the thread's [`Functions`] computes them.
pub trait Elementary: Copy {
    /// Sine.
    #[must_use]
    fn e_sin(self) -> Self;
    /// Cosine.
    #[must_use]
    fn e_cos(self) -> Self;
    /// Sine and cosine.
    fn e_sin_cos(self) -> (Self, Self);
    /// Tangent.
    #[must_use]
    fn e_tan(self) -> Self;
    /// Arcsine.
    #[must_use]
    fn e_asin(self) -> Self;
    /// Arccosine.
    #[must_use]
    fn e_acos(self) -> Self;
    /// Arctangent.
    #[must_use]
    fn e_atan(self) -> Self;
    /// Four-quadrant arctangent of `self / x`.
    #[must_use]
    fn e_atan2(self, x: Self) -> Self;
    /// Hyperbolic cosine.
    #[must_use]
    fn e_cosh(self) -> Self;
    /// Inverse hyperbolic cosine.
    #[must_use]
    fn e_acosh(self) -> Self;
    /// Exponential.
    #[must_use]
    fn e_exp(self) -> Self;
    /// Natural logarithm.
    #[must_use]
    fn e_ln(self) -> Self;
    /// Decimal logarithm.
    #[must_use]
    fn e_log10(self) -> Self;
    /// `self` to a real power.
    #[must_use]
    fn e_powf(self, y: Self) -> Self;
    /// `sqrt(self² + y²)` without undue overflow.
    #[must_use]
    fn e_hypot(self, y: Self) -> Self;
}

macro_rules! one {
    ($name:ident, $std:ident, $libm:ident) => {
        #[inline]
        fn $name(self) -> f64 {
            if platform() {
                self.$std()
            } else {
                libm::$libm(self)
            }
        }
    };
}

macro_rules! two {
    ($name:ident, $std:ident, $libm:ident) => {
        #[inline]
        fn $name(self, y: f64) -> f64 {
            if platform() {
                self.$std(y)
            } else {
                libm::$libm(self, y)
            }
        }
    };
}

#[allow(clippy::disallowed_methods)]
impl Elementary for f64 {
    one!(e_sin, sin, sin);
    one!(e_cos, cos, cos);
    one!(e_tan, tan, tan);
    one!(e_asin, asin, asin);
    one!(e_acos, acos, acos);
    one!(e_atan, atan, atan);
    one!(e_cosh, cosh, cosh);
    one!(e_acosh, acosh, acosh);
    one!(e_exp, exp, exp);
    one!(e_ln, ln, log);
    one!(e_log10, log10, log10);
    two!(e_atan2, atan2, atan2);
    two!(e_powf, powf, pow);
    two!(e_hypot, hypot, hypot);

    #[inline]
    fn e_sin_cos(self) -> (f64, f64) {
        if platform() {
            self.sin_cos()
        } else {
            libm::sincos(self)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The portable functions are the default; the platform's are taken inside `following`
    /// only, nested scopes restore theirs, and the choice comes back after a panic.
    #[test]
    fn the_choice_is_scoped() {
        assert_eq!(current(), Functions::Portable);
        following(Functions::Platform, || {
            assert_eq!(current(), Functions::Platform);
            following(Functions::Portable, || {
                assert_eq!(current(), Functions::Portable);
            });
            assert_eq!(current(), Functions::Platform);
        });
        assert_eq!(current(), Functions::Portable);
        let _ = std::panic::catch_unwind(|| {
            following(Functions::Platform, || panic!("inside"));
        });
        assert_eq!(current(), Functions::Portable);
    }

    /// Each method computes its function (against identities, not against itself), in both
    /// choices, to within a few units in the last place.
    #[test]
    fn each_function_is_the_one_named() {
        for f in [Functions::Portable, Functions::Platform] {
            following(f, || {
                let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON * b.abs().max(1.0);
                let x = 0.7_f64;
                let (s, c) = x.e_sin_cos();
                assert!(close(s, x.e_sin()) && close(c, x.e_cos()));
                assert!(close(s * s + c * c, 1.0));
                assert!(close(x.e_tan(), s / c));
                assert!(close(s.e_asin(), x) && close(c.e_acos(), x));
                assert!(close(x.e_tan().e_atan(), x) && close(s.e_atan2(c), x));
                assert!(close(x.e_exp().e_ln(), x) && close(1000.0_f64.e_log10(), 3.0));
                assert!(close(2.0_f64.e_powf(0.5), std::f64::consts::SQRT_2));
                assert!(close(3.0_f64.e_hypot(4.0), 5.0));
                assert!(close(x.e_cosh().e_acosh(), x));
            });
        }
    }
}
