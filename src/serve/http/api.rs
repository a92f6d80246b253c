//! The online page's requests decoded into plain values, without a socket: the method, the
//! path, the query and the body in, a [`Call`] — or the refusal — out. The fuzz target
//! `http_decode` feeds it arbitrary requests.

use serde::Deserialize;

use crate::serve::online::error::OnlineError;
use crate::serve::online::timeline::MOST_SECONDS;
use crate::serve::request::{Control, Format};

/// What a request asks for.
#[derive(Debug, Clone, PartialEq)]
pub enum Call {
    /// The page itself.
    Page,
    Cpu,
    Mode(Control),
    /// Operands, each with its format (`None`: the program's own notation).
    Values(Vec<(String, Option<Format>)>),
    Modify {
        operand: String,
        value: toml::Value,
    },
    Force {
        operand: String,
        value: toml::Value,
    },
    /// The force of one operand ends, or (`None`) every force.
    Unforce(Option<String>),
    Forces,
    /// Program status of a block (on the level of an OB).
    Status {
        block: String,
        level: Option<String>,
    },
    Diagnostics,
    /// A snapshot of the whole CPU (the file `--from` continues from).
    Snapshot,
    /// The last seconds of the timeline.
    Timeline(f64),
    /// The WebSocket of the live view.
    Live,
    /// A debugger's Debug Adapter Protocol request (`awl dap` attached).
    Debug(Vec<u8>),
    /// The debugger's events since it last asked.
    DebugEvents,
}

impl Call {
    /// Whether it changes the CPU: refused when the server is read-only.
    pub fn changes(&self) -> bool {
        matches!(
            self,
            Call::Mode(_)
                | Call::Modify { .. }
                | Call::Force { .. }
                | Call::Unforce(_)
                | Call::Debug(_)
        )
    }
}

/// A path, the methods it takes, and an example of its body or query for the help.
struct Route {
    path: &'static str,
    methods: &'static str,
    example: &'static str,
}

const ROUTES: [Route; 14] = [
    Route {
        path: "/",
        methods: "GET",
        example: "",
    },
    Route {
        path: "/api/cpu",
        methods: "GET",
        example: "",
    },
    Route {
        path: "/api/mode",
        methods: "POST",
        example: r#"{"mode": "stop"}"#,
    },
    Route {
        path: "/api/values",
        methods: "GET",
        example: "/api/values?operands=MW%2010,Q%204.0&formats=HEX,",
    },
    Route {
        path: "/api/modify",
        methods: "POST",
        example: r#"{"operand": "MW 10", "value": 42}"#,
    },
    Route {
        path: "/api/force",
        methods: "POST or DELETE",
        example: r#"{"operand": "I 0.0", "value": 1}; DELETE /api/force?operand=I%200.0"#,
    },
    Route {
        path: "/api/forces",
        methods: "GET",
        example: "",
    },
    Route {
        path: "/api/status",
        methods: "GET",
        example: "/api/status?block=OB%201 (or &level=OB%2035: its invocation on that level)",
    },
    Route {
        path: "/api/diagnostics",
        methods: "GET",
        example: "",
    },
    Route {
        path: "/api/snapshot",
        methods: "POST",
        example: "",
    },
    Route {
        path: "/api/timeline",
        methods: "GET",
        example: "/api/timeline?seconds=5",
    },
    Route {
        path: "/api/debug",
        methods: "POST",
        example: r#"{"seq": 1, "type": "request", "command": "attach", "arguments": {}}"#,
    },
    Route {
        path: "/api/debug/events",
        methods: "GET",
        example: "",
    },
    Route {
        path: "/api/live",
        methods: "GET (a WebSocket)",
        example: r#"{"subscribe": {"cpu": true, "values": [{"operand": "MW 10", "format": "HEX"}]}}"#,
    },
];

/// How many seconds the timeline shows without `seconds`.
const TIMELINE_SECONDS: f64 = 5.0;

/// Decodes one request; `query` is the part after `?`, undecoded.
pub fn decode(
    method: &str,
    path: &str,
    query: Option<&str>,
    body: &[u8],
) -> Result<Call, OnlineError> {
    let Some(route) = ROUTES.iter().find(|route| route.path == path) else {
        return Err(OnlineError::NoSuchPath {
            path: path.to_string(),
        });
    };
    let query = Query::parse(query.unwrap_or(""));
    match (route.path, method) {
        ("/", "GET") => Ok(Call::Page),
        ("/api/cpu", "GET") => Ok(Call::Cpu),
        ("/api/mode", "POST") => mode(route, body),
        ("/api/values", "GET") => values(route, &query),
        ("/api/modify", "POST") => {
            let Change { operand, value } = json(route, body)?;
            let value = value.into_toml()?;
            Ok(Call::Modify { operand, value })
        }
        ("/api/force", "POST") => {
            let Change { operand, value } = json(route, body)?;
            let value = value.into_toml()?;
            Ok(Call::Force { operand, value })
        }
        ("/api/force", "DELETE") => match query.get("operand").map(str::trim) {
            None => Ok(Call::Unforce(None)),
            Some("") => Err(missing(route, "operand")),
            Some(operand) => Ok(Call::Unforce(Some(operand.to_string()))),
        },
        ("/api/forces", "GET") => Ok(Call::Forces),
        ("/api/status", "GET") => {
            let block = query.get("block").map(str::trim).unwrap_or("");
            if block.is_empty() {
                return Err(missing(route, "block"));
            }
            let level = query
                .get("level")
                .map(str::trim)
                .filter(|level| !level.is_empty());
            Ok(Call::Status {
                block: block.to_string(),
                level: level.map(str::to_string),
            })
        }
        ("/api/diagnostics", "GET") => Ok(Call::Diagnostics),
        ("/api/snapshot", "POST") => Ok(Call::Snapshot),
        ("/api/timeline", "GET") => match query.get("seconds").map(str::trim) {
            None | Some("") => Ok(Call::Timeline(TIMELINE_SECONDS)),
            Some(text) => match text.parse::<f64>() {
                Ok(seconds) if seconds > 0.0 && seconds <= MOST_SECONDS => {
                    Ok(Call::Timeline(seconds))
                }
                _ => Err(OnlineError::Seconds {
                    text: text.to_string(),
                }),
            },
        },
        ("/api/live", "GET") => Ok(Call::Live),
        ("/api/debug", "POST") => Ok(Call::Debug(body.to_vec())),
        ("/api/debug/events", "GET") => Ok(Call::DebugEvents),
        _ => Err(OnlineError::Method {
            method: method.to_string(),
            path: route.path,
            allowed: route.methods,
        }),
    }
}

fn missing(route: &Route, name: &'static str) -> OnlineError {
    OnlineError::Missing {
        path: route.path,
        name,
        example: route.example,
    }
}

/// A query's parameters, percent-decoded.
struct Query(Vec<(String, String)>);

impl Query {
    fn parse(query: &str) -> Query {
        Query(
            form_urlencoded::parse(query.as_bytes())
                .into_owned()
                .collect(),
        )
    }

    fn get(&self, name: &str) -> Option<&str> {
        self.0
            .iter()
            .find(|(key, _)| key == name)
            .map(|(_, value)| value.as_str())
    }
}

/// A body as the route's JSON.
fn json<'a, T: Deserialize<'a>>(route: &Route, body: &'a [u8]) -> Result<T, OnlineError> {
    serde_json::from_slice(body).map_err(|error| OnlineError::BadJson {
        path: route.path,
        reason: error.to_string(),
        example: route.example,
    })
}

#[derive(Deserialize)]
struct ModeBody {
    mode: String,
}

fn mode(route: &Route, body: &[u8]) -> Result<Call, OnlineError> {
    let ModeBody { mode } = json(route, body)?;
    let command = match mode.trim().to_ascii_lowercase().as_str() {
        "stop" => Control::Stop,
        "warm" => Control::HotStart,
        "cold" => Control::ColdStart,
        _ => return Err(OnlineError::UnknownMode { mode }),
    };
    Ok(Call::Mode(command))
}

/// `operands=MW 10,Q 4.0&formats=HEX,`: the formats a parallel list, empty ones the default.
fn values(route: &Route, query: &Query) -> Result<Call, OnlineError> {
    let operands = query
        .get("operands")
        .ok_or_else(|| missing(route, "operands"))?;
    let mut formats = query.get("formats").unwrap_or("").split(',');
    operands
        .split(',')
        .map(str::trim)
        .filter(|operand| !operand.is_empty())
        .map(|operand| Ok((operand.to_string(), format(formats.next().unwrap_or(""))?)))
        .collect::<Result<_, _>>()
        .map(Call::Values)
}

/// A modify's or force's body.
#[derive(Deserialize)]
struct Change {
    operand: String,
    value: Written,
}

/// A value as JSON gives it: a number, true or false, or text as a scenario's `set` takes it.
#[derive(Deserialize)]
#[serde(untagged)]
enum Written {
    Integer(i64),
    Real(f64),
    Bool(bool),
    Text(String),
}

impl Written {
    fn into_toml(self) -> Result<toml::Value, OnlineError> {
        match self {
            Written::Integer(number) => Ok(toml::Value::Integer(number)),
            Written::Real(real) => Ok(toml::Value::Float(real)),
            Written::Bool(flag) => Ok(toml::Value::Boolean(flag)),
            Written::Text(text) => scenario_value(&text).ok_or(OnlineError::Value { text }),
        }
    }
}

/// `text` read as the value of a scenario's key: `42`, `-5`, `0x2A`, `true`, `1.5`.
fn scenario_value(text: &str) -> Option<toml::Value> {
    let mut table: toml::Table = format!("value = {text}").parse().ok()?;
    let value = table.remove("value")?;
    table.is_empty().then_some(value)
}

/// What a live connection pushes (`/api/live`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Subscription {
    pub cpu: bool,
    pub values: Vec<(String, Option<Format>)>,
    /// The block and the level of program status.
    pub status: Option<(String, Option<String>)>,
    pub timeline: bool,
    pub diagnostics: bool,
}

#[derive(Deserialize)]
struct Subscribe {
    subscribe: SubscribeBody,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct SubscribeBody {
    cpu: bool,
    values: Vec<WatchRow>,
    status: Option<StatusOf>,
    timeline: bool,
    diagnostics: bool,
}

#[derive(Deserialize)]
struct WatchRow {
    operand: String,
    #[serde(default)]
    format: Option<String>,
}

#[derive(Deserialize)]
struct StatusOf {
    block: String,
    #[serde(default)]
    level: Option<String>,
}

/// A live connection's message: `{"subscribe": {…}}`, every part optional.
pub fn subscription(text: &str) -> Result<Subscription, OnlineError> {
    let route = ROUTES
        .iter()
        .find(|route| route.path == "/api/live")
        .expect("the live route is listed");
    let Subscribe { subscribe } = json(route, text.as_bytes())?;
    let values = subscribe
        .values
        .into_iter()
        .map(|row| Ok((row.operand, format(row.format.as_deref().unwrap_or(""))?)))
        .collect::<Result<_, OnlineError>>()?;
    Ok(Subscription {
        cpu: subscribe.cpu,
        values,
        status: subscribe.status.map(|status| (status.block, status.level)),
        timeline: subscribe.timeline,
        diagnostics: subscribe.diagnostics,
    })
}

/// A format by its name; an empty one is the program's own notation.
fn format(name: &str) -> Result<Option<Format>, OnlineError> {
    match name.trim() {
        "" => Ok(None),
        name => Format::parse(name)
            .map(Some)
            .ok_or_else(|| OnlineError::UnknownFormat {
                format: name.to_string(),
            }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refusal(method: &str, path: &str, query: Option<&str>, body: &str) -> String {
        match decode(method, path, query, body.as_bytes()) {
            Ok(call) => panic!("decoded {call:?}"),
            Err(error) => error.to_string(),
        }
    }

    #[test]
    fn values_take_operands_and_a_parallel_list_of_formats() {
        let call = decode(
            "GET",
            "/api/values",
            Some("operands=MW%2010,Q+4.0,%22Motor%22&formats=hex,"),
            b"",
        );
        assert_eq!(
            call.unwrap(),
            Call::Values(vec![
                ("MW 10".into(), Some(Format::Hex)),
                ("Q 4.0".into(), None),
                ("\"Motor\"".into(), None),
            ])
        );
    }

    #[test]
    fn values_are_numbers_booleans_or_a_scenario_s_text() {
        let modify = |body: &str| decode("POST", "/api/modify", None, body.as_bytes());
        let value = |body: &str| match modify(body) {
            Ok(Call::Modify { value, .. }) => value,
            other => panic!("{other:?}"),
        };
        assert_eq!(
            value(r#"{"operand": "MW 10", "value": 42}"#),
            toml::Value::Integer(42)
        );
        assert_eq!(
            value(r#"{"operand": "MW 10", "value": "0x2A"}"#),
            toml::Value::Integer(42)
        );
        assert_eq!(
            value(r#"{"operand": "Q 4.0", "value": true}"#),
            toml::Value::Boolean(true)
        );
        assert_eq!(
            value(r#"{"operand": "MD 4", "value": 1.5}"#),
            toml::Value::Float(1.5)
        );
        assert!(matches!(
            modify(r#"{"operand": "MW 10", "value": "1\nother = 2"}"#),
            Err(OnlineError::Value { .. })
        ));
    }

    #[test]
    fn a_force_ends_for_one_operand_or_for_all() {
        let delete = |query| decode("DELETE", "/api/force", query, b"");
        assert_eq!(
            delete(Some("operand=I%200.0")).unwrap(),
            Call::Unforce(Some("I 0.0".into()))
        );
        assert_eq!(delete(None).unwrap(), Call::Unforce(None));
        assert!(
            delete(Some("operand=")).is_err(),
            "an empty operand is no \"all\""
        );
        assert!(delete(None).unwrap().changes());
        assert!(!decode("GET", "/api/forces", None, b"").unwrap().changes());
    }

    #[test]
    fn a_subscription_names_what_to_push_and_leaves_out_the_rest() {
        let text = r#"{"subscribe": {"cpu": true, "values": [{"operand": "MW 10", "format": "HEX"},
            {"operand": "Q 4.0"}], "status": {"block": "OB 1", "level": null}}}"#;
        assert_eq!(
            subscription(text).unwrap(),
            Subscription {
                cpu: true,
                values: vec![("MW 10".into(), Some(Format::Hex)), ("Q 4.0".into(), None)],
                status: Some(("OB 1".into(), None)),
                timeline: false,
                diagnostics: false,
            }
        );
        assert_eq!(
            subscription(r#"{"subscribe": {}}"#).unwrap(),
            Subscription::default()
        );
        for bad in [
            "",
            "{}",
            r#"{"subscribe": {"values": [{"format": "HEX"}]}}"#,
            r#"{"subscribe": {"values": [{"operand": "MW 10", "format": "OCT"}]}}"#,
            r#"{"subscribe": {"cpu": "yes"}}"#,
        ] {
            assert!(subscription(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn malformed_requests_are_refused_with_what_was_wrong() {
        assert_eq!(
            refusal("GET", "/api/nothing", None, ""),
            "`/api/nothing` is no page of the online view"
        );
        assert_eq!(
            refusal("GET", "/api/mode", None, ""),
            "/api/mode does not take GET"
        );
        assert!(
            refusal("POST", "/api/mode", None, "{mode: stop")
                .starts_with("the request is not the JSON /api/mode takes: key must be a string")
        );
        assert_eq!(
            refusal("POST", "/api/mode", None, r#"{"mode": "run"}"#),
            "`run` is no mode to change to"
        );
        assert_eq!(
            refusal("GET", "/api/values", None, ""),
            "/api/values needs `operands`"
        );
        assert_eq!(
            refusal(
                "GET",
                "/api/values",
                Some("operands=MW%2010&formats=OCT"),
                ""
            ),
            "`OCT` is no display format"
        );
        assert!(
            refusal("POST", "/api/modify", None, r#"{"operand": "MW 10"}"#)
                .contains("missing field `value`")
        );
        assert!(refusal("POST", "/api/modify", None, "\u{0}\u{ff}").contains("/api/modify"));
        assert_eq!(
            refusal(
                "POST",
                "/api/modify",
                None,
                r#"{"operand": "MW 10", "value": "ten"}"#
            ),
            "`ten` is no value"
        );
        assert_eq!(
            refusal("GET", "/api/timeline", Some("seconds=-1"), ""),
            "`-1` is no number of seconds the timeline shows"
        );
        assert_eq!(
            decode("GET", "/api/timeline", None, b"").unwrap(),
            Call::Timeline(5.0)
        );
    }

    proptest::proptest! {
        /// Any request decodes into a call or is refused with a code and a 4xx status; a live
        /// connection's message is taken or refused the same way. (The fuzz target `http_decode`
        /// tries far more.)
        #[test]
        fn any_request_is_decoded_or_refused_with_a_code(
            method in "GET|POST|DELETE|PUT",
            path in "/(api/(cpu|mode|values|modify|force|forces|status|diagnostics|timeline|live|x))?",
            query in "[a-z=&%0-9A-F ,+.]{0,40}",
            body in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..80),
        ) {
            if let Err(error) = decode(&method, &path, Some(&query), &body) {
                let refusal = error.refusal();
                proptest::prop_assert!((400..500).contains(&refusal.kind.status()));
                proptest::prop_assert!(refusal.code.is_some_and(|code| code.starts_with("awl::online::")));
            }
            if let Err(error) = subscription(&String::from_utf8_lossy(&body)) {
                proptest::prop_assert!(error.refusal().code.is_some());
            }
        }
    }
}
