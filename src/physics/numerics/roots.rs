//! Bracketed root finding shared by the event locators.

/// A root of `f` in `[a, b]` where `f(a)` and `f(b)` differ in sign (or one is zero), by the
/// Illinois variant of regula falsi; converges superlinearly and never leaves the bracket.
pub fn find_root(mut f: impl FnMut(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let mut fa = f(a);
    let mut fb = f(b);
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
}
