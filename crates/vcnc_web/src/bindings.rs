//! The wasm-bindgen surface of the engine (wasm32 only): each function
//! takes the program text as UTF-8 bytes (a `Uint8Array`: the page encodes
//! it with `TextEncoder`, a native copy, where a string parameter would be
//! converted by wasm-bindgen's JavaScript loop, a character at a time —
//! 7 % of a 1 M-block run) and the settings as a JS object
//! (`{dialect, file_name, machine, tools, tools_name, block_delete,
//! optional_stop}`, every key optional) and returns a JS object made by
//! serde-wasm-bindgen from the structs of `check.rs`, or throws a string
//! that says what is wrong with the settings.

use crate::Settings;
use serde::Serialize;
use std::borrow::Cow;
use wasm_bindgen::prelude::*;

fn settings(v: JsValue) -> Result<Settings, JsValue> {
    if v.is_undefined() || v.is_null() {
        return Ok(Settings::default());
    }
    serde_wasm_bindgen::from_value(v).map_err(|e| JsValue::from_str(&format!("settings: {e}")))
}

/// The text of `bytes` (as it is when it is UTF-8, as `TextEncoder`'s
/// always is; else with replacement characters).
fn utf8(bytes: &[u8]) -> Cow<'_, str> {
    String::from_utf8_lossy(bytes)
}

fn out<T: Serialize>(r: Result<T, String>) -> Result<JsValue, JsValue> {
    let v = r.map_err(|e| JsValue::from_str(&e))?;
    // Maps as plain objects, so `extents.min.x` reads as in JSON.
    let ser = serde_wasm_bindgen::Serializer::json_compatible();
    v.serialize(&ser)
        .map_err(|e| JsValue::from_str(&format!("result: {e}")))
}

/// Diagnostics, summary and (with `view`) the viewer's data of `text`.
#[wasm_bindgen]
pub fn check(text: &[u8], settings_js: JsValue, view: bool) -> Result<JsValue, JsValue> {
    out(crate::check(&utf8(text), &settings(settings_js)?, view))
}

/// The viewer page the app loads once and posts each plot to
/// (`vcnc_plot::write_viewer`).
#[wasm_bindgen]
pub fn viewer() -> String {
    crate::viewer()
}

/// The planned time and its split (`vcnc time`).
#[wasm_bindgen]
pub fn time(text: &[u8], settings_js: JsValue) -> Result<JsValue, JsValue> {
    out(crate::time(&utf8(text), &settings(settings_js)?))
}

/// The flattened program (`vcnc run --format gcode`).
#[wasm_bindgen]
pub fn flatten(text: &[u8], settings_js: JsValue) -> Result<JsValue, JsValue> {
    out(crate::flatten(&utf8(text), &settings(settings_js)?))
}

/// The events (`vcnc run --format jsonl`), as objects.
#[wasm_bindgen]
pub fn events(text: &[u8], settings_js: JsValue) -> Result<JsValue, JsValue> {
    out(crate::events(&utf8(text), &settings(settings_js)?))
}

/// Material removal on `stock` (`--stock`'s syntax; empty: the header
/// comment, else automatic): removed volume and collisions, and (with
/// `meshes`) the stock and the finished part for the viewer.
#[wasm_bindgen]
pub fn sim(
    text: &[u8],
    settings_js: JsValue,
    stock: Option<String>,
    meshes: bool,
) -> Result<JsValue, JsValue> {
    out(crate::sim(
        &utf8(text),
        &settings(settings_js)?,
        stock.as_deref(),
        meshes,
    ))
}

/// The dialect detection picks for `text`, with its evidence.
#[wasm_bindgen]
pub fn detect(text: &[u8], file_name: Option<String>) -> Result<JsValue, JsValue> {
    out(Ok(crate::detect(&utf8(text), file_name.as_deref())))
}

/// The dialect names besides auto.
#[wasm_bindgen]
pub fn dialects() -> Result<JsValue, JsValue> {
    out(Ok(crate::dialects()))
}

/// Panics, for the page's test of a worker that traps: a panic in wasm32
/// is a trap the worker cannot recover from, and the page must replace
/// the worker and say so (crates/vcnc/tests/web.rs).
#[wasm_bindgen]
pub fn trap_for_tests() {
    panic!("trap_for_tests: a deliberate panic");
}
