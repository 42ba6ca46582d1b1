//! Reading NFF text into an [`NffDocument`]: entity by entity, each keyword followed by its
//! numbers. Every mistake (an unknown keyword, a missing or malformed number, a value out of
//! range, a polygon with fewer than 3 vertices) is a [`SceneError`] at its line and column.

use std::iter::Peekable;
use std::ops::Range;

use glam::DVec3;

use super::document::{Fill, Item, NffDocument, NffLight, PatchVertex, View};
use super::tokens::{Token, Tokens};
use crate::formats::{SceneError, Source};
use crate::limits::MAX_IMAGE_SIDE;

/// Where the parts of a document were written, for errors found when it is built.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Locations {
    /// The `v` keyword.
    pub view: Option<Range<usize>>,
    /// The `l` keyword of each light, in the order of [`NffDocument::lights`].
    pub lights: Vec<Range<usize>>,
    /// The keyword of each item, in the order of [`NffDocument::items`].
    pub items: Vec<Range<usize>>,
}

/// The entity keywords, for messages.
const KEYWORDS: &str = "`v`, `b`, `l`, `f`, `c`, `s`, `p`, `pp`";

/// Reads NFF text. `source` names it in errors.
pub(crate) fn parse(source: Source) -> Result<(NffDocument, Locations), SceneError> {
    let mut parser = Parser {
        tokens: Tokens::new(source.text).peekable(),
        source,
    };
    let mut document = NffDocument::default();
    let mut locations = Locations::default();
    while let Some(keyword) = parser.tokens.next() {
        let mut entity = Entity {
            parser: &mut parser,
            keyword,
        };
        let item = match keyword.text {
            "b" => {
                document.background = Some(entity.color("the background colour")?);
                continue;
            }
            "v" => {
                if locations.view.is_some() {
                    return Err(entity.error_here("a second view (`v`); a file has one".into()));
                }
                document.view = Some(entity.view()?);
                locations.view = Some(keyword.span());
                continue;
            }
            "l" => {
                document.lights.push(entity.light()?);
                locations.lights.push(keyword.span());
                continue;
            }
            "f" => Item::Fill(entity.fill()?),
            "s" => Item::Sphere {
                center: entity.vector("the centre")?,
                radius: entity.number("the radius")?,
            },
            "c" => Item::Cone {
                base: entity.vector("the base")?,
                base_radius: entity.number("the base radius")?,
                apex: entity.vector("the apex")?,
                apex_radius: entity.number("the apex radius")?,
            },
            "p" => {
                let count = entity.vertex_count()?;
                let mut vertices = Vec::with_capacity(count.min(1024));
                for _ in 0..count {
                    vertices.push(entity.vector("a vertex")?);
                }
                Item::Polygon(vertices)
            }
            "pp" => {
                let count = entity.vertex_count()?;
                let mut vertices = Vec::with_capacity(count.min(1024));
                for _ in 0..count {
                    vertices.push(PatchVertex {
                        position: entity.vector("a vertex")?,
                        normal: entity.vector("a vertex normal")?,
                    });
                }
                Item::Patch(vertices)
            }
            other => {
                return Err(entity.error_here(format!(
                    "unknown entity `{other}`; expected one of {KEYWORDS}"
                )));
            }
        };
        document.items.push(item);
        locations.items.push(keyword.span());
    }
    Ok((document, locations))
}

struct Parser<'a> {
    tokens: Peekable<Tokens<'a>>,
    source: Source<'a>,
}

/// The entity being read: its keyword, and the tokens after it.
struct Entity<'p, 'a> {
    parser: &'p mut Parser<'a>,
    keyword: Token<'a>,
}

impl<'a> Entity<'_, 'a> {
    /// An error at the entity's keyword.
    fn error_here(&self, message: String) -> SceneError {
        self.parser.source.error(self.keyword.span(), message)
    }

    /// The next token, which `what` should be; running out of text is an error at the keyword.
    #[inline]
    fn token(&mut self, what: &str) -> Result<Token<'a>, SceneError> {
        match self.parser.tokens.next() {
            Some(token) => Ok(token),
            None => Err(self.cut_short(what)),
        }
    }

    /// The error for a file that ends before `what`. Errors are made apart from the reading
    /// (`#[cold]`), so that reading a number stays a few instructions.
    #[cold]
    fn cut_short(&self, what: &str) -> SceneError {
        self.error_here(format!(
            "`{}` is cut short: the file ends before {what}",
            self.keyword.text
        ))
    }

    /// An error at `token`, which is not the `what` expected.
    fn unexpected(&self, token: Token, what: &str) -> SceneError {
        self.parser.source.error(
            token.span(),
            format!(
                "expected {what} of `{}`, found `{}`",
                self.keyword.text, token.text
            ),
        )
    }

    /// An error at `token`, whose value is out of range.
    fn out_of_range(&self, token: Token, message: String) -> SceneError {
        self.parser.source.error(token.span(), message)
    }

    /// The next token as a finite number, with the token. raylab renders in single
    /// precision, so larger magnitudes than it holds are errors here, where they are written.
    #[inline]
    fn number_token(&mut self, what: &str) -> Result<(f64, Token<'a>), SceneError> {
        let token = self.token(what)?;
        match token.text.parse::<f64>() {
            Ok(x) if (x as f32).is_finite() => Ok((x, token)),
            number => Err(self.not_a_number(token, number.ok(), what)),
        }
    }

    /// The error for `token`, read as `number`, which is not a finite single-precision `what`.
    #[cold]
    fn not_a_number(&self, token: Token, number: Option<f64>, what: &str) -> SceneError {
        match number {
            Some(x) if x.is_finite() => self.out_of_range(
                token,
                format!("{what} is too large for single precision: {x}"),
            ),
            _ => self.unexpected(token, &format!("a number for {what}")),
        }
    }

    /// The next token as a finite number.
    fn number(&mut self, what: &str) -> Result<f64, SceneError> {
        Ok(self.number_token(what)?.0)
    }

    /// A number that must not be negative.
    fn non_negative(&mut self, what: &str) -> Result<f64, SceneError> {
        let (x, token) = self.number_token(what)?;
        if x < 0.0 {
            return Err(self.out_of_range(token, format!("{what} must not be negative, got {x}")));
        }
        Ok(x)
    }

    /// The next three tokens as a vector.
    fn vector(&mut self, what: &str) -> Result<DVec3, SceneError> {
        Ok(DVec3::new(
            self.number(what)?,
            self.number(what)?,
            self.number(what)?,
        ))
    }

    /// Three numbers from 0 on.
    fn color(&mut self, what: &str) -> Result<DVec3, SceneError> {
        Ok(DVec3::new(
            self.non_negative(what)?,
            self.non_negative(what)?,
            self.non_negative(what)?,
        ))
    }

    /// A whole number from `min` to `max`.
    fn whole(&mut self, what: &str, min: u64, max: u64) -> Result<u64, SceneError> {
        let token = self.token(what)?;
        let n = token
            .text
            .parse::<u64>()
            .map_err(|_| self.unexpected(token, &format!("a whole number for {what}")))?;
        if n < min || n > max {
            return Err(self.out_of_range(
                token,
                format!("{what} must be from {min} to {max}, got {n}"),
            ));
        }
        Ok(n)
    }

    /// The vertex count of `p` or `pp`: at least 3.
    fn vertex_count(&mut self) -> Result<usize, SceneError> {
        let token = self.token("the number of vertices")?;
        match token.text.parse::<u64>() {
            Ok(n) if n >= 3 => Ok(usize::try_from(n).unwrap_or(usize::MAX)),
            Ok(n) => Err(self.out_of_range(
                token,
                format!("a polygon needs at least 3 vertices, got {n}"),
            )),
            Err(_) => Err(self.unexpected(token, "a whole number of vertices")),
        }
    }

    /// The sub-keyword `name` of the `v` block.
    fn expect_word(&mut self, name: &str) -> Result<(), SceneError> {
        let token = self.token(&format!("`{name}`"))?;
        if token.text == name {
            Ok(())
        } else {
            Err(self.unexpected(token, &format!("`{name}`")))
        }
    }

    /// `v`, then `from`, `at`, `up`, `angle`, `hither` and `resolution` with their numbers.
    fn view(&mut self) -> Result<View, SceneError> {
        self.expect_word("from")?;
        let from = self.vector("the eye position")?;
        self.expect_word("at")?;
        let at = self.vector("the look-at point")?;
        self.expect_word("up")?;
        let up = self.vector("the up vector")?;
        self.expect_word("angle")?;
        let (angle, token) = self.number_token("the view angle")?;
        if !(angle > 0.0 && angle < 180.0) {
            return Err(self.out_of_range(
                token,
                format!("the view angle must be between 0 and 180 degrees, got {angle}"),
            ));
        }
        self.expect_word("hither")?;
        let (hither, token) = self.number_token("the hither distance")?;
        // 0 means no clipping: SPD's `lattice` and BRL-CAD's exporter write it.
        if hither < 0.0 {
            return Err(self.out_of_range(
                token,
                format!("the hither distance must not be negative, got {hither}"),
            ));
        }
        self.expect_word("resolution")?;
        let side = u64::from(MAX_IMAGE_SIDE);
        let width = self.whole("the image width", 1, side)?;
        let height = self.whole("the image height", 1, side)?;
        Ok(View {
            from,
            at,
            up,
            angle,
            hither,
            resolution: [width as u32, height as u32],
        })
    }

    /// `l X Y Z`, optionally followed by a colour.
    fn light(&mut self) -> Result<NffLight, SceneError> {
        let position = self.vector("the light position")?;
        let has_color = self
            .parser
            .tokens
            .peek()
            .is_some_and(|t| t.text.parse::<f64>().is_ok());
        let color = if has_color {
            Some(self.color("the light colour")?)
        } else {
            None
        };
        Ok(NffLight { position, color })
    }

    /// `f R G B Kd Ks Shine T IOR`.
    fn fill(&mut self) -> Result<Fill, SceneError> {
        let color = self.color("the colour")?;
        let kd = self.non_negative("Kd")?;
        let ks = self.non_negative("Ks")?;
        let shine = self.non_negative("Shine")?;
        let transmittance = self.non_negative("T")?;
        let (ior, token) = self.number_token("the index of refraction")?;
        if transmittance > 0.0 && ior <= 0.0 {
            return Err(self.out_of_range(
                token,
                format!("a transmitting material needs a positive index of refraction, got {ior}"),
            ));
        }
        Ok(Fill {
            color,
            kd,
            ks,
            shine,
            transmittance,
            ior,
        })
    }
}
