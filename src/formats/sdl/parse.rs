//! Reading SDL statements the way the book's `Scene::getObject` does, and telling the
//! [`Builder`] what they mean. Where the book's parser stops reading without a word (an unknown
//! keyword, a missing `{`, an undefined `use`) or ends the program (a bad number), this one
//! reports the place and what was expected there.

use glam::Vec3;

use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::Arc;

use super::build::{Builder, PIXMAPS, SdlMaterial};
use super::expand::{Tokens, Word};
use super::mesh_3vn::parse_3vn;
use super::solids::{self, POLYHEDRA};
use super::suggest::did_you_mean;
use crate::color::Color;
use crate::formats::{SceneError, SceneFiles, Source, ascii_text};
use crate::light::Light;
use crate::limits;
use crate::scene::Scene;
use crate::shapes::{Csg, CsgOperation, Operand, Shape};
use crate::srgb_image::SrgbImage;
use crate::transform::TransformStep;

/// Every keyword raylab's SDL reader knows but the polyhedra ([`POLYHEDRA`]), for suggestions.
const KEYWORDS: &[&str] = &[
    "light",
    "globalAmbient",
    "background",
    "minReflectivity",
    "minTransparency",
    "maxRecursionDepth",
    "ambient",
    "diffuse",
    "specular",
    "emissive",
    "specularExponent",
    "reflectivity",
    "transparency",
    "speedOfLight",
    "specularFraction",
    "surfaceRoughness",
    "texture",
    "parameters",
    "defaultMaterials",
    "translate",
    "scale",
    "rotate",
    "push",
    "pop",
    "identityAffine",
    "def",
    "use",
    "sphere",
    "cube",
    "cylinder",
    "cone",
    "taperedCylinder",
    "taperedTube",
    "torus",
    "square",
    "plane",
    "teapot",
    "mesh",
    "union",
    "intersection",
    "difference",
    "makePixmap",
    "backgroundImage",
];

/// The most numbers `parameters` takes (the book's array holds 10).
const MAX_PARAMETERS: f32 = 10.0;

/// What the parser reads and what it builds.
struct Parser<'a> {
    tokens: Tokens<'a>,
    build: Builder,
    source: Source<'a>,
    files: SceneFiles<'a>,
    /// Files (meshes, pixmaps) already reported missing, so that each is reported once.
    missing: Vec<String>,
    /// Warnings given once per file, already given.
    noted: Vec<&'static str>,
}

/// Reads a whole SDL text into a scene.
pub(crate) fn parse(source: Source, files: SceneFiles) -> Result<Scene, SceneError> {
    let mut parser = Parser {
        tokens: Tokens::new(source),
        build: Builder::new(),
        source,
        files,
        missing: Vec::new(),
        noted: Vec::new(),
    };
    while parser.object()?.is_some() {}
    let open = parser.build.open_pushes();
    if open > 0 {
        let origin = source.origin.display();
        parser.build.scene.warnings.push(format!(
            "{origin}: {open} `push` never popped (harmless: the book's reader allows it)"
        ));
    }
    Ok(parser.build.scene)
}

impl<'a> Parser<'a> {
    /// Reads statements up to and including one shape, which it returns the keyword of (as
    /// `getObject` does); `None` at the end of the file.
    fn object(&mut self) -> Result<Option<Word<'a>>, SceneError> {
        while let Some(word) = self.tokens.next() {
            if self.statement(&word)? {
                if self.build.pixmap_missing() {
                    self.warn_once(
                        &word,
                        "a shape's texture names a pixmap that no `makePixmap` has read; it \
                         keeps its colour",
                    );
                }
                return Ok(Some(word));
            }
        }
        Ok(None)
    }

    /// Reads the statement `word` begins; `true` when it made a shape.
    fn statement(&mut self, word: &Word<'a>) -> Result<bool, SceneError> {
        match word.text() {
            "light" => {
                let position = self.point(word)?;
                let color = self.vector(word, "the light's colour")?;
                self.build
                    .scene
                    .lights
                    .push(Light::Point { position, color });
            }
            "globalAmbient" => {
                let ambient = self.vector(word, "a colour")?;
                self.build.scene.settings.ambient = ambient;
                self.check_settings(word)?;
            }
            "background" => {
                let background = self.vector(word, "a colour")?;
                self.build.scene.settings.background = background;
                self.check_settings(word)?;
            }
            "minReflectivity" => {
                self.build.min_reflectivity = self.fraction(word)?;
                self.build.set_cutoff();
            }
            "minTransparency" => {
                self.build.min_transparency = self.fraction(word)?;
                self.build.set_cutoff();
            }
            "maxRecursionDepth" => {
                let depth = self.number(word, "a whole number")?;
                self.build.scene.settings.max_depth = depth.max(0.0) as u32;
                self.check_settings(word)?;
            }
            "ambient" => self.build.material.ambient = self.vector(word, "a colour")?,
            "diffuse" => self.build.material.diffuse = self.vector(word, "a colour")?,
            "specular" => self.build.material.specular = self.vector(word, "a colour")?,
            "emissive" => self.build.material.emissive = self.vector(word, "a colour")?,
            "specularExponent" => {
                self.build.material.specular_exponent = self.number(word, "a number")?;
            }
            "exponent" => {
                self.warn_once(word, "`exponent` is read as `specularExponent`");
                self.build.material.specular_exponent = self.number(word, "a number")?;
            }
            "reflectivity" => self.build.material.reflectivity = self.number(word, "a number")?,
            "transparency" => self.build.material.transparency = self.number(word, "a number")?,
            "speedOfLight" => {
                let speed = self.number(word, "a number")?;
                if speed <= 0.0 {
                    return Err(self.tokens.error(
                        word,
                        format!("`speedOfLight` must be positive, got {speed}"),
                    ));
                }
                self.build.material.speed_of_light = speed;
            }
            "specularFraction" | "surfaceRoughness" => {
                // The book stores these and uses neither.
                self.number(word, "a number")?;
            }
            "texture" => {
                let number = self.number(word, "a texture number")?;
                // The book reads it into an int, dropping the fraction.
                let texture = number as i32;
                if !(-3..PIXMAPS as i32).contains(&texture) {
                    self.warn_once(
                        word,
                        "a texture number other than 0 (none), -1 (checkerboard), -2 (wood), \
                         -3 (marble) or 1 to 15 (a pixmap) gives no texture",
                    );
                }
                self.build.material.texture = texture;
            }
            "parameters" => {
                let count = self.number(word, "how many parameters follow")?;
                if !(0.0..=MAX_PARAMETERS).contains(&count) {
                    return Err(self.tokens.error(
                        word,
                        format!("`parameters` takes 0 to {MAX_PARAMETERS} numbers, not {count}"),
                    ));
                }
                let mut parameters = Vec::with_capacity(count as usize);
                for _ in 0..count as usize {
                    parameters.push(self.number(word, "a parameter")?);
                }
                self.build.material.parameters = parameters;
            }
            "makePixmap" => self.make_pixmap(word)?,
            "backgroundImage" => {
                let name = self.word(word, "an image file name")?;
                self.build.scene.background_image = self.image_beside(&name, "background image");
            }
            "defaultMaterials" => self.build.material = SdlMaterial::default(),
            "translate" => {
                let by = self.vector(word, "a distance along x, y and z")?;
                self.transform(word, TransformStep::Translate(by))?;
            }
            "scale" => {
                let by = self.vector(word, "a factor along x, y and z")?;
                self.transform(word, TransformStep::Scale(by))?;
            }
            "rotate" => {
                let degrees = self.number(word, "an angle in degrees")?;
                let axis = self.vector(word, "an axis")?;
                self.transform(word, TransformStep::Rotate { axis, degrees })?;
            }
            "push" => self.build.push(),
            "pop" => {
                if !self.build.pop() {
                    self.warn_once(
                        word,
                        "`pop` with nothing pushed (the transform becomes the identity)",
                    );
                }
            }
            "identityAffine" => self.build.identity(),
            "def" => self.tokens.define(word)?,
            "use" => self.tokens.expand(word)?,
            "sphere" => return self.shape(word, solids::sphere()),
            "cube" => return self.shape(word, solids::cube()),
            "cylinder" => return self.shape(word, solids::tapered_cylinder(1.0)),
            "cone" => return self.shape(word, solids::tapered_cylinder(0.0)),
            "taperedCylinder" => {
                let top = self.number(word, "the small radius")?;
                return self.shape(word, solids::tapered_cylinder(top));
            }
            "taperedTube" => {
                let top = self.number(word, "the small radius")?;
                let thickness = self.number(word, "the wall's thickness")?;
                let result = solids::tapered_tube(top, thickness)
                    .and_then(|(solid, hole)| self.build.hollow(solid, hole));
                result.map_err(|e| self.tokens.error(word, e))?;
                return Ok(true);
            }
            "square" => return self.shape(word, solids::square()),
            "plane" => return self.shape(word, solids::plane()),
            "teapot" => {
                let result = self.build.solid("teapot", solids::teapot);
                result.map_err(|e| self.tokens.error(word, e))?;
                return Ok(true);
            }
            name if POLYHEDRA.contains(&name) => {
                let result = self.build.solid(name, || solids::polyhedron(name));
                result.map_err(|e| self.tokens.error(word, e))?;
                return Ok(true);
            }
            "mesh" => {
                self.mesh_file(word)?;
                return Ok(true);
            }
            "torus" => {
                let result = solids::torus()
                    .and_then(|(torus, frame)| self.build.shape_in_frame(torus, frame));
                result.map_err(|e| self.tokens.error(word, e))?;
                return Ok(true);
            }
            "union" | "intersection" | "difference" => {
                self.boolean(word)?;
                return Ok(true);
            }
            other => {
                let hint = did_you_mean(other, KEYWORDS.iter().chain(&POLYHEDRA).copied());
                let message = if matches!(other, "{" | "}") {
                    format!("unexpected `{other}` (braces belong to a `def`)")
                } else {
                    format!("unknown keyword `{other}`{hint}")
                };
                return Err(self.tokens.error(word, message));
            }
        }
        Ok(false)
    }

    /// The next word, which `after` needs as `what`.
    fn word(&mut self, after: &Word, what: &str) -> Result<Word<'a>, SceneError> {
        self.tokens.next().ok_or_else(|| {
            self.tokens.error(
                after,
                format!("`{}` needs {what}, but the file ends", after.text()),
            )
        })
    }

    /// A number: what C++ reads into a float (`.7`, `-3`, `1e-3`, `+2`), the whole word.
    fn number(&mut self, after: &Word, what: &str) -> Result<f32, SceneError> {
        let word = self.word(after, what)?;
        word.text()
            .parse::<f32>()
            .ok()
            .filter(|x| x.is_finite() && !word.text().starts_with(['i', 'I', 'n', 'N']))
            .ok_or_else(|| {
                self.tokens.error(
                    &word,
                    format!(
                        "expected {what} after `{}`, found `{}`",
                        after.text(),
                        word.text()
                    ),
                )
            })
    }

    /// A number from 0 to 1 (`minReflectivity`, `minTransparency`).
    fn fraction(&mut self, after: &Word) -> Result<f32, SceneError> {
        let value = self.number(after, "a number from 0 to 1")?;
        if !(0.0..=1.0).contains(&value) {
            let message = format!("`{}` must be between 0 and 1, got {value}", after.text());
            return Err(self.tokens.error(after, message));
        }
        Ok(value)
    }

    /// Three numbers.
    fn vector(&mut self, after: &Word, what: &str) -> Result<Color, SceneError> {
        Ok(Vec3::new(
            self.number(after, what)?,
            self.number(after, what)?,
            self.number(after, what)?,
        ))
    }

    /// A point, within raylab's range.
    fn point(&mut self, after: &Word) -> Result<Vec3, SceneError> {
        let point = self.vector(after, "a position x y z")?;
        if !limits::within_range(point) {
            let message = limits::out_of_range_message("the position", point);
            return Err(self.tokens.error(after, message));
        }
        Ok(point)
    }

    fn transform(&mut self, word: &Word, step: TransformStep) -> Result<(), SceneError> {
        self.build
            .transform(step)
            .map_err(|e| self.tokens.error(word, e))
    }

    fn check_settings(&mut self, word: &Word) -> Result<(), SceneError> {
        self.build
            .scene
            .settings
            .validate()
            .map_err(|e| self.tokens.error(word, e))
    }

    /// Adds a shape; `true`, for [`Self::statement`].
    fn shape(&mut self, word: &Word, shape: Result<Shape, String>) -> Result<bool, SceneError> {
        shape
            .and_then(|shape| self.build.shape(shape))
            .map_err(|e| self.tokens.error(word, e))?;
        Ok(true)
    }

    /// `mesh FILE`: a `.3vn` file beside the scene file. A missing file is a warning, once.
    fn mesh_file(&mut self, word: &Word<'a>) -> Result<(), SceneError> {
        let name = self.word(word, "a .3vn file name")?;
        let Some((bytes, path)) = self.read_beside(&name, "mesh") else {
            return Ok(());
        };
        let mesh = parse_3vn(&ascii_text(&bytes))
            .map_err(|e| self.tokens.error(&name, format!("{}: {e}", path.display())))?;
        self.build
            .mesh(mesh)
            .map_err(|e| self.tokens.error(&name, e))
    }

    /// `makePixmap N FILE`: reads the image into pixmap N (0 to 15). The other version of the
    /// book's code writes a third number (the OpenGL texture's name), which is read and not
    /// needed. A file that cannot be read or decoded is a warning, once, and leaves the pixmap
    /// empty.
    fn make_pixmap(&mut self, word: &Word<'a>) -> Result<(), SceneError> {
        let number = self.number(word, "a pixmap number from 0 to 15")?;
        if !(number.fract() == 0.0 && (0.0..PIXMAPS as f32).contains(&number)) {
            let message = format!("pixmaps are numbered 0 to {}, not {number}", PIXMAPS - 1);
            return Err(self.tokens.error(word, message));
        }
        let name = self.word(word, "an image file name")?;
        if self.tokens.peek().is_some_and(|t| t.parse::<f32>().is_ok()) {
            self.number(word, "a texture name")?;
        }
        self.build.pixmaps[number as usize] = self.image_beside(&name, "pixmap");
        Ok(())
    }

    /// The image file `name` names, beside the scene file, decoded; a warning, once, and
    /// `None` if it cannot be read or decoded.
    fn image_beside(&mut self, name: &Word, what: &str) -> Option<Arc<SrgbImage>> {
        let (bytes, path) = self.read_beside(name, what)?;
        match SrgbImage::decode(&bytes) {
            Ok(image) => Some(Arc::new(image)),
            Err(why) => {
                let message = format!("cannot decode {what} {}: {why}; left out", path.display());
                self.warn(name, &message);
                None
            }
        }
    }

    /// The bytes of the file `name` names, beside the scene file, and its path. A file that
    /// cannot be read is a warning, the first time it is named, and `None`.
    fn read_beside(&mut self, name: &Word, what: &str) -> Option<(Cow<'a, [u8]>, PathBuf)> {
        let path = self.files.path(name.text());
        match self.files.read(&path) {
            Ok(bytes) => Some((bytes, path)),
            Err(why) => {
                if !self.missing.iter().any(|m| m == name.text()) {
                    self.missing.push(name.text().to_string());
                    let message = format!(
                        "cannot read {what} file {}: {why}; left out",
                        path.display()
                    );
                    self.warn(name, &message);
                }
                None
            }
        }
    }

    /// `union A B`, `intersection A B`, `difference A B`: the next two objects (each any number
    /// of statements and then one shape, itself maybe a boolean) become the operands.
    fn boolean(&mut self, word: &Word<'a>) -> Result<(), SceneError> {
        let operation = match word.text() {
            "union" => CsgOperation::Union,
            "intersection" => CsgOperation::Intersection,
            _ => CsgOperation::Difference,
        };
        let mut operands = Vec::new();
        for side in ["first", "second"] {
            let (objects, meshes) = (self.objects(), self.build.scene.geometry.meshes.len());
            let Some(shape) = self.object()? else {
                let message = format!(
                    "`{}` needs two shapes, but the file ends before its {side}",
                    word.text()
                );
                return Err(self.tokens.error(word, message));
            };
            if self.build.scene.geometry.meshes.len() != meshes || self.objects() != objects + 1 {
                let message = format!(
                    "`{}` is a mesh (or a missing one), which a boolean object cannot cut: its \
                     operands must be solids (sphere, cube, cylinder, cone, taperedCylinder, \
                     torus, plane or another boolean)",
                    shape.text()
                );
                return Err(self.tokens.error(&shape, message));
            }
            let object = self
                .build
                .scene
                .geometry
                .objects
                .pop()
                .expect("one object was added");
            operands.push(Operand {
                shape: object.shape,
                transform: object.transform.map(|transform| *transform),
                material: object.material,
            });
        }
        let result = Csg::new(operation, operands).and_then(|csg| self.build.boolean(csg));
        result.map_err(|e| self.tokens.error(word, e))
    }

    fn objects(&self) -> usize {
        self.build.scene.geometry.objects.len()
    }

    /// A warning the first time `message` comes up, and no more.
    fn warn_once(&mut self, word: &Word, message: &'static str) {
        if !self.noted.contains(&message) {
            self.noted.push(message);
            self.warn(word, message);
        }
    }

    /// A warning at `word`'s line: `file:line: message`.
    fn warn(&mut self, word: &Word, message: &str) {
        let at = self.tokens.error(word, message);
        self.build.scene.warnings.push(format!(
            "{}:{}: {}",
            self.source.origin.display(),
            at.line,
            at.message
        ));
    }
}
