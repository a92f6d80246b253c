//! Who may use the online page's server: a request must name this server as its `Host` — the
//! address it listens on, or the loopback by name or number — so that no web site can reach it
//! through a name of its own that resolves to the loopback (DNS rebinding); and a request that
//! changes the CPU, or opens the live connection, must come from the page itself (its `Origin`),
//! so that another page the browser shows cannot send one.

use std::net::{IpAddr, SocketAddr};

use crate::serve::online::error::OnlineError;

/// The loopback's names a browser on this machine uses.
const LOOPBACK_NAMES: [&str; 3] = ["localhost", "127.0.0.1", "[::1]"];

/// Whether `host` (the `Host` header, `None` without one) names the server listening on
/// `listening`. Listening on every address (`0.0.0.0`, `[::]`), any address written as a number
/// names it too: a name resolved by DNS is what rebinding needs.
pub fn check_host(host: Option<&str>, listening: SocketAddr) -> Result<(), OnlineError> {
    let refused = || OnlineError::ForeignHost {
        host: host.unwrap_or("").to_string(),
        listening: listening.to_string(),
        port: listening.port(),
    };
    let (name, port) = host.and_then(split_host).ok_or_else(refused)?;
    let name = name.to_ascii_lowercase();
    let listening_name = SocketAddr::new(listening.ip(), 0)
        .to_string()
        .trim_end_matches(":0")
        .to_string();
    let numeric = name
        .trim_start_matches('[')
        .trim_end_matches(']')
        .parse::<IpAddr>()
        .is_ok();
    let named = LOOPBACK_NAMES.contains(&name.as_str())
        || name == listening_name
        || (listening.ip().is_unspecified() && numeric);
    if port == listening.port() && named {
        Ok(())
    } else {
        Err(refused())
    }
}

/// `localhost:8102` → (`localhost`, 8102); `[::1]:8102` → (`[::1]`, 8102); no port is 80.
fn split_host(host: &str) -> Option<(&str, u16)> {
    let host = host.trim();
    let (name, port) = match host.rfind(':') {
        Some(colon) if !host[colon..].contains(']') => (&host[..colon], Some(&host[colon + 1..])),
        _ => (host, None),
    };
    let port = match port {
        Some(port) => port.parse().ok()?,
        None => 80,
    };
    (!name.is_empty()).then_some((name, port))
}

/// Whether a request that changes the CPU may: without an `Origin` (a program, not a browser's
/// page) it may; with one, only the page's own, `http://` and the `Host` it was sent to.
pub fn check_origin(origin: Option<&str>, host: &str) -> Result<(), OnlineError> {
    match origin {
        None => Ok(()),
        Some(origin) if origin.eq_ignore_ascii_case(&format!("http://{host}")) => Ok(()),
        Some(origin) => Err(OnlineError::ForeignOrigin {
            origin: origin.to_string(),
            host: host.to_string(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn host_ok(host: &str, listening: &str) -> bool {
        check_host(Some(host), listening.parse().unwrap()).is_ok()
    }

    #[test]
    fn the_listening_address_and_the_loopback_s_names_are_this_server() {
        for host in [
            "127.0.0.1:8102",
            "localhost:8102",
            "LOCALHOST:8102",
            "[::1]:8102",
        ] {
            assert!(host_ok(host, "127.0.0.1:8102"), "{host}");
        }
        assert!(host_ok("192.168.1.5:8102", "192.168.1.5:8102"));
        assert!(host_ok("[::1]:8102", "[::1]:8102"));
        assert!(host_ok("10.0.0.7:8102", "0.0.0.0:8102"));
        assert!(host_ok("localhost", "127.0.0.1:80"));
    }

    #[test]
    fn other_names_and_ports_are_refused() {
        for host in [
            "evil.example:8102",
            "localhost.evil.example:8102",
            "localhost:8103",
            "127.0.0.1",
            "",
            ":8102",
            "localhost:99999",
        ] {
            assert!(!host_ok(host, "127.0.0.1:8102"), "{host}");
        }
        assert!(!host_ok("evil.example:8102", "0.0.0.0:8102"));
        assert!(check_host(None, "127.0.0.1:8102".parse().unwrap()).is_err());
    }

    #[test]
    fn only_the_page_s_own_origin_may_change_the_cpu() {
        assert!(check_origin(None, "localhost:8102").is_ok());
        assert!(check_origin(Some("http://localhost:8102"), "localhost:8102").is_ok());
        for origin in ["http://evil.example", "null", "https://localhost:8102"] {
            assert!(
                check_origin(Some(origin), "localhost:8102").is_err(),
                "{origin}"
            );
        }
    }
}
