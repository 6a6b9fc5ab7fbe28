//! The SVG reader of sketches (\[A11\] §5): the strokes of a drawing, each flattened to a polyline
//! in the root element's user units (y axis flipped up), with its `class` and `data-*`
//! attributes. The XML is parsed by `roxmltree`; path data, transforms, lengths and number lists
//! by `svgtypes`.
//!
//! | read | how |
//! | --- | --- |
//! | `path` | every command (`M L H V C S Q T A Z`, absolute and relative); curves and arcs flattened to chords of about `step` |
//! | `circle`, `ellipse` | `cx cy r`, `cx cy rx ry` (SVG 2: one of `rx`, `ry` alone stands for both) |
//! | `rect` | `x y width height`, rounded corners `rx ry` |
//! | `line`, `polyline`, `polygon` | open, open, closed |
//! | `g`, `a`, `switch`, nested `svg` | containers (a nested `svg` is moved by its `x`, `y`) |
//! | `use` | `href` or `xlink:href="#id"`, moved by its `x`, `y`; a `symbol` through it |
//! | `transform` | on every element, composed down the tree (`matrix translate scale rotate skewX skewY`) |
//! | lengths | user units, `px`, and the absolute units `in cm mm pt pc` (96 user units an inch) |
//!
//! Not strokes, skipped with their content: `defs`, `symbol` (unless instantiated by a `use`),
//! `clipPath`, `mask`, `pattern`, `marker`, `metadata`, `text`, `image`, any other element, and
//! every element outside the SVG namespace (editors' own, e.g. Inkscape's). The root's `x`,
//! `y`, `width`, `height` and `viewBox` are ignored: coordinates stay in its user units.
//! Presentation (stroke, fill, `display`, CSS) is ignored.
//!
//! Refused, as [`Error::Parse`] at the element or the attribute value: malformed XML, a root
//! that is not `svg`, malformed numbers, path data or transforms, relative units (`%`, `em`,
//! `ex`), a `viewBox` on a nested `svg` or an instantiated `symbol`, `use` references that are
//! not `#id` of this file, name no element, or contain themselves, non-positive radii and sizes,
//! coordinates that overflow, and inputs beyond the limits: [`MAX_NODES`] XML nodes,
//! [`MAX_ELEMENTS`] elements instantiated (each copy a `use` makes counts), [`MAX_USE_DEPTH`]
//! nested `use`, [`MAX_POINTS`] points. The tree is walked without recursion, so the depth of
//! the nesting costs no stack; the work is linear in the size of the input and the elements
//! instantiated.

use crate::error::{Error, Result};
use crate::geom::DVec2;
use roxmltree::{Attribute, Document, Node, NodeId, ParsingOptions};
use std::collections::HashMap;
use std::str::FromStr;

/// The largest coordinate (user units, after the transforms) a sketch may have: the
/// triangulation (spade) refuses points beyond about 1e150 with a bare "too large", and a
/// drawing with such coordinates is a broken file, not a design.
pub const MAX_COORDINATE: f64 = 1e15;

/// One flattened outline of a sketch.
#[derive(Clone, Debug, PartialEq)]
pub struct SketchPath {
    /// Points in SVG user units, y axis flipped (up) so that counter-clockwise is positive.
    pub points: Vec<DVec2>,
    /// A closed outline (the last point joins the first; it is not repeated).
    pub closed: bool,
    /// The element's `class` attribute (space-separated names).
    pub class: String,
    /// `data-sharpness` (degrees), when given.
    pub sharpness: Option<f64>,
    /// `data-kind` (`crease`, `inactive`, `boundary`), when given.
    pub kind: Option<String>,
    /// 1-based line of the element in the file (for messages).
    pub line: usize,
}

/// XML nodes (elements, text, comments…) a file may hold.
pub const MAX_NODES: u32 = 4_000_000;
/// Elements instantiated at most, counting every copy a `use` makes (against exponential
/// expansion by `use` of `use`).
pub const MAX_ELEMENTS: usize = 1_000_000;
/// `use` elements nested at most (a `use` of an element that holds a `use` of…).
pub const MAX_USE_DEPTH: usize = 64;
/// Points at most in all the flattened outlines together.
pub const MAX_POINTS: usize = 10_000_000;

const SVG_NS: &str = "http://www.w3.org/2000/svg";
const XLINK_NS: &str = "http://www.w3.org/1999/xlink";

/// Reads the outlines of an SVG text. `step` is the flattening chord length (user units of the
/// root; `f64::INFINITY` for the coarsest flattening); `source` names the file in messages.
pub fn read_svg(text: &str, source: &str, step: f64) -> Result<Vec<SketchPath>> {
    let lines = Lines::new(text);
    let options = ParsingOptions { allow_dtd: true, nodes_limit: MAX_NODES, ..ParsingOptions::default() };
    let doc = Document::parse_with_options(text, options).map_err(|e| {
        let pos = e.pos();
        let message = e.to_string();
        let message = message.strip_suffix(&format!(" at {pos}")).unwrap_or(&message);
        Error::parse(source, pos.row as usize, pos.col as usize, format!("XML: {message}"))
    })?;
    let root = doc.root_element();
    let mut reader = Reader {
        doc: &doc,
        lines,
        source,
        step,
        out: Vec::new(),
        elements: 0,
        points_left: MAX_POINTS,
        uses: Vec::new(),
        ids: None,
    };
    if !is_svg(root) || root.tag_name().name() != "svg" {
        return Err(reader.error(root.range().start, format!("the root element is <{}>, not <svg>", name(root))));
    }
    reader.walk(root)?;
    if reader.out.is_empty() {
        return Err(reader.error(
            root.range().start,
            "no path, circle, ellipse, rect, line, polygon or polyline element outside <defs>",
        ));
    }
    Ok(reader.out)
}

/// 1-based lines and columns of byte offsets, by a table of line starts built once.
struct Lines<'t> {
    text: &'t str,
    starts: Vec<usize>,
}

impl<'t> Lines<'t> {
    fn new(text: &'t str) -> Self {
        let starts = std::iter::once(0).chain(text.match_indices('\n').map(|(i, _)| i + 1)).collect();
        Lines { text, starts }
    }

    /// Line and column (in characters) of the byte `offset`.
    fn at(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let line = self.starts.partition_point(|&s| s <= offset).max(1);
        let start = self.starts[line - 1];
        let column = self.text.get(start..offset).map_or(offset - start, |s| s.chars().count());
        (line, column + 1)
    }
}

/// An affine map `(x, y) ↦ (a x + c y + e, b x + d y + f)`: SVG's `matrix(a b c d e f)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Affine([f64; 6]);

impl Affine {
    const IDENTITY: Affine = Affine([1.0, 0.0, 0.0, 1.0, 0.0, 0.0]);

    fn translate(x: f64, y: f64) -> Self {
        Affine([1.0, 0.0, 0.0, 1.0, x, y])
    }

    /// `self ∘ inner`: `inner` applies first (SVG's parent · child). Exact when either is the
    /// identity.
    fn then(self, inner: Affine) -> Affine {
        if inner == Self::IDENTITY {
            return self;
        }
        if self == Self::IDENTITY {
            return inner;
        }
        let [a, b, c, d, e, f] = self.0;
        let [p, q, r, s, t, u] = inner.0;
        Affine([a * p + c * q, b * p + d * q, a * r + c * s, b * r + d * s, a * t + c * u + e, b * t + d * u + f])
    }

    fn apply(self, p: DVec2) -> DVec2 {
        let [a, b, c, d, e, f] = self.0;
        DVec2::new(a * p.x + c * p.y + e, b * p.x + d * p.y + f)
    }

    /// The largest factor by which the map stretches a vector (largest singular value).
    fn stretch(self) -> f64 {
        let [a, b, c, d, ..] = self.0;
        let sum = a * a + b * b + c * c + d * d;
        let det = a * d - b * c;
        ((sum + (sum * sum - 4.0 * det * det).max(0.0).sqrt()) / 2.0).sqrt()
    }
}

/// What an element is to the reader.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// `g`, `a`, `switch`, the root `svg`, a `symbol` instantiated by a `use`.
    Group,
    /// A nested `svg`.
    Viewport,
    /// `use`.
    Use,
    /// `path`, `circle`, `ellipse`, `rect`, `line`, `polyline`, `polygon`.
    Shape,
    /// Not drawn: skipped with its content.
    Skip,
}

fn is_svg(node: Node) -> bool {
    node.is_element() && matches!(node.tag_name().namespace(), None | Some(SVG_NS))
}

fn name<'a>(node: Node<'a, '_>) -> &'a str {
    node.tag_name().name()
}

/// A node to visit: the map of its parent's coordinates to the root's, the chain of `use`
/// that instantiated it (an index into [`Reader::uses`]), whether a `use` names it.
struct Visit<'a, 'i> {
    node: Node<'a, 'i>,
    to_root: Affine,
    chain: Option<usize>,
    used: bool,
}

/// Where a flattening failed: in the attribute's syntax (a position in it) or elsewhere.
enum Fault {
    Syntax(svgtypes::Error),
    Other(String),
}

impl From<svgtypes::Error> for Fault {
    fn from(e: svgtypes::Error) -> Self {
        Fault::Syntax(e)
    }
}

struct Reader<'a, 'i> {
    doc: &'a Document<'i>,
    lines: Lines<'i>,
    source: &'a str,
    step: f64,
    out: Vec<SketchPath>,
    /// Elements instantiated so far.
    elements: usize,
    /// Points the outlines may still add.
    points_left: usize,
    /// The `use` chains: (the element a `use` names, the chain of that `use`).
    uses: Vec<(NodeId, Option<usize>)>,
    /// Elements by `id`, built at the first `use`.
    ids: Option<HashMap<&'a str, Node<'a, 'i>>>,
}

impl<'a, 'i> Reader<'a, 'i> {
    fn error(&self, offset: usize, message: impl Into<String>) -> Error {
        let (line, column) = self.lines.at(offset);
        Error::parse(self.source, line, column, message)
    }

    /// An error in the value of `attr` of `node`: at the position `e` gives, or at the value.
    fn syntax_error(&self, node: Node, attr: &Attribute, e: &svgtypes::Error) -> Error {
        use svgtypes::Error as E;
        let value = attr.value();
        let (pos, what) = match *e {
            E::UnexpectedEndOfStream => (None, "ends early (a number is missing)".to_string()),
            E::InvalidNumber(p) => (Some(p), "malformed number".to_string()),
            E::UnexpectedData(p) | E::InvalidChar(_, p) | E::InvalidString(_, p) => {
                let c = value.chars().nth(p.saturating_sub(1));
                (Some(p), c.map_or("unexpected end".to_string(), |c| format!("unexpected {c:?}")))
            }
            _ => (None, "invalid value".to_string()),
        };
        let range = attr.range_value();
        let raw = self.doc.input_text().get(range.clone()).unwrap_or("");
        // Positions count characters of the value; entities make it differ from the file.
        let offset = match pos {
            Some(p) if raw == value => {
                range.start + raw.char_indices().nth(p.saturating_sub(1)).map_or(raw.len(), |c| c.0)
            }
            Some(_) => range.start,
            None if raw == value => range.end,
            None => range.start,
        };
        self.error(offset, format!("<{}> {}: {what}", name(node), attr.name()))
    }

    /// Visits the tree in document order with an explicit stack.
    fn walk(&mut self, root: Node<'a, 'i>) -> Result<()> {
        let mut stack = vec![Visit { node: root, to_root: Affine::IDENTITY, chain: None, used: false }];
        while let Some(v) = stack.pop() {
            let node = v.node;
            let kind = self.kind(&v);
            if kind == Kind::Skip {
                continue;
            }
            self.elements += 1;
            if self.elements > MAX_ELEMENTS {
                return Err(self.error(
                    node.range().start,
                    format!("more than {MAX_ELEMENTS} elements (counting each copy a <use> makes)"),
                ));
            }
            let m = v.to_root.then(self.transform(node)?);
            match kind {
                Kind::Group | Kind::Viewport => {
                    let m = if kind == Kind::Viewport { m.then(self.position(node)?) } else { m };
                    let first = stack.len();
                    stack.extend(node.children().filter(|c| c.is_element()).map(|c| Visit {
                        node: c,
                        to_root: m,
                        chain: v.chain,
                        used: false,
                    }));
                    stack[first..].reverse();
                }
                Kind::Use => {
                    let (target, chain) = self.reference(node, v.chain)?;
                    let m = m.then(self.position(node)?);
                    stack.push(Visit { node: target, to_root: m, chain: Some(chain), used: true });
                }
                Kind::Shape => self.shape(node, m)?,
                Kind::Skip => {}
            }
        }
        Ok(())
    }

    fn kind(&self, v: &Visit) -> Kind {
        if !is_svg(v.node) {
            return Kind::Skip;
        }
        match name(v.node) {
            "svg" if v.node == self.doc.root_element() => Kind::Group,
            "svg" => Kind::Viewport,
            "g" | "a" | "switch" => Kind::Group,
            "symbol" if v.used => Kind::Viewport,
            "use" => Kind::Use,
            "path" | "circle" | "ellipse" | "rect" | "line" | "polyline" | "polygon" => Kind::Shape,
            _ => Kind::Skip,
        }
    }

    /// The element's `transform` attribute (identity when absent).
    fn transform(&self, node: Node) -> Result<Affine> {
        let Some(attr) = node.attribute_node("transform") else { return Ok(Affine::IDENTITY) };
        let t = svgtypes::Transform::from_str(attr.value()).map_err(|e| self.syntax_error(node, &attr, &e))?;
        let m = Affine([t.a, t.b, t.c, t.d, t.e, t.f]);
        if !m.0.iter().all(|x| x.is_finite()) {
            return Err(self.error(attr.range_value().start, format!("<{}> transform: overflows", name(node))));
        }
        Ok(m)
    }

    /// The translation by `x`, `y` of a `use` or a nested `svg`; a `viewBox` is refused.
    fn position(&self, node: Node) -> Result<Affine> {
        if let Some(attr) = node.attribute_node("viewBox") {
            return Err(self.error(
                attr.range().start,
                format!("<{}>: a viewBox inside the drawing is not supported", name(node)),
            ));
        }
        let (x, y) = (self.length(node, "x", 0.0)?, self.length(node, "y", 0.0)?);
        Ok(if x == 0.0 && y == 0.0 { Affine::IDENTITY } else { Affine::translate(x, y) })
    }

    /// The element a `use` names and the chain of `use` that leads to it.
    fn reference(&mut self, node: Node<'a, 'i>, chain: Option<usize>) -> Result<(Node<'a, 'i>, usize)> {
        let attr = node
            .attribute_node("href")
            .or_else(|| node.attribute_node((XLINK_NS, "href")))
            .ok_or_else(|| self.error(node.range().start, "<use> without href"))?;
        let value = attr.value().trim();
        let Some(id) = value.strip_prefix('#') else {
            return Err(self.error(
                attr.range_value().start,
                format!("<use> href=\"{value}\": only elements of this file (#id) can be used"),
            ));
        };
        let doc = self.doc;
        let ids = self.ids.get_or_insert_with(|| {
            let mut ids = HashMap::new();
            for n in doc.descendants().filter(|n| n.is_element()) {
                if let Some(id) = n.attribute("id") {
                    ids.entry(id).or_insert(n);
                }
            }
            ids
        });
        let Some(&target) = ids.get(id) else {
            return Err(self.error(attr.range_value().start, format!("<use>: no element has id=\"{id}\"")));
        };
        let (mut link, mut depth) = (chain, 0);
        while let Some(i) = link {
            if self.uses[i].0 == target.id() {
                return Err(self.error(
                    node.range().start,
                    format!("<use> of #{id}: a reference cycle (#{id} contains this <use>)"),
                ));
            }
            depth += 1;
            link = self.uses[i].1;
        }
        if depth >= MAX_USE_DEPTH {
            return Err(self.error(node.range().start, format!("<use>: more than {MAX_USE_DEPTH} nested <use>")));
        }
        self.uses.push((target.id(), chain));
        Ok((target, self.uses.len() - 1))
    }

    /// A length attribute in user units; `default` when absent.
    fn length(&self, node: Node, attr_name: &str, default: f64) -> Result<f64> {
        use svgtypes::LengthUnit as U;
        let Some(attr) = node.attribute_node(attr_name) else { return Ok(default) };
        let length =
            svgtypes::Length::from_str(attr.value().trim_end()).map_err(|e| self.syntax_error(node, &attr, &e))?;
        let factor = match length.unit {
            U::None | U::Px => return Ok(length.number),
            U::In => 96.0,
            U::Cm => 96.0 / 2.54,
            U::Mm => 96.0 / 25.4,
            U::Pt => 96.0 / 72.0,
            U::Pc => 16.0,
            U::Em | U::Ex | U::Percent => {
                return Err(self.error(
                    attr.range_value().start,
                    format!(
                        "<{}> {attr_name}=\"{}\": relative units (%, em, ex) are not supported; use user units",
                        name(node),
                        attr.value()
                    ),
                ))
            }
        };
        Ok(length.number * factor)
    }

    /// Flattens a shape and adds its outlines, mapped to the root.
    fn shape(&mut self, node: Node, m: Affine) -> Result<()> {
        let stretch = m.stretch();
        // Chords of `step` in the root: shorter in the element's own units when it is enlarged.
        let step =
            if m == Affine::IDENTITY || stretch.is_nan() || stretch <= 0.0 { self.step } else { self.step / stretch };
        let mut pen = Pen::new(self.points_left);
        match name(node) {
            "path" => self.path(node, step, &mut pen)?,
            "circle" | "ellipse" => self.ellipse(node, step, &mut pen)?,
            "rect" => self.rect(node, step, &mut pen)?,
            "line" => {
                let (x1, y1) = (self.length(node, "x1", 0.0)?, self.length(node, "y1", 0.0)?);
                let (x2, y2) = (self.length(node, "x2", 0.0)?, self.length(node, "y2", 0.0)?);
                pen.cur = vec![DVec2::new(x1, y1), DVec2::new(x2, y2)];
                pen.finish(false);
            }
            _ => self.points(node, &mut pen)?,
        }
        self.points_left = pen.left;
        let sharpness = match node.attribute_node("data-sharpness") {
            Some(attr) => match attr.value().trim().parse::<f64>() {
                Ok(s) if s.is_finite() && s.abs() <= 180.0 => Some(s),
                Ok(s) if s.is_finite() => {
                    return Err(self.error(
                        attr.range_value().start,
                        format!("data-sharpness=\"{}\" is not in [-180, 180] degrees", attr.value()),
                    ))
                }
                _ => {
                    return Err(self.error(
                        attr.range_value().start,
                        format!("data-sharpness=\"{}\" is not a number", attr.value()),
                    ))
                }
            },
            None => None,
        };
        let line = self.lines.at(node.range().start).0;
        for (points, closed) in pen.subs {
            let points: Vec<DVec2> =
                if m == Affine::IDENTITY { points } else { points.into_iter().map(|p| m.apply(p)).collect() };
            if !points.iter().all(|p| p.is_finite()) {
                return Err(self.error(node.range().start, format!("<{}>: the coordinates overflow", name(node))));
            }
            if let Some(p) = points.iter().find(|p| p.x.abs().max(p.y.abs()) > MAX_COORDINATE) {
                return Err(self.error(
                    node.range().start,
                    format!(
                        "<{}>: a point ({:e}, {:e}) lies beyond ±{MAX_COORDINATE:e}: too far out to triangulate; scale the drawing",
                        name(node),
                        p.x,
                        p.y
                    ),
                ));
            }
            self.out.push(SketchPath {
                // SVG's y axis points down: flip it.
                points: points.into_iter().map(|p| DVec2::new(p.x, -p.y)).collect(),
                closed,
                class: node.attribute("class").unwrap_or("").to_string(),
                sharpness,
                kind: node.attribute("data-kind").map(str::to_string),
                line,
            });
        }
        Ok(())
    }

    fn fault(&self, node: Node, attr: Option<&Attribute>, f: Fault) -> Error {
        match (f, attr) {
            (Fault::Syntax(e), Some(attr)) => self.syntax_error(node, attr, &e),
            // (svgtypes' Display may panic on non-ASCII input: never used.)
            (Fault::Syntax(_), None) => self.error(node.range().start, format!("<{}>: invalid value", name(node))),
            (Fault::Other(m), _) => self.error(node.range().start, format!("<{}>: {m}", name(node))),
        }
    }

    fn path(&self, node: Node, step: f64, pen: &mut Pen) -> Result<()> {
        let attr = node.attribute_node("d");
        let d = attr.as_ref().map_or("", |a| a.value());
        flatten_path(d, step, pen).map_err(|f| self.fault(node, attr.as_ref(), f))
    }

    fn ellipse(&self, node: Node, step: f64, pen: &mut Pen) -> Result<()> {
        let (cx, cy) = (self.length(node, "cx", 0.0)?, self.length(node, "cy", 0.0)?);
        let (rx, ry) = if name(node) == "circle" {
            let r = self.length(node, "r", 0.0)?;
            (r, r)
        } else {
            let rx = self.length(node, "rx", f64::NAN)?;
            let ry = self.length(node, "ry", rx)?;
            (if rx.is_nan() { ry } else { rx }, ry)
        };
        if !(rx > 0.0 && ry > 0.0) {
            return Err(self.error(node.range().start, format!("<{}>: the radius must be positive", name(node))));
        }
        let n = pieces(std::f64::consts::TAU * rx.max(ry), step).max(12);
        for k in 0..n {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            pen.push(DVec2::new(cx + rx * a.cos(), cy + ry * a.sin())).map_err(|f| self.fault(node, None, f))?;
        }
        pen.finish(true);
        Ok(())
    }

    fn rect(&self, node: Node, step: f64, pen: &mut Pen) -> Result<()> {
        let (x, y) = (self.length(node, "x", 0.0)?, self.length(node, "y", 0.0)?);
        let (w, h) = (self.length(node, "width", 0.0)?, self.length(node, "height", 0.0)?);
        if !(w > 0.0 && h > 0.0) {
            return Err(self.error(node.range().start, "<rect>: width and height must be positive"));
        }
        let rx = self.length(node, "rx", f64::NAN)?;
        let ry = self.length(node, "ry", rx)?;
        let rx = if rx.is_nan() { ry } else { rx };
        let (rx, ry) = if ry.is_nan() { (0.0, 0.0) } else { (rx, ry) };
        if rx < 0.0 || ry < 0.0 {
            return Err(self.error(node.range().start, "<rect>: rx and ry must not be negative"));
        }
        let (rx, ry) = (rx.min(w / 2.0), ry.min(h / 2.0));
        if rx == 0.0 || ry == 0.0 {
            pen.cur = vec![DVec2::new(x, y), DVec2::new(x + w, y), DVec2::new(x + w, y + h), DVec2::new(x, y + h)];
            pen.finish(true);
            return Ok(());
        }
        // Quarter ellipses around the corners' centres, clockwise on the page from the top right.
        use std::f64::consts::FRAC_PI_2;
        let n = pieces(FRAC_PI_2 * rx.max(ry), step);
        let centres = [(x + w - rx, y + ry), (x + w - rx, y + h - ry), (x + rx, y + h - ry), (x + rx, y + ry)];
        for (q, &(cx, cy)) in centres.iter().enumerate() {
            for k in 0..=n {
                let a = FRAC_PI_2 * (q as f64 - 1.0 + k as f64 / n as f64);
                let p = DVec2::new(cx + rx * a.cos(), cy + ry * a.sin());
                if pen.cur.last() != Some(&p) {
                    pen.push(p).map_err(|f| self.fault(node, None, f))?;
                }
            }
        }
        if pen.cur.len() > 1
            && pen.cur.first().zip(pen.cur.last()).is_some_and(|(a, b)| a.distance(*b) < 1e-12 * w.max(h))
        {
            pen.cur.pop();
        }
        pen.finish(true);
        Ok(())
    }

    /// `polyline` and `polygon`.
    fn points(&self, node: Node, pen: &mut Pen) -> Result<()> {
        let attr = node.attribute_node("points");
        let mut nums = Vec::new();
        if let Some(attr) = &attr {
            for n in svgtypes::NumberListParser::from(attr.value()) {
                nums.push(n.map_err(|e| self.syntax_error(node, attr, &e))?);
            }
        }
        if nums.len() < 4 || nums.len() % 2 != 0 {
            return Err(self.error(
                node.range().start,
                format!("<{}>: points must hold an even number (≥ 4) of coordinates", name(node)),
            ));
        }
        for c in nums.chunks(2) {
            pen.push(DVec2::new(c[0], c[1])).map_err(|f| self.fault(node, None, f))?;
        }
        pen.finish(name(node) == "polygon");
        Ok(())
    }
}

/// Outlines being flattened: the finished subpaths `(points, closed)` and the current one,
/// with the number of points they may still take.
struct Pen {
    subs: Vec<(Vec<DVec2>, bool)>,
    cur: Vec<DVec2>,
    left: usize,
}

impl Pen {
    fn new(left: usize) -> Self {
        Pen { subs: Vec::new(), cur: Vec::new(), left }
    }

    fn push(&mut self, p: DVec2) -> std::result::Result<(), Fault> {
        if self.left == 0 {
            return Err(Fault::Other(format!("the sketch flattens to more than {MAX_POINTS} points")));
        }
        self.left -= 1;
        self.cur.push(p);
        Ok(())
    }

    /// Ends the current subpath (dropped if it has fewer than two points).
    fn finish(&mut self, closed: bool) {
        if self.cur.len() >= 2 {
            self.subs.push((std::mem::take(&mut self.cur), closed));
        } else {
            self.cur.clear();
        }
    }
}

/// Segments per Bézier piece or arc: enough for chords ≲ `step`.
fn pieces(len: f64, step: f64) -> usize {
    ((len / step).ceil() as usize).clamp(4, 10_000)
}

/// Flattens a path's `d` into `pen`'s subpaths; `step` is the flattening chord.
fn flatten_path(d: &str, step: f64, pen: &mut Pen) -> std::result::Result<(), Fault> {
    use svgtypes::PathSegment as S;
    let (mut p, mut start) = (DVec2::ZERO, DVec2::ZERO);
    // The last control point of a C/S ('C') or Q/T ('Q'), for the reflections of S and T.
    let mut last_ctrl: Option<(char, DVec2)> = None;
    for seg in svgtypes::PathParser::from(d) {
        let seg = seg?;
        let base = if seg.is_abs() { DVec2::ZERO } else { p };
        let at = |x: f64, y: f64| base + DVec2::new(x, y);
        // A drawing command right after Z starts at the closed subpath's start.
        if pen.cur.is_empty() && !matches!(seg, S::MoveTo { .. } | S::ClosePath { .. }) {
            pen.push(p)?;
        }
        match seg {
            S::MoveTo { x, y, .. } => {
                pen.finish(false);
                p = at(x, y);
                start = p;
                pen.push(p)?;
            }
            S::LineTo { x, y, .. } => {
                p = at(x, y);
                pen.push(p)?;
            }
            S::HorizontalLineTo { abs, x } => {
                p = DVec2::new(if abs { x } else { p.x + x }, p.y);
                pen.push(p)?;
            }
            S::VerticalLineTo { abs, y } => {
                p = DVec2::new(p.x, if abs { y } else { p.y + y });
                pen.push(p)?;
            }
            S::CurveTo { x1, y1, x2, y2, x, y, .. } => {
                let (c1, c2, e) = (at(x1, y1), at(x2, y2), at(x, y));
                cubic(pen, [p, c1, c2, e], step)?;
                (p, last_ctrl) = (e, Some(('C', c2)));
                continue;
            }
            S::SmoothCurveTo { x2, y2, x, y, .. } => {
                let c1 = match last_ctrl {
                    Some(('C', c)) => 2.0 * p - c,
                    _ => p,
                };
                let (c2, e) = (at(x2, y2), at(x, y));
                cubic(pen, [p, c1, c2, e], step)?;
                (p, last_ctrl) = (e, Some(('C', c2)));
                continue;
            }
            S::Quadratic { x1, y1, x, y, .. } => {
                let (c, e) = (at(x1, y1), at(x, y));
                quadratic(pen, [p, c, e], step)?;
                (p, last_ctrl) = (e, Some(('Q', c)));
                continue;
            }
            S::SmoothQuadratic { x, y, .. } => {
                let c = match last_ctrl {
                    Some(('Q', c)) => 2.0 * p - c,
                    _ => p,
                };
                let e = at(x, y);
                quadratic(pen, [p, c, e], step)?;
                (p, last_ctrl) = (e, Some(('Q', c)));
                continue;
            }
            S::EllipticalArc { rx, ry, x_axis_rotation, large_arc, sweep, x, y, .. } => {
                let e = at(x, y);
                let shape =
                    ArcShape { radii: DVec2::new(rx, ry), phi: x_axis_rotation.to_radians(), large: large_arc, sweep };
                arc(pen, p, e, &shape, step)?;
                p = e;
            }
            S::ClosePath { .. } => {
                if pen.cur.first().is_some_and(|f| pen.cur.last().is_some_and(|l| f.distance(*l) < 1e-12)) {
                    pen.cur.pop();
                }
                pen.finish(true);
                p = start;
            }
        }
        last_ctrl = None;
    }
    pen.finish(false);
    Ok(())
}

/// The cubic Bézier `c` after its first point, in `pieces` of its control polygon.
fn cubic(pen: &mut Pen, c: [DVec2; 4], step: f64) -> std::result::Result<(), Fault> {
    let [p, c1, c2, e] = c;
    let len = p.distance(c1) + c1.distance(c2) + c2.distance(e);
    let n = pieces(len, step);
    for k in 1..=n {
        let t = k as f64 / n as f64;
        let s = 1.0 - t;
        pen.push(s * s * s * p + 3.0 * s * s * t * c1 + 3.0 * s * t * t * c2 + t * t * t * e)?;
    }
    Ok(())
}

/// The quadratic Bézier `c` after its first point, in `pieces` of its control polygon.
fn quadratic(pen: &mut Pen, c: [DVec2; 3], step: f64) -> std::result::Result<(), Fault> {
    let [p, c, e] = c;
    let n = pieces(p.distance(c) + c.distance(e), step);
    for k in 1..=n {
        let t = k as f64 / n as f64;
        let s = 1.0 - t;
        pen.push(s * s * p + 2.0 * s * t * c + t * t * e)?;
    }
    Ok(())
}

/// The ellipse of an arc command (`A rx ry rotation large-arc sweep x y`).
struct ArcShape {
    radii: DVec2,
    /// Rotation of the ellipse's x axis, radians.
    phi: f64,
    large: bool,
    sweep: bool,
}

/// The SVG elliptical arc from `p0` to `p1` after its first point, in `pieces` of its length,
/// by the conversion to centre parameters of SVG 2 (appendix B.2.4–5): no arc when the ends
/// coincide, a line when a radius is zero, radii enlarged until the ends fit.
fn arc(pen: &mut Pen, p0: DVec2, p1: DVec2, shape: &ArcShape, step: f64) -> std::result::Result<(), Fault> {
    let (mut rx, mut ry) = (shape.radii.x.abs(), shape.radii.y.abs());
    if p0 == p1 {
        return Ok(());
    }
    if !(rx > 0.0 && ry > 0.0) {
        return pen.push(p1);
    }
    let (sin, cos) = shape.phi.sin_cos();
    // The ends in the ellipse's axes, relative to their midpoint.
    let h = (p0 - p1) / 2.0;
    let q = DVec2::new(cos * h.x + sin * h.y, -sin * h.x + cos * h.y);
    let lambda = (q.x / rx).powi(2) + (q.y / ry).powi(2);
    let coef = if lambda >= 1.0 {
        // Radii enlarged just enough: the centre is the midpoint (exactly, not by cancellation).
        (rx, ry) = (rx * lambda.sqrt(), ry * lambda.sqrt());
        0.0
    } else {
        let num = (rx * ry).powi(2) - (rx * q.y).powi(2) - (ry * q.x).powi(2);
        let den = (rx * q.y).powi(2) + (ry * q.x).powi(2);
        let sign = if shape.large == shape.sweep { -1.0 } else { 1.0 };
        sign * (num / den).max(0.0).sqrt()
    };
    let cq = coef * DVec2::new(rx * q.y / ry, -ry * q.x / rx);
    let centre = DVec2::new(cos * cq.x - sin * cq.y, sin * cq.x + cos * cq.y) + (p0 + p1) / 2.0;
    let u = DVec2::new((q.x - cq.x) / rx, (q.y - cq.y) / ry);
    let v = DVec2::new((-q.x - cq.x) / rx, (-q.y - cq.y) / ry);
    let theta = u.y.atan2(u.x);
    let mut delta = u.perp_dot(v).atan2(u.dot(v));
    if !shape.sweep && delta > 0.0 {
        delta -= std::f64::consts::TAU;
    } else if shape.sweep && delta < 0.0 {
        delta += std::f64::consts::TAU;
    }
    if ![rx, ry, centre.x, centre.y, theta, delta].iter().all(|x| x.is_finite()) {
        // A degenerate arc (overflowing radii): the straight line.
        return pen.push(p1);
    }
    let n = pieces(delta.abs() * rx.max(ry), step);
    for k in 1..n {
        let a = theta + delta * k as f64 / n as f64;
        let e = DVec2::new(rx * a.cos(), ry * a.sin());
        pen.push(centre + DVec2::new(cos * e.x - sin * e.y, sin * e.x + cos * e.y))?;
    }
    pen.push(p1)
}

#[cfg(test)]
#[path = "tests/svg.rs"]
mod tests;
