//! The expression language: a hand-written Pratt parser into a [`Graph`].
//!
//! ```text
//! expr     := term (('+' | '-') term)*          left-associative
//! term     := unary (('*' | '/') unary)*         left-associative
//! unary    := ('-' | '+') unary | power
//! power    := atom ('^' unary)?                  right-associative: -x^2 = -(x^2), 2^-1 = 0.5
//! atom     := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
//! ```
//!
//! Numbers are decimal (`2`, `0.5`, `1e-3`); `pi` is π; functions are `sqrt sin cos tan asin
//! acos atan sinh cosh tanh exp log abs sign` of one argument, `atan2(y, x)` and `pow(x, y)`
//! (also `x^y`). Any other name must be in the caller's scope. An expression is data: it names
//! numbers and reads nothing else. Text longer than [`MAX_LEN`] bytes or nested deeper than
//! [`MAX_DEPTH`] is refused before it is parsed.

use super::{Fun, Graph, Id};

/// The longest expression accepted, in bytes.
pub const MAX_LEN: usize = 10_000;
/// The deepest nesting of parentheses, calls and unary signs accepted.
pub const MAX_DEPTH: usize = 64;

/// What is wrong with an expression, and where (a byte range of its text).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct ParseError {
    /// Byte offset of the fault in the expression.
    pub offset: usize,
    /// Its length in bytes (at least 1 for the caret).
    pub len: usize,
    /// What is wrong, and what to write instead.
    pub message: String,
}

impl ParseError {
    /// The expression on one line with carets under the fault.
    #[must_use]
    pub fn excerpt(&self, text: &str) -> String {
        let line: String = text
            .chars()
            .map(|c| if c == '\n' || c == '\t' { ' ' } else { c })
            .collect();
        let start = text
            .get(..self.offset.min(text.len()))
            .map_or(0, |s| s.chars().count());
        let width = text
            .get(self.offset.min(text.len())..(self.offset + self.len).min(text.len()))
            .map_or(1, |s| s.chars().count().max(1));
        format!("    {line}\n    {}{}", " ".repeat(start), "^".repeat(width))
    }
}

/// The names an expression may use besides the built-in ones: resolves a name to a node.
pub trait Scope {
    /// The node `name` stands for.
    fn resolve(&self, name: &str, graph: &mut Graph) -> Option<Id>;
    /// Every name in scope, for the message of an unknown one.
    fn names(&self) -> Vec<String>;
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Tok<'a> {
    Num(f64),
    Name(&'a str),
    Op(char),
    End,
}

struct Parser<'s, 'g> {
    text: &'s str,
    pos: usize,
    /// The current token and its byte range.
    tok: Tok<'s>,
    start: usize,
    graph: &'g mut Graph,
    scope: &'g dyn Scope,
    depth: usize,
}

/// Parses `text` into `graph`, names resolved by `scope`.
///
/// # Errors
/// [`ParseError`] at the first fault: a character that is no part of the language, a number
/// that is not finite, an unknown name (listing the names in scope), a wrong number of
/// arguments, unbalanced parentheses, text too long or nested too deep.
pub fn parse(text: &str, graph: &mut Graph, scope: &dyn Scope) -> Result<Id, ParseError> {
    if text.len() > MAX_LEN {
        return Err(ParseError {
            offset: MAX_LEN,
            len: 1,
            message: format!(
                "the expression is {} bytes long, more than the {MAX_LEN} allowed; split it \
                 into named outputs or parameters",
                text.len()
            ),
        });
    }
    let mut p = Parser {
        text,
        pos: 0,
        tok: Tok::End,
        start: 0,
        graph,
        scope,
        depth: 0,
    };
    p.advance()?;
    if p.tok == Tok::End {
        return Err(p.error("an empty expression; write a number or a formula such as `m*g*l`"));
    }
    let id = p.expr(0)?;
    if p.tok != Tok::End {
        return Err(p.error(&format!(
            "unexpected {} after a complete expression (a missing operator?)",
            p.describe()
        )));
    }
    Ok(id)
}

impl Parser<'_, '_> {
    fn error(&self, message: &str) -> ParseError {
        ParseError {
            offset: self.start,
            len: (self.pos - self.start).max(1),
            message: message.to_string(),
        }
    }

    fn describe(&self) -> String {
        match self.tok {
            Tok::End => "end of the expression".to_string(),
            _ => format!("`{}`", &self.text[self.start..self.pos]),
        }
    }

    fn advance(&mut self) -> Result<(), ParseError> {
        let bytes = self.text.as_bytes();
        while self.pos < bytes.len() && bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        self.start = self.pos;
        let Some(&c) = bytes.get(self.pos) else {
            self.tok = Tok::End;
            return Ok(());
        };
        if c.is_ascii_digit() || c == b'.' {
            while self.pos < bytes.len()
                && (bytes[self.pos].is_ascii_digit() || bytes[self.pos] == b'.')
            {
                self.pos += 1;
            }
            if self.pos < bytes.len() && (bytes[self.pos] == b'e' || bytes[self.pos] == b'E') {
                let mut q = self.pos + 1;
                if q < bytes.len() && (bytes[q] == b'+' || bytes[q] == b'-') {
                    q += 1;
                }
                if q < bytes.len() && bytes[q].is_ascii_digit() {
                    while q < bytes.len() && bytes[q].is_ascii_digit() {
                        q += 1;
                    }
                    self.pos = q;
                }
            }
            let lexeme = &self.text[self.start..self.pos];
            let x: f64 = lexeme
                .parse()
                .map_err(|_| self.error(&format!("`{lexeme}` is not a number")))?;
            if !x.is_finite() {
                return Err(self.error(&format!("`{lexeme}` is not a finite number")));
            }
            self.tok = Tok::Num(x);
        } else if c.is_ascii_alphabetic() || c == b'_' {
            while self.pos < bytes.len()
                && (bytes[self.pos].is_ascii_alphanumeric() || bytes[self.pos] == b'_')
            {
                self.pos += 1;
            }
            self.tok = Tok::Name(&self.text[self.start..self.pos]);
        } else if b"+-*/^(),".contains(&c) {
            self.pos += 1;
            self.tok = Tok::Op(c as char);
        } else {
            let ch = self.text[self.pos..].chars().next().unwrap_or('?');
            self.pos += ch.len_utf8();
            return Err(self.error(&format!(
                "`{ch}` is not part of the expression language (numbers, names, + - * / ^, \
                 parentheses and function calls)"
            )));
        }
        Ok(())
    }

    fn enter(&mut self) -> Result<(), ParseError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.error(&format!(
                "nested more than {MAX_DEPTH} deep; simplify the expression"
            )));
        }
        Ok(())
    }

    /// Binding powers `(left, right)` of an infix operator.
    fn infix(tok: Tok<'_>) -> Option<(u8, u8)> {
        match tok {
            Tok::Op('+' | '-') => Some((1, 2)),
            Tok::Op('*' | '/') => Some((3, 4)),
            Tok::Op('^') => Some((8, 7)),
            _ => None,
        }
    }

    fn expr(&mut self, min_bp: u8) -> Result<Id, ParseError> {
        self.enter()?;
        let mut lhs = self.prefix()?;
        while let Some((l, r)) = Self::infix(self.tok) {
            if l < min_bp {
                break;
            }
            let Tok::Op(op) = self.tok else { break };
            self.advance()?;
            // The exponent may carry a sign: 2^-1.
            let rhs = if op == '^' {
                self.unary(r)?
            } else {
                self.expr(r)?
            };
            lhs = match op {
                '+' => self.graph.add(lhs, rhs),
                '-' => self.graph.sub(lhs, rhs),
                '*' => self.graph.mul(lhs, rhs),
                '/' => self.graph.div(lhs, rhs),
                _ => self.graph.pow(lhs, rhs),
            };
        }
        self.depth -= 1;
        Ok(lhs)
    }

    /// A signed operand of `^` (binding power `bp` on the right).
    fn unary(&mut self, bp: u8) -> Result<Id, ParseError> {
        match self.tok {
            Tok::Op('-') => {
                self.enter()?;
                self.advance()?;
                let x = self.unary(bp)?;
                self.depth -= 1;
                Ok(self.graph.neg(x))
            }
            Tok::Op('+') => {
                self.advance()?;
                self.unary(bp)
            }
            _ => self.expr(bp),
        }
    }

    fn prefix(&mut self) -> Result<Id, ParseError> {
        match self.tok {
            Tok::Num(x) => {
                self.advance()?;
                Ok(self.graph.constant(x))
            }
            Tok::Op('-') => {
                self.advance()?;
                // Binds looser than ^ and tighter than * /: -x^2 = -(x^2), -a*b = (-a)*b.
                let x = self.expr(5)?;
                Ok(self.graph.neg(x))
            }
            Tok::Op('+') => {
                self.advance()?;
                self.expr(5)
            }
            Tok::Op('(') => {
                let open = self.start;
                self.advance()?;
                let x = self.expr(0)?;
                if self.tok != Tok::Op(')') {
                    return Err(ParseError {
                        offset: open,
                        len: 1,
                        message: format!(
                            "this parenthesis is not closed (found {} where `)` belongs)",
                            self.describe()
                        ),
                    });
                }
                self.advance()?;
                Ok(x)
            }
            Tok::Name(name) => self.name(name),
            Tok::Op(_) | Tok::End => Err(self.error(&format!(
                "expected a number, a name or `(`, found {}",
                self.describe()
            ))),
        }
    }

    fn name(&mut self, name: &str) -> Result<Id, ParseError> {
        let here = self.error("");
        self.advance()?;
        if self.tok == Tok::Op('(') {
            let args = self.arguments(name)?;
            let arity = |n: usize| -> Result<(), ParseError> {
                if args.len() == n {
                    Ok(())
                } else {
                    Err(ParseError {
                        message: format!(
                            "`{name}` takes {n} argument{}, found {}",
                            if n == 1 { "" } else { "s" },
                            args.len()
                        ),
                        ..here.clone()
                    })
                }
            };
            if let Some((_, f)) = Fun::ALL.iter().find(|(n, _)| *n == name) {
                arity(1)?;
                return Ok(self.graph.call(*f, args[0]));
            }
            return match name {
                "atan2" => {
                    arity(2)?;
                    Ok(self.graph.atan2(args[0], args[1]))
                }
                "pow" => {
                    arity(2)?;
                    Ok(self.graph.pow(args[0], args[1]))
                }
                _ => Err(ParseError {
                    message: format!(
                        "unknown function `{name}`; functions: {}, atan2, pow",
                        Fun::ALL
                            .iter()
                            .map(|(n, _)| *n)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                    ..here
                }),
            };
        }
        if name == "pi" {
            return Ok(self.graph.constant(std::f64::consts::PI));
        }
        if let Some(id) = self.scope.resolve(name, self.graph) {
            return Ok(id);
        }
        let is_function =
            Fun::ALL.iter().any(|(n, _)| *n == name) || name == "atan2" || name == "pow";
        let mut names = self.scope.names();
        names.push("pi".to_string());
        Err(ParseError {
            message: if is_function {
                format!("`{name}` is a function: write `{name}(x)`")
            } else {
                format!(
                    "unknown name `{name}`; names in scope: {}",
                    names.join(", ")
                )
            },
            ..here
        })
    }

    fn arguments(&mut self, name: &str) -> Result<Vec<Id>, ParseError> {
        let open = self.start;
        self.enter()?;
        self.advance()?;
        let mut args = Vec::new();
        if self.tok == Tok::Op(')') {
            self.advance()?;
            self.depth -= 1;
            return Ok(args);
        }
        loop {
            args.push(self.expr(0)?);
            match self.tok {
                Tok::Op(',') => self.advance()?,
                Tok::Op(')') => {
                    self.advance()?;
                    break;
                }
                _ => {
                    return Err(ParseError {
                        offset: open,
                        len: 1,
                        message: format!(
                            "the arguments of `{name}` are not closed (found {} where `,` or \
                             `)` belongs)",
                            self.describe()
                        ),
                    });
                }
            }
        }
        self.depth -= 1;
        Ok(args)
    }
}
