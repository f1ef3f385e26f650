//! The page: one HTML document (a compiled askama template carrying the token), its
//! script and its style sheet, all embedded in the binary: the page works offline.

use askama::Template;
use axum::http::{StatusCode, header};
use axum::response::{Html, IntoResponse, Response};

/// `templates/index.html`.
#[derive(Template)]
#[template(path = "index.html")]
pub struct Index<'a> {
    pub token: &'a str,
    pub version: &'a str,
}

/// The page's script.
pub const APP_JS: &str = include_str!("../assets/app.js");

/// The page's style sheet.
pub const APP_CSS: &str = include_str!("../assets/app.css");

/// The page with `token` in it.
pub fn index(token: &str) -> Response {
    let page = Index {
        token,
        version: env!("CARGO_PKG_VERSION"),
    };
    match page.render() {
        Ok(html) => Html(html).into_response(),
        Err(e) => (
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("cannot build the page: {e}"),
        )
            .into_response(),
    }
}

/// An embedded asset with its type.
pub fn asset(body: &'static str, content_type: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, content_type),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        body,
    )
        .into_response()
}
