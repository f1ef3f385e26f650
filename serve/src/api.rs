//! The routes: the page, and the JSON API it uses (docs/serve.md documents it for
//! scripts). Handlers are thin: the work is in [`crate::jobs`], [`crate::catalogue`],
//! [`crate::uploads`] and [`crate::store`].

use std::collections::HashMap;
use std::convert::Infallible;
use std::sync::Arc;

use axum::Json;
use axum::Router;
use axum::body::Bytes;
use axum::extract::rejection::{BytesRejection, JsonRejection};
use axum::extract::{DefaultBodyLimit, Path, Query, State};
use axum::http::{StatusCode, header};
use axum::response::sse::{Event, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use futures_util::stream::Stream;

use crate::error::ApiError;
use crate::guard::Guard;
use crate::job::{Job, JobRequest};
use crate::jobs::Jobs;
use crate::store::safe_join;

#[derive(Clone)]
pub struct AppState {
    pub jobs: Arc<Jobs>,
    pub token: String,
}

/// Every route, behind the guard.
pub fn router(state: AppState, guard: Guard, max_upload_bytes: u64) -> Router {
    let upload_limit = usize::try_from(max_upload_bytes).unwrap_or(usize::MAX);
    Router::new()
        .route("/", get(page))
        .route(
            "/assets/app.js",
            get(|| async {
                crate::page::asset(crate::page::APP_JS, "text/javascript; charset=utf-8")
            }),
        )
        .route(
            "/assets/app.css",
            get(|| async { crate::page::asset(crate::page::APP_CSS, "text/css; charset=utf-8") }),
        )
        .route(
            "/api/scenes",
            get(scenes)
                .post(upload)
                .layer(DefaultBodyLimit::max(upload_limit)),
        )
        .route("/api/jobs", get(list_jobs).post(submit))
        .route("/api/jobs/{id}", get(job).delete(cancel_or_delete))
        .route("/api/jobs/{id}/cancel", post(cancel))
        .route("/api/jobs/{id}/events", get(events))
        .route("/api/jobs/{id}/files/{*path}", get(file))
        .route("/api/jobs/{id}/values", get(values))
        .route("/api/jobs/{id}/pixel", get(pixel))
        .route("/api/estimate", get(estimate))
        .route("/api/gate", get(gate))
        .fallback(|| async {
            ApiError::not_found("no such page: the API is under /api (docs/serve.md)")
        })
        .layer(axum::middleware::from_fn_with_state(
            guard,
            crate::guard::guard,
        ))
        .layer(axum::middleware::map_response(crate::guard::no_framing))
        .with_state(state)
}

async fn page(State(state): State<AppState>) -> Response {
    crate::page::index(&state.token)
}

async fn scenes(State(state): State<AppState>) -> Response {
    let jobs = state.jobs;
    blocking(move || Ok(Json(jobs.catalogue().listing()))).await
}

/// Runs blocking work (file system, parsing) off the async threads.
async fn blocking<T: IntoResponse + Send + 'static>(
    work: impl FnOnce() -> Result<T, ApiError> + Send + 'static,
) -> Response {
    match tokio::task::spawn_blocking(work).await {
        Ok(Ok(value)) => value.into_response(),
        Ok(Err(e)) => e.into_response(),
        Err(_) => {
            ApiError::internal("internal error while answering; please report it").into_response()
        }
    }
}

async fn upload(
    State(state): State<AppState>,
    Query(query): Query<HashMap<String, String>>,
    body: Result<Bytes, BytesRejection>,
) -> Response {
    let body = match body {
        Ok(body) => body,
        Err(rejection) => {
            let status = rejection.status();
            let message = if status == StatusCode::PAYLOAD_TOO_LARGE {
                format!(
                    "the scene is larger than this server's upload limit of {} bytes (rtprof serve --max-upload-bytes)",
                    state.jobs.catalogue().max_upload_bytes()
                )
            } else {
                rejection.body_text()
            };
            return ApiError::new(status, message).into_response();
        }
    };
    let Some(name) = query.get("name").cloned() else {
        return ApiError::invalid("name the scene: POST /api/scenes?name=NAME").into_response();
    };
    let jobs = state.jobs;
    let response =
        blocking(move || crate::uploads::save(jobs.catalogue(), &name, &body).map(Json)).await;
    match response.status() {
        StatusCode::OK => (StatusCode::CREATED, response).into_response(),
        _ => response,
    }
}

async fn list_jobs(State(state): State<AppState>) -> Json<serde_json::Value> {
    let jobs: Vec<Job> = state.jobs.list().into_iter().map(Job::with_text).collect();
    Json(serde_json::json!({ "jobs": jobs }))
}

async fn submit(
    State(state): State<AppState>,
    request: Result<Json<JobRequest>, JsonRejection>,
) -> Response {
    let request = match request {
        Ok(Json(request)) => request,
        Err(rejection) => {
            return ApiError::new(rejection.status(), rejection.body_text()).into_response();
        }
    };
    let jobs = state.jobs;
    match blocking(move || jobs.submit(request).map(|j| Json(j.with_text()))).await {
        r if r.status() == StatusCode::OK => (StatusCode::ACCEPTED, r).into_response(),
        r => r,
    }
}

/// A job id of a path: a number (400 otherwise).
fn parse_id(text: &str) -> Result<u64, ApiError> {
    text.parse()
        .map_err(|_| ApiError::bad_request(format!("'{text}' is not a job id: ids are numbers")))
}

async fn job(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<Job>, ApiError> {
    Ok(Json(state.jobs.get(parse_id(&id)?)?.with_text()))
}

/// Cancels a queued or running job (202); 409 when it has ended.
async fn cancel(State(state): State<AppState>, Path(id): Path<String>) -> Response {
    match parse_id(&id).and_then(|id| state.jobs.cancel(id)) {
        Ok(job) => (StatusCode::ACCEPTED, Json(job.with_text())).into_response(),
        Err(e) => e.into_response(),
    }
}

/// A queued or running job is cancelled (202, as `POST .../cancel`); a finished one
/// is deleted with its directory (200).
async fn cancel_or_delete(State(state): State<AppState>, Path(id): Path<String>) -> Response {
    let jobs = state.jobs;
    blocking(move || {
        let id = parse_id(&id)?;
        if !jobs.get(id)?.status.is_final() {
            let job = jobs.cancel(id)?.with_text();
            return Ok((
                StatusCode::ACCEPTED,
                Json(serde_json::to_value(job).unwrap_or_default()),
            ));
        }
        jobs.delete(id)?;
        Ok((
            StatusCode::OK,
            Json(serde_json::json!({ "deleted": id.to_string() })),
        ))
    })
    .await
}

/// The figures of a finished job as the page shows them, each written by
/// `reports::format` (`reports::page_values`).
async fn values(State(state): State<AppState>, Path(id): Path<String>) -> Response {
    let jobs = state.jobs;
    blocking(move || {
        let id = parse_id(&id)?;
        let results = read_results(&jobs, id)?;
        Ok(Json(reports::page_values::run_values(&results)))
    })
    .await
}

/// One sample of a finished job's per-pixel maps: `?scene=N&x=X&y=Y` (the scene's
/// index in the run, the pixel of its image); every map's value there, written.
async fn pixel(
    State(state): State<AppState>,
    Path(id): Path<String>,
    Query(query): Query<HashMap<String, String>>,
) -> Response {
    let jobs = state.jobs;
    blocking(move || {
        let id = parse_id(&id)?;
        let number = |key: &str| {
            query
                .get(key)
                .and_then(|v| v.parse::<u32>().ok())
                .ok_or_else(|| {
                    ApiError::invalid(format!("give ?scene=N&x=X&y=Y (no number {key})"))
                })
        };
        let (scene, x, y) = (number("scene")?, number("x")?, number("y")?);
        let results = read_results(&jobs, id)?;
        let dir = jobs.store().job_dir(id);
        crate::pixel::at(&results, &dir, scene as usize, x, y).map(Json)
    })
    .await
}

/// What a job would cost before it runs: the scene's primitives and, for a brute-force
/// render of a big scene, `runner::estimate`'s time. `?scene=ID&width=W&height=H`
/// (`&threads=N`).
async fn estimate(
    State(state): State<AppState>,
    Query(query): Query<HashMap<String, String>>,
) -> Response {
    let jobs = state.jobs;
    blocking(move || crate::estimate::of_query(jobs.catalogue(), &query).map(Json)).await
}

/// A finished job's results.json, read and checked.
fn read_results(jobs: &Jobs, id: u64) -> Result<results::Results, ApiError> {
    jobs.get(id)?;
    let path = jobs.store().job_dir(id).join("results.json");
    if !path.is_file() {
        return Err(ApiError::invalid(format!(
            "job {id} has no results.json: only a finished job has figures"
        )));
    }
    results::Results::read_file(&path).map_err(|e| ApiError::invalid(e.to_string()))
}

/// The job's state now, at every change and every [`TICK`] while it runs (its clock
/// moves, and a page notices a lost server within a tick), as server-sent events named
/// `job`; the stream ends after a final status.
async fn events(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> Result<Sse<impl Stream<Item = Result<Event, Infallible>>>, ApiError> {
    let receiver = state.jobs.subscribe(parse_id(&id)?)?;
    let stream = futures_util::stream::unfold(
        (receiver, true, false),
        |(mut receiver, first, ended)| async move {
            if ended {
                return None;
            }
            if !first {
                // A change or a tick: either way the job is sent; a closed channel ends.
                if let Ok(Err(_)) = tokio::time::timeout(TICK, receiver.changed()).await {
                    return None;
                }
            }
            let job = receiver.borrow_and_update().clone().with_text();
            let data = serde_json::to_string(&job).unwrap_or_default();
            let event = Event::default().event("job").data(data);
            Some((Ok(event), (receiver, false, job.status.is_final())))
        },
    );
    Ok(Sse::new(stream).keep_alive(KeepAlive::default()))
}

/// How often a running job's event stream speaks without a change.
const TICK: std::time::Duration = std::time::Duration::from_secs(1);

/// The content type of a job's file, by its extension.
fn content_type(path: &std::path::Path) -> &'static str {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default()
    {
        "png" => "image/png",
        "svg" => "image/svg+xml",
        "html" => "text/html; charset=utf-8",
        "pdf" => "application/pdf",
        "json" => "application/json",
        "csv" => "text/csv; charset=utf-8",
        "md" | "txt" => "text/plain; charset=utf-8",
        "gz" => "application/gzip",
        _ => "application/octet-stream",
    }
}

async fn file(State(state): State<AppState>, Path((id, rel)): Path<(String, String)>) -> Response {
    let jobs = state.jobs;
    blocking(move || {
        let id = parse_id(&id)?;
        jobs.get(id)?;
        let path = safe_join(&jobs.store().job_dir(id), &rel)?;
        let bytes = std::fs::read(&path)
            .map_err(|e| ApiError::not_found(format!("cannot read '{rel}': {e}")))?;
        Ok((
            [
                (header::CONTENT_TYPE, content_type(&path)),
                (header::CACHE_CONTROL, "no-cache"),
                // Shown in the browser (report.pdf opens rather than downloads).
                (header::CONTENT_DISPOSITION, "inline"),
            ],
            bytes,
        ))
    })
    .await
}

/// The regression gate of job `new` against job `old` (both finished), as text and
/// JSON; 422 when the runs cannot be compared.
async fn gate(
    State(state): State<AppState>,
    Query(query): Query<HashMap<String, String>>,
) -> Response {
    let jobs = state.jobs;
    blocking(move || {
        let id = |key: &str| {
            query
                .get(key)
                .ok_or_else(|| ApiError::invalid(format!("give ?old=ID&new=ID (no {key})")))
                .and_then(|v| parse_id(v))
        };
        let (old, new) = (id("old")?, id("new")?);
        let (old_results, new_results) = (read_results(&jobs, old)?, read_results(&jobs, new)?);
        let options = results::gate::GateOptions::default();
        let report = results::gate::gate(&old_results, &new_results, options)
            .map_err(|e| ApiError::invalid(e.to_string()))?;
        Ok(Json(serde_json::json!({
            "old": old.to_string(),
            "new": new.to_string(),
            "passed": !report.failed(),
            "text": reports::gate_text::to_text(&report),
            "gate": report,
        })))
    })
    .await
}
