//! Which requests come from this machine's own pages. A page of any web site can make the
//! browser send requests to a server on `127.0.0.1`: through a name of its own that it points
//! at this machine (DNS rebinding, which then reads the answers) or by plain cross-site requests
//! (which start work without reading it). The first carries a foreign `Host`, the second a foreign
//! `Origin` or `Sec-Fetch-Site: cross-site`; both are refused before any work.
//!
//! Reachable from other machines (`--host`), the explorer also asks for a token: a random one,
//! printed in its address (`?token=…`) and then kept by the browser as a cookie, so that on a
//! shared machine or network only whoever was given the address can use it (as Jupyter does).

use std::net::{IpAddr, SocketAddr};

/// The names this server answers to, from the address it listens on.
#[derive(Clone, Debug)]
pub struct Local {
    /// The port listened on.
    port: u16,
    /// The address listened on.
    ip: IpAddr,
    /// Other names of this machine that address it (a classroom machine's), lowercase.
    allowed: Vec<String>,
    /// The token every request must carry, if one is asked for.
    token: Option<String>,
}

/// The access to a server beyond its own addresses: other names of the machine it answers to
/// (`--allow-host`), and the token it asks for, if any.
#[derive(Clone, Debug, Default)]
pub struct Access {
    /// Names of this machine the server answers to as well.
    pub allow_hosts: Vec<String>,
    /// The token every request must carry (in its query or as the cookie the page gets).
    pub token: Option<String>,
}

/// A new random token: 128 bits from the operating system's randomness (through the standard
/// library's randomly keyed hashers), as 32 hexadecimal digits.
pub fn new_token() -> String {
    use std::hash::{BuildHasher, RandomState};
    let (a, b) = (RandomState::new(), RandomState::new());
    format!("{:016x}{:016x}", a.hash_one(0u8), b.hash_one(1u8))
}

/// Whether `a` and `b` are equal, in a time that does not tell how much of them is.
fn same_secret(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.bytes().zip(b.bytes()).fold(0, |d, (x, y)| d | (x ^ y)) == 0
}

/// Why a request is refused.
pub type Refusal = &'static str;

impl Local {
    /// The names of a server listening on `addr`.
    #[cfg(test)]
    pub fn new(addr: SocketAddr) -> Local {
        Local::with_access(addr, Access::default())
    }

    /// The names of a server listening on `addr`, with `access`'s other names and token.
    pub fn with_access(addr: SocketAddr, access: Access) -> Local {
        Local {
            port: addr.port(),
            ip: addr.ip(),
            allowed: access
                .allow_hosts
                .iter()
                .map(|h| h.to_ascii_lowercase())
                .collect(),
            token: access.token,
        }
    }

    /// The token asked for, if any.
    pub fn token(&self) -> Option<&str> {
        self.token.as_deref()
    }

    /// The name of the cookie that holds the token (one per port: two explorers of one machine
    /// keep theirs apart).
    pub fn cookie_name(&self) -> String {
        format!("bentstraw-token-{}", self.port)
    }

    /// Whether a request with this query and `Cookie` header carries the token (always, when
    /// none is asked for); `Some(true)` when it came in the query (the page then gets the
    /// cookie).
    pub fn token_given(&self, query: &str, cookie: Option<&str>) -> Option<bool> {
        let Some(token) = &self.token else {
            return Some(false);
        };
        let in_query = query
            .split('&')
            .filter_map(|pair| pair.strip_prefix("token="))
            .any(|t| same_secret(t, token));
        if in_query {
            return Some(true);
        }
        let name = self.cookie_name();
        let in_cookie = cookie.is_some_and(|c| {
            c.split(';')
                .filter_map(|pair| pair.trim().split_once('='))
                .any(|(n, v)| n == name && same_secret(v, token))
        });
        in_cookie.then_some(false)
    }

    /// Whether `host` (a `Host` header or a URL's authority, `name[:port]`) names this server:
    /// `localhost`, `127.0.0.1`, `[::1]` or the address listened on, with its port. Listening on
    /// every address (or on one of the network's), any address written as numbers is taken too:
    /// a rebinding page always comes under a name.
    pub fn is_own_host(&self, host: &str) -> bool {
        let (name, port) = match host.strip_prefix('[') {
            Some(rest) => match rest.split_once(']') {
                Some((inside, after)) => (inside, after.strip_prefix(':')),
                None => return false,
            },
            None => match host.rsplit_once(':') {
                Some((name, port)) => (name, Some(port)),
                None => (host, None),
            },
        };
        let port_ok = match port {
            Some(p) => p.parse::<u16>().ok() == Some(self.port),
            None => self.port == 80,
        };
        if !port_ok {
            return false;
        }
        if name.eq_ignore_ascii_case("localhost")
            || self.allowed.iter().any(|a| name.eq_ignore_ascii_case(a))
        {
            return true;
        }
        let Ok(ip) = name.parse::<IpAddr>() else {
            return false;
        };
        // An address of IPv6's form must come in brackets, one of IPv4's without.
        if ip.is_ipv6() != host.starts_with('[') {
            return false;
        }
        ip.is_loopback() || ip == self.ip || !self.ip.is_loopback()
    }

    /// Whether a request with these headers comes from this server's own page (or from no page
    /// at all: a program, the address typed in): `host` must name this server, and `origin` and
    /// `fetch_site` (`Sec-Fetch-Site`), when given, must not name another site. `api` requests
    /// (which compute) must come from the page itself, not from a page of the same site on
    /// another port.
    pub fn check(
        &self,
        host: Option<&str>,
        origin: Option<&str>,
        fetch_site: Option<&str>,
        api: bool,
    ) -> Result<(), Refusal> {
        let Some(host) = host else {
            return Err("a request must name the server it is for (Host)");
        };
        if !self.is_own_host(host) {
            return Err("this server answers only addresses of this machine (Host)");
        }
        if let Some(origin) = origin {
            let same = origin
                .strip_prefix("http://")
                .is_some_and(|o| o.eq_ignore_ascii_case(host));
            if !same {
                return Err("this server answers only its own page (Origin)");
            }
        }
        match fetch_site {
            None | Some("same-origin") | Some("none") => Ok(()),
            Some("same-site") if !api => Ok(()),
            Some(_) => Err("this server answers only its own page (Sec-Fetch-Site)"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn local(addr: &str) -> Local {
        Local::new(addr.parse().unwrap())
    }

    #[test]
    fn own_names_with_the_port_are_taken_others_refused() {
        let l = local("127.0.0.1:8157");
        for ok in [
            "127.0.0.1:8157",
            "localhost:8157",
            "LocalHost:8157",
            "[::1]:8157",
        ] {
            assert!(l.is_own_host(ok), "{ok}");
        }
        for bad in [
            "evil.example:8157",
            "127.0.0.1",
            "127.0.0.1:80",
            "localhost:8158",
            "localhost.evil.example:8157",
            "192.168.1.4:8157",
            "::1:8157",
            "[127.0.0.1]:8157",
            "[::1",
            "",
            "127.0.0.1:8157:8157",
        ] {
            assert!(!l.is_own_host(bad), "{bad}");
        }
        // On port 80 a browser leaves the port out.
        assert!(local("127.0.0.1:80").is_own_host("localhost"));
        // Listening on IPv6's loopback, or on every address.
        assert!(local("[::1]:9000").is_own_host("[::1]:9000"));
        let all = local("0.0.0.0:9000");
        assert!(all.is_own_host("192.168.1.4:9000"));
        assert!(!all.is_own_host("evil.example:9000"));
        let lan = local("192.168.1.4:9000");
        assert!(lan.is_own_host("192.168.1.4:9000"));
        assert!(lan.is_own_host("localhost:9000"));
    }

    #[test]
    fn allowed_names_are_taken_with_the_port() {
        let access = Access {
            allow_hosts: vec!["Lab-PC.school.example".into()],
            token: None,
        };
        let l = Local::with_access("0.0.0.0:9000".parse().unwrap(), access);
        assert!(l.is_own_host("lab-pc.school.example:9000"));
        assert!(!l.is_own_host("lab-pc.school.example:9001"));
        assert!(!l.is_own_host("lab-pc.school.example.evil:9000"));
        assert!(l
            .check(
                Some("lab-pc.school.example:9000"),
                Some("http://lab-pc.school.example:9000"),
                None,
                true
            )
            .is_ok());
        assert!(!local("0.0.0.0:9000").is_own_host("lab-pc.school.example:9000"));
    }

    #[test]
    fn the_token_is_asked_for_in_the_query_or_the_cookie() {
        let token = new_token();
        assert_eq!(token.len(), 32);
        assert_ne!(token, new_token());
        let l = Local::with_access(
            "0.0.0.0:9000".parse().unwrap(),
            Access {
                allow_hosts: vec![],
                token: Some(token.clone()),
            },
        );
        assert_eq!(
            l.token_given(&format!("a=1&token={token}"), None),
            Some(true)
        );
        let cookie = format!("other=1; bentstraw-token-9000={token}");
        assert_eq!(l.token_given("", Some(&cookie)), Some(false));
        assert_eq!(l.token_given("", None), None);
        assert_eq!(l.token_given("token=0123", None), None);
        let wrong_port = format!("bentstraw-token-9001={token}");
        assert_eq!(l.token_given("", Some(&wrong_port)), None);
        let truncated = &token[..31];
        assert_eq!(l.token_given(&format!("token={truncated}"), None), None);
        // No token asked for: every request has what it needs.
        assert_eq!(local("127.0.0.1:9000").token_given("", None), Some(false));
    }

    #[test]
    fn foreign_origins_and_cross_site_requests_are_refused() {
        let l = local("127.0.0.1:8157");
        let h = Some("127.0.0.1:8157");
        assert!(l.check(h, None, None, true).is_ok());
        assert!(l
            .check(h, Some("http://127.0.0.1:8157"), None, true)
            .is_ok());
        assert!(l.check(h, None, Some("same-origin"), true).is_ok());
        assert!(l.check(h, None, Some("none"), false).is_ok());
        assert!(l.check(None, None, None, false).is_err());
        assert!(l.check(Some("evil.example"), None, None, false).is_err());
        for origin in [
            "http://evil.example",
            "null",
            "https://127.0.0.1:8157",
            "http://localhost:8157",
            "http://127.0.0.1:3000",
        ] {
            assert!(l.check(h, Some(origin), None, true).is_err(), "{origin}");
        }
        assert!(l.check(h, None, Some("cross-site"), false).is_err());
        assert!(l.check(h, None, Some("cross-site"), true).is_err());
        // Another port of this machine may link to the page, not make it compute.
        assert!(l.check(h, None, Some("same-site"), false).is_ok());
        assert!(l.check(h, None, Some("same-site"), true).is_err());
    }
}
