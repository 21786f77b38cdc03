//! `file:` URIs and paths, both ways: the client names documents by URI,
//! while subprograms, the machine file and the program directory are
//! paths. Only `file:` URIs have a path; an `untitled:` buffer has none,
//! and then calls find only the programs of the document itself.
//!
//! Percent-decoding and -encoding follow RFC 3986: every byte outside the
//! unreserved characters and `/` is written `%XX`.

use lsp_types::Uri;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// The local path of a `file:` URI.
pub fn to_path(uri: &Uri) -> Option<PathBuf> {
    let s = uri.as_str();
    let rest = s
        .strip_prefix("file://")
        .or_else(|| s.strip_prefix("FILE://"))?;
    // `file:///p` (empty authority) or `file://localhost/p`.
    let path = match rest.find('/') {
        Some(0) => rest,
        Some(i) if rest[..i].eq_ignore_ascii_case("localhost") => &rest[i..],
        _ => return None,
    };
    let path = path.split(['?', '#']).next().unwrap_or_default();
    let bytes = percent_decode(path)?;
    let text = String::from_utf8(bytes).ok()?;
    // Windows: `/C:/dir/x.nc` is `C:/dir/x.nc`.
    let text = match text.as_bytes() {
        [b'/', d, b':', ..] if d.is_ascii_alphabetic() && cfg!(windows) => text[1..].to_string(),
        _ => text,
    };
    Some(PathBuf::from(text))
}

/// The `file:` URI of an absolute path.
pub fn from_path(path: &Path) -> Option<Uri> {
    let text = path.to_str()?.replace('\\', "/");
    let mut out = String::from("file://");
    if !text.starts_with('/') {
        out.push('/');
    }
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/:".contains(&b) {
            out.push(char::from(b));
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    Uri::from_str(&out).ok()
}

fn percent_decode(s: &str) -> Option<Vec<u8>> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while let Some(&c) = b.get(i) {
        if c == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(c);
            i += 1;
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_uris_round_trip_with_escapes() {
        let uri = Uri::from_str("file:///home/cnc/my%20parts/O0100.nc").unwrap();
        let path = to_path(&uri).unwrap();
        assert_eq!(path, PathBuf::from("/home/cnc/my parts/O0100.nc"));
        assert_eq!(from_path(&path).unwrap().as_str(), uri.as_str());
        let untitled = Uri::from_str("untitled:Untitled-1").unwrap();
        assert_eq!(to_path(&untitled), None);
        let host = Uri::from_str("file://localhost/tmp/a.ngc").unwrap();
        assert_eq!(to_path(&host), Some(PathBuf::from("/tmp/a.ngc")));
    }
}
