//! The expression parser (`alea_study::expr::Expr`): any text parses to an expression or an
//! error, never a panic or a stack overflow; a parsed expression evaluates at any point
//! (values chosen by the fuzzer, NaN and infinities included) without panicking.
#![no_main]

use alea_study::expr::Expr;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|input: (&str, [f64; 3])| {
    let (text, point) = input;
    if let Ok(e) = Expr::parse(text, &["x", "y", "a"]) {
        let _ = e.eval(&point);
        let _ = e.uses(2);
    }
});
