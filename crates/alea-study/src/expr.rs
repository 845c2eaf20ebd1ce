//! A small expression language for quantities that depend on parameters and position:
//! friction and gap profiles along an interface (thesis (5.1)-(5.4)), Young's moduli, load
//! factors.
//!
//! Grammar (usual precedence, `^` right-associative, unary minus binds looser than `^`):
//! ```text
//! expr  := term (('+' | '-') term)*
//! term  := unary (('*' | '/') unary)*
//! unary := ('-' | '+') unary | power
//! power := atom ('^' unary)?
//! atom  := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
//! ```
//! Functions: `exp ln log10 sqrt abs sin cos tan atan tanh` (one argument), `min max pow
//! atan2` (two). Constant: `pi`. Names are resolved at compile time against the variables the
//! caller allows (parameter names, and `x y z` for profiles); an unknown name is an error that
//! says which names exist. Expressions nest at most [`MAX_DEPTH`] deep (parentheses, unary
//! signs, powers, calls and chains of binary operators all count): parsing, evaluating and
//! dropping a tree are recursive, and a deeper one is refused with an error instead of
//! overflowing the stack. Written by hand: the crates that do this (meval, evalexpr) bring an
//! interpreter with dynamic types and their own error model, for ~250 lines here.

use std::fmt;

/// Deepest expression tree accepted (far beyond any hand-written formula).
pub const MAX_DEPTH: usize = 200;

/// A compiled expression; variables are slots in the array passed to [`Expr::eval`].
#[derive(Clone, Debug)]
pub struct Expr {
    node: Node,
    text: String,
}

#[derive(Clone, Debug)]
enum Node {
    Num(f64),
    Var(usize),
    Neg(Box<Node>),
    Bin(char, Box<Node>, Box<Node>),
    Call1(fn(f64) -> f64, Box<Node>),
    Call2(fn(f64, f64) -> f64, Box<Node>, Box<Node>),
}

/// A syntax or name error, with the byte position in the expression text.
#[derive(Clone, Debug, PartialEq)]
pub struct ExprError {
    /// Byte offset in the text.
    pub pos: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ExprError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "at character {}: {}", self.pos + 1, self.message)
    }
}

struct Parser<'a> {
    s: &'a [u8],
    pos: usize,
    vars: &'a [&'a str],
    /// Current recursion depth of the parser.
    nesting: usize,
}

/// A node with the depth of its tree.
type Sized = (Node, usize);

fn func1(name: &str) -> Option<fn(f64) -> f64> {
    Some(match name {
        "exp" => f64::exp,
        "ln" => f64::ln,
        "log10" => f64::log10,
        "sqrt" => f64::sqrt,
        "abs" => f64::abs,
        "sin" => f64::sin,
        "cos" => f64::cos,
        "tan" => f64::tan,
        "atan" => f64::atan,
        "tanh" => f64::tanh,
        _ => return None,
    })
}

fn func2(name: &str) -> Option<fn(f64, f64) -> f64> {
    Some(match name {
        "min" => f64::min,
        "max" => f64::max,
        "pow" => f64::powf,
        "atan2" => f64::atan2,
        _ => return None,
    })
}

impl<'a> Parser<'a> {
    fn err<T>(&self, message: impl Into<String>) -> Result<T, ExprError> {
        Err(ExprError {
            pos: self.pos,
            message: message.into(),
        })
    }
    fn skip(&mut self) {
        while self.pos < self.s.len() && self.s[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }
    fn peek(&mut self) -> Option<u8> {
        self.skip();
        self.s.get(self.pos).copied()
    }
    /// A node over children of depths `depths`, refused beyond [`MAX_DEPTH`].
    fn node(&self, n: Node, depths: &[usize]) -> Result<Sized, ExprError> {
        let d = 1 + depths.iter().copied().max().unwrap_or(0);
        if d > MAX_DEPTH {
            return self.err(format!(
                "expression nested more than {MAX_DEPTH} deep (parentheses, signs, powers, calls or a chain of operators); simplify it"
            ));
        }
        Ok((n, d))
    }
    fn bin(&self, op: char, (a, da): Sized, (b, db): Sized) -> Result<Sized, ExprError> {
        self.node(Node::Bin(op, Box::new(a), Box::new(b)), &[da, db])
    }
    fn expr(&mut self) -> Result<Sized, ExprError> {
        let mut a = self.term()?;
        while let Some(c @ (b'+' | b'-')) = self.peek() {
            self.pos += 1;
            let b = self.term()?;
            a = self.bin(c as char, a, b)?;
        }
        Ok(a)
    }
    fn term(&mut self) -> Result<Sized, ExprError> {
        let mut a = self.unary()?;
        while let Some(c @ (b'*' | b'/')) = self.peek() {
            self.pos += 1;
            let b = self.unary()?;
            a = self.bin(c as char, a, b)?;
        }
        Ok(a)
    }
    /// Every recursive path of the grammar goes through here: the nesting is bounded here.
    fn unary(&mut self) -> Result<Sized, ExprError> {
        self.nesting += 1;
        if self.nesting > MAX_DEPTH {
            return self.err(format!(
                "expression nested more than {MAX_DEPTH} deep (parentheses, signs, powers, calls or a chain of operators); simplify it"
            ));
        }
        let r = match self.peek() {
            Some(b'-') => {
                self.pos += 1;
                let (a, da) = self.unary()?;
                self.node(Node::Neg(Box::new(a)), &[da])
            }
            Some(b'+') => {
                self.pos += 1;
                self.unary()
            }
            _ => self.power(),
        };
        self.nesting -= 1;
        r
    }
    fn power(&mut self) -> Result<Sized, ExprError> {
        let a = self.atom()?;
        if self.peek() == Some(b'^') {
            self.pos += 1;
            let b = self.unary()?;
            return self.bin('^', a, b);
        }
        Ok(a)
    }
    fn atom(&mut self) -> Result<Sized, ExprError> {
        match self.peek() {
            None => self.err("unexpected end of expression"),
            Some(b'(') => {
                self.pos += 1;
                let e = self.expr()?;
                if self.peek() != Some(b')') {
                    return self.err("expected ')'");
                }
                self.pos += 1;
                Ok(e)
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => {
                let start = self.pos;
                while self.pos < self.s.len()
                    && (self.s[self.pos].is_ascii_digit() || self.s[self.pos] == b'.')
                {
                    self.pos += 1;
                }
                if self.pos < self.s.len() && (self.s[self.pos] | 0x20) == b'e' {
                    let save = self.pos;
                    self.pos += 1;
                    if self.pos < self.s.len()
                        && (self.s[self.pos] == b'+' || self.s[self.pos] == b'-')
                    {
                        self.pos += 1;
                    }
                    let digits = self.pos;
                    while self.pos < self.s.len() && self.s[self.pos].is_ascii_digit() {
                        self.pos += 1;
                    }
                    if self.pos == digits {
                        self.pos = save;
                    }
                }
                let text = std::str::from_utf8(&self.s[start..self.pos]).unwrap_or("");
                match text.parse::<f64>() {
                    Ok(v) => Ok((Node::Num(v), 1)),
                    Err(_) => {
                        self.pos = start;
                        self.err(format!("malformed number '{}'", abbreviate(text)))
                    }
                }
            }
            Some(c) if c.is_ascii_alphabetic() || c == b'_' => {
                let start = self.pos;
                while self.pos < self.s.len()
                    && (self.s[self.pos].is_ascii_alphanumeric() || self.s[self.pos] == b'_')
                {
                    self.pos += 1;
                }
                let name = std::str::from_utf8(&self.s[start..self.pos]).unwrap_or("");
                if self.peek() == Some(b'(') {
                    self.pos += 1;
                    let mut args = vec![self.expr()?];
                    while self.peek() == Some(b',') {
                        self.pos += 1;
                        args.push(self.expr()?);
                    }
                    if self.peek() != Some(b')') {
                        return self.err("expected ')' after the arguments");
                    }
                    self.pos += 1;
                    let mut args = args.into_iter();
                    return match (args.len(), func1(name), func2(name)) {
                        (1, Some(f), _) => {
                            let (a, da) = args.next().unwrap();
                            self.node(Node::Call1(f, Box::new(a)), &[da])
                        }
                        (2, _, Some(f)) => {
                            let (a, da) = args.next().unwrap();
                            let (b, db) = args.next().unwrap();
                            self.node(Node::Call2(f, Box::new(a), Box::new(b)), &[da, db])
                        }
                        (n, f1, f2) if f1.is_some() || f2.is_some() => {
                            self.pos = start;
                            self.err(format!(
                                "function '{}' takes {} argument(s), got {n}",
                                abbreviate(name),
                                if f1.is_some() { 1 } else { 2 }
                            ))
                        }
                        _ => {
                            self.pos = start;
                            self.err(format!("unknown function '{}'; known: exp ln log10 sqrt abs sin cos tan atan tanh min max pow atan2", abbreviate(name)))
                        }
                    };
                }
                if name == "pi" {
                    return Ok((Node::Num(std::f64::consts::PI), 1));
                }
                match self.vars.iter().position(|v| *v == name) {
                    Some(i) => Ok((Node::Var(i), 1)),
                    None => {
                        self.pos = start;
                        self.err(format!(
                            "unknown name '{}'; available: {}",
                            abbreviate(name),
                            if self.vars.is_empty() {
                                "none".to_string()
                            } else {
                                self.vars.join(", ")
                            }
                        ))
                    }
                }
            }
            Some(c) => self.err(format!("unexpected character '{}'", c as char)),
        }
    }
}

/// `text` cut at 5 x [`MAX_QUOTED`] characters (a message that quotes no value but could be
/// long), with its length said.
pub fn abbreviate_long(text: &str) -> String {
    match text.char_indices().nth(5 * MAX_QUOTED) {
        None => text.to_string(),
        Some((end, _)) => format!("{}... ({} characters)", &text[..end], text.chars().count()),
    }
}

/// Characters of a text quoted in an error message, at most.
pub const MAX_QUOTED: usize = 200;

/// `text` as quoted in an error message: whole up to [`MAX_QUOTED`] characters, else its first
/// ones and how long it is (an error line never echoes a 200 kB expression).
pub fn abbreviate(text: &str) -> String {
    match text.char_indices().nth(MAX_QUOTED) {
        None => text.to_string(),
        Some((end, _)) => format!("{}... ({} characters)", &text[..end], text.chars().count()),
    }
}

impl Expr {
    /// Compiles `text`, allowing the variables `vars` (slot `i` is `vars[i]`).
    pub fn parse(text: &str, vars: &[&str]) -> Result<Self, ExprError> {
        let mut p = Parser {
            s: text.as_bytes(),
            pos: 0,
            vars,
            nesting: 0,
        };
        let (node, _) = p.expr()?;
        if p.peek().is_some() {
            return p.err("unexpected text after the expression");
        }
        Ok(Expr {
            node,
            text: text.to_string(),
        })
    }

    /// A constant.
    pub fn constant(v: f64) -> Self {
        Expr {
            node: Node::Num(v),
            text: v.to_string(),
        }
    }

    /// The source text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// True if the expression uses variable slot `i`.
    pub fn uses(&self, i: usize) -> bool {
        fn walk(n: &Node, i: usize) -> bool {
            match n {
                Node::Num(_) => false,
                Node::Var(j) => *j == i,
                Node::Neg(a) | Node::Call1(_, a) => walk(a, i),
                Node::Bin(_, a, b) | Node::Call2(_, a, b) => walk(a, i) || walk(b, i),
            }
        }
        walk(&self.node, i)
    }

    /// Evaluates with `vars[i]` the value of slot `i`.
    pub fn eval(&self, vars: &[f64]) -> f64 {
        ev(&self.node, vars)
    }

    /// The expression with the slots `known[i] = Some(value)` substituted and every subtree
    /// that then depends on no free slot replaced by its value. The values are computed by the
    /// arithmetic of [`Expr::eval`] in the same order, so for any values of the free slots the
    /// folded expression evaluates to the same bits as the original (slots beyond `known`
    /// stay free). What a profile tabulated on a point set uses: the parts that depend on the
    /// point only are evaluated once per point, not once per parameter point.
    pub fn fold(&self, known: &[Option<f64>]) -> Expr {
        fn fold(n: &Node, k: &[Option<f64>]) -> Node {
            let num = |n: &Node| match n {
                Node::Num(x) => Some(*x),
                _ => None,
            };
            match n {
                Node::Num(x) => Node::Num(*x),
                Node::Var(i) => k
                    .get(*i)
                    .copied()
                    .flatten()
                    .map_or(Node::Var(*i), Node::Num),
                Node::Neg(a) => {
                    let a = fold(a, k);
                    num(&a).map_or_else(|| Node::Neg(Box::new(a)), |x| Node::Num(-x))
                }
                Node::Bin(op, a, b) => {
                    let (a, b) = (fold(a, k), fold(b, k));
                    match (num(&a), num(&b)) {
                        (Some(x), Some(y)) => Node::Num(binary(*op, x, y)),
                        _ => Node::Bin(*op, Box::new(a), Box::new(b)),
                    }
                }
                Node::Call1(f, a) => {
                    let a = fold(a, k);
                    num(&a).map_or_else(|| Node::Call1(*f, Box::new(a)), |x| Node::Num(f(x)))
                }
                Node::Call2(f, a, b) => {
                    let (a, b) = (fold(a, k), fold(b, k));
                    match (num(&a), num(&b)) {
                        (Some(x), Some(y)) => Node::Num(f(x, y)),
                        _ => Node::Call2(*f, Box::new(a), Box::new(b)),
                    }
                }
            }
        }
        Expr {
            node: fold(&self.node, known),
            text: self.text.clone(),
        }
    }

    /// The value, when the expression is a constant (as after [`Expr::fold`] of all its slots).
    pub fn as_constant(&self) -> Option<f64> {
        match self.node {
            Node::Num(x) => Some(x),
            _ => None,
        }
    }
}

/// The value of node `n` with slot values `v`.
fn ev(n: &Node, v: &[f64]) -> f64 {
    match n {
        Node::Num(x) => *x,
        Node::Var(i) => v[*i],
        Node::Neg(a) => -ev(a, v),
        Node::Bin(op, a, b) => binary(*op, ev(a, v), ev(b, v)),
        Node::Call1(f, a) => f(ev(a, v)),
        Node::Call2(f, a, b) => f(ev(a, v), ev(b, v)),
    }
}

/// The binary operator `op` (`+ - * /`, else the power) on `a` and `b`.
fn binary(op: char, a: f64, b: f64) -> f64 {
    match op {
        '+' => a + b,
        '-' => a - b,
        '*' => a * b,
        '/' => a / b,
        // Squares, the most common power in profiles: `a * a` is correctly rounded, as `powf`
        // is, hence the same value, several times faster.
        _ if b == 2.0 => a * a,
        _ => a.powf(b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Folding known slots keeps the value bit for bit at any value of the free ones, and
    /// folding all of them leaves a constant.
    #[test]
    fn folding_known_slots_keeps_the_bits() {
        let v = ["a", "b", "x"];
        let texts = [
            "0.2 + 0.6 * (a * exp(-(x - 0.7)^2 / 0.13) + b * exp(-(x - 1.5)^2 / 0.13))",
            "-x^3 / (1 + a) + max(b, sin(x)) * pow(x, 0.5) - (x - 2) ^ 2",
        ];
        for t in texts {
            let e = Expr::parse(t, &v).unwrap();
            for x in [0.1, 0.77, 1.9] {
                let folded = e.fold(&[None, None, Some(x)]);
                let all = e.fold(&[Some(0.3), Some(0.9), Some(x)]);
                assert_eq!(
                    all.as_constant().map(f64::to_bits),
                    Some(e.eval(&[0.3, 0.9, x]).to_bits())
                );
                for (a, b) in [(0.0, 1.0), (0.3, 0.9), (-2.5, 1e-3)] {
                    assert_eq!(
                        folded.eval(&[a, b, 0.0]).to_bits(),
                        e.eval(&[a, b, x]).to_bits(),
                        "{t} at {x}"
                    );
                }
                assert!(folded.as_constant().is_none());
            }
        }
    }

    #[test]
    fn precedence_associativity_and_functions() {
        let v = ["a", "b", "x"];
        let e = |t: &str, vals: &[f64]| Expr::parse(t, &v).unwrap().eval(vals);
        assert_eq!(e("1 + 2 * 3", &[0.0; 3]), 7.0);
        assert_eq!(e("2 ^ 3 ^ 2", &[0.0; 3]), 512.0);
        assert_eq!(e("-2 ^ 2", &[0.0; 3]), -4.0);
        assert_eq!(e("(1 + 2) * 3", &[0.0; 3]), 9.0);
        assert_eq!(e("8 / 4 / 2", &[0.0; 3]), 1.0);
        assert_eq!(e("1.5e3 + 2E-1", &[0.0; 3]), 1500.2);
        assert_eq!(e("a * x + b", &[2.0, 1.0, 3.0]), 7.0);
        assert!(
            (e("exp(ln(2)) + max(a, b) + pow(2, 0.5)^2", &[5.0, 1.0, 0.0]) - 9.0).abs() < 1e-14
        );
        assert!((e("sin(pi / 2)", &[0.0; 3]) - 1.0).abs() < 1e-15);
        // Thesis (5.2) friction profile at x = La: mu ~ 0.2 + 0.6 a.
        let mu = "0.2 + 0.6 * (a * exp(-(x - 0.7)^2 / 0.13) + b * exp(-(x - 1.5)^2 / 0.13))";
        let got = e(mu, &[0.5, 0.0, 0.7]);
        assert!((got - 0.5).abs() < 1e-12);
    }

    #[test]
    fn squares_are_the_powers_they_replace() {
        let e = Expr::parse("x^2", &["x"]).unwrap();
        let mut x = -7.3e3;
        while x < 7.3e3 {
            assert_eq!(e.eval(&[x]).to_bits(), x.powf(2.0).to_bits(), "{x}");
            x += 0.7312345;
        }
        assert!(e.eval(&[f64::NAN]).is_nan());
    }

    #[test]
    fn errors_say_where_and_what() {
        let v = ["a"];
        let err = Expr::parse("a + bb", &v).unwrap_err();
        assert_eq!(err.pos, 4);
        assert!(err.message.contains("unknown name 'bb'") && err.message.contains("a"));
        assert!(
            Expr::parse("2 * (a + 1", &v)
                .unwrap_err()
                .message
                .contains("')'")
        );
        assert!(
            Expr::parse("foo(1)", &v)
                .unwrap_err()
                .message
                .contains("unknown function")
        );
        assert!(
            Expr::parse("min(1)", &v)
                .unwrap_err()
                .message
                .contains("2 argument")
        );
        assert!(
            Expr::parse("1 2", &v)
                .unwrap_err()
                .message
                .contains("after the expression")
        );
        assert!(
            Expr::parse("", &v)
                .unwrap_err()
                .message
                .contains("end of expression")
        );
        assert!(Expr::parse("3 $", &v).is_err());
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        let n = 10_000;
        let cases = [
            format!("{}1{}", "(".repeat(n), ")".repeat(n)),
            format!("{}1", "-".repeat(n)),
            format!("{}1", "+".repeat(n)),
            vec!["2"; n].join("^"),
            vec!["1"; n].join(" + "),
            vec!["a"; n].join(" * "),
            format!("{}1{}", "sin(".repeat(n), ")".repeat(n)),
        ];
        for (k, t) in cases.iter().enumerate() {
            // On a quarter of the stack rayon workers and spawned threads get by default (2 MiB).
            // Measured: the parser needs about 1.3 - 1.6 KB per nesting level in release builds
            // (the limit's 200 levels passed on 320 KB, not on 256 KB, with rustc 1.95), so
            // the default stacks hold the limit about 6x over.
            let t = t.clone();
            let r = std::thread::Builder::new()
                .stack_size(512 * 1024)
                .spawn(move || Expr::parse(&t, &["a"]).map(|_| ()))
                .unwrap()
                .join()
                .expect("no stack overflow");
            let e = r.expect_err("refused");
            assert!(e.message.contains("nested more than"), "case {k}: {e}");
        }
        // Up to the limit, parse and evaluate on a small stack.
        let ok = format!(
            "{}x{}",
            "(".repeat(MAX_DEPTH / 2),
            ")".repeat(MAX_DEPTH / 2)
        );
        let sum = vec!["x"; MAX_DEPTH - 1].join(" + ");
        let v = std::thread::Builder::new()
            .stack_size(512 * 1024)
            .spawn(move || {
                Expr::parse(&ok, &["x"]).unwrap().eval(&[2.0])
                    + Expr::parse(&sum, &["x"]).unwrap().eval(&[1.0])
            })
            .unwrap()
            .join()
            .unwrap();
        assert_eq!(v, 2.0 + (MAX_DEPTH - 1) as f64);
    }
}
