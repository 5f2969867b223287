//! Bracketed root finding shared by the event locators.

/// A root of `f` in `[a, b]` where `f(a)` and `f(b)` differ in sign (or one is zero), by the
/// Illinois variant of regula falsi; converges superlinearly and never leaves the bracket.
pub fn find_root(mut f: impl FnMut(f64) -> f64, a: f64, b: f64) -> f64 {
    let (fa, fb) = (f(a), f(b));
    illinois(f, a, b, fa, fb)
}

/// [`find_root`] for a root known to lie near `guess` (a nudged copy's zero beside its start's):
/// brackets `guess ± d` inside `[a, b]`, `d` from `1e-9 (b − a)` growing a thousandfold, and
/// searches the first that changes sign, else the whole of `[a, b]`. A narrow bracket takes a
/// few evaluations where the whole step, across a fast ripple, takes tens.
pub fn find_root_near(mut f: impl FnMut(f64) -> f64, a: f64, b: f64, guess: f64) -> f64 {
    let (lo, hi) = (a.min(b), a.max(b));
    if guess > lo && guess < hi {
        let mut d = 1e-9 * (hi - lo);
        while d < hi - lo {
            let (x, y) = ((guess - d).max(lo), (guess + d).min(hi));
            let (fx, fy) = (f(x), f(y));
            if (fx <= 0.0) != (fy <= 0.0) || fx == 0.0 || fy == 0.0 {
                return illinois(f, x, y, fx, fy);
            }
            d *= 1e3;
        }
    }
    find_root(f, a, b)
}

/// The Illinois iteration on `[a, b]` with `f(a) = fa`, `f(b) = fb` of different signs.
fn illinois(
    mut f: impl FnMut(f64) -> f64,
    mut a: f64,
    mut b: f64,
    mut fa: f64,
    mut fb: f64,
) -> f64 {
    if fa == 0.0 {
        return a;
    }
    if fb == 0.0 {
        return b;
    }
    let mut side = 0;
    for _ in 0..200 {
        let c = (a * fb - b * fa) / (fb - fa);
        let c = if c.is_finite() && c > a.min(b) && c < a.max(b) {
            c
        } else {
            0.5 * (a + b)
        };
        let fc = f(c);
        if fc == 0.0 {
            return c;
        }
        if (fc > 0.0) == (fb > 0.0) {
            b = c;
            fb = fc;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            a = c;
            fa = fc;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        }
        if (b - a).abs() <= 4.0 * f64::EPSILON * a.abs().max(b.abs()).max(f64::MIN_POSITIVE) {
            break;
        }
    }
    if fa.abs() < fb.abs() { a } else { b }
}

#[cfg(test)]
mod tests {
    use super::find_root;

    #[test]
    fn finds_cosine_root() {
        let r = find_root(f64::cos, 1.0, 2.0);
        assert!((r - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let r = find_root(|x| x * x * x, -1.0, 2.0);
        assert!(r.abs() < 1e-5, "{r}");
    }

    #[test]
    #[allow(clippy::float_cmp)]
    fn a_guess_near_the_root_finds_it_in_few_evaluations() {
        // A slope with a fast ripple (monotone, as a reconstructed spin rate is): across the
        // whole bracket the iteration crawls, from a guess 1e-9 away it does not, and both
        // find the same zero.
        let f = |x: f64| (x - 0.3) + 2e-5 * (2e4 * x).sin();
        let count = |near: Option<f64>| {
            let mut n = 0;
            let g = |x| {
                n += 1;
                f(x)
            };
            let r = match near {
                Some(guess) => super::find_root_near(g, 0.0, 1.0, guess),
                None => find_root(g, 0.0, 1.0),
            };
            (r, n)
        };
        let (whole, n_whole) = count(None);
        let (near, n_near) = count(Some(whole + 1e-9));
        assert!(
            f(whole).abs() < 1e-15 && (near - whole).abs() < 1e-15,
            "{whole} {near}"
        );
        assert!(
            n_near * 2 < n_whole,
            "{n_near} evaluations near, {n_whole} across"
        );
        // A guess with no zero near it still finds the zero.
        let (far, _) = count(Some(0.9));
        assert!(f(far).abs() < 1e-15, "{far}");
        // A guess outside the bracket searches the whole of it.
        let (outside, _) = count(Some(2.0));
        assert_eq!(outside, whole);
    }
}
