//! Number and text formatting shared by the plots and the HTML page.

/// `v` with `sig` significant digits, fixed notation for 1e-3 <= |v| < 1e6, scientific
/// otherwise, trailing zeros dropped: 240000, 0.5, 1.25e-7, -3.1.
pub fn num(v: f64, sig: usize) -> String {
    if !v.is_finite() {
        return if v.is_nan() {
            "NaN".into()
        } else if v > 0.0 {
            "∞".into()
        } else {
            "−∞".into()
        };
    }
    let sig = sig.max(1);
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    let s = if (1e-3..1e6).contains(&a) {
        let exponent = a.log10().floor() as i32;
        let decimals = (sig as i32 - 1 - exponent).max(0) as usize;
        let s = format!("{v:.decimals$}");
        // Rounding may carry into a new digit (999.95 -> 1000.0): still fine as text.
        trim_zeros(&s)
    } else {
        let s = format!("{v:.prec$e}", prec = sig - 1);
        match s.split_once('e') {
            Some((mantissa, exp)) => format!("{}e{exp}", trim_zeros(mantissa)),
            None => s,
        }
    };
    if s == "-0" { "0".into() } else { s }
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

/// A probability: 4 significant digits, `0` and `1` exact.
pub fn prob(p: f64) -> String {
    num(p, 4)
}

/// A count with thin-space thousands separators: 250 000.
pub fn count(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (k, c) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k).is_multiple_of(3) {
            out.push('\u{2009}');
        }
        out.push(c);
    }
    out
}

/// Seconds as "12.3 s", "850 ms", "2 min 05 s".
pub fn seconds(s: f64) -> String {
    if s >= 120.0 {
        let m = (s / 60.0).floor();
        format!("{} min {:02.0} s", m, s - 60.0 * m)
    } else if s >= 1.0 || s == 0.0 {
        format!("{} s", num(s, 3))
    } else {
        format!("{} ms", num(s * 1e3, 3))
    }
}

/// A file-name stem: ASCII letters, digits, `-`, `_`; anything else becomes `_`.
pub fn slug(name: &str) -> String {
    let s = alea_mesh::atomic::safe_file_name(name);
    let s = s.trim_matches('_').to_string();
    if s.is_empty() { "qoi".into() } else { s }
}

/// Escapes text for HTML element content and attribute values.
pub fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers() {
        assert_eq!(num(240000.0, 4), "240000");
        assert_eq!(num(0.5, 4), "0.5");
        assert_eq!(num(0.30000000004, 4), "0.3");
        assert_eq!(num(-4.56789, 3), "-4.57");
        assert_eq!(num(1.25e-7, 3), "1.25e-7");
        assert_eq!(num(2.5e7, 4), "2.5e7");
        assert_eq!(num(0.0, 4), "0");
        assert_eq!(num(-0.0001, 1), "-1e-4");
        assert_eq!(count(250_000), "250\u{2009}000");
        assert_eq!(count(121), "121");
        assert_eq!(count(1000), "1\u{2009}000");
        assert_eq!(seconds(0.0123), "12.3 ms");
        assert_eq!(seconds(3.0), "3 s");
        assert_eq!(seconds(125.0), "2 min 05 s");
        assert_eq!(slug("work (N.mm)"), "work__N_mm");
        assert_eq!(slug("é"), "qoi");
        assert_eq!(esc("<a & 'b'>"), "&lt;a &amp; &#39;b&#39;&gt;");
    }
}
