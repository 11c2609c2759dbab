//! The SVG plotters writes, made to render the same in every common rasteriser.
//!
//! Two constructs of plotters' SVG backend are read differently by ImageMagick's own SVG
//! renderer (MSVG, what `convert plot.svg plot.png` uses without librsvg) than by rsvg,
//! browsers and Inkscape:
//!
//! - `opacity`: MSVG applies an `opacity` after `fill="none"` as a fill, so every
//!   polyline of a curve is drawn as a filled black polygon, and it ignores the opacity of
//!   lines and polygons (the light grid lines come out black, a shaded band opaque). Every
//!   figure here is drawn on white, so an element's opacity is folded into its colours
//!   (each `#rrggbb` of its fill and stroke mixed with white) and the attribute dropped:
//!   the same picture on white for every renderer. An opacity of a colour that is not
//!   `#rrggbb` is kept, moved before the fill.
//! - `<text x="X" y="Y" transform="rotate(A, X, Y)">`: MSVG drops text rotated about a
//!   point (the three-argument `rotate`), so the vertical axis labels vanish. The text is
//!   placed at the origin and moved there: `x="0" y="0" transform="translate(X, Y)
//!   rotate(A)"`, the same picture for every renderer.

/// `svg` with the two constructs above rewritten; every other byte is kept.
pub fn portable(svg: &str) -> String {
    let mut out = String::with_capacity(svg.len());
    let mut rest = svg;
    while let Some(at) = rest.find('<') {
        out.push_str(&rest[..at]);
        rest = &rest[at..];
        let Some(end) = rest.find('>') else {
            break;
        };
        let tag = &rest[..=end];
        out.push_str(&rewrite_tag(tag));
        rest = &rest[end + 1..];
    }
    out.push_str(rest);
    out
}

/// (key, value) pairs in the order of the tag.
type Attributes<'a> = Vec<(&'a str, &'a str)>;

/// The attributes of a start tag `<name a="1" b="2"/>`: (name, [(key, value)], self-closing).
fn parse(tag: &str) -> Option<(&str, Attributes<'_>, bool)> {
    let inner = tag.strip_prefix('<')?.strip_suffix('>')?;
    if inner.starts_with(['/', '?', '!']) {
        return None;
    }
    let (inner, closing) = match inner.strip_suffix('/') {
        Some(s) => (s, true),
        None => (inner, false),
    };
    let name_end = inner
        .find(|c: char| c.is_ascii_whitespace())
        .unwrap_or(inner.len());
    let name = &inner[..name_end];
    let mut attrs = Vec::new();
    let mut s = inner[name_end..].trim_start();
    while !s.is_empty() {
        let eq = s.find('=')?;
        let key = s[..eq].trim();
        let after = s[eq + 1..].trim_start();
        let quote = after.chars().next()?;
        if quote != '"' && quote != '\'' {
            return None;
        }
        let close = after[1..].find(quote)? + 1;
        attrs.push((key, &after[1..close]));
        s = after[close + 1..].trim_start();
    }
    Some((name, attrs, closing))
}

fn rewrite_tag(tag: &str) -> String {
    let Some((name, mut attrs, closing)) = parse(tag) else {
        return tag.to_owned();
    };
    let mut changed = false;
    // the blended colours, in the order of the fill and stroke they replace (marked "")
    let mut blended: Vec<String> = Vec::new();
    // the opacity folded into the colours (on white), or at least before the fill
    if let Some(k) = attrs.iter().position(|(key, _)| *key == "opacity") {
        let (_, v) = attrs.remove(k);
        let o = v
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|o| (0.0..=1.0).contains(o));
        let hex = |c: &str| c == "none" || rgb(c).is_some();
        let paints = attrs
            .iter()
            .filter(|(key, _)| matches!(*key, "fill" | "stroke"))
            .all(|(_, c)| hex(c));
        match o {
            Some(o) if paints => {
                for (key, value) in attrs.iter_mut() {
                    if matches!(*key, "fill" | "stroke") {
                        if let Some((r, g, b)) = rgb(value) {
                            let mix = |c: u8| (f64::from(c) * o + 255.0 * (1.0 - o)).round() as u8;
                            blended.push(format!("#{:02X}{:02X}{:02X}", mix(r), mix(g), mix(b)));
                            *value = "";
                        }
                    }
                }
            }
            _ => attrs.insert(0, ("opacity", v)),
        }
        changed = true;
    }
    // text rotated about a point: placed at the origin, translated, rotated there
    let mut moved = None;
    if name == "text" {
        if let Some(t) = attrs.iter().position(|(key, _)| *key == "transform") {
            if let Some((a, cx, cy)) = rotate_about(attrs[t].1) {
                let get = |k: &str| {
                    attrs
                        .iter()
                        .find(|(key, _)| *key == k)
                        .and_then(|(_, v)| v.trim().parse::<f64>().ok())
                };
                let (x, y) = (get("x").unwrap_or(0.0), get("y").unwrap_or(0.0));
                let (fx, fy) = (
                    cx.parse::<f64>().unwrap_or(0.0),
                    cy.parse::<f64>().unwrap_or(0.0),
                );
                // rotate(a, cx, cy) then (x, y) = translate(cx, cy) rotate(a) at (x - cx, y - cy)
                moved = Some(match (font_size(&attrs), dy_em(&attrs), a.parse::<f64>()) {
                    // with its dy: the glyphs' middle (0.35 em above the baseline) put on
                    // the rotation's centre, so that ImageMagick, which turns text the
                    // other way and ignores dy, draws the label over the same band
                    (Some(size), Some((k, em)), Ok(deg)) => {
                        let c0 = (y - fy) + (em - MIDDLE) * size;
                        let (sin, cos) = deg.to_radians().sin_cos();
                        let (px, py) = (fx - c0 * sin, fy + c0 * cos);
                        attrs.remove(k);
                        changed = true;
                        (
                            format!(
                                "translate({}, {}) rotate({a})",
                                fmt_num((px * 1e3).round() / 1e3),
                                fmt_num((py * 1e3).round() / 1e3)
                            ),
                            fmt_num(x - fx),
                            fmt_num((MIDDLE * size * 1e3).round() / 1e3),
                        )
                    }
                    _ => (
                        format!("translate({cx}, {cy}) rotate({a})"),
                        fmt_num(x - fx),
                        fmt_num(y - fy),
                    ),
                });
            }
        }
    }
    // a polygon without a stroke: ImageMagick outlines it in black, rsvg does not
    if name == "polygon" && !attrs.iter().any(|(key, _)| *key == "stroke") {
        attrs.push(("stroke", "none"));
        changed = true;
    }
    // `dy` (plotters' vertical anchoring of text, "0.76em" or "0.5ex"): ImageMagick ignores
    // it, so titles lose their top and legend labels sit half a row low; folded into y,
    // with 1 ex = 0.5 em as rsvg
    let mut shifted = None;
    if name == "text" && moved.is_none() {
        if let (Some(size), Some((k, em))) = (font_size(&attrs), dy_em(&attrs)) {
            let y = attrs
                .iter()
                .find(|(key, _)| *key == "y")
                .and_then(|(_, v)| v.trim().parse::<f64>().ok())
                .unwrap_or(0.0);
            attrs.remove(k);
            shifted = Some(fmt_num(((y + em * size) * 1e3).round() / 1e3));
            changed = true;
        }
    }
    if !changed && moved.is_none() {
        return tag.to_owned();
    }
    let mut s = format!("<{name}");
    let mut blended = blended.iter();
    for (key, value) in &attrs {
        let value: &str = match (&moved, *key) {
            (_, "fill" | "stroke") if value.is_empty() => blended.next().map_or("", String::as_str),
            (_, "y") if shifted.is_some() => shifted.as_deref().unwrap_or(value),
            (Some((t, _, _)), "transform") => t,
            (Some((_, x, _)), "x") => x,
            (Some((_, _, y)), "y") => y,
            _ => value,
        };
        s.push_str(&format!(" {key}=\"{value}\""));
    }
    s.push_str(if closing { "/>" } else { ">" });
    s
}

/// Where the middle of a line of glyphs sits above its baseline, in em (lower case and
/// capitals of a sans-serif face).
const MIDDLE: f64 = 0.35;

/// A text's font size (px).
fn font_size(attrs: &Attributes<'_>) -> Option<f64> {
    attrs
        .iter()
        .find(|(key, _)| *key == "font-size")
        .and_then(|(_, v)| v.trim().trim_end_matches("px").parse::<f64>().ok())
}

/// The index of a text's `dy` and its value in em (1 ex = 0.5 em, as rsvg takes it).
fn dy_em(attrs: &Attributes<'_>) -> Option<(usize, f64)> {
    let k = attrs.iter().position(|(key, _)| *key == "dy")?;
    let v = attrs[k].1.trim();
    let em = if let Some(n) = v.strip_suffix("em") {
        n.parse::<f64>().ok()?
    } else if let Some(n) = v.strip_suffix("ex") {
        0.5 * n.parse::<f64>().ok()?
    } else {
        v.parse::<f64>().ok()? / font_size(attrs)?
    };
    Some((k, em))
}

/// The (r, g, b) of a `#rrggbb` colour.
fn rgb(c: &str) -> Option<(u8, u8, u8)> {
    let h = c.trim().strip_prefix('#')?;
    if h.len() != 6 || !h.is_ascii() {
        return None;
    }
    let byte = |i: usize| u8::from_str_radix(&h[i..i + 2], 16).ok();
    Some((byte(0)?, byte(2)?, byte(4)?))
}

/// (angle, cx, cy) of a transform that is exactly `rotate(a, cx, cy)`.
fn rotate_about(t: &str) -> Option<(String, String, String)> {
    let args = t.trim().strip_prefix("rotate(")?.strip_suffix(')')?;
    let parts: Vec<&str> = args
        .split(|c: char| c == ',' || c.is_ascii_whitespace())
        .filter(|p| !p.is_empty())
        .collect();
    match parts[..] {
        [a, cx, cy] if [a, cx, cy].iter().all(|p| p.parse::<f64>().is_ok()) => {
            Some((a.to_owned(), cx.to_owned(), cy.to_owned()))
        }
        _ => None,
    }
}

fn fmt_num(v: f64) -> String {
    if v == v.trunc() && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn opacity_is_folded_into_the_colours_on_white() {
        assert_eq!(
            portable(r##"<polyline fill="none" opacity="1" stroke="#000000" points="1,2 3,4 "/>"##),
            r##"<polyline fill="none" stroke="#000000" points="1,2 3,4 "/>"##
        );
        assert_eq!(
            portable(r##"<line opacity="0.1" stroke="#000000" x1="1"/>"##),
            r##"<line stroke="#E6E6E6" x1="1"/>"##
        );
        assert_eq!(
            portable(r##"<polygon opacity="0.25" fill="#1E3CC8" stroke="none"/>"##),
            r##"<polygon fill="#C7CEF1" stroke="none"/>"##
        );
        // a polygon without a stroke is given none (ImageMagick would outline it black)
        assert_eq!(
            portable(r##"<polygon fill="#C7CEF1" points="1,2 3,4 5,6"/>"##),
            r##"<polygon fill="#C7CEF1" points="1,2 3,4 5,6" stroke="none"/>"##
        );
        // a colour that is not #rrggbb keeps its opacity, before the fill
        assert_eq!(
            portable(r##"<rect fill="red" opacity="0.85" x="0"/>"##),
            r##"<rect opacity="0.85" fill="red" x="0"/>"##
        );
    }

    #[test]
    fn text_rotated_about_a_point_is_translated_then_rotated() {
        let s = portable(
            "<text x=\"12\" y=\"286\" dy=\"0.76em\" fill=\"#000000\" transform=\"rotate(270, 12, 286)\">\nlabel\n</text>",
        );
        assert_eq!(
            s,
            "<text x=\"0\" y=\"0\" dy=\"0.76em\" fill=\"#000000\" transform=\"translate(12, 286) rotate(270)\">\nlabel\n</text>"
        );
        // with its font size and dy, the glyphs' middle goes on the rotation's centre,
        // moved to where rsvg drew it (0.76 - 0.35 em = 4.1 px across the axis)
        assert_eq!(
            portable(
                "<text x=\"12\" y=\"286\" dy=\"0.76em\" font-size=\"10\" transform=\"rotate(270, 12, 286)\">\nlabel\n</text>"
            ),
            "<text x=\"0\" y=\"3.5\" font-size=\"10\" transform=\"translate(16.1, 286) rotate(270)\">\nlabel\n</text>"
        );
        // with its font size, the dy of unrotated text is folded into y
        assert_eq!(
            portable("<text x=\"5\" y=\"20\" dy=\"0.76em\" font-size=\"10\">t</text>"),
            "<text x=\"5\" y=\"27.6\" font-size=\"10\">t</text>"
        );
        assert_eq!(
            portable("<text x=\"5\" y=\"20\" dy=\"0.5ex\" font-size=\"16\">t</text>"),
            "<text x=\"5\" y=\"24\" font-size=\"16\">t</text>"
        );
        // text and other bytes pass through
        assert_eq!(portable("a < b"), "a < b");
        assert_eq!(
            portable("<svg width=\"1\">x</svg>\n"),
            "<svg width=\"1\">x</svg>\n"
        );
    }
}
