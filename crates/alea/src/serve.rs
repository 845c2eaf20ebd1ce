//! `alea serve`: a study's model over the UM-Bridge protocol (`umbridge.rs`), each evaluation a
//! run of the study (`alea_study::model_session`).
//!
//! Threads: one **model thread** owns the study and its session (store, solver); **HTTP
//! threads** read requests, answer those that need no evaluation themselves, and hand each
//! evaluation to the model thread with a channel for its answer. The model thread takes every
//! evaluation queued when it is free and solves them together (one `evaluate` call: warm starts
//! from the nearest finished runs, groups sharing their solves), so concurrent clients are
//! batched without waiting for one another. A request's body is read up to [`MAX_BODY`]; a
//! malformed request, a dropped connection or a failed run is an answer (or nothing), never
//! the end of the server. Ctrl-C or SIGTERM: no new run starts, the runs under way finish and
//! are committed, and the server ends.

use std::io::Read;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, mpsc};
use std::time::{Duration, Instant};

use alea_study::model_session::{ModelSession, PointAnswer};
use alea_study::runner::Progress;
use alea_study::study::Study;
use anyhow::{Context, Result, anyhow};
use serde_json::Value;

use crate::out::{errln, outln};
use crate::umbridge::{self, Request, Sizes};

/// The largest request body read (a point is a few hundred bytes).
const MAX_BODY: usize = 1 << 20;

/// HTTP threads: the most evaluations solved together.
const HTTP_THREADS: usize = 16;

/// One evaluation handed to the model thread.
struct Job {
    point: Vec<f64>,
    reply: mpsc::Sender<(u16, Value)>,
}

/// Where to serve and what.
pub struct ServeOptions<'a> {
    /// The study file.
    pub study: &'a Path,
    /// The study directory (its store holds every evaluation).
    pub dir: &'a Path,
    /// Discard the runs of a previous version of the study file.
    pub restart: bool,
    /// Address to listen on.
    pub host: &'a str,
    /// Port (0: any free port, printed).
    pub port: u16,
}

/// The model thread's view of a stop request (Ctrl-C, SIGTERM).
struct Stop(Arc<AtomicBool>);

impl Progress for Stop {
    fn note(&self, message: &str) {
        errln!("note: {message}");
    }
    fn stop_requested(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}

/// Runs the server until Ctrl-C or SIGTERM.
pub fn serve(opts: &ServeOptions<'_>) -> Result<()> {
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = stop.clone();
        ctrlc::set_handler(move || stop.store(true, Ordering::SeqCst))
            .context("installing the Ctrl-C / SIGTERM handler")?;
    }
    let (jobs_tx, jobs_rx) = mpsc::channel::<Job>();
    let (ready_tx, ready_rx) = mpsc::channel::<Result<(Sizes, String, usize), String>>();
    let model = {
        let (study, dir, restart, stop) = (
            opts.study.to_path_buf(),
            opts.dir.to_path_buf(),
            opts.restart,
            stop.clone(),
        );
        std::thread::spawn(move || model_thread(&study, &dir, restart, stop, ready_tx, jobs_rx))
    };
    let (sizes, description, stored) = match ready_rx.recv() {
        Ok(Ok(ready)) => ready,
        Ok(Err(e)) => return Err(anyhow!(e)),
        Err(_) => return Err(anyhow!("the model thread ended before it was ready")),
    };
    let server = tiny_http::Server::http((opts.host, opts.port))
        .map_err(|e| anyhow!("listening on {}:{}: {e}", opts.host, opts.port))?;
    let addr = server
        .server_addr()
        .to_ip()
        .map_or_else(|| format!("{}:{}", opts.host, opts.port), |a| a.to_string());
    outln!(
        "serving {description} as UM-Bridge model '{}' at http://{addr} ({stored} runs in {}); Ctrl-C to stop",
        umbridge::MODEL,
        opts.dir.display()
    );
    let server = Arc::new(server);
    let answered = Arc::new(AtomicUsize::new(0));
    let busy_us = Arc::new(AtomicUsize::new(0));
    let http: Vec<_> = (0..HTTP_THREADS)
        .map(|_| {
            let (server, jobs, stop, answered, busy_us) = (
                server.clone(),
                jobs_tx.clone(),
                stop.clone(),
                answered.clone(),
                busy_us.clone(),
            );
            std::thread::spawn(move || {
                http_thread(&server, &jobs, &stop, &answered, &busy_us, sizes)
            })
        })
        .collect();
    drop(jobs_tx);
    for h in http {
        let _ = h.join();
    }
    let stored = model
        .join()
        .map_err(|_| anyhow!("the model thread panicked"))??;
    let n = answered.load(Ordering::SeqCst);
    outln!(
        "stopped: {n} requests answered (in the server {:.3} ms each on average, from the request read to the answer sent, solves included), {stored} runs in {}",
        busy_us.load(Ordering::SeqCst) as f64 / 1e3 / n.max(1) as f64,
        opts.dir.display()
    );
    Ok(())
}

/// Reads requests until a stop is requested.
fn http_thread(
    server: &tiny_http::Server,
    jobs: &mpsc::Sender<Job>,
    stop: &AtomicBool,
    answered: &AtomicUsize,
    busy_us: &AtomicUsize,
    sizes: Sizes,
) {
    while !stop.load(Ordering::SeqCst) {
        let mut request = match server.recv_timeout(Duration::from_millis(200)) {
            Ok(Some(r)) => r,
            Ok(None) => continue,
            Err(_) => break,
        };
        let t0 = Instant::now();
        let (status, body) = answer(&mut request, jobs, sizes);
        let response = tiny_http::Response::from_string(body.to_string())
            .with_status_code(status)
            .with_header(
                tiny_http::Header::from_bytes("Content-Type", "application/json")
                    .expect("a valid header"),
            );
        // A client that dropped the connection gets nothing; the server goes on.
        let _ = request.respond(response);
        answered.fetch_add(1, Ordering::SeqCst);
        busy_us.fetch_add(t0.elapsed().as_micros() as usize, Ordering::SeqCst);
    }
}

/// The answer to one request.
fn answer(
    request: &mut tiny_http::Request,
    jobs: &mpsc::Sender<Job>,
    sizes: Sizes,
) -> (u16, Value) {
    if request.body_length().is_some_and(|n| n > MAX_BODY) {
        return umbridge::error(
            413,
            "InvalidInput",
            &format!("the body exceeds {MAX_BODY} bytes"),
        );
    }
    let mut body = Vec::new();
    let read = request
        .as_reader()
        .take(MAX_BODY as u64 + 1)
        .read_to_end(&mut body);
    if read.is_err() {
        return umbridge::error(400, "InvalidInput", "the body could not be read");
    }
    if body.len() > MAX_BODY {
        return umbridge::error(
            413,
            "InvalidInput",
            &format!("the body exceeds {MAX_BODY} bytes"),
        );
    }
    let method = request.method().as_str().to_string();
    let path = request.url().split('?').next().unwrap_or("").to_string();
    match umbridge::parse(&method, &path, &body, sizes) {
        Request::Answer(status, value) => (status, value),
        Request::Evaluate(point) => {
            let (reply, rx) = mpsc::channel();
            if jobs.send(Job { point, reply }).is_err() {
                return umbridge::error(503, "InvalidInput", "the server is stopping");
            }
            rx.recv()
                .unwrap_or_else(|_| umbridge::error(503, "InvalidInput", "the server is stopping"))
        }
    }
}

/// Owns the study and its session; answers the queued evaluations together. Returns the runs
/// in the store at the end.
fn model_thread(
    study: &Path,
    dir: &Path,
    restart: bool,
    stop: Arc<AtomicBool>,
    ready: mpsc::Sender<Result<(Sizes, String, usize), String>>,
    jobs: mpsc::Receiver<Job>,
) -> Result<usize> {
    let progress = Stop(stop.clone());
    let study = match Study::load(study) {
        Ok(s) => s,
        Err(e) => {
            let _ = ready.send(Err(e.to_string()));
            return Err(anyhow!(e.to_string()));
        }
    };
    let command = format!("alea serve {}", study.source.path.display());
    let mut session = match ModelSession::open(&study, dir, restart, &command, &progress) {
        Ok(s) => s,
        Err(e) => {
            let _ = ready.send(Err(e.to_string()));
            return Err(anyhow!(e.to_string()));
        }
    };
    let sizes = Sizes {
        inputs: session.input_size(),
        outputs: session.output_size(),
    };
    let description = format!(
        "'{}' (inputs: {}; outputs: {})",
        study.title(),
        study.params.names.join(", "),
        study
            .qois
            .iter()
            .map(|q| q.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = ready.send(Ok((sizes, description, session.stored_runs())));
    while !stop.load(Ordering::SeqCst) {
        let first = match jobs.recv_timeout(Duration::from_millis(200)) {
            Ok(job) => job,
            Err(mpsc::RecvTimeoutError::Timeout) => continue,
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        };
        let mut batch = vec![first];
        batch.extend(jobs.try_iter());
        evaluate_batch(&mut session, batch);
    }
    Ok(session.stored_runs())
}

/// Evaluates a batch of jobs together and answers each.
fn evaluate_batch(session: &mut ModelSession<'_>, batch: Vec<Job>) {
    let t0 = Instant::now();
    let points: Vec<Vec<f64>> = batch.iter().map(|j| j.point.clone()).collect();
    let before = session.stored_runs();
    match session.evaluate(&points) {
        Ok(answers) => {
            errln!(
                "evaluated {} point(s), {} solved, in {:.2} s",
                points.len(),
                session.stored_runs() - before,
                t0.elapsed().as_secs_f64()
            );
            for (job, a) in batch.into_iter().zip(answers) {
                let _ = job.reply.send(point_answer(&a));
            }
        }
        Err(e) => {
            let message = e.to_string();
            for job in batch {
                let _ = job
                    .reply
                    .send(umbridge::error(500, "ModelFailed", &message));
            }
        }
    }
}

/// One point's answer as UM-Bridge JSON.
fn point_answer(a: &PointAnswer) -> (u16, Value) {
    match a {
        PointAnswer::Values(v) => umbridge::evaluated(v),
        PointAnswer::Invalid(why) => umbridge::error(400, "InvalidInput", why),
        PointAnswer::Failed {
            status,
            residual,
            iterations,
        } => umbridge::error(
            500,
            "ModelFailed",
            &format!(
                "the run did not give an answer: {status} (last residual {residual:.3e} after {iterations} LATIN iterations; stored, asked again it is answered the same)"
            ),
        ),
    }
}
