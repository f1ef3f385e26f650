//! What keeps other sites off the local server: every request must address it by a
//! local name (a page elsewhere that rebinds its own host name to 127.0.0.1 is
//! refused), and every state-changing request must carry this server's token, which
//! only a page it served (or a script reading `server.json`) knows, and come from no
//! other origin.

use axum::extract::{Request, State};
use axum::http::{Method, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use crate::error::ApiError;

/// The header that carries the token.
pub const TOKEN_HEADER: &str = "x-rtprof-token";

/// The guard's settings.
#[derive(Clone, Debug)]
pub struct Guard {
    pub token: String,
    /// Host names (without port) requests may address the server by; empty: any (an
    /// explicit `--bind` to a non-local address).
    pub hosts: Vec<String>,
}

/// A fresh random token: 128 bits from the operating system, in hex.
pub fn new_token() -> Result<String, String> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes).map_err(|e| format!("no random numbers for the token: {e}"))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// The host name of a `Host` header value (`127.0.0.1:8080`, `[::1]:80`, `localhost`).
fn host_name(value: &str) -> &str {
    if let Some(rest) = value.strip_prefix('[') {
        return rest.split(']').next().unwrap_or(rest);
    }
    value.rsplit_once(':').map_or(value, |(host, _)| host)
}

/// Whether the two strings are equal, in time independent of where they differ.
fn same(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

impl Guard {
    /// Checks one request: 403 when it is addressed to another host name, or changes
    /// state without the token or from another origin.
    pub fn check(&self, request: &Request) -> Result<(), ApiError> {
        let headers = request.headers();
        let host = headers
            .get(header::HOST)
            .and_then(|h| h.to_str().ok())
            .unwrap_or_default();
        if !self.hosts.is_empty() && !self.hosts.iter().any(|h| h == host_name(host)) {
            return Err(ApiError::forbidden(format!(
                "this server answers only requests to {}, not to '{host}'",
                self.hosts.join(" or ")
            )));
        }
        if matches!(*request.method(), Method::GET | Method::HEAD) {
            return Ok(());
        }
        if let Some(origin) = headers.get(header::ORIGIN) {
            let origin = origin.to_str().unwrap_or_default();
            let expected = format!("http://{host}");
            if origin != expected {
                return Err(ApiError::forbidden(format!(
                    "cross-site request from {origin} refused: only this server's own page may change its state"
                )));
            }
        }
        let token = headers
            .get(TOKEN_HEADER)
            .and_then(|t| t.to_str().ok())
            .unwrap_or_default();
        if !same(token, &self.token) {
            return Err(ApiError::forbidden(
                "missing or wrong X-Rtprof-Token header: the page sends it; scripts read it from server.json in the data directory",
            ));
        }
        Ok(())
    }
}

/// The middleware form of [`Guard::check`].
pub async fn guard(State(guard): State<Guard>, request: Request, next: Next) -> Response {
    match guard.check(&request) {
        Ok(()) => next.run(request).await,
        Err(e) => e.into_response(),
    }
}

/// The anti-framing headers of every answer: no other site may frame the page (a
/// click on Run or Delete through a transparent frame). The job's own files (its
/// flamegraphs, shown in the page with `<object>`) may be framed by this server's page
/// and by no one else.
pub async fn no_framing(uri: axum::http::Uri, mut response: Response) -> Response {
    let own_file = uri.path().starts_with("/api/jobs/") && uri.path().contains("/files/");
    let (frame_options, ancestors) = match own_file {
        true => ("SAMEORIGIN", "frame-ancestors 'self'"),
        false => ("DENY", "frame-ancestors 'none'"),
    };
    let headers = response.headers_mut();
    headers.insert(
        header::X_FRAME_OPTIONS,
        header::HeaderValue::from_static(frame_options),
    );
    headers.insert(
        header::CONTENT_SECURITY_POLICY,
        header::HeaderValue::from_static(ancestors),
    );
    response
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn host_names_are_read_without_the_port() {
        assert_eq!(host_name("127.0.0.1:8080"), "127.0.0.1");
        assert_eq!(host_name("[::1]:8080"), "::1");
        assert_eq!(host_name("localhost"), "localhost");
    }

    #[test]
    fn tokens_are_random_and_compared_whole() {
        let (a, b) = (new_token().unwrap(), new_token().unwrap());
        assert_eq!(a.len(), 32);
        assert_ne!(a, b);
        assert!(same(&a, &a.clone()));
        assert!(!same(&a, &b));
        assert!(!same(&a, &a[..31]));
    }
}
