//! Numbers the way SPD writes them, C's `%g`: six significant digits, trailing zeros dropped,
//! an exponent only for very small or large magnitudes (`0.5`, `1.11022e-16`, `100000`).

use std::fmt;

/// Shows a number as C's `printf("%g")` does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct G(pub f64);

/// Significant digits of `%g`.
const PRECISION: i32 = 6;

impl fmt::Display for G {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x.is_nan() {
            return f.write_str("nan");
        }
        if x.is_infinite() {
            return f.write_str(if x > 0.0 { "inf" } else { "-inf" });
        }
        if x == 0.0 {
            // `-0` keeps its sign, as in C.
            return f.write_str(if x.is_sign_negative() { "-0" } else { "0" });
        }
        // The exponent after rounding to the precision decides between the two styles.
        let scientific = format!("{:.*e}", (PRECISION - 1) as usize, x);
        let (mantissa, exponent) = scientific
            .split_once('e')
            .expect("`{:e}` always writes an exponent");
        let exponent: i32 = exponent.parse().expect("the exponent is an integer");
        if !(-4..PRECISION).contains(&exponent) {
            let sign = if exponent < 0 { '-' } else { '+' };
            write!(
                f,
                "{}e{sign}{:02}",
                trim_zeros(mantissa),
                exponent.unsigned_abs()
            )
        } else {
            let decimals = (PRECISION - 1 - exponent) as usize;
            write!(f, "{}", trim_zeros(&format!("{x:.decimals$}")))
        }
    }
}

/// `1.50000` → `1.5`, `2.00000` → `2`; numbers without a point stay as they are.
fn trim_zeros(digits: &str) -> &str {
    if digits.contains('.') {
        digits.trim_end_matches('0').trim_end_matches('.')
    } else {
        digits
    }
}

#[cfg(test)]
mod tests {
    use super::G;

    #[test]
    fn matches_c_printf_g() {
        let cases = [
            (0.0, "0"),
            (-0.0, "-0"),
            (1.0, "1"),
            (0.5, "0.5"),
            (1.0 / 3.0, "0.333333"),
            (2.613125929752753, "2.61313"),
            (100000.0, "100000"),
            (1000000.0, "1e+06"),
            (1234567.0, "1.23457e+06"),
            (0.0001, "0.0001"),
            (0.00001234, "1.234e-05"),
            (1.1102230246251565e-16, "1.11022e-16"),
            (-2.55836e-17, "-2.55836e-17"),
            (999999.5, "1e+06"),
            (-0.0724237, "-0.0724237"),
            (3.0827, "3.0827"),
        ];
        for (x, expected) in cases {
            assert_eq!(G(x).to_string(), expected, "{x:e}");
        }
    }
}
