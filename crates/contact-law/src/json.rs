//! JSON paths and the no-null rule of the law file, shared by the reader (`format`) and
//! the law's scene echo (`law`) without either importing the other.

use crate::error::LawError;
use serde_json::Value;

/// `path.key` (or `key` at the root).
pub(crate) fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// Rejects `null` anywhere inside `v` (the format omits absent values instead).
pub(crate) fn check_no_null(v: &Value, path: &str) -> Result<(), LawError> {
    match v {
        Value::Null => Err(LawError::format(
            path,
            "null is not allowed (omit absent values)",
        )),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .try_for_each(|(i, x)| check_no_null(x, &format!("{path}[{i}]"))),
        Value::Object(m) => m
            .iter()
            .try_for_each(|(k, x)| check_no_null(x, &join(path, k))),
        _ => Ok(()),
    }
}
