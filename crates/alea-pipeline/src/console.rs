//! Where the account of a study goes: lines for the user and warnings, said at once or kept
//! and said later ([`Deferred`], for the outputs of a study: files first).

/// Receives what a study reports while it runs: the `alea` CLI prints lines to stdout and
/// warnings to stderr (`warning: ...`); Python keeps quiet and gets the warnings back as notes.
pub trait Console {
    /// One line of the account (may start with `\n` or be empty).
    fn line(&self, text: &str);
    /// A warning (also kept in the notes of `summary.json` and the report).
    fn warning(&self, text: &str);
}

/// A console that shows nothing.
pub struct Silent;

impl Console for Silent {
    fn line(&self, _text: &str) {}
    fn warning(&self, _text: &str) {}
}

/// One thing said to a [`Deferred`] console.
enum Said {
    Line(String),
    Warning(String),
}

/// A console that keeps what it is told and says it later to another console, in the same
/// order ([`Deferred::replay`]): the outputs of a study print their account once their files
/// are written, so that a reader that stops reading (`alea run study.toml | head -2`) leaves
/// complete files behind.
#[derive(Default)]
pub(crate) struct Deferred {
    said: std::sync::Mutex<Vec<Said>>,
}

impl Deferred {
    /// Says to `to` everything this console was told, in order.
    pub(crate) fn replay(self, to: &dyn Console) {
        let said = self
            .said
            .into_inner()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        for s in said {
            match s {
                Said::Line(text) => to.line(&text),
                Said::Warning(text) => to.warning(&text),
            }
        }
    }

    fn keep(&self, s: Said) {
        self.said
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(s);
    }
}

impl Console for Deferred {
    fn line(&self, text: &str) {
        self.keep(Said::Line(text.to_string()));
    }
    fn warning(&self, text: &str) {
        self.keep(Said::Warning(text.to_string()));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    /// Records what it is told, warnings marked.
    #[derive(Default)]
    struct Record(RefCell<Vec<String>>);

    impl Console for Record {
        fn line(&self, text: &str) {
            self.0.borrow_mut().push(text.to_string());
        }
        fn warning(&self, text: &str) {
            self.0.borrow_mut().push(format!("warning: {text}"));
        }
    }

    #[test]
    fn a_deferred_console_says_nothing_until_replayed_then_all_in_order() {
        let to = Record::default();
        let d = Deferred::default();
        d.line("table");
        d.warning("w");
        d.line("");
        d.line("report: r.html");
        assert!(to.0.borrow().is_empty());
        d.replay(&to);
        assert_eq!(
            *to.0.borrow(),
            ["table", "warning: w", "", "report: r.html"]
        );
    }
}
