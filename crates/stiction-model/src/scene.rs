//! Scenes as written: a TOML or JSON file (or a tree built in code), not yet validated.
//!
//! A [`Scene`] is a tree of keys and values with the name of its source. It is checked
//! once, when a spec is made from it ([`crate::spec`]); until then it can be edited key by
//! key ([`Scene::set`], the `--set section.key=value` of every command, a design point's
//! varied field), and every edit is checked like a value of the file. Scenes merge
//! ([`Scene::merge`]: `--scene A --scene B`, the later winning key by key), and each key
//! remembers the file that gave it, for messages and for paths relative to that file.

use crate::error::SceneError;
use crate::keys::{self, Kind};
use std::collections::BTreeSet;
use std::io::Read;
use std::path::{Path, PathBuf};

/// Scene files are at most this large (1 MiB): a scene is a few dozen lines.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// The paper's Fig 2 scene, embedded.
pub const PAPER_ASPERITY: &str = include_str!("../scenes/asperity.toml");
/// The paper's rough-surface scene, embedded.
pub const PAPER_SURFACE: &str = include_str!("../scenes/surface.toml");
/// The paper's micro-switch scene (Fig 4), embedded: the main job.
pub const PAPER_SWITCH: &str = include_str!("../scenes/switch.toml");

/// The name the embedded scenes carry in messages.
pub const PAPER_FILE: &str = "<default scene>";

/// A scene as written, with the name of its source.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    file: String,
    text: Option<String>,
    tree: toml::Table,
    is_paper: bool,
    /// The folder of the file read (relative paths in the scene are relative to it).
    dir: Option<PathBuf>,
    /// The scenes merged into this one, the first the base (empty unless merged).
    layers: Vec<Layer>,
}

/// One scene of a merge: its name, text, folder and the keys it gave.
#[derive(Debug, Clone, PartialEq)]
struct Layer {
    file: String,
    text: Option<String>,
    dir: Option<PathBuf>,
    keys: BTreeSet<String>,
}

impl Layer {
    fn of(s: &Scene) -> Self {
        let mut keys = BTreeSet::new();
        leaf_keys(&s.tree, "", &mut keys);
        Layer {
            file: s.file.clone(),
            text: s.text.clone(),
            dir: s.dir.clone(),
            keys,
        }
    }
}

/// Every leaf key (`section.key`) of a tree; a law table's parameters are leaves too.
fn leaf_keys(t: &toml::Table, prefix: &str, out: &mut BTreeSet<String>) {
    for (k, v) in t {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            toml::Value::Table(sub) => leaf_keys(sub, &key, out),
            _ => {
                out.insert(key);
            }
        }
    }
}

/// `over` merged into `base` key by key: a table into a table recursively, any other value
/// replacing what `base` had.
fn merge_tables(base: &mut toml::Table, over: &toml::Table) {
    for (k, v) in over {
        match (base.get_mut(k), v) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge_tables(b, o),
            _ => {
                base.insert(k.clone(), v.clone());
            }
        }
    }
}

impl Scene {
    /// The embedded paper scene of `kind`.
    pub fn paper(kind: Kind) -> Self {
        let text = match kind {
            Kind::Asperity => PAPER_ASPERITY,
            Kind::Surface => PAPER_SURFACE,
            Kind::Switch => PAPER_SWITCH,
        };
        let mut s = Self::from_toml_str(PAPER_FILE, text).expect("the embedded scenes parse");
        s.is_paper = true;
        s
    }

    /// A scene from TOML text; `file` names it in messages.
    pub fn from_toml_str(file: &str, text: &str) -> Result<Self, SceneError> {
        if text.trim().is_empty() {
            return Err(SceneError::Empty { file: file.into() });
        }
        let tree: toml::Table = toml::from_str(text).map_err(|e| SceneError::Parse {
            file: file.into(),
            message: short_lines(e.to_string().trim_end()),
        })?;
        Ok(Self {
            file: file.into(),
            text: Some(text.to_string()),
            tree,
            is_paper: false,
            dir: None,
            layers: Vec::new(),
        })
    }

    /// A scene from JSON text (an object of the same keys as the TOML form; an infinite
    /// yield stress is the string `"inf"`); `file` names it in messages.
    pub fn from_json_str(file: &str, text: &str) -> Result<Self, SceneError> {
        if text.trim().is_empty() {
            return Err(SceneError::Empty { file: file.into() });
        }
        // a key given twice is refused, as TOML refuses it (serde_json's own value keeps the
        // last without a word)
        let mut de = serde_json::Deserializer::from_str(text);
        let v = serde::de::DeserializeSeed::deserialize(NoDuplicates(""), &mut de)
            .and_then(|v| de.end().map(|()| v))
            .map_err(|e| SceneError::Parse {
                file: file.into(),
                message: short_lines(&format!("JSON parse error: {e}")),
            })?;
        let mut s = Self::from_json_value(file, &v)?;
        s.text = Some(text.to_string());
        Ok(s)
    }

    /// A scene from a tree of keys and values built in code; `file` names it.
    pub fn from_tree(file: &str, tree: toml::Table) -> Self {
        Self {
            file: file.into(),
            text: None,
            tree,
            is_paper: false,
            dir: None,
            layers: Vec::new(),
        }
    }

    /// A scene from a JSON value (an object), as front ends that hold data structures
    /// build it (a Python dict).
    pub fn from_json_value(file: &str, v: &serde_json::Value) -> Result<Self, SceneError> {
        let tree = match json_to_toml(file, "", v)? {
            toml::Value::Table(t) => t,
            _ => {
                return Err(SceneError::Parse {
                    file: file.into(),
                    message: "a scene is an object of keys and values".into(),
                })
            }
        };
        Ok(Self {
            file: file.into(),
            text: None,
            tree,
            is_paper: false,
            dir: None,
            layers: Vec::new(),
        })
    }

    /// Reads a scene file: JSON if its name ends in `.json` or its text starts with `{`,
    /// TOML otherwise. Anything but a regular file (a folder, a FIFO, a device, a socket)
    /// is refused before it is opened: a FIFO with no writer would block for ever. Files
    /// larger than [`MAX_SCENE_BYTES`] are refused before they are read whole.
    pub fn read(path: &std::path::Path) -> Result<Self, SceneError> {
        let file = path.display().to_string();
        let read = |e: std::io::Error| SceneError::Read {
            file: file.clone(),
            message: e.to_string(),
        };
        let regular = |m: &std::fs::Metadata| match not_regular(m) {
            Some(what) => Err(SceneError::Read {
                file: file.clone(),
                message: format!("it is {what}, not a scene file"),
            }),
            None => Ok(()),
        };
        // the type first, from the path: opening a FIFO would wait for a writer
        regular(&std::fs::metadata(path).map_err(read)?)?;
        let f = std::fs::File::open(path).map_err(read)?;
        // the same check on the file opened (the path may have changed in between)
        regular(&f.metadata().map_err(read)?)?;
        let mut bytes = Vec::new();
        f.take(MAX_SCENE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(read)?;
        if bytes.len() as u64 > MAX_SCENE_BYTES {
            return Err(SceneError::TooLarge {
                file,
                limit: MAX_SCENE_BYTES,
            });
        }
        let text =
            String::from_utf8(bytes).map_err(|_| SceneError::NotText { file: file.clone() })?;
        let json = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"))
            || text.trim_start().starts_with('{');
        let mut scene = if json {
            Self::from_json_str(&file, &text)
        } else {
            Self::from_toml_str(&file, &text)
        }?;
        scene.dir = Some(path.parent().map_or_else(PathBuf::new, Path::to_path_buf));
        Ok(scene)
    }

    /// Reads the scene files `paths` and merges them in order ([`Self::merge`]), or gives
    /// the embedded paper scene of `kind` when there are none.
    pub fn read_merged(paths: &[PathBuf], kind: Kind) -> Result<Self, SceneError> {
        let Some((first, rest)) = paths.split_first() else {
            return Ok(Self::paper(kind));
        };
        let mut scene = Self::read(first)?;
        for p in rest {
            scene.merge(&Self::read(p)?);
        }
        Ok(scene)
    }

    /// Merges `other` into this scene key by key, `other` winning: each of its values
    /// replaces this scene's at the same key (sections and law tables merge key by key, a
    /// list is one value). Keys keep the file that gave them ([`Self::file_of`],
    /// [`Self::dir_of`], [`Self::line_of`]); the merged scene is named `a.toml + b.toml`.
    pub fn merge(&mut self, other: &Scene) {
        if self.layers.is_empty() {
            self.layers.push(Layer::of(self));
        }
        if other.layers.is_empty() {
            self.layers.push(Layer::of(other));
        } else {
            self.layers.extend(other.layers.iter().cloned());
        }
        merge_tables(&mut self.tree, &other.tree);
        self.file = format!("{} + {}", self.file, other.file);
        self.text = None;
        self.is_paper = false;
    }

    /// The folder of the scene file read, if it was read from a file (relative paths in
    /// it are relative to this folder).
    pub fn dir(&self) -> Option<&Path> {
        self.dir.as_deref()
    }

    /// The layer (of a merged scene) that gave `key`, the last one to give it.
    fn layer_of(&self, key: &str) -> Option<&Layer> {
        self.layers.iter().rev().find(|l| l.keys.contains(key))
    }

    /// The file that gave `key`: in a merged scene the last file to give it (the scene's
    /// name for a key set by an edit or not given at all), else the scene's name.
    pub fn file_of(&self, key: &str) -> &str {
        self.layer_of(key).map_or(&self.file, |l| &l.file)
    }

    /// The folder a relative path at `key` is relative to: that of the file that gave the
    /// key; None for a scene not read from a file and for a key set by an edit (the
    /// working directory).
    pub fn dir_of(&self, key: &str) -> Option<&Path> {
        if self.layers.is_empty() {
            return self.dir.as_deref();
        }
        self.layer_of(key).and_then(|l| l.dir.as_deref())
    }

    /// Reads `path`, or the embedded paper scene of `kind` when `path` is None.
    pub fn read_or_paper(path: Option<&std::path::Path>, kind: Kind) -> Result<Self, SceneError> {
        match path {
            Some(p) => Self::read(p),
            None => Ok(Self::paper(kind)),
        }
    }

    /// The name of the source in messages.
    pub fn file(&self) -> &str {
        &self.file
    }

    /// Whether this is an embedded paper scene, unedited.
    pub fn is_paper(&self) -> bool {
        self.is_paper
    }

    /// The tree of keys and values.
    pub fn tree(&self) -> &toml::Table {
        &self.tree
    }

    /// The scene's `title`, if it gives one.
    pub fn title(&self) -> Option<&str> {
        self.tree.get("title").and_then(|t| t.as_str())
    }

    /// The title of plots and tables: the scene's, else the file name.
    pub fn display_title(&self) -> String {
        self.title()
            .map(str::to_string)
            .unwrap_or_else(|| self.file.clone())
    }

    /// The line of the source text where `key` (`section.key`) is written, if known (in a
    /// merged scene, in the file that gave it: [`Self::file_of`]).
    pub fn line_of(&self, key: &str) -> Option<usize> {
        if !self.layers.is_empty() {
            return locate(self.layer_of(key)?.text.as_deref()?, key);
        }
        locate(self.text.as_deref()?, key)
    }

    /// The scene's kind: its `kind` key, else inferred (`delta_max`: asperity; a `[switch]`
    /// section: switch; a `[surface]` section: surface).
    pub fn kind(&self) -> Result<Kind, SceneError> {
        if let Some(v) = self.tree.get("kind") {
            return match v.as_str() {
                Some("asperity") => Ok(Kind::Asperity),
                Some("surface") => Ok(Kind::Surface),
                Some("switch") => Ok(Kind::Switch),
                _ => Err(SceneError::Field {
                    file: self.file.clone(),
                    key: "kind".into(),
                    value: v.to_string(),
                    line: String::new(),
                    allowed: keys::Domain::Choice(keys::KINDS).describe(),
                }),
            };
        }
        if self.tree.contains_key("delta_max") {
            Ok(Kind::Asperity)
        } else if self.tree.contains_key("switch") {
            Ok(Kind::Switch)
        } else if self.tree.contains_key("surface") {
            Ok(Kind::Surface)
        } else {
            Err(SceneError::Missing {
                file: self.file.clone(),
                key: "kind".into(),
                explanation: "the scene has no delta_max, [switch] or [surface]: say which it is with kind = \"asperity\" | \"surface\" | \"switch\"".into(),
            })
        }
    }

    /// Sets `key` (`section.key`, sections created as needed) to `value`. The value is
    /// checked when a spec is made, like a value of the file. An edited scene is no longer
    /// the paper's.
    pub fn set(&mut self, key: &str, value: toml::Value) -> Result<(), SceneError> {
        self.remember_files();
        let parts: Vec<&str> = key.split('.').collect();
        if parts.iter().any(|p| p.is_empty()) {
            return Err(SceneError::Parse {
                file: self.file.clone(),
                message: format!("`{key}` is not a key (section.key)"),
            });
        }
        let mut node = &mut self.tree;
        for part in &parts[..parts.len() - 1] {
            let entry = node
                .entry(part.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            node = match entry {
                toml::Value::Table(t) => t,
                other => {
                    return Err(SceneError::Parse {
                        file: self.file.clone(),
                        message: format!(
                            "`{part}` of `{key}` is {}, not a section",
                            other.type_str()
                        ),
                    })
                }
            };
        }
        node.insert(parts[parts.len() - 1].to_string(), value);
        self.edited(key);
        Ok(())
    }

    /// Sets a numeric key: an integer for a count key of the registry, a float otherwise
    /// (infinity included: a yield stress).
    pub fn set_number(&mut self, key: &str, value: f64) -> Result<(), SceneError> {
        let v = match keys::key(key).map(|k| k.domain) {
            Some(keys::Domain::Count { .. }) => {
                if value.fract() != 0.0 || value < 0.0 || value > i64::MAX as f64 {
                    return Err(SceneError::Field {
                        file: self.file.clone(),
                        key: key.into(),
                        value: keys::num(value),
                        line: String::new(),
                        allowed: "an integer".into(),
                    });
                }
                toml::Value::Integer(value as i64)
            }
            _ => toml::Value::Float(value),
        };
        self.set(key, v)
    }

    /// Sets `key` from text as a command line gives it (`--set contact.reload=bounded`): a
    /// TOML value (`1e-9`, `"bounded"`, `true`, `[1, 2, 3]`), or a bare word as a string.
    pub fn set_text(&mut self, key: &str, text: &str) -> Result<(), SceneError> {
        self.set(key, parse_value(text))
    }

    /// Removes `key` (`section.key`) if present.
    pub fn remove(&mut self, key: &str) {
        self.remember_files();
        let parts: Vec<&str> = key.split('.').collect();
        let mut node = &mut self.tree;
        for part in &parts[..parts.len() - 1] {
            match node.get_mut(*part) {
                Some(toml::Value::Table(t)) => node = t,
                _ => return,
            }
        }
        node.remove(parts[parts.len() - 1]);
        self.edited(key);
    }

    /// Before the first edit of a scene read from a file: which keys the file gave, so that
    /// an edited key is no longer the file's (a relative path set by an edit is relative
    /// to the working directory, not to the file's folder).
    fn remember_files(&mut self) {
        if self.layers.is_empty() && self.dir.is_some() {
            self.layers.push(Layer::of(self));
        }
    }

    /// After an edit of `key`: no longer the paper's, and the key (or section) no longer
    /// any file's: no line number for it (a scene read from a file keeps those of the keys
    /// the file still gives; one built from text alone keeps none).
    fn edited(&mut self, key: &str) {
        self.is_paper = false;
        self.text = None;
        let section = format!("{key}.");
        for l in &mut self.layers {
            l.keys.retain(|k| k != key && !k.starts_with(&section));
        }
    }

    /// The value of `key` (`section.key`), if present.
    pub fn get(&self, key: &str) -> Option<&toml::Value> {
        let mut node = &self.tree;
        let parts: Vec<&str> = key.split('.').collect();
        for part in &parts[..parts.len() - 1] {
            node = node.get(*part)?.as_table()?;
        }
        node.get(parts[parts.len() - 1])
    }
}

/// What an input path is when it is not a regular file ("a folder", "a FIFO", ...), None
/// for a regular file. Inputs are read from regular files only: a FIFO with no writer
/// would block the reader for ever, a device may never end.
pub fn not_regular(m: &std::fs::Metadata) -> Option<&'static str> {
    let t = m.file_type();
    if t.is_file() {
        return None;
    }
    if t.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO");
        }
        if t.is_char_device() {
            return Some("a character device");
        }
        if t.is_block_device() {
            return Some("a block device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("an unknown kind of file")
}

/// A parser's message with every line cut to 160 characters: a message quotes the line at
/// fault, which may be a 200 kB line of a broken file.
fn short_lines(message: &str) -> String {
    message
        .lines()
        .map(|l| {
            if l.chars().count() > 160 {
                let cut: String = l.chars().take(150).collect();
                format!("{cut}... ({} characters)", l.chars().count())
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A value as a command line gives it: TOML if it parses as one, else a string.
pub fn parse_value(text: &str) -> toml::Value {
    let doc = format!("v = {text}");
    match toml::from_str::<toml::Table>(&doc) {
        Ok(mut t) => t.remove("v").unwrap_or(toml::Value::String(text.into())),
        Err(_) => toml::Value::String(text.trim().to_string()),
    }
}

/// A JSON value read with every object's keys checked: a key given twice in one object is
/// an error naming it (`contact.radius`), where serde_json's own `Value` keeps the last.
/// The `&str` is where the value sits (`""` at the top).
struct NoDuplicates<'a>(&'a str);

impl<'de> serde::de::DeserializeSeed<'de> for NoDuplicates<'_> {
    type Value = serde_json::Value;

    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<serde_json::Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> serde::de::Visitor<'de> for NoDuplicates<'_> {
    type Value = serde_json::Value;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_bool<E: serde::de::Error>(self, v: bool) -> Result<serde_json::Value, E> {
        Ok(serde_json::Value::Bool(v))
    }

    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<serde_json::Value, E> {
        Ok(serde_json::Value::Number(v.into()))
    }

    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<serde_json::Value, E> {
        Ok(serde_json::Value::Number(v.into()))
    }

    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<serde_json::Value, E> {
        serde_json::Number::from_f64(v)
            .map(serde_json::Value::Number)
            .ok_or_else(|| E::custom(format!("`{}`: not a finite number", self.0)))
    }

    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<serde_json::Value, E> {
        Ok(serde_json::Value::String(v.to_owned()))
    }

    fn visit_string<E: serde::de::Error>(self, v: String) -> Result<serde_json::Value, E> {
        Ok(serde_json::Value::String(v))
    }

    fn visit_unit<E: serde::de::Error>(self) -> Result<serde_json::Value, E> {
        Ok(serde_json::Value::Null)
    }

    fn visit_none<E: serde::de::Error>(self) -> Result<serde_json::Value, E> {
        Ok(serde_json::Value::Null)
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(
        self,
        mut seq: A,
    ) -> Result<serde_json::Value, A::Error> {
        let mut items = Vec::new();
        loop {
            let at = format!("{}[{}]", self.0, items.len());
            match seq.next_element_seed(NoDuplicates(&at))? {
                Some(x) => items.push(x),
                None => return Ok(serde_json::Value::Array(items)),
            }
        }
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(
        self,
        mut map: A,
    ) -> Result<serde_json::Value, A::Error> {
        let mut object = serde_json::Map::new();
        while let Some(k) = map.next_key::<String>()? {
            let at = if self.0.is_empty() {
                k.clone()
            } else {
                format!("{}.{k}", self.0)
            };
            if object.contains_key(&k) {
                return Err(serde::de::Error::custom(format!(
                    "duplicate key `{at}`: give each key once"
                )));
            }
            let x = map.next_value_seed(NoDuplicates(&at))?;
            object.insert(k, x);
        }
        Ok(serde_json::Value::Object(object))
    }
}

fn json_to_toml(file: &str, at: &str, v: &serde_json::Value) -> Result<toml::Value, SceneError> {
    use serde_json::Value as J;
    Ok(match v {
        J::Null => {
            return Err(SceneError::Field {
                file: file.into(),
                key: if at.is_empty() {
                    "(top)".into()
                } else {
                    at.into()
                },
                value: "null".into(),
                line: String::new(),
                allowed: "a value (leave the key out for its default; write \"inf\" for infinity)"
                    .into(),
            })
        }
        J::Bool(b) => toml::Value::Boolean(*b),
        J::Number(n) => match n.as_i64() {
            Some(i) => toml::Value::Integer(i),
            None => toml::Value::Float(n.as_f64().unwrap_or(f64::NAN)),
        },
        J::String(s) => toml::Value::String(s.clone()),
        J::Array(a) => toml::Value::Array(
            a.iter()
                .enumerate()
                .map(|(i, x)| json_to_toml(file, &format!("{at}[{i}]"), x))
                .collect::<Result<_, _>>()?,
        ),
        J::Object(o) => {
            let mut t = toml::Table::new();
            for (k, x) in o {
                let key = if at.is_empty() {
                    k.clone()
                } else {
                    format!("{at}.{k}")
                };
                t.insert(k.clone(), json_to_toml(file, &key, x)?);
            }
            toml::Value::Table(t)
        }
    })
}

/// The 1-based line where `key` (`section.key`) is written in TOML `text`: the line
/// `leaf = ...` inside the section's `[section]` header (or at the top for top-level keys).
fn locate(text: &str, key: &str) -> Option<usize> {
    let (section, leaf) = match key.rsplit_once('.') {
        Some((s, l)) => (s, l),
        None => ("", key),
    };
    let leaf = leaf.split('[').next().unwrap_or(leaf);
    let mut current = String::new();
    for (i, line) in text.lines().enumerate() {
        let l = line.trim();
        if let Some(h) = l.strip_prefix('[') {
            current = h
                .split(']')
                .next()
                .unwrap_or("")
                .trim()
                .trim_matches('[')
                .to_string();
            continue;
        }
        if current == section {
            if let Some((k, _)) = l.split_once('=') {
                if k.trim() == leaf {
                    return Some(i + 1);
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_found_on_their_lines() {
        let t = "title = \"x\"\n[contact]\nradius = 1\n\n[switch]\nd0 = 2\nradius = 3\n";
        assert_eq!(locate(t, "title"), Some(1));
        assert_eq!(locate(t, "contact.radius"), Some(3));
        assert_eq!(locate(t, "switch.radius"), Some(7));
        assert_eq!(locate(t, "surface.sigma_s"), None);
    }

    #[test]
    fn values_from_a_command_line_are_toml_or_words() {
        assert_eq!(parse_value("1e-9"), toml::Value::Float(1e-9));
        assert_eq!(parse_value("10"), toml::Value::Integer(10));
        assert_eq!(
            parse_value("bounded"),
            toml::Value::String("bounded".into())
        );
        assert_eq!(
            parse_value("\"bounded\""),
            toml::Value::String("bounded".into())
        );
        assert_eq!(parse_value("true"), toml::Value::Boolean(true));
        assert_eq!(parse_value("inf"), toml::Value::Float(f64::INFINITY));
    }

    #[test]
    fn json_and_toml_scenes_are_the_same_tree() {
        let t = Scene::from_toml_str("t", "a = 1\n[b]\nc = \"x\"\nd = [1.5, 2.0]\n").unwrap();
        let j = Scene::from_json_str("j", r#"{"a": 1, "b": {"c": "x", "d": [1.5, 2.0]}}"#).unwrap();
        assert_eq!(t.tree(), j.tree());
        let e = Scene::from_json_str("j", r#"{"contact": {"radius": null}}"#).unwrap_err();
        assert!(e.to_string().contains("contact.radius"), "{e}");
    }

    #[test]
    fn a_json_key_given_twice_is_refused_naming_it() {
        let e = Scene::from_json_str(
            "j.json",
            r#"{"kind": "asperity", "contact": {"radius": 1e-6, "radius": 2e-6}}"#,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("j.json") && e.contains("duplicate key `contact.radius`"),
            "{e}"
        );
        let e = Scene::from_json_str("j.json", r#"{"cycles": 3, "cycles": 4}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("duplicate key `cycles`"), "{e}");
        // the same key in two objects is two keys
        let s = Scene::from_json_str(
            "j.json",
            r#"{"contact": {"radius": 1e-6}, "switch": {"radius": 2e-6}, "a": [{"x": 1}, {"x": 2}]}"#,
        )
        .unwrap();
        assert_eq!(s.get("switch.radius"), Some(&toml::Value::Float(2e-6)));
    }

    #[test]
    fn the_kind_is_given_or_inferred() {
        assert_eq!(Scene::paper(Kind::Switch).kind().unwrap(), Kind::Switch);
        assert_eq!(Scene::paper(Kind::Surface).kind().unwrap(), Kind::Surface);
        assert_eq!(Scene::paper(Kind::Asperity).kind().unwrap(), Kind::Asperity);
        let mut s = Scene::paper(Kind::Switch);
        s.set("kind", toml::Value::String("surface".into()))
            .unwrap();
        assert_eq!(s.kind().unwrap(), Kind::Surface);
        assert!(!s.is_paper());
    }
}
