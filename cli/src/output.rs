//! Printing to stdout. A closed pipe (`meshloom stats x.off | head -1`)
//! ends the output quietly instead of panicking.

use std::io::Write;

use crate::Failure;

/// Print `text` as it is.
pub fn print(text: &str) -> Result<(), Failure> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(Failure::input(format!("cannot write to stdout: {e}")))
        }
        _ => Ok(()),
    }
}

/// Print `value` as JSON on one line (JSON Lines, as the commands that take
/// several files print one object per file).
pub fn json(value: &serde_json::Value) -> Result<(), Failure> {
    let text = serde_json::to_string(value)
        .map_err(|e| Failure::input(format!("cannot encode JSON: {e}")))?;
    print(&format!("{text}\n"))
}

/// `value` as a JSON value; our report types always serialize.
pub fn to_json<T: serde::Serialize>(value: &T) -> Result<serde_json::Value, Failure> {
    serde_json::to_value(value).map_err(|e| Failure::input(format!("cannot encode JSON: {e}")))
}
