//! The messages between ranks as bytes, in alea's one binary encoding (`alea_uq::bytes`:
//! little-endian `u64` and `f64`, counts before vectors and strings, every `f64` bit for bit):
//! four flat records - a job, a group of jobs, a result and the ranks' settings.

use std::sync::Arc;

use alea_latin::LocalState;
pub(crate) use alea_uq::bytes::{ByteReader as Reader, ByteWriter as Writer, BytesError};

use crate::solve::{RunJob, RunOutcome};
use crate::store::RunRecord;

/// A message that does not decode (a bug or a mismatched build on another rank).
pub(crate) type WireError = BytesError;

/// A job: its id, its point and its warm-start state (empty: cold start). Returns the bytes and
/// how many of them are the state.
pub(crate) fn encode_job(id: u64, job: &RunJob) -> (Vec<u8>, usize) {
    let mut w = Writer::default();
    w.u64(id).f64s_counted(&job.theta);
    let before = w.len();
    match &job.start {
        Some(s) => w.u64(1).f64s_counted(&s.to_vec()),
        None => w.u64(0),
    };
    let state = w.len() - before;
    (w.into_bytes(), state)
}

/// Decodes a job; `sizes` are the interface point counts of this rank's solver.
pub(crate) fn decode_job(buf: &[u8], sizes: &[usize]) -> Result<(u64, RunJob), WireError> {
    let mut r = Reader::new(buf);
    let id = r.u64()?;
    let theta = r.f64s_counted()?;
    let start = match r.u64()? {
        0 => None,
        _ => {
            let v = r.f64s_counted()?;
            Some(Arc::new(LocalState::from_slice(sizes, &v).ok_or_else(
                || {
                    BytesError(format!(
                        "a warm-start state of {} values does not fit this rank's interfaces",
                        v.len()
                    ))
                },
            )?))
        }
    };
    r.end()?;
    Ok((id, RunJob { theta, start }))
}

/// A group of jobs solved together (`RunContext::solve_batch`): their number, then each job
/// as [`encode_job`] writes it. Returns the bytes and how many of them are states.
pub(crate) fn encode_group(jobs: &[(u64, &RunJob)]) -> (Vec<u8>, usize) {
    let mut w = Writer::default();
    w.u64(jobs.len() as u64);
    let mut state = 0;
    for (id, job) in jobs {
        let (bytes, s) = encode_job(*id, job);
        w.bytes_counted(&bytes);
        state += s;
    }
    (w.into_bytes(), state)
}

/// Decodes a group of jobs: each job, or its id (when it can be read) and why it does not
/// decode.
#[allow(clippy::type_complexity)]
pub(crate) fn decode_group(
    buf: &[u8],
    sizes: &[usize],
) -> Result<Vec<Result<(u64, RunJob), (Option<u64>, WireError)>>, WireError> {
    let mut r = Reader::new(buf);
    let n = r.count(8)?;
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        let b = r.bytes_counted()?;
        out.push(decode_job(b, sizes).map_err(|e| (Reader::new(b).u64().ok(), e)));
    }
    r.end()?;
    Ok(out)
}

/// A result: the job id, then either the outcome or the error message of the failed run.
pub(crate) fn encode_result(id: u64, out: &Result<RunOutcome, String>) -> Vec<u8> {
    let mut w = Writer::default();
    w.u64(id);
    match out {
        Ok(o) => {
            let r = &o.rec;
            w.u64(1)
                .f64s_counted(&r.params)
                .str(&r.status)
                .u64(r.iterations as u64)
                .f64(r.residual)
                .f64(r.seconds)
                .f64s_counted(&r.qois)
                .f64s_counted(&r.history)
                .f64s_counted(&r.state)
                .f64s_counted(&o.fields)
                .f64(o.estimate_seconds);
            match &o.cre {
                Some(c) => w.u64(1).f64s_counted(c),
                None => w.u64(0),
            };
            match &r.slide {
                Some(s) => w.u64(1).str(&s.interface).f64(s.slip).f64(s.ratio),
                None => w.u64(0),
            };
        }
        Err(msg) => {
            w.u64(0).str(msg);
        }
    }
    w.into_bytes()
}

/// Decodes a result.
pub(crate) fn decode_result(buf: &[u8]) -> Result<(u64, Result<RunOutcome, String>), WireError> {
    let mut r = Reader::new(buf);
    let id = r.u64()?;
    let out = match r.u64()? {
        0 => Err(r.str()?),
        _ => {
            let mut rec = RunRecord {
                params: r.f64s_counted()?,
                status: r.str()?,
                iterations: r.u64()? as usize,
                residual: r.f64()?,
                seconds: r.f64()?,
                qois: r.f64s_counted()?,
                history: r.f64s_counted()?,
                state: r.f64s_counted()?,
                slide: None,
            };
            let fields = r.f64s_counted()?;
            let estimate_seconds = r.f64()?;
            let cre = match r.u64()? {
                0 => None,
                _ => Some(r.f64s_counted()?),
            };
            rec.slide = match r.u64()? {
                0 => None,
                _ => Some(crate::store::RunSlide {
                    interface: r.str()?,
                    slip: r.f64()?,
                    ratio: r.f64()?,
                }),
            };
            Ok(RunOutcome {
                rec,
                fields,
                cre,
                estimate_seconds,
            })
        }
    };
    r.end()?;
    Ok((id, out))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_and_jobs_round_trip_bit_for_bit() {
        let out = RunOutcome {
            rec: RunRecord {
                params: vec![0.1, -0.0, f64::MIN_POSITIVE / 3.0],
                status: "no equilibrium: \u{e9}".into(),
                iterations: 17,
                residual: f64::MAX,
                seconds: 0.25,
                qois: vec![f64::NAN, 1e300],
                history: vec![1.0, 0.5],
                state: vec![3.0; 12],
                slide: Some(crate::store::RunSlide {
                    interface: "G2".into(),
                    slip: 0.25,
                    ratio: 0.75,
                }),
            },
            fields: (0..100).map(|i| (i as f64).sin()).collect(),
            cre: Some(vec![1.5, 2.5]),
            estimate_seconds: 0.125,
        };
        let b = encode_result(9, &Ok(out.clone()));
        let (id, back) = decode_result(&b).unwrap();
        assert_eq!(id, 9);
        let back = back.unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back.rec.params), bits(&out.rec.params));
        assert_eq!(bits(&back.rec.qois), bits(&out.rec.qois));
        assert_eq!(back.rec.status, out.rec.status);
        assert_eq!(back.fields, out.fields);
        assert_eq!(back.cre, out.cre);
        assert_eq!(back.rec.slide, out.rec.slide);
        let (id, e) = decode_result(&encode_result(3, &Err("boom".into()))).unwrap();
        assert_eq!((id, e.unwrap_err()), (3, "boom".to_string()));
        // A truncated message is an error, never a panic.
        for cut in [0, 5, 8, 40, b.len() - 1] {
            assert!(decode_result(&b[..cut]).is_err());
        }
        let sizes = [1usize];
        let state = LocalState::from_slice(&sizes, &[0.5; 12]).unwrap();
        let job = RunJob {
            theta: vec![1.0, 2.0],
            start: Some(Arc::new(state.clone())),
        };
        let (b, state_bytes) = encode_job(4, &job);
        assert_eq!(state_bytes, 8 + 8 + 12 * 8);
        let (id, back) = decode_job(&b, &sizes).unwrap();
        assert_eq!(id, 4);
        assert_eq!(back.theta, job.theta);
        assert_eq!(back.start.as_deref(), Some(&state));
        assert!(decode_job(&b, &[2]).is_err());
        let cold = RunJob {
            theta: vec![3.0],
            start: None,
        };
        let (g, gs) = encode_group(&[(7, &job), (8, &cold)]);
        assert_eq!(gs, state_bytes + 8);
        let back = decode_group(&g, &sizes).unwrap();
        assert_eq!(back.len(), 2);
        let (i7, j7) = back[0].as_ref().unwrap();
        assert_eq!((*i7, j7.start.as_deref()), (7, Some(&state)));
        let (i8, j8) = back[1].as_ref().unwrap();
        assert_eq!(
            (*i8, j8.theta.clone(), j8.start.is_none()),
            (8, vec![3.0], true)
        );
        let bad = decode_group(&g, &[2]).unwrap();
        assert!(matches!(bad[0], Err((Some(7), _))) && bad[1].is_ok());
        for cut in [0, 7, 20, g.len() - 1] {
            assert!(decode_group(&g[..cut], &sizes).is_err());
        }
    }
}
