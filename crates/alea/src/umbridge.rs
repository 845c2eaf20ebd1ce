//! The UM-Bridge protocol (version 1.0: HTTP + JSON, the protocol of the `umbridge` clients of
//! Python, C++, MATLAB, R and Julia): the requests `alea serve` answers and their JSON, apart
//! from the server that carries them (`serve.rs`).
//!
//! One model, named [`MODEL`]: its input one vector (the study's parameters), its output one
//! vector (the study's quantities). `GET /Info`, `POST /InputSizes`, `/OutputSizes`,
//! `/ModelInfo`, `/Evaluate`; `/Gradient`, `/ApplyJacobian` and `/ApplyHessian` answer
//! `UnsupportedFeature`. An error is `{"error": {"type": T, "message": M}}` with HTTP status
//! 400 (the request's fault) or 500 (the model's: a run that did not converge).

use serde_json::{Value, json};

/// The one model's name.
pub const MODEL: &str = "forward";

/// What a request asks for, once checked.
#[derive(Debug, PartialEq)]
pub enum Request {
    /// An answer that needs no evaluation: status and JSON body.
    Answer(u16, Value),
    /// Evaluate the model at one point (already of the input size).
    Evaluate(Vec<f64>),
}

/// The model's sizes.
#[derive(Clone, Copy, Debug)]
pub struct Sizes {
    /// The study's parameters.
    pub inputs: usize,
    /// The study's quantities.
    pub outputs: usize,
}

/// An error answer.
pub fn error(status: u16, kind: &str, message: &str) -> (u16, Value) {
    (
        status,
        json!({ "error": { "type": kind, "message": message } }),
    )
}

/// Reads a request: `method` and `path` of the HTTP request, `body` its bytes.
pub fn parse(method: &str, path: &str, body: &[u8], sizes: Sizes) -> Request {
    let answer = |(status, value): (u16, Value)| Request::Answer(status, value);
    if path == "/Info" {
        return if method == "GET" {
            Request::Answer(200, json!({ "protocolVersion": 1.0, "models": [MODEL] }))
        } else {
            answer(error(405, "InvalidInput", "/Info is a GET request"))
        };
    }
    let known = [
        "/InputSizes",
        "/OutputSizes",
        "/ModelInfo",
        "/Evaluate",
        "/Gradient",
        "/ApplyJacobian",
        "/ApplyHessian",
    ];
    if !known.contains(&path) {
        return answer(error(
            404,
            "InvalidInput",
            &format!(
                "no such request '{path}' (UM-Bridge 1.0: /Info, {})",
                known.join(", ")
            ),
        ));
    }
    if method != "POST" {
        return answer(error(
            405,
            "InvalidInput",
            &format!("{path} is a POST request"),
        ));
    }
    let body: Value = match serde_json::from_slice(body) {
        Ok(v) => v,
        Err(e) => {
            return answer(error(
                400,
                "InvalidInput",
                &format!("the body is not JSON: {e}"),
            ));
        }
    };
    match body.get("name").and_then(Value::as_str) {
        Some(MODEL) => {}
        Some(other) => {
            return answer(error(
                400,
                "ModelNotFound",
                &format!("model '{other}' not found; this server has one model, '{MODEL}'"),
            ));
        }
        None => {
            return answer(error(
                400,
                "InvalidInput",
                "the request has no string 'name'",
            ));
        }
    }
    if let Err(message) = check_config(&body) {
        return answer(error(400, "InvalidInput", &message));
    }
    match path {
        "/InputSizes" => Request::Answer(200, json!({ "inputSizes": [sizes.inputs] })),
        "/OutputSizes" => Request::Answer(200, json!({ "outputSizes": [sizes.outputs] })),
        "/ModelInfo" => Request::Answer(
            200,
            json!({ "support": {
                "Evaluate": true, "Gradient": false, "ApplyJacobian": false, "ApplyHessian": false
            } }),
        ),
        "/Evaluate" => match input_point(&body, sizes.inputs) {
            Ok(p) => Request::Evaluate(p),
            Err(message) => answer(error(400, "InvalidInput", &message)),
        },
        _ => answer(error(
            400,
            "UnsupportedFeature",
            &format!(
                "{} is not supported: the model has no derivatives",
                &path[1..]
            ),
        )),
    }
}

/// The model takes no configuration: `config` absent, or an empty object.
fn check_config(body: &Value) -> Result<(), String> {
    match body.get("config") {
        None | Some(Value::Null) => Ok(()),
        Some(Value::Object(map)) => match map.keys().next() {
            None => Ok(()),
            Some(key) => Err(format!(
                "unknown config key '{key}': the model takes no configuration (its settings are the study file's)"
            )),
        },
        Some(_) => Err("'config' must be a JSON object".into()),
    }
}

/// The one input vector of an `/Evaluate` request, of `n` finite numbers.
fn input_point(body: &Value, n: usize) -> Result<Vec<f64>, String> {
    let Some(Value::Array(vectors)) = body.get("input") else {
        return Err("'input' must be a list of input vectors".into());
    };
    let [Value::Array(values)] = vectors.as_slice() else {
        return Err(format!(
            "'input' holds {} vectors; the model has 1 input vector (its {n} parameters)",
            vectors.len()
        ));
    };
    if values.len() != n {
        return Err(format!(
            "input vector 0 has {} values; the model's input has {n} (its parameters)",
            values.len()
        ));
    }
    values
        .iter()
        .enumerate()
        .map(|(i, v)| {
            v.as_f64()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("input value {i} is {v}, not a finite number"))
        })
        .collect()
}

/// The answer to an evaluation: the quantities, or why there are none.
pub fn evaluated(values: &[f64]) -> (u16, Value) {
    (200, json!({ "output": [values] }))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIZES: Sizes = Sizes {
        inputs: 2,
        outputs: 3,
    };

    fn post(path: &str, body: &str) -> Request {
        parse("POST", path, body.as_bytes(), SIZES)
    }

    fn error_type(r: &Request) -> String {
        match r {
            Request::Answer(_, v) => v["error"]["type"].as_str().unwrap_or("").to_string(),
            Request::Evaluate(_) => String::new(),
        }
    }

    #[test]
    fn sizes_info_and_evaluate_follow_the_protocol() {
        assert_eq!(
            parse("GET", "/Info", b"", SIZES),
            Request::Answer(
                200,
                json!({ "protocolVersion": 1.0, "models": ["forward"] })
            )
        );
        assert_eq!(
            post("/InputSizes", r#"{"name": "forward", "config": {}}"#),
            Request::Answer(200, json!({ "inputSizes": [2] }))
        );
        assert_eq!(
            post("/OutputSizes", r#"{"name": "forward"}"#),
            Request::Answer(200, json!({ "outputSizes": [3] }))
        );
        assert_eq!(
            post(
                "/Evaluate",
                r#"{"name": "forward", "input": [[1.5, -2]], "config": {}}"#
            ),
            Request::Evaluate(vec![1.5, -2.0])
        );
    }

    #[test]
    fn bad_requests_are_errors_naming_their_cause() {
        let cases = [
            (
                "/Evaluate",
                r#"{"name": "other", "input": [[1, 2]]}"#,
                "ModelNotFound",
            ),
            (
                "/Evaluate",
                r#"{"name": "forward", "input": [[1, 2, 3]]}"#,
                "InvalidInput",
            ),
            (
                "/Evaluate",
                r#"{"name": "forward", "input": [[1], [2]]}"#,
                "InvalidInput",
            ),
            (
                "/Evaluate",
                r#"{"name": "forward", "input": [[1, "a"]]}"#,
                "InvalidInput",
            ),
            (
                "/Evaluate",
                r#"{"name": "forward", "input": [[1, null]]}"#,
                "InvalidInput",
            ),
            (
                "/Evaluate",
                r#"{"name": "forward", "input": [[1, 2]], "config": {"x": 1}}"#,
                "InvalidInput",
            ),
            (
                "/Evaluate",
                r#"{"name": "forward", "input": [[1, 2]"#,
                "InvalidInput",
            ),
            ("/Gradient", r#"{"name": "forward"}"#, "UnsupportedFeature"),
            (
                "/ApplyHessian",
                r#"{"name": "forward"}"#,
                "UnsupportedFeature",
            ),
            ("/Nothing", r#"{"name": "forward"}"#, "InvalidInput"),
        ];
        for (path, body, kind) in cases {
            assert_eq!(error_type(&post(path, body)), kind, "{path} {body}");
        }
        // A number too large for f64 is infinite after parsing: refused.
        assert_eq!(
            error_type(&post(
                "/Evaluate",
                r#"{"name": "forward", "input": [[1, 1e999]]}"#
            )),
            "InvalidInput"
        );
    }
}
